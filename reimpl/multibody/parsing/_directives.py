"""Model directives (``.dmd.yaml``), read with PyYAML (Drake 1.51.1, measured).

A document is ``{directives: [directive, ...]}``; each directive has exactly
one key. Reading happens in three steps, as in Drake:

1. the YAML is matched against ``_FIELDS``; an unknown key gives yaml-cpp's
   message (``<string>:2:14: YAML node of type Mapping (with size 3 and keys
   {file, foo, name}) key 'foo' did not match any visited value entry for
   <root> while accepting ...``);
2. every directive is checked (``IsValid``); a failure is logged and ends the
   program (SystemExit, as pydrake's DRAKE_DEMAND does);
3. the directives run in order, names read in the current namespace
   ``prefix::model_namespace`` (``ns`` below):

   =============================  ==================================================
   ``add_model``                  instance ``ns::name`` from ``file`` (``package://``)
   ``add_model_instance``         an empty instance ``ns::name`` (not returned)
   ``add_frame``                  FixedOffsetFrame ``name`` on ``X_PF.base_frame``
   ``add_weld``                   WeldFrames(``parent``, ``child``, ``X_PC``)
   ``add_collision_filter_group`` a group in instance ``ns::model_namespace`` (or
                                  at global scope), skipped without a SceneGraph
   ``add_directives``             ``file``'s directives in ``ns::model_namespace``
   =============================  ==================================================

The groups of a directives file and of all it adds form one parse. Errors
about them carry no source (``error: body with name 'a::zz' not found``).
"""

from __future__ import annotations

import logging
import math
import os
from dataclasses import dataclass, field
from typing import Any

import yaml

from reimpl.math import RigidTransform, RollPitchYaw
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._package_map import UriError, resolve_uri
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext
from reimpl.multibody.tree import FixedOffsetFrame

__all__ = ["read_directives"]

_LOG = logging.getLogger("drake")
_NAMESPACE = "drake::multibody::parsing::"
_VECTOR = (
    f"std::vector<{_NAMESPACE}ModelDirective,std::allocator<{_NAMESPACE}ModelDirective>> directives"
)

#: directive -> (Drake's struct, its fields)
_FIELDS: dict[str, tuple[str, frozenset[str]]] = {
    "add_model": (
        "AddModel",
        frozenset({"name", "file", "default_free_body_pose", "default_joint_positions"}),
    ),
    "add_model_instance": ("AddModelInstance", frozenset({"name"})),
    "add_frame": ("AddFrame", frozenset({"name", "X_PF"})),
    "add_weld": ("AddWeld", frozenset({"parent", "child", "X_PC"})),
    "add_collision_filter_group": (
        "AddCollisionFilterGroup",
        frozenset(
            {
                "name",
                "model_namespace",
                "members",
                "member_groups",
                "ignored_collision_filter_groups",
            }
        ),
    ),
    "add_directives": ("AddDirectives", frozenset({"file", "model_namespace"})),
}

#: directive -> the fields that must be non-empty (Drake's IsValid)
_REQUIRED: dict[str, tuple[str, ...]] = {
    "add_model": ("name", "file"),
    "add_model_instance": ("name",),
    "add_frame": ("name",),
    "add_weld": ("parent", "child"),
    "add_collision_filter_group": ("name",),
    "add_directives": ("file",),
}
_KINDS = {
    yaml.ScalarNode: "Scalar",
    yaml.SequenceNode: "Sequence",
    yaml.MappingNode: "Mapping",
}


