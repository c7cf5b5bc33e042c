"""A campaign's counters, and where its examples may stop.

``FuzzStats`` is shared by every example of a campaign: examples, steps,
seconds in backend calls, the divergences seen (the smallest so far is kept
for an interrupted run), the known divergences set aside, and the coverage
reached. ``stop_point`` is where each example begins: a pending interrupt
ends the run there, and shrinking whose time is up ends the batch.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from conformance._engine import Divergence, HarnessError
from conformance._fuzz.coverage import Coverage
from conformance._fuzz.sequence_coverage import SequenceCoverage

__all__ = [
    "FuzzStats",
    "HarnessAbort",
    "ShrinkTimeUp",
    "interrupt_requested",
    "stop_point",
]


class ShrinkTimeUp(KeyboardInterrupt):
    """Shrinking ran out of ``FuzzStats.shrink_seconds``: the batch ends with the best so far.

    N.B. A ``KeyboardInterrupt``, because that is the one exception Hypothesis
    lets through at once from any point of a run, shrinking included: any
    other, raised before the example draws anything, is a failure whose
    draws differ from the one being shrunk (``FlakyStrategyDefinition``).
    Hypothesis has no public bound on shrinking time. ``Campaign`` catches it
    before a real interrupt.
    """


#: Set by the signal handler that raises KeyboardInterrupt (``cli.fuzz``). Python only
#: prints an exception raised inside a gc callback or a ``__del__``, and a signal can land
#: there; the next example then raises it again (``stop_point``), so the run still ends.
interrupt_requested = threading.Event()


def stop_point(stats: FuzzStats) -> None:
    """Where each example begins: a pending interrupt ends the run, and shrinking time
    that is up ends the batch (``ShrinkTimeUp``)."""
    if interrupt_requested.is_set():
        raise KeyboardInterrupt
    if stats.shrink_time_up():
        raise ShrinkTimeUp


class HarnessAbort(BaseException):
    """Carries a ``HarnessError`` out through Hypothesis at once.

    As an ``Exception`` it would be a failing example: Hypothesis would
    shrink it, calling the broken (or hanging) backend again and again, and
    report an intermittent one as a ``FlakyFailure``. A ``BaseException`` ends
    the run; ``Campaign.run`` turns it back into the ``HarnessError``.
    """

    def __init__(self, error: HarnessError) -> None:
        super().__init__(str(error))
        self.error = error


@dataclass
class FuzzStats:
    """Counters shared by every machine of a campaign; ``on_step`` reports progress."""

    examples: int = 0
    steps: int = 0
    backend_seconds: float = 0.0
    divergences_seen: int = 0
    #: Known divergences met (and set aside): id → how many examples.
    known: dict[str, int] = field(default_factory=dict)
    #: The smallest divergence seen so far (kept if the run is interrupted).
    best: Divergence | None = None
    #: When (``time.perf_counter()``) this batch's first divergence was seen.
    best_since: float | None = None
    #: The example (counted from 1 over the campaign) in which a divergence was first seen.
    first_example: int | None = None
    #: Seconds shrinking may take after the first divergence; None: no bound.
    shrink_seconds: float | None = None
    #: The state-space features reached (``conformance._fuzz.coverage``).
    coverage: Coverage = field(default_factory=Coverage)
    #: Pairs and triples of consecutive located events (``conformance._fuzz.sequence_coverage``).
    sequences: SequenceCoverage = field(default_factory=SequenceCoverage)
    on_step: Callable[[FuzzStats], None] | None = field(default=None, repr=False)
    #: Called with every new ``best`` at once (for writing the finding before shrinking ends).
    on_best: Callable[[Divergence], None] | None = field(default=None, repr=False)

    def record(self, divergence: Divergence) -> None:
        """Counts ``divergence``; it becomes ``best`` if no longer than the best so far."""
        self.divergences_seen += 1
        if self.first_example is None:
            self.first_example = self.examples
        if self.best is None or len(divergence.trace) <= len(self.best.trace):
            if self.best is None:
                self.best_since = time.perf_counter()
            self.best = divergence
            if self.on_best is not None:
                self.on_best(divergence)

    def new_batch(self) -> None:
        """Forgets the last batch's best divergence."""
        self.best = None
        self.best_since = None

    def shrink_time_up(self) -> bool:
        """A divergence was seen more than ``shrink_seconds`` ago."""
        return (
            self.shrink_seconds is not None
            and self.best_since is not None
            and time.perf_counter() - self.best_since > self.shrink_seconds
        )
