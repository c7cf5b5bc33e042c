"""``python -m conformance``: the command line.

``run`` executes the corpus (by default the embedded one) on every chosen
backend (by default reimpl and pydrake) and compares them pair by pair.
``fuzz`` drives two backends (by default reimpl against pydrake) with
Hypothesis-generated command sequences and writes each shrunk divergence as a
scenario file that ``run`` replays.

Exit codes: 0 every case passed (no divergence); 1 a conformance failure (a
divergence); 2 a usage or input error (bad arguments, a malformed scenario,
an unknown name or backend, a backend that breaks) or an interrupted run
that found nothing. Results found before an error are still printed and
written to the --json/--junit files; findings are written as they are made.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, TextIO

from conformance.backends.loader import BackendLoadError, load_backend
from conformance.backends.scene_graph import UnknownNameError
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.fuzz import fuzz_command
from conformance.corpus.loader import ScenarioError, ScenarioFile, load_corpus
from conformance.fuzz.campaign import BATCH_EXAMPLES, DEFAULT_STEPS
from conformance.fuzz.regression import DEFAULT_REGRESSIONS
from conformance.protocol import Backend
from conformance.run.report import RunReport, write_json, write_junit
from conformance.run.runner import BackendError, Status, run_case

__all__ = ["EXIT_FAILURE", "EXIT_OK", "EXIT_USAGE", "main", "main_console"]

PROG = "python -m conformance"


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # type: ignore[override]
        self.print_usage(sys.stderr)
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        raise SystemExit(EXIT_USAGE)


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog=PROG, description=__doc__.split("\n\n")[0] if __doc__ else None)
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    run = commands.add_parser("run", help="run scenario cases on backends and compare them")
    run.add_argument("paths", nargs="*", type=Path, help="scenario files or directories")
    run.add_argument(
        "--backend",
        action="append",
        dest="backends",
        metavar="NAME",
        help="reimpl, pydrake, or package.module:attribute (repeatable; default: both built-ins)",
    )
    run.add_argument("--case", help="run only the case with this exact description")
    run.add_argument("--junit", type=Path, metavar="FILE", help="write a JUnit XML report")
    run.add_argument("--json", type=Path, metavar="FILE", help="write a JSON report")
    run.add_argument("-q", "--quiet", action="store_true", help="no per-case progress lines")
    _add_fuzz(commands)
    return parser


def _positive(kind: type[int] | type[float]) -> Callable[[str], float]:
    def parse(text: str) -> float:
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
        if value <= 0:
            raise argparse.ArgumentTypeError(f"must be positive, got {text}")
        return value

    return parse


def _add_fuzz(commands: Any) -> None:
    fuzz = commands.add_parser(
        "fuzz", help="differential fuzzing of two backends; findings become scenario files"
    )
    fuzz.add_argument("--backend", default="reimpl", help="the backend under test (reimpl)")
    fuzz.add_argument("--against", default="pydrake", help="the reference backend (pydrake)")
    fuzz.add_argument("--seed", type=int, default=0, help="the same seed gives the same run (0)")
    budget = fuzz.add_mutually_exclusive_group()
    budget.add_argument(
        "--max-examples", type=_positive(int), metavar="N", help="one batch of N examples (100)"
    )
    budget.add_argument(
        "--time-budget",
        type=_positive(float),
        metavar="SEC",
        help=f"batches of {BATCH_EXAMPLES} examples until SEC seconds have passed",
    )
    fuzz.add_argument(
        "--steps", type=_positive(int), default=DEFAULT_STEPS, help="commands per example"
    )
    fuzz.add_argument(
        "--out",
        type=Path,
        default=DEFAULT_REGRESSIONS,
        metavar="DIR",
        help=f"where findings are written ({DEFAULT_REGRESSIONS}/)",
    )
    fuzz.add_argument(
        "--database", type=Path, metavar="DIR", help="a Hypothesis example database to share"
    )
    fuzz.add_argument(
        "--keep-going", action="store_true", help="with --time-budget, go on after a finding"
    )
    fuzz.add_argument("-q", "--quiet", action="store_true", help="no progress lines")


def _backends(specs: Sequence[str] | None) -> list[Backend]:
    specs = list(specs or ("reimpl", "pydrake"))
    backends = [load_backend(spec) for spec in specs]
    names = [b.name for b in backends]
    if len(set(names)) != len(names):
        raise BackendLoadError(f"backend names must differ, got {names}")
    return backends


def _progress(out: TextIO, index: int, total: int, name: str, statuses: dict[str, Status]) -> None:
    marks = " ".join(f"{b}:{s.value}" for b, s in statuses.items())
    out.write(f"[{index:>{len(str(total))}}/{total}] {name}  {marks}\n")
    out.flush()


def _run(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    try:
        backends = _backends(args.backends)
        files: list[ScenarioFile] = load_corpus(args.paths)
    except (BackendLoadError, ScenarioError) as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    cases = [c for f in files for c in f.cases]
    if args.case is not None:
        cases = [c for c in cases if c.description == args.case]
        if not cases:
            err.write(f"error: no case is described {args.case!r}\n")
            return EXIT_USAGE
    report = RunReport(backends)
    code = EXIT_OK
    try:
        for index, case in enumerate(cases, 1):
            try:
                case_report = run_case(case, backends)
            except (BackendError, UnknownNameError) as exc:
                report.aborted = f"{case.qualified_name}: {exc}"
                err.write(f"error: {case.file.path}: case {case.description!r}: {exc}\n")
                code = EXIT_USAGE
                break
            report.cases.append(case_report)
            if not args.quiet:
                _progress(err, index, len(cases), case.qualified_name, case_report.status)
    except KeyboardInterrupt:
        report.aborted = "interrupted"
        err.write("interrupted: reporting the cases finished so far\n")
        code = EXIT_USAGE
    report.print_failures(out, prog=PROG)
    out.write("\n")
    report.print_summary(out)
    if args.junit:
        write_junit(report, args.junit)
    if args.json:
        write_json(report, args.json)
    if code == EXIT_OK and report.failed:
        code = EXIT_FAILURE
    ran = sum(1 for c in report.cases for s in c.status.values() if s is not Status.SKIP)
    if code == EXIT_OK and ran == 0:
        err.write("error: no case ran on any backend\n")
        code = EXIT_USAGE
    return code


def main(
    argv: Sequence[str] | None = None, out: TextIO | None = None, err: TextIO | None = None
) -> int:
    """Entry point; returns the exit code."""
    args = _parser().parse_args(argv)
    out, err = out or sys.stdout, err or sys.stderr
    if args.command == "run":
        return _run(args, out, err)
    if args.command == "fuzz":
        return fuzz_command(args, out, err)
    raise AssertionError(args.command)  # pragma: no cover


def main_console() -> None:
    """Console-script entry point (``drake-filter-conformance``)."""
    sys.exit(main())
