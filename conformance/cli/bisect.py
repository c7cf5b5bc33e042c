"""``python -m conformance bisect CASE --good V1 --bad V2``: the release where a case changed.

CASE is a description or a qualified name (``file > description``), or a
glob matching exactly one case. The releases between V1 and V2 come from the
package index; each probe runs the case alone in that release's cached
environment (built on first use). ``--by behaviour`` compares what the
releases answered step by step rather than the outcome.

Exit codes: 0 the change was found (or there is none: V1 and V2 agree);
2 bad arguments, a case name matching no case or several, or a release that
cannot be run.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TextIO

from conformance._backends.calls import BackendError
from conformance._backends.environments import DrakeEnvironmentError
from conformance._backends.releases import (
    ReleaseSpecError,
    check_release,
    drake_releases,
    releases_between,
)
from conformance._corpus.loader import ScenarioError
from conformance._policy.versions import parse_version
from conformance._run.bisect import Bisection, By, Probe, bisect_case, run_probe
from conformance._run.matrix import label
from conformance.cli.exit_codes import EXIT_OK, EXIT_USAGE
from conformance.cli.options import add_python, add_step_timeout
from conformance.cli.run import NoCaseError, corpus_cases

__all__ = ["add_bisect_parser", "bisect_command"]


def add_bisect_parser(commands: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    bisect = commands.add_parser(
        "bisect", help="find the first Drake release in which a case's outcome changed"
    )
    bisect.add_argument(
        "case", metavar="CASE", help="a case's description or qualified name, or a glob of either"
    )
    bisect.add_argument("paths", nargs="*", type=Path, help="scenario files or directories")
    bisect.add_argument("--good", required=True, metavar="V1", help="the older release")
    bisect.add_argument("--bad", required=True, metavar="V2", help="the newer release")
    bisect.add_argument(
        "--by",
        choices=[b.value for b in By],
        default=By.OUTCOME.value,
        help="what must change: the outcome (default), or the behaviour step by step",
    )
    add_step_timeout(bisect, what="is a timeout")
    add_python(bisect)


def _describe(probe: Probe) -> str:
    detail = probe.cell.expected_by or probe.cell.detail
    return label(probe.cell.outcome) + (f" ({detail[:100]})" if detail else "")


def _releases(good: str, bad: str) -> list[str]:
    for option, release in (("--good", good), ("--bad", bad)):
        try:
            check_release(release)
        except ReleaseSpecError as exc:
            raise ReleaseSpecError(f"{option} {exc}") from None
    if parse_version(good) >= parse_version(bad):
        raise ReleaseSpecError(f"--good {good} must be older than --bad {bad}")
    listed = releases_between(good, bad, drake_releases())
    inner = [v for v in listed if v not in (good, bad)]
    return [good, *inner, bad]


def _print(result: Bisection, out: TextIO) -> None:
    tested = len(result.probes)
    out.write(f"\n{result.case}\n")
    if result.first_bad is None:
        first, last = result.releases[0], result.releases[-1]
        out.write(f"no change by {result.by.value}: {first} and {last} agree ({tested} probes)\n")
        return
    out.write(
        f"first release that differs by {result.by.value}: {result.first_bad} "
        f"(last that agrees: {result.last_good}); {tested} of {len(result.releases)} "
        "releases tested\n"
    )
    out.write(f"  {result.last_good}: {_describe(result.probe(result.last_good or ''))}\n")
    out.write(f"  {result.first_bad}: {_describe(result.probe(result.first_bad))}\n")
    for failure in result.differences[:10]:
        before, after = str(failure.expected)[:200], str(failure.actual)[:200]
        out.write(f"  at {failure.step}: {failure.what}: {before} → {after}\n")


def bisect_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``bisect``; returns the exit code."""
    try:
        releases = _releases(args.good, args.bad)
        cases = corpus_cases(args.paths, args.case)
    except (ReleaseSpecError, ScenarioError, NoCaseError) as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    if len(cases) != 1:
        names = "".join(f"\n  {c.qualified_name}" for c in cases[:10])
        err.write(f"error: {args.case!r} names {len(cases)} cases, not one{names}\n")
        return EXIT_USAGE
    (case,) = cases
    err.write(
        f"bisect: {case.qualified_name}\n  {len(releases)} releases {releases[0]}..{releases[-1]}, "
        f"by {args.by}\n"
    )

    def log(line: str) -> None:
        err.write(line + "\n")
        err.flush()

    def probe(version: str) -> Probe:
        return run_probe(
            case, version, python=args.python, step_timeout=args.step_timeout or None, log=log
        )

    def report(answer: Probe, agrees: bool) -> None:
        verdict = "agrees with --good" if agrees else "differs from --good"
        err.write(f"  {answer.version}: {_describe(answer)}: {verdict}\n")
        err.flush()

    try:
        result = bisect_case(case, releases, by=By(args.by), probe=probe, on_probe=report)
    except (DrakeEnvironmentError, BackendError) as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    _print(result, out)
    return EXIT_OK
