"""Numbers the docs quote, read from committed files: the cog blocks of README.md and docs/.

Every function reads a file the repository commits (a report a command wrote, the corpus,
the release table) and returns Markdown. ``cog -r README.md docs/*.md`` (run from the
repository root, with this folder importable: ``cog -I docs``) rewrites the text between a
block and its ``[[[end]]]``; ``cog --check`` in CI fails when a committed file changed and
the docs did not follow. Nothing here runs a backend or a release. Run cog with the
worktree's own package first on the path (``PYTHONPATH=. cog -I docs ...``): the counts
come from its ``conformance`` (corpus, mutants), not from another installed copy.

Measured numbers come from reports under docs/reports/, each written by one command (the
page that quotes it names the command): ``benchmarks/bench_{calls,filter,queries,fuzz,
matrix,legacy}.py --json FILE``,
``benchmarks/measure_{tolerances,hull_tolerances,mesh_script}.py --json FILE`` (reimpl's
numbers against pydrake's), ``python -m conformance fuzz ... --json FILE`` (a campaign's
statistics and coverage), a fuzz finding file (a shrunk example), and
``python -m conformance bisect ...``'s stdout. To refresh one, run its command again,
then ``cog -r``. A timing the docs would quote from nowhere else is left out of the text.
"""

from __future__ import annotations

import importlib
import json
import re
from collections import Counter
from collections.abc import Iterable
from functools import cache
from pathlib import Path
from typing import Any

from conformance._corpus.loader import load_corpus

__all__ = [
    "bench_calls_table",
    "bench_filter_table",
    "bench_fuzz_table",
    "bench_matrix_summary",
    "bench_queries_table",
    "bisect_summary",
    "corpus_count",
    "corpus_files",
    "corpus_summary",
    "coverage_features_text",
    "feature_counts",
    "file_count",
    "finding_steps",
    "fuzz_features_sentence",
    "fuzz_report",
    "legacy_table",
    "mesh_script_differences",
    "model_mutant_count",
    "model_report_summary",
    "module_constant",
    "mutant_count",
    "release_changes_table",
    "release_counts_table",
    "release_facts_summary",
    "release_report_folder",
    "release_report_summary",
    "scale_import_rss",
    "scale_ratios",
    "scale_split",
    "scale_stage",
    "scale_table",
    "tolerance_rows_table",
    "tolerance_study_summary",
    "tolerance_study_table",
]

ROOT = Path(__file__).resolve().parent.parent
RELEASE_REPORT = ROOT / "docs" / "releases" / "report.json"
MODEL_REPORT = ROOT / "docs" / "models" / "drake-examples.txt"
SCALE = ROOT / "docs" / "img" / "scale.json"
#: Reports that commands and benchmarks wrote (each names its command in docs/reports/README.md).
REPORTS = ROOT / "docs" / "reports"
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


def _scale_run(label: str, n: int) -> dict[str, Any]:
    (run,) = (r for r in _json(SCALE)["runs"] if r["label"] == label and r["n"] == n)
    return dict(run)


def _factor(value: float) -> str:
    """A ratio as ``0.032×`` or, when small, ``1.9·10⁻⁵×``."""
    if value >= 0.001:
        return f"{value:.2g}×"
    mantissa, exponent = f"{value:.1e}".split("e")
    sup = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
    return f"{mantissa}·10{str(int(exponent)).translate(sup)}×"


def scale_ratios(n: int) -> str:
    """docs/img/scale.json at one n: reimpl's case time, cycle and peak RSS over each pydrake's."""
    ours = _scale_run("reimpl", n)
    others = [r for r in _json(SCALE)["runs"] if r["n"] == n and r["label"] != "reimpl"]

    def ratios(key: str) -> str:
        return " and ".join(_factor(value(ours, key) / value(r, key)) for r in others)

    def value(run: dict[str, Any], key: str) -> float:
        return float(sum(run["seconds"].values()) if key == "case" else run[key])

    names = " and ".join(r["label"] for r in others)
    return (
        f"At n = {n:,} the case takes reimpl {ratios('case')} the time of {names} (in that order), "
        f"a transient cycle {ratios('cycle_ms')}, and peak RSS {ratios('peak_rss_mb')}. "
        f"All three agree on |C| ({ours['candidates']:,}) and on how many of the 10,000 "
        f"random pairs are filtered ({ours['filtered']:,})."
    )


