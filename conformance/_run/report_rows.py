"""The rows a person reads first: cases whose outcome or answers change across columns.

A report's table is a ``Matrix`` (``run.matrix``): a column per Drake release
or per implementation, a cell per case. Each column is compared with one
other column, its *baseline* (``against``):

- a release matrix (``release_baselines``): each release with the release
  before it; an implementation's column (``reimpl==1.58.0``) with Drake's
  column of the same release if there is one, else with the first column;
- implementations (``run``, ``models --backend``; ``reference_baselines``):
  each with the reference.

A row *changes* when its cells' outcomes are not all alike, or when a cell's
answers differ, step by step, from its baseline's (``Matrix.behaviour_change``,
the one comparison, whose first difference the cell keeps as its ``Step``).
``sections`` splits the rows into those that change (a failing cell first,
then a break, then answers that differ, then outcomes alone, e.g. a feature a
release lacks; each in corpus order), those alike everywhere but failing, and
those alike everywhere (which a report folds into one count).

``bands`` folds the changing rows for a picture: rows whose cells look alike
column by column (the same kinds, answers differing in the same columns) are
one band, labelled by what they share (``unsupported 1.12.0–1.30.0 · pass
1.31.0–1.58.0``); a failing row is always a band of its own, named by its case.

A cell's ``kind`` names how it looks: its outcome's label, except that a
crash, timeout or error that a crash row or a known divergence expects is
``expected-crash`` (``expected-timeout``, ``expected-error``): the report
draws expected and unexpected breaks differently.

``matrix_of_run`` turns a ``run``'s report into such a matrix, a column per
backend, so that ``run`` writes the same page.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from conformance._run.case_report import CaseReport
from conformance._run.matrix import Cell, Matrix, Outcome, ReleaseRun, label, outcome_of
from conformance._run.report import RunReport

__all__ = [
    "BROKEN_KINDS",
    "Band",
    "Row",
    "RowCell",
    "Sections",
    "Step",
    "bands",
    "kind",
    "matrix_of_run",
    "reference_baselines",
    "release_baselines",
    "rows",
    "sections",
]

#: The outcomes a break (not an answer) gives.
_BREAKS = frozenset({Outcome.CRASH, Outcome.TIMEOUT, Outcome.ERROR})
#: Every break kind, expected or not.
BROKEN_KINDS = tuple(
    f"{prefix}{o.value}"
    for o in (Outcome.CRASH, Outcome.TIMEOUT, Outcome.ERROR)
    for prefix in ("expected-", "")
)


def kind(cell: Cell | None) -> str:
    """How a cell looks: ``missing`` (no cell), ``expected-crash`` (a break that a crash
    row or a known divergence expects; also ``-timeout``, ``-error``), else its label."""
    if cell is None:
        return "missing"
    if cell.outcome in _BREAKS and cell.expected_by is not None:
        return f"expected-{cell.outcome.value}"
    return label(cell.outcome)


@dataclass(frozen=True)
class Step:
    """The first step where a column's answers differ from its baseline's, both answers."""

    step: str
    what: str
    #: The step's operation (``""`` for the end of a case, where one side broke).
    op: str
    baseline: str
    before: Any
    after: Any
    #: How many differences the comparison found in all (this is the first).
    differences: int


@dataclass(frozen=True)
class RowCell:
    column: str
    cell: Cell | None
    #: How it differs from its baseline column's answers (None: alike, or not compared).
    step: Step | None = None

    @property
    def kind(self) -> str:
        return kind(self.cell)

    @property
    def outcome(self) -> str:
        return "—" if self.cell is None else label(self.cell.outcome)


@dataclass(frozen=True)
class Row:
    case: str
    cells: tuple[RowCell, ...]

    @property
    def outcome_changes(self) -> bool:
        """The cells' kinds are not all alike (an expected crash is not an unexpected one)."""
        return len({c.kind for c in self.cells}) > 1

    @property
    def answers_change(self) -> bool:
        return any(c.step is not None for c in self.cells)

    @property
    def changes(self) -> bool:
        return self.outcome_changes or self.answers_change

    @property
    def failing(self) -> bool:
        return any(c.cell is not None and c.cell.failing for c in self.cells)


def release_baselines(matrix: Matrix) -> dict[str, str]:
    """Each column's baseline in a release matrix (see the module doc); the first release
    has none."""
    ran = [v for v in matrix.versions if matrix.runs[v].error is None]
    releases = [v for v in matrix.release_columns if v in ran]
    against = {newer: older for older, newer in itertools.pairwise(releases)}
    for column in ran:
        if column in releases:
            continue
        same = column.partition("==")[2]
        if same in releases:
            against[column] = same
        elif ran and ran[0] != column:
            against[column] = ran[0]
    return against


def reference_baselines(matrix: Matrix, reference: str) -> dict[str, str]:
    """Each column but the reference compared with the reference."""
    return {
        v: reference
        for v in matrix.versions
        if v != reference and matrix.runs[v].error is None and reference in matrix.runs
    }


