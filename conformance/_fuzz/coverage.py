"""What a fuzz run reached: state-space features, counted, with the ones never reached as gaps.

A ``CoverageBook`` follows one example's commands, with the reference's
results (as ``operations.PoseBook`` does), and names the features each
command reaches. ``Coverage`` counts them over a run, keeps the maxima, and
prints the table ``fuzz --coverage`` shows. Every feature is a fact about the
state the commands built, never about how the machine chose them, so the
table reads the same for any generator.

The book keeps, per *location* (the model, or a context by name):

- ``proximity[loc]``: the proximity geometries there. A context starts with
  the model's (``create_context``) or its origin's (``clone_context``);
  register_geometry with the proximity role, assign_role, remove_role (of a
  geometry, or of every geometry on a frame) and remove_geometry change it
  where they run;
- ``active[loc]``: the labels of the transient declarations active there, in
  the order they were applied.

The features (``FEATURES``; ``{op}@{kind}`` and ``error:{kind}`` besides):

=================================  ============================================================
proximity>16                       a command of the sequence (not the initial scene) takes a
                                   location past 16 proximity geometries
transients>=5                      an apply_transient leaves 5 or more active at its location
out_of_order_removal               remove_declaration of an active declaration that is not the
                                   newest at its location
out_of_order_removal_from_5        the same, with 5 or more active before it
clone_with_history                 clone_context of a location with active transient
                                   declarations
clone_with_history_edited_both     after such a clone, an edit in the clone and one in its
                                   origin (counted once per clone)
model_edit_after_context           a model edit while contexts exist
edit_in_clone                      an edit in a context made by clone_context
edit_in_clone_origin               an edit in a location after a clone was made of it
edit_stretch>=8                    8 edits in a row, 2 or more of the model and of contexts
                                   each, with no transient declaration active anywhere, while
                                   contexts exist
role_by_frame_then_filter          a filter edit after a remove_role by frame
reassigned_by_frame_then_filter    a filter edit after a geometry whose roles were removed by
                                   frame got the proximity role back
{op}@model, @context, @clone       the op ran at that kind of location
error:{kind}                       the reference raised an error of that ``ErrorKind``
=================================  ============================================================

Posed campaigns (a machine that issues the query ops) also count, from the
reference's answers (``QUERY_FEATURES``): a penetration, a signed distance and
a point distance with a ``mesh``, and with a ``convex``, among its records.

An *edit* is a command that changes the state (``EDITS``), run without error.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from conformance._grammar import GRAMMAR, ArgKind
from conformance.protocol import MODEL, Command, ErrorKind, Result

__all__ = [
    "EDITS",
    "ERROR_KINDS",
    "FEATURES",
    "FILTER_EDITS",
    "QUERY_FEATURES",
    "Coverage",
    "CoverageBook",
    "LocationKind",
    "campaign_features",
    "expected_features",
    "located_ops",
]

#: The state-space features and what each means (the module doc has the table).
FEATURES: dict[str, str] = {
    "proximity>16": "a location grows past 16 proximity geometries during the sequence",
    "transients>=5": "5 or more transient declarations active at a location",
    "out_of_order_removal": "an active declaration removed while a newer one is active",
    "out_of_order_removal_from_5": "... while 4 or more others are active there",
    "clone_with_history": "a context cloned while it has transient declarations",
    "clone_with_history_edited_both": "... then edits in both the clone and its origin",
    "model_edit_after_context": "a model edit while contexts exist",
    "edit_in_clone": "an edit in a cloned context",
    "edit_in_clone_origin": "an edit in a location after it was cloned",
    "edit_stretch>=8": "8 edits in a row, of the model and of contexts (2+ of each), "
    "with no transient declaration active anywhere, while contexts exist",
    "role_by_frame_then_filter": "a filter edit after a remove_role by frame",
    "reassigned_by_frame_then_filter": "a filter edit after a geometry whose role was "
    "removed by frame got the proximity role back",
}

#: Ops that change the state when they succeed.
EDITS = frozenset(
    {
        "register_source",
        "register_frame",
        "register_geometry",
        "assign_role",
        "remove_role",
        "remove_geometry",
        "apply",
        "apply_transient",
        "remove_declaration",
        "activate",
        "deactivate",
    }
)
#: Edits of the collision filters themselves.
FILTER_EDITS = frozenset(
    {"apply", "apply_transient", "remove_declaration", "activate", "deactivate"}
)

#: The error kinds the fuzzer provokes on purpose (unknown names, edits refused by
#: the history, roles twice or missing, sources that do not own the geometry);
#: BINDING, REFUSED, OTHER and INVALID_QUERY mean a harness or version problem,
#: not a state, so they are counted but not expected.
ERROR_KINDS = (
    ErrorKind.UNKNOWN_GEOMETRY,
    ErrorKind.UNKNOWN_FRAME,
    ErrorKind.UNKNOWN_SOURCE,
    ErrorKind.TRANSIENT_HISTORY,
    ErrorKind.DUPLICATE_ROLE,
    ErrorKind.MISSING_ROLE,
    ErrorKind.NOT_OWNED,
)

#: The features that need several commands in an order: ``hypothesis.target`` seeks them.
_COMPOUND = frozenset(
    {
        "proximity>16",
        "out_of_order_removal_from_5",
        "clone_with_history_edited_both",
        "edit_stretch>=8",
        "reassigned_by_frame_then_filter",
    }
)

#: Where one edit stretch needs to go on before it counts.
_STRETCH = 8
_CROWD = 16
_STACK = 5


class LocationKind:
    """The three kinds of location a command runs at."""

    MODEL = "model"
    CONTEXT = "context"
    CLONE = "clone"
    ALL = (MODEL, CONTEXT, CLONE)


def located_ops(ops: Iterable[str]) -> dict[str, tuple[str, ...]]:
    """op → the location kinds it can run at: all three if it takes a context, else the model.

    ``set_default_context`` and ``clone_context`` need a context; every other op
    whose context is optional also runs at the model.
    """
    kinds: dict[str, tuple[str, ...]] = {}
    for op in ops:
        spec = GRAMMAR[op]
        located = [a for a in spec.args if a.kind is ArgKind.CONTEXT]
        if not located:
            kinds[op] = (LocationKind.MODEL,)
        elif all(a.required for a in located):
            kinds[op] = (LocationKind.CONTEXT, LocationKind.CLONE)
        else:
            kinds[op] = LocationKind.ALL
    return kinds


def expected_features(ops: Iterable[str]) -> list[str]:
    """Every feature a run that issues ``ops`` should reach: ``FEATURES``, each op at
    each kind of location it can run at, and ``ERROR_KINDS``."""
    located = [f"{op}@{kind}" for op, kinds in located_ops(ops).items() for kind in kinds]
    errors = [f"error:{kind.value}" for kind in ERROR_KINDS]
    return [*FEATURES, *sorted(located), *errors]


def campaign_features(operations: Iterable[str], shared: frozenset[str]) -> list[str]:
    """``expected_features`` of the grammar ops a machine's operations issue
    (``operations.issued_ops``), less those of a feature both backends lack
    (``shared``: ``activation``, ``queries``); with the query ops, ``QUERY_FEATURES``."""
    ops = sorted(op for op in operations if GRAMMAR[op].feature not in _OPTIONAL - shared)
    queried = set(_QUERY_RECORDS) <= set(ops)
    return [*expected_features(ops), *(QUERY_FEATURES if queried else ())]


#: Query op → its short name in ``QUERY_FEATURES``.
_QUERY_RECORDS = {
    "compute_point_pair_penetration": "penetration",
    "compute_signed_distance_pairwise_closest_points": "distance",
    "compute_signed_distance_to_point": "point_distance",
}
#: A query record (in the reference's answer) with a mesh or convex hull among its shapes.
QUERY_FEATURES: dict[str, str] = {
    f"{name}:{shape}": f"a {name.replace('_', ' ')} record of a {shape}"
    for name in _QUERY_RECORDS.values()
    for shape in ("mesh", "convex")
}


def _query_features(op: str, value: object) -> Iterator[str]:
    """``QUERY_FEATURES`` a query's answer reaches (its records' shapes)."""
    name = _QUERY_RECORDS.get(op)
    if name is None or not isinstance(value, list):
        return
    shapes = {
        shape
        for record in value
        if isinstance(record, Mapping)
        for shape in (*record.get("shapes", ()), record.get("shape"))
    }
    yield from (f"{name}:{shape}" for shape in ("mesh", "convex") if shape in shapes)


#: Grammar features that some backends lack; their ops are expected only if both have them.
_OPTIONAL = frozenset({"activation", "queries"})


@cache
def _location_keys(op: str) -> tuple[str, ...]:
    """The keys of ``op``'s arguments that name a context."""
    return tuple(arg.key for arg in GRAMMAR[op].args if arg.kind is ArgKind.CONTEXT)


