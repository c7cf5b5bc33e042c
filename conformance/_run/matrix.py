"""The release matrix: every case on every chosen Drake release, one outcome per cell.

Each release runs alone, in a worker (``drake==X``), and is held to the
cases' own expectations (those whose since/until range holds it). A cell is
one ``Outcome``, derived from the case's report by one table
(``outcome_of``):

==================  ===========================================================
outcome             when
==================  ===========================================================
``pass``            every expectation held
``fail``            an expectation failed, and no known divergence says so
``xfail``           it failed as a known divergence in range says it does
``unsupported``     the release lacks a feature tag of the case (``activation``
                    before 1.55, ``scope`` before 1.42), or lacks the Python
                    binding a step calls (error kind ``binding``)
``crash``           the worker died (a signal or an exit), expected or not
``timeout``         a step took longer than the step timeout
``error``           the backend broke otherwise
==================  ===========================================================

A column may also be an implementation named by a backend spec, run alone
on each case like a release, beside Drake's columns: ``reimpl==1.58.0``
(reimpl following a release, in its worker), or any ``--backend`` spec
(``extra`` of ``run_matrix``). Its column is named by the spec, and the
changes between consecutive releases skip it (``release_columns``).

Releases run in parallel (``jobs`` threads, each driving its own worker
processes); ``on_case`` reports progress as cases finish. A release whose
environment cannot be built or whose worker cannot start gets no cells and
an ``error`` in its ``ReleaseRun``; the other releases still run.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from conformance._backends.calls import BackendError
from conformance._backends.environments import DrakeEnvironmentError
from conformance._backends.loader import BackendLoadError, load_backend
from conformance._backends.subprocess_backend import WorkerBackend
from conformance._corpus.loader import Case
from conformance._engine import Outcome, Track
from conformance._run.case_report import CaseReport, Failure
from conformance._run.runner import run_case, trace_disagreements
from conformance._run.verdict import binding_gap
from conformance.protocol import Backend

__all__ = [
    "MATRIX_ORDER",
    "Cell",
    "Matrix",
    "Outcome",
    "ReleaseRun",
    "label",
    "outcome_of",
    "run_backends",
    "run_column",
    "run_matrix",
    "run_release",
    "run_spec",
]


#: The outcomes in the order a matrix shows them.
MATRIX_ORDER = (
    Outcome.PASS,
    Outcome.FAIL,
    Outcome.XFAIL,
    Outcome.SKIP,
    Outcome.CRASH,
    Outcome.TIMEOUT,
    Outcome.ERROR,
)


def label(outcome: Outcome) -> str:
    """How a matrix names an outcome: a skipped case is ``unsupported`` there (the release
    lacks a feature or a binding the case needs); the others by their value."""
    return "unsupported" if outcome is Outcome.SKIP else outcome.value


#: Outcomes that make ``matrix`` exit 1 (a crash or timeout that a known
#: divergence expects does not).
FAILING = frozenset({Outcome.FAIL, Outcome.CRASH, Outcome.TIMEOUT, Outcome.ERROR})


@dataclass(frozen=True)
class Cell:
    """One case on one release: its outcome, and why (a reason, a divergence id, an error)."""

    outcome: Outcome
    detail: str = ""
    #: The id of the known divergence that expects it, if one does.
    expected_by: str | None = None

    @property
    def failing(self) -> bool:
        return self.outcome in FAILING and self.expected_by is None

    def to_json(self) -> dict[str, Any]:
        return {
            "outcome": label(self.outcome),
            "detail": self.detail,
            **({"expected_by": self.expected_by} if self.expected_by else {}),
        }


def _broke(report: CaseReport, backend: str) -> str:
    """Where the backend broke, and the last line of what it said (a worker's stderr)."""
    trace = report.traces.get(backend)
    if trace is None or trace.broken is None:
        return report.aborted or ""
    lines = trace.broken.message.strip().splitlines()
    last = f" … {lines[-1].strip()}" if len(lines) > 1 else ""
    return f"{trace.broken.where}: {lines[0] if lines else ''}{last}"


def _failed(report: CaseReport, backend: str) -> Cell:
    gap = binding_gap(report, backend)
    if gap is not None:  # a backend not named like a Drake release (run's SKIP covers those)
        return Cell(Outcome.SKIP, f"no binding: {gap}")
    first = report.failures_of(backend)[0]
    return Cell(Outcome.FAIL, f"{first.step}: {first.what}")


def _passed(report: CaseReport, backend: str) -> Cell:
    if report.aborted is not None and not report.recoverable:  # e.g. an unknown name
        return Cell(Outcome.ERROR, report.aborted)
    return Cell(Outcome.PASS)


#: The cell of a backend that finished the case, by its outcome.
_BY_OUTCOME: dict[Outcome, Callable[[CaseReport, str], Cell]] = {
    Outcome.PASS: _passed,
    Outcome.FAIL: _failed,
    Outcome.XFAIL: lambda r, b: Cell(Outcome.XFAIL, r.xfails[b], r.xfails[b]),
    Outcome.SKIP: lambda r, b: Cell(Outcome.SKIP, r.skip_reasons.get(b, "")),
}


def outcome_of(report: CaseReport, backend: str) -> Cell:
    """The cell of ``backend`` in ``report`` (the module doc's table)."""
    if backend in report.broken:
        outcome = report.broken[backend]
        expected = report.xfails.get(backend) or report.recorded.get(backend)
        return Cell(outcome, _broke(report, backend), expected)
    return _BY_OUTCOME[report.status.get(backend, Outcome.PASS)](report, backend)


@dataclass
class ReleaseRun:
    """One release's column: a cell per case, or the error that kept it from running."""

    version: str
    python: str = ""
    cells: dict[str, Cell] = field(default_factory=dict)
    error: str | None = None
    seconds: float = 0.0
    #: What the release answered, per case (for behaviour changes; not written out).
    traces: dict[str, Track] = field(default_factory=dict, repr=False)

    def count(self, outcome: Outcome) -> int:
        return sum(1 for c in self.cells.values() if c.outcome is outcome)


@dataclass
class Matrix:
    """Every release's column, in the order the releases were given."""

    versions: list[str]
    cases: list[str]
    runs: dict[str, ReleaseRun] = field(default_factory=dict)
    #: The cases themselves, by qualified name (to compare traces step by step).
    sources: dict[str, Case] = field(default_factory=dict, repr=False)
    _changes: dict[tuple[str, str, str], list[Failure]] = field(
        default_factory=dict, repr=False, compare=False
    )

    def behaviour_change(self, case: str, older: str, newer: str) -> list[Failure]:
        """How ``newer`` answered ``case`` differently from ``older`` (the one comparison,
        step by step); [] if alike or if either did not run it."""
        key = (case, older, newer)
        if key not in self._changes:  # the report's three files all ask
            before = self.runs[older].traces.get(case)
            after = self.runs[newer].traces.get(case)
            found = []
            if before is not None and after is not None and case in self.sources:
                found = trace_disagreements(self.sources[case], before, after, ends=True)
            self._changes[key] = found
        return self._changes[key]

    def cell(self, case: str, version: str) -> Cell | None:
        run = self.runs.get(version)
        return None if run is None else run.cells.get(case)

    @property
    def failing(self) -> list[tuple[str, str]]:
        """(case, version) of every failing cell."""
        return [
            (case, v)
            for v in self.versions
            for case in self.cases
            if (cell := self.cell(case, v)) is not None and cell.failing
        ]

    @property
    def release_columns(self) -> list[str]:
        """The columns that are Drake releases (not an implementation's ``spec``)."""
        return [v for v in self.versions if "==" not in v and ":" not in v]

    @property
    def broken_releases(self) -> list[str]:
        return [v for v in self.versions if self.runs[v].error is not None]


def run_release(
    version: str,
    cases: Sequence[Case],
    *,
    python: Sequence[str] | None = None,
    step_timeout: float | None = None,
    strict_divergences: bool = False,
    on_case: Callable[[str, int, int], None] = lambda version, done, total: None,
    log: Callable[[str], None] = lambda line: None,
) -> ReleaseRun:
    """Runs ``cases`` on Drake ``version`` alone, in a worker (see the module doc)."""
    run = ReleaseRun(version)
    start = time.perf_counter()
    try:
        worker = WorkerBackend(version, python=python, step_timeout=step_timeout, log=log)
    except (DrakeEnvironmentError, BackendError, OSError) as exc:
        run.error = f"drake=={version}: {exc}"
        return run
    run.python = worker.environment.python
    try:
        run_column(
            run,
            worker,
            cases,
            strict_divergences=strict_divergences,
            step_timeout=step_timeout,
            on_case=on_case,
        )
    finally:
        worker.close()
        run.seconds = time.perf_counter() - start
    return run


def run_column(
    run: ReleaseRun,
    backend: Backend,
    cases: Sequence[Case],
    *,
    strict_divergences: bool = False,
    step_timeout: float | None = None,
    on_case: Callable[[str, int, int], None] = lambda name, done, total: None,
) -> None:
    """Fills ``run`` (a column) with ``backend``'s cell and trace of each case, run alone."""
    for done, case in enumerate(cases, 1):
        report = run_case(
            case, [backend], strict_divergences=strict_divergences, step_timeout=step_timeout
        )
        run.cells[case.qualified_name] = outcome_of(report, backend.name)
        if (trace := report.traces.get(backend.name)) is not None:
            run.traces[case.qualified_name] = trace
        on_case(run.version, done, len(cases))


def run_backends(
    backends: Sequence[Backend],
    cases: Sequence[Case],
    *,
    step_timeout: float | None = None,
    on_case: Callable[[str, int, int], None] = lambda name, done, total: None,
) -> Matrix:
    """Every case on every backend (in this process, one after another), a column each,
    named after the backend: the matrix of implementations rather than releases."""
    matrix = Matrix(
        [b.name for b in backends],
        [c.qualified_name for c in cases],
        sources={c.qualified_name: c for c in cases},
    )
    for backend in backends:
        run = ReleaseRun(backend.name)
        start = time.perf_counter()
        run_column(run, backend, cases, step_timeout=step_timeout, on_case=on_case)
        run.seconds = time.perf_counter() - start
        matrix.runs[backend.name] = run
    return matrix


def run_spec(
    spec: str,
    cases: Sequence[Case],
    *,
    python: Sequence[str] | None = None,
    step_timeout: float | None = None,
    strict_divergences: bool = False,
    on_case: Callable[[str, int, int], None] = lambda version, done, total: None,
) -> ReleaseRun:
    """Runs ``cases`` on the backend ``spec`` alone (a column named by the spec)."""
    run = ReleaseRun(spec)
    start = time.perf_counter()
    try:
        backend = load_backend(spec, python=python, step_timeout=step_timeout)
    except BackendLoadError as exc:
        run.error = str(exc)
        return run
    run.python = sys.version.split()[0]
    try:
        run_column(
            run,
            backend,
            cases,
            strict_divergences=strict_divergences,
            step_timeout=step_timeout,
            on_case=on_case,
        )
    finally:
        close = getattr(backend, "close", None)  # N.B. a worker's; in-process ones have none
        if callable(close):
            close()
        run.seconds = time.perf_counter() - start
    return run


def run_matrix(
    versions: Sequence[str],
    cases: Sequence[Case],
    *,
    extra: Sequence[str] = (),
    jobs: int = 1,
    python: Sequence[str] | None = None,
    step_timeout: float | None = None,
    strict_divergences: bool = False,
    on_case: Callable[[str, int, int], None] = lambda version, done, total: None,
    on_release: Callable[[ReleaseRun], None] = lambda run: None,
    log: Callable[[str], None] = lambda line: None,
) -> Matrix:
    """Every case on every release, then on every ``extra`` backend spec (a column each,
    beside the releases), ``jobs`` columns at a time."""
    matrix = Matrix(
        [*versions, *extra],
        [c.qualified_name for c in cases],
        sources={c.qualified_name: c for c in cases},
    )
    lock = threading.Lock()

    def one(version: str) -> ReleaseRun:
        if version in extra:
            run = run_spec(
                version,
                cases,
                python=python,
                step_timeout=step_timeout,
                strict_divergences=strict_divergences,
                on_case=on_case,
            )
        else:
            run = run_release(
                version,
                cases,
                python=python,
                step_timeout=step_timeout,
                strict_divergences=strict_divergences,
                on_case=on_case,
                log=log,
            )
        with lock:
            matrix.runs[version] = run
            on_release(run)
        return run

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        list(pool.map(one, matrix.versions))
    return matrix
