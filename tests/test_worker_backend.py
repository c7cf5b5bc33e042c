"""``drake==X``: a Drake release in a worker process, against real pydrake 1.58.0.

These tests build (once; then cached) the Python 3.12 environment holding
Drake 1.58.0, as ``--backend drake==1.58.0`` does.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator

import pytest

from conformance._backends.calls import BackendCrashError, StepTimeoutError, call
from conformance._backends.environments import DrakeEnvironmentError, find_python, pythons_for
from conformance._backends.loader import load_backend
from conformance._backends.subprocess_backend import WorkerBackend
from conformance._corpus.loader import default_corpus_root, load_corpus
from conformance._engine import Outcome
from conformance._run.runner import run_case
from conformance.protocol import Command, ErrorKind

RELEASE = "1.58.0"


def _have_python_312() -> bool:
    try:
        find_python(RELEASE)
    except DrakeEnvironmentError:
        return False
    return True


needs_312 = pytest.mark.skipif(not _have_python_312(), reason="no Python 3.12+ for Drake 1.58")


@pytest.fixture(scope="module")
def worker() -> Iterator[WorkerBackend]:
    backend = load_backend(f"drake=={RELEASE}")
    assert isinstance(backend, WorkerBackend)
    yield backend
    backend.close()


def test_releases_map_to_the_pythons_their_wheels_support() -> None:
    assert pythons_for("1.12.0") == ("3.11",)
    assert pythons_for("1.30.0") == ("3.11", "3.12")
    assert pythons_for("1.51.1") == ("3.11", "3.12")
    assert pythons_for("1.58.0") == ("3.12", "3.13")
    assert pythons_for("1.11.0") == ()


def test_a_python_that_the_release_does_not_support_is_refused() -> None:
    try:
        _, python_311 = find_python("1.12.0")  # Drake 1.12 wheels are for Python 3.11 only
    except DrakeEnvironmentError:
        pytest.skip("no Python 3.11 here")
    with pytest.raises(DrakeEnvironmentError, match=r"drake==1\.58\.0 needs Python 3\.12 or 3\.13"):
        find_python("1.58.0", override=python_311)


@needs_312
def test_the_worker_reports_its_release_and_features(worker: WorkerBackend) -> None:
    assert worker.name == "drake==1.58.0"
    assert worker.version() == "1.58.0"
    assert "activation" in worker.features()
    assert worker.environment.python in {"3.12", "3.13"}


@needs_312
def test_table_1_passes_on_the_worker_against_reimpl(worker: WorkerBackend) -> None:
    table1 = next(f for f in load_corpus() if f.name == "transient/table1")
    for case in table1.cases:
        report = run_case(case, [load_backend("reimpl"), worker], reference=worker.name)
        assert report.status == {"reimpl": Outcome.PASS, "drake==1.58.0": Outcome.PASS}


@needs_312
def test_a_killed_worker_is_a_crash_naming_the_signal_and_a_new_worker_takes_over(
    worker: WorkerBackend,
) -> None:
    worker.reset()  # travels with the next request: a worker that died before it is replaced
    register_g = Command("register_frame", {"name": "g"})
    assert call(worker, "execute", register_g, where="step 0", returns=object).error is None
    assert worker._process is not None
    os.kill(worker._process.pid, signal.SIGKILL)  # mid-case
    with pytest.raises(
        BackendCrashError, match=r"at step 1 \(register_frame\): the worker killed by SIGKILL"
    ):
        call(
            worker,
            "execute",
            Command("register_frame", {"name": "f"}),
            where="step 1 (register_frame)",
            returns=object,
        )
    worker.reset()  # a new worker
    assert (
        call(
            worker,
            "execute",
            Command("register_frame", {"name": "f"}),
            where="step 1",
            returns=object,
        ).error
        is None
    )  # type: ignore[attr-defined]


@needs_312
def test_a_worker_killed_between_cases_is_replaced_at_the_next_reset_without_a_crash(
    worker: WorkerBackend,
) -> None:
    worker.reset()
    register = Command("register_frame", {"name": "f"})
    assert call(worker, "execute", register, where="step 1", returns=object).error is None
    killed = worker.pid
    assert killed is not None
    os.kill(killed, signal.SIGKILL)
    assert worker._process is not None
    assert worker._process.wait(timeout=30) == -signal.SIGKILL  # dead before the next case
    worker.reset()  # the next case
    assert call(worker, "execute", register, where="step 1", returns=object).error is None
    assert worker.pid not in {None, killed}


@needs_312
def test_unguarded_deactivate_of_anchored_geometry_is_1_58s_failed_demand_and_the_worker_lives(
    worker: WorkerBackend,
) -> None:
    """Drake 1.55-1.58 fail a DRAKE_DEMAND on it (known divergence deactivate-anchored-aborts);
    pydrake raises SystemExit, which the worker answers as an error of kind 'assertion'."""
    worker.reset()
    worker.arm_guards(frozenset())  # no guard: let the release fail its demand
    try:
        register = Command(
            "register_geometry", {"name": "A", "frame": "world", "roles": ["proximity"]}
        )
        assert worker.execute(register).error is None
        result = worker.execute(Command("deactivate", {"set": {"frames": ["world"]}}))
    finally:
        worker.arm_guards(frozenset({"deactivate-anchored-aborts"}))
    assert result.error is not None
    assert result.error.kind is ErrorKind.ASSERTION
    assert result.error.message == (
        "Failure at external/drake+/geometry/proximity_engine.cc:# in ApplyActiveStatusChange(): "
        "condition 'iter != dynamic_objects_.end()' failed."
    )
    worker.reset()
    assert worker.execute(register).error is None


@needs_312
def test_run_with_a_worker_backend_exits_zero_with_the_known_divergences_as_xfail() -> None:
    corpus = default_corpus_root()
    process = subprocess.run(
        [sys.executable, "-m", "conformance", "run", str(corpus / "transient"),
         str(corpus / "errors"), "--backend", "reimpl", "--backend", f"drake=={RELEASE}", "-q"],
        capture_output=True, text=True, timeout=600, check=False,
    )  # fmt: skip
    assert process.returncode == 0, process.stdout + process.stderr
    assert "drake==1.58.0 (1.58.0) [reference]" in process.stdout


@needs_312
def test_a_hanging_worker_is_a_timeout_and_a_new_worker_takes_over() -> None:
    """A stopped process (SIGSTOP) really hangs; the worker's own deadline ends the wait."""
    backend = WorkerBackend(RELEASE, step_timeout=1.0)
    try:
        backend.reset()
        assert backend.pid is not None
        os.kill(backend.pid, signal.SIGSTOP)
        with pytest.raises(
            StepTimeoutError, match=r"at step 1 \(register_frame\): no answer within 1 s"
        ):
            call(backend, "execute", Command("register_frame", {"name": "f"}),
                 where="step 1 (register_frame)", returns=object)  # fmt: skip
        assert backend.pid is None  # the hung worker was killed
        backend.reset()  # a new worker
        assert backend.execute(Command("register_frame", {"name": "f"})).error is None
    finally:
        backend.close()


@needs_312
def test_a_hang_mid_case_is_a_recoverable_timeout_and_the_other_backend_finishes() -> None:
    table1 = next(f for f in load_corpus() if f.name == "transient/table1")
    case = table1.cases[0]
    backend = WorkerBackend(RELEASE, step_timeout=1.0)
    original = backend.run_steps

    def stop_then_run(steps):  # type: ignore[no-untyped-def]
        assert backend.pid is not None
        os.kill(backend.pid, signal.SIGSTOP)  # the worker hangs from the first step on
        return original(steps)

    backend.run_steps = stop_then_run  # type: ignore[method-assign]
    try:
        report = run_case(case, [backend, load_backend("reimpl")], step_timeout=1.0)
    finally:
        backend.close()
    assert report.status == {"drake==1.58.0": Outcome.TIMEOUT, "reimpl": Outcome.PASS}
    assert report.recoverable
    assert "no answer within 1 s" in (report.aborted or "")
