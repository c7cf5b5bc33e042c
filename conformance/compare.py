"""The one agreement check: do two backends answer a command the same way?

Everything that compares backends (the scenario runner, the lockstep fuzzer,
tests) calls ``diff``. Two answers agree iff ``diff`` is empty:

- **Results** agree iff both returned values that agree, or both raised the
  same ``ErrorKind`` with the same normalised message. Binding errors (no
  overload accepts the arguments) compare by kind alone: their wording is
  pybind11's, and it changes between releases.
- **Values** agree as the op's ``CommandSpec.compare`` says
  (``value_differences``, which the expectations' ``returns`` use too):
  ``EXACT``, equal JSON values; ``PROXIMITY``, query records (one, or a
  sorted list) with equal pairs and shapes in the same order and every
  number within the tolerance of its record's shape pair
  (``conformance.tolerances``); ``POSE``, ``xyz`` and rotation entries within
  ``tolerances.POSE_TOLERANCE``.
- **Observations** agree iff they have the same locations and, at each one,
  the same candidate set C, the same IsActive of every declaration label and
  the same ``has_transient_history()``. Two filters are equivalent iff they
  report the same CanCollideWith for every pair (collision_filter.h), so C is
  compared as a set of name pairs.

Differences are ordered (result first, then locations by name) and carry the
*reference*'s value first, so a report can say what the oracle did.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from conformance.grammar import GRAMMAR, Comparison
from conformance.protocol import ErrorKind, Observation, Pair, Result
from conformance.tolerances import POSE_TOLERANCE, tolerance

__all__ = [
    "Difference",
    "diff",
    "diff_observations",
    "diff_results",
    "format_pairs",
    "value_differences",
]


@dataclass(frozen=True)
class Difference:
    """One way in which ``other`` differs from ``reference`` (both JSON-able values)."""

    what: str
    reference: Any
    other: Any

    def __str__(self) -> str:
        return (
            f"{self.what}: reference {json.dumps(self.reference, sort_keys=True)}, "
            f"other {json.dumps(self.other, sort_keys=True)}"
        )


def format_pairs(pairs: Iterable[Pair]) -> list[str]:
    """``["a-b", ...]``, sorted: how reports show a set of pairs."""
    return sorted(f"{a}-{b}" for a, b in pairs)


#: A record field → the Tolerance attribute it is compared within.
_FIELD_TOLERANCE: Mapping[str, str] = {
    "depth": "distance",
    "distance": "distance",
    "p_WCa": "witness",
    "p_WCb": "witness",
    "p_ACa": "witness",
    "p_BCb": "witness",
    "nhat_BA_W": "normal",
}
#: Record fields compared exactly.
_EXACT_FIELDS = ("pair", "shapes")


def _gap(reference: Any, other: Any) -> float:
    """``|a − b|`` of two numbers, ``‖a − b‖`` of two vectors (NaN if either is malformed)."""
    if isinstance(reference, (int, float)) and isinstance(other, (int, float)):
        return abs(float(reference) - float(other))
    if (
        isinstance(reference, Sequence)
        and isinstance(other, Sequence)
        and len(reference) == len(other)
        and all(isinstance(x, (int, float)) for x in (*reference, *other))
    ):
        return math.sqrt(
            sum((float(a) - float(b)) ** 2 for a, b in zip(reference, other, strict=True))
        )
    return math.nan


def _record_differences(reference: Any, other: Any) -> Iterator[str]:
    """How a query record differs beyond its shape pair's tolerances."""
    if not isinstance(reference, Mapping) or not isinstance(other, Mapping):
        yield "not a query record"
        return
    name = "-".join(map(str, reference.get("pair", ())))
    if sorted(reference) != sorted(other):
        yield f"{name} fields {sorted(reference)} vs {sorted(other)}"
        return
    for key in _EXACT_FIELDS:
        if reference.get(key) != other.get(key):
            yield f"{name} {key} {reference.get(key)} vs {other.get(key)}"
            return
    shapes = reference.get("shapes")
    if not isinstance(shapes, list) or len(shapes) != 2:
        yield f"{name} shapes {shapes} are not a pair"
        return
    row = tolerance(*map(str, shapes))
    for key in sorted(reference):
        if key in _EXACT_FIELDS:
            continue
        attribute = _FIELD_TOLERANCE.get(key)
        if attribute is None:
            if reference[key] != other[key]:
                yield f"{name} {key} differs"
            continue
        allowed = getattr(row, attribute)
        gap = _gap(reference[key], other[key])
        if reference[key] != other[key] and not gap <= allowed:
            yield (
                f"{name} {key}: |Δ| = {gap:.3g} > {allowed:g} "
                f"({'-'.join(shapes)} {attribute} tolerance)"
            )


