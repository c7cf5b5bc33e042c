"""The shape of a grammar row: ``CommandSpec`` (one op) built from ``Arg`` (one argument).

An argument's ``ArgKind`` says everything the harness derives from it: the
JSON-schema fragment that validates it, and the kind of name it refers to or
declares, which the corpus's name check follows (a step may only refer to
names declared in the scene or an earlier step). A ``CommandSpec`` with
``scoped_names`` (``add_models``) makes model-scoped names (``m::l1``,
``m::l1/Sphere``) referable from then on, as the model it parses holds them.
"""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

__all__ = ["Arg", "ArgKind", "CommandSpec", "Comparison", "NameKind"]


class NameKind(enum.Enum):
    """The namespaces of a case: what a name can stand for."""

    SOURCE = "source"
    FRAME = "frame"
    GEOMETRY = "geometry"
    CONTEXT = "context"
    LABEL = "label"
    BODY = "body"


#: A path below a case's temporary folder: relative, no ``..`` part.
_RELATIVE_PATH = {"type": "string", "pattern": "^(?!/)(?!.*(^|/)[.][.](/|$))[^\\\\]+$"}


class ArgKind(enum.Enum):
    """Argument types: (schema fragment, the NameKind it refers to, the NameKind it declares,
    and the NameKinds it also declares).

    ``SET``, ``PAIR`` and ``DECLARATION`` refer to frames and geometries inside
    them; ``names_in`` walks those. Two kinds never share a value (an Enum
    would make the second an alias of the first): kinds that validate alike
    differ in their schema's ``description``.
    """

    NEW_SOURCE = ({"$ref": "#/$defs/name"}, None, NameKind.SOURCE)
    NEW_FRAME = ({"$ref": "#/$defs/name"}, None, NameKind.FRAME)
    NEW_GEOMETRY = ({"$ref": "#/$defs/name"}, None, NameKind.GEOMETRY)
    NEW_CONTEXT = ({"$ref": "#/$defs/name"}, None, NameKind.CONTEXT)
    NEW_LABEL = ({"$ref": "#/$defs/name"}, None, NameKind.LABEL)
    SOURCE = ({"$ref": "#/$defs/name"}, NameKind.SOURCE, None)
    FRAME = ({"$ref": "#/$defs/ref"}, NameKind.FRAME, None)
    GEOMETRY = ({"$ref": "#/$defs/ref"}, NameKind.GEOMETRY, None)
    CONTEXT = ({"$ref": "#/$defs/context_arg"}, NameKind.CONTEXT, None)
    LABEL = ({"$ref": "#/$defs/label_ref"}, NameKind.LABEL, None)
    SET = ({"$ref": "#/$defs/geometry_set"}, None, None)
    PAIR = ({"$ref": "#/$defs/pair"}, None, None)
    DECLARATION = ({"$ref": "#/$defs/declaration"}, None, None)
    ROLE = ({"$ref": "#/$defs/role"}, None, None)
    ROLES = (
        {"type": "array", "items": {"$ref": "#/$defs/role"}, "uniqueItems": True},
        None,
        None,
    )
    ANY_ROLE = ({"enum": ["proximity", "illustration", "perception", "unassigned"]}, None, None)
    ASSIGN = ({"enum": ["new", "replace"]}, None, None)
    TEXT = ({"type": "string"}, None, None)
    # Multibody plants and model files (grammar.multibody).
    NEW_BODY = ({"$ref": "#/$defs/name"}, None, NameKind.BODY, (NameKind.FRAME,))
    BODY = (
        {
            "$ref": "#/$defs/ref",
            "description": "A body: 'world', a declared body, or 'model::body'.",
        },
        NameKind.BODY,
        None,
    )
    MODEL_INSTANCE = (
        {"type": "string", "minLength": 1, "description": "A model instance name."},
        None,
        None,
    )
    MODEL_TEXT = ({"type": "string", "description": "A model file's text."}, None, None)
    MODEL_FORMAT = ({"enum": ["urdf", "sdf", "dmd.yaml"]}, None, None)
    FILES = (
        {
            "type": "object",
            "description": "Files written to the case's package 'pkg': relative path to text.",
            "propertyNames": _RELATIVE_PATH,
            "additionalProperties": {"type": "string"},
        },
        None,
        None,
    )
    PATH = (
        {**_RELATIVE_PATH, "description": "A path below ``folder`` if given, else below 'pkg'."},
        None,
        None,
    )
    FOLDER = (
        {
            "type": "string",
            "minLength": 1,
            "description": "A folder of model files and their packages: absolute, or "
            "relative to the scenario file.",
        },
        None,
        None,
    )
    PACKAGES = (
        {
            "type": "object",
            "description": "Packages by name: each a folder, absolute or relative to the "
            "scenario file.",
            "propertyNames": {"type": "string", "minLength": 1},
            "additionalProperties": {"type": "string", "minLength": 1},
        },
        None,
        None,
    )
    BOOL = ({"type": "boolean"}, None, None)
    # Posed scenes and proximity queries (grammar.queries).
    SHAPE = ({"$ref": "#/$defs/shape"}, None, None)
    POSE = ({"$ref": "#/$defs/pose"}, None, None)
    POSES = ({"$ref": "#/$defs/poses"}, None, None)
    DISTANCE = ({"type": "number", "description": "A distance (m)."}, None, None)
    POINT = ({"$ref": "#/$defs/point"}, None, None)
    JOINT_TYPE = (
        {
            "enum": [
                "revolute",
                "prismatic",
                "weld",
                "ball_rpy",
                "universal",
                "planar",
                "quaternion_floating",
                "rpy_floating",
            ]
        },
        None,
        None,
    )

    @property
    def schema(self) -> dict[str, Any]:
        return dict(self.value[0])

    @property
    def refers(self) -> NameKind | None:
        return self.value[1]  # type: ignore[no-any-return]

    @property
    def declares(self) -> NameKind | None:
        return self.value[2]  # type: ignore[no-any-return]

    @property
    def also_declares(self) -> tuple[NameKind, ...]:
        """Further namespaces the declared name enters (a body's name is also its frame's)."""
        also: tuple[NameKind, ...] = self.value[3] if len(self.value) > 3 else ()
        return also


