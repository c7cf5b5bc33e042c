"""Bisecting a case between two Drake releases: the first release whose answer changed.

The releases ``good``..``bad`` are those on the index (``backends.releases``).
Each probe runs the case alone on one release, in a worker. Two releases
*agree* on the case:

- ``by="outcome"``: iff their matrix cells have the same outcome
  (``run.matrix.outcome_of``: pass, fail, xfail, unsupported, crash ...);
- ``by="behaviour"``: iff their traces agree step by step under the one
  comparison (``conformance.compare`` through ``runner.trace_disagreements``):
  the same Results, the same states, the same length. This finds a change that
  the case's since/until expectations already allow for.

Assuming one change in the range (a behaviour changes once and stays), the
first release that disagrees with ``good`` is found by halving: about
log₂(n) probes for n releases, besides ``good`` and ``bad`` themselves.
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from conformance._backends.subprocess_backend import WorkerBackend
from conformance._corpus.loader import Case
from conformance._engine import Track
from conformance._run.case_report import Failure
from conformance._run.matrix import Cell, label, outcome_of
from conformance._run.runner import run_case, trace_disagreements

__all__ = ["Bisection", "By", "Probe", "bisect_case"]


class By(enum.Enum):
    OUTCOME = "outcome"
    BEHAVIOUR = "behaviour"


@dataclass(frozen=True)
class Probe:
    """One release's answer to the case: its matrix cell and its trace."""

    version: str
    cell: Cell
    trace: Track | None


@dataclass
class Bisection:
    """Where the case changed: ``last_good`` is the last release that agrees with ``good``,
    ``first_bad`` the next one; ``None`` if ``good`` and ``bad`` agree."""

    case: str
    by: By
    releases: list[str]
    probes: list[Probe] = field(default_factory=list)
    last_good: str | None = None
    first_bad: str | None = None
    #: How ``first_bad`` differs from ``last_good`` (behaviour: the differences).
    differences: list[Failure] = field(default_factory=list)

    def probe(self, version: str) -> Probe:
        return next(p for p in self.probes if p.version == version)


def run_probe(
    case: Case,
    version: str,
    *,
    python: Sequence[str] | None = None,
    step_timeout: float | None = None,
    log: Callable[[str], None] = lambda line: None,
) -> Probe:
    """Runs ``case`` on Drake ``version`` alone, in a new worker."""
    worker = WorkerBackend(version, python=python, step_timeout=step_timeout, log=log)
    try:
        report = run_case(case, [worker], step_timeout=step_timeout)
    finally:
        worker.close()
    return Probe(version, outcome_of(report, worker.name), report.traces.get(worker.name))


def _differences(case: Case, by: By, good: Probe, other: Probe) -> list[Failure]:
    """[] iff ``other`` agrees with ``good`` (see the module doc)."""
    if by is By.OUTCOME or good.trace is None or other.trace is None:
        if good.cell.outcome is other.cell.outcome:
            return []
        return [
            Failure(
                "case",
                "outcome",
                label(good.cell.outcome),
                label(other.cell.outcome),
                other.version,
                good.version,
            )
        ]
    return trace_disagreements(case, good.trace, other.trace, ends=True)


def bisect_case(
    case: Case,
    releases: Sequence[str],
    *,
    by: By = By.OUTCOME,
    probe: Callable[[str], Probe] | None = None,
    on_probe: Callable[[Probe, bool], None] = lambda probe, agrees: None,
) -> Bisection:
    """Finds the first of ``releases`` (oldest first; the first is good, the last bad) that
    disagrees with the first. ``probe`` runs the case on a release (default: ``run_probe``);
    ``on_probe(probe, agrees_with_good)`` reports each probe."""
    run = probe or (lambda version: run_probe(case, version))
    result = Bisection(case.qualified_name, by, list(releases))

    def agrees(version: str) -> bool:
        answer = run(version)
        result.probes.append(answer)
        same = len(result.probes) == 1 or not _differences(case, by, result.probes[0], answer)
        on_probe(answer, same)
        return same

    agrees(releases[0])
    if agrees(releases[-1]):
        return result
    low, high = 0, len(releases) - 1
    while high - low > 1:
        middle = (low + high) // 2
        low, high = (middle, high) if agrees(releases[middle]) else (low, middle)
    result.last_good, result.first_bad = releases[low], releases[high]
    result.differences = _differences(
        case, by, result.probe(result.last_good), result.probe(result.first_bad)
    )
    return result
