"""``report.html``: one self-contained page a person reads, for ``run``, ``matrix`` and ``models``.

``run`` (``write_run_html``) has a column per backend, each compared with
the reference; ``matrix`` a column per release, each compared with the one
before; ``models`` either (``report_rows`` names each column's baseline).

One file, no network, no external assets: inline CSS, no script; what opens
and closes is a ``<details>`` element. The page holds:

1. a title and one sentence of counts (cases, columns, how many change);
2. a table of each column's outcome counts, and the legend;
3. **the rows that change** (``report_rows.sections``): outcome changes
   first, then cases whose answers differ; each cell whose answers differ
   from its baseline column opens (``<details class="step">``) the first
   step where they differ, with both answers;
4. the rows alike everywhere but failing, if any, in full;
5. the rows alike everywhere, folded into one count (a closed
   ``<details id="alike">`` listing each case and its outcome).

A cell is drawn by its ``kind`` (``report_rows.kind``): a class
``k-<kind>``, a colour, and a symbol and words, so that no meaning rests on
colour alone. An expected crash (``◇ expected crash``, pale, dashed) and an
unexpected one (``‼ crash``, dark, solid) look different, and say why.

The page depends on nothing but the matrix: written twice, it is the same
bytes.
"""

from __future__ import annotations

import html
import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from conformance._run.matrix import Matrix
from conformance._run.report import RunReport
from conformance._run.report_rows import (
    Row,
    RowCell,
    Sections,
    Step,
    matrix_of_run,
    reference_baselines,
    rows,
    sections,
)

__all__ = ["KINDS", "html_report", "write_html", "write_run_html"]

#: Each kind of cell: (symbol, words, background, text colour, border).
KINDS: dict[str, tuple[str, str, str, str, str]] = {
    "pass": ("✓", "pass", "#e8f5e9", "#1b5e20", "1px solid #c8e6c9"),
    "fail": ("✗", "fail", "#ffcdd2", "#b71c1c", "2px solid #c62828"),
    "xfail": ("≈", "xfail", "#f1f8e9", "#33691e", "1px dashed #9ccc65"),
    "unsupported": ("–", "unsupported", "#eeeeee", "#555555", "1px solid #d5d5d5"),
    "crash": ("‼", "crash", "#4a148c", "#ffffff", "2px solid #1a0033"),
    "expected-crash": ("◇", "expected crash", "#f3e5f5", "#6a1b9a", "2px dashed #ab47bc"),
    "timeout": ("‼", "timeout", "#e65100", "#ffffff", "2px solid #8c3000"),
    "expected-timeout": ("◇", "expected timeout", "#fff3e0", "#bf5f00", "2px dashed #ffa726"),
    "error": ("‼", "error", "#212121", "#ffffff", "2px solid #000000"),
    "expected-error": ("◇", "expected error", "#f5f5f5", "#212121", "2px dashed #757575"),
    "missing": ("·", "not run", "#ffffff", "#999999", "1px dotted #bbbbbb"),
}

#: With more columns than this, a cell shows its symbol only (its words in its title).
_WIDE = 8
#: A cell's reason is cut to this many characters (its title holds it whole).
_WHY = 72
#: An answer's JSON longer than this is laid out an entry per line.
_LINE = 90
#: Answers longer than this are cut (the JSON report holds them whole).
_LONGEST = 4000


