"""``python -m conformance fuzz``: a campaign with progress lines and findings on disk.

Progress goes to stderr about once a second: elapsed time, examples and steps
(with rates), and findings. Each divergence is written as soon as it is first
seen, raw and unshrunk (a line on stderr names the file), then replaced by
every smaller one while Hypothesis shrinks it, and by the final one when its
batch ends (``conformance._fuzz.findings``): a run that is killed leaves the
best finding so far on disk. ``--shrink-time SEC`` ends shrinking SEC seconds
after the first sighting, with the best so far. Ctrl-C and SIGTERM end the run
with the best so far written. The final file is replayed under ``run`` to
confirm it (``conformance._fuzz.findings``).

``--models`` runs a ``ModelCampaign`` (``conformance._fuzz.model_campaign``):
each example is a random model case run by the corpus runner, not a lockstep
command sequence; everything else (seeds, budgets, findings, exit codes) is
the same. ``--without ELEMENT,...`` leaves grammar elements out of its draws
(``conformance._fuzz.model_scenes.SWITCHES``, and ``rename-then-parse``), and
its ``--coverage`` table counts the model grammar features the drawn files
and the reference's answers reached (``conformance._fuzz.model_coverage``).

``--poses`` runs the lockstep machine on posed scenes
(``PosedLockstepMachine``): random shapes and poses, near-touching offsets,
set_poses and every QueryObject query, besides all the filter operations;
both backends need the ``queries`` feature. It is a flag, not the default,
so that ``fuzz --seed S`` draws what it always drew: the findings already
written name their command (``fuzz --seed S``), and a backend without the
queries (an older Drake release in a worker, a mutant) still fuzzes the
filters. A finding's file name starts with ``poses-``.

``--coverage`` runs the campaign guided and prints what it reached:
reimpl's lines and branches never run, by function
(``conformance._fuzz.branch_coverage``; each lockstep example feeds its new
branches to ``hypothesis.target``, a model case does not, so that ``--models
--coverage`` draws what ``--models`` draws), the pairs of consecutive located events
(``conformance._fuzz.sequence_coverage``; the lockstep machines also get
``sequence_tour``, ``conformance._fuzz.sequence_tour``), then the feature
table. A guided campaign draws differently from the same seed without it.
"""

from __future__ import annotations

import argparse
import faulthandler
import json
import signal
import sys
import threading
import time
from collections import Counter
from collections.abc import Iterator
from contextlib import contextmanager, nullcontext
from pathlib import Path
from types import FrameType
from typing import TextIO

from hypothesis.errors import HypothesisException

from conformance._backends.loader import BackendLoadError, load_backend
from conformance._corpus.loader import ScenarioError
from conformance._engine import HarnessError
from conformance._fuzz.branch_coverage import BranchCoverage, BranchReport
from conformance._fuzz.campaign import Campaign, CampaignResult
from conformance._fuzz.coverage import campaign_features
from conformance._fuzz.findings import Findings, Origin, replay_command, write_finding
from conformance._fuzz.lockstep import LockstepMachine, PosedLockstepMachine
from conformance._fuzz.model_campaign import MODEL_SWITCHES, SEQUENCE_OPS_ISSUED, ModelCampaign
from conformance._fuzz.model_coverage import expected_model_features
from conformance._fuzz.operations import issued_ops
from conformance._fuzz.regression import prepare_writing, write_reproducer
from conformance._fuzz.sequence_coverage import expected_pairs
from conformance._fuzz.sequence_tour import guided
from conformance._fuzz.stats import FuzzStats, interrupt_requested
from conformance._grammar import GRAMMAR
from conformance._run.drake_log import drake_log_of_case
from conformance._run.outputs import unwritable, unwritable_dir, write_or_fall_back
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.options import refuse
from conformance.cli.run import PROG
from conformance.protocol import MODEL, Backend

__all__ = ["Progress", "fuzz_command"]


