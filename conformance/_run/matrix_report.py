"""The release matrix, written for people and programs: ``report.json``, ``report.md``,
``report.html`` and a heatmap.

- ``report.json``: ``{"versions": [...], "cases": {case: {version: outcome}}}``,
  plus ``details`` (``{case: {version: {"outcome", "detail", "expected_by"}}}``
  for every cell that is not ``pass``), ``releases`` (per release: its
  Python, outcome counts, and the error that kept it from running, if any)
  and ``changes`` (per consecutive pair of releases, the cases whose outcome
  changed).
- ``report.md``: a summary table per release, then for each consecutive pair
  the cases whose outcome changed, with the reasons.
- ``report.html``: one self-contained page (``run.html_report``): the cases
  whose outcome or answers change across the releases first, each changed
  cell opening the first step that differs with both answers; the cases
  alike everywhere folded into one count.
- ``heatmap.png``: the cases that change (or fail alike) × releases, cases
  whose cells look alike folded into one labelled row (``report_rows.bands``;
  a failing case always has its own row), one colour per kind of cell (an
  expected crash pale, an unexpected one dark and crossed), a dot where the
  answers differ from the release before; with no such case, a line of text
  that says so (matplotlib).

Nothing in the files depends on timing or on the order the releases
finished, so the same corpus on the same releases writes the same files.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

from conformance._run.case_report import Failure
from conformance._run.html_report import write_html
from conformance._run.matrix import MATRIX_ORDER, Cell, Matrix, Outcome, label
from conformance._run.report_rows import bands, release_baselines, rows, sections

__all__ = [
    "COLOURS",
    "KIND_COLOURS",
    "behaviour_changes",
    "changes",
    "matrix_json",
    "matrix_markdown",
    "write_heatmap",
    "write_report",
]

#: One colour per outcome (the heatmap and its legend).
COLOURS: dict[Outcome, str] = {
    Outcome.PASS: "#4caf50",
    Outcome.XFAIL: "#aed581",
    Outcome.SKIP: "#d0d0d0",
    Outcome.FAIL: "#e53935",
    Outcome.CRASH: "#6a1b9a",
    Outcome.TIMEOUT: "#ff9800",
    Outcome.ERROR: "#212121",
}
_MISSING = "#ffffff"


def _outcome(cell: Cell | None) -> str:
    return "—" if cell is None else label(cell.outcome)


def changes(matrix: Matrix) -> Iterator[tuple[str, str, list[str]]]:
    """(older, newer, cases whose outcome changed) for each consecutive pair of releases."""
    versions = [v for v in matrix.release_columns if matrix.runs[v].error is None]
    for older, newer in itertools.pairwise(versions):
        changed = [
            case
            for case in matrix.cases
            if _outcome(matrix.cell(case, older)) != _outcome(matrix.cell(case, newer))
        ]
        yield older, newer, changed


def behaviour_changes(matrix: Matrix, older: str, newer: str) -> list[tuple[str, list[Failure]]]:
    """(case, differences) for each case whose outcome stayed but whose answers changed
    between ``older`` and ``newer`` (step by step, the one comparison)."""
    found = []
    for case in matrix.cases:
        if _outcome(matrix.cell(case, older)) != _outcome(matrix.cell(case, newer)):
            continue  # an outcome change, listed as such
        differences = matrix.behaviour_change(case, older, newer)
        if differences:
            found.append((case, differences))
    return found


def _difference_json(case: str, differences: list[Failure]) -> dict[str, Any]:
    first = differences[0]
    return {
        "case": case,
        "step": first.step,
        "what": first.what,
        "from": first.expected,
        "to": first.actual,
        "differences": len(differences),
    }


def matrix_json(matrix: Matrix) -> dict[str, Any]:
    """The ``report.json`` document (see the module doc)."""
    cases = {
        case: {v: _outcome(matrix.cell(case, v)) for v in matrix.versions} for case in matrix.cases
    }
    details: dict[str, dict[str, Any]] = {}
    for case in matrix.cases:
        for v in matrix.versions:
            cell = matrix.cell(case, v)
            if cell is not None and cell.outcome is not Outcome.PASS:
                details.setdefault(case, {})[v] = cell.to_json()
    releases = {
        v: {
            "python": run.python,
            "counts": {label(o): run.count(o) for o in MATRIX_ORDER},
            **({"error": run.error} if run.error else {}),
        }
        for v, run in ((v, matrix.runs[v]) for v in matrix.versions)
    }
    return {
        "versions": list(matrix.versions),
        "cases": cases,
        "details": details,
        "releases": releases,
        "changes": [
            {
                "from": older,
                "to": newer,
                "cases": changed,
                "behaviour": [
                    _difference_json(case, found)
                    for case, found in behaviour_changes(matrix, older, newer)
                ],
            }
            for older, newer, changed in changes(matrix)
        ],
    }


def _escape(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _why(cell: Cell | None) -> str:
    if cell is None:
        return "—"
    detail = cell.expected_by or cell.detail
    detail = detail if len(detail) <= 140 else detail[:139] + "…"
    return f"**{label(cell.outcome)}**" + (f" ({_escape(detail)})" if detail else "")


def matrix_markdown(matrix: Matrix, *, title: str = "Release matrix") -> str:
    """The ``report.md`` text (see the module doc)."""
    shown = list(MATRIX_ORDER)
    releases = len(matrix.release_columns)
    others = len(matrix.versions) - releases
    beside = f" and {others} implementation(s)" if others else ""
    lines = [f"# {title}", "", f"{len(matrix.cases)} cases on {releases} releases{beside}.", ""]
    lines.append("| release | Python | " + " | ".join(label(o) for o in shown) + " |")
    lines.append("|---|---|" + "---:|" * len(shown))
    for v in matrix.versions:
        run = matrix.runs[v]
        if run.error:
            lines.append(f"| {v} | {run.python or '—'} | {_escape(run.error)} |")
            continue
        counts = " | ".join(str(run.count(o)) for o in shown)
        lines.append(f"| {v} | {run.python} | {counts} |")
    lines += ["", "## What changed between consecutive releases", ""]
    lines += [
        "An *outcome* change is a cell that changed; a *behaviour* change is a case whose",
        "outcome stayed but whose answers differ step by step (the case's since/until",
        "expectations already allow for it). Only the first difference of a case is shown.",
        "",
    ]
    quiet = []
    for older, newer, changed in changes(matrix):
        behaviour = behaviour_changes(matrix, older, newer)
        if not changed and not behaviour:
            quiet.append(f"{older} → {newer}")
            continue
        lines.append(
            f"### {older} → {newer}: {len(changed)} outcome, {len(behaviour)} behaviour change(s)"
        )
        lines.append("")
        if changed:
            lines += [f"| case | {older} | {newer} |", "|---|---|---|"]
            for case in changed:
                before, after = matrix.cell(case, older), matrix.cell(case, newer)
                lines.append(f"| {_escape(case)} | {_why(before)} | {_why(after)} |")
            lines.append("")
        if behaviour:
            lines += ["| case | first difference | " + f"{older} | {newer} |", "|---|---|---|---|"]
            for case, found in behaviour:
                first = found[0]
                lines.append(
                    f"| {_escape(case)} | {_escape(first.step)}: {_escape(first.what)} | "
                    f"{_short(first.expected)} | {_short(first.actual)} |"
                )
            lines.append("")
    if quiet:
        lines += ["No change between: " + ", ".join(quiet) + ".", ""]
    return "\n".join(lines)


def _short(value: Any) -> str:
    text = json.dumps(value, ensure_ascii=False) if not isinstance(value, str) else value
    return _escape(text if len(text) <= 120 else text[:119] + "…")


#: The heatmap's colour of each kind of cell (``report_rows.kind``): an expected break is
#: pale and hatched, an unexpected one dark.
KIND_COLOURS: dict[str, str] = {
    "pass": COLOURS[Outcome.PASS],
    "xfail": COLOURS[Outcome.XFAIL],
    "unsupported": COLOURS[Outcome.SKIP],
    "fail": COLOURS[Outcome.FAIL],
    "crash": COLOURS[Outcome.CRASH],
    "expected-crash": "#e1bee7",
    "timeout": COLOURS[Outcome.TIMEOUT],
    "expected-timeout": "#ffe0b2",
    "error": COLOURS[Outcome.ERROR],
    "expected-error": "#bdbdbd",
    "missing": _MISSING,
}
#: Longest case label drawn (the rest is cut with an ellipsis).
_LABEL = 96


def _label(case: str) -> str:
    return case if len(case) <= _LABEL else case[: _LABEL - 1] + "…"


def _no_change(matrix: Matrix, columns: list[str], path: Path) -> Path:
    """A line of text instead of an empty grid."""
    import matplotlib.pyplot as plt  # noqa: PLC0415

    figure = plt.figure(figsize=(7.0, 1.2), dpi=110)
    figure.text(
        0.5,
        0.5,
        f"No case changes: all {len(matrix.cases)} cases answer alike\n"
        f"on {', '.join(columns) or 'no column'}.",
        ha="center",
        va="center",
        fontsize=11,
    )
    figure.savefig(path, metadata={"Software": None})
    plt.close(figure)
    return path


def _handles(present: set[str], unexpected: list[Any], marks: list[Any]) -> list[Any]:
    """The heatmap legend's entries: each kind drawn, then the two marks if drawn."""
    from matplotlib.lines import Line2D  # noqa: PLC0415
    from matplotlib.patches import Patch  # noqa: PLC0415

    handles: list[Any] = [
        Patch(color=KIND_COLOURS[k], label=k.replace("-", " "))
        for k in KIND_COLOURS
        if k in present
    ]
    if unexpected:
        handles.append(
            Line2D([], [], color="black", marker="x", linestyle="None", label="× unexpected break")
        )
    if marks:
        handles.append(
            Line2D(
                [],
                [],
                color="black",
                marker="o",
                markersize=4,
                linestyle="None",
                label="answers differ from\nthe baseline column",
            )
        )
    return handles


