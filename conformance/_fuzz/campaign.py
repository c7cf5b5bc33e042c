"""Differential fuzzing campaigns: a LockstepMachine run under fixed Hypothesis settings.

A campaign is one or more *batches*. A batch is one Hypothesis run of the
lockstep machine with a fixed seed. ``--max-examples N`` is one batch of N
examples with seed S. ``--time-budget SEC`` runs batches of ``BATCH_EXAMPLES``
examples, with seeds derived from S (``batch_seed(S, k)``), until the budget
is spent. The same seed therefore gives the same batches in the same order.
A budget decides only how many batches run, and it can overrun by at most
one batch.

Settings that keep runs reproducible: no example database unless one is
given (``database=``; share it between machines to replay each other's
failures first), no deadline, every health check suppressed (the backends
are slow by Hypothesis's standards), and one bug per batch
(``report_multiple_bugs=False``), shrunk to a minimal sequence.
"""

from __future__ import annotations

import hashlib
import importlib
import pkgutil
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

from hypothesis import HealthCheck, Phase, Verbosity, settings
from hypothesis import seed as hypothesis_seed
from hypothesis.database import DirectoryBasedExampleDatabase
from hypothesis.stateful import run_state_machine_as_test

from conformance._engine import Divergence
from conformance._fuzz.lockstep import LockstepMachine, lockstep_machine
from conformance._fuzz.stats import FuzzStats, HarnessAbort, ShrinkTimeUp
from conformance.protocol import Backend

__all__ = [
    "BATCH_EXAMPLES",
    "DEFAULT_STEPS",
    "BatchResult",
    "Campaign",
    "CampaignResult",
    "batch_seed",
    "fuzz_settings",
    "load_local_modules",
]

#: Typed alias: Hypothesis releases differ in whether this function is annotated,
#: so the call must type-check without a version-specific ``type: ignore``.
_run_machine: Callable[..., None] = run_state_machine_as_test

BATCH_EXAMPLES = 50
DEFAULT_STEPS = 50


@cache
def load_local_modules() -> tuple[str, ...]:
    """Imports every module of ``conformance`` and ``reimpl``; returns their names.

    N.B. Hypothesis draws now and then from the literal constants of the
    *local* modules already imported (``hypothesis.internal.conjecture.
    providers``), so what the caller happened to import changes the run. A
    campaign therefore loads all of this project's modules first: the same
    seed then gives the same run from the CLI, from pytest, or from a script.
    """
    names: list[str] = []
    for package_name in ("conformance", "reimpl"):
        package = importlib.import_module(package_name)
        for info in pkgutil.walk_packages(package.__path__, prefix=f"{package_name}."):
            if info.name.endswith(".__main__"):
                continue
            try:
                importlib.import_module(info.name)
            except ImportError:  # e.g. the pytest plugin without pytest installed
                continue
            names.append(info.name)
    return tuple(sorted(names))


def batch_seed(seed: int, batch: int) -> int:
    """Batch 0 uses ``seed`` itself; later batches a 63-bit hash of (seed, batch)."""
    if batch == 0:
        return seed
    digest = hashlib.sha256(f"{seed}/{batch}".encode()).digest()
    return int.from_bytes(digest[:8], "big") >> 1


def fuzz_settings(
    *,
    max_examples: int,
    steps: int = DEFAULT_STEPS,
    database: Path | None = None,
    verbosity: Verbosity = Verbosity.quiet,
) -> settings:
    """The Hypothesis settings of one batch (see the module doc)."""
    return settings(
        max_examples=max_examples,
        stateful_step_count=steps,
        deadline=None,
        database=DirectoryBasedExampleDatabase(str(database)) if database else None,
        suppress_health_check=list(HealthCheck),
        report_multiple_bugs=False,
        phases=(Phase.explicit, Phase.reuse, Phase.generate, Phase.target, Phase.shrink),
        verbosity=verbosity,
        print_blob=False,
    )


@dataclass(frozen=True)
class BatchResult:
    seed: int
    divergence: Divergence | None
    #: Shrinking was stopped by ``Campaign.shrink_time`` (the divergence is the best so far).
    shrink_stopped: bool = False


