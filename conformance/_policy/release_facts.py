"""The release table: every fact about Drake releases, one row each (``release_facts.json``).

A row says what changes between Drake releases and where that is shown:

- ``id``: its name, cited by everything that depends on it;
- ``releases``: the releases it holds for (``VersionRange``: since ≤ release
  ≤ until, inclusive; ``until`` "1.51" covers 1.51.x);
- ``kind`` (``FactKind``):

  ============  ==============================================================
  ``binding``   a Python binding (class, method, overload, keyword) arrives at
                ``since`` or leaves after ``until``; ``bindings`` names it. A
                backend offers a command, and reimpl defines the binding, only
                on the releases the row holds for.
  ``behaviour`` what a call does changes: its result, the state it leaves, or
                whether it raises.
  ``crash``     the call ends the process on these releases; ``answer`` says
                how (the error pydrake raises for it, or ``abort``). A release
                guard (``policy.guards``) refuses it where it would end a run.
  ``wording``   only the text of an error message changes.
  ============  ==============================================================

- ``summary``: one line; ``evidence``: scenario cases (qualified names) and
  tests (paths or node ids) that show it on real pydrake.

Every home of a release fact reads this table: the grammar's commands and
feature tags (``CommandSpec.binding``, ``grammar.FEATURE_BINDINGS``), the
backends' capabilities (``fact_holds(id, backend.version())``), the release
guards, the known divergences (``release_fact``), scenario expectations
(``"release_fact": "<id>"``, ``"before <id>"``, ``"after <id>"``), the
``release_fact`` test marker, and reimpl's own release switches
(``reimpl/_release.py``, which reads the same file).
"""

from __future__ import annotations

import enum
import json
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

from conformance._policy.versions import VersionRange

__all__ = [
    "FactKind",
    "ReleaseFact",
    "Side",
    "crash_answer",
    "fact_holds",
    "fact_side",
    "recorded_crash",
    "release_fact",
    "release_facts",
    "table_releases",
]


class FactKind(enum.Enum):
    """What a release fact is about (see the module doc's table)."""

    BINDING = "binding"
    BEHAVIOUR = "behaviour"
    CRASH = "crash"
    WORDING = "wording"


class Side(enum.Enum):
    """Where a release lies against a fact's range: before ``since``, in it, after ``until``."""

    BEFORE = "before"
    HOLDS = "holds"
    AFTER = "after"


@dataclass(frozen=True)
class ReleaseFact:
    """One row of the release table."""

    id: str
    kind: FactKind
    releases: VersionRange
    summary: str
    scenarios: tuple[str, ...] = ()
    tests: tuple[str, ...] = ()
    #: A binding row's bindings (``module.Class.member``).
    bindings: tuple[str, ...] = ()
    #: A crash row's answer: ``{"error": {"kind", "message"}}`` or ``{"abort": text}``.
    answer: Mapping[str, Any] | None = None

    def holds(self, version: str) -> bool:
        """Whether the fact holds for Drake ``version``."""
        return version in self.releases

    def side(self, version: str) -> Side | None:
        """Where ``version`` lies (None for a version that names no release)."""
        if self.holds(version):
            return Side.HOLDS
        if self.releases.before(version):
            return Side.BEFORE
        return Side.AFTER if self.releases.after(version) else None

    def on_side(self, version: str, side: Side) -> bool:
        return self.side(version) is side


def _fact(data: Mapping[str, Any]) -> ReleaseFact:
    releases = data["releases"]
    evidence = data["evidence"]
    return ReleaseFact(
        id=data["id"],
        kind=FactKind(data["kind"]),
        releases=VersionRange(releases.get("since"), releases.get("until")),
        summary=data["summary"],
        scenarios=tuple(evidence.get("scenarios", ())),
        tests=tuple(evidence.get("tests", ())),
        bindings=tuple(data.get("bindings", ())),
        answer=data.get("answer"),
    )


@cache
def _table() -> dict[str, Any]:
    text = resources.files("conformance._policy").joinpath("release_facts.json").read_text("utf-8")
    data: dict[str, Any] = json.loads(text)
    return data


@cache
def release_facts() -> Mapping[str, ReleaseFact]:
    """Every row, by id, in the table's order."""
    return {row["id"]: _fact(row) for row in _table()["facts"]}


def release_fact(fact_id: str) -> ReleaseFact:
    """The row ``fact_id`` (KeyError naming it if the table has none)."""
    try:
        return release_facts()[fact_id]
    except KeyError:
        raise KeyError(f"no release fact {fact_id!r} in release_facts.json") from None


def fact_holds(fact_id: str, version: str) -> bool:
    """Whether the row ``fact_id`` holds for Drake ``version``."""
    return release_fact(fact_id).holds(version)


def table_releases() -> VersionRange:
    """The releases the table describes, oldest to newest (``first_release``..``last_release``)."""
    return VersionRange(_table()["first_release"], _table()["last_release"])


def recorded_crash(case: str, version: str) -> str | None:
    """The crash row that records a crash of Drake ``version`` in ``case`` (a qualified name
    among the row's evidence), if one does: there, ending the process is the release's answer."""
    for fact in release_facts().values():
        if fact.kind is FactKind.CRASH and case in fact.scenarios and fact.holds(version):
            return fact.id
    return None


def crash_answer(fact_id: str) -> Mapping[str, str] | None:
    """The error a crash row's call raises where it is not refused (``answer.error``), if the
    release answers at all (None: the process ends)."""
    answer = release_fact(fact_id).answer
    error: Mapping[str, str] | None = None if answer is None else answer.get("error")
    return error


def fact_side(reference: str) -> tuple[ReleaseFact, Side]:
    """A scenario's ``release_fact`` reference: ``"<id>"`` (where the row holds),
    ``"before <id>"`` (releases before its ``since``) or ``"after <id>"`` (after its
    ``until``). KeyError for an unknown id; ValueError for a side the row has no bound for."""
    side_text, _, fact_id = reference.rpartition(" ")
    side = Side(side_text) if side_text else Side.HOLDS
    fact = release_fact(fact_id)
    bound = {Side.BEFORE: fact.releases.since, Side.AFTER: fact.releases.until}
    if side in bound and bound[side] is None:
        raise ValueError(f"{reference!r}: release fact {fact_id} has no {side.value} side")
    return fact, side