def scale_import_rss() -> str:
    """docs/img/scale.json: the RSS of each implementation's import alone, as a range."""
    per: dict[str, list[float]] = {}
    for run in _json(SCALE)["runs"]:
        per.setdefault("reimpl" if run["label"] == "reimpl" else "pydrake", []).append(
            run["import_rss_mb"]
        )
    low, high = (f"{min(per['pydrake']):.0f}", f"{max(per['pydrake']):.0f}")
    span = low if low == high else f"{low}–{high}"
    return f"pydrake's import alone is {span} MB, reimpl's {max(per['reimpl']):.0f} MB"


def scale_split(n: int) -> str:
    """docs/img/scale.json: reimpl's registration and candidate stages against its whole case."""
    run = _scale_run("reimpl", n)
    seconds = run["seconds"]
    return (
        f"at n = {n:,}, registration takes {_seconds(seconds['register'])} and the "
        f"{run['candidates']:,} candidate pairs {_seconds(seconds['candidate count'])} of "
        f"the case's {_seconds(sum(seconds.values()))}."
    )


def scale_stage(label: str, n: int, stage: str) -> str:
    """docs/img/scale.json: one stage's seconds of one run, e.g. reimpl's ``register``."""
    return _seconds(_scale_run(label, n)["seconds"][stage])


def _report(name: str) -> Any:
    return _json(REPORTS / name)


def _us(value: float) -> str:
    return f"{value:.3g}" if value < 1000 else f"{value:,.0f}"


def bench_calls_table() -> str:
    """docs/reports/bench_calls.json (benchmarks/bench_calls.py): µs per call and the ratio."""
    data = _report("bench_calls.json")
    lines = [_row(["n", "operation", "reimpl", "pydrake", "ratio"]), _row(["---"] * 5)]
    lines += [
        _row(
            [
                row["n"],
                row["operation"],
                _us(row["reimpl_us"]),
                _us(row["pydrake_us"]),
                f"{row['reimpl_us'] / row['pydrake_us']:.2f}",
            ]
        )
        for row in data["rows"]
    ]
    worst = max(row["reimpl_us"] / row["pydrake_us"] for row in data["rows"])
    head = (
        f"µs per call against pydrake {data['pydrake']}, the median of {data['repeat']} "
        f"batches; the largest ratio is {worst:.2f}:"
    )
    return head + "\n\n" + "\n".join(lines)


def bench_filter_table() -> str:
    """docs/reports/bench_filter.json (benchmarks/bench_filter.py): median ms and the ratio."""
    data = _report("bench_filter.json")
    lines = [_row(["n", "operation", "reimpl ms", "pydrake ms", "ratio"]), _row(["---"] * 5)]
    lines += [
        _row(
            [
                f"{row['n']:,}",
                row["operation"],
                _us(row["reimpl_ms"]),
                _us(row["pydrake_ms"]),
                f"{row['reimpl_ms'] / row['pydrake_ms']:.3g}",
            ]
        )
        for row in data["rows"]
    ]
    return f"Against pydrake {data['pydrake']}:\n\n" + "\n".join(lines)


def bench_queries_table(*names: str) -> str:
    """docs/reports/bench_queries*.json (benchmarks/bench_queries.py): reimpl/pydrake ratios."""
    reports = [_report(name) for name in names]
    hows = ("same poses", "new poses")
    columns = [f"{r['scene'].split(',')[0].split(' (')[0]}: {how}" for r in reports for how in hows]
    lines = [_row(["query", *columns]), _row(["---"] * (len(columns) + 1))]
    for index, row in enumerate(reports[0]["rows"]):
        cells = [
            f"{r['rows'][index][how]['reimpl_ms'] / r['rows'][index][how]['pydrake_ms']:.2g}×"
            for r in reports
            for how in hows
        ]
        lines.append(_row([row["query"], *cells]))
    scenes = "; ".join(
        f"{r['scene']}: n = {r['n']:,}, cube side {r['side']:g}, pydrake {r['pydrake']}, "
        f"{r['rows'][0]['answers']['pydrake']:,} penetrating pairs"
        for r in reports
    )
    return f"reimpl / pydrake, medians ({scenes}):\n\n" + "\n".join(lines)


