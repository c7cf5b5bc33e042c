"""Numbers the docs quote, read from committed files: the cog blocks of README.md and docs/.

Every function reads a file the repository commits (a report a command wrote, the corpus,
the release table) and returns Markdown. ``cog -r README.md docs/*.md`` (run from the
repository root, with this folder importable: ``cog -I docs``) rewrites the text between a
block and its ``[[[end]]]``; ``cog --check`` in CI fails when a committed file changed and
the docs did not follow. Nothing here runs a backend or a release.
"""

from __future__ import annotations

import json
import re
from collections import Counter
from collections.abc import Iterable
from functools import cache
from pathlib import Path
from typing import Any

from conformance._corpus.loader import load_corpus

__all__ = [
    "corpus_count",
    "corpus_files",
    "corpus_summary",
    "file_count",
    "model_report_summary",
    "release_changes_table",
    "release_counts_table",
    "release_facts_summary",
    "release_report_summary",
    "scale_table",
]

ROOT = Path(__file__).resolve().parent.parent
RELEASE_REPORT = ROOT / "docs" / "releases" / "report.json"
MODEL_REPORT = ROOT / "docs" / "models" / "drake-examples.txt"
SCALE = ROOT / "docs" / "img" / "scale.json"
RELEASE_FACTS = ROOT / "conformance" / "_policy" / "release_facts.json"
OUTCOMES = ("pass", "fail", "xfail", "unsupported", "crash", "timeout", "error")


def _json(path: Path) -> Any:
    return json.loads(path.read_text(encoding="utf-8"))


@cache
def _corpus() -> tuple[tuple[str, int], ...]:
    """(qualified file name, case count) per scenario file of the embedded corpus."""
    return tuple((scenario.name, len(scenario.cases)) for scenario in load_corpus())


def corpus_count(*folders: str) -> int:
    """How many cases the embedded corpus has (below these top folders, if given)."""
    return sum(
        count for name, count in _corpus() if not folders or name.split("/", 1)[0] in folders
    )


def file_count(*names: str) -> int:
    """How many cases these scenario files (qualified names, e.g. ``queries/meshes``) hold."""
    return sum(count for name, count in _corpus() if name in names)


def corpus_files(folder: str) -> str:
    """``N cases in M files`` below one top folder of the corpus."""
    files = [count for name, count in _corpus() if name.split("/", 1)[0] == folder]
    return f"{sum(files)} cases in {len(files)} files"


def corpus_summary() -> str:
    """One line: cases and files, and the cases per top folder, largest first."""
    files = _corpus()
    per_folder: Counter[str] = Counter()
    for name, count in files:
        per_folder[name.split("/", 1)[0] if "/" in name else name] += count
    folders = ", ".join(f"`{folder}/` {count}" for folder, count in per_folder.most_common())
    return f"{corpus_count()} cases in {len(files)} files ({folders})"


def release_report_summary() -> str:
    """What docs/releases/report.json covers, against the corpus as it is now."""
    report = _json(RELEASE_REPORT)
    versions, cases = report["versions"], report["cases"]
    failing = sum(
        counts["counts"].get("fail", 0) + counts["counts"].get("error", 0)
        for counts in report["releases"].values()
    )
    now = corpus_count()
    cover = "the whole corpus" if len(cases) == now else f"{len(cases)} of today's {now} cases"
    return (
        f"{len(cases)} cases on {len(versions)} Drake releases, {versions[0]} to "
        f"{versions[-1]} ({cover}); {failing} failing cell(s)"
    )


def _row(cells: Iterable[object]) -> str:
    return "| " + " | ".join(str(cell) for cell in cells) + " |"


def release_counts_table() -> str:
    """docs/releases/report.json: outcome counts per release (outcomes that occur only)."""
    releases = _json(RELEASE_REPORT)["releases"]
    used = [o for o in OUTCOMES if any(r["counts"].get(o) for r in releases.values())]
    lines = [_row(["release", "Python", *used]), _row(["---"] * (len(used) + 2))]
    lines += [
        _row([version, row["python"], *(row["counts"].get(o, 0) for o in used)])
        for version, row in releases.items()
    ]
    return "\n".join(lines)


def release_changes_table() -> str:
    """docs/releases/report.json: consecutive releases where outcomes or answers change."""
    lines = [_row(["from", "to", "outcome changes", "behaviour changes"]), _row(["---"] * 4)]
    for change in _json(RELEASE_REPORT)["changes"]:
        if change["cases"] or change["behaviour"]:
            lines.append(
                _row([change["from"], change["to"], len(change["cases"]), len(change["behaviour"])])
            )
    return "\n".join(lines)


def model_report_summary() -> str:
    """docs/models/drake-examples.txt: its per-pair headline lines, as a list."""
    text = MODEL_REPORT.read_text(encoding="utf-8")
    heads = [line for line in text.splitlines() if re.match(r"^\d+\.\d+\.\d+ → ", line)]
    return "\n".join(f"- `{line}`" for line in heads)


def release_facts_summary() -> str:
    """conformance/_policy/release_facts.json: how many rows of each kind."""
    data = _json(RELEASE_FACTS)
    rows = data["facts"] if isinstance(data, dict) and "facts" in data else data
    kinds = Counter(row["kind"] for row in rows)
    parts = ", ".join(f"{count} `{kind}`" for kind, count in sorted(kinds.items()))
    return f"{len(rows)} rows ({parts})"


def _seconds(value: float) -> str:
    return f"{value:,.2f} s" if value < 10 else f"{value:,.0f} s"


def _ms(value: float) -> str:
    return f"{value:.3g} ms" if value < 10 else f"{value:,.0f} ms"


def scale_table() -> str:
    """docs/img/scale.json (benchmarks/bench_scale.py): the whole case, cycle and peak RSS."""
    data = _json(SCALE)
    labels: list[str] = []
    cells: dict[int, dict[str, str]] = {}
    candidates: dict[int, int] = {}
    for run in data["runs"]:
        if run["label"] not in labels:
            labels.append(run["label"])
        if run["ok"]:
            case = sum(run["seconds"].values())
            cell = f"{_seconds(case)}, cycle {_ms(run['cycle_ms'])}, {run['peak_rss_mb']:,.0f} MB"
            candidates[run["n"]] = run["candidates"]
        else:
            peak = f", peak {run['peak_rss_mb']:,.0f} MB" if run["peak_rss_mb"] else ""
            cell = f"**fails** after {run['wall_s']:,.0f} s: {run['failure']}{peak}"
        cells.setdefault(run["n"], {})[run["label"]] = cell
    lines = [_row(["n", *labels, "\\|C\\|"]), _row(["---"] * (len(labels) + 2))]
    for n, row in sorted(cells.items()):
        lines.append(
            _row(
                [
                    f"{n:,}",
                    *(row.get(label, "not run") for label in labels),
                    f"{candidates[n]:,}" if n in candidates else "",
                ]
            )
        )
    return "\n".join(lines)