class _Schema:
    """Checks the YAML nodes against _FIELDS with yaml-cpp's messages."""

    def __init__(self, label: str) -> None:
        self.label = label

    def _where(self, node: yaml.Node) -> str:
        return f"{self.label}:{node.start_mark.line + 1}:{node.start_mark.column + 1}"

    @staticmethod
    def _mapping(node: yaml.MappingNode) -> str:
        keys = ", ".join(sorted(str(k.value) for k, _ in node.value))
        return f"YAML node of type Mapping (with size {len(node.value)} and keys {{{keys}}})"

    def _unknown_key(self, node: yaml.MappingNode, allowed: frozenset[str], chain: str) -> None:
        for key, _ in node.value:
            if key.value not in allowed:
                raise ModelParseError(
                    f"{self._where(node)}: {self._mapping(node)} key '{key.value}' did not match "
                    f"any visited value entry for <root>{chain}."
                )

    def check(self, root: yaml.Node | None) -> list[tuple[str, dict[str, Any]]]:
        if not isinstance(root, yaml.MappingNode):
            kind = _KINDS.get(type(root), "Scalar")
            raise ModelParseError(
                f"{self.label}: invalid document: the top level element should be a Mapping "
                f"(not a {kind})"
            )
        self._unknown_key(root, frozenset({"directives"}), "")
        top = self._mapping(root)
        directives: list[tuple[str, dict[str, Any]]] = []
        for _, sequence in root.value:
            if not isinstance(sequence, yaml.SequenceNode):
                kind = "Null" if sequence.tag.endswith(":null") else _KINDS[type(sequence)]
                raise ModelParseError(
                    f"{self._where(root)}: {top} has non-Sequence ({kind}) entry for {_VECTOR}."
                )
            for i, node in enumerate(sequence.value):
                directives.append(self._directive(node, i, top))
        return directives

    def _directive(self, node: yaml.Node, i: int, top: str) -> tuple[str, dict[str, Any]]:
        chain = (
            f" while accepting  (with size 1 and keys {{directives[{i}]}}) while visiting "
            f"{_NAMESPACE}ModelDirective directives[{i}] while accepting {top} while visiting "
            f"{_VECTOR}"
        )
        assert isinstance(node, yaml.MappingNode)
        self._unknown_key(node, frozenset(_FIELDS), chain)
        values = {key.value: value for key, value in node.value}
        for name, value in values.items():
            struct, fields = _FIELDS[name]
            if isinstance(value, yaml.MappingNode):
                self._unknown_key(
                    value,
                    fields,
                    f" while accepting {self._mapping(node)} while visiting "
                    f"std::optional<{_NAMESPACE}{struct}> {name}{chain}",
                )
        if len(values) != 1:
            _demand_failed(
                "directive: Specify one of `add_model`, `add_model_instance`, `add_frame`, "
                "`add_collision_filter_group`, or `add_directives`"
            )
        ((name, value),) = values.items()
        return name, _python(value) or {}


def _python(node: yaml.Node) -> Any:
    """The node as plain Python values (tags such as ``!Rpy`` are read as their mapping)."""
    if isinstance(node, yaml.MappingNode):
        return {key.value: _python(value) for key, value in node.value}
    if isinstance(node, yaml.SequenceNode):
        return [_python(item) for item in node.value]
    return None if node.tag.endswith(":null") else node.value


def _demand_failed(message: str) -> None:
    _LOG.error(message)
    raise SystemExit(
        "Failure at external/drake+/multibody/parsing/detail_dmd_parser.cc:332 in "
        "LoadModelDirectives(): condition 'directives.IsValid()' failed."
    )


def _validate(name: str, directive: dict[str, Any]) -> None:
    for required in _REQUIRED[name]:
        if not directive.get(required):
            _demand_failed(f"{name}: `{required}` must be non-empty")
    if name == "add_collision_filter_group" and not (
        directive.get("members") or directive.get("member_groups")
    ):
        _demand_failed(f"{name}: at least one of `members` or `member_groups` must be non-empty")


def _transform(value: dict[str, Any] | None) -> RigidTransform:
    """``{translation: [x, y, z], rotation: !Rpy {deg: [r, p, y]}}``."""
    if not value:
        return RigidTransform()
    translation = [float(v) for v in value.get("translation") or (0, 0, 0)]
    rotation = value.get("rotation") or {}
    if "deg" in rotation:
        rpy = [math.radians(float(v)) for v in rotation["deg"]]
    else:
        rpy = [float(v) for v in rotation.get("rad", (0, 0, 0))]
    return RigidTransform(RollPitchYaw(rpy), translation)


