"""A run of model files on several columns (implementations or releases), for people and CI.

The run is a ``Matrix`` (``run.matrix``): a column per implementation
(``--backend``) or per Drake release (``--drake``), a cell per case. Which
columns are compared, ``comparisons``:

- releases: each with the one before (oldest first), so the report reads as
  what changed from release to release;
- implementations: each with the reference (pydrake if present, else the
  first), so the report reads as what each implementation does otherwise.

Per compared pair, every difference of every file, by scoped name
(``run.model_changes``). ``write_models_report`` writes ``report.json`` (the
columns, each file's outcome per column, and the changes), ``report.md``,
``report.html`` (``run.html_report``: the cases that change first, each
changed cell opening the first step that differs) and ``heatmap.png`` (the
changing cases × columns, the matrix's picture).

A golden file (``save_golden``/``load_golden``) holds one column's answers
per case, keyed by the case's description (the file's path below the folder
given), so a later run on another release, or on edited models, is checked
against it (``golden_changes``).
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from conformance._corpus.loader import Case
from conformance._run.html_report import write_html
from conformance._run.matrix import Matrix, label
from conformance._run.matrix_report import write_heatmap
from conformance._run.model_changes import Answers, Change, changes, file_of

__all__ = [
    "GOLDEN_FORMAT",
    "Comparison",
    "GoldenError",
    "comparisons",
    "golden_changes",
    "load_golden",
    "models_json",
    "models_markdown",
    "save_golden",
    "write_models_report",
]

#: The version of the golden file's layout.
GOLDEN_FORMAT = 1


@dataclass(frozen=True)
class Comparison:
    """Two columns compared, and every change between them, file by file."""

    older: str
    newer: str
    changes: tuple[Change, ...]

    @property
    def files(self) -> list[str]:
        """The files that changed, in the order met."""
        return list(dict.fromkeys(c.file for c in self.changes))


def _answers(matrix: Matrix, column: str, case: str) -> Answers | None:
    run = matrix.runs.get(column)
    trace = None if run is None else run.traces.get(case)
    return None if trace is None else Answers.of(trace)


def compare_columns(matrix: Matrix, cases: Sequence[Case], older: str, newer: str) -> Comparison:
    """Every change from column ``older`` to column ``newer``."""
    found: list[Change] = []
    for case in cases:
        before = _answers(matrix, older, case.qualified_name)
        after = _answers(matrix, newer, case.qualified_name)
        if before is not None and after is not None:
            found += changes(case, before, after)
    return Comparison(older, newer, tuple(found))


def comparisons(
    matrix: Matrix, cases: Sequence[Case], *, reference: str | None
) -> list[Comparison]:
    """The pairs of columns to compare (see the module doc): each with ``reference`` if
    given, else each with the one before."""
    columns = [v for v in matrix.versions if matrix.runs[v].error is None]
    if reference is not None:
        pairs = [(reference, c) for c in columns if c != reference]
    else:
        pairs = list(itertools.pairwise(columns))
    return [compare_columns(matrix, cases, older, newer) for older, newer in pairs]


def _files(cases: Sequence[Case]) -> list[str]:
    return list(dict.fromkeys(file_of(c.description) for c in cases))


def _outcomes(matrix: Matrix, cases: Sequence[Case]) -> dict[str, dict[str, str]]:
    """Per file and column: ``pass``, or the worst outcome of its cases there."""
    table: dict[str, dict[str, str]] = {}
    for case in cases:
        row = table.setdefault(file_of(case.description), {})
        for column in matrix.versions:
            cell = matrix.cell(case.qualified_name, column)
            outcome = "—" if cell is None else label(cell.outcome)
            if row.get(column, "pass") == "pass":
                row[column] = outcome
    return table


def models_json(
    matrix: Matrix, cases: Sequence[Case], found: Sequence[Comparison]
) -> dict[str, Any]:
    """The ``report.json`` document (see the module doc)."""
    return {
        "columns": list(matrix.versions),
        "files": _outcomes(matrix, cases),
        "comparisons": [
            {
                "from": c.older,
                "to": c.newer,
                "files": c.files,
                "changes": [change.to_json() for change in c.changes],
            }
            for c in found
        ],
        "errors": {v: matrix.runs[v].error for v in matrix.versions if matrix.runs[v].error},
    }


def change_lines(comparison: Comparison, *, indent: str = "  ") -> list[str]:
    """Each changed file and, under it, each of its changes in full."""
    lines: list[str] = []
    for file in comparison.files:
        lines.append(f"{indent}{file}")
        for change in comparison.changes:
            if change.file == file:
                lines += [
                    f"{indent}  {line}" for line in change.lines(comparison.older, comparison.newer)
                ]
    return lines


def _escape(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def models_markdown(
    matrix: Matrix, cases: Sequence[Case], found: Sequence[Comparison], *, title: str
) -> str:
    """The ``report.md`` text: each column's outcomes, then each comparison's changes."""
    files = _files(cases)
    outcomes = _outcomes(matrix, cases)
    lines = [f"# {title}", "", f"{len(files)} model files on {len(matrix.versions)} columns.", ""]
    lines += ["| column | files | pass | other outcomes |", "|---|---:|---:|---|"]
    for column in matrix.versions:
        run = matrix.runs[column]
        if run.error:
            lines.append(f"| {column} | — | — | {_escape(run.error)} |")
            continue
        counts: dict[str, int] = {}
        for file in files:
            outcome = outcomes[file].get(column, "—")
            counts[outcome] = counts.get(outcome, 0) + 1
        other = ", ".join(f"{n} {o}" for o, n in sorted(counts.items()) if o != "pass")
        lines.append(f"| {column} | {len(files)} | {counts.get('pass', 0)} | {other or '—'} |")
    lines.append("")
    for comparison in found:
        header = f"## {comparison.older} → {comparison.newer}"
        if not comparison.changes:
            lines += [header, "", "No change.", ""]
            continue
        lines += [header, "", f"{len(comparison.files)} of {len(files)} files changed.", ""]
        lines += ["| file | what | " + f"only {comparison.older} | only {comparison.newer} |"]
        lines += ["|---|---|---|---|"]
        for change in comparison.changes:
            if change.before is not None or change.after is not None:
                old, new = change.before or "", change.after or ""
            else:
                old, new = "<br>".join(change.removed), "<br>".join(change.added)
            lines.append(
                f"| {_escape(change.file)} | {change.what} | {_escape(old)} | {_escape(new)} |"
            )
        lines.append("")
    return "\n".join(lines)


def write_models_report(
    matrix: Matrix,
    cases: Sequence[Case],
    found: Sequence[Comparison],
    folder: Path,
    *,
    title: str,
    reference: str | None = None,
) -> list[Path]:
    """Writes report.json, report.md, report.html and heatmap.png to ``folder``; returns
    their paths. The page and the picture compare the columns as ``found`` does: each
    implementation with the ``reference``, or (None) each release with the one before."""
    folder.mkdir(parents=True, exist_ok=True)
    json_path, md_path = folder / "report.json", folder / "report.md"
    document = models_json(matrix, cases, found)
    json_path.write_text(json.dumps(document, indent=2, ensure_ascii=False) + "\n")
    md_path.write_text(models_markdown(matrix, cases, found, title=title) + "\n")
    against = {c.newer: c.older for c in found if c.older in matrix.runs}
    baseline = "the release before it" if reference is None else f"the reference, {reference}"
    page = write_html(matrix, against, folder / "report.html", title=title, baseline=baseline)
    return [json_path, md_path, page, write_heatmap(matrix, folder / "heatmap.png", against)]


# ------------------------------------------------------------------ golden files
class GoldenError(ValueError):
    """A golden file that cannot be read, or that does not fit the run."""


def save_golden(path: Path, matrix: Matrix, cases: Sequence[Case], column: str) -> None:
    """Writes ``column``'s answers to every case to ``path`` (JSON)."""
    answers = {
        case.description: a.to_json()
        for case in cases
        if (a := _answers(matrix, column, case.qualified_name)) is not None
    }
    document = {"format": GOLDEN_FORMAT, "column": column, "answers": answers}
    path.write_text(json.dumps(document, indent=1, sort_keys=True) + "\n", encoding="utf-8")


