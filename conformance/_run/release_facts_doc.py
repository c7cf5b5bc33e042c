"""docs/release_facts.md, generated from the release table and its schema.

Nothing in the page is written by hand: each kind's title and description
come from the schema (``release_facts.schema.json``, ``kind.oneOf``), each
row from the table (``release_facts.json``), and the "read by" column from
the places that cite the row: known divergences (``release_fact``), scenario
expectations, release guards, the ``release_fact`` test marker, the grammar's
and the backends' binding checks, and reimpl's switches (``release.has("<id>")``
and the tables of ``reimpl/``): modules are found by the row's quoted id.

``python -m conformance._run.release_facts_doc [--check] [PATH]`` writes the
page (default docs/release_facts.md of this checkout), or with ``--check``
exits 1 if the page differs from what the table gives.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

from conformance._corpus.loader import load_corpus
from conformance._policy.divergences import known_divergences
from conformance._policy.guards import GUARDS
from conformance._policy.release_facts import FactKind, ReleaseFact, release_facts, table_releases

__all__ = ["DOC_PATH", "kind_descriptions", "main", "render"]

#: The checkout the harness runs from (the page and reimpl's sources live there).
_ROOT = Path(__file__).resolve().parents[2]
DOC_PATH = _ROOT / "docs" / "release_facts.md"
_MARKER = re.compile(r"""release_fact\(\s*["']([a-z0-9.-]+)["']""")


@cache
def _schema() -> dict[str, Any]:
    text = resources.files("conformance._policy").joinpath("release_facts.schema.json")
    schema: dict[str, Any] = json.loads(text.read_text("utf-8"))
    return schema


def kind_descriptions() -> dict[FactKind, tuple[str, str]]:
    """Each kind's (title, description), as the schema gives them."""
    kind = _schema()["$defs"]["fact"]["properties"]["kind"]
    return {FactKind(k["const"]): (k["title"], k["description"]) for k in kind["oneOf"]}


def _releases(fact: ReleaseFact) -> str:
    since, until = fact.releases.since, fact.releases.until
    if since and until:
        return f"{since} to {until}"
    return f"since {since}" if since else f"until {until}"


def _expectation_counts() -> Counter[str]:
    """How many scenario expectations name each row (on any side)."""
    counts: Counter[str] = Counter()
    for scenario_file in load_corpus():
        for case in scenario_file.cases:
            for step in case.steps:
                for expectation in step.expect:
                    references = expectation.get("release_fact", ())
                    if isinstance(references, str):
                        references = (references,)
                    for reference in references:
                        counts[reference.rpartition(" ")[2]] += 1
    return counts


def _sources(folder: str, pattern: str) -> Iterable[Path]:
    root = _ROOT / folder
    return sorted(root.rglob(pattern)) if root.is_dir() else ()


def _cited_in(ids: Iterable[str], folder: str) -> dict[str, list[str]]:
    """Row id → the modules under ``folder`` that quote it (``"<id>"``)."""
    texts = {p: p.read_text("utf-8") for p in _sources(folder, "*.py")}
    return {
        fact_id: [
            str(path.relative_to(_ROOT)) for path, text in texts.items() if f'"{fact_id}"' in text
        ]
        for fact_id in ids
    }


def _test_markers() -> Counter[str]:
    counts: Counter[str] = Counter()
    for path in _sources("tests", "*.py"):
        counts.update(_MARKER.findall(path.read_text("utf-8")))
    return counts


def _read_by(
    fact: ReleaseFact,
    divergences: Mapping[str, list[str]],
    expectations: Counter[str],
    markers: Counter[str],
    reimpl: Mapping[str, list[str]],
) -> str:
    parts = [f"divergence `{d}`" for d in divergences.get(fact.id, ())]
    if expectations[fact.id]:
        parts.append(f"{expectations[fact.id]} expectation(s)")
    if fact.id in GUARDS:
        parts.append("release guard")
    if markers[fact.id]:
        parts.append(f"{markers[fact.id]} test marker(s)")
    parts += [f"`{path}`" for path in reimpl.get(fact.id, ())]
    return "; ".join(parts) or "evidence only"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _rows(
    facts: Sequence[ReleaseFact],
    divergences: Mapping[str, list[str]],
    expectations: Counter[str],
    markers: Counter[str],
    reimpl: Mapping[str, list[str]],
) -> list[str]:
    lines = ["| id | releases | summary | evidence | read by |", "|---|---|---|---:|---|"]
    for fact in facts:
        summary = fact.summary
        if fact.bindings:
            summary += " Bindings: " + ", ".join(f"`{b}`" for b in fact.bindings) + "."
        if fact.answer is not None:
            summary += f" Answer: `{json.dumps(fact.answer, sort_keys=True)}`."
        evidence = len(fact.scenarios) + len(fact.tests)
        read_by = _read_by(fact, divergences, expectations, markers, reimpl)
        lines.append(
            f"| `{fact.id}` | {_releases(fact)} | {_cell(summary)} | {evidence} | {read_by} |"
        )
    return lines


def render() -> str:
    """The page, from the table, its schema and the rows' citations."""
    facts = list(release_facts().values())
    divergences: dict[str, list[str]] = {}
    for entry in known_divergences():
        if entry.release_fact is not None:
            divergences.setdefault(entry.release_fact, []).append(entry.id)
    expectations, markers = _expectation_counts(), _test_markers()
    reimpl: dict[str, list[str]] = {}
    for folder in ("conformance/_grammar", "conformance/_backends", "reimpl"):
        for fact_id, paths in _cited_in([f.id for f in facts], folder).items():
            reimpl.setdefault(fact_id, []).extend(paths)
    span = table_releases()
    by_kind = Counter(f.kind for f in facts)
    lines = [
        "# Release facts",
        "",
        "<!-- Generated by `python -m conformance._run.release_facts_doc` from",
        "     conformance/_policy/release_facts.json and its schema; do not edit. -->",
        "",
        f"The release table (`conformance/_policy/release_facts.json`) holds {len(facts)} facts "
        f"about the Drake releases {span.since} to {span.until}, one row each: "
        + ", ".join(f"{by_kind[k]} {k.value}" for k in FactKind)
        + ". A row gives the releases it holds for (inclusive; an `until` of two numbers "
        "covers that minor release's patches), a summary and the scenario cases or tests "
        "that show it on real pydrake. Everything that depends on a release cites a row by "
        "its id: the grammar's commands and features, the backends' capabilities, the "
        "release guards, known divergences, scenario expectations (`release_fact`), the "
        "`release_fact` test marker, and reimpl, which follows any release of the table "
        "(`--backend reimpl==X.Y.Z`; `REIMPL_DRAKE_RELEASE` in `reimpl/_release.py`).",
        "",
        "The *read by* column lists what cites each row.",
    ]
    for kind, (title, description) in kind_descriptions().items():
        of_kind = [f for f in facts if f.kind is kind]
        lines += ["", f"## `{kind.value}`: {title}", "", description, ""]
        lines += _rows(of_kind, divergences, expectations, markers, reimpl)
    return "\n".join(lines) + "\n"


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m conformance._run.release_facts_doc")
    parser.add_argument("path", nargs="?", type=Path, default=DOC_PATH)
    parser.add_argument("--check", action="store_true", help="exit 1 if the page is stale")
    args = parser.parse_args(argv)
    text = render()
    if args.check:
        current = args.path.read_text("utf-8") if args.path.is_file() else ""
        if current != text:
            print(f"{args.path} is stale: run {parser.prog}", file=sys.stderr)
            return 1
        return 0
    args.path.write_text(text, "utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
