"""One divergence's scenario file, on disk from its first sighting to the end of shrinking.

``fuzz`` writes a divergence as soon as it is first seen (raw, unshrunk), so
a run that is killed keeps it. While Hypothesis shrinks, shorter divergences
replace it, and the batch's final one replaces it at the end. Each write
lands whole (``write_regression`` moves a temporary file over the name), and
the new file is written before the old one is removed: from the first
sighting on there is always a file, and at the end exactly one per finding
(a kill between the two steps can leave both, each a valid finding).

N.B. Writing a file costs 0.1-0.3 s for a 50-150 step sequence (most of it
checking the file against the scenario schema), and Hypothesis can find a
shorter sequence every few examples. So while shrinking, a shorter
divergence is written at once only if the last write ended at least
``interval`` seconds ago (and ten times that write's duration, which bounds
the cost to about a tenth of the run); else it waits as ``pending`` until
``flush`` (after every step) or ``settle`` (at the end) writes it. A killed
run therefore loses at most the last ``interval`` seconds or so of shrinking,
never the finding.

``Findings`` keeps a campaign's findings on disk: each batch's divergence
from first sighting (``on_best``) to the batch's end (``on_batch``), when it
is reported and replayed under ``run`` to confirm it (the file holds the
engine's trace as a case: ``Trace.to_case``).

File names are a hash of the steps, so the name changes as the finding
shrinks: ``path`` is the current one, and ``fuzz`` names the first and the
final file on its output.
"""

from __future__ import annotations

import shlex
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol, TextIO

from conformance._corpus.loader import ScenarioError, load_file
from conformance._engine import Divergence
from conformance._fuzz.campaign import BatchResult
from conformance._fuzz.regression import drake_release, write_regression
from conformance._fuzz.stats import FuzzStats
from conformance._run.runner import run_case
from conformance.protocol import Backend, backend_id

__all__ = [
    "FALLBACK_FINDINGS",
    "FindingFile",
    "Findings",
    "Origin",
    "Progress",
    "cross_release",
    "passes_alone",
    "replay",
    "replay_command",
    "replays",
    "write_finding",
]

#: Where findings go when ``--out`` cannot be written after all.
FALLBACK_FINDINGS = Path(tempfile.gettempdir()) / "drake-filter-conformance-findings"


@dataclass
class FindingFile:
    """The file of one batch's divergence, rewritten as it shrinks.

    ``write`` writes a divergence's scenario and returns its path (None if
    it could not be written anywhere).
    """

    write: Callable[[Divergence], Path | None]
    #: Seconds between two writes while shrinking (see the module doc).
    interval: float = 1.0
    #: The file on disk now (None before the first write).
    path: Path | None = None
    #: The length of the trace in ``path``.
    steps: int | None = None
    #: A shorter divergence not written yet.
    pending: Divergence | None = None
    #: ``time.perf_counter()`` before which no write is due.
    _quiet_until: float = field(default=0.0, repr=False)

    def offer(self, divergence: Divergence) -> bool:
        """Takes ``divergence`` if shorter than the shortest so far; True if it was written now.

        The first one is written at once; later ones as the interval allows.
        """
        shortest = len(self.pending.trace) if self.pending is not None else self.steps
        if shortest is not None and len(divergence.trace) >= shortest:
            return False
        self.pending = divergence
        return self.flush()

    def flush(self) -> bool:
        """Writes the pending divergence if a write is due; True if it was written."""
        if self.pending is None:
            return False
        if self.path is not None and time.perf_counter() < self._quiet_until:
            return False
        return self.settle(self.pending) is not None

    def settle(self, divergence: Divergence) -> Path | None:
        """Writes ``divergence`` now, whatever its length (the batch's last word); its path.

        The previous file is removed only once the new one is on disk; if the
        new one cannot be written (None, or an exception), the previous one
        stays. Either way nothing is pending any more: a write that failed is
        not retried before the next ``offer`` or ``settle``.
        """
        self.pending = None
        start = time.perf_counter()
        try:
            path = self.write(divergence)
        finally:
            end = time.perf_counter()
            self._quiet_until = end + max(self.interval, 10 * (end - start))
        if path is None:
            return None
        previous, self.path, self.steps = self.path, path, len(divergence.trace)
        if previous is not None and previous != path:
            previous.unlink(missing_ok=True)
        return path