@dataclass
class _Run:
    """One directives document being run in namespace ``namespace``."""

    context: ParseContext
    prefix: str
    namespace: str
    root_dir: str | None
    #: the instances each add_model made (welded children must be among them)
    added: list[Any] = field(default_factory=list)

    @property
    def plant(self) -> Any:
        return self.context.plant

    def scoped(self, name: str) -> str:
        return scoped.join(self.prefix, self.namespace, name)

    def resolve(self, uri: str) -> str:
        try:
            return resolve_uri(self.context.package_map, uri, self.root_dir)
        except UriError as exc:
            raise Diagnostics(None).error(str(exc)) from None

    def frame(self, name: str) -> Any:
        if name == "world":
            return self.plant.world_frame()
        namespace, element = scoped.split(self.scoped(name))
        if not namespace:
            return self.plant.GetFrameByName(element)
        return self.plant.GetFrameByName(element, self.plant.GetModelInstanceByName(namespace))

    def run(self, directives: list[tuple[str, dict[str, Any]]]) -> list[Any]:
        instances: list[Any] = []
        for name, directive in directives:
            instances += getattr(self, name)(directive)
        return instances

    # ----------------------------------------------------------- directives
    def add_model(self, d: dict[str, Any]) -> list[Any]:
        path = self.resolve(d["file"])
        scope, name = scoped.split(self.scoped(d["name"]))
        instances = self.context.read_file(self.context, path, name, scope)
        self.added += instances[:1]
        return instances

    def add_model_instance(self, d: dict[str, Any]) -> list[Any]:
        self.plant.AddModelInstance(self.scoped(d["name"]))
        return []

    def add_frame(self, d: dict[str, Any]) -> list[Any]:
        X_PF = d.get("X_PF") or {}
        base = self.frame(X_PF.get("base_frame", "world"))
        namespace, element = scoped.split(self.scoped(d["name"]))
        instance = (
            self.plant.GetModelInstanceByName(namespace) if namespace else base.model_instance()
        )
        self.plant.AddFrame(FixedOffsetFrame(element, base, _transform(X_PF), instance))
        return []

    def add_weld(self, d: dict[str, Any]) -> list[Any]:
        parent, child = self.frame(d["parent"]), self.frame(d["child"])
        self.plant.WeldFrames(parent, child, _transform(d.get("X_PC")))
        if child.model_instance() not in self.added:
            raise SystemExit(
                "Failure at external/drake+/multibody/parsing/detail_dmd_parser.cc:46 in "
                "AddWeld(): condition 'found' failed."
            )
        return []

    def add_collision_filter_group(self, d: dict[str, Any]) -> list[Any]:
        if not self.context.has_scene_graph():
            return []
        scope = scoped.join(self.prefix, self.namespace, d.get("model_namespace") or "")
        if scope:
            self.plant.GetModelInstanceByName(scope)
        resolver = self.context.resolver
        resolver.add_group(
            Diagnostics(None),
            None,
            group_name=d["name"],
            body_names=set(d.get("members") or ()),
            member_group_names=set(d.get("member_groups") or ()),
            scope=scope,
        )
        for other in sorted(set(d.get("ignored_collision_filter_groups") or ())):
            resolver.add_pair(d["name"], other, scope)
        return []

    def add_directives(self, d: dict[str, Any]) -> list[Any]:
        namespace = self.namespace
        if d.get("model_namespace"):
            namespace = scoped.join(namespace, d["model_namespace"])
            if not self.plant.HasModelInstanceNamed(scoped.join(self.prefix, namespace)):
                raise RuntimeError(
                    f"Namespace '{d['model_namespace']}' does not exist as model instance"
                )
        path = self.resolve(d["file"])
        with open(path, encoding="utf-8") as stream:
            text = stream.read()
        nested = _Run(self.context, self.prefix, namespace, os.path.dirname(path), self.added)
        return nested.run(_load(text, path))


def _load(text: str, label: str) -> list[tuple[str, dict[str, Any]]]:
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "unknown"
        raise ModelParseError(f"yaml-cpp: error at {where}: {exc.problem}") from None
    directives = _Schema(label).check(root)
    for name, directive in directives:
        _validate(name, directive)
    return directives


def read_directives(
    context: ParseContext, source: ModelSource, model_name: str | None, parent_scope: str
) -> list[Any]:
    """Runs the directives in ``source``; returns the model instances they add."""
    del model_name  # N.B. A directives file names its own models.
    directives = _load(source.text, source.path or "<string>")
    return _Run(context, parent_scope, "", source.root_dir).run(directives)
