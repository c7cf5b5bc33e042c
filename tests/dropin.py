"""Running a pydrake script as written and with its imports switched to reimpl."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

__all__ = ["ROOT", "as_reimpl", "run_script"]

ROOT = Path(__file__).resolve().parents[1]


def as_reimpl(script: str) -> str:
    """The textual switch a user makes: ``pydrake.`` becomes ``reimpl.`` in the imports."""
    return "".join(
        line.replace("pydrake.", "reimpl.", 1)
        if line.startswith(("from pydrake.", "import pydrake."))
        else line
        for line in script.splitlines(keepends=True)
    )


def run_script(script: str) -> str:
    """The script's stdout, run in a fresh interpreter from the repository; it must exit 0
    without a traceback."""
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)
    completed = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=dict(os.environ, PYTHONPATH=path),
        timeout=120,
        check=False,
    )
    assert completed.returncode == 0, completed.stderr
    assert "Traceback" not in completed.stderr, completed.stderr
    return completed.stdout