_FLAKY = "does NOT reproduce: a flaky backend?"


@dataclass(frozen=True)
class Origin:
    """Where a campaign's findings come from and go: what their files and messages name."""

    backend: str
    against: str
    out: Path
    seed: int | None = None
    models: bool = False
    poses: bool = False
    shrink_time: float | None = None
    prog: str = "python -m conformance"


class Progress(Protocol):
    """What ``Findings`` reports through: a line now, progress after each step, a count."""

    found: int

    def say(self, text: str) -> None: ...

    def __call__(self, stats: FuzzStats) -> None: ...


def replays(path: Path, backends: list[Backend]) -> bool:
    """True iff the scenario file fails on ``backends`` (the last is the reference)."""
    return replay(path, backends)[0]


def replay(path: Path, backends: list[Backend]) -> tuple[bool, str | None]:
    """Whether the scenario file fails on ``backends`` (the last is the reference), and why
    a backend sat a case out (it lacks a feature the file's cases need), if one did."""
    scenario = load_file(path, root=path.parent)
    reference = backends[-1].name
    reports = [run_case(case, backends, reference=reference) for case in scenario.cases]
    skipped = next(
        (f"{name} {why}" for report in reports for name, why in report.skip_reasons.items()),
        None,
    )
    return any(not report.passed for report in reports), skipped


def replay_command(prog: str, path: Path, backend: str, against: str) -> str:
    """The ``run`` command that replays ``path`` on the two backends, quoted for a shell
    (an ``exec:'CMD ARGS'`` spec holds spaces)."""
    return shlex.join([*prog.split(), "run", str(path), "--backend", backend, "--backend", against])


def passes_alone(path: Path, backend: Backend) -> bool:
    """True iff ``backend`` alone meets every expectation of the scenario file for its release."""
    scenario = load_file(path, root=path.parent)
    return all(run_case(case, [backend]).passed for case in scenario.cases)


def cross_release(backend: Backend, reference: Backend) -> str | None:
    """The backend's Drake release if both backends are different Drake releases, else None.

    Then a finding records both releases' answers (``since``/``until``), not
    the reference's alone (``conformance._fuzz.regression``).
    """
    mine, theirs = drake_release(backend_id(backend)), drake_release(backend_id(reference))
    return mine if mine is not None and theirs is not None and mine != theirs else None


