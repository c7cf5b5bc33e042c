"""Drake collision-filter conformance: run the corpus, fuzz, compare Drake releases and model files.

``run`` executes the corpus (by default the embedded one) on every chosen
backend (by default reimpl and pydrake) and compares them pair by pair.
``fuzz`` drives two backends (by default reimpl against pydrake) with
Hypothesis-generated command sequences and writes each shrunk divergence as a
scenario file that ``run`` replays. ``models`` parses model files on every
backend and compares what each gives. ``schema`` prints the scenario schema.

Exit codes: 0 every case passed (no divergence); 1 a conformance failure (a
divergence); 2 a usage or input error (bad arguments, a malformed scenario,
an unknown name or backend, a backend that breaks) or an interrupted run
that found nothing. Results found before an error are still printed and
written to the --json/--junit files; findings are written as they are made.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable, Sequence
from importlib import metadata
from pathlib import Path
from typing import Any, TextIO

from conformance._corpus_root import is_installed, package_folder
from conformance._fuzz.campaign import BATCH_EXAMPLES, DEFAULT_STEPS
from conformance._fuzz.regression import DEFAULT_REGRESSIONS
from conformance._grammar.schema import scenario_schema, write_schema
from conformance.cli.bisect import add_bisect_parser, bisect_command
from conformance.cli.cache import add_cache_parser, cache_command
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.fuzz import fuzz_command
from conformance.cli.legacy_diff import add_legacy_diff_parser, legacy_diff_command
from conformance.cli.matrix import add_matrix_parser, matrix_command
from conformance.cli.models import add_models_parser, models_command
from conformance.cli.new_backend import add_new_backend_parser, new_backend_command
from conformance.cli.options import add_backend_options, seconds
from conformance.cli.run import PROG, add_run_parser, run_command
from conformance.protocol_schemas import write_command_schema

__all__ = ["EXIT_FAILURE", "EXIT_OK", "EXIT_USAGE", "main", "main_console"]


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # type: ignore[override]
        self.print_usage(sys.stderr)
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        raise SystemExit(EXIT_USAGE)


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog=PROG, description=__doc__.split("\n\n")[0] if __doc__ else None)
    parser.add_argument("--version", action="version", version=_version())
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    add_run_parser(commands)
    _add_fuzz(commands)
    add_matrix_parser(commands)
    add_bisect_parser(commands)
    add_legacy_diff_parser(commands)
    add_models_parser(commands)
    add_cache_parser(commands)
    add_new_backend_parser(commands)
    schema = commands.add_parser(
        "schema", help="print the scenario schema (its step rules come from the grammar)"
    )
    schema.add_argument(
        "--write",
        action="store_true",
        help="in a clone: write it to scenarios/scenario.schema.json, and the worker "
        "protocol's Command schema (generated from it) to "
        "conformance/protocol_schemas/command.json (an installed package refuses, exit 2)",
    )
    return parser


def _version() -> str:
    """This package's version, and the Drake release installed here (if any)."""
    try:
        mine = metadata.version("drake-filter-conformance")
    except metadata.PackageNotFoundError:
        mine = "unknown (not installed)"
    try:
        drake = f"drake {metadata.version('drake')}"
    except metadata.PackageNotFoundError:
        drake = "no drake installed"
    return f"drake-filter-conformance {mine} ({drake}, Python {sys.version.split()[0]})"


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


def _non_negative(text: str) -> float:
    """A number of seconds, 0 or more (``fuzz --shrink-time``)."""
    return seconds(text, zero="no shrinking")


def _add_fuzz(commands: Any) -> None:
    fuzz = commands.add_parser(
        "fuzz", help="differential fuzzing of two backends; findings become scenario files"
    )
    fuzz.add_argument(
        "--backend",
        default="reimpl",
        help="the backend under test (reimpl; any SPEC run takes, e.g. exec:'CMD ARGS')",
    )
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
        "--models",
        action="store_true",
        help="fuzz random model files (URDF, SDFormat, model directives, with packages, "
        "includes and meshes; parse, reports, Finalize) instead of SceneGraph command sequences",
    )
    fuzz.add_argument(
        "--without",
        metavar="ELEMENT,...",
        default="",
        help="with --models: leave out these model grammar elements (e.g. "
        "packages,sdf:merge-include; see conformance._fuzz.model_scenes.SWITCHES)",
    )
    fuzz.add_argument(
        "--poses",
        action="store_true",
        help="fuzz posed scenes: shapes, poses, near touches and the QueryObject queries "
        "(both backends need the 'queries' feature)",
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
    fuzz.add_argument(
        "--shrink-time",
        type=_non_negative,
        metavar="SEC",
        help="stop shrinking a divergence SEC seconds after it was first seen and keep the "
        "best so far (default: no bound but Hypothesis' own 300 s); the finding is on disk "
        "from its first sighting either way",
    )
    fuzz.add_argument(
        "--coverage",
        action="store_true",
        help="run guided by coverage (new reimpl branches targeted, sequence_tour added: "
        "it draws differently from the same seed without it) and print reimpl's lines and "
        "branches never run, the sequence-pair table and the state-space features reached",
    )
    fuzz.add_argument(
        "--json",
        type=Path,
        metavar="FILE",
        help="write the run's statistics, findings count and coverage as JSON",
    )
    add_backend_options(
        fuzz,
        strict="report known divergences as findings (default: set aside and counted)",
        timeout="breaks the run",
        quiet="no progress lines",
    )
    fuzz.add_argument(
        "-v",
        "--verbose",
        action="store_true",
        help="after the run, what Drake logged during it (WARNING:drake lines, each distinct "
        "line with its count); otherwise they are not shown",
    )


def main(
    argv: Sequence[str] | None = None, out: TextIO | None = None, err: TextIO | None = None
) -> int:
    """Entry point; returns the exit code."""
    args = _parser().parse_args(argv)
    return _COMMANDS[args.command](args, out or sys.stdout, err or sys.stderr)


def _schema(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    if args.write and is_installed():
        err.write(
            "error: schema --write writes the schema files of a clone (scenarios/, "
            f"conformance/protocol_schemas/); this conformance is installed in {package_folder()}"
            ", not a clone: print the schema with `schema` instead\n"
        )
        return EXIT_USAGE
    if args.write:
        out.write(f"wrote {write_schema()}\n")
        out.write(f"wrote {write_command_schema()}\n")
    else:
        out.write(json.dumps(scenario_schema(), indent=2) + "\n")
    return EXIT_OK


#: Subcommand → what runs it: (args, out, err) → exit code.
_COMMANDS: dict[str, Callable[[argparse.Namespace, TextIO, TextIO], int]] = {
    "run": run_command,
    "fuzz": fuzz_command,
    "matrix": matrix_command,
    "bisect": bisect_command,
    "legacy-diff": legacy_diff_command,
    "models": models_command,
    "cache": cache_command,
    "new-backend": new_backend_command,
    "schema": _schema,
}


def main_console() -> None:
    """Console-script entry point (``drake-filter-conformance``)."""
    sys.exit(main())
