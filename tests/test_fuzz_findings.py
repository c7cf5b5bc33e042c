"""Findings are never lost (issue 16): on disk when first seen, replaced as they shrink.

Real pydrake against reimpl mutants (``conformance._testing.mutants``), through
the real command line: in-process for whole runs, in a subprocess for the
signals. At seed 1 both mutants below are first seen within about a second,
then shrink for 25 s or more (measured: ``allow_clears_invariants`` 73 -> 6
steps in 26 s, ``allow_between_clears_within`` 116 -> 18 steps until
Hypothesis' own 300 s limit; the numbers move with the fuzzer's draws), long
enough to kill them mid-shrink; ``--shrink-time`` keeps whole runs short.
"""

from __future__ import annotations

import io
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

from conformance._backends.loader import load_backend
from conformance._corpus.loader import load_file
from conformance._engine import Divergence, Trace
from conformance._fuzz.campaign import Campaign
from conformance._fuzz.findings import FindingFile
from conformance._fuzz.stats import interrupt_requested
from conformance.cli.main import EXIT_FAILURE, EXIT_OK, main
from conformance.compare import Difference
from conformance.protocol import Command, Observation, Result

SLOW = "conformance._testing.mutants:allow_between_clears_within"
QUICK = "conformance._testing.mutants:allow_clears_invariants"
#: The stderr line of a first sighting: "divergence seen: ... written in N ms to PATH (...)".
SEEN = re.compile(r"divergence seen: .* after step (\d+); written in (\d+) ms to (\S+) \(")


