"""The scenario grammar: one table of commands, from which everything else is derived.

``GRAMMAR`` maps each op to its ``CommandSpec``. From it come the scenario
schema's step rules and feature tags (``grammar.schema``), the corpus's name
check, the feature tags a case needs, the backend's dispatch (one method per
op), the fuzzer's coverage check and the feature tags of regression files. A
new kind of work adds one table module here (``scene_graph``, ``multibody``)
and one handler module on the backend side (``queries``: posed scenes and
proximity queries, ``backends.queries``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from typing import Any

from conformance._grammar.multibody import MODEL_COMMANDS
from conformance._grammar.queries import QUERY_COMMANDS
from conformance._grammar.scene_graph import SCENE_GRAPH_COMMANDS
from conformance._grammar.spec import Arg, ArgKind, CommandSpec, Comparison, NameKind
from conformance._policy.release_facts import fact_holds

__all__ = [
    "FEATURE_BINDINGS",
    "GRAMMAR",
    "Arg",
    "ArgKind",
    "CommandSpec",
    "Comparison",
    "NameKind",
    "UnknownOpError",
    "declared_names",
    "features_of",
    "has_binding",
    "ops_of",
    "referenced_names",
    "release_features",
    "spec",
]

#: Every op of the scenario grammar, in the order the schema lists them.
GRAMMAR: Mapping[str, CommandSpec] = {
    command.op: command for command in (*SCENE_GRAPH_COMMANDS, *MODEL_COMMANDS, *QUERY_COMMANDS)
}


#: Feature tag → the release fact whose releases have it: a ``binding`` row, or a
#: ``behaviour`` row before which a case cannot be run at all (``gltf_meshes``: a .gltf
#: mesh cannot take the proximity role). Tags not listed are on every release (``core``,
#: ``transient``, ...), or need a module rather than a release (``multibody``,
#: ``parsing``: ``backends.multibody``).
FEATURE_BINDINGS: Mapping[str, str] = {
    "activation": "activation-since-1.55",
    "scope": "collision-filter-scope-since-1.42",
    "adjacency_opt_out": "adjacent-filters-opt-out-since-1.13",
    "filter_groups_report": "filter-groups-report-since-1.31",
    "gltf_meshes": "gltf-mesh-proximity-since-1.28",
}


def release_features(version: str) -> frozenset[str]:
    """The tags of ``FEATURE_BINDINGS`` that Drake ``version`` has, by the release table."""
    return frozenset(tag for tag, fact in FEATURE_BINDINGS.items() if fact_holds(fact, version))


def has_binding(op: str, version: str) -> bool:
    """Whether Drake ``version`` binds the call ``op`` makes (its ``CommandSpec.binding``)."""
    binding = spec(op).binding
    return binding is None or fact_holds(binding, version)


class UnknownOpError(KeyError):
    """Raised for an op the grammar does not have."""

    def __str__(self) -> str:
        return f"unknown op {self.args[0]!r} (the grammar has: {', '.join(GRAMMAR)})"


def spec(op: str) -> CommandSpec:
    """The CommandSpec of ``op``."""
    try:
        return GRAMMAR[op]
    except KeyError:
        raise UnknownOpError(op) from None


def ops_of(domain: str) -> tuple[str, ...]:
    """The ops of ``domain`` (``scene_graph``, ``model`` or ``queries``), in grammar order."""
    return tuple(op for op, command in GRAMMAR.items() if command.domain == domain)


def features_of(ops: Iterable[str]) -> frozenset[str]:
    """The feature tags a backend needs to run ``ops`` (unknown ops need none here)."""
    return frozenset(GRAMMAR[op].feature for op in ops if op in GRAMMAR)


def _set_names(value: Mapping[str, Sequence[str]]) -> Iterator[tuple[NameKind, str, str]]:
    for name in value.get("geometries", ()):
        yield NameKind.GEOMETRY, name, "geometries"
    for name in value.get("frames", ()):
        yield NameKind.FRAME, name, "frames"


def _pair_names(value: Sequence[str]) -> Iterator[tuple[NameKind, str, str]]:
    for name in value:
        yield NameKind.GEOMETRY, name, ""


def _pose_names(value: Mapping[str, Any]) -> Iterator[tuple[NameKind, str, str]]:
    for name in value:
        yield NameKind.FRAME, name, f".{name}"


def _statement_names(value: Mapping[str, Any]) -> Iterator[tuple[NameKind, str, str]]:
    for i, statement in enumerate(value.get("statements", ()), 1):
        for part in ("set", "a", "b"):
            for name_kind, name, _ in _set_names(statement.get(part, {})):
                yield name_kind, name, f".statements[{i}].{part}"


#: Argument kinds that hold names inside them → (kind, name, field suffix) of each.
_NAMES_INSIDE: Mapping[ArgKind, Callable[[Any], Iterator[tuple[NameKind, str, str]]]] = {
    ArgKind.PAIR: _pair_names,
    ArgKind.POSES: _pose_names,
    ArgKind.SET: lambda value: ((kind, name, "") for kind, name, _ in _set_names(value)),
    ArgKind.DECLARATION: _statement_names,
}


def referenced_names(op: str, args: Mapping[str, Any]) -> Iterator[tuple[NameKind, str, str]]:
    """(kind, name, field) for every name the command's arguments refer to (not declare)."""
    for key, kind in spec(op).arg_kinds.items():
        if key not in args:
            continue
        value = args[key]
        if kind.refers is not None:
            yield kind.refers, value, key
        elif kind in _NAMES_INSIDE:
            for name_kind, name, suffix in _NAMES_INSIDE[kind](value):
                yield name_kind, name, f"{key}{suffix}"


def declared_names(op: str, args: Mapping[str, Any]) -> Iterator[tuple[NameKind, str, str]]:
    """(kind, name, field) for every name the command declares (a body's name also
    declares its frame)."""
    for key, kind in spec(op).arg_kinds.items():
        if kind.declares is not None and key in args:
            yield kind.declares, args[key], key
            for also in kind.also_declares:
                yield also, args[key], key
