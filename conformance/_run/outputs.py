"""Output files (reports, findings): checked before a run, never lost after it.

``unwritable(path)`` says, before any work is done, why a file could not be
written (None if it can). ``write_or_fall_back`` writes a file; if that fails
after all (a disk filled up, a folder vanished) it writes the same content to
a fallback path in the temporary directory and says so, so that a long run's
results are kept.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import TextIO

__all__ = ["fallback_path", "unwritable", "unwritable_dir", "write_or_fall_back"]


def _nearest_existing(path: Path) -> Path:
    for candidate in (path, *path.parents):
        if candidate.exists():
            return candidate
    return Path.cwd()


def unwritable_dir(path: Path) -> str | None:
    """Why files cannot be created in folder ``path`` (made if missing), or None."""
    existing = _nearest_existing(path)
    if existing == path and not path.is_dir():
        return f"{path} is not a folder"
    if not existing.is_dir():
        return f"{existing} is not a folder"
    if not os.access(existing, os.W_OK | os.X_OK):
        return f"{existing} is not writable"
    return None


def unwritable(path: Path) -> str | None:
    """Why file ``path`` cannot be written (its folder is made if missing), or None."""
    if path.is_dir():
        return f"{path} is a folder"
    if path.exists():
        return None if os.access(path, os.W_OK) else f"{path} is not writable"
    return unwritable_dir(path.parent)


def fallback_path(path: Path) -> Path:
    """Where ``path``'s content goes if ``path`` cannot be written."""
    return Path(tempfile.gettempdir()) / f"drake-filter-conformance-{path.name}"


def write_or_fall_back(path: Path, write: Callable[[Path], None], err: TextIO) -> Path | None:
    """``write(path)``; on OSError ``write(fallback_path(path))``. Returns where it went."""
    try:
        write(path)
        return path
    except OSError as exc:
        fallback = fallback_path(path)
        try:
            write(fallback)
        except OSError as again:
            err.write(f"error: cannot write {path} ({exc}) nor {fallback} ({again})\n")
            return None
        err.write(f"warning: cannot write {path} ({exc}); wrote {fallback} instead\n")
        return fallback
