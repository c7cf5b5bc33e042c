"""Processes that want the same Drake environment at once wait for one build."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from conformance._backends.environments import _locked

PROBE = """
import fcntl, sys
with open(sys.argv[1], "w") as handle:
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        print("held")
    else:
        print("free")
"""


def probe(lock: Path) -> str:
    done = subprocess.run(
        [sys.executable, "-c", PROBE, str(lock)], capture_output=True, text=True, check=True
    )
    return done.stdout.strip()


def test_an_environment_is_locked_against_other_processes_while_it_is_built(
    tmp_path: Path,
) -> None:
    environment = tmp_path / "drake-1.58.0-py3.12"
    lock = tmp_path / "drake-1.58.0-py3.12.lock"
    with _locked(environment):
        assert probe(lock) == "held"
    assert probe(lock) == "free"
