"""``python -m conformance fuzz``: a campaign with progress lines and findings on disk.

Progress goes to stderr about once a second: elapsed time, examples and steps
(with rates), and findings. Each divergence is written as soon as its batch
ends (or on Ctrl-C, the smallest one seen so far). The file is then replayed
with the scenario runner to confirm that ``run`` reproduces it.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import TextIO

from conformance.backends.loader import BackendLoadError, load_backend
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.run import PROG
from conformance.corpus.loader import ScenarioError, load_file
from conformance.fuzz.campaign import BatchResult, Campaign, CampaignResult
from conformance.fuzz.lockstep import FuzzStats, HarnessError
from conformance.fuzz.regression import write_regression
from conformance.protocol import Backend
from conformance.run.runner import run_case

__all__ = ["Progress", "fuzz_command", "replays"]


class Progress:
    """Writes a progress line to ``err`` at most once per ``interval`` seconds."""

    def __init__(self, err: TextIO, *, interval: float = 1.0, quiet: bool = False) -> None:
        self.err = err
        self.interval = interval
        self.quiet = quiet
        self.start = time.perf_counter()
        self.last = self.start
        self.found = 0

    def line(self, stats: FuzzStats) -> str:
        elapsed = max(time.perf_counter() - self.start, 1e-9)
        shrinking = " (shrinking)" if stats.divergences_seen and stats.best is not None else ""
        return (
            f"[fuzz {elapsed:6.1f}s] examples {stats.examples} ({stats.examples / elapsed:.1f}/s)"
            f"  steps {stats.steps} ({stats.steps / elapsed:.0f}/s)"
            f"  divergences {self.found}{shrinking}"
        )

    def __call__(self, stats: FuzzStats) -> None:
        now = time.perf_counter()
        if not self.quiet and now - self.last >= self.interval:
            self.last = now
            self.err.write(self.line(stats) + "\n")
            self.err.flush()


def replays(path: Path, backends: list[Backend]) -> bool:
    """True iff the scenario file fails on ``backends`` (the last is the reference)."""
    scenario = load_file(path, root=path.parent)
    reference = backends[-1].name
    return any(not run_case(case, backends, reference=reference).passed for case in scenario.cases)


def _report(
    outcome: BatchResult,
    args: argparse.Namespace,
    backends: tuple[Backend, Backend],
    out: TextIO,
    written: list[Path],
) -> None:
    divergence = outcome.divergence
    if divergence is None:
        return
    backend, reference = backends
    path = write_regression(
        divergence,
        args.out,
        backend=args.backend,
        reference=args.against,
        reference_version=reference.version(),
        seed=args.seed,
    )
    written.append(path)
    reproduced = replays(path, [backend, reference])
    out.write(
        f"DIVERGENCE (batch seed {outcome.seed}): {divergence.what} after step "
        f"{len(divergence.trace)} of the shrunk sequence\n  {divergence.detail}\n"
        f"  written: {path}\n"
        f"  replay:  {PROG} run {path} --backend {args.backend} --backend {args.against}"
        f"  ({'reproduces' if reproduced else 'does NOT reproduce: a flaky backend?'})\n"
    )


def _summary(result: CampaignResult, out: TextIO, progress: Progress) -> None:
    stats = result.stats
    seconds = max(result.seconds, 1e-9)
    share = stats.backend_seconds / seconds
    out.write(
        f"fuzz: {len(result.batches)} batch(es), {stats.examples} examples, {stats.steps} steps "
        f"in {result.seconds:.1f}s ({stats.examples / seconds:.1f} examples/s, "
        f"{stats.steps / seconds:.0f} steps/s; {share:.0%} of the time in backend calls); "
        f"{progress.found} divergence(s)"
        f"{'; interrupted' if result.interrupted else ''}\n"
    )
    for divergence, examples in sorted(stats.known.items()):
        out.write(f"fuzz: known divergence {divergence} met in {examples} example(s), set aside\n")


def fuzz_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``fuzz``; returns the exit code (see ``conformance.cli.exit_codes``)."""
    try:
        backend, reference = load_backend(args.backend), load_backend(args.against)
    except BackendLoadError as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    if backend.name == reference.name:
        err.write(f"error: --backend and --against are both named {backend.name!r}\n")
        return EXIT_USAGE
    progress = Progress(err, quiet=args.quiet)
    written: list[Path] = []

    def on_batch(outcome: BatchResult) -> None:
        if outcome.divergence is not None:
            progress.found += 1
            _report(outcome, args, (backend, reference), out, written)

    max_examples = args.max_examples
    if max_examples is None and args.time_budget is None:
        max_examples = 100
    campaign = Campaign(
        backend=lambda: backend,
        reference=lambda: reference,
        seed=args.seed,
        max_examples=max_examples,
        time_budget=args.time_budget,
        steps=args.steps,
        database=args.database,
        on_step=progress,
        on_batch=on_batch,
        stop_at_first=not args.keep_going,
        strict_divergences=args.strict_divergences,
    )
    err.write(
        f"fuzz: {backend.name} {backend.version()} against {reference.name} "
        f"{reference.version()}, seed {args.seed}, "
        + (f"{max_examples} examples" if max_examples else f"time budget {args.time_budget}s")
        + f", {args.steps} steps each\n"
    )
    try:
        result = campaign.run()
    except HarnessError as exc:
        err.write(f"error: a backend broke (not a divergence): {exc}\n")
        return EXIT_USAGE
    except ScenarioError as exc:
        err.write(f"error: could not write the finding as a scenario: {exc}\n")
        return EXIT_USAGE
    _summary(result, out, progress)
    return _exit_code(result, written, err)


def _exit_code(result: CampaignResult, written: list[Path], err: TextIO) -> int:
    if written:
        return EXIT_FAILURE
    if result.interrupted:
        err.write("interrupted: no divergence found before the interrupt\n")
        return EXIT_USAGE
    return EXIT_OK
