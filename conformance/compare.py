"""The one agreement check: do two backends answer a command the same way?

Everything that compares backends (the scenario runner, the lockstep fuzzer,
tests) calls ``diff``. Two answers agree iff ``diff`` is empty:

- **Results** agree iff both returned values that agree, or both raised the
  same ``ErrorKind`` with the same normalised message (where the op's
  ``CommandSpec.error_choice`` names a part of it that is Drake's unspecified
  choice, whatever that part says: ``comparable_message``). Binding errors (no
  overload accepts the arguments) compare by kind alone: their wording is
  pybind11's, and it changes between releases.
- **Values** agree as the op's ``CommandSpec.compare`` says
  (``value_differences``, which the expectations' ``returns`` use too):
  ``EXACT``, equal JSON values; ``PROXIMITY``, query records (one, or a
  sorted list) with equal pairs and shapes in the same order and their
  numbers within the tolerances of the record's shape pair
  (``conformance._tolerances``: the depth or distance; unless the contact is
  a touch, the witness points, and the normal through the separation vector
  ``d·nhat``); ``POSE``, ``xyz`` and rotation entries within
  ``tolerances.POSE_TOLERANCE``.
- **Observations** agree iff they have the same locations and, at each one,
  the same candidate set C, the same IsActive of every declaration label and
  the same ``has_transient_history()``. Two filters are equivalent iff they
  report the same CanCollideWith for every pair (collision_filter.h), so C is
  compared as a set of name pairs. Where both backends report them
  (``LocationState``: None is "not reported"), also the same
  ``CollisionFiltered`` answer for every sampled pair both asked, the same
  inspector count under every key both report, and at the model the same
  collision filter group report.

Differences are ordered (result first, then locations by name) and carry the
*reference*'s value first, so a report can say what the oracle did.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from conformance._grammar import GRAMMAR, Comparison
from conformance._tolerances import POSE_TOLERANCE, tolerance
from conformance.protocol import ErrorKind, LocationState, Observation, Pair, Result

__all__ = [
    "CHOICE",
    "Difference",
    "comparable_message",
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


#: Record fields: the signed number d (depth or distance), the witness points, the normal
#: (of a pair, ``nhat_BA_W``; of a point's distance, the gradient ``grad_W``).
_NUMBER_FIELDS = ("depth", "distance")
_WITNESS_FIELDS = ("p_WCa", "p_WCb", "p_ACa", "p_BCb", "p_GN")
_NORMAL_FIELDS = ("nhat_BA_W", "grad_W")
#: A record field → the Tolerance attribute it is compared within (tests and reports).
_FIELD_TOLERANCE: Mapping[str, str] = {
    **dict.fromkeys(_NUMBER_FIELDS, "distance"),
    **dict.fromkeys(_WITNESS_FIELDS, "witness"),
    **dict.fromkeys(_NORMAL_FIELDS, "normal"),
}
#: Record fields compared exactly: a pair's names and shapes, a point distance's geometry and
#: shape (its row is the shape's against ``point``).
_EXACT_FIELDS = ("pair", "shapes", "geometry", "shape")


def _numbers(value: Any) -> list[float] | None:
    """A number or a vector of numbers as a list of floats (None if malformed)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return [float(value)]
    if isinstance(value, Sequence) and all(
        isinstance(x, (int, float)) and not isinstance(x, bool) for x in value
    ):
        return [float(x) for x in value]
    return None


def _gap(reference: Any, other: Any) -> float:
    """``|a − b|`` of two numbers, ``‖a − b‖`` of two vectors; a NaN entry agrees only with a
    NaN (gap 0), else the gap is infinite; NaN if either is malformed."""
    a, b = _numbers(reference), _numbers(other)
    if a is None or b is None or len(a) != len(b):
        return math.nan
    total = 0.0
    for x, y in zip(a, b, strict=True):
        if math.isnan(x) or math.isnan(y):
            if not (math.isnan(x) and math.isnan(y)):
                return math.inf
            continue
        total += (x - y) ** 2
    return math.sqrt(total)


