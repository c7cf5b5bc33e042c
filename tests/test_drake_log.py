"""Drake's own log lines are kept with the case that caused them: stderr shows them with ``-v``
or in the report of a failing case, never for a run that passes.

Measured before this (``python -m conformance run -q`` on the whole corpus, pydrake 1.51.1):
728 lines on stderr (565 ``WARNING:drake:PackageMap is ignoring ...``, 5 ``ERROR:drake:SDFormat
Error ...``, the rest parser warnings), from both reimpl and pydrake; after it, none.
"""

from __future__ import annotations

import json
import logging
import os
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from conformance._backends.env_cache import missing_releases
from conformance._corpus.loader import default_corpus_root
from conformance._run.drake_log import DRAKE_LOGGER, drake_log_of_case

REPO = Path(__file__).resolve().parents[1]
URDF_GROUPS = default_corpus_root() / "models" / "urdf_groups.json"
FLOATING = (
    "a URDF continuous joint filters its links and a floating joint leaves its child a free body"
)
#: What pydrake 1.51.1 logs for that case's URDF (reimpl logs the same line).
WARNING = (
    "WARNING:drake:<literal-string>.urdf:7: warning: Joint 'l3_l4' specified as type floating "
    "which is not supported by MultibodyPlant.  Leaving 'l4' as a free body."
)


def _run(*args: str, cwd: Path = REPO) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "conformance", "run", *args],
        cwd=cwd,
        env={**os.environ, "PYTHONPATH": str(REPO)},
        capture_output=True,
        text=True,
        check=False,
    )


def test_a_passing_case_that_makes_drake_warn_writes_nothing_to_stderr() -> None:
    done = _run(str(URDF_GROUPS), "--case", FLOATING, "-q")
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""


def test_with_v_the_warnings_are_shown_under_the_case_that_caused_them() -> None:
    done = _run(str(URDF_GROUPS), "--case", FLOATING, "-v")
    assert done.returncode == 0, done.stderr
    lines = done.stderr.splitlines()
    assert lines[0].startswith("[1/1] models/urdf_groups > a URDF continuous joint")
    assert lines[1:] == [f"    {WARNING}", f"    {WARNING}"]  # reimpl's, then pydrake's


def test_a_failing_case_shows_drake_s_log_in_its_report(tmp_path: Path) -> None:
    cases = json.loads(URDF_GROUPS.read_text(encoding="utf-8"))["cases"]
    case = next(c for c in cases if c["description"] == FLOATING)
    case["steps"][-1]["expect"]["candidates"] = []  # a wrong expectation: the case fails
    path = tmp_path / "wrong.json"
    path.write_text(json.dumps({"description": "wrong", "cases": [case]}), encoding="utf-8")
    done = _run(str(path), "-q", cwd=tmp_path)
    assert done.returncode == 1
    assert done.stderr == ""
    report = done.stdout.splitlines()
    start = report.index("  Drake's log during the case:")
    assert report[start + 1 : start + 3] == [f"    {WARNING}", f"    {WARNING}"]


def test_a_thread_that_does_not_capture_logs_as_before(caplog: pytest.LogCaptureFixture) -> None:
    logger = logging.getLogger(DRAKE_LOGGER)
    propagate = logger.propagate
    with drake_log_of_case() as lines:
        logger.warning("mine")
        other = threading.Thread(target=logger.warning, args=("another thread's",))
        other.start()
        other.join()
    assert lines == ["WARNING:drake:mine"]
    assert [r.getMessage() for r in caplog.records] == ["another thread's"]
    assert logger.propagate is propagate
    assert all(type(h).__name__ != "_CaseHandler" for h in logger.handlers)
    logger.warning("after")
    assert [r.getMessage() for r in caplog.records][-1] == "after"


@pytest.mark.skipif(
    bool(missing_releases(["1.30.0"])), reason="no cached environment for Drake 1.30.0"
)
def test_a_worker_crash_its_release_is_known_for_is_shown_only_with_v() -> None:
    """Drake 1.30.0 aborts on an undefined ignored group (release fact
    undefined-ignored-group-aborts): the case passes, its worker's last words are kept."""
    models = default_corpus_root() / "models" / "model_errors.json"
    case = "ignoring an undefined group is an error naming the scoped group"
    args = (str(models), "--case", case, "--backend", "drake==1.30.0", "--backend", "pydrake")
    quiet = _run(*args, "-q")
    assert quiet.returncode == 0, quiet.stderr
    assert quiet.stderr == ""
    verbose = _run(*args, "-v")
    assert verbose.returncode == 0, verbose.stderr
    assert verbose.stderr.splitlines()[1:] == [
        "    backend 'drake==1.30.0' at step 1 (add_models): the worker killed by SIGABRT; "
        "its stderr ends:",
        "terminate called after throwing an instance of 'std::runtime_error'",
        "  what():  error: collision filter group with name 'r::nope' not found",
        "    (a new worker takes over)",
    ]
