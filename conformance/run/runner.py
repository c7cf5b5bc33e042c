"""Runs one case on backends in lockstep: expectations per backend, agreement with a reference.

After every step the runner (1) checks the step's expectations on each
backend that supports the case's features and whose Drake release lies in
the expectation's since/until range (``run.expectations``), and (2) compares
every other backend with the *reference* (``conformance.compare``): the
step's Result and the whole Observation.

The reference is the oracle of the run: the backend named by ``reference``,
else the first real Drake (``pydrake``, or ``drake==X`` in its own
environment), else the first backend. A disagreement is the fault of the
backend that is not the reference, and only it is failed.

State is observed after every step that has expectations or is not part of
the scene, and after the scene's last registration: a big scene costs one
observation, not one per geometry (the scene's Results are still compared).

A backend that breaks (raises, returns the wrong type, exceeds
``step_timeout``, or its worker process dies; see ``backends.calls``) ends
the case: the report gets status ``error``, ``timeout`` or ``crash`` for
that backend and ``aborted`` says why. After a crash or a timeout of an
*isolated* backend (``isolated = True``: a worker, replaced at its next
reset) the case is ``recoverable`` and a run may go on.
A step naming something never made ends it too (an input error).

A backend whose first failure in a case matches a known divergence
(``policy.divergences``) for the reference's release gets ``xfail`` with
the divergence's id instead of ``fail``, unless ``strict_divergences``.
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from conformance.backends.calls import BackendCrashError, BackendError, StepTimeoutError, call
from conformance.compare import diff, diff_results
from conformance.corpus.loader import Case, Step
from conformance.policy.divergences import KnownDivergence, match_case
from conformance.policy.guards import arm_guards
from conformance.policy.versions import version_in_range
from conformance.protocol import (
    Backend,
    BackendId,
    Command,
    Observation,
    Result,
    UnknownNameError,
    backend_id,
)
from conformance.run.expectations import check

__all__ = [
    "BackendError",
    "CaseReport",
    "Failure",
    "Status",
    "choose_reference",
    "run_case",
]

#: Backend names that are real Drake: preferred as the reference.
_DRAKE_NAMES = ("pydrake", "drake")


class Status(enum.Enum):
    PASS = "pass"
    FAIL = "fail"
    XFAIL = "xfail"  # failed as a known divergence says it does
    SKIP = "skip"
    ERROR = "error"  # the backend broke: raised, returned the wrong type
    TIMEOUT = "timeout"  # a call took longer than the step timeout
    CRASH = "crash"  # the backend's process died (a worker backend)


@dataclass(frozen=True)
class Failure:
    """One broken expectation of ``backend``, or one disagreement of ``backend`` with ``reference``.

    For a disagreement, ``expected`` is the reference's value and ``actual`` the backend's.
    """

    step: str
    what: str
    expected: Any
    actual: Any
    backend: str
    reference: str | None = None

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
    status: dict[str, Status] = field(default_factory=dict)
    skip_reasons: dict[str, str] = field(default_factory=dict)
    failures: list[Failure] = field(default_factory=list)
    #: backend → the id of the known divergence its failures are.
    xfails: dict[str, str] = field(default_factory=dict)
    #: Why the case stopped early (a backend broke, or a step named something unknown).
    aborted: str | None = None
    #: The run can go on after ``aborted``: an isolated backend (a worker) crashed or
    #: timed out, and its next reset starts a new worker.
    recoverable: bool = False

    @property
    def passed(self) -> bool:
        broken = _BROKEN & set(self.status.values())
        return self.aborted is None and not broken

    def failures_of(self, backend: str) -> list[Failure]:
        return [f for f in self.failures if f.backend == backend]


def choose_reference(backends: Sequence[Backend], name: str | None = None) -> Backend:
    """``name``'s backend; else the first real Drake; else the first backend."""
    if name is not None:
        for backend in backends:
            if backend.name == name:
                return backend
        raise ValueError(f"no backend is named {name!r} (have {[b.name for b in backends]})")
    for backend in backends:
        if backend.name.startswith(_DRAKE_NAMES):
            return backend
    return backends[0]


def _execute(backend: Backend, step: Step, timeout: float | None) -> Result:
    if step.op == "check":
        return Result()
    command = Command(step.op, step.args)
    where = f"{step.label} ({step.op})"
    return call(backend, "execute", command, where=where, returns=Result, timeout=timeout)


def _observe(backend: Backend, step: Step, timeout: float | None) -> Observation:
    where = f"{step.label} ({step.op}), observe"
    return call(backend, "observe", where=where, returns=Observation, timeout=timeout)


def _observed_steps(steps: Sequence[Step]) -> list[bool]:
    """Whether the state is observed after each step (see the module doc)."""
    return [
        bool(step.expect) or step.index != 0 or i + 1 == len(steps) or steps[i + 1].index != 0
        for i, step in enumerate(steps)
    ]