class Progress:
    """Writes a progress line to ``err`` at most once per ``interval`` seconds."""

    def __init__(self, err: TextIO, *, interval: float = 1.0, quiet: bool = False) -> None:
        self.err = err
        self.interval = interval
        self.quiet = quiet
        self.start = time.perf_counter()
        self.last = self.start
        self.last_step = self.start
        self.found = 0

    def line(self, stats: FuzzStats) -> str:
        elapsed = max(time.perf_counter() - self.start, 1e-9)
        shrinking = " (shrinking)" if stats.divergences_seen and stats.best is not None else ""
        return (
            f"[fuzz {elapsed:6.1f}s] examples {stats.examples} ({stats.examples / elapsed:.1f}/s)"
            f"  steps {stats.steps} ({stats.steps / elapsed:.0f}/s)"
            f"  divergences {self.found}{shrinking}"
        )

    def say(self, text: str) -> None:
        """Writes ``text`` to ``err`` at once, stamped with the elapsed time (even when quiet)."""
        self.err.write(f"[fuzz {time.perf_counter() - self.start:6.1f}s] {text}\n")
        self.err.flush()

    def __call__(self, stats: FuzzStats) -> None:
        now = time.perf_counter()
        self.last_step = now
        if not self.quiet and now - self.last >= self.interval:
            self.last = now
            self.err.write(self.line(stats) + "\n")
            self.err.flush()

    def watch(self, *, after: float = 10.0, every: float = 10.0) -> threading.Event:
        """Says so on ``err`` every ``every`` s while no step has finished for ``after`` s.

        A backend that hangs shows as waiting, not as silence. Set the
        returned event to stop watching.
        """
        stop = threading.Event()

        def run() -> None:
            while not stop.wait(every):
                waited = time.perf_counter() - self.last_step
                if not self.quiet and waited >= after:
                    line = f"[fuzz] waiting: no backend call has returned for {waited:.0f}s"
                    self.err.write(line + "\n")
                    self.err.flush()

        threading.Thread(target=run, name="fuzz-progress", daemon=True).start()
        return stop