def _css() -> str:
    kinds = "\n".join(
        f".k-{name}{{background:{bg};color:{fg};border:{border}}}"
        for name, (_, _, bg, fg, border) in KINDS.items()
    )
    return f"""
body{{font:14px/1.4 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:1.5em;color:#222}}
h1{{font-size:1.5em;margin:0 0 .3em}} h2{{font-size:1.15em;margin:1.4em 0 .4em}}
table{{border-collapse:separate;border-spacing:2px}}
th,td{{padding:3px 6px;text-align:left;vertical-align:top}}
thead th{{position:sticky;top:0;background:#fafafa;border-bottom:2px solid #999;font-weight:600}}
th.case{{font-weight:normal;max-width:28em}}
.file{{display:block;color:#666;font-size:.85em}}
td.cell{{min-width:7.5em;white-space:nowrap}}
td.cell details{{white-space:normal}}
.changed-cell{{box-shadow:inset 0 0 0 2px #1565c0}}
.delta{{font-weight:700;color:#0d47a1;background:#e3f2fd;border-radius:3px;padding:0 3px;
margin-left:4px;font-size:.85em}}
.k-crash .delta,.k-timeout .delta,.k-error .delta{{color:#0d47a1}}
summary{{cursor:pointer}}
.sym{{display:inline-block;width:1.1em;text-align:center;font-weight:700}}
.why{{display:block;font-size:.85em;opacity:.9;white-space:normal;max-width:15em}}
.step-detail{{margin:.4em 0 .2em;padding:.5em;background:#fff;color:#222;border:1px solid #90caf9;
border-radius:4px;min-width:16em;max-width:26em}}
.step-detail p{{margin:.1em 0 .4em}}
.answers{{display:grid;grid-template-columns:max-content 1fr;gap:2px 8px;margin:0}}
.answers dt{{font-weight:600}} .answers dd{{margin:0}}
pre{{margin:0;white-space:pre-wrap;word-break:break-all;max-height:16em;overflow:auto;
background:#f6f8fa;padding:2px 4px;font-size:12px}}
.counts td,.counts th{{text-align:right}} .counts th:first-child{{text-align:left}}
.compact td.cell{{min-width:0;padding:2px 3px;text-align:center}}
.compact .why,.compact td.cell>.words,.compact summary .words,.compact .delta .words{{display:none}}
.compact .step-detail{{text-align:left}}
.legend span{{display:inline-block;margin:2px 6px 2px 0;padding:1px 6px;border-radius:3px}}
.note{{color:#555}}
{kinds}
"""


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def _badge(cell: RowCell) -> str:
    symbol, words, *_ = KINDS[cell.kind]
    return f'<span class="sym">{symbol}</span> <span class="words">{_e(words)}</span>'


def _why(cell: RowCell) -> str:
    """The cell's reason: the known divergence or crash row that expects it, else its
    detail (cut)."""
    if cell.cell is None:
        return ""
    text = cell.cell.expected_by or cell.cell.detail
    if cell.cell.expected_by and cell.kind.startswith("expected-"):
        text = f"expected by {cell.cell.expected_by}"
    elif cell.cell.expected_by:
        text = f"known divergence {cell.cell.expected_by}"
    return text if len(text) <= _WHY else text[: _WHY - 1] + "…"


def _layout(value: Any, indent: str = "") -> str:
    """JSON on one line if short, else one entry per line (each laid out the same way)."""
    compact = json.dumps(value, ensure_ascii=False)
    if len(compact) <= _LINE or not isinstance(value, list | dict) or not value:
        return compact
    inner = indent + "  "
    if isinstance(value, list):
        entries = [inner + _layout(v, inner) for v in value]
        return "[\n" + ",\n".join(entries) + f"\n{indent}]"
    entries = [f"{inner}{json.dumps(str(k))}: {_layout(v, inner)}" for k, v in value.items()]
    return "{\n" + ",\n".join(entries) + f"\n{indent}}}"


def _answer(value: Any) -> str:
    text = value if isinstance(value, str) else _layout(value)
    if len(text) > _LONGEST:
        text = text[:_LONGEST] + f"… ({len(text) - _LONGEST} more characters)"
    return f"<pre>{_e(text)}</pre>"


def _step_html(step: Step, column: str) -> str:
    op = f" (<code>{_e(step.op)}</code>)" if step.op else ""
    more = (
        f'<p class="note">the first of {step.differences} differences</p>'
        if step.differences > 1
        else ""
    )
    return (
        '<div class="step-detail">'
        f"<p>first difference from <b>{_e(step.baseline)}</b>: "
        f'<b class="where">{_e(step.step)}</b>{op}: {_e(step.what)}</p>'
        '<dl class="answers">'
        f'<dt class="before">{_e(step.baseline)}</dt><dd>{_answer(step.before)}</dd>'
        f'<dt class="after">{_e(column)}</dt><dd>{_answer(step.after)}</dd>'
        f"</dl>{more}</div>"
    )


