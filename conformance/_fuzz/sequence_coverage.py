"""Sequence coverage: which pairs and triples of consecutive located events a campaign ran.

The feature table (``conformance._fuzz.coverage``) counts each event on its
own, so it reads "reached" while the *combinations* never happen. Here an
**event** is one command of the grammar's filter, context and role ops
(``SEQUENCE_OPS``) with the kind of location it ran at (``op@kind``: the
model, a context made by ``create_context``, or a clone made by
``clone_context``), and a **pair** is two consecutive events of one example:

- commands that only read (queries, ``is_active``, ``check``...) sit between
  events without separating them; an edit that is not a sequence op
  (``register_geometry``, ``remove_geometry``, ``register_frame``,
  ``register_source``) ends the run of events, so ``a`` then a registration
  then ``b`` is no pair;
- a command that the reference refused because a name it got does not
  exist (``UNKNOWN_KINDS``), or that the harness could not send, is no
  event; a refusal for a reason of state (transient history, a role twice
  or missing, a source that does not own the geometry) is one.

Each pair has the **relation** of the second event's location to the
first's (``Relation``): the same location; a descendant (model → context,
context → its clone, a clone → its clone); its origin (clone → the context
it was cloned from, context → model); or other (two unrelated contexts).

A pair is **reachable** when both events are issued by the campaign and its
relation is the one its kinds imply when the locations are related
(``PRINCIPAL``: same kind → same location, model → context or clone →
descendant, clone → context or model and context → model → origin). Every
reachable pair is ``expected_pairs``; ``SequenceCoverage.table`` lists the
ones never reached. Pairs of other relations, and triples (three consecutive
events, with both relations), are counted and reported as numbers.

Steering towards the pairs never reached: ``conformance._fuzz.sequence_tour``.
"""

from __future__ import annotations

import enum
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from conformance._fuzz.coverage import EDITS, LocationKind, located_ops
from conformance._grammar import GRAMMAR, ArgKind
from conformance.protocol import Command, ErrorKind, Result

__all__ = [
    "BREAKERS",
    "PRINCIPAL",
    "SEQUENCE_OPS",
    "UNKNOWN_KINDS",
    "Relation",
    "SequenceBook",
    "SequenceCoverage",
    "expected_pairs",
    "sequence_events",
]

MODEL = LocationKind.MODEL
CONTEXT = LocationKind.CONTEXT
CLONE = LocationKind.CLONE

#: The grammar's filter, context and role ops: the events of a sequence.
SEQUENCE_OPS = frozenset(
    {
        "apply",
        "apply_transient",
        "remove_declaration",
        "activate",
        "deactivate",
        "create_context",
        "clone_context",
        "set_default_context",
        "assign_role",
        "remove_role",
    }
)
#: Edits that are not sequence ops: one ends the run of consecutive events.
BREAKERS = EDITS - SEQUENCE_OPS

#: Refusals that mean nothing happened at the location (a name that is not there),
#: or that the harness could not send the call: such a command is no event.
UNKNOWN_KINDS = frozenset(
    {
        ErrorKind.UNKNOWN_GEOMETRY,
        ErrorKind.UNKNOWN_FRAME,
        ErrorKind.UNKNOWN_SOURCE,
        ErrorKind.BINDING,
        ErrorKind.REFUSED,
    }
)


class Relation(enum.Enum):
    """Where the second event of a pair ran, seen from the first's location."""

    SAME = "same"
    DESCENDANT = "descendant"  # model → context, context → its clone
    ORIGIN = "origin"  # clone → the context it came from, context → model
    OTHER = "other"  # two unrelated contexts


#: The relation a pair of kinds has when its locations are related: (kind, kind) → relation.
_DEPTH = {MODEL: 0, CONTEXT: 1, CLONE: 2}
PRINCIPAL: dict[tuple[str, str], Relation] = {
    (a, b): (
        Relation.SAME
        if a == b
        else Relation.DESCENDANT
        if _DEPTH[a] < _DEPTH[b]
        else Relation.ORIGIN
    )
    for a in LocationKind.ALL
    for b in LocationKind.ALL
}


def sequence_events(ops: Iterable[str], kinds: Iterable[str] = LocationKind.ALL) -> list[str]:
    """The events (``op@kind``) of the sequence ops among ``ops`` at the location
    ``kinds`` a campaign uses, in a stable order."""
    chosen = sorted(op for op in ops if op in SEQUENCE_OPS)
    used = set(kinds)
    return [
        f"{op}@{kind}"
        for op, located in located_ops(chosen).items()
        for kind in located
        if kind in used
    ]


def expected_pairs(
    ops: Iterable[str], kinds: Iterable[str] = LocationKind.ALL
) -> list[tuple[str, str]]:
    """Every reachable pair of the events of ``ops`` at ``kinds``: all ordered pairs,
    loops included (each in its ``PRINCIPAL`` relation)."""
    events = sequence_events(ops, kinds)
    return [(a, b) for a in events for b in events]


def _kind(event: str) -> str:
    return event.rpartition("@")[2]


@cache
def _location_keys(op: str) -> tuple[str, ...]:
    return tuple(arg.key for arg in GRAMMAR[op].args if arg.kind is ArgKind.CONTEXT)


