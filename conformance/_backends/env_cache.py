"""The release environments in the cache: listed with their size and last use, and pruned.

An environment is a folder ``drake-<X.Y.Z>-py<A.B>`` of the cache
(``environments.cache_dir``); it is complete once its ``.complete`` marker
exists. Its last use is the time of its ``.last-used`` stamp (touched by
``ensure_environment`` each time a run uses it), else of its ``.complete``
marker, else of the folder. Its size is the disk its files take (allocated
blocks, each hard-linked file counted once). Files that uv hard-links with
its own cache (and with other environments) are counted in each environment
that holds them, so pruning one frees less than its size when others share
its files.

``prune`` keeps the ``keep`` most recently used environments, or removes
those unused for ``older_than_days``; it skips an environment another
process holds the lock of (being built or checked), and leaves the lock
files (empty) in place, so a process waiting on one never races a new one.
"""

from __future__ import annotations

import fcntl
import os
import re
import shutil
import time
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from conformance._backends.environments import COMPLETE, LAST_USED, cache_dir, read_only_caches

__all__ = [
    "MANY_NEW_ENVIRONMENTS",
    "TYPICAL_ENVIRONMENT_BYTES",
    "CachedEnvironment",
    "PruneResult",
    "cached_environments",
    "disk_note",
    "disk_usage",
    "human_size",
    "missing_releases",
    "new_environment_bytes",
    "prune",
]

#: A matrix that would build more new environments than this says how much disk they take.
MANY_NEW_ENVIRONMENTS = 10

#: The disk one release environment takes when none is cached to measure (bytes): measured
#: with pip, 416 MB (1.48.0) to 515 MB (1.45.0); 386 MB for 1.58.0 on Python 3.12.
TYPICAL_ENVIRONMENT_BYTES = 450 * 10**6

_NAME = re.compile(r"drake-(?P<release>\d+\.\d+\.\d+)-py(?P<python>\d+\.\d+)")


@dataclass(frozen=True)
class CachedEnvironment:
    path: Path
    release: str
    python: str
    complete: bool
    size: int  # bytes on disk
    last_used: float  # seconds since the epoch


@dataclass(frozen=True)
class PruneResult:
    removed: tuple[CachedEnvironment, ...]
    busy: tuple[CachedEnvironment, ...]  # locked by another process: left in place
    kept: tuple[CachedEnvironment, ...]


def disk_usage(paths: Iterable[Path]) -> int:
    """Bytes allocated to the files below ``paths``, each inode counted once (as ``du``)."""
    seen: set[tuple[int, int]] = set()
    total = 0
    for root in paths:
        for folder, dirs, files in os.walk(root):
            for name in (*dirs, *files):
                stat = os.lstat(os.path.join(folder, name))
                if (stat.st_dev, stat.st_ino) not in seen:
                    seen.add((stat.st_dev, stat.st_ino))
                    total += stat.st_blocks * 512
    return total


def _last_used(path: Path) -> float:
    for candidate in (path / LAST_USED, path / COMPLETE, path):
        if candidate.exists():
            return candidate.stat().st_mtime
    return 0.0


def cached_environments(cache: Path | None = None) -> list[CachedEnvironment]:
    """The environments in ``cache`` (default: ``cache_dir()``), most recently used first."""
    root = cache or cache_dir()
    found = []
    for path in root.iterdir() if root.is_dir() else ():
        match = _NAME.fullmatch(path.name)
        if match is None or not path.is_dir() or path.is_symlink():
            continue
        found.append(
            CachedEnvironment(
                path=path,
                release=match["release"],
                python=match["python"],
                complete=(path / COMPLETE).is_file(),
                size=disk_usage([path]),
                last_used=_last_used(path),
            )
        )
    return sorted(found, key=lambda e: (-e.last_used, e.path.name))


def new_environment_bytes(cache: Path | None = None) -> tuple[int, str]:
    """What one more environment will take: (bytes, where the figure comes from)."""
    complete = [e for e in cached_environments(cache) if e.complete]
    if not complete:
        return TYPICAL_ENVIRONMENT_BYTES, "a typical environment"
    sizes = sorted(e.size for e in complete)
    return sizes[len(sizes) // 2], f"the median of the {len(sizes)} cached"


def missing_releases(releases: Iterable[str], cache: Path | None = None) -> list[str]:
    """The ``releases`` no complete environment exists for (in the cache or a read-only one)."""
    roots = [cache or cache_dir(), *read_only_caches()]
    return [
        release
        for release in releases
        if not any(any(root.glob(f"drake-{release}-py*/{COMPLETE}")) for root in roots)
    ]


def disk_note(releases: Iterable[str], cache: Path | None = None) -> str | None:
    """What building the environments ``releases`` lack will take on disk, when they are more
    than ``MANY_NEW_ENVIRONMENTS`` (a matrix says it before it starts); else None."""
    missing = missing_releases(releases, cache)
    if len(missing) <= MANY_NEW_ENVIRONMENTS:
        return None
    each, source = new_environment_bytes(cache)
    return (
        f"{len(missing)} release environments to build in {cache or cache_dir()}: about "
        f"{human_size(each * len(missing))} on disk ({human_size(each)} each, {source}; "
        "less where uv hard-links the files they share); "
        "`python -m conformance cache prune` removes them"
    )


@contextmanager
def _try_lock(path: Path) -> Iterator[bool]:
    """Holds ``<path>.lock`` if no other process does; yields whether it got it."""
    lock = path.with_name(path.name + ".lock")
    with lock.open("a") as handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            yield False
            return
        try:
            yield True
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def prune(
    *,
    keep: int | None = None,
    older_than_days: float | None = None,
    cache: Path | None = None,
    now: float | None = None,
    dry_run: bool = False,
) -> PruneResult:
    """Removes environments: all but the ``keep`` most recently used, or those whose last
    use is more than ``older_than_days`` days before ``now``. Exactly one of the two."""
    if (keep is None) == (older_than_days is None):
        raise ValueError("give exactly one of keep and older_than_days")
    environments = cached_environments(cache)
    if keep is not None:
        doomed = environments[keep:]
    else:
        assert older_than_days is not None
        cutoff = (time.time() if now is None else now) - older_than_days * 86400
        doomed = [e for e in environments if e.last_used < cutoff]
    removed, busy = [], []
    for environment in doomed:
        if dry_run:
            removed.append(environment)
            continue
        with _try_lock(environment.path) as locked:
            if locked:
                shutil.rmtree(environment.path)
                removed.append(environment)
            else:
                busy.append(environment)
    kept = [e for e in environments if e not in removed]
    return PruneResult(tuple(removed), tuple(busy), tuple(kept))


def human_size(size: float) -> str:
    """``size`` bytes in decimal units: ``512 B``, ``3.4 MB``, ``20.1 GB``."""
    for unit in ("B", "kB", "MB", "GB"):
        if size < 1000 or unit == "GB":
            return f"{size:.0f} {unit}" if unit == "B" else f"{size:.1f} {unit}"
        size /= 1000
    raise AssertionError("unreachable")