def _broken(exc: HarnessError, args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Reports a broken backend with a reproducer file; exit 2."""
    err.write(f"error: a backend broke (not a divergence): {exc}\n")
    path = write_finding(
        lambda folder: write_reproducer(
            exc,
            folder,
            backend=args.backend,
            reference=args.against,
            seed=args.seed,
            poses=_posed(args),
        ),
        args.out,
        out,
    )
    if path is not None:
        err.write(
            f"  reproducer: {path} ({len(exc.commands)} commands)\n"
            f"  replay:     {replay_command(PROG, path, args.backend, args.against)}\n"
        )
    return EXIT_USAGE


def _drake_log(lines: list[str], err: TextIO) -> None:
    """``-v``: each distinct line Drake (or reimpl) logged during the campaign, with its count
    (without ``-v`` they are kept from stderr: a campaign that passes says nothing of them)."""
    counts = Counter(lines)
    err.write(f"fuzz: Drake logged {len(lines)} warning line(s), {len(counts)} distinct\n")
    for line, count in counts.most_common():
        err.write(f"  {count} x {line}\n")


def _first_seen(example: int | None) -> str:
    """Where the summary says how soon the campaign met its first divergence."""
    return "" if example is None else f", the first seen in example {example}"


def _summary(result: CampaignResult, out: TextIO, progress: Progress) -> None:
    stats = result.stats
    seconds = max(result.seconds, 1e-9)
    share = stats.backend_seconds / seconds
    out.write(
        f"fuzz: {len(result.batches)} batch(es), {stats.examples} examples, {stats.steps} steps "
        f"in {result.seconds:.1f}s ({stats.examples / seconds:.1f} examples/s, "
        f"{stats.steps / seconds:.0f} steps/s; {share:.0%} of the time in backend calls); "
        f"{progress.found} divergence(s)"
        f"{_first_seen(stats.first_example)}"
        f"{'; interrupted' if result.interrupted else ''}\n"
    )
    for divergence, examples in sorted(stats.known.items()):
        out.write(f"fuzz: known divergence {divergence} met in {examples} example(s), set aside\n")


def _without(args: argparse.Namespace) -> frozenset[str]:
    """``--without``: the model grammar elements to leave out."""
    value = getattr(args, "without", "") or ""
    return frozenset(part.strip() for part in value.split(",") if part.strip())


def _expected(args: argparse.Namespace, pair: tuple[Backend, Backend]) -> list[str] | None:
    """The coverage table's features for this campaign."""
    shared = pair[0].features() & pair[1].features()
    if args.models:
        reported = GRAMMAR["collision_filter_groups"].feature in shared
        return expected_model_features(_without(args), groups_report=reported)
    machine = PosedLockstepMachine if _posed(args) else LockstepMachine
    return campaign_features(issued_ops(machine.OPERATIONS), shared)


def _expected_pairs(
    args: argparse.Namespace, pair: tuple[Backend, Backend]
) -> list[tuple[str, str]]:
    """The reachable sequence pairs of this campaign (``sequence_coverage.expected_pairs``)."""
    if args.models:
        return expected_pairs(SEQUENCE_OPS_ISSUED, kinds=[MODEL])  # a model case has no context
    shared = pair[0].features() & pair[1].features()
    machine = PosedLockstepMachine if _posed(args) else LockstepMachine
    optional = {"activation", "queries"} - shared
    ops = issued_ops(machine.OPERATIONS)
    return expected_pairs(op for op in ops if GRAMMAR[op].feature not in optional)


def _coverage(
    result: CampaignResult,
    expected: list[str] | None,
    pairs: list[tuple[str, str]],
    branches: BranchReport | None,
    out: TextIO,
) -> None:
    """``--coverage``: reimpl's lines and branches never run, by function; the sequence
    pairs; then the table of features reached, gaps last."""
    if branches is not None:
        out.write(branches.table() + "\n")
    out.write(result.stats.sequences.table(pairs) + "\n")
    if expected is not None:
        out.write(result.stats.coverage.table(expected) + "\n")


def _stats_json(
    result: CampaignResult, expected: list[str] | None, args: argparse.Namespace
) -> dict[str, object]:
    """``--json``: the run's numbers, its findings and its coverage."""
    stats = result.stats
    return {
        "seed": args.seed,
        "mode": _mode(args).strip(" -") or "sequences",
        "batches": len(result.batches),
        "examples": stats.examples,
        "steps": stats.steps,
        "seconds": round(result.seconds, 3),
        "backend_seconds": round(stats.backend_seconds, 3),
        "divergences": len(result.divergences),
        "shrink_stopped": any(batch.shrink_stopped for batch in result.batches),
        "interrupted": result.interrupted,
        "known_divergences": dict(sorted(stats.known.items())),
        "coverage": None if expected is None else stats.coverage.to_json(expected),
    }


def _load_pair(args: argparse.Namespace) -> tuple[Backend, Backend]:
    options = {"python": args.python, "step_timeout": args.step_timeout or None}
    backend = load_backend(args.backend, **options)
    reference = load_backend(args.against, **options)
    if backend.name == reference.name:
        raise BackendLoadError(f"--backend and --against are both named {backend.name!r}")
    lacking = [b.name for b in (backend, reference) if "queries" not in b.features()]
    if _posed(args) and lacking:
        raise BackendLoadError(
            f"--poses needs the posed queries (feature 'queries'), which "
            f"{' and '.join(lacking)} lack"
        )
    return backend, reference


def _shrink_time(args: argparse.Namespace) -> float | None:
    """``--shrink-time`` (a parser without the option means no bound)."""
    value = getattr(args, "shrink_time", None)
    return None if value is None else float(value)


@contextmanager
def _interrupts() -> Iterator[None]:
    """In the block, SIGTERM raises KeyboardInterrupt, as Ctrl-C does; restored after.

    So ``kill PID`` (a CI job's timeout, a container stop) writes the best
    finding so far, as Ctrl-C does. Both also set ``interrupt_requested``, so a
    KeyboardInterrupt that Python swallowed (raised inside a gc callback) is
    raised again when the next example begins. Only the main thread can handle
    signals: elsewhere the block runs with the handlers as they were.

    A SIGTERM first prints every thread's stack to stderr (``faulthandler``, from
    C, so it works while the main thread is stuck inside a backend's C++ call and
    Python's handler cannot run yet): a run killed by a CI timeout shows where it
    was.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def interrupt(signum: int, frame: FrameType | None) -> None:
        interrupt_requested.set()
        raise KeyboardInterrupt

    interrupt_requested.clear()
    previous = {sig: signal.signal(sig, interrupt) for sig in (signal.SIGTERM, signal.SIGINT)}
    stacks = _stack_printing_on_sigterm()
    try:
        yield
    finally:
        if stacks:
            faulthandler.unregister(signal.SIGTERM)
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        interrupt_requested.clear()


def _stack_printing_on_sigterm() -> bool:
    """Has ``faulthandler`` print every thread's stack on SIGTERM, then call the Python
    handler; False when stderr is not a file (a caller capturing it in memory)."""
    try:
        sys.stderr.fileno()
    except (AttributeError, OSError, ValueError):  # io.UnsupportedOperation is an OSError
        return False
    faulthandler.register(signal.SIGTERM, file=sys.stderr, all_threads=True, chain=True)
    return True


def _guide(args: argparse.Namespace, campaign: Campaign) -> BranchCoverage | None:
    """``--coverage``: a guided campaign (``sequence_tour.guided`` for the lockstep
    machines) and the branch coverage to measure it with; None without it."""
    if not getattr(args, "coverage", False):
        return None
    if not isinstance(campaign, ModelCampaign):
        campaign.machine_base = guided(campaign.machine_base)
    return BranchCoverage()


def _posed(args: argparse.Namespace) -> bool:
    """``--poses`` was given (a parser without the option means no)."""
    return bool(getattr(args, "poses", False))


def _mode(args: argparse.Namespace) -> str:
    return " --models" if args.models else " --poses" if _posed(args) else ""


def fuzz_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``fuzz``; returns the exit code (see ``conformance.cli.exit_codes``)."""
    json_path: Path | None = getattr(args, "json", None)
    problems = _output_problems(args, json_path)
    if args.models and _posed(args):
        problems.append("--models and --poses are two different campaigns: choose one")
    problems += _without_problems(args)
    if refuse(problems, err):
        return EXIT_USAGE
    try:
        backend, reference = _load_pair(args)
    except BackendLoadError as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    progress = Progress(err, quiet=args.quiet)
    origin = Origin(
        backend=args.backend,
        against=args.against,
        out=args.out,
        seed=args.seed,
        models=args.models,
        poses=_posed(args),
        shrink_time=_shrink_time(args),
        prog=PROG,
    )
    findings = Findings(origin, (backend, reference), out, progress)

    max_examples = args.max_examples
    if max_examples is None and args.time_budget is None:
        max_examples = 100
    kind = ModelCampaign if args.models else Campaign
    campaign = kind(
        backend=lambda: backend,
        reference=lambda: reference,
        seed=args.seed,
        max_examples=max_examples,
        time_budget=args.time_budget,
        steps=args.steps,
        database=args.database,
        on_step=findings.on_step,
        on_batch=findings.on_batch,
        stop_at_first=not args.keep_going,
        strict_divergences=args.strict_divergences,
        step_timeout=args.step_timeout or None,
        shrink_time=_shrink_time(args),
        on_best=findings.on_best,
    )
    if isinstance(campaign, ModelCampaign):
        campaign.without = _without(args)
    else:
        campaign.machine_base = PosedLockstepMachine if _posed(args) else LockstepMachine
    branches = _guide(args, campaign)
    err.write(
        f"fuzz{_mode(args)}: {backend.name} {backend.version()} against "
        f"{reference.name} {reference.version()}, seed {args.seed}, "
        + (f"{max_examples} examples" if max_examples else f"time budget {args.time_budget}s")
        + (", one model case each\n" if args.models else f", {args.steps} steps each\n")
    )
    prepare_writing()
    watching = progress.watch()
    try:
        with (
            _interrupts(),
            branches.measuring() if branches else nullcontext(),
            drake_log_of_case() as logged,
        ):
            result = campaign.run()
    except HarnessError as exc:
        findings.kept(err)
        return _broken(exc, args, out, err)
    except ScenarioError as exc:
        err.write(f"error: could not write the finding as a scenario: {exc}\n")
        return EXIT_USAGE
    except HypothesisException as exc:  # e.g. a flaky backend Hypothesis could not replay
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        err.write(f"error: the fuzz run failed ({type(exc).__name__}): {first}\n")
        findings.kept(err)
        return EXIT_USAGE
    finally:
        watching.set()
    if args.verbose:
        _drake_log(logged, err)
    _summary(result, out, progress)
    _report(args, result, (backend, reference), branches, out=out, err=err)
    return _exit_code(result, findings.written, err)


def _report(
    args: argparse.Namespace,
    result: CampaignResult,
    pair: tuple[Backend, Backend],
    branches: BranchCoverage | None,
    *,
    out: TextIO,
    err: TextIO,
) -> None:
    """After the run: the coverage tables (``--coverage``) and the statistics (``--json``)."""
    expected = _expected(args, pair)
    pairs = _expected_pairs(args, pair)
    report = branches.report() if branches else None
    if branches:
        _coverage(result, expected, pairs, report, out)
    json_path: Path | None = getattr(args, "json", None)
    if json_path is not None:
        stats_json = _stats_json(result, expected, args)
        stats_json["sequences"] = result.stats.sequences.to_json(pairs)
        stats_json["branches"] = None if report is None else report.to_json()
        text = json.dumps(stats_json, indent=1) + "\n"
        _write_statistics(json_path, text, err)


def _without_problems(args: argparse.Namespace) -> list[str]:
    """Why ``--without`` cannot be used: without ``--models``, or naming no element."""
    without = _without(args)
    if not without:
        return []
    if not args.models:
        return ["--without leaves out model grammar elements: it needs --models"]
    unknown = sorted(without - set(MODEL_SWITCHES))
    if unknown:
        return [f"--without: unknown model grammar element(s) {', '.join(unknown)}"]
    return []


def _output_problems(args: argparse.Namespace, json_path: Path | None) -> list[str]:
    """Why --out, --database or --json cannot be written, checked before the run."""
    folders = (("--out", args.out), ("--database", args.database))
    problems = [
        f"{option} {path}: {problem}"
        for option, path in folders
        if path is not None and (problem := unwritable_dir(path)) is not None
    ]
    if json_path is not None and (problem := unwritable(json_path)) is not None:
        problems.append(f"--json {json_path}: {problem}")
    return problems


def _write_statistics(json_path: Path, text: str, err: TextIO) -> None:
    """``--json``: the file, or the fallback file with a warning if it cannot be written."""

    def write(path: Path) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)

    written_to = write_or_fall_back(json_path, write, err)
    if written_to is not None:
        err.write(f"fuzz: statistics written to {written_to}\n")


def _exit_code(result: CampaignResult, written: list[Path], err: TextIO) -> int:
    if written and result.interrupted:
        err.write(f"interrupted: the smallest divergence so far is written: {written[-1]}\n")
    if written:
        return EXIT_FAILURE
    if result.interrupted:
        err.write("interrupted: no divergence found before the interrupt\n")
        return EXIT_USAGE
    return EXIT_OK
