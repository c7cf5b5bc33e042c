"""Runs one case on backends: expectations per backend, agreement with a reference.

Each backend runs the whole case from a reset and leaves a ``Trace``: the
Result of every step and the Observation after the observed ones. A worker
(``run_steps``) answers the case in one batch; other backends are called
step by step. The traces are then compared step by step: (1) each step's
expectations on each backend whose Drake release lies in the expectation's
since/until range (``run.expectations``), and (2) every other backend
against the *reference* (``conformance.compare``): the step's Result and the
whole Observation.

The reference is the oracle of the run: the backend named by ``reference``,
else the first real Drake (``pydrake``, or ``drake==X`` in its own
environment), else the first backend. A disagreement is the fault of the
backend that is not the reference, and only it is failed.

State is observed after every step that has expectations or is not part of
the scene, and after the scene's last registration: a big scene costs one
observation, not one per geometry (the scene's Results are still compared).

A backend that breaks (raises, returns the wrong type, exceeds
``step_timeout``, or its worker process dies; see ``backends.calls``) ends
its own trace there: the report gets status ``error``, ``timeout`` or
``crash`` for it and ``aborted`` says why, while the other backends finish
the case and are still checked and compared wherever both answered. After
a crash or a timeout of an *isolated* backend (``isolated = True``: a
worker, replaced at its next reset) the case is ``recoverable`` and a run
goes on. Workers are not protected by release guards (``policy.guards``,
``crash_isolated``): their release may crash, and a crash that a known
divergence of kind ``drake_crash`` expects of that release is ``xfail``.
A step naming something never made ends the case (an input error).

A backend whose first failure in a case matches a known divergence
(``policy.divergences``) for the reference's release gets ``xfail`` with
the divergence's id instead of ``fail``, unless ``strict_divergences``.
"""

from __future__ import annotations

import contextlib
import enum
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

from conformance.backends.calls import (
    BackendCrashError,
    BackendError,
    StepTimeoutError,
    call,
    call_function,
)
from conformance.compare import diff, diff_results
from conformance.corpus.loader import Case, Step
from conformance.grammar import spec
from conformance.policy.divergences import KnownDivergence, match_case
from conformance.policy.guards import arm_guards
from conformance.policy.versions import version_in_range
from conformance.protocol import (
    Backend,
    BackendId,
    Command,
    ErrorKind,
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
    "Trace",
    "choose_reference",
    "reference_name",
    "run_case",
    "trace_disagreements",
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
    #: backend → how it broke (CRASH, TIMEOUT or ERROR), also when that is ``xfail``.
    broken: dict[str, Status] = field(default_factory=dict)
    #: backend → what it answered (``Trace``), for each backend that ran the case.
    traces: dict[str, Trace] = field(default_factory=dict, repr=False)

    @property
    def passed(self) -> bool:
        broken = _BROKEN & set(self.status.values())
        return (self.aborted is None or self.recoverable) and not broken

    def failures_of(self, backend: str) -> list[Failure]:
        return [f for f in self.failures if f.backend == backend]


def choose_reference(backends: Sequence[Backend], name: str | None = None) -> Backend:
    """``name``'s backend; else the first real Drake; else the first backend."""
    names = [b.name for b in backends]
    return backends[names.index(reference_name(names, name))]


def reference_name(names: Sequence[str], name: str | None = None) -> str:
    """``name`` (one of ``names``); else the first real Drake's name; else the first."""
    if name is not None:
        if name not in names:
            raise ValueError(f"no backend is named {name!r} (have {list(names)})")
        return name
    return next((n for n in names if n.startswith(_DRAKE_NAMES)), names[0])


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
    step: Step, reference: Trace, other: Trace, index: int, observed: bool
) -> Iterator[Failure]:
    """``other``'s differences from ``reference`` at step ``index``: Results, and states if
    observed."""
    ours, theirs = reference.results[index], other.results[index]
    seen, seen_other = reference.observations[index], other.observations[index]
    if observed and seen is not None and seen_other is not None:
        differences = diff((ours, seen), (theirs, seen_other), op=step.op)
    else:
        differences = diff_results(ours, theirs, op=step.op)
    for d in differences:
        yield Failure(step.label, d.what, d.reference, d.other, other.name, reference.name)


@dataclass
class Trace:
    """One backend's answers to a case: a Result per step run, the Observation after each
    observed step (None after the others), and the error that ended it early, if one did."""

    backend: Backend
    results: list[Result] = field(default_factory=list)
    observations: list[Observation | None] = field(default_factory=list)
    broken: BackendError | None = None

    @property
    def name(self) -> str:
        return self.backend.name

    def covers(self, index: int) -> bool:
        return index < len(self.results)


