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

A backend whose first failure in a case matches a known divergence
(``policy.divergences``) for the reference's release gets ``xfail`` with
the divergence's id instead of ``fail``, unless ``strict_divergences``.
"""

from __future__ import annotations

import enum
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from conformance.compare import diff
from conformance.corpus.loader import Case, Step
from conformance.policy.divergences import KnownDivergence, match_case
from conformance.policy.guards import arm_guards
from conformance.policy.versions import version_in_range
from conformance.protocol import Backend, BackendId, Command, Observation, Result, backend_id
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


class BackendError(RuntimeError):
    """Raised when a backend itself breaks (not a conformance failure): exit 2."""


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

    @property
    def passed(self) -> bool:
        return Status.FAIL not in self.status.values()

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


def _execute(backend: Backend, step: Step) -> Result:
    if step.op == "check":
        return Result()
    try:
        return backend.execute(Command(step.op, step.args))
    except (KeyError, AttributeError, AssertionError) as exc:
        raise BackendError(
            f"backend {backend.name!r} failed on {step.label} ({step.op}): {exc!r}"
        ) from exc


def _expectation_failures(
    step: Step, backend: Backend, result: Result, observation: Observation
) -> Iterator[Failure]:
    for expectation in step.expect:
        if version_in_range(backend.version(), expectation.get("since"), expectation.get("until")):
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
    observations: Mapping[str, Observation],
) -> Iterator[Failure]:
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
) -> CaseReport:
    """Runs ``case`` on every backend whose features cover it (see the module doc)."""
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
    for backend in active:
        backend.reset()
    ref = oracle if oracle in active else (active[0] if active else None)
    report.reference = ref.name if ref is not None and len(active) > 1 else None
    for step in case.steps:
        results = {b.name: _execute(b, step) for b in active}
        observations = {b.name: b.observe() for b in active}
        for backend in active:
            report.failures.extend(
                _expectation_failures(
                    step, backend, results[backend.name], observations[backend.name]
                )
            )
        for other in active:
            if ref is not None and other is not ref:
                report.failures.extend(_disagreements(step, ref, other, results, observations))
    release = ref.version() if ref is not None else ""
    for backend in active:
        report.status[backend.name] = _status(
            report, backend_id(backend), release, strict_divergences, divergences
        )
    return report


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