def _cell_html(cell: RowCell, *, opened: bool = False) -> str:
    why = _why(cell)
    said = [cell.column, KINDS[cell.kind][1]]
    if cell.cell is not None and cell.cell.detail:
        said.append(cell.cell.detail)
    title = f' title="{_e(": ".join(said))}"'
    why_html = f'<span class="why">{_e(why)}</span>' if why else ""
    column = f'data-column="{_e(cell.column)}"{title}'
    if cell.step is None:
        return f'<td class="cell k-{cell.kind}" {column}>{_badge(cell)}{why_html}</td>'
    details = '<details class="step" open>' if opened else '<details class="step">'
    return (
        f'<td class="cell k-{cell.kind} changed-cell" {column}>{details}'
        f'<summary>{_badge(cell)}<span class="delta" title="answers differ from '
        f'{_e(cell.step.baseline)}">Δ <span class="words">{_e(cell.step.step)}</span></span>'
        "</summary>"
        f"{why_html}{_step_html(cell.step, cell.column)}</details></td>"
    )


def _case_html(case: str) -> str:
    file, sep, description = case.partition(" > ")
    if not sep:
        return f'<th scope="row" class="case">{_e(case)}</th>'
    return (
        f'<th scope="row" class="case"><span class="file">{_e(file)}</span>{_e(description)}</th>'
    )


def _table(columns: Sequence[str], table_rows: Sequence[Row], *, section: str) -> str:
    """The rows of a section, a cell per column; in the changing rows, the first cell whose
    answers differ is shown open, as an example of what each opens."""
    head = "".join(f'<th scope="col">{_e(c)}</th>' for c in columns)
    steps = [c for r in table_rows for c in r.cells if c.step is not None and section == "changed"]
    first = next((c for c in steps if c.step and c.step.step != "end"), steps[0] if steps else None)
    body = "\n".join(
        f'<tr class="row {section}" data-case="{_e(row.case)}">{_case_html(row.case)}'
        + "".join(_cell_html(cell, opened=cell is first) for cell in row.cells)
        + "</tr>"
        for row in table_rows
    )
    compact = " compact" if len(columns) > _WIDE else ""
    return (
        f'<table class="grid{compact}" id="{section}-rows"><thead><tr><th scope="col">case</th>'
        f"{head}</tr></thead>\n<tbody>\n{body}\n</tbody></table>"
    )


def _alike_html(alike: Sequence[Row], columns: int) -> str:
    """The rows alike everywhere: one count, a closed ``<details>`` listing each."""
    by_kind: dict[str, int] = {}
    for row in alike:
        by_kind[row.cells[0].kind if row.cells else "missing"] = (
            by_kind.get(row.cells[0].kind if row.cells else "missing", 0) + 1
        )
    split = ", ".join(
        f"{n} {KINDS[k][1]}" for k, n in sorted(by_kind.items(), key=lambda kn: -kn[1])
    )
    everywhere = {1: "on the one column", 2: "on both columns"}.get(
        columns, f"on all {columns} columns"
    )
    items = "\n".join(
        f'<tr class="row alike" data-case="{_e(row.case)}">{_case_html(row.case)}'
        + (_cell_html(row.cells[0]) if row.cells else "<td></td>")
        + "</tr>"
        for row in alike
    )
    return (
        f'<details id="alike"><summary><b>{len(alike)} case(s) answer alike {everywhere}</b>'
        f" ({_e(split)}): identical outcomes and answers, folded</summary>\n"
        f'<table class="grid" id="alike-rows"><thead><tr><th scope="col">case</th>'
        f'<th scope="col">every column</th></tr></thead>\n<tbody>\n{items}\n</tbody></table>'
        "</details>"
    )


def _counts_html(matrix: Matrix, found: Sequence[Row]) -> str:
    kinds = [k for k in KINDS if any(c.kind == k for r in found for c in r.cells)]
    head = "".join(f'<th scope="col" class="k-{k}">{_e(KINDS[k][1])}</th>' for k in kinds)
    lines = []
    for column in matrix.versions:
        run = matrix.runs[column]
        if run.error is not None:
            lines.append(
                f'<tr><th scope="row">{_e(column)}</th>'
                f'<td colspan="{max(1, len(kinds))}" class="k-error">could not run: '
                f"{_e(run.error)}</td></tr>"
            )
            continue
        counts = {k: 0 for k in kinds}
        for row in found:
            for cell in row.cells:
                if cell.column == column:
                    counts[cell.kind] += 1
        python = f" <small>(Python {_e(run.python)})</small>" if run.python else ""
        lines.append(
            f'<tr><th scope="row">{_e(column)}{python}</th>'
            + "".join(f"<td>{counts[k]}</td>" for k in kinds)
            + "</tr>"
        )
    return (
        f'<table class="counts"><thead><tr><th scope="col">column</th>{head}</tr></thead>'
        f"<tbody>{''.join(lines)}</tbody></table>"
    )