def _scaled(d: Any, vector: Any) -> Any:
    """``d·vector`` (the separation vector of a record), or ``vector`` if malformed."""
    scale, entries = _numbers(d), _numbers(vector)
    if scale is None or entries is None or len(scale) != 1:
        return vector
    return [scale[0] * x for x in entries]


def _record_differences(reference: Any, other: Any) -> Iterator[str]:
    """How a query record differs beyond its shape pair's tolerances (``tolerances``)."""
    if not isinstance(reference, Mapping) or not isinstance(other, Mapping):
        yield "not a query record"
        return
    name = "-".join(map(str, reference.get("pair", (reference.get("geometry"),))))
    if sorted(reference) != sorted(other):
        yield f"{name} fields {sorted(reference)} vs {sorted(other)}"
        return
    for key in _EXACT_FIELDS:
        if reference.get(key) != other.get(key):
            yield f"{name} {key} {reference.get(key)} vs {other.get(key)}"
            return
    shapes = reference.get("shapes", [reference.get("shape"), "point"])
    number = next((key for key in _NUMBER_FIELDS if key in reference), None)
    if not isinstance(shapes, list) or len(shapes) != 2 or number is None:
        yield f"{name} is not a query record of a shape pair"
        return
    row = tolerance(*map(str, shapes))
    d, d_other = reference[number], other[number]
    magnitude = abs(d) if isinstance(d, (int, float)) else math.inf
    for key in sorted(reference):
        if key in _EXACT_FIELDS or reference[key] == other[key]:
            continue
        if key != number and magnitude < row.touching:
            continue  # a touch: no unique witness points or normal (tolerances' module doc)
        attribute = _FIELD_TOLERANCE.get(key)
        if attribute is None:
            yield f"{name} {key} differs"
            continue
        allowed = getattr(row, attribute)
        if key in _NORMAL_FIELDS:
            gap = _gap(_scaled(d, reference[key]), _scaled(d_other, other[key]))
            what = f"{number}·{key}"
        else:
            gap, what = _gap(reference[key], other[key]), key
        if not gap <= allowed:
            yield (
                f"{name} {what}: |Δ| = {gap:.3g} > {allowed:g} "
                f"({'-'.join(shapes)} {attribute} tolerance)"
            )


def _proximity_differences(reference: Any, other: Any) -> list[str]:
    """Query values: one record, or lists of records with the same pairs (see the module doc)."""
    if isinstance(reference, list) and isinstance(other, list):
        pairs = [
            r.get("pair", r.get("geometry")) if isinstance(r, Mapping) else r for r in reference
        ]
        other_pairs = [
            o.get("pair", o.get("geometry")) if isinstance(o, Mapping) else o for o in other
        ]
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


def _inventory_differences(reference: Any, other: Any) -> list[str]:
    """``{key: [entries]}``: per key, the entries only one side has (a few of each shown)."""
    if reference == other:
        return []
    if not isinstance(reference, Mapping) or not isinstance(other, Mapping):
        return ["values differ"]
    lines = []
    for key in sorted(set(reference) | set(other)):
        ours, theirs = reference.get(key, []), other.get(key, [])
        if ours == theirs:
            continue
        if not isinstance(ours, list) or not isinstance(theirs, list):
            lines.append(f"{key} differ")
            continue
        only_ours = [e for e in ours if e not in theirs]
        only_theirs = [e for e in theirs if e not in ours]
        lines.append(
            f"{key}: only reference {_some(only_ours)}, only other {_some(only_theirs)}"
            if only_ours or only_theirs
            else f"{key}: same entries in another order"
        )
    return lines