def write_heatmap(matrix: Matrix, path: Path, against: Mapping[str, str] | None = None) -> Path:
    """Draws the cases that change across the columns (``report_rows``) × the columns, a
    colour per kind of cell, to ``path`` (PNG); a cell whose answers differ from its
    baseline column's is marked with a dot. If no case changes, the picture says so in
    words instead of drawing an empty grid."""
    import matplotlib  # noqa: PLC0415 (only the matrix draws)

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415
    from matplotlib.colors import ListedColormap  # noqa: PLC0415

    against = release_baselines(matrix) if against is None else against
    parts = sections(rows(matrix, against))
    shown = [*parts.changed, *parts.failing_alike]
    columns = [v for v in matrix.versions if matrix.runs[v].error is None]
    if not shown:
        return _no_change(matrix, columns, path)
    drawn = bands(shown)
    kinds = list(KIND_COLOURS)
    index = {k: i for i, k in enumerate(kinds)}
    grid = [[index[cell.kind] for cell in band.cells] for band in drawn]
    colours = ListedColormap([KIND_COLOURS[k] for k in kinds])
    labels = [_label(band.label) for band in drawn]
    longest = max(len(text) for text in labels)
    label_width = 0.062 * longest  # inches at 8.5 pt
    column = max(0.3, min(0.85, 14.0 / len(columns)))  # inches: ≤ about 15 for them all
    width = label_width + column * len(columns) + 2.6
    height = 0.22 * len(drawn) + 1.6
    figure, axes = plt.subplots(figsize=(width, height), dpi=110)
    axes.imshow(
        grid, aspect="auto", cmap=colours, vmin=-0.5, vmax=len(kinds) - 0.5, interpolation="nearest"
    )
    rotation = 90 if len(columns) > 12 else 0
    axes.set_xticks(range(len(columns)), columns, fontsize=9, rotation=rotation)
    axes.xaxis.tick_top()
    axes.set_yticks(range(len(drawn)), labels, fontsize=8.5)
    axes.set_xticks([x - 0.5 for x in range(1, len(columns))], minor=True)
    axes.set_yticks([y - 0.5 for y in range(1, len(drawn))], minor=True)
    axes.grid(which="minor", color="white", linewidth=1.5)
    axes.tick_params(which="minor", length=0)
    marks = [
        (x, y) for y, band in enumerate(drawn) for x, cell in enumerate(band.cells) if cell.step
    ]
    unexpected = [
        (x, y)
        for y, band in enumerate(drawn)
        for x, cell in enumerate(band.cells)
        if cell.kind in ("crash", "timeout", "error")
    ]
    if marks:
        axes.scatter([x for x, _ in marks], [y for _, y in marks], s=14, c="black", marker="o")
    if unexpected:
        axes.scatter(
            [x for x, _ in unexpected], [y for _, y in unexpected], s=40, c="white", marker="x"
        )
    handles = _handles({cell.kind for band in drawn for cell in band.cells}, unexpected, marks)
    axes.legend(
        handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8.5, frameon=False
    )
    alike = len(parts.alike)
    folded = (
        f", in {len(drawn)} rows (cases that look alike folded)" if len(drawn) < len(shown) else ""
    )
    axes.set_title(
        f"{len(shown)} of {len(matrix.cases)} cases change or fail × {len(columns)} columns"
        f"{folded}; {alike} alike everywhere, not drawn",
        pad=28 if rotation == 0 else 40,
        fontsize=10,
    )
    figure.tight_layout()
    figure.savefig(path, metadata={"Software": None})
    plt.close(figure)
    return path


def write_report(matrix: Matrix, folder: Path) -> list[Path]:
    """Writes report.json, report.md, report.html and heatmap.png to ``folder``; returns
    their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    json_path, md_path = folder / "report.json", folder / "report.md"
    json_path.write_text(json.dumps(matrix_json(matrix), indent=2, ensure_ascii=False) + "\n")
    md_path.write_text(matrix_markdown(matrix) + "\n")
    against = release_baselines(matrix)
    page = write_html(
        matrix,
        against,
        folder / "report.html",
        title="Release matrix",
        baseline="the release before it (an implementation's column: Drake's column of its "
        "release, else the first column)",
    )
    return [json_path, md_path, page, write_heatmap(matrix, folder / "heatmap.png", against)]