def _step(matrix: Matrix, case: str, baseline: str, column: str) -> Step | None:
    found = matrix.behaviour_change(case, baseline, column)
    if not found:
        return None
    first = found[0]
    source = matrix.sources.get(case)
    op = ""
    if source is not None and first.index < len(source.steps):
        op = source.steps[first.index].op
    return Step(first.step, first.what, op, baseline, first.expected, first.actual, len(found))


def rows(matrix: Matrix, against: Mapping[str, str]) -> list[Row]:
    """A row per case of ``matrix``, in corpus order, a cell per column that ran (a column
    that could not run has none), each with its first difference from its baseline column
    (``against``) if it has one."""
    columns = [v for v in matrix.versions if matrix.runs[v].error is None]
    found = []
    for case in matrix.cases:
        cells = []
        for column in columns:
            baseline = against.get(column)
            step = None if baseline is None else _step(matrix, case, baseline, column)
            cells.append(RowCell(column, matrix.cell(case, column), step))
        found.append(Row(case, tuple(cells)))
    return found


@dataclass(frozen=True)
class Sections:
    """The rows as a report shows them (see the module doc)."""

    changed: tuple[Row, ...]
    failing_alike: tuple[Row, ...]
    alike: tuple[Row, ...]


def _rank(row: Row) -> int:
    """Where a changing row goes: 0 a cell fails (nothing expects it), 1 a cell broke (as
    expected), 2 the answers differ, 3 only the outcomes differ (e.g. a release lacks a
    feature the case needs)."""
    if row.failing:
        return 0
    if any(c.kind in BROKEN_KINDS for c in row.cells):
        return 1
    return 2 if row.answers_change else 3


def sections(all_rows: Sequence[Row]) -> Sections:
    """The changing rows first, most telling first (``_rank``, then corpus order), then the
    rows alike everywhere, split into the failing ones and the others."""
    changed = sorted((r for r in all_rows if r.changes), key=_rank)
    same = [r for r in all_rows if not r.changes]
    return Sections(
        tuple(changed),
        tuple(r for r in same if r.failing),
        tuple(r for r in same if not r.failing),
    )


@dataclass(frozen=True)
class Band:
    """One drawn row of a picture: one case, or several whose cells look alike."""

    rows: tuple[Row, ...]

    @property
    def cells(self) -> tuple[RowCell, ...]:
        return self.rows[0].cells

    @property
    def label(self) -> str:
        """The case's name, or for several cases how their cells run across the columns:
        ``43 cases: unsupported 1.12.0–1.30.0 · pass 1.31.0–1.58.0`` (then ``· answers
        change at …`` where they differ from the baseline column)."""
        if len(self.rows) == 1:
            return self.rows[0].case
        spans = []
        for kind_, group in itertools.groupby(self.cells, key=lambda c: c.kind):
            columns = [c.column for c in group]
            span = columns[0] if len(columns) == 1 else f"{columns[0]}–{columns[-1]}"
            spans.append(f"{kind_.replace('-', ' ')} {span}")
        changed = [c.column for c in self.cells if c.step is not None]
        if changed:
            spans.append(f"answers change at {', '.join(changed)}")
        return f"{len(self.rows)} cases: {' · '.join(spans)}"


def _look(row: Row) -> tuple[tuple[str, bool], ...]:
    """What a row looks like in a picture: each cell's kind and whether it carries a
    difference from its baseline column."""
    return tuple((c.kind, c.step is not None) for c in row.cells)


def bands(shown: Sequence[Row]) -> list[Band]:
    """``shown`` folded for a picture, in its order (a band where its first row was): rows
    that look alike (``_look``) are one band; a failing row is always its own."""
    folded: dict[object, list[Row]] = {}
    for index, row in enumerate(shown):
        key: object = ("failing", index) if row.failing else _look(row)
        folded.setdefault(key, []).append(row)
    return [Band(tuple(group)) for group in folded.values()]


def _run_cell(case: CaseReport, backend: str) -> Cell:
    """As ``outcome_of``, except that a failure is a failure (``run`` judges an
    implementation's missing binding a failure; only a release's is unsupported)."""
    if case.status.get(backend) is Outcome.FAIL and backend not in case.broken:
        first = case.failures_of(backend)[0]
        return Cell(Outcome.FAIL, f"{first.step}: {first.what}")
    return outcome_of(case, backend)


def matrix_of_run(report: RunReport) -> Matrix:
    """A ``run``'s report as a matrix: a column per backend (the reference first), its cell
    of each case as the release matrix would give it (``outcome_of``), and its answers."""
    names = [b.name for b in report.backends]
    names.sort(key=lambda name: name != report.reference)  # the reference first
    matrix = Matrix(
        names,
        [c.case.qualified_name for c in report.cases],
        sources={c.case.qualified_name: c.case for c in report.cases},
    )
    for name in names:
        run = ReleaseRun(name)
        for case in report.cases:
            if name in case.status or name in case.broken:
                run.cells[case.case.qualified_name] = _run_cell(case, name)
            if (track := case.traces.get(name)) is not None:
                run.traces[case.case.qualified_name] = track
        matrix.runs[name] = run
    return matrix