def fuzz(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    code = main(["fuzz", "--seed", "1", "--max-examples", "300", *argv], out=out, err=err)
    return code, out.getvalue(), err.getvalue()


def run(path: Path, backend: str) -> int:
    """``python -m conformance run PATH --backend BACKEND --backend pydrake``'s exit code."""
    argv = ["run", str(path), "--backend", backend, "--backend", "pydrake", "-q"]
    return main(argv, out=io.StringIO(), err=io.StringIO())


def start(out_dir: Path, backend: str) -> subprocess.Popen[str]:
    """A real ``python -m conformance fuzz`` process (no shrink bound)."""
    argv = ["fuzz", "--backend", backend, "--seed", "1", "--max-examples", "300"]
    return subprocess.Popen(
        [sys.executable, "-m", "conformance", *argv, "--out", str(out_dir)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )


def stop(process: subprocess.Popen[str]) -> None:
    """Kills the process if it still runs and closes its pipes (no leak into later tests)."""
    process.kill()
    for stream in (process.stdout, process.stderr):
        if stream is not None:
            stream.close()
    process.wait(timeout=30)


def first_sighting(process: subprocess.Popen[str]) -> re.Match[str]:
    """Reads the process's stderr up to its first-sighting line."""
    assert process.stderr is not None
    deadline = time.monotonic() + 60
    for line in process.stderr:
        if (seen := SEEN.search(line)) is not None:
            return seen
        assert time.monotonic() < deadline, "no divergence within 60 s"
    raise AssertionError(f"the process ended without a divergence ({process.wait()})")


def assert_replays(path: Path, mutant: str) -> None:
    load_file(path, root=path.parent)
    assert run(path, mutant) == EXIT_FAILURE
    assert run(path, "reimpl") == EXIT_OK


def test_a_finding_is_on_disk_before_its_shrink_ends_and_survives_sigkill(
    tmp_path: Path,
) -> None:
    process = start(tmp_path, SLOW)
    try:
        seen = first_sighting(process)
        raw = Path(seen[3])
        assert raw.is_file(), "the file is there when the line says so"
        assert int(seen[1]) > 6, "killed before shrinking ended: the raw sequence"
    finally:
        process.kill()
        process.communicate(timeout=30)
    assert process.returncode == -signal.SIGKILL
    files = sorted(tmp_path.glob("*.json"))
    assert files, "a SIGKILL keeps the finding"
    for path in files:  # one, or two if the kill fell between writing and removing
        assert_replays(path, SLOW)


def test_shrink_time_ends_shrinking_with_the_best_so_far_and_says_so(tmp_path: Path) -> None:
    handler = signal.getsignal(signal.SIGTERM)
    code, out, err = fuzz("--backend", SLOW, "--shrink-time", "0", "--out", str(tmp_path))
    assert code == EXIT_FAILURE, out + err
    assert "shrinking stopped by --shrink-time 0s" in out
    (path,) = tmp_path.glob("*.json")
    seen = SEEN.search(err)
    assert seen is not None, err
    assert Path(seen[3]) == path, "stopped at once: the raw sequence is the finding"
    assert f"written: {path}\n" in out
    assert "(reproduces)" in out
    assert signal.getsignal(signal.SIGTERM) is handler, "the SIGTERM handler is restored"


def test_sigterm_mid_shrink_exits_1_with_the_finding_named_on_disk(tmp_path: Path) -> None:
    process = start(tmp_path, SLOW)
    try:
        first_sighting(process)
        time.sleep(1.0)  # mid-shrink: it shrinks for about 30 s
        process.send_signal(signal.SIGTERM)
        out, err = process.communicate(timeout=60)
    finally:
        stop(process)
    assert process.returncode == EXIT_FAILURE, out + err
    (path,) = tmp_path.glob("*.json")
    assert f"interrupted: the smallest divergence so far is written: {path}" in err
    assert f"written: {path}" in out
    assert "interrupted" in out.splitlines()[-1]
    # faulthandler printed where each thread was when the signal came, from C
    assert "Current thread 0x" in err, err
    assert "(most recent call first)" in err, err
    assert "conformance/" in err.split("Current thread 0x", 1)[1], err
    assert_replays(path, SLOW)


def test_the_shrunk_file_replaces_the_raw_one(tmp_path: Path) -> None:
    code, out, err = fuzz("--backend", QUICK, "--shrink-time", "60", "--out", str(tmp_path))
    assert code == EXIT_FAILURE, out + err
    seen = SEEN.search(err)
    assert seen is not None, err
    raw = Path(seen[3])
    (path,) = tmp_path.glob("*.json")
    assert path != raw
    assert not raw.exists()
    assert f"written: {path}\n" in out
    assert len(load_file(path, root=tmp_path).cases[0].steps) < int(seen[1])
    assert not list(tmp_path.glob("*.tmp")), "no temporary file is left behind"


# ------------------------------------------------- FindingFile, without backends


def divergence(steps: int) -> Divergence:
    """A divergence after ``steps`` frames were registered (only its length matters here)."""
    trace = Trace.of(
        "reference",
        "backend",
        [(Command("register_frame", {"name": f"f{i}"}), Result(), Result()) for i in range(steps)],
    )
    states = {"reference": Observation({}), "backend": Observation({})}
    return Divergence("backend", trace, [Difference("candidates", "made", "up")], states=states)


class Folder:
    """Writes a divergence as ``<steps>.txt`` into a folder, as ``write_regression`` would."""

    def __init__(self, root: Path) -> None:
        self.root = root

    def __call__(self, found: Divergence) -> Path:
        path = self.root / f"{len(found.trace)}.txt"
        path.write_text("finding\n")
        return path

    def files(self) -> list[str]:
        return sorted(p.name for p in self.root.iterdir())


def test_the_first_divergence_is_written_at_once_and_shorter_ones_wait_for_the_interval(
    tmp_path: Path,
) -> None:
    folder = Folder(tmp_path)
    finding = FindingFile(folder, interval=3600)
    assert finding.offer(divergence(20))
    assert folder.files() == ["20.txt"]
    assert not finding.offer(divergence(12)), "within the interval: pending"
    assert not finding.offer(divergence(15)), "longer than the pending one: dropped"
    assert not finding.flush()
    assert folder.files() == ["20.txt"]
    finding.settle(divergence(9))
    assert folder.files() == ["9.txt"], "the last word replaces the file"
    assert finding.pending is None


def test_a_pending_divergence_is_written_by_flush_once_the_interval_is_over(
    tmp_path: Path,
) -> None:
    folder = Folder(tmp_path)
    finding = FindingFile(folder, interval=0.05)
    finding.offer(divergence(20))
    finding.offer(divergence(12))
    time.sleep(0.1)
    assert finding.flush()
    assert folder.files() == ["12.txt"]
    assert finding.path == tmp_path / "12.txt"


def test_a_failed_write_keeps_the_previous_file(tmp_path: Path) -> None:
    folder = Folder(tmp_path)
    finding = FindingFile(lambda found: folder(found) if len(found.trace) > 10 else None)
    finding.offer(divergence(20))
    assert finding.settle(divergence(5)) is None
    assert folder.files() == ["20.txt"]
    assert finding.path == tmp_path / "20.txt"


def test_a_pending_interrupt_ends_the_run_when_the_next_example_begins() -> None:
    """A signal's KeyboardInterrupt that Python swallowed (inside a gc callback, which the
    SIGTERM test once hit) is raised again by the next example: the run ends, interrupted."""
    interrupt_requested.set()
    try:
        result = Campaign(
            backend=lambda: load_backend("reimpl"),
            reference=lambda: load_backend("pydrake"),
            seed=1,
            max_examples=300,
        ).run()
    finally:
        interrupt_requested.clear()
    assert result.interrupted
    assert result.stats.examples == 0
    assert result.stats.steps == 0