def bench_fuzz_table() -> str:
    """docs/reports/bench_fuzz.json (benchmarks/bench_fuzz.py): one row per band of sizes."""
    data = _report("bench_fuzz.json")
    head = [
        "geometries",
        "steps/s",
        "bound",
        "in backends",
        "reimpl µs/step",
        "pydrake µs/step",
        "reimpl / pydrake",
        "overhead ratio",
        "at end",
    ]
    lines = [_row(head), _row(["---"] * len(head))]
    for row in data["rows"]:
        lines.append(
            _row(
                [
                    row["band"],
                    f"{row['steps_per_s']:,.0f}",
                    f"{row['bound_steps_per_s']:,.0f}",
                    f"{row['in_backends']:.0%}",
                    f"{row['backend_us_per_step']:,.0f}",
                    f"{row['reference_us_per_step']:,.0f}",
                    f"{row['backend_us_per_step'] / row['reference_us_per_step']:.2f}",
                    f"{row['overhead_ratio']:.2f}",
                    f"{row['final_geometries']:.1f}",
                ]
            )
        )
    rows = data["rows"]
    cheaper = sum(row["backend_us_per_step"] < row["reference_us_per_step"] for row in rows)
    ceiling = max(row["bound_steps_per_s"] / row["steps_per_s"] for row in rows)
    return (
        f"Against pydrake {data['pydrake']}, seed {data['seed']}, {data['examples']} examples, "
        f"{data['repeat']} run(s) per band (Hypothesis alone, a state machine of two no-op "
        f"rules: {data['hypothesis_steps_per_s']:,.0f} steps/s in the same run):"
        "\n\n" + "\n".join(lines) + "\n\n"
        f"reimpl takes less time per step than pydrake in {cheaper} of {len(rows)} bands; "
        f"if reimpl took no time at all, steps/s would rise by at most {ceiling:.2f}×."
    )


def fuzz_report(name: str) -> dict[str, Any]:
    """A committed ``fuzz --json`` report below docs/reports/."""
    return dict(_report(name))


def feature_counts(feature: str, *names: str) -> str:
    """How often ``fuzz --json`` reports reached one feature (``35, 26 and 58 times at ...``)."""
    reports = [fuzz_report(name) for name in names]
    counts = _and([f"{r['coverage']['features'][feature]:,}" for r in reports])
    seeds = _and([str(r["seed"]) for r in reports])
    return f"{counts} times at seed{'s' if len(reports) > 1 else ''} {seeds}"


