"""Running a pydrake script as written and with its imports switched to reimpl."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path
from types import ModuleType

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


def run_python(script: str, *args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    """``python -c script args...`` in a fresh interpreter that imports this checkout."""
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)
    return subprocess.run(
        [sys.executable, "-c", script, *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=dict(os.environ, PYTHONPATH=path),
        timeout=120,
        check=False,
    )


def run_script(script: str) -> str:
    """The script's stdout, run in a fresh interpreter from the repository; it must exit 0
    without a traceback."""
    completed = run_python(script)
    assert completed.returncode == 0, completed.stderr
    assert "Traceback" not in completed.stderr, completed.stderr
    return completed.stdout


def benchmark_module(name: str) -> ModuleType:
    """``benchmarks/NAME.py`` imported as module ``NAME`` (its folder on sys.path, so that a
    benchmark may import another beside it)."""
    folder = str(ROOT / "benchmarks")
    if folder not in sys.path:
        sys.path.insert(0, folder)
    spec = importlib.util.spec_from_file_location(name, ROOT / "benchmarks" / f"{name}.py")
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module
