"""``python -m conformance run``: the corpus on backends, a report, and an exit code.

Progress goes to stderr, one line per case. Failures (with rerun commands),
known divergences met (xfail), skip reasons and the summary table go to
stdout; ``--json`` and ``--junit`` write the same results to files, also when
the run stops early.
"""

from __future__ import annotations

import argparse
import fnmatch
import time
from collections.abc import Callable, Sequence
from functools import partial
from pathlib import Path
from typing import TextIO

from conformance._backends.calls import BackendError
from conformance._backends.loader import BackendLoadError, load_backend
from conformance._corpus.loader import Case, ScenarioError, load_corpus
from conformance._engine import Outcome
from conformance._run.html_report import write_run_html
from conformance._run.outputs import unwritable, write_or_fall_back
from conformance._run.report import RunReport, write_json, write_junit
from conformance._run.runner import choose_reference, run_case
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.options import add_backend_options, refuse
from conformance.protocol import Backend

__all__ = [
    "PROG",
    "NoCaseError",
    "add_run_parser",
    "corpus_cases",
    "load_backends",
    "run_cases",
    "run_command",
    "select_cases",
    "write_outputs",
]

PROG = "python -m conformance"


def add_run_parser(commands: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    run = commands.add_parser("run", help="run scenario cases on backends and compare them")
    run.add_argument("paths", nargs="*", type=Path, help="scenario files or directories")
    run.add_argument(
        "--backend",
        action="append",
        dest="backends",
        metavar="SPEC",
        help="reimpl, reimpl==X.Y.Z (reimpl as that release), pydrake, drake==X.Y.Z, "
        "exec:'CMD ARGS' (a program that speaks docs/protocol.md), or package.module:attribute "
        "(repeatable; default: reimpl and pydrake)",
    )
    run.add_argument(
        "--reference",
        metavar="NAME",
        help="the backend others are judged against (default: pydrake if given, else the first)",
    )
    run.add_argument(
        "--case",
        metavar="NAME",
        help="run only cases whose description or qualified name ('file > description') "
        "is NAME or matches it as a glob",
    )
    run.add_argument("--junit", type=Path, metavar="FILE", help="write a JUnit XML report")
    run.add_argument("--json", type=Path, metavar="FILE", help="write a JSON report")
    run.add_argument(
        "--report",
        type=Path,
        metavar="DIR",
        help="write report.json (as --json) and report.html (the cases where the backends "
        "differ first) to DIR",
    )
    add_backend_options(
        run,
        strict="report known divergences as failures, not xfail",
        timeout="is a timeout",
        quiet="no per-case progress lines",
    )
    run.add_argument(
        "-v",
        "--verbose",
        action="store_true",
        help="under each case, what Drake logged (WARNING:drake lines) and the stderr of a "
        "worker that crashed as its release is known to; otherwise they are shown only in "
        "the report of a case that fails",
    )


def load_backends(
    specs: Sequence[str] | None,
    *,
    python: Sequence[str] | None = None,
    step_timeout: float | None = None,
) -> list[Backend]:
    """The backends of ``specs`` (default reimpl and pydrake); names must differ."""
    specs = list(specs or ("reimpl", "pydrake"))
    backends = [load_backend(s, python=python, step_timeout=step_timeout) for s in specs]
    names = [b.name for b in backends]
    if len(set(names)) != len(names):
        raise BackendLoadError(f"backend names must differ, got {names}")
    return backends


class NoCaseError(ValueError):
    """``--case`` (or bisect's CASE) matches no case of the corpus."""


def corpus_cases(
    paths: Sequence[Path], pattern: str | None, *, errors: list[ScenarioError] | None = None
) -> list[Case]:
    """The cases of the corpus at ``paths`` (default: the embedded one) that ``pattern``
    selects; NoCaseError if none is selected.

    A bad file or case raises ScenarioError, or, with an ``errors`` list, is
    recorded there while the good ones are kept (``load_corpus``).
    """
    cases = select_cases([c for f in load_corpus(paths, errors=errors) for c in f.cases], pattern)
    if not cases and pattern is not None:
        raise NoCaseError(f"no case is described or named {pattern!r}")
    if not cases and not errors:
        raise NoCaseError("the corpus holds no case")
    return cases


def select_cases(cases: Sequence[Case], pattern: str | None) -> list[Case]:
    """The cases whose description or qualified name equals or glob-matches ``pattern``."""
    if pattern is None:
        return list(cases)
    return [
        case
        for case in cases
        if pattern in (case.description, case.qualified_name)
        or fnmatch.fnmatchcase(case.description, pattern)
        or fnmatch.fnmatchcase(case.qualified_name, pattern)
    ]


class _LongCase:
    """Progress inside a case: a line every ``every`` s once the case has run that long."""

    def __init__(self, err: TextIO, name: str, *, every: float = 5.0, quiet: bool = False) -> None:
        self.err, self.name, self.every, self.quiet = err, name, every, quiet
        self.start = self.last = time.perf_counter()

    def __call__(self, done: int, total: int) -> None:
        now = time.perf_counter()
        if not self.quiet and now - self.last >= self.every:
            self.last = now
            self.err.write(f"    {self.name}: step {done}/{total} ({now - self.start:.0f}s)\n")
            self.err.flush()


def _progress(out: TextIO, index: int, total: int, name: str, statuses: dict[str, Outcome]) -> None:
    marks = " ".join(f"{b}:{s.value}" for b, s in statuses.items())
    out.write(f"[{index:>{len(str(total))}}/{total}] {name}  {marks}\n")
    out.flush()


def _output_problems(args: argparse.Namespace) -> list[str]:
    """Why --json/--junit/--report cannot be written, checked before the run."""
    report = getattr(args, "report", None)
    found = [
        f"--{option} {path}: {problem}"
        for option, path in (("json", args.json), ("junit", args.junit))
        if path is not None and (problem := unwritable(path)) is not None
    ]
    if report is not None and (problem := unwritable(report / "report.html")) is not None:
        found.append(f"--report {report}: {problem}")
    return found


def run_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``run``; returns the exit code (see ``conformance.cli.exit_codes``)."""
    if refuse(_output_problems(args), err):
        return EXIT_USAGE
    input_errors: list[ScenarioError] = []
    try:
        backends = load_backends(
            args.backends, python=args.python, step_timeout=args.step_timeout or None
        )
        reference = choose_reference(backends, args.reference).name
        cases = corpus_cases(args.paths, args.case, errors=input_errors)
    except (BackendLoadError, ScenarioError, ValueError) as exc:
        err.writelines(f"error: {e}\n" for e in input_errors)
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    err.writelines(f"error: {e}\n" for e in input_errors)
    if not cases:
        return EXIT_USAGE
    if input_errors:
        err.write(
            f"{len(input_errors)} bad scenario file(s) or case(s) left out; "
            f"running the other {len(cases)} case(s)\n"
        )
    report = RunReport(
        backends,
        specs=list(args.backends or ("reimpl", "pydrake")),
        reference=reference,
        rerun_options=["--strict-divergences"] if args.strict_divergences else [],
        input_errors=[str(exc) for exc in input_errors],
    )
    code = run_cases(args, cases, report, err)
    write_outputs(args, report, out, err)
    if input_errors:
        err.write(f"error: {len(input_errors)} bad scenario file(s) or case(s); see above\n")
        return EXIT_USAGE
    if code == EXIT_OK and report.failed:
        code = EXIT_FAILURE
    ran = sum(1 for c in report.cases for s in c.status.values() if s is not Outcome.SKIP)
    if code == EXIT_OK and ran == 0:
        err.write("error: no case ran on any backend\n")
        code = EXIT_USAGE
    return code


def write_outputs(args: argparse.Namespace, report: RunReport, out: TextIO, err: TextIO) -> None:
    """The failures, xfails, skips and summary on ``out``; ``--junit`` and ``--json`` files,
    and ``--report DIR``'s report.json and report.html (falling back as ``run.outputs``
    says if they cannot be written)."""
    report.print_failures(out, prog=PROG)
    out.write("\n")
    report.print_xfails(out)
    report.print_skips(out)
    report.print_summary(out)
    if args.junit:
        write_or_fall_back(args.junit, lambda path: write_junit(report, path), err)
    if args.json:
        write_or_fall_back(args.json, lambda path: write_json(report, path), err)
    folder = getattr(args, "report", None)
    if folder is not None:

        def page(path: Path) -> None:
            path.parent.mkdir(parents=True, exist_ok=True)
            write_run_html(report, path)

        pages: list[tuple[str, Callable[[Path], None]]] = [
            ("report.json", partial(write_json, report)),
            ("report.html", page),
        ]
        for name, write in pages:
            written = write_or_fall_back(folder / name, write, err)
            if written is not None:
                out.write(f"wrote {written}\n")


def run_cases(
    args: argparse.Namespace,
    cases: Sequence[Case],
    report: RunReport,
    err: TextIO,
    *,
    bad_models_are_input_errors: bool = True,
    keep_going: bool = False,
) -> int:
    """Runs the cases into ``report``; stops at the first broken backend or input error,
    unless ``keep_going``: then every case runs (each from a reset), and a broken one is
    reported with its error and makes the exit code 2.

    ``args`` has ``strict_divergences``, ``step_timeout`` and ``quiet``; see
    ``run_case`` for ``bad_models_are_input_errors``."""
    code = EXIT_OK
    try:
        for index, case in enumerate(cases, 1):
            case_report = run_case(
                case,
                report.backends,
                reference=report.reference,
                strict_divergences=args.strict_divergences,
                step_timeout=args.step_timeout or None,
                on_step=_LongCase(err, case.qualified_name, quiet=args.quiet),
                bad_models_are_input_errors=bad_models_are_input_errors,
            )
            report.cases.append(case_report)
            verbose = getattr(args, "verbose", False)
            if not args.quiet:
                _progress(err, index, len(cases), case.qualified_name, case_report.status)
            if verbose:
                err.writelines(f"    {line}\n" for line in case_report.log)
            if case_report.aborted is not None and case_report.recoverable:
                if verbose or not case_report.passed:  # an expected crash says nothing
                    err.write(f"    {case_report.aborted}\n    (a new worker takes over)\n")
            elif case_report.aborted is not None and keep_going:
                err.write(f"error: {case.qualified_name}: {case_report.aborted}\n")
                code = EXIT_USAGE
            elif case_report.aborted is not None:
                report.aborted = f"{case.qualified_name}: {case_report.aborted}"
                err.write(
                    f"error: {case.file.path}: case {case.description!r}: {case_report.aborted}\n"
                    f"stopped after {index} of {len(cases)} cases; reporting what was found\n"
                )
                return EXIT_USAGE
    except KeyboardInterrupt:
        report.aborted = "interrupted"
        err.write("interrupted: reporting the cases finished so far\n")
        return EXIT_USAGE
    except BackendError as exc:  # broke outside a step's call (the engine records those)
        report.aborted = str(exc)
        err.write(f"error: {exc}\nstopped; reporting the cases finished so far\n")
        return EXIT_USAGE
    return code
