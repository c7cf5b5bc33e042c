"""Runs cases on backends in lockstep: expectations per backend, agreement between them.

After every step the runner (1) checks the step's expectations on each backend
that supports the case's features and whose Drake version is in the
expectation's since/until range, and (2) compares every backend with the first
one: the step's Result (value, or error kind plus message) and the whole
Observation (candidate pairs per location, FilterId activity, history).
"""

from __future__ import annotations

import enum
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from conformance.corpus.loader import Case, Step
from conformance.protocol import (
    MODEL,
    Backend,
    Command,
    ErrorKind,
    LocationState,
    Observation,
    Result,
    normalise_message,
)

__all__ = [
    "BackendError",
    "CaseReport",
    "Failure",
    "Status",
    "results_agree",
    "run_case",
    "version_in_range",
]


class Status(enum.Enum):
    PASS = "pass"
    FAIL = "fail"
    SKIP = "skip"


class BackendError(RuntimeError):
    """Raised when a backend itself breaks (not a conformance failure): exit 2."""


@dataclass(frozen=True)
class Failure:
    """One broken expectation, or one disagreement between backends."""

    step: str
    what: str
    expected: Any
    actual: Any
    backend: str  # the backend at fault, or "a vs b" for a disagreement

    def to_json(self) -> dict[str, Any]:
        return {
            "step": self.step,
            "what": self.what,
            "expected": self.expected,
            "actual": self.actual,
            "backend": self.backend,
        }


@dataclass
class CaseReport:
    case: Case
    status: dict[str, Status] = field(default_factory=dict)
    skip_reasons: dict[str, str] = field(default_factory=dict)
    failures: list[Failure] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return not self.failures

    def failures_of(self, backend: str) -> list[Failure]:
        return [f for f in self.failures if backend in f.backend.split(" vs ")]


def _version(text: str) -> tuple[int, ...]:
    return tuple(int(part) for part in text.split("+", maxsplit=1)[0].split(".") if part.isdigit())


def version_in_range(version: str, since: str | None, until: str | None) -> bool:
    """since ≤ version ≤ until, comparing dotted release numbers."""
    v = _version(version)
    return (since is None or v >= _version(since)) and (until is None or v <= _version(until))


def _pairs(raw: Iterable[Sequence[str]]) -> frozenset[tuple[str, str]]:
    return frozenset(tuple(sorted(p)) for p in raw)  # type: ignore[misc]


def _fmt_pairs(pairs: Iterable[tuple[str, str]]) -> list[str]:
    return sorted(f"{a}-{b}" for a, b in pairs)


def _check_result(expectation: Mapping[str, Any], result: Result) -> Iterator[tuple[str, Any, Any]]:
    error = expectation.get("error")
    if error is not None:
        actual = result.error.to_json() if result.error else "no error"
        if result.error is None or result.error.kind.value != error["kind"]:
            yield "error", error, actual
        elif not result.error.message.startswith(normalise_message(error.get("message", ""))):
            yield "error message prefix", error, actual
    elif result.error is not None:
        yield "no error", None, result.error.to_json()
    if "returns" in expectation and result.error is None and result.value != expectation["returns"]:
        yield "return value", expectation["returns"], result.value


def _check_state(
    expectation: Mapping[str, Any], at: str, state: LocationState
) -> Iterator[tuple[str, Any, Any]]:
    if "candidates" in expectation:
        expected = _pairs(expectation["candidates"])
        if state.candidates != expected:
            yield f"candidates at {at}", _fmt_pairs(expected), _fmt_pairs(state.candidates)
    for key, want_in in (("filtered", False), ("unfiltered", True)):
        for pair in _pairs(expectation.get(key, ())):
            if (pair in state.candidates) != want_in:
                yield f"{'-'.join(pair)} {key} at {at}", want_in, not want_in
    for label, active in expectation.get("active", {}).items():
        if state.active.get(label) != active:
            yield f"IsActive({label}) at {at}", active, state.active.get(label)
    if "history" in expectation and state.has_transient_history != expectation["history"]:
        yield f"has_transient_history at {at}", expectation["history"], state.has_transient_history


def _check(
    step: Step, expectation: Mapping[str, Any], result: Result, observation: Observation
) -> Iterator[tuple[str, Any, Any]]:
    """(what, expected, actual) for every part of ``expectation`` that does not hold."""
    yield from _check_result(expectation, result)
    at = expectation.get("at", step.args.get("context", MODEL))
    state = observation.locations.get(at)
    if state is None:
        yield f"location {at!r} exists", at, sorted(observation.locations)
    else:
        yield from _check_state(expectation, at, state)


def results_agree(a: Result, b: Result) -> bool:
    """Same value; or same error kind and, unless BINDING, the same normalised message."""
    if (a.error is None) != (b.error is None):
        return False
    if a.error is None or b.error is None:
        return bool(a.value == b.value)
    if a.error.kind != b.error.kind:
        return False
    # Binding errors are pybind11's wording, which changes between releases.
    return a.error.kind is ErrorKind.BINDING or a.error.message == b.error.message


def _observation_diff(a: Observation, b: Observation) -> Iterator[tuple[str, Any, Any]]:
    for location in sorted(set(a.locations) | set(b.locations)):
        sa, sb = a.locations.get(location), b.locations.get(location)
        if sa is None or sb is None:
            yield f"location {location}", sa is not None, sb is not None
            continue
        if sa.candidates != sb.candidates:
            yield (
                f"candidates at {location} (only in one side)",
                _fmt_pairs(sa.candidates - sb.candidates),
                _fmt_pairs(sb.candidates - sa.candidates),
            )
        if dict(sa.active) != dict(sb.active):
            yield f"IsActive at {location}", dict(sa.active), dict(sb.active)
        if sa.has_transient_history != sb.has_transient_history:
            yield (
                f"has_transient_history at {location}",
                sa.has_transient_history,
                sb.has_transient_history,
            )


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
            for what, expected, actual in _check(step, expectation, result, observation):
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
    pair = f"{reference.name} vs {other.name}"
    ra, rb = results[reference.name], results[other.name]
    if not results_agree(ra, rb):
        yield Failure(step.label, f"{step.op} result", ra.to_json(), rb.to_json(), pair)
    observed = _observation_diff(observations[reference.name], observations[other.name])
    for what, va, vb in observed:
        yield Failure(step.label, what, va, vb, pair)


def run_case(case: Case, backends: Sequence[Backend]) -> CaseReport:
    """Runs ``case`` on every backend whose features cover it; compares them pairwise."""
    report = CaseReport(case)
    active: list[Backend] = []
    for backend in backends:
        missing = case.features - backend.features()
        if missing:
            report.status[backend.name] = Status.SKIP
            report.skip_reasons[backend.name] = f"needs feature(s) {', '.join(sorted(missing))}"
        else:
            backend.reset()
            active.append(backend)
    for step in case.steps:
        results = {b.name: _execute(b, step) for b in active}
        observations = {b.name: b.observe() for b in active}
        for backend in active:
            report.failures.extend(
                _expectation_failures(
                    step, backend, results[backend.name], observations[backend.name]
                )
            )
        for other in active[1:]:
            report.failures.extend(_disagreements(step, active[0], other, results, observations))
    for backend in active:
        report.status[backend.name] = (
            Status.FAIL if report.failures_of(backend.name) else Status.PASS
        )
    return report
