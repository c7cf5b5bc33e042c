"""Runs one case on backends: expectations per backend, agreement with a reference.

The case runs on one ``Engine`` (``conformance._engine``): every backend
from a reset, step by step in lockstep, a worker answering the whole case in
one batch. Each backend leaves a ``Track``: the Result of every step and the
Observation after the observed ones. The steps are then checked: (1) each step's
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

from collections.abc import Callable, Iterator, Sequence

from conformance._backends.calls import BackendError
from conformance._corpus.loader import Case, Step
from conformance._engine import (
    Engine,
    Outcome,
    Plan,
    StepRecord,
    Trace,
    Track,
    step_differences,
)
from conformance._grammar import spec
from conformance._policy.divergences import KnownDivergence
from conformance._run.case_report import CaseReport, Failure
from conformance._run.drake_log import drake_log_of_case
from conformance._run.expectations import applies, check
from conformance._run.verdict import DRAKE_NAMES, judge
from conformance.protocol import (
    Backend,
    Command,
    ErrorKind,
    UnknownNameError,
)

__all__ = [
    "BackendError",
    "CaseReport",
    "Failure",
    "choose_reference",
    "reference_name",
    "run_case",
    "trace_disagreements",
]


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
    return next((n for n in names if n.startswith(DRAKE_NAMES)), names[0])


def _observed_steps(steps: Sequence[Step]) -> list[bool]:
    """Whether the state is observed after each step (see the module doc)."""
    return [
        bool(step.expect) or step.index != 0 or i + 1 == len(steps) or steps[i + 1].index != 0
        for i, step in enumerate(steps)
    ]


def _plans(case: Case) -> list[Plan]:
    observed = _observed_steps(case.steps)
    return [
        Plan(None if step.op == "check" else Command(step.op, step.args), look, step.label)
        for step, look in zip(case.steps, observed, strict=True)
    ]


def _expectation_failures(
    step: Step, index: int, backend: Backend, record: StepRecord
) -> Iterator[Failure]:
    """The step's expectations (observed steps only: a step with any is observed), and a
    scene registration that failed."""
    result, observation = record.results[backend.name], record.observations[backend.name]
    if observation is not None:
        for expectation in step.expect:
            if applies(expectation, backend.version()):
                for what, expected, actual in check(step, expectation, result, observation):
                    yield Failure(step.label, what, expected, actual, backend.name, index=index)
    if step.index == 0 and result.error is not None:
        what = f"scene {step.op} {step.args.get('name')}"
        yield Failure(step.label, what, None, result.error.to_json(), backend.name, index=index)


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
    active = _able(case, backends, report)
    if not active:
        return report
    ref = oracle if oracle in active else active[0]
    report.reference = ref.name if len(active) > 1 else None
    total, done = len(case.steps) * len(active), 0

    def answered() -> None:
        nonlocal done
        done += 1
        if on_step is not None:
            on_step(done, total)

    engine = Engine(
        active, ref.name, step_timeout=step_timeout, crash_isolated=True, on_answer=answered
    )  # one engine per case: its guards are those of this case's backends
    try:
        with drake_log_of_case() as report.log:
            engine.reset()
            for record in engine.run(_plans(case)):
                step = case.steps[record.index]
                for backend in active:
                    if backend.name in record.results:
                        report.failures.extend(
                            _expectation_failures(step, record.index, backend, record)
                        )
    except UnknownNameError as exc:
        where = f"{exc.where}: " if exc.where else ""
        report.aborted = f"{where}{exc} (the case names something no earlier step made)"
        return report
    report.trace = engine.trace
    report.traces = dict(engine.tracks)
    if bad_models_are_input_errors:
        report.aborted = _bad_model(case, engine.trace, [b.name for b in active], ref.name)
        if report.aborted is not None:
            report.failures.clear()
            return report
    if report.reference is not None:
        for other in active:
            if other is not ref:
                report.failures.extend(_step_failures(case, engine.trace, ref.name, other.name))
    judge(report, engine, strict_divergences, divergences)
    return report


def _able(case: Case, backends: Sequence[Backend], report: CaseReport) -> list[Backend]:
    """The backends whose features cover the case; the others are skipped, saying why."""
    able: list[Backend] = []
    for backend in backends:
        missing = case.features - backend.features()
        if missing:
            report.status[backend.name] = Outcome.SKIP
            report.skip_reasons[backend.name] = f"needs feature(s) {', '.join(sorted(missing))}"
        else:
            able.append(backend)
    return able


def _bad_model(case: Case, trace: Trace, names: Sequence[str], ref: str) -> str | None:
    """Why the case's model is bad, if a model step failed on every backend unexpectedly.

    A user's model that Drake rejects (an unknown link in a group, an
    undefined group, a malformed file) is an input error, not a conformance
    result, unless the step expects an error: then the case tests it. If the
    backends disagree, it is a conformance failure, and the comparison says so.
    A binding error (the release lacks a call, e.g. RpyFloatingJoint before 1.27)
    is no bad model, nor is what follows it (a rename that was not made leaves a
    name taken): the verdict skips the case on that release (``binding_gap``).
    """
    names = [ref, *(n for n in names if n != ref)]  # the reference first
    for record in trace.records:
        step = case.steps[record.index]
        errors = [record.results[n].error for n in names if n in record.results]
        if any(e is not None and e.kind is ErrorKind.BINDING for e in errors):
            return None
        if spec(step.op).domain != "model" or any("error" in e for e in step.expect):
            continue
        if errors and len(errors) == len(names) and errors[0] is not None and all(errors):
            return (
                f"{step.label} ({step.op}): the model is invalid on {names[0]}: "
                f"{errors[0].message} (a case that tests this error says so with "
                '"expect": {"error": ...})'
            )
    return None


def _step_failures(case: Case, trace: Trace, reference: str, other: str) -> Iterator[Failure]:
    """``other``'s differences from ``reference``, step by step, where both answered."""
    for record in trace.records:
        if reference in record.results and other in record.results:
            label = case.steps[record.index].label
            for d in step_differences(record, reference, other):
                yield Failure(label, d.what, d.reference, d.other, other, reference, record.index)


def trace_disagreements(
    case: Case, reference: Track, other: Track, *, ends: bool = False
) -> list[Failure]:
    """``other``'s differences from ``reference``, step by step, where both answered (two
    Tracks of one case, e.g. two releases' runs); with ``ends``, a track that ends earlier
    than the other (it broke) is one too."""
    plans = _plans(case)
    trace = Trace(reference.name)
    for index, plan in enumerate(plans):
        if reference.covers(index) and other.covers(index):
            trace.records.append(
                StepRecord(
                    index,
                    plan,
                    {reference.name: reference.results[index], other.name: other.results[index]},
                    {
                        reference.name: reference.observations[index],
                        other.name: other.observations[index],
                    },
                )
            )
    failures = list(_step_failures(case, trace, reference.name, other.name))
    if ends and len(reference.results) != len(other.results):
        failures.append(
            Failure(
                "end",
                "steps answered",
                _ended(reference, len(case.steps)),
                _ended(other, len(case.steps)),
                other.name,
                reference.name,
                len(case.steps),
            )
        )
    return failures


def _ended(track: Track, total: int) -> str:
    if track.broken is None:
        return f"all {total}"
    return f"{len(track.results)} of {total}: {type(track.broken).__name__} at {track.broken.where}"
