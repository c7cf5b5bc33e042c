"""``python -m conformance legacy-diff MODEL.urdf``: RigidBodyTree-era filtering against today's.

Exit codes: 0 the comparison ran (the differing pairs are its output, not a
failure); 2 an input error: a missing or malformed file, a legacy group
naming an unknown link, a model the modern backend refuses, an unknown backend.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import TextIO

from conformance._backends.calls import BackendError
from conformance._backends.loader import BackendLoadError, load_backend
from conformance._legacy_diff import LegacyDiffError, legacy_diff
from conformance.cli.exit_codes import EXIT_OK, EXIT_USAGE

__all__ = ["add_legacy_diff_parser", "legacy_diff_command"]


def add_legacy_diff_parser(commands: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    parser = commands.add_parser(
        "legacy-diff",
        help="one URDF under RigidBodyTree's filtering (unprefixed groups, auto cliques) "
        "and under modern Drake's, pair by pair, each difference with its rule",
    )
    parser.add_argument("model", type=Path, metavar="MODEL.urdf", help="the URDF file")
    parser.add_argument(
        "--backend",
        default="pydrake",
        metavar="SPEC",
        help="the modern side: pydrake (default), reimpl, drake==X.Y.Z, exec:'CMD ARGS' "
        "or package.module:attribute",
    )
    parser.add_argument("--json", action="store_true", help="print JSON instead of text")
    parser.add_argument(
        "--all",
        action="store_true",
        help="also list every pair side by side, not only differing ones",
    )


def legacy_diff_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    try:
        backend = load_backend(args.backend)
        diff = legacy_diff(args.model, backend)
    except (BackendLoadError, BackendError, LegacyDiffError) as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    if args.json:
        out.write(json.dumps(diff.to_json(), indent=2) + "\n")
    else:
        out.write(diff.to_text(all_pairs=args.all))
    return EXIT_OK