def _location_arg(command: Command) -> str | None:
    for key in _location_keys(command.op):
        if key in command.args:
            return str(command.args[key])
    return None


@dataclass
class CoverageBook:
    """One example's state, as far as the features need it (see the module doc)."""

    proximity: dict[str, set[str]] = field(default_factory=lambda: {MODEL: set()})
    active: dict[str, list[str]] = field(default_factory=lambda: {MODEL: []})
    #: geometry → its frame.
    frames: dict[str, str] = field(default_factory=dict)
    clones: set[str] = field(default_factory=set)
    cloned: set[str] = field(default_factory=set)
    #: The initial scene is registered: growth from here on is the sequence's.
    sequence_started: bool = False
    #: The current edit stretch: how many edits of the model and of contexts.
    stretch: Counter[str] = field(default_factory=Counter)
    role_by_frame: bool = False
    #: Geometries whose proximity role was removed by frame.
    lost_by_frame: set[str] = field(default_factory=set)
    reassigned: bool = False
    #: Clones of a location with history → the sides (the clone, its origin) not edited since.
    watched: dict[str, set[str]] = field(default_factory=dict)
    #: The largest count of proximity geometries at a location, and of active declarations.
    max_proximity: int = 0
    max_transients: int = 0
    #: How often the example reached each compound feature (``_COMPOUND``).
    compound: Counter[str] = field(default_factory=Counter)

    def follow(self, command: Command, result: Result) -> list[str]:
        """The features ``command`` reached, given the reference's ``result``."""
        reached = list(self._reached(command, result))
        self.compound.update(name for name in reached if name in _COMPOUND)
        return reached

    def _reached(self, command: Command, result: Result) -> Iterator[str]:
        where = _location_arg(command) or MODEL
        kind = (
            LocationKind.MODEL
            if where == MODEL
            else LocationKind.CLONE
            if where in self.clones
            else LocationKind.CONTEXT
        )
        yield f"{command.op}@{kind}"
        if result.error is not None:
            yield f"error:{result.error.kind.value}"
            return
        follow = _FOLLOW.get(command.op)
        if follow is not None:
            yield from follow(self, command.args, where)
        yield from _query_features(command.op, result.value)
        if command.op in EDITS:
            yield from self._edit(command.op, where)

    def targets(self) -> dict[str, float]:
        """What ``hypothesis.target`` maximises for the example.

        Each score stops growing once its feature is reached (17 proximity
        geometries, 5 active declarations, each compound feature once): a
        larger scene costs every later comparison, and finds nothing more.
        """
        return {
            "proximity geometries at a location": float(min(self.max_proximity, _CROWD + 1)),
            "active transient declarations": float(min(self.max_transients, _STACK)),
            "compound features": float(len(self.compound)),
        }

    # ------------------------------------------------------------ edits
    def _edit(self, op: str, where: str) -> Iterator[str]:
        contexts = len(self.proximity) > 1
        if where == MODEL and contexts:
            yield "model_edit_after_context"
        if where in self.clones:
            yield "edit_in_clone"
        if where in self.cloned:
            yield "edit_in_clone_origin"
        yield from self._edited_both(where)
        if op in FILTER_EDITS:
            if self.role_by_frame:
                yield "role_by_frame_then_filter"
            if self.reassigned:
                yield "reassigned_by_frame_then_filter"
        if contexts and not any(self.active.values()):
            self.stretch[LocationKind.MODEL if where == MODEL else LocationKind.CONTEXT] += 1
            if (
                self.stretch.total() >= _STRETCH
                and min(self.stretch[LocationKind.MODEL], self.stretch[LocationKind.CONTEXT]) >= 2
            ):
                yield "edit_stretch>=8"
                self.stretch.clear()
        else:
            self.stretch.clear()

    def _edited_both(self, where: str) -> Iterator[str]:
        for clone, unedited in list(self.watched.items()):
            unedited.discard(where)
            if not unedited:
                del self.watched[clone]
                yield "clone_with_history_edited_both"

    # ----------------------------------------------------------- follow
    def _grow(self, where: str, geometries: Iterable[str]) -> Iterator[str]:
        at = self.proximity.setdefault(where, set())
        before = len(at)
        at.update(geometries)
        self.max_proximity = max(self.max_proximity, len(at))
        if self.sequence_started and before <= _CROWD < len(at):
            yield "proximity>16"

    def _register(self, args: Mapping[str, Any], where: str) -> Iterator[str]:
        self.frames[args["name"]] = args.get("frame", "world")
        if "proximity" in args.get("roles", ()):
            yield from self._grow(where, [args["name"]])

    def _assign(self, args: Mapping[str, Any], where: str) -> Iterator[str]:
        if args.get("role") == "proximity":
            self.reassigned = self.reassigned or args["geometry"] in self.lost_by_frame
            yield from self._grow(where, [args["geometry"]])

    def _remove_role(self, args: Mapping[str, Any], where: str) -> Iterator[str]:
        if args.get("role") in ("proximity", "unassigned"):
            if "frame" in args:
                self.role_by_frame = True
                gone = {g for g, f in self.frames.items() if f == args["frame"]}
                self.lost_by_frame.update(gone)
            else:
                gone = {args["geometry"]}
            self.proximity.setdefault(where, set()).difference_update(gone)
        return iter(())

    def _remove_geometry(self, args: Mapping[str, Any], where: str) -> Iterator[str]:
        self.proximity.setdefault(where, set()).discard(args["geometry"])
        return iter(())

    def _apply_transient(self, args: Mapping[str, Any], where: str) -> Iterator[str]:
        stack = self.active.setdefault(where, [])
        stack.append(args["label"])
        self.max_transients = max(self.max_transients, len(stack))
        if len(stack) >= _STACK:
            yield "transients>=5"

    def _remove_declaration(self, args: Mapping[str, Any], where: str) -> Iterator[str]:
        stack = self.active.setdefault(where, [])
        label = args["label"]
        if label in stack:
            if label != stack[-1]:
                yield "out_of_order_removal"
                if len(stack) >= _STACK:
                    yield "out_of_order_removal_from_5"
            stack.remove(label)

    def _new_context(self, args: Mapping[str, Any], where: str) -> Iterator[str]:
        self.proximity[args["name"]] = set(self.proximity[MODEL])
        self.active[args["name"]] = []
        return iter(())

    def _clone(self, args: Mapping[str, Any], where: str) -> Iterator[str]:
        origin = args["from"]
        if self.active.get(origin):
            yield "clone_with_history"
            self.watched[args["name"]] = {origin, args["name"]}
        self.proximity[args["name"]] = set(self.proximity.get(origin, ()))
        self.active[args["name"]] = list(self.active.get(origin, ()))
        self.clones.add(args["name"])
        self.cloned.add(origin)