class Findings:
    """The run's findings on disk: each batch's divergence, from first sighting to report.

    ``on_best`` (``Campaign.on_best``) writes a batch's first divergence at
    once, then shorter ones over the same finding's file (at most about once
    a second, ``FindingFile``; ``on_step`` writes one that waited);
    ``on_batch`` writes the batch's final divergence over it, reports it and
    replays it.
    """

    def __init__(
        self,
        origin: Origin,
        backends: tuple[Backend, Backend],
        out: TextIO,
        progress: Progress,
    ) -> None:
        self.origin = origin
        self.backends = backends
        self.out = out
        self.progress = progress
        self.release = cross_release(*backends)
        self.reference_version = backends[1].version()
        #: The current batch's finding (None: no divergence seen in it yet).
        self.current: FindingFile | None = None
        #: The files reported (or ``--out`` for a finding that could not be written).
        self.written: list[Path] = []

    def write(self, divergence: Divergence) -> Path | None:
        """Writes ``divergence``'s scenario into ``--out`` (or ``FALLBACK_FINDINGS``)."""
        origin = self.origin
        return write_finding(
            lambda folder: write_regression(
                divergence,
                folder,
                backend=origin.backend,
                reference=origin.against,
                reference_version=self.reference_version,
                seed=origin.seed,
                backend_version=self.release,
                models=origin.models,
                poses=origin.poses,
            ),
            origin.out,
            self.out,
        )

    def on_best(self, divergence: Divergence) -> None:
        """Writes a new best divergence over the batch's file; names the file the first time."""
        first = self.current is None
        finding = self.current = self.current or FindingFile(self.write)
        start = time.perf_counter()
        try:
            landed = finding.offer(divergence)
        except ScenarioError as exc:  # the batch's final write says so, and ends the run
            self.progress.say(f"the divergence cannot be written as a scenario yet: {exc}")
            return
        if first and landed:
            took = (time.perf_counter() - start) * 1000
            self.progress.say(
                f"divergence seen: {divergence.what} after step {len(divergence.trace)}; "
                f"written in {took:.0f} ms to {finding.path} (replaced as it shrinks)"
            )

    def on_batch(self, outcome: BatchResult) -> None:
        """Writes the batch's final divergence over its file so far, says so, replays it."""
        divergence = outcome.divergence
        if divergence is None:
            self.current = None
            return
        self.progress.found += 1
        origin, out = self.origin, self.out
        # Kept as current until settled: an interrupt in between reports into the same file.
        finding = self.current = self.current or FindingFile(self.write)
        path = finding.settle(divergence)
        self.current = None
        if path is None:
            out.write(f"DIVERGENCE (batch seed {outcome.seed}), not written: {divergence}\n")
            self.written.append(origin.out)
            return
        self.written.append(path)
        reproduced, skipped = replay(path, list(self.backends))
        verdict = "reproduces" if reproduced else f"not replayed: {skipped}" if skipped else _FLAKY
        stopped = (
            f"  shrinking stopped by --shrink-time {origin.shrink_time or 0:g}s: "
            "the sequence may not be minimal\n"
            if outcome.shrink_stopped
            else ""
        )
        out.write(
            f"DIVERGENCE (batch seed {outcome.seed}): {divergence.what} after step "
            f"{len(divergence.trace)} of the {'partly ' if outcome.shrink_stopped else ''}"
            f"shrunk sequence\n  {divergence.detail}\n"
            f"{stopped}  written: {path}\n"
            f"  replay:  {replay_command(origin.prog, path, origin.backend, origin.against)}"
            f"  ({verdict})\n"
        )
        if self.release is not None:
            alone = [b.name for b in self.backends if not passes_alone(path, b)]
            out.write(
                "  each release alone meets its own (since/until) expectations\n"
                if not alone
                else f"  NOT met alone by {', '.join(alone)}: "
                f"see `{origin.prog} run {path} --backend NAME`\n"
            )

    def on_step(self, stats: FuzzStats) -> None:
        """After every step: a progress line now and then; the pending shorter finding if due."""
        self.progress(stats)
        if self.current is not None and self.current.pending is not None:
            try:
                self.current.flush()
            except ScenarioError as exc:  # the batch's final write says so, and ends the run
                self.progress.say(f"the divergence cannot be written as a scenario yet: {exc}")

    def kept(self, err: TextIO) -> None:
        """Names the divergence written before the run failed, if any (it stays on disk)."""
        if self.current is not None and self.current.path is not None:
            err.write(f"  a divergence seen before that is kept: {self.current.path}\n")


def write_finding(write: Callable[[Path], Path | None], folder: Path, out: TextIO) -> Path | None:
    """``write(folder)``; if that fails, ``write(FALLBACK_FINDINGS)``, saying so."""
    try:
        return write(folder)
    except OSError as exc:
        out.write(f"warning: cannot write into {folder} ({exc}); using {FALLBACK_FINDINGS}\n")
    try:
        return write(FALLBACK_FINDINGS)
    except OSError as exc:
        out.write(f"error: cannot write into {FALLBACK_FINDINGS} either ({exc})\n")
        return None