def _answers(
    backend: Backend, steps: Sequence[Step], observed: Sequence[bool], timeout: float | None
) -> Iterator[tuple[Result, Observation | None]]:
    """The backend's Result and Observation (if ``observed``) per step, checked by
    ``call``: one batch if the backend has ``run_steps`` (a worker), else call by call."""
    where = [f"{step.label} ({step.op})" for step in steps]
    if hasattr(backend, "run_steps"):
        commands = [None if s.op == "check" else Command(s.op, s.args) for s in steps]
        stream = iter(backend.run_steps(list(zip(commands, observed, strict=True))))
        for label in where:
            with _naming_step(label):
                answer = call_function(
                    backend,
                    lambda: next(stream),
                    "run_steps",
                    where=label,
                    returns=tuple,
                    timeout=timeout,
                )
            yield answer
        return
    for step, label, look in zip(steps, where, observed, strict=True):
        result = Result()
        with _naming_step(label):
            if step.op != "check":
                command = Command(step.op, step.args)
                result = call(
                    backend, "execute", command, where=label, returns=Result, timeout=timeout
                )
        observation = None
        if look:
            observation = call(
                backend, "observe", where=f"{label}, observe", returns=Observation, timeout=timeout
            )
        yield result, observation


@contextlib.contextmanager
def _naming_step(label: str) -> Iterator[None]:
    """Adds the step (``label``) to an UnknownNameError raised inside: the input error names it."""
    try:
        yield
    except UnknownNameError as exc:
        exc.where = exc.where or label
        raise


def _trace(
    backend: Backend,
    steps: Sequence[Step],
    observed: Sequence[bool],
    timeout: float | None,
    on_step: Callable[[], None],
) -> Trace:
    """``backend``'s Trace of the case, from a reset; a BackendError ends it early."""
    trace = Trace(backend)
    try:
        call(backend, "reset", where="reset", returns=object, timeout=timeout)
        for result, observation in _answers(backend, steps, observed, timeout):
            if not isinstance(result, Result) or not isinstance(observation, Observation | None):
                raise BackendError(backend.name, "run_steps", "answered the wrong types")
            trace.results.append(result)
            trace.observations.append(observation)
            on_step()
    except BackendError as exc:
        trace.broken = exc
    return trace