_FOLLOW = {
    "register_geometry": CoverageBook._register,
    "assign_role": CoverageBook._assign,
    "remove_role": CoverageBook._remove_role,
    "remove_geometry": CoverageBook._remove_geometry,
    "apply_transient": CoverageBook._apply_transient,
    "remove_declaration": CoverageBook._remove_declaration,
    "create_context": CoverageBook._new_context,
    "clone_context": CoverageBook._clone,
}


@dataclass
class Coverage:
    """Feature counts over a run, and the maxima of ``CoverageBook``."""

    hits: Counter[str] = field(default_factory=Counter)
    max_proximity: int = 0
    max_transients: int = 0

    def add(self, features: Iterable[str]) -> None:
        self.hits.update(features)

    def close(self, book: CoverageBook) -> None:
        """Takes an example's maxima."""
        self.max_proximity = max(self.max_proximity, book.max_proximity)
        self.max_transients = max(self.max_transients, book.max_transients)

    def rows(self, expected: Iterable[str]) -> list[tuple[str, int]]:
        """(feature, count) for every expected feature, then any other feature reached."""
        expected = list(expected)
        others = sorted(set(self.hits) - set(expected))
        return [(name, self.hits[name]) for name in [*expected, *others]]

    def gaps(self, expected: Iterable[str], *, at_least: int = 1) -> list[str]:
        """The expected features reached fewer than ``at_least`` times."""
        return [name for name in expected if self.hits[name] < at_least]

    def headline(self, expected: list[str]) -> str:
        """The table's first line: how many features were reached, and the maxima."""
        return (
            f"coverage: {len(expected) - len(self.gaps(expected))} of {len(expected)} features "
            f"reached; max {self.max_proximity} proximity geometries at a location, "
            f"max {self.max_transients} active transient declarations"
        )

    def table(self, expected: Iterable[str]) -> str:
        """The coverage table ``fuzz --coverage`` prints."""
        expected = list(expected)
        rows = self.rows(expected)
        width = max(len(name) for name, _ in rows)
        lines = [self.headline(expected)]
        for name, count in rows:
            mark = "GAP" if count == 0 and name in expected else ""
            lines.append(f"  {name:<{width}}  {count:>7}  {mark}".rstrip())
        gaps = self.gaps(expected)
        lines.append(f"gaps: {', '.join(gaps)}" if gaps else "gaps: none")
        return "\n".join(lines)

    def to_json(self, expected: Iterable[str]) -> dict[str, Any]:
        expected = list(expected)
        return {
            "features": dict(self.rows(expected)),
            "expected": expected,
            "gaps": self.gaps(expected),
            "max_proximity_geometries": self.max_proximity,
            "max_active_transients": self.max_transients,
        }