@dataclass
class SequenceBook:
    """One example's locations and its last events (see the module doc)."""

    #: context → the location it was made from (``MODEL`` for create_context).
    parent: dict[str, str] = field(default_factory=dict)
    clones: set[str] = field(default_factory=set)
    #: The last two events: (event, location).
    last: list[tuple[str, str]] = field(default_factory=list)
    #: Transient labels active at each location, oldest first (``sequence_tour`` reads it).
    active: dict[str, list[str]] = field(default_factory=lambda: {MODEL: []})
    pairs: Counter[tuple[str, Relation, str]] = field(default_factory=Counter)
    triples: Counter[tuple[str, str, str]] = field(default_factory=Counter)
    #: How many events the example has had, and how many commands.
    events: int = 0
    commands: int = 0
    #: The frames and geometries each location has (``sequence_tour`` names only these).
    names: dict[str, set[str]] = field(default_factory=lambda: {MODEL: {"world"}})

    def kind(self, location: str) -> str:
        if location == MODEL:
            return MODEL
        return CLONE if location in self.clones else CONTEXT

    def ancestors(self, location: str) -> list[str]:
        """``location``'s origin, its origin's, ... up to the model."""
        chain = []
        while location in self.parent:
            location = self.parent[location]
            chain.append(location)
        return chain

    def relation(self, first: str, second: str) -> Relation:
        if first == second:
            return Relation.SAME
        if first in self.ancestors(second):
            return Relation.DESCENDANT
        if second in self.ancestors(first):
            return Relation.ORIGIN
        return Relation.OTHER

    def follow(self, command: Command, result: Result) -> None:
        """Counts the pair and triple ``command`` ends, given the reference's ``result``."""
        self.commands += 1
        where = next(
            (str(command.args[k]) for k in _location_keys(command.op) if k in command.args),
            MODEL,
        )
        if result.error is None:
            self._track(command, where)
        if command.op in BREAKERS:
            self.last.clear()
            return
        if command.op not in SEQUENCE_OPS:
            return
        if result.error is not None and result.error.kind in UNKNOWN_KINDS:
            return
        event = f"{command.op}@{self.kind(where)}"
        self.events += 1
        if self.last:
            before, at = self.last[-1]
            self.pairs[(before, self.relation(at, where), event)] += 1
            if len(self.last) == 2:
                self.triples[(self.last[0][0], before, event)] += 1
        self.last = [*self.last[-1:], (event, where)]

    def _track(self, command: Command, where: str) -> None:
        args = command.args
        if command.op in ("create_context", "clone_context"):
            name = str(args["name"])
            self.parent[name] = where
            self.active[name] = list(self.active.get(where, ())) if where != MODEL else []
            self.names[name] = set(self.names.get(where, ()))
            if command.op == "clone_context":
                self.clones.add(name)
        elif command.op in ("register_frame", "register_geometry"):
            self.names.setdefault(where, set()).add(str(args["name"]))
        elif command.op == "remove_geometry":
            self.names.setdefault(where, set()).discard(str(args["geometry"]))
        elif command.op == "apply_transient":
            self.active.setdefault(where, []).append(str(args["label"]))
        elif command.op == "remove_declaration":
            stack = self.active.setdefault(where, [])
            if args["label"] in stack:
                stack.remove(str(args["label"]))


@dataclass
class SequenceCoverage:
    """Pair and triple counts over a run (``SequenceBook.pairs`` of every example)."""

    pairs: Counter[tuple[str, Relation, str]] = field(default_factory=Counter)
    triples: Counter[tuple[str, str, str]] = field(default_factory=Counter)

    def close(self, book: SequenceBook) -> None:
        """Takes an example's counts."""
        self.pairs.update(book.pairs)
        self.triples.update(book.triples)

    def principal(self, pair: tuple[str, str]) -> int:
        """How often ``pair`` was reached in its principal relation."""
        a, b = pair
        return self.pairs[(a, PRINCIPAL[(_kind(a), _kind(b))], b)]

    def gaps(self, expected: Iterable[tuple[str, str]]) -> list[tuple[str, str]]:
        """The reachable pairs never reached (in their principal relation)."""
        return [pair for pair in expected if not self.principal(pair)]

    def table(self, expected: Iterable[tuple[str, str]]) -> str:
        """What ``fuzz --coverage`` prints: a headline, one row per first event (pairs
        reached of those reachable, the rarest count), and the pairs never reached."""
        expected = list(expected)
        gaps = self.gaps(expected)
        other = sum(n for (_, rel, _), n in self.pairs.items() if rel is Relation.OTHER)
        lines = [
            f"sequence pairs: {len(expected) - len(gaps)} of {len(expected)} reachable pairs "
            f"reached ({sum(self.pairs.values())} pairs in all, {other} between unrelated "
            f"contexts); {len(self.triples)} distinct triples"
        ]
        firsts = list(dict.fromkeys(a for a, _ in expected))
        width = max((len(a) for a in firsts), default=0)
        for first in firsts:
            counts = [self.principal(p) for p in expected if p[0] == first]
            reached = sum(1 for n in counts if n)
            lines.append(
                f"  {first:<{width}}  then {reached:>2} of {len(counts)}  "
                f"rarest {min(counts):>5}  {'GAP' if reached < len(counts) else ''}".rstrip()
            )
        lines.append(
            "pair gaps: " + (", ".join(f"{a} -> {b}" for a, b in gaps) if gaps else "none")
        )
        return "\n".join(lines)

    def to_json(self, expected: Iterable[tuple[str, str]]) -> dict[str, Any]:
        expected = list(expected)
        return {
            "pairs": {f"{a} -> {b}": self.principal((a, b)) for a, b in expected},
            "gaps": [f"{a} -> {b}" for a, b in self.gaps(expected)],
            "other_relation_pairs": sum(
                n for (_, rel, _), n in self.pairs.items() if rel is Relation.OTHER
            ),
            "distinct_triples": len(self.triples),
        }
