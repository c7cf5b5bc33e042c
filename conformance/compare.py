"""The one agreement check: do two backends answer a command the same way?

Everything that compares backends (the scenario runner, the lockstep fuzzer,
tests) calls ``diff``. Two answers agree iff ``diff`` is empty:

- **Results** agree iff both returned the same value, or both raised the same
  ``ErrorKind`` with the same normalised message. Binding errors (no overload
  accepts the arguments) compare by kind alone: their wording is pybind11's,
  and it changes between releases.
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
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import Any

from conformance.protocol import ErrorKind, Observation, Pair, Result

__all__ = ["Difference", "diff", "diff_observations", "diff_results", "format_pairs"]


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


def diff_results(reference: Result, other: Result, *, op: str = "command") -> list[Difference]:
    """[] iff the two Results agree (see the module doc)."""
    if _results_agree(reference, other):
        return []
    return [Difference(f"{op} result", reference.to_json(), other.to_json())]


def _results_agree(a: Result, b: Result) -> bool:
    if a.error is None and b.error is None:
        return bool(a.value == b.value)
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
