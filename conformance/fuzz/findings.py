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

File names are a hash of the steps, so the name changes as the finding
shrinks: ``path`` is the current one, and ``fuzz`` names the first and the
final file on its output.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from conformance.fuzz.lockstep import Divergence

__all__ = ["FindingFile"]


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
