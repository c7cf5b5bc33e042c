"""``python -m conformance cache list|prune|path``: the release environments on disk.

``list`` prints one line per environment (release, Python, size on disk, last
use, and ``incomplete`` for a build that never finished), most recently used
first, then the total (each shared file counted once). ``prune --keep N``
keeps the N most recently used; ``prune --older-than DAYS`` removes those
unused for more than DAYS days; ``--dry-run`` only says what it would remove.
``path`` prints the cache folder (``$DRAKE_FILTER_CONFORMANCE_CACHE``, else
``~/.cache/drake-filter-conformance``).

Exit codes: 0 done; 2 bad arguments (no or both prune options, a negative
count) or an environment another process holds (being built), left in place.
"""

from __future__ import annotations

import argparse
import time
from typing import TextIO

from conformance._backends.env_cache import (
    CachedEnvironment,
    cached_environments,
    disk_usage,
    human_size,
    prune,
)
from conformance._backends.environments import cache_dir
from conformance.cli.exit_codes import EXIT_OK, EXIT_USAGE

__all__ = ["add_cache_parser", "cache_command"]


def _count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be 0 or more, got {text}")
    return value


def _days(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not 0 <= value < float("inf"):  # also refuses nan
        raise argparse.ArgumentTypeError(f"must be 0 or more days, got {text}")
    return value


def add_cache_parser(commands: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    parser = commands.add_parser(
        "cache", help="list or prune the cached Drake release environments, or print the folder"
    )
    actions = parser.add_subparsers(dest="cache_command", required=True)
    actions.add_parser("list", help="each environment: release, Python, size, last use")
    actions.add_parser("path", help="print the cache folder")
    pruning = actions.add_parser("prune", help="remove environments (--keep N or --older-than)")
    rule = pruning.add_mutually_exclusive_group(required=True)
    rule.add_argument(
        "--keep", type=_count, metavar="N", help="keep the N most recently used, remove the rest"
    )
    rule.add_argument(
        "--older-than",
        type=_days,
        metavar="DAYS",
        help="remove those not used for more than DAYS days",
    )
    pruning.add_argument(
        "--dry-run", action="store_true", help="say what would be removed; remove nothing"
    )


def _line(environment: CachedEnvironment, now: float) -> str:
    days = (now - environment.last_used) / 86400
    when = time.strftime("%Y-%m-%d %H:%M", time.localtime(environment.last_used))
    ago = "today" if days < 1 else f"{days:.0f} day{'s' if days >= 1.5 else ''} ago"
    state = "" if environment.complete else "  (incomplete)"
    return (
        f"drake=={environment.release:<8} Python {environment.python:<5} "
        f"{human_size(environment.size):>9}  last used {when} ({ago}){state}"
    )


def _list(out: TextIO) -> int:
    environments = cached_environments()
    now = time.time()
    for environment in environments:
        out.write(_line(environment, now) + "\n")
    total = disk_usage(e.path for e in environments)
    out.write(f"{len(environments)} environment(s), {human_size(total)} on disk in {cache_dir()}\n")
    return EXIT_OK


def _prune(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    result = prune(keep=args.keep, older_than_days=args.older_than, dry_run=args.dry_run)
    now = time.time()
    verb = "would remove" if args.dry_run else "removed"
    for environment in result.removed:
        out.write(f"{verb} {_line(environment, now)}\n")
    freed = sum(e.size for e in result.removed)
    out.write(
        f"{verb} {len(result.removed)} environment(s), {human_size(freed)}; "
        f"kept {len(result.kept) - len(result.busy)}\n"
    )
    for environment in result.busy:
        err.write(f"error: {environment.path} is in use by another process (left in place)\n")
    return EXIT_USAGE if result.busy else EXIT_OK


def cache_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``cache``; returns the exit code."""
    if args.cache_command == "path":
        out.write(f"{cache_dir()}\n")
        return EXIT_OK
    if args.cache_command == "list":
        return _list(out)
    return _prune(args, out, err)