def run_case(
    case: Case,
    backends: Sequence[Backend],
    *,
    reference: str | None = None,
    strict_divergences: bool = False,
    divergences: Sequence[KnownDivergence] | None = None,
    step_timeout: float | None = None,
    on_step: Callable[[int, int], None] | None = None,
    bad_models_are_input_errors: bool = False,
) -> CaseReport:
    """Runs ``case`` on every backend whose features cover it (see the module doc).

    ``on_step(done, total)`` is called after each step of each backend (for progress
    on long cases). With ``bad_models_are_input_errors`` (the ``run`` command), a
    model step that every backend rejects, in a case that does not expect an
    error there, ends the case as an input error (``_bad_model``).
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
    arm_guards(active, crash_isolated=True)
    ref = oracle if oracle in active else (active[0] if active else None)
    report.reference = ref.name if ref is not None and len(active) > 1 else None
    observed = _observed_steps(case.steps)
    total, done = len(case.steps) * len(active), 0

    def step_done() -> None:
        nonlocal done
        done += 1
        if on_step is not None:
            on_step(done, total)

    try:
        traces = [_trace(b, case.steps, observed, step_timeout, step_done) for b in active]
    except UnknownNameError as exc:
        where = f"{exc.where}: " if exc.where else ""
        report.aborted = f"{where}{exc} (the case names something no earlier step made)"
        return report
    report.traces = {t.name: t for t in traces}
    if bad_models_are_input_errors:
        report.aborted = _bad_model(case, traces, ref)
        if report.aborted is not None:
            return report
    _compare(case, traces, ref, observed, report)
    release = ref.version() if ref is not None else ""
    for trace in traces:
        if trace.broken is not None:
            _broke(report, trace, strict_divergences, divergences)
        else:
            report.status[trace.name] = _status(
                report, backend_id(trace.backend), release, strict_divergences, divergences
            )
    return report


def _bad_model(case: Case, traces: Sequence[Trace], ref: Backend | None) -> str | None:
    """Why the case's model is bad, if a model step failed on every backend unexpectedly.

    A user's model that Drake rejects (an unknown link in a group, an
    undefined group, a malformed file) is an input error, not a conformance
    result, unless the step expects an error: then the case tests it. If the
    backends disagree, it is a conformance failure, and the comparison says so.
    """
    for index, step in enumerate(case.steps):
        if spec(step.op).domain != "model" or any("error" in e for e in step.expect):
            continue
        first = sorted(traces, key=lambda t: t.backend is not ref)  # the reference first
        errors = [t.results[index].error for t in first if t.covers(index)]
        if errors and len(errors) == len(traces) and errors[0] is not None and all(errors):
            return (
                f"{step.label} ({step.op}): the model is invalid on {first[0].name}: "
                f"{errors[0].message} (a case that tests this error says so with "
                '"expect": {"error": ...})'
            )
    return None


def _compare(
    case: Case,
    traces: Sequence[Trace],
    ref: Backend | None,
    observed: Sequence[bool],
    report: CaseReport,
) -> None:
    """Adds each step's expectation failures and disagreements with the reference (where
    both answered) to ``report``."""
    reference = next((t for t in traces if t.backend is ref), None)
    for index, (step, look) in enumerate(zip(case.steps, observed, strict=True)):
        for trace in traces:
            if trace.covers(index):
                report.failures.extend(
                    _expectation_failures(
                        step,
                        trace.backend,
                        trace.results[index],
                        trace.observations[index] if look else None,
                    )
                )
    if reference is not None:
        for other in traces:
            if other is not reference:
                report.failures.extend(trace_disagreements(case, reference, other))


def trace_disagreements(
    case: Case, reference: Trace, other: Trace, *, ends: bool = False
) -> list[Failure]:
    """``other``'s differences from ``reference``, step by step, where both answered;
    with ``ends``, a trace that ends earlier than the other (it broke) is one too."""
    observed = _observed_steps(case.steps)
    failures: list[Failure] = []
    for index, (step, look) in enumerate(zip(case.steps, observed, strict=True)):
        if reference.covers(index) and other.covers(index):
            failures.extend(_disagreements(step, reference, other, index, look))
    if ends and len(reference.results) != len(other.results):
        failures.append(
            Failure(
                "end",
                "steps answered",
                _ended(reference, len(case.steps)),
                _ended(other, len(case.steps)),
                other.name,
                reference.name,
            )
        )
    return failures


def _ended(trace: Trace, total: int) -> str:
    if trace.broken is None:
        return f"all {total}"
    return f"{len(trace.results)} of {total}: {type(trace.broken).__name__} at {trace.broken.where}"


#: Statuses that fail a case.
_BROKEN = frozenset({Status.FAIL, Status.ERROR, Status.TIMEOUT, Status.CRASH})


def _broken_status(exc: BackendError) -> Status:
    """CRASH, TIMEOUT or ERROR for a backend that broke."""
    if isinstance(exc, BackendCrashError):
        return Status.CRASH
    return Status.TIMEOUT if isinstance(exc, StepTimeoutError) else Status.ERROR


def _broke(
    report: CaseReport,
    trace: Trace,
    strict: bool,
    divergences: Sequence[KnownDivergence] | None,
) -> None:
    """Records a backend that broke: its status, and why the case stopped early.

    A crash or a timeout of an isolated backend is recoverable (a new worker
    takes over); one that a known divergence expects of that backend's own
    release is ``xfail``, unless ``strict``.
    """
    assert trace.broken is not None
    status = _broken_status(trace.broken)
    report.broken[trace.name] = status
    isolated = bool(getattr(trace.backend, "isolated", False))
    recoverable = isolated and status is not Status.ERROR
    report.recoverable = (report.aborted is None or report.recoverable) and recoverable
    report.aborted = "; ".join(filter(None, (report.aborted, str(trace.broken))))
    me = backend_id(trace.backend)
    known = None if strict else match_case(report.case.qualified_name, me, me.version, divergences)
    if known is not None and recoverable:
        report.xfails[trace.name] = known.id
        status = Status.XFAIL
    report.status[trace.name] = status


def binding_gap(report: CaseReport, backend: str) -> str | None:
    """The first step ``backend`` answered with an error of kind ``binding`` (its Python
    bindings lack the call, or the keywords, the step uses), if any."""
    trace = report.traces.get(backend)
    if trace is None:
        return None
    for step, result in zip(report.case.steps, trace.results, strict=False):
        if result.error is not None and result.error.kind is ErrorKind.BINDING:
            return f"{step.label} ({step.op}): {result.error.message}"
    return None


def _status(
    report: CaseReport,
    backend: BackendId,
    release: str,
    strict: bool,
    divergences: Sequence[KnownDivergence] | None,
) -> Status:
    """PASS, or, for a backend with failures: SKIP if it is a Drake release whose bindings
    lack a call the case makes (it cannot run the case; an implementation's missing
    binding is a failure), XFAIL if a known divergence expects them, else FAIL."""
    if not report.failures_of(backend.name):
        return Status.PASS
    gap = binding_gap(report, backend.name)
    if gap is not None and backend.name.startswith(_DRAKE_NAMES):
        report.skip_reasons[backend.name] = f"no binding: {gap}"
        return Status.SKIP
    if strict:
        return Status.FAIL
    known = match_case(report.case.qualified_name, backend, release, divergences)
    if known is None:
        return Status.FAIL
    report.xfails[backend.name] = known.id
    return Status.XFAIL
