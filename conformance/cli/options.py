"""Options and checks that ``run`` and ``fuzz`` share."""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from typing import TextIO

from conformance._backends.calls import DEFAULT_STEP_TIMEOUT

__all__ = ["add_backend_options", "add_python", "add_step_timeout", "refuse", "seconds"]


def seconds(text: str, *, zero: str = "none") -> float:
    """A non-negative number of seconds; ``zero`` says what 0 means in the message."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not value >= 0:  # also refuses nan
        raise argparse.ArgumentTypeError(f"must be 0 ({zero}) or positive, got {text}")
    return value


#: The longest step timeout the interval timer takes (a year); ``inf`` means none.
_LONGEST_STEP_TIMEOUT = 365 * 24 * 3600.0


def _seconds(text: str) -> float:
    """A non-negative number of seconds (0 or ``inf``: no limit)."""
    value = seconds(text)
    if value == math.inf:
        return 0.0
    if value > _LONGEST_STEP_TIMEOUT:
        raise argparse.ArgumentTypeError(
            f"at most {_LONGEST_STEP_TIMEOUT:g} seconds (0 or inf: none), got {text}"
        )
    return value


def add_step_timeout(parser: argparse.ArgumentParser, *, what: str) -> None:
    """``--step-timeout SEC``: how long one backend call may take."""
    parser.add_argument(
        "--step-timeout",
        type=_seconds,
        default=DEFAULT_STEP_TIMEOUT,
        metavar="SEC",
        help=f"a backend call taking longer {what}, exit 2 "
        f"(default {DEFAULT_STEP_TIMEOUT:g}; 0 or inf: none)",
    )


def add_python(parser: argparse.ArgumentParser) -> None:
    """``--python PATH`` (repeatable): the interpreters ``drake==X`` environments are built on."""
    parser.add_argument(
        "--python",
        action="append",
        metavar="PATH",
        help="an interpreter for drake==X environments (repeatable; the first that the "
        "release supports is used; default: found on PATH or in pyenv)",
    )


def add_backend_options(
    parser: argparse.ArgumentParser, *, strict: str, timeout: str, quiet: str
) -> None:
    """What every command that drives backends takes: ``--strict-divergences``,
    ``--step-timeout``, ``--python`` and ``-q``; the texts say what each does there."""
    parser.add_argument("--strict-divergences", action="store_true", help=strict)
    add_step_timeout(parser, what=timeout)
    add_python(parser)
    parser.add_argument("-q", "--quiet", action="store_true", help=quiet)


def refuse(problems: Sequence[str], err: TextIO) -> bool:
    """Writes each problem as an ``error:`` line; True if there were any."""
    for problem in problems:
        err.write(f"error: {problem}\n")
    return bool(problems)
