"""The release matrix, written for people and programs: ``report.json``, ``report.md``, a heatmap.

- ``report.json``: ``{"versions": [...], "cases": {case: {version: outcome}}}``,
  plus ``details`` (``{case: {version: {"outcome", "detail", "expected_by"}}}``
  for every cell that is not ``pass``), ``releases`` (per release: its
  Python, outcome counts, and the error that kept it from running, if any)
  and ``changes`` (per consecutive pair of releases, the cases whose outcome
  changed).
- ``report.md``: a summary table per release, then for each consecutive pair
  the cases whose outcome changed, with the reasons.
- ``heatmap.png``: cases × releases, one colour per outcome (matplotlib).

Nothing in the files depends on timing or on the order the releases
finished, so the same corpus on the same releases writes the same files.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from conformance._run.case_report import Failure
from conformance._run.matrix import MATRIX_ORDER, Cell, Matrix, Outcome, label

__all__ = [
    "COLOURS",
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


def write_heatmap(matrix: Matrix, path: Path) -> Path:
    """Draws cases × releases, a colour per outcome, to ``path`` (PNG)."""
    import matplotlib  # noqa: PLC0415 (only the matrix draws)

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415
    from matplotlib.artist import Artist  # noqa: PLC0415
    from matplotlib.colors import ListedColormap  # noqa: PLC0415
    from matplotlib.lines import Line2D  # noqa: PLC0415
    from matplotlib.patches import Patch  # noqa: PLC0415

    order = list(MATRIX_ORDER)
    index = {o: i for i, o in enumerate(order)}
    grid = [
        [
            index[cell.outcome] if (cell := matrix.cell(case, v)) is not None else len(order)
            for v in matrix.versions
        ]
        for case in matrix.cases
    ]
    colours = ListedColormap([COLOURS[o] for o in order] + [_MISSING])
    height = max(4.0, 0.16 * len(matrix.cases) + 1.8)
    column = max(0.22, min(0.9, 12.0 / max(1, len(matrix.versions))))
    width = max(7.0, 5.5 + column * len(matrix.versions))
    figure, axes = plt.subplots(figsize=(width, height), dpi=110)
    axes.imshow(
        grid, aspect="auto", cmap=colours, vmin=-0.5, vmax=len(order) + 0.5, interpolation="nearest"
    )
    rotation = 90 if len(matrix.versions) > 8 else 0
    axes.set_xticks(range(len(matrix.versions)), matrix.versions, fontsize=7, rotation=rotation)
    axes.xaxis.tick_top()
    labels = [c if len(c) <= 70 else c[:69] + "…" for c in matrix.cases]
    axes.set_yticks(range(len(matrix.cases)), labels, fontsize=4.5)
    axes.set_xticks([x - 0.5 for x in range(1, len(matrix.versions))], minor=True)
    axes.grid(which="minor", axis="x", color="white", linewidth=1.5)
    axes.tick_params(which="minor", length=0)
    changed = _behaviour_marks(matrix)
    if changed:
        axes.scatter([x for x, _ in changed], [y for _, y in changed], s=6, c="black", marker="o")
    present = {c.outcome for run in matrix.runs.values() for c in run.cells.values()}
    handles: list[Artist] = [Patch(color=COLOURS[o], label=label(o)) for o in order if o in present]
    if changed:
        handles.append(
            Line2D(
                [],
                [],
                color="black",
                marker="o",
                markersize=3,
                linestyle="None",
                label="answers differ from the\nrelease before",
            )
        )
    axes.legend(
        handles=handles,
        loc="upper left",
        bbox_to_anchor=(1.01, 1.0),
        fontsize=8,
        frameon=False,
    )
    axes.set_title(f"{len(matrix.cases)} cases × {len(matrix.versions)} Drake releases", pad=24)
    figure.tight_layout()
    figure.savefig(path, metadata={"Software": None})
    plt.close(figure)
    return path


def _behaviour_marks(matrix: Matrix) -> list[tuple[int, int]]:
    """(column, row) of each cell whose outcome stayed but whose answers differ from the
    previous release's."""
    row = {case: i for i, case in enumerate(matrix.cases)}
    column = {v: i for i, v in enumerate(matrix.versions)}
    return [
        (column[newer], row[case])
        for older, newer, _ in changes(matrix)
        for case, _ in behaviour_changes(matrix, older, newer)
    ]


def write_report(matrix: Matrix, folder: Path) -> list[Path]:
    """Writes report.json, report.md and heatmap.png to ``folder``; returns their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    json_path, md_path = folder / "report.json", folder / "report.md"
    json_path.write_text(json.dumps(matrix_json(matrix), indent=2, ensure_ascii=False) + "\n")
    md_path.write_text(matrix_markdown(matrix) + "\n")
    return [json_path, md_path, write_heatmap(matrix, folder / "heatmap.png")]
