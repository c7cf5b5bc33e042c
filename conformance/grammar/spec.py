"""The shape of a grammar row: ``CommandSpec`` (one op) built from ``Arg`` (one argument).

An argument's ``ArgKind`` says everything the harness derives from it: the
JSON-schema fragment that validates it, and the kind of name it refers to or
declares, which the corpus's name check follows (a step may only refer to
names declared in the scene or an earlier step).
"""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

__all__ = ["Arg", "ArgKind", "CommandSpec", "NameKind"]


class NameKind(enum.Enum):
    """The namespaces of a case: what a name can stand for."""

    SOURCE = "source"
    FRAME = "frame"
    GEOMETRY = "geometry"
    CONTEXT = "context"
    LABEL = "label"


class ArgKind(enum.Enum):
    """Argument types: (schema fragment, the NameKind it refers to, the NameKind it declares).

    ``SET``, ``PAIR`` and ``DECLARATION`` refer to frames and geometries inside
    them; ``names_in`` walks those.
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

    @property
    def schema(self) -> dict[str, Any]:
        return dict(self.value[0])

    @property
    def refers(self) -> NameKind | None:
        return self.value[1]  # type: ignore[no-any-return]

    @property
    def declares(self) -> NameKind | None:
        return self.value[2]  # type: ignore[no-any-return]


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
    - ``feature``: the feature tag a backend needs to run it;
    - ``since``/``until``: the Drake releases that have the call;
    - ``harness_only``: no backend executes it (``check`` only checks
      expectations); every other op is executed by the backend method of the
      same name;
    - ``doc``: one line for the schema and the README.
    """

    op: str
    args: tuple[Arg, ...]
    feature: str
    doc: str
    one_of: tuple[tuple[str, ...], ...] = ()
    since: str | None = None
    until: str | None = None
    harness_only: bool = False

    @property
    def handler(self) -> str | None:
        """The name of the backend method that executes it (``None`` if ``harness_only``)."""
        return None if self.harness_only else self.op

    @property
    def arg_kinds(self) -> Mapping[str, ArgKind]:
        return {arg.key: arg.kind for arg in self.args}