class Comparison(enum.Enum):
    """How two values of an op compare (``compare.value_differences``).

    - ``EXACT``: equal JSON values;
    - ``PROXIMITY``: query records (``{"pair", "shapes", ...}``, one or a
      sorted list): the pairs and shapes equal, every number within the
      tolerance of its shape pair (``conformance._tolerances``);
    - ``POSE``: ``{"xyz", "rotation"}`` within ``tolerances.POSE_TOLERANCE``;
    - ``INVENTORY``: ``{key: sorted list of strings}``, equal; a difference names,
      per key, the entries only one side has.
    """

    EXACT = "exact"
    PROXIMITY = "proximity"
    POSE = "pose"
    INVENTORY = "inventory"


@dataclass(frozen=True)
class Arg:
    """One argument of a command: its key in the step, its kind, whether it is required."""

    key: str
    kind: ArgKind
    required: bool = False


@dataclass(frozen=True)
class CommandSpec:
    """One op of the scenario grammar.

    - ``args``: the arguments, in the order a scenario writes them;
    - ``one_of``: groups of keys of which exactly one must be given;
    - ``needs``: (key, keys it needs): given ``key``, those are required too;
    - ``feature``: the feature tag a backend needs to run it;
    - ``binding``: the release fact (a ``binding`` row of
      ``policy/release_facts.json``) whose releases have the call; a backend
      of another release answers the op with a binding error, as that
      release's pydrake does (None: every release has it);
    - ``harness_only``: no backend executes it (``check`` only checks
      expectations); every other op is executed by the backend method of the
      same name;
    - ``doc``: one line for the schema and the README;
    - ``domain``: what it drives: ``scene_graph``, ``model`` (a plant and
      its parsers) or ``queries`` (poses and QueryObject queries); the
      lockstep fuzzer drives the SceneGraph ops;
    - ``compare``: how two of its values compare (``Comparison``: exact by
      default; the proximity queries and poses within tolerances);
    - ``error_choice``: a regular expression for the part of the op's error
      message that names one of several equally valid choices Drake makes
      in no specified order; two messages agree whatever that part says;
    - ``scoped_names``: from this step on, a case may refer to model-scoped
      names (``m::l1``, ``m::l1/Sphere``) that the corpus cannot see
      statically (the model text holds them).
    """

    op: str
    args: tuple[Arg, ...]
    feature: str
    doc: str
    one_of: tuple[tuple[str, ...], ...] = ()
    needs: tuple[tuple[str, tuple[str, ...]], ...] = ()
    binding: str | None = None
    harness_only: bool = False
    domain: str = "scene_graph"
    scoped_names: bool = False
    compare: Comparison = Comparison.EXACT
    error_choice: str | None = None

    @property
    def handler(self) -> str | None:
        """The name of the backend method that executes it (``None`` if ``harness_only``)."""
        return None if self.harness_only else self.op

    @property
    def arg_kinds(self) -> Mapping[str, ArgKind]:
        return {arg.key: arg.kind for arg in self.args}