@dataclass
class CampaignResult:
    batches: list[BatchResult] = field(default_factory=list)
    interrupted: bool = False
    stats: FuzzStats = field(default_factory=FuzzStats)
    seconds: float = 0.0

    @property
    def divergences(self) -> list[Divergence]:
        return [b.divergence for b in self.batches if b.divergence is not None]


@dataclass
class Campaign:
    """Runs batches of the lockstep machine for ``backend`` against ``reference``."""

    backend: Callable[[], Backend]
    reference: Callable[[], Backend]
    seed: int = 0
    max_examples: int | None = 100
    time_budget: float | None = None
    steps: int = DEFAULT_STEPS
    database: Path | None = None
    #: Called after every step with the running counters (for progress lines).
    on_step: Callable[[FuzzStats], None] | None = None
    #: Called after every batch (for writing a finding at once).
    on_batch: Callable[[BatchResult], None] | None = None
    #: Stop at the first divergence even with a time budget.
    stop_at_first: bool = False
    machine_base: type[LockstepMachine] = LockstepMachine
    #: Bounds on the initial scene (default: ``machine_base``'s).
    scene_frames: tuple[int, int] | None = None
    scene_geometries: tuple[int, int] | None = None
    #: Report known divergences as divergences (default: set them aside, counted).
    strict_divergences: bool = False
    #: Seconds one backend call may take; None: no limit.
    step_timeout: float | None = None
    #: Seconds shrinking may take after a batch's first divergence; None: no bound.
    shrink_time: float | None = None
    #: Called with each batch's first divergence and every smaller one, at once.
    on_best: Callable[[Divergence], None] | None = None

    def run(self) -> CampaignResult:
        """Runs the campaign. On Ctrl-C, keeps the smallest divergence seen so far.

        A backend that breaks raises ``HarnessError`` (with the commands that
        led there) at once, after the batches done so far were reported.
        """
        load_local_modules()
        stats = FuzzStats(
            on_step=self.on_step, on_best=self.on_best, shrink_seconds=self.shrink_time
        )
        result = CampaignResult(stats=stats)
        start = time.perf_counter()
        # One backend pair for the whole campaign (each example resets them).
        backend, reference = self.backend(), self.reference()
        batch = 0
        try:
            while self._more(batch, start, result):
                size = self.max_examples if self.time_budget is None else BATCH_EXAMPLES
                seed = batch_seed(self.seed, batch)
                outcome = self._batch(backend, reference, stats, seed, size)
                result.batches.append(outcome)
                if self.on_batch is not None:
                    self.on_batch(outcome)
                batch += 1
        except KeyboardInterrupt:
            result.interrupted = True
            if stats.best is not None:
                outcome = BatchResult(batch_seed(self.seed, batch), stats.best)
                result.batches.append(outcome)
                if self.on_batch is not None:
                    self.on_batch(outcome)
        result.seconds = time.perf_counter() - start
        return result

    def _more(self, batch: int, start: float, result: CampaignResult) -> bool:
        if self.stop_at_first and result.divergences:
            return False
        if self.time_budget is None:
            return batch == 0
        return time.perf_counter() - start < self.time_budget

    def _batch(
        self, backend: Backend, reference: Backend, stats: FuzzStats, seed: int, size: int | None
    ) -> BatchResult:
        machine = lockstep_machine(
            lambda: backend,
            lambda: reference,
            stats=stats,
            base=self.machine_base,
            scene_frames=self.scene_frames,
            scene_geometries=self.scene_geometries,
            strict_divergences=self.strict_divergences,
            step_timeout=self.step_timeout,
        )
        hypothesis_seed(seed)(machine)
        stats.new_batch()
        try:
            _run_machine(
                machine,
                settings=fuzz_settings(
                    max_examples=size or 100, steps=self.steps, database=self.database
                ),
            )
        except Divergence as divergence:
            return BatchResult(seed, divergence)
        except ShrinkTimeUp:
            return BatchResult(seed, stats.best, shrink_stopped=True)
        except HarnessAbort as abort:
            raise abort.error from None
        return BatchResult(seed, None)
