"""Speed of ``python -m conformance models`` across releases: 100 model files on 6 releases.

The files are the first 100 of the vendored real models (Drake's repository,
then its drake_models package, in sorted order), each with the vendored
``drake`` and ``drake_models`` packages, as a team's robot folder would be
given. The releases (default 1.30.0, 1.40.0, 1.45.0, 1.51.1, 1.55.0, 1.58.0)
run ``--jobs`` at a time, each in its own cached environment; a first run
builds the environments and is not timed (``--build`` does only that).
Printed: the wall time (target: under 2 minutes on 2 cores), each release's
seconds, and the changes found from release to release.

Usage: python benchmarks/bench_models.py [--drake V ...] [--files N] [--jobs J] [--build]
                                         [--json FILE]

``--json FILE`` writes the measurement too (the committed one is
``docs/reports/bench_models.json``, which docs/models.md quotes).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

from conformance._corpus.loader import Case, default_corpus_root
from conformance._corpus.model_files import find_model_files
from conformance._run.matrix import run_matrix
from conformance._run.models_report import comparisons
from conformance.cli.models import model_file_cases

RELEASES = ("1.30.0", "1.40.0", "1.45.0", "1.51.1", "1.55.0", "1.58.0")
REAL = default_corpus_root() / "real_models"
PACKAGES = {"drake": str(REAL / "drake"), "drake_models": str(REAL / "drake_models")}


def _cases(count: int) -> list[Case]:
    """The cases of the first ``count`` vendored model files (with their packages)."""
    paths: list[Path] = []
    for folder in ("drake", "drake_models"):
        paths += [REAL / folder / f for f in find_model_files(REAL / folder)]
    chosen = paths[:count]
    return [c for path in chosen for c in model_file_cases([path], packages=PACKAGES)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--drake", nargs="+", default=list(RELEASES), metavar="V")
    parser.add_argument("--files", type=int, default=100)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--build", action="store_true", help="only build the environments")
    parser.add_argument("--json", type=Path, metavar="FILE", help="write the results to this file")
    args = parser.parse_args(argv)
    cases = _cases(args.files)
    if args.build:
        run_matrix(args.drake, cases[:1], jobs=args.jobs, log=print)
        return 0
    start = time.perf_counter()
    matrix = run_matrix(args.drake, cases, jobs=args.jobs)
    seconds = time.perf_counter() - start
    files = len({c.description.removesuffix(" (filter groups)") for c in cases})
    print(
        f"models: {files} files ({len(cases)} cases) x {len(args.drake)} releases, "
        f"--jobs {args.jobs}"
    )
    for version in args.drake:
        run = matrix.runs[version]
        print(
            f"  {version:>8}: {run.seconds:6.1f} s" + (f"  ERROR {run.error}" if run.error else "")
        )
    for comparison in comparisons(matrix, cases, reference=None):
        print(
            f"  {comparison.older} -> {comparison.newer}: {len(comparison.files)} file(s) changed"
        )
    print(f"  wall time {seconds:.1f} s (target < 120 s)")
    if args.json is not None:
        report = {
            "files": files,
            "cases": len(cases),
            "releases": list(args.drake),
            "jobs": args.jobs,
            "cores": os.cpu_count(),
            "seconds": round(seconds, 1),
            "release_seconds": {v: round(matrix.runs[v].seconds, 1) for v in args.drake},
            "changed_files": {
                f"{c.older} -> {c.newer}": len(c.files)
                for c in comparisons(matrix, cases, reference=None)
            },
        }
        args.json.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    return 1 if matrix.broken_releases else 0


if __name__ == "__main__":
    sys.exit(main())