def _proximity_differences(reference: Any, other: Any) -> list[str]:
    """Query values: one record, or lists of records with the same pairs (see the module doc)."""
    if isinstance(reference, list) and isinstance(other, list):
        pairs = [r.get("pair") if isinstance(r, Mapping) else r for r in reference]
        other_pairs = [o.get("pair") if isinstance(o, Mapping) else o for o in other]
        if pairs != other_pairs:
            return [f"pairs {pairs} vs {other_pairs}"]
        return [d for r, o in zip(reference, other, strict=True) for d in _record_differences(r, o)]
    return list(_record_differences(reference, other))


def _entries(pose: Mapping[str, Any]) -> list[Any]:
    """A pose's 12 numbers: ``xyz``, then the rotation by rows (fewer if malformed)."""
    rows = [pose["xyz"], *pose["rotation"]]
    return [x for row in rows if isinstance(row, Sequence) for x in row]


def _pose_differences(reference: Any, other: Any) -> list[str]:
    """Poses ``{"xyz", "rotation"}``: every entry within ``POSE_TOLERANCE``."""
    if not isinstance(reference, Mapping) or not isinstance(other, Mapping):
        return ["not a pose"]
    if sorted(reference) != sorted(other) or sorted(reference) != ["rotation", "xyz"]:
        return [f"fields {sorted(reference)} vs {sorted(other)}"]
    if reference == other:
        return []
    ours, theirs = _entries(reference), _entries(other)
    if len(ours) != 12 or len(theirs) != 12:
        return ["not a pose of 3 + 3x3 numbers"]
    worst = max(_gap(a, b) for a, b in zip(ours, theirs, strict=True))
    if not worst <= POSE_TOLERANCE:
        return [f"pose entries differ by up to {worst:.3g} > {POSE_TOLERANCE:g}"]
    return []


def _exact_differences(reference: Any, other: Any) -> list[str]:
    return [] if reference == other else ["values differ"]


_COMPARISONS: Mapping[Comparison, Callable[[Any, Any], list[str]]] = {
    Comparison.EXACT: _exact_differences,
    Comparison.PROXIMITY: _proximity_differences,
    Comparison.POSE: _pose_differences,
}


def value_differences(op: str, reference: Any, other: Any) -> list[str]:
    """[] iff two values of ``op`` agree, as its ``CommandSpec.compare`` says (exact for an op
    the grammar lacks); else what differs, one line each."""
    command = GRAMMAR.get(op)
    comparison = Comparison.EXACT if command is None else command.compare
    return _COMPARISONS[comparison](reference, other)


def diff_results(reference: Result, other: Result, *, op: str = "command") -> list[Difference]:
    """[] iff the two Results agree (see the module doc)."""
    if reference.error is None and other.error is None:
        details = value_differences(op, reference.value, other.value)
        if not details:
            return []
        shown = "" if details == ["values differ"] else f" ({'; '.join(details)})"
        return [Difference(f"{op} result{shown}", reference.to_json(), other.to_json())]
    if _errors_agree(reference, other):
        return []
    return [Difference(f"{op} result", reference.to_json(), other.to_json())]


def _errors_agree(a: Result, b: Result) -> bool:
    if a.error is None or b.error is None or a.error.kind != b.error.kind:
        return False
    return a.error.kind is ErrorKind.BINDING or a.error.message == b.error.message


def _observation_differences(reference: Observation, other: Observation) -> Iterator[Difference]:
    for location in sorted(set(reference.locations) | set(other.locations)):
        ra, rb = reference.locations.get(location), other.locations.get(location)
        if ra is None or rb is None:
            yield Difference(f"location {location} exists", ra is not None, rb is not None)
            continue
        if ra.candidates != rb.candidates:
            yield Difference(
                f"candidates at {location} (only in one side)",
                format_pairs(ra.candidates - rb.candidates),
                format_pairs(rb.candidates - ra.candidates),
            )
        if dict(ra.active) != dict(rb.active):
            yield Difference(f"IsActive at {location}", dict(ra.active), dict(rb.active))
        if ra.has_transient_history != rb.has_transient_history:
            yield Difference(
                f"has_transient_history at {location}",
                ra.has_transient_history,
                rb.has_transient_history,
            )


def diff_observations(reference: Observation, other: Observation) -> list[Difference]:
    """[] iff the two Observations agree (see the module doc)."""
    if reference == other:
        return []
    return list(_observation_differences(reference, other))


def diff(
    reference: tuple[Result, Observation],
    other: tuple[Result, Observation],
    *,
    op: str = "command",
) -> list[Difference]:
    """Every difference between two answers to one command: the Result, then the state."""
    return diff_results(reference[0], other[0], op=op) + diff_observations(reference[1], other[1])
