"""What one case did on its backends: a ``CaseReport`` of ``Failure`` records and outcomes.

A failure is one broken expectation of a backend (``reference`` is None), or one
disagreement of a backend with the reference (``expected`` is the reference's
value). A case passes when no backend's outcome is in ``BROKEN`` and it was
not stopped early by an input error.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from conformance._corpus.loader import Case
from conformance._engine import Outcome, Trace, Track

__all__ = ["BROKEN", "CaseReport", "Failure"]

#: Outcomes that fail a case.
BROKEN = frozenset({Outcome.FAIL, Outcome.ERROR, Outcome.TIMEOUT, Outcome.CRASH})


@dataclass(frozen=True)
class Failure:
    """One broken expectation of ``backend``, or one disagreement of ``backend`` with ``reference``.

    For a disagreement, ``expected`` is the reference's value and ``actual`` the backend's.
    ``index`` is the step's place in the case (0-based).
    """

    step: str
    what: str
    expected: Any
    actual: Any
    backend: str
    reference: str | None = None
    index: int = 0

    @property
    def source(self) -> str:
        """Where ``expected`` comes from: ``case`` or ``reference <name>``."""
        return "case" if self.reference is None else f"reference {self.reference}"

    def to_json(self) -> dict[str, Any]:
        return {
            "step": self.step,
            "what": self.what,
            "expected": self.expected,
            "actual": self.actual,
            "backend": self.backend,
            "reference": self.reference,
        }


@dataclass
class CaseReport:
    case: Case
    reference: str | None = None
    status: dict[str, Outcome] = field(default_factory=dict)
    skip_reasons: dict[str, str] = field(default_factory=dict)
    failures: list[Failure] = field(default_factory=list)
    #: backend → the id of the known divergence its failures are.
    xfails: dict[str, str] = field(default_factory=dict)
    #: Why the case stopped early (a backend broke, or a step named something unknown).
    aborted: str | None = None
    #: The run can go on after ``aborted``: an isolated backend (a worker) crashed or
    #: timed out, and its next reset starts a new worker.
    recoverable: bool = False
    #: backend → how it broke (CRASH, TIMEOUT or ERROR), also when that is ``xfail``.
    broken: dict[str, Outcome] = field(default_factory=dict)
    #: backend → the crash row (``policy.release_facts``) that records its crash as its
    #: release's answer: it passes.
    recorded: dict[str, str] = field(default_factory=dict)
    #: backend → what it answered (``Track``), for each backend that ran the case.
    traces: dict[str, Track] = field(default_factory=dict, repr=False)
    #: The engine's steps, every backend's answers side by side (None: the case never ran).
    trace: Trace | None = field(default=None, repr=False)
    #: What Drake (or reimpl) logged while the case ran (``drake_log``), not shown on stderr.
    log: list[str] = field(default_factory=list, repr=False)

    @property
    def passed(self) -> bool:
        broken = BROKEN & set(self.status.values())
        return (self.aborted is None or self.recoverable) and not broken

    def failures_of(self, backend: str) -> list[Failure]:
        return [f for f in self.failures if f.backend == backend]