def _expectation_failures(
    step: Step, backend: Backend, result: Result, observation: Observation | None
) -> Iterator[Failure]:
    """The step's expectations (observed steps only: a step with any is observed), and a
    scene registration that failed."""
    if observation is not None:
        for expectation in step.expect:
            since, until = expectation.get("since"), expectation.get("until")
            if version_in_range(backend.version(), since, until):
                for what, expected, actual in check(step, expectation, result, observation):
                    yield Failure(step.label, what, expected, actual, backend.name)
    if step.index == 0 and result.error is not None:
        what = f"scene {step.op} {step.args.get('name')}"
        yield Failure(step.label, what, None, result.error.to_json(), backend.name)


def _disagreements(
    step: Step,
    reference: Backend,
    other: Backend,
    results: Mapping[str, Result],
    observations: Mapping[str, Observation] | None,
) -> Iterator[Failure]:
    """``other``'s differences from ``reference``: Results, and states if observed."""
    if observations is None:
        differences = diff_results(results[reference.name], results[other.name], op=step.op)
    else:
        differences = diff(
            (results[reference.name], observations[reference.name]),
            (results[other.name], observations[other.name]),
            op=step.op,
        )
    for d in differences:
        yield Failure(step.label, d.what, d.reference, d.other, other.name, reference.name)


def run_case(
    case: Case,
    backends: Sequence[Backend],
    *,
    reference: str | None = None,
    strict_divergences: bool = False,
    divergences: Sequence[KnownDivergence] | None = None,
    step_timeout: float | None = None,
    on_step: Callable[[int, int], None] | None = None,
) -> CaseReport:
    """Runs ``case`` on every backend whose features cover it (see the module doc).

    ``on_step(done, total)`` is called after each step (for progress on long cases).
    """
    oracle = choose_reference(backends, reference)
    report = CaseReport(case)
    active: list[Backend] = []
    for backend in backends:
        missing = case.features - backend.features()
        if missing:
            report.status[backend.name] = Status.SKIP
            report.skip_reasons[backend.name] = f"needs feature(s) {', '.join(sorted(missing))}"
        else:
            active.append(backend)
    arm_guards(active)
    ref = oracle if oracle in active else (active[0] if active else None)
    report.reference = ref.name if ref is not None and len(active) > 1 else None
    try:
        _run_steps(case, active, ref, report, timeout=step_timeout, on_step=on_step)
    except BackendError as exc:
        report.status[exc.backend] = _broken_status(exc)
        report.aborted = str(exc)
        isolated = any(getattr(b, "isolated", False) for b in active if b.name == exc.backend)
        report.recoverable = isolated and report.status[exc.backend] is not Status.ERROR
        return report
    except UnknownNameError as exc:
        report.aborted = f"{exc} (the case names something no earlier step made)"
        return report
    release = ref.version() if ref is not None else ""
    for backend in active:
        report.status[backend.name] = _status(
            report, backend_id(backend), release, strict_divergences, divergences
        )
    return report


#: Statuses that fail a case.
_BROKEN = frozenset({Status.FAIL, Status.ERROR, Status.TIMEOUT, Status.CRASH})


def _broken_status(exc: BackendError) -> Status:
    """CRASH, TIMEOUT or ERROR for a backend that broke."""
    if isinstance(exc, BackendCrashError):
        return Status.CRASH
    return Status.TIMEOUT if isinstance(exc, StepTimeoutError) else Status.ERROR


def _run_steps(
    case: Case,
    active: Sequence[Backend],
    ref: Backend | None,
    report: CaseReport,
    *,
    timeout: float | None,
    on_step: Callable[[int, int], None] | None = None,
) -> None:
    """Runs the steps on ``active``, adding failures to ``report``."""
    for backend in active:
        call(backend, "reset", where="reset", returns=object, timeout=timeout)
    for done, (step, observed) in enumerate(
        zip(case.steps, _observed_steps(case.steps), strict=True)
    ):
        if on_step is not None:
            on_step(done, len(case.steps))
        results = {b.name: _execute(b, step, timeout) for b in active}
        observations = {b.name: _observe(b, step, timeout) for b in active} if observed else None
        for backend in active:
            observation = None if observations is None else observations[backend.name]
            report.failures.extend(
                _expectation_failures(step, backend, results[backend.name], observation)
            )
        for other in active:
            if ref is not None and other is not ref:
                report.failures.extend(_disagreements(step, ref, other, results, observations))


def _status(
    report: CaseReport,
    backend: BackendId,
    release: str,
    strict: bool,
    divergences: Sequence[KnownDivergence] | None,
) -> Status:
    if not report.failures_of(backend.name):
        return Status.PASS
    if strict:
        return Status.FAIL
    known = match_case(report.case.qualified_name, backend, release, divergences)
    if known is None:
        return Status.FAIL
    report.xfails[backend.name] = known.id
    return Status.XFAIL
