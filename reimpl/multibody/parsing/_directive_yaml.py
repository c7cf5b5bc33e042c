"""Model-directive YAML to ``ModelDirectives``, as Drake's YamlReadArchive reads it.

The YAML is composed with PyYAML, then read field by field against the
structs (in each struct's ``Serialize`` order, then unknown keys in sorted
order), so the first error is Drake's first error, in Drake's words (measured
on pydrake 1.51.1)::

    <string>:3:5: YAML node of type Mapping (with size 2 and keys {file, name})
    has non-Scalar (Sequence) entry for std::string name while accepting ...

The position is that of the nearest mapping; the chain names each enclosing
node and the C++ type visited in it. Rules of the reading:

=================================  ============================================
 missing key                        the field keeps its default
 null (``~``, empty)                None for an optional; else ``has non-X
                                    (Null)``
 key no field reads                 ``key 'k' did not match any visited value``
 the same key twice                 ``Cannot Node::Add(key, value) using
                                    duplicate key 'k'`` (before anything else)
 ``<<`` merge key                   copies the keys the mapping lacks
 a scalar for a string              its text (``3`` is ``'3'``)
 a double                           C++ ``>>`` syntax, or ``.inf``/``.nan``;
                                    overflow is ``could not parse double value``
 a variant (rotation, translation)  chosen by the tag (``!Rpy``, ...); untagged
                                    is the first alternative
=================================  ============================================

N.B. PyYAML's syntax-error messages are not yaml-cpp's: a document that is not
YAML gives ``yaml-cpp: error at line L, column C: <PyYAML's problem>``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import yaml

from reimpl._release import release
from reimpl.common.schema import Rotation, Transform
from reimpl.multibody.parsing._diagnostics import ModelParseError
from reimpl.multibody.parsing._directive_structs import (
    AddCollisionFilterGroup,
    AddDirectives,
    AddFrame,
    AddModel,
    AddModelInstance,
    AddWeld,
    ModelDirective,
    ModelDirectives,
)

__all__ = ["load_directives"]

_P = "drake::multibody::parsing::"
#: Whether an error starts with ``<label>:<line>:<column>:`` (directives-yaml-position-
#: since-1.15: measured on pydrake 1.14.0, no position, and 1.15.0).
_POSITIONED = release.has("directives-yaml-position-since-1.15")
_S = "drake::schema::"
_STRING = "std::string"
_OPTIONAL_STRING = "std::optional<std::string>"
_STRINGS = "std::vector<std::string,std::allocator<std::string>>"
_VECTOR3 = "Eigen::Vector3d"
_VECTOR_VARIANT = (
    f"std::variant<Eigen::Vector3d,{_S}DeterministicVector<3>,{_S}GaussianVector<3>,"
    f"{_S}UniformVector<3>,{_S}internal::InvalidVariantSelection<{_S}Deterministic>,"
    f"{_S}internal::InvalidVariantSelection<{_S}Gaussian>,"
    f"{_S}internal::InvalidVariantSelection<{_S}Uniform>>"
)
_SCALAR_VARIANT = (
    f"std::variant<double,{_S}Deterministic,{_S}Gaussian,{_S}Uniform,{_S}UniformDiscrete>"
)
_ROTATION_VARIANT = (
    f"std::variant<{_S}Rotation::Identity,{_S}Rotation::Rpy,{_S}Rotation::AngleAxis,"
    f"{_S}Rotation::Uniform>"
)
_DOUBLE = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_SPECIAL_DOUBLES = {
    ".inf": math.inf,
    ".Inf": math.inf,
    ".INF": math.inf,
    "+.inf": math.inf,
    "+.Inf": math.inf,
    "+.INF": math.inf,
    "-.inf": -math.inf,
    "-.Inf": -math.inf,
    "-.INF": -math.inf,
    ".nan": math.nan,
    ".NaN": math.nan,
    ".NAN": math.nan,
}
_KINDS = {yaml.ScalarNode: "Scalar", yaml.SequenceNode: "Sequence", yaml.MappingNode: "Mapping"}


def _is_null(node: yaml.Node) -> bool:
    return isinstance(node, yaml.ScalarNode) and node.tag.endswith(":null")


def _kind(node: yaml.Node) -> str:
    return "Null" if _is_null(node) else _KINDS[type(node)]


def _explicit_tag(node: yaml.Node) -> str:
    """The tag the text wrote (``!Rpy``), or "" for none (PyYAML's resolved tags)."""
    return "" if node.tag.startswith("tag:yaml.org,2002:") else str(node.tag)


def _entries(node: yaml.MappingNode) -> dict[str, yaml.Node]:
    """The mapping's entries, ``<<`` merge keys applied (existing keys win)."""
    entries: dict[str, yaml.Node] = {}
    merges: list[yaml.Node] = []
    for key, value in node.value:
        if key.tag.endswith(":merge") or key.value == "<<":
            merges.append(value)
        else:
            entries[str(key.value)] = value
    for merge in merges:
        sources = merge.value if isinstance(merge, yaml.SequenceNode) else [merge]
        for source in sources:
            if isinstance(source, yaml.MappingNode):
                for key, value in _entries(source).items():
                    entries.setdefault(key, value)
    return entries


def _check_duplicates(node: yaml.Node) -> None:
    """Drake's conversion of the document rejects a repeated key, depth first."""
    if isinstance(node, yaml.MappingNode):
        seen: set[str] = set()
        for key, value in node.value:
            if key.value in seen:
                raise ModelParseError(
                    f"Cannot Node::Add(key, value) using duplicate key '{key.value}'"
                )
            seen.add(key.value)
            _check_duplicates(value)
    elif isinstance(node, yaml.SequenceNode):
        for item in node.value:
            _check_duplicates(item)


@dataclass
class _Archive:
    """One level of the reading: a mapping, or one item of a sequence or map."""

    label: str
    #: the mapping read at this level; None for an item
    node: yaml.MappingNode | None
    parent: _Archive | None = None
    #: for an item: its name (``directives[0]``) and node
    item: tuple[str, yaml.Node] | None = None
    #: "type name" of the field being read, for the messages
    visiting: str | None = None
    visited: set[str] = field(default_factory=set)

    def entries(self) -> dict[str, yaml.Node]:
        if self.item is not None:
            return {self.item[0]: self.item[1]}
        assert self.node is not None
        return _entries(self.node)

    def _summary(self) -> str:
        if self.item is not None:
            return f" (with size 1 and keys {{{self.item[0]}}})"
        keys = sorted(self.entries())
        return f"YAML node of type Mapping (with size {len(keys)} and keys {{{', '.join(keys)}}})"

    def error(self, note: str) -> ModelParseError:
        mark = ""
        archive: _Archive | None = self
        while archive is not None:
            if archive.node is not None:
                start = archive.node.start_mark
                mark = f"{start.line + 1}:{start.column + 1}:"
                break
            archive = archive.parent
        text = f"{self._summary()} {note} entry for {self.visiting}"
        if _POSITIONED:
            text = f"{self.label}:{mark} {text}"
        archive = self.parent
        while archive is not None:
            text += f" while accepting {archive._summary()}"
            if archive.visiting is not None:
                text += f" while visiting {archive.visiting}"
            archive = archive.parent
        return ModelParseError(text + ".")

    # ------------------------------------------------------------- fields
    def get(self, name: str, type_name: str) -> yaml.Node | None:
        """The field's node, or None if the mapping lacks it (the default stays)."""
        self.visiting = f"{type_name} {name}"
        self.visited.add(name)
        return self.entries().get(name)

    def expect(self, node: yaml.Node, kind: type[yaml.Node], kind_name: str) -> None:
        if not isinstance(node, kind) or _is_null(node):
            raise self.error(f"has non-{kind_name} ({_kind(node)})")

    def mapping(self, node: yaml.Node) -> yaml.MappingNode:
        """``node``, which must be a mapping."""
        if not isinstance(node, yaml.MappingNode):
            raise self.error(f"has non-Mapping ({_kind(node)})")
        return node

    def check_all_accepted(self) -> None:
        for key in sorted(self.entries()):
            if key not in self.visited:
                self.visiting = "<root>"
                raise self.error(f"key '{key}' did not match any visited value")

    def child(self, node: yaml.MappingNode) -> _Archive:
        return _Archive(self.label, node, parent=self)

    def item_archive(self, name: str, node: yaml.Node) -> _Archive:
        return _Archive(self.label, None, parent=self, item=(name, node))


# ------------------------------------------------------------------ readers
#: reads a field: (archive, field name, current value) -> new value
Reader = Callable[[_Archive, str, Any], Any]


def _string(archive: _Archive, name: str, value: Any, type_name: str = _STRING) -> Any:
    node = archive.get(name, type_name)
    if node is None:
        return value
    archive.expect(node, yaml.ScalarNode, "Scalar")
    return str(node.value)


def _optional_string(archive: _Archive, name: str, value: Any) -> Any:
    node = archive.get(name, _OPTIONAL_STRING)
    if node is None:
        return value
    if _is_null(node):
        return None
    return _string(archive, name, value, _OPTIONAL_STRING)


def _double(archive: _Archive, name: str, value: Any, type_name: str = "double") -> Any:
    node = archive.get(name, type_name)
    if node is None:
        return value
    archive.expect(node, yaml.ScalarNode, "Scalar")
    text = str(node.value)
    number = _SPECIAL_DOUBLES.get(text)
    if number is None and _DOUBLE.fullmatch(text):
        number = float(text)
        if math.isinf(number):
            number = None
    if number is None:
        raise archive.error("could not parse double value")
    return number


def _vector(archive: _Archive, name: str, value: Any, size: int | None) -> Any:
    type_name = "Eigen::VectorXd" if size is None else _VECTOR3
    node = archive.get(name, type_name)
    if node is None:
        return value
    archive.expect(node, yaml.SequenceNode, "Sequence")
    items = node.value
    if size is not None and len(items) != size:
        raise archive.error(f"has {len(items)}-size entry (wanted {size}-size)")
    numbers = []
    for i, item in enumerate(items):
        key = f"{name}[{i}]"
        numbers.append(_double(archive.item_archive(key, item), key, 0.0))
    return np.array(numbers, dtype=float)


def _strings(archive: _Archive, name: str, value: Any) -> Any:
    node = archive.get(name, _STRINGS)
    if node is None:
        return value
    archive.expect(node, yaml.SequenceNode, "Sequence")
    result = []
    for i, item in enumerate(node.value):
        key = f"{name}[{i}]"
        result.append(_string(archive.item_archive(key, item), key, ""))
    return result


def _struct(
    archive: _Archive, name: str, value: Any, kind: type, type_name: str, *, optional: bool
) -> Any:
    node = archive.get(name, type_name)
    if node is None:
        return value
    if optional and _is_null(node):
        return None
    mapping = archive.mapping(node)
    target = value if value is not None else kind()
    _read_struct(archive.child(mapping), target)
    return target


def _read_struct(archive: _Archive, target: Any) -> None:
    """Reads ``target``'s fields from ``archive``'s mapping, then checks its keys."""
    for name, reader in _READERS[type(target)]:
        current = object.__getattribute__(target, "_" + name)
        object.__setattr__(target, "_" + name, reader(archive, name, current))
    archive.check_all_accepted()


def _optional(kind: type, type_name: str) -> Reader:
    def read(archive: _Archive, name: str, value: Any) -> Any:
        return _struct(archive, name, value, kind, f"std::optional<{type_name}>", optional=True)

    return read


def _required(kind: type, type_name: str) -> Reader:
    def read(archive: _Archive, name: str, value: Any) -> Any:
        return _struct(archive, name, value, kind, type_name, optional=False)

    return read


def _map(value_type: str, read_value: Reader) -> Reader:
    """A ``std::map<std::string, V>``: a mapping whose every key is an item."""
    full = (
        f"std::map<std::string,{value_type},std::less<std::string>,"
        f"std::allocator<std::pair<std::stringconst,{value_type}>>>"
    )

    def read(archive: _Archive, name: str, value: Any) -> Any:
        node = archive.get(name, full)
        if node is None:
            return value
        mapping = archive.mapping(node)
        result = {}
        child = archive.child(mapping)
        for key in sorted(_entries(mapping)):
            result[key] = read_value(child, key, None)
        return result

    return read


def _vector_variant(archive: _Archive, name: str, value: Any) -> Any:
    """``DistributionVectorVariant<3>``: a plain vector, or a tagged distribution."""
    node = archive.entries().get(name)
    if node is None:
        return value
    tag = _explicit_tag(node)
    if tag in ("", "?", "!") or _is_null(node):
        return _vector(archive, name, value, 3)
    if tag == "!DeterministicVector":
        deterministic = _required(_DeterministicVector, f"{_S}DeterministicVector<3>")
        return deterministic(archive, name, None).value
    if tag in ("!GaussianVector", "!UniformVector"):
        archive.get(name, f"{_S}{tag[1:]}<3>")
        return _RANDOM
    archive.get(name, _VECTOR_VARIANT)
    raise archive.error(f"has unsupported type tag {tag} while selecting a variant<>")


def _scalar_variant(archive: _Archive, name: str, value: Any) -> Any:
    """``DistributionVariant``: a plain double, or a tagged distribution."""
    node = archive.entries().get(name)
    if node is None:
        return value
    tag = _explicit_tag(node)
    if tag in ("", "?", "!") or _is_null(node):
        return _double(archive, name, value)
    if tag in ("!Deterministic", "!Gaussian", "!Uniform", "!UniformDiscrete"):
        archive.get(name, f"{_S}{tag[1:]}")
        return _RANDOM
    archive.get(name, _SCALAR_VARIANT)
    raise archive.error(f"has unsupported type tag {tag} while selecting a variant<>")


class _Random:
    """A distribution where a value was expected: reimpl does not sample."""

    def __repr__(self) -> str:
        return "<distribution>"


_RANDOM: Any = _Random()


class _DeterministicVector:
    """``!DeterministicVector {value: [x, y, z]}``: read as its value."""

    def __init__(self) -> None:
        self._value = np.zeros(3)

    @property
    def value(self) -> Any:
        return self._value


_ROTATIONS = {
    "!Identity": Rotation.Identity,
    "!Rpy": Rotation.Rpy,
    "!AngleAxis": Rotation.AngleAxis,
    "!Uniform": Rotation.Uniform,
}


def _rotation(archive: _Archive, name: str, value: Any) -> Any:
    """``Rotation::value``, a variant chosen by the tag (none: Identity)."""
    node = archive.entries().get(name)
    if node is None:
        return value
    tag = _explicit_tag(node)
    kind = Rotation.Identity if tag in ("", "?", "!") or _is_null(node) else _ROTATIONS.get(tag)
    if kind is None:
        archive.get(name, _ROTATION_VARIANT)
        raise archive.error(f"has unsupported type tag {tag} while selecting a variant<>")
    current = value.value if isinstance(value, Rotation) and type(value.value) is kind else None
    type_name = f"{_S}Rotation::{kind._short_name()}"
    read = _struct(archive, name, current, kind, type_name, optional=False)
    return Rotation(value=read)


def _transform_random(target: Transform) -> None:
    """Marks a transform whose value is a distribution (it is not deterministic)."""
    rotation = target.rotation
    if not isinstance(rotation.value, Rotation.Uniform):
        rotation.value = Rotation.Uniform()


_TRANSFORM = f"{_S}Transform"
#: add_collision_filter_group's keys in Serialize order, each with the release fact from
#: which it is read (None: every release); before it, the key is one no field reads
#: (directive-group-keys-since-1.26, member-groups-since-1.27: measured on pydrake 1.25.0,
#: 1.26.0 and 1.27.0).
_GROUP_FIELDS: tuple[tuple[str, Reader, str | None], ...] = (
    ("name", _string, None),
    ("members", _strings, None),
    ("member_groups", _strings, "member-groups-since-1.27"),
    ("model_namespace", _optional_string, "directive-group-keys-since-1.26"),
    ("ignored_collision_filter_groups", _strings, None),
)
_READERS: dict[type, tuple[tuple[str, Reader], ...]] = {
    Transform: (
        ("base_frame", _optional_string),
        ("translation", _vector_variant),
        ("rotation", _rotation),
    ),
    Rotation.Identity: (),
    Rotation.Uniform: (),
    Rotation.Rpy: (("deg", _vector_variant),),
    Rotation.AngleAxis: (("angle_deg", _scalar_variant), ("axis", _vector_variant)),
    _DeterministicVector: (("value", lambda a, n, v: _vector(a, n, v, 3)),),
    AddWeld: (
        ("parent", _string),
        ("child", _string),
        ("X_PC", _optional(Transform, _TRANSFORM)),
    ),
    AddModel: (
        ("file", _string),
        ("name", _string),
        (
            "default_joint_positions",
            _map("Eigen::VectorXd", lambda a, n, v: _vector(a, n, v, None)),
        ),
        ("default_free_body_pose", _map(_TRANSFORM, _required(Transform, _TRANSFORM))),
    ),
    AddModelInstance: (("name", _string),),
    AddFrame: (("name", _string), ("X_PF", _required(Transform, _TRANSFORM))),
    AddCollisionFilterGroup: tuple(
        (name, read) for name, read, fact in _GROUP_FIELDS if fact is None or release.has(fact)
    ),
    AddDirectives: (("file", _string), ("model_namespace", _optional_string)),
    ModelDirective: tuple(
        (name, _optional(kind, f"{_P}{kind.__name__}"))
        for name, kind in (
            ("add_model", AddModel),
            ("add_model_instance", AddModelInstance),
            ("add_frame", AddFrame),
            ("add_weld", AddWeld),
            ("add_collision_filter_group", AddCollisionFilterGroup),
            ("add_directives", AddDirectives),
        )
    ),
}


def _directives(archive: _Archive, name: str, value: Any) -> Any:
    vector_type = f"std::vector<{_P}ModelDirective,std::allocator<{_P}ModelDirective>>"
    node = archive.get(name, vector_type)
    if node is None:
        return value
    archive.expect(node, yaml.SequenceNode, "Sequence")
    result = []
    for i, item in enumerate(node.value):
        key = f"{name}[{i}]"
        read = _required(ModelDirective, f"{_P}ModelDirective")
        result.append(read(archive.item_archive(key, item), key, None))
    return result


_READERS[ModelDirectives] = (("directives", _directives),)


def _fix_random(directives: ModelDirectives) -> None:
    """Distributions read as _RANDOM become a non-deterministic rotation."""
    for directive in directives.directives:
        for _, struct in directive._set_fields():
            for transform in _transforms(struct):
                _mark_random(transform)


def _transforms(struct: Any) -> list[Transform]:
    if isinstance(struct, AddFrame):
        return [struct.X_PF]
    if isinstance(struct, AddWeld):
        return [struct.X_PC] if struct.X_PC is not None else []
    if isinstance(struct, AddModel):
        return list(struct.default_free_body_pose.values())
    return []


def _mark_random(transform: Transform) -> None:
    translation = object.__getattribute__(transform, "_translation")
    rotation = transform.rotation.value
    random_rotation = any(
        object.__getattribute__(rotation, "_" + name) is _RANDOM
        for name in ("deg", "angle_deg", "axis")
        if any(spec.name == name for spec in type(rotation).FIELDS)
    )
    if translation is _RANDOM:
        object.__setattr__(transform, "_translation", np.zeros(3))
    if random_rotation:
        for spec in type(rotation).FIELDS:
            if object.__getattribute__(rotation, "_" + spec.name) is _RANDOM:
                object.__setattr__(rotation, "_" + spec.name, spec.default())
    if translation is _RANDOM or random_rotation:
        _transform_random(transform)


def load_directives(text: str, label: str) -> ModelDirectives:
    """The directives ``text`` holds; ``label`` names it in messages (a file name,
    or ``<string>``). Raises ModelParseError with Drake's message."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "unknown"
        raise ModelParseError(f"yaml-cpp: error at {where}: {exc.problem}") from None
    if root is not None:
        _check_duplicates(root)
    if not isinstance(root, yaml.MappingNode):
        kind = "Scalar" if root is None or _is_null(root) else _KINDS[type(root)]
        raise ModelParseError(
            f"{label}: invalid document: the top level element should be a Mapping (not a {kind})"
        )
    directives = ModelDirectives()
    _read_struct(_Archive(label, root), directives)
    _fix_random(directives)
    return directives
