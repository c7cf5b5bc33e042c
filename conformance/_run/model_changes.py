"""What changed in a model file's answers between two columns, by scoped name.

A model file's cases (``corpus.model_files``) leave ``Answers`` per column
(an implementation, or a Drake release): the Result of each step, C after
each, and where the implementation broke, if it did; they round-trip
through JSON (a golden file, ``models --save``). ``changes(case, before,
after)`` names every difference between two columns' answers as a
``Change``:

=====================  ======================================================
``what``               compared
=====================  ======================================================
``add_models``         the parse: the model instances it made, or its error
``finalize``           Finalize's error, if it raised
``models`` ...         each list of ``model_inventory``: ``models``,
``geometries``         ``bodies``, ``frames``, ``joints``, ``geometries``
``groups``             the parser's groups (``group: member`` entries)
``exclusion pairs``    the parser's excluded group pairs (``a, b``)
``candidate pairs``    C after Finalize (``a-b``, by scoped geometry name)
``broke``              one side's implementation broke on the file
=====================  ======================================================

Set-valued answers list what only ``before`` has (``removed``) and what only
``after`` has (``added``), in full; the others give both texts. A file's
changes are the changes of its cases, its filter-group case included.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from conformance._corpus.loader import Case
from conformance._engine import Track
from conformance.compare import format_pairs
from conformance.protocol import MODEL, Observation, Result

__all__ = ["Answers", "Change", "changes", "file_of"]

#: How a case of a file that may declare groups is named (corpus.model_files).
_GROUPS_SUFFIX = " (filter groups)"


def file_of(case_description: str) -> str:
    """The model file a case is of (the filter-group case is of its file too)."""
    return case_description.removesuffix(_GROUPS_SUFFIX)


@dataclass(frozen=True)
class Change:
    """One difference between two columns' answers for a model file."""

    file: str
    what: str
    removed: tuple[str, ...] = ()
    added: tuple[str, ...] = ()
    before: str | None = None
    after: str | None = None

    def lines(self, older: str, newer: str) -> list[str]:
        """How a report shows it: the text pair, or each side's entries in full."""
        if self.before is not None or self.after is not None:
            return [f"{self.what}: {older}: {self.before}", f"{self.what}: {newer}: {self.after}"]
        return [f"{self.what}: only {older}: {entry}" for entry in self.removed] + [
            f"{self.what}: only {newer}: {entry}" for entry in self.added
        ]

    def to_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {"file": self.file, "what": self.what}
        if self.before is not None or self.after is not None:
            data |= {"before": self.before, "after": self.after}
        else:
            data |= {"removed": list(self.removed), "added": list(self.added)}
        return data


@dataclass(frozen=True)
class Answers:
    """A column's answers to one case: a Result per step answered, C after each observed
    step (None after the others), and how the implementation broke, if it did."""

    results: tuple[Result, ...]
    observations: tuple[Observation | None, ...]
    broken: str | None = None

    @classmethod
    def of(cls, trace: Track) -> Answers:
        broken = None if trace.broken is None else str(trace.broken)
        return cls(tuple(trace.results), tuple(trace.observations), broken)

    def covers(self, index: int) -> bool:
        return index < len(self.results)

    def to_json(self) -> dict[str, Any]:
        return {
            "results": [r.to_json() for r in self.results],
            "observations": [None if o is None else o.to_json() for o in self.observations],
            "broken": self.broken,
        }

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> Answers:
        return cls(
            tuple(Result.from_json(r) for r in data["results"]),
            tuple(None if o is None else Observation.from_json(o) for o in data["observations"]),
            data.get("broken"),
        )


def _entries(value: Any) -> list[str]:
    return [str(v) for v in value] if isinstance(value, list) else []


def _set_change(
    file: str, what: str, before: Iterable[str], after: Iterable[str]
) -> Iterator[Change]:
    old, new = set(before), set(after)
    if old != new:
        yield Change(file, what, tuple(sorted(old - new)), tuple(sorted(new - old)))


def _text(result: Result) -> str:
    if result.error is not None:
        return f"error ({result.error.kind.value}): {result.error.message}"
    return "ok" if result.value is None else f"ok: {result.value}"


def _group_entries(report: Mapping[str, Any]) -> tuple[list[str], list[str]]:
    groups = report.get("groups", {}) if isinstance(report, Mapping) else {}
    pairs = report.get("pairs", []) if isinstance(report, Mapping) else []
    members = [f"{name}: {m}" for name, ms in groups.items() for m in ms] + [
        f"{name}: (no members)" for name, ms in groups.items() if not ms
    ]
    return members, [", ".join(pair) for pair in pairs]


def _step_changes(file: str, op: str, before: Result, after: Result) -> Iterator[Change]:
    """The changes of one step's Results (see the module doc's table)."""
    if (before.error is None) != (after.error is None) or (
        before.error is not None and before.error != after.error
    ):
        yield Change(file, op, before=_text(before), after=_text(after))
        return
    if before.error is not None or before.value == after.value:
        return
    if op == "model_inventory":
        keys = sorted(set(before.value or {}) | set(after.value or {}))
        for key in keys:
            yield from _set_change(
                file, key, _entries(before.value.get(key)), _entries(after.value.get(key))
            )
    elif op == "collision_filter_groups":
        (old_groups, old_pairs), (new_groups, new_pairs) = (
            _group_entries(before.value),
            _group_entries(after.value),
        )
        yield from _set_change(file, "groups", old_groups, new_groups)
        yield from _set_change(file, "exclusion pairs", old_pairs, new_pairs)
    elif op == "add_models":
        yield from _set_change(file, op, _entries(before.value), _entries(after.value))
    else:
        yield Change(file, op, before=_text(before), after=_text(after))


def _final_candidates(answers: Answers) -> list[str] | None:
    observed = [o for o in answers.observations if o is not None and MODEL in o.locations]
    return format_pairs(observed[-1].locations[MODEL].candidates) if observed else None


def changes(case: Case, before: Answers, after: Answers) -> list[Change]:
    """Every difference between two columns' answers to a model file's case (module doc)."""
    file = file_of(case.description)
    found: list[Change] = []
    steps: Sequence[Any] = case.steps
    for index, step in enumerate(steps):
        if before.covers(index) and after.covers(index):
            found += _step_changes(file, step.op, before.results[index], after.results[index])
    if any(step.op == "finalize" for step in steps):
        old, new = _final_candidates(before), _final_candidates(after)
        if old is not None and new is not None:
            found += _set_change(file, "candidate pairs", old, new)
    if before.broken != after.broken:
        found.append(
            Change(
                file,
                "broke",
                before=before.broken or "answered every step",
                after=after.broken or "answered every step",
            )
        )
    return found
