"""Release-matrix speed: the whole matrix's wall time, and a worker's per-step overhead.

Two measurements, both with the environments already cached (a first
``python -m conformance matrix`` builds them):

1. **Matrix wall time**: ``run_matrix`` over the corpus on the releases given
   (default the six of the committed report), ``--jobs`` at a time. Target:
   under 2 minutes on a 2-core machine.
2. **Per-step overhead of a worker**: the corpus on the same Drake release
   twice, in this process (``pydrake``) and in a worker (``drake==X`` with X the
   installed release), each backend alone, ``--repeat`` times after a warm-up
   pass; the median time per step of each and their ratio. Cases that crash
   the worker (it is not guarded) are left out: a crash costs a new worker.
   Target: below 2x. The worker sends a whole case in one request
   (``run_steps``) and reads the answers as they come, so its cost over
   in-process is one round trip per case plus the JSON of each answer.

Usage: python benchmarks/bench_matrix.py [--drake V ...] [--jobs J] [--repeat R]
                                         [--skip-matrix] [--skip-overhead] [--json FILE]

``--json FILE`` writes both measurements too (the committed one is
``docs/reports/bench_matrix.json``, which docs/releases.md quotes).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from importlib import metadata
from pathlib import Path
from typing import Any

from conformance._backends.loader import load_backend
from conformance._corpus.loader import Case, load_corpus
from conformance._run.matrix import run_matrix
from conformance._run.runner import run_case
from conformance.protocol import Backend

REPORT_RELEASES = ("1.12.0", "1.20.0", "1.30.0", "1.40.0", "1.51.1", "1.58.0")


def _cases() -> list[Case]:
    return [case for file in load_corpus() for case in file.cases]


def _corpus_seconds(backend: Backend, cases: list[Case]) -> float:
    start = time.perf_counter()
    for case in cases:
        run_case(case, [backend])
    return time.perf_counter() - start


def matrix_wall_time(releases: list[str], jobs: int) -> dict[str, Any]:
    cases = _cases()
    start = time.perf_counter()
    matrix = run_matrix(releases, cases, jobs=jobs)
    seconds = time.perf_counter() - start
    broken = matrix.broken_releases
    print(f"matrix: {len(cases)} cases x {len(releases)} releases, --jobs {jobs}")
    for version in releases:
        run = matrix.runs[version]
        print(
            f"  {version:>8}: {run.seconds:6.1f} s" + (f"  ERROR {run.error}" if run.error else "")
        )
    print(f"  wall time {seconds:.1f} s (target < 120 s){'  [releases broken]' if broken else ''}")
    return {
        "cases": len(cases),
        "releases": releases,
        "jobs": jobs,
        "seconds": seconds,
        "broken": bool(broken),
    }


def per_step_overhead(repeat: int) -> dict[str, Any]:
    release = metadata.version("drake")
    cases = _cases()
    in_process = load_backend("pydrake")
    worker = load_backend(f"drake=={release}")
    try:
        # A warm-up pass; cases that crash the (unguarded) worker are left out, as a
        # crash costs a new worker (pydrake's import), which is not a per-step cost.
        crashing = [c for c in cases if run_case(c, [worker]).broken]
        cases = [c for c in cases if c not in crashing]
        steps = sum(len(case.steps) for case in cases)
        _corpus_seconds(in_process, cases)
        local = [_corpus_seconds(in_process, cases) for _ in range(repeat)]
        remote = [_corpus_seconds(worker, cases) for _ in range(repeat)]
    finally:
        getattr(worker, "close", lambda: None)()
    a, b = statistics.median(local), statistics.median(remote)
    print(
        f"per-step cost, Drake {release}, {len(cases)} cases ({len(crashing)} that crash the "
        f"worker left out), {steps} steps, median of {repeat}:"
    )
    print(f"  pydrake in-process      {a / steps * 1e6:8.1f} us/step  ({a:.2f} s)")
    print(f"  drake=={release} worker  {b / steps * 1e6:8.1f} us/step  ({b:.2f} s)")
    print(f"  ratio worker / in-process: {b / a:.2f}x (target < 2x)")
    return {
        "release": release,
        "cases": len(cases),
        "crashing": len(crashing),
        "steps": steps,
        "repeat": repeat,
        "in_process_us_per_step": a / steps * 1e6,
        "worker_us_per_step": b / steps * 1e6,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--drake", nargs="+", default=list(REPORT_RELEASES), metavar="V")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--skip-matrix", action="store_true")
    parser.add_argument("--skip-overhead", action="store_true")
    parser.add_argument("--json", type=Path, metavar="FILE", help="write the results to this file")
    args = parser.parse_args(argv)
    report: dict[str, Any] = {}
    if not args.skip_overhead:
        report["overhead"] = per_step_overhead(args.repeat)
    if not args.skip_matrix:
        report["matrix"] = matrix_wall_time(args.drake, args.jobs)
    if args.json is not None:
        args.json.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