def _some(entries: Sequence[Any], shown: int = 3) -> str:
    """``entries`` for a one-line report: the first few and how many more."""
    listed = json.dumps(list(entries[:shown]))
    return listed if len(entries) <= shown else f"{listed} and {len(entries) - shown} more"


_COMPARISONS: Mapping[Comparison, Callable[[Any, Any], list[str]]] = {
    Comparison.EXACT: _exact_differences,
    Comparison.PROXIMITY: _proximity_differences,
    Comparison.POSE: _pose_differences,
    Comparison.INVENTORY: _inventory_differences,
}


def value_differences(op: str, reference: Any, other: Any) -> list[str]:
    """[] iff two values of ``op`` agree, as its ``CommandSpec.compare`` says (exact for an op
    the grammar lacks); else what differs, one line each."""
    command = GRAMMAR.get(op)
    comparison = Comparison.EXACT if command is None else command.compare
    return _COMPARISONS[comparison](reference, other)


#: What ``comparable_message`` puts where an op's ``error_choice`` matched.
CHOICE = "<Drake's choice>"


def comparable_message(op: str, message: str) -> str:
    """``message`` with the part naming Drake's unspecified choice (the op's
    ``CommandSpec.error_choice``) replaced by ``CHOICE``."""
    command = GRAMMAR.get(op)
    if command is None or command.error_choice is None:
        return message
    return re.sub(command.error_choice, CHOICE, message, count=1)


def diff_results(reference: Result, other: Result, *, op: str = "command") -> list[Difference]:
    """[] iff the two Results agree (see the module doc)."""
    if reference.error is None and other.error is None:
        details = value_differences(op, reference.value, other.value)
        if not details:
            return []
        shown = "" if details == ["values differ"] else f" ({'; '.join(details)})"
        return [Difference(f"{op} result{shown}", reference.to_json(), other.to_json())]
    if _errors_agree(op, reference, other):
        return []
    return [Difference(f"{op} result", reference.to_json(), other.to_json())]


def _errors_agree(op: str, a: Result, b: Result) -> bool:
    if a.error is None or b.error is None or a.error.kind != b.error.kind:
        return False
    return a.error.kind is ErrorKind.BINDING or (
        comparable_message(op, a.error.message) == comparable_message(op, b.error.message)
        and a.error.detail == b.error.detail
    )


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
        yield from _reported_differences(location, ra, rb)


def _common(
    reference: Mapping[Any, Any] | None, other: Mapping[Any, Any] | None
) -> tuple[dict[Any, Any], dict[Any, Any]]:
    """The entries of two optional reports under the keys both have ({} if either is None)."""
    if reference is None or other is None:
        return {}, {}
    keys = reference.keys() & other.keys()
    return {k: reference[k] for k in keys}, {k: other[k] for k in keys}


def _reported_differences(
    location: str, ra: LocationState, rb: LocationState
) -> Iterator[Difference]:
    """The optional observables (``LocationState.filtered``, ``counts``, ``filter_groups``)."""
    ours, theirs = _common(ra.filtered, rb.filtered)
    if ours != theirs:
        wrong = sorted(pair for pair in ours if ours[pair] != theirs[pair])
        yield Difference(
            f"CollisionFiltered at {location}",
            {f"{a}-{b}": ours[(a, b)] for a, b in wrong},
            {f"{a}-{b}": theirs[(a, b)] for a, b in wrong},
        )
    ours, theirs = _common(ra.counts, rb.counts)
    if ours != theirs:
        wrong = sorted(key for key in ours if ours[key] != theirs[key])
        yield Difference(
            f"inspector counts at {location}",
            {key: ours[key] for key in wrong},
            {key: theirs[key] for key in wrong},
        )
    if (
        ra.filter_groups is not None
        and rb.filter_groups is not None
        and ra.filter_groups != rb.filter_groups
    ):
        yield Difference(
            f"collision filter groups at {location}",
            dict(ra.filter_groups),
            dict(rb.filter_groups),
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