def _and(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def fuzz_features_sentence(*names: str) -> str:
    """``fuzz --json`` reports of one campaign at several seeds: features reached, steps."""
    reports = [fuzz_report(name) for name in names]
    parts = []
    for r in reports:
        coverage = r["coverage"]
        expected = coverage["expected"]
        reached = len(expected) - len(coverage["gaps"])
        parts.append(
            f"all {reached}" if reached == len(expected) else f"{reached} of {len(expected)}"
        )
    least = min(
        min(r["coverage"]["features"][f] for f in r["coverage"]["expected"]) for r in reports
    )
    seeds = _and([str(r["seed"]) for r in reports])
    examples = _and(sorted({f"{r['examples']:,}" for r in reports}))
    what = parts[0] if len(set(parts)) == 1 else _and(parts)
    steps = _and([f"{r['steps']:,}" for r in reports])
    divergences = sum(r["divergences"] for r in reports)
    return (
        f"at seed{'s' if len(reports) > 1 else ''} {seeds}, {examples} examples reach {what} "
        f"features of the campaign, each at least {least:,} time{'s' if least != 1 else ''} "
        f"({steps} steps), with {divergences} divergence{'s' if divergences != 1 else ''}"
    )


def mutant_count(*modules: str) -> int:
    """How many mutants these modules of conformance/_testing list (``mutants_state`` ...)."""
    total = 0
    for module in modules:
        loaded = importlib.import_module(f"conformance._testing.{module}")
        (name,) = (name for name in loaded.__all__ if name.endswith("MUTANTS"))
        total += len(getattr(loaded, name))
    return total


def module_constant(module: str, name: str) -> str:
    """A constant of a module of this repository (e.g. a mutant's word width), as text."""
    return str(getattr(importlib.import_module(module), name))


def coverage_features_text() -> str:
    """What conformance/_fuzz/coverage.py counts as a feature, with its thresholds."""
    coverage = importlib.import_module("conformance._fuzz.coverage")
    crowd, stack, stretch = coverage._CROWD, coverage._STACK, coverage._STRETCH
    return (
        "The features are the largest count of proximity geometries at a location (and "
        f"growth past {crowd} during a sequence), {stack} or more active transient "
        f"declarations, out-of-order removals (also from a stack of {stack}), clones of "
        "contexts with history, then edited on both sides, model edits after contexts exist, "
        f"edits in clones and in their origins, stretches of {stretch} model and context "
        "edits without history, filter edits after roles were removed and re-assigned by "
        "frame, each op at each kind of location (model, context, clone), and each kind of "
        "error."
    )


def model_mutant_count(prefix: str) -> int:
    """How many model mutants (conformance/_testing/model_mutants.py) have names so starting."""
    loaded = importlib.import_module("conformance._testing.model_mutants")
    return sum(name.startswith(prefix) for name in loaded.MODEL_MUTANTS)


def bisect_summary(name: str) -> str:
    """A committed ``bisect`` output (docs/reports/): how many releases it tested, its answer."""
    lines = (REPORTS / name).read_text(encoding="utf-8").splitlines()
    (head,) = (line for line in lines if line.startswith("first release that differs"))
    answer, tested = head.split("; ")
    first_step = next(line.strip() for line in lines if line.strip().startswith("at "))
    return (
        f"tests {tested.removesuffix(' tested')} and prints `{answer}` with the first "
        f"difference (`{first_step}`)"
    )


def bench_matrix_summary() -> str:
    """docs/reports/bench_matrix.json (benchmarks/bench_matrix.py): matrix time, worker cost."""
    data = _report("bench_matrix.json")
    matrix, overhead = data["matrix"], data["overhead"]
    releases = _and(matrix["releases"])
    local, worker = overhead["in_process_us_per_step"], overhead["worker_us_per_step"]
    return (
        f"the {len(matrix['releases'])} releases {releases} over the corpus "
        f"({matrix['cases']:,} cases) took {_seconds(matrix['seconds'])} with `--jobs "
        f"{matrix['jobs']}`; a worker cost {worker:,.0f} µs per step against "
        f"{local:,.0f} µs for pydrake {overhead['release']} in-process, {worker / local:.2f}× "
        f"(the matrix {_met(matrix['seconds'] < 120)}, the worker {_met(worker / local < 2)})"
    )


def bench_models_summary() -> str:
    """docs/reports/bench_models.json (benchmarks/bench_models.py): models across releases."""
    data = _report("bench_models.json")
    return (
        f"{data['files']} model files ({data['cases']} cases) on the {len(data['releases'])} "
        f"releases {_and(data['releases'])} took {_seconds(data['seconds'])} with `--jobs "
        f"{data['jobs']}` on {data['cores']} cores (target: under 2 minutes; "
        f"{_met(data['seconds'] < 120)})"
    )


def _met(ok: bool) -> str:
    return "within its target" if ok else "**over its target**"


def legacy_table(name: str) -> str:
    """docs/reports/bench_legacy.json (benchmarks/bench_legacy.py): one of its three tables."""
    return "\n".join(_report("bench_legacy.json")["tables"][name])


def release_report_folder(folder: str) -> str:
    """docs/releases/report.json restricted to one corpus folder: outcome counts, and crashes
    that a known divergence expects (``expected_by``) apart from those none does."""
    report = _json(RELEASE_REPORT)
    cases = {name: row for name, row in report["cases"].items() if name.startswith(folder + "/")}
    outcomes: Counter[str] = Counter()
    for name, row in cases.items():
        for version, outcome in row.items():
            detail = report["details"].get(name, {}).get(version, {})
            expected = outcome == "crash" and detail.get("expected_by")
            outcomes["expected crash" if expected else outcome] += 1
    counts = ", ".join(f"{count:,} {outcome}" for outcome, count in sorted(outcomes.items()))
    return f"its {len(cases)} cases on {len(report['versions'])} releases: {counts}"


def finding_steps(name: str, indent: str = "") -> str:
    """A committed fuzz finding (a scenario file in docs/reports/): its step count, then each
    step as compact JSON, one list item a step, and the disagreement its comment records."""
    scenario = _report(name)
    (case,) = scenario["cases"]
    steps = case["steps"]
    items = [
        f"{indent}{number}. `{json.dumps(step, separators=(', ', ': '))}`"
        for number, step in enumerate(steps, 1)
    ]
    disagreement = scenario["comment"].split("The disagreement: ", 1)[-1]
    return (
        f"{len(steps)} steps:\n\n"
        + "\n".join(items)
        + f"\n\n{indent}The disagreement (the reference is pydrake): `{disagreement}`"
    )


def _sci(value: float) -> str:
    return "0" if value == 0 else f"{value:.1e}"


def tolerance_study_table(report: str = "tolerances.json") -> str:
    """docs/reports/tolerances.json (benchmarks/measure_tolerances.py; or ``report``, e.g.
    tolerances_hull.json of measure_hull_tolerances.py): one row per shape pair, the
    largest differences reimpl-pydrake and the counts outside the tolerances (and, where
    the report counts them, the records whose ``d`` is equal to the bit)."""
    data = _report(report)
    far = f"{data['far']:g}"
    equal = "equal_dd" in next(iter(data["pairs"].values()))
    head = [
        "shape pair",
        "scenes",
        "records",
        *(["d equal to the bit"] if equal else []),
        "max \\|Δd\\|",
        f"max ‖Δp‖, \\|d\\| ≥ {far}",
        "max ‖Δp‖, any d",
        f"max ‖Δ(d·n)‖, \\|d\\| ≥ {far}",
        "outside (d / p / d·n)",
        "missed the gap",
        "HasCollisions differs",
        "raised",
        "aborted",
    ]
    lines = [_row(head), _row(["---", *["---:"] * (len(head) - 1)])]
    for pair, row in data["pairs"].items():
        outside = "/".join(str(row[f"outside_{k}"]) for k in ("distance", "witness", "normal"))
        lines.append(
            _row(
                [
                    pair,
                    f"{row['scenes']:,}",
                    f"{row['records']:,}",
                    *([f"{row['equal_dd']:,}"] if equal else []),
                    _sci(row["max_dd"]),
                    _sci(row["max_dp_far"]),
                    _sci(row["max_dp"]),
                    _sci(row["max_dn_far"]),
                    f"{row['outside']} ({outside})" if row["outside"] else "0",
                    f"{row['gap_missed']:,}",
                    row["has_collisions_disagreements"],
                    row["raised"],
                    row["aborted"],
                ]
            )
        )
    return "\n".join(lines)


def tolerance_study_summary(report: str = "tolerances.json") -> str:
    """docs/reports/tolerances.json (or ``report``): the study's size, its command and its
    totals."""
    data = _report(report)
    rows = data["pairs"].values()
    total = {key: sum(row[key] for row in rows) for key in next(iter(rows))}
    low, high = data["gap_range"]
    errors = "".join(f"\n- {count:,} × {message}" for message, count in data["errors"].items())
    return (
        f"`{data['command']} --json docs/reports/{report}` on pydrake "
        f"{data['pydrake']}: {total['scenes']:,} scenes measured, gaps ±[{low:g}, {high:g}], "
        f"{total['records']:,} records; {total['outside']:,} records with a number outside "
        f"the tolerances, {total['has_collisions_disagreements']:,} `HasCollisions` "
        f"disagreements, {total['penetration_set_disagreements']:,} records one side "
        f"reports and the other does not; on {total['gap_missed']:,} scenes pydrake's signed "
        f"distance missed the gap by more than {data['gap_miss']:g} m. "
        f"{total['raised']:,} scenes raised an error and {total['aborted']:,} ended their "
        f"process (side, phase, FCL's message):\n{errors or ' none'}"
    )


def hull_study_hulls() -> str:
    """docs/reports/tolerances_hull.json: the hull files the study drew from, with the
    number of scenes each took part in."""
    data = _report("tolerances_hull.json")
    return ", ".join(f"`{path}` ({count:,})" for path, count in data["hulls"].items())


def hull_study_outside() -> str:
    """docs/reports/tolerances_hull.json: the records outside conformance/_tolerances.py's
    ``HULL`` and ``HULL_HALFSPACE`` rows, and the disagreements of pair sets and booleans."""
    data = _report("tolerances_hull.json")
    rows = data["pairs"]
    halfspace = [row for pair, row in rows.items() if pair.endswith("halfspace")]
    hull = [row for pair, row in rows.items() if not pair.endswith("halfspace")]

    def total(group: list[dict[str, Any]], key: str) -> int:
        return sum(row[key] for row in group)

    def outside(group: list[dict[str, Any]]) -> str:
        counts = "/".join(
            f"{total(group, f'outside_{k}'):,}" for k in ("distance", "witness", "normal")
        )
        return (
            f"{total(group, 'outside'):,} of {total(group, 'records'):,} records "
            f"(d / p / d·n: {counts})"
        )

    differ = total([*hull, *halfspace], "has_collisions_disagreements")
    sets = total([*hull, *halfspace], "penetration_set_disagreements")
    nearest = max(row["max_d_disagreeing"] for row in rows.values())
    return (
        f"Outside the `HULL` row: {outside(hull)}; outside the `HULL_HALFSPACE` row: "
        f"{outside(halfspace)}, {total(halfspace, 'equal_dd'):,} of its depths equal to the "
        f"bit; {differ:,} `HasCollisions` disagreements and {sets:,} records one side "
        f"reports and the other does not, all on scenes where pydrake's signed distance (or "
        f"depth) is at most {_sci(nearest)} m from contact"
    )


def tolerance_rows_table() -> str:
    """conformance/_tolerances.py: each row's values and the unordered shape pairs it
    covers (a mesh and a convex hull written as one, ``mesh/convex``)."""
    module = importlib.import_module("conformance._tolerances")
    names = ("CLOSED", "ITERATIVE", "HULL", "HULL_HALFSPACE")
    rows = {id(getattr(module, name)): name for name in names}
    order = ("sphere", "box", "cylinder", "capsule", "ellipsoid", "halfspace", "mesh/convex")
    pairs: dict[str, set[tuple[str, ...]]] = {name: set() for name in names}
    for pair, row in module.TOLERANCES.items():
        shapes = sorted(
            {"mesh/convex" if s in ("mesh", "convex") else s for s in pair},
            key=lambda s: order.index(s) if s in order else len(order),
        )
        pairs[rows[id(row)]].add(tuple(shapes))
    head = ["row", "shape pairs", "distance", "witness", "normal", "touching"]
    lines = [_row(head), _row(["---"] * len(head))]
    for name in names:
        row = getattr(module, name)
        covered = sorted(
            pairs[name],
            key=lambda p: [order.index(s) if s in order else len(order) for s in p],
        )
        text = ", ".join("–".join(p) if len(p) > 1 else f"{p[0]}–{p[0]}" for p in covered)
        values = (row.distance, row.witness, row.normal, row.touching)
        lines.append(_row([f"`{name}`", text, *(f"{v:g}" for v in values)]))
    return "\n".join(lines)


def mesh_script_differences() -> str:
    """docs/reports/mesh_script.json (benchmarks/measure_mesh_script.py): the largest
    differences of examples/mesh_robot_queries.py's numbers, reimpl against pydrake."""
    data = _report("mesh_script.json")
    largest = list(data["largest"].items())
    named = [f"{value:.3g} ({kind.replace('-', '–')})" for kind, value in largest[:2]]
    rest = max((value for _, value in largest[2:]), default=0.0)
    return (
        f"{data['lines']} lines; reimpl's numbers differ from pydrake {data['pydrake']}'s "
        f"by at most {', '.join(named)} and ≤ {rest:.2g} elsewhere"
    )


def guidance_table() -> str:
    """What coverage guidance bought a campaign: ``docs/reports/guidance.json``, written by
    ``python benchmarks/bench_guidance.py --examples 100 --seeds 1 --json ...``."""
    report = _json(ROOT / "docs" / "reports" / "guidance.json")
    names = {
        "plain": "plain (`fuzz`)",
        "target": "`hypothesis.target` on new branches",
        "tour": "`sequence_tour`",
        "both": "both (`fuzz --coverage`)",
    }
    lines = [
        "| arm | seed × examples | steps | reimpl branches run | sequence pairs reached |",
        "|---|---:|---:|---:|---:|",
    ]
    for row in report["rows"]:
        lines.append(
            f"| {names[row['arm']]} | {row['seed']} × {row['examples']} | {row['steps']:,} "
            f"| {row['covered_branches']} of {row['branches']} "
            f"| {row['pairs_reached']} of {row['pairs']} |"
        )
    return "\n".join(lines)