def load_golden(path: Path) -> tuple[str, dict[str, Answers]]:
    """(the column it was saved from, answers by case description)."""
    try:
        document = json.loads(path.read_text(encoding="utf-8"))
        if document.get("format") != GOLDEN_FORMAT:
            raise GoldenError(f"{path}: not a golden file of format {GOLDEN_FORMAT}")
        answers = {name: Answers.from_json(a) for name, a in document["answers"].items()}
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        if isinstance(exc, GoldenError):
            raise
        raise GoldenError(f"{path}: cannot be read as a golden file: {exc}") from None
    return str(document["column"]), answers


def golden_changes(
    golden: tuple[str, dict[str, Answers]], matrix: Matrix, cases: Sequence[Case], column: str
) -> Comparison:
    """Every change from the golden answers to ``column``'s; a file the golden file lacks,
    or that the run lacks, is a change too."""
    saved_from, saved = golden
    found: list[Change] = []
    for case in cases:
        now = _answers(matrix, column, case.qualified_name)
        before = saved.get(case.description)
        if before is None:
            found.append(Change(file_of(case.description), "file", added=(case.description,)))
        elif now is not None:
            found += changes(case, before, now)
    run_names = {case.description for case in cases}
    found += [
        Change(file_of(name), "file", removed=(name,)) for name in saved if name not in run_names
    ]
    return Comparison(f"golden ({saved_from})", column, tuple(found))
