"""``python -m conformance matrix``: the corpus on several Drake releases, and a report.

Each release runs alone in its own cached environment (``drake==X``),
``--jobs`` releases at a time. ``--backend SPEC`` adds an implementation's
column beside them, run alone on each case the same way: ``reimpl==1.58.0``
is reimpl following 1.58.0, to read beside Drake 1.58.0's column.
Progress goes to stderr; the summary table
and the outcome changes between consecutive releases go to stdout; ``--report
DIR`` writes report.json, report.md, report.html and heatmap.png.

Exit codes: 0 no failing cell; 1 a cell is ``fail``, or a ``crash``,
``timeout`` or ``error`` that no known divergence expects; 2 bad arguments
or input, or a release that could not be run at all (the others are still
reported).
"""

from __future__ import annotations

import argparse
import threading
import time
from pathlib import Path
from typing import TextIO

from conformance._backends.env_cache import disk_note
from conformance._backends.releases import ReleaseSpecError, expand
from conformance._corpus.loader import ScenarioError
from conformance._run.matrix import MATRIX_ORDER, Matrix, ReleaseRun, label, run_matrix
from conformance._run.matrix_report import matrix_markdown, write_report
from conformance._run.outputs import unwritable
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.options import add_backend_options, refuse
from conformance.cli.run import NoCaseError, corpus_cases

__all__ = ["add_matrix_parser", "matrix_command"]


def add_matrix_parser(commands: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    matrix = commands.add_parser(
        "matrix", help="run the corpus on several Drake releases, each in its own environment"
    )
    matrix.add_argument("paths", nargs="*", type=Path, help="scenario files or directories")
    matrix.add_argument(
        "--drake",
        nargs="+",
        default=[],
        metavar="SPEC",
        help="releases: 1.30.0, or a range such as 1.40..1.58 (every release on the index in it)",
    )
    matrix.add_argument(
        "--backend",
        action="append",
        default=[],
        metavar="SPEC",
        dest="columns",
        help="add an implementation's column, e.g. reimpl==1.58.0 (repeatable)",
    )
    matrix.add_argument(
        "--report",
        type=Path,
        metavar="DIR",
        help="write report.json, report.md, report.html, heatmap.png",
    )
    matrix.add_argument(
        "--jobs", type=int, default=2, metavar="J", help="releases run at a time (2)"
    )
    matrix.add_argument("--case", metavar="NAME", help="only cases matching NAME (as in run)")
    add_backend_options(
        matrix,
        strict="known divergences are failures, not xfail",
        timeout="is a timeout",
        quiet="no progress lines",
    )


def _name(column: str) -> str:
    """``drake==X`` for a release's column; an implementation's column is its spec."""
    return column if "==" in column or ":" in column else f"drake=={column}"


class _Progress:
    """A line per release every ``every`` s while it runs, and one when it ends."""

    def __init__(self, err: TextIO, *, quiet: bool, every: float = 5.0) -> None:
        self.err, self.quiet, self.every = err, quiet, every
        self.lock = threading.Lock()
        self.last: dict[str, float] = {}
        self.start = time.perf_counter()

    def write(self, line: str) -> None:
        if not self.quiet:
            with self.lock:
                self.err.write(line + "\n")
                self.err.flush()

    def case(self, version: str, done: int, total: int) -> None:
        now = time.perf_counter()
        if now - self.last.setdefault(version, self.start) >= self.every:
            self.last[version] = now
            self.write(f"  {_name(version)}: {done}/{total} cases")

    def release(self, run: ReleaseRun) -> None:
        if run.error:
            self.write(f"  {_name(run.version)}: could not run: {run.error}")
            return
        counts = ", ".join(
            f"{n} {label(o)}"
            for n, o in sorted(((run.count(o), o) for o in MATRIX_ORDER), key=lambda no: -no[0])
            if n
        )
        self.write(f"  {_name(run.version)} (Python {run.python}): {counts} [{run.seconds:.1f} s]")


def _problems(args: argparse.Namespace) -> list[str]:
    problems = []
    if args.jobs < 1:
        problems.append(f"--jobs must be at least 1, got {args.jobs}")
    if not args.drake and not args.columns:
        problems.append("name releases (--drake) or implementations (--backend) to run")
    if args.report is not None and (problem := unwritable(args.report / "report.json")):
        problems.append(f"--report {args.report}: {problem}")
    return problems


def matrix_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``matrix``; returns the exit code."""
    if refuse(_problems(args), err):
        return EXIT_USAGE
    try:
        versions = expand(args.drake)
        cases = corpus_cases(args.paths, args.case)
    except (ReleaseSpecError, ScenarioError, NoCaseError) as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    progress = _Progress(err, quiet=args.quiet)
    if note := disk_note(versions):  # written even with -q
        err.write(f"matrix: {note}\n")
    progress.write(
        f"matrix: {len(cases)} cases on {len(versions)} release(s) and "
        f"{len(args.columns)} implementation(s) ({', '.join([*versions, *args.columns])}), "
        f"{args.jobs} at a time"
    )
    try:
        matrix = run_matrix(
            versions,
            cases,
            extra=args.columns,
            jobs=args.jobs,
            python=args.python,
            step_timeout=args.step_timeout or None,
            strict_divergences=args.strict_divergences,
            on_case=progress.case,
            on_release=progress.release,
            log=progress.write,
        )
    except KeyboardInterrupt:
        err.write("interrupted: no report written\n")
        return EXIT_USAGE
    progress.write(f"matrix: done in {time.perf_counter() - progress.start:.1f} s")
    out.write(matrix_markdown(matrix) + "\n")
    if args.report is not None:
        for path in write_report(matrix, args.report):
            out.write(f"wrote {path}\n")
    return _exit_code(matrix, err)


def _exit_code(matrix: Matrix, err: TextIO) -> int:
    for version in matrix.broken_releases:
        err.write(f"error: {matrix.runs[version].error}\n")
    if matrix.broken_releases:
        return EXIT_USAGE
    failing = matrix.failing
    if failing:
        err.write(f"{len(failing)} failing cell(s); see the tables above\n")
        return EXIT_FAILURE
    return EXIT_OK