def _legend(present: set[str]) -> str:
    """The kinds on the page, each as drawn; an expected and an unexpected crash always."""
    shown = present | {"crash", "expected-crash"}
    spans = "".join(
        f'<span class="k-{name}"><span class="sym">{symbol}</span> {_e(words)}</span>'
        for name, (symbol, words, *_) in KINDS.items()
        if name in shown
    )
    return (
        f'<p class="legend">{spans}</p><p class="note">'
        "◇ marks a crash, timeout or error that the release table's crash row or a known "
        "divergence expects; ‼ one that nothing expects. "
        '<span class="delta">Δ step</span> marks a cell whose answers differ from its '
        "baseline column's: click it for the first step that differs and both answers.</p>"
    )


def html_report(
    matrix: Matrix,
    against: Mapping[str, str],
    *,
    title: str,
    baseline: str,
    notes: Sequence[str] = (),
) -> str:
    """The page (see the module doc); ``against`` gives each column's baseline column
    (``report_rows``), and ``baseline`` says in words what that is."""
    found = rows(matrix, against)
    parts: Sections = sections(found)
    columns = [v for v in matrix.versions if matrix.runs[v].error is None]
    changed = len(parts.changed)
    summary = (
        f"{len(matrix.cases)} cases on {len(matrix.versions)} column(s): "
        f"{changed} change across them, {len(parts.failing_alike)} fail alike everywhere, "
        f"{len(parts.alike)} answer alike everywhere."
    )
    body = [
        f"<h1>{_e(title)}</h1>",
        f'<p class="summary" id="summary">{_e(summary)}</p>',
        f'<p class="note">Each column is compared with {_e(baseline)}.</p>',
        *(f'<p class="note">{_e(note)}</p>' for note in notes),
        _counts_html(matrix, found),
        _legend({c.kind for r in found for c in r.cells}),
        f'<h2 id="changed">Cases that change across the columns ({changed})</h2>',
    ]
    if parts.changed:
        body.append(_table(columns, parts.changed, section="changed"))
    else:
        body.append(
            '<p id="no-change">No case changes: every case has the same outcome and the '
            "same answers on every column.</p>"
        )
    if parts.failing_alike:
        body += [
            f'<h2 id="failing">Cases that fail alike on every column '
            f"({len(parts.failing_alike)})</h2>",
            _table(columns, parts.failing_alike, section="failing"),
        ]
    if parts.alike:
        body += [
            '<h2 id="same">Cases alike everywhere</h2>',
            _alike_html(parts.alike, len(columns)),
        ]
    kinds = sorted({c.kind for r in found for c in r.cells})
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
        f"<title>{_e(title)}</title>\n<style>{_css()}</style>\n</head>\n"
        f'<body data-kinds="{_e(" ".join(kinds))}">\n' + "\n".join(body) + "\n</body>\n</html>\n"
    )


def write_html(
    matrix: Matrix,
    against: Mapping[str, str],
    path: Path,
    *,
    title: str,
    baseline: str,
    notes: Sequence[str] = (),
) -> Path:
    """Writes ``html_report(...)`` to ``path``; returns it."""
    path.write_text(
        html_report(matrix, against, title=title, baseline=baseline, notes=notes),
        encoding="utf-8",
    )
    return path


def write_run_html(report: RunReport, path: Path) -> Path:
    """``run``'s page: a column per backend, each compared with the reference."""
    matrix = matrix_of_run(report)
    reference = report.reference or (matrix.versions[0] if matrix.versions else "")
    backends = ", ".join(
        f"{b.name} {b.version()}" + (" (reference)" if b.name == reference else "")
        for b in report.backends
    )
    notes = [f"Backends: {backends}."]
    if report.aborted is not None:
        notes.append(f"The run stopped early ({report.aborted}): only the cases run are shown.")
    notes += [f"Left out as malformed: {message}" for message in report.input_errors]
    return write_html(
        matrix,
        reference_baselines(matrix, reference),
        path,
        title="Conformance run",
        baseline=f"the reference, {reference}",
        notes=notes,
    )
