"""The engine: drives backends in lockstep, step by step, and says where they differ.

Both ``run`` (a scenario case) and ``fuzz`` (a Hypothesis state machine)
drive their backends through one ``Engine``; nothing else calls a backend.

``Engine(backends, reference)`` resets every backend, then runs steps. A
step is one ``Command`` (or none: a ``check`` step) and whether to observe
the state after it. Each step gives a ``StepRecord``: every backend's
``Result``, its ``Observation`` if asked, and the backends that broke there.
``differences(record)`` compares every other backend with the *reference*
(the oracle of the run) through ``conformance.compare``:

====================================  =========================================
both answered and were observed       ``compare.diff``: Result and whole state
both answered, not observed           ``compare.diff_results``
either broke or did not answer        nothing to compare (the caller decides)
====================================  =========================================

A backend that breaks (raises, answers the wrong type, times out, or its
worker process dies: ``backends.calls``) is recorded in the step's
``broken`` and answers no later step until the next ``reset``; the others go
on. A step that names something no earlier step made (``UnknownNameError``)
is the input's fault, not a backend's: it is raised, naming the step.

**Batching.** A backend that ``run_steps`` (a worker in its own process,
``protocol.BatchingBackend``) gets all the steps of ``run(plans)`` in one
request and streams its answers back; the others are called step by step.
``step`` is ``run`` of one.

**Guards.** The engine arms the release guards (``policy.guards``) the
backends' releases need, once, when it is made: with ``crash_isolated``, the
releases of isolated backends (workers, whose crash loses nothing) arm
none.

**Divergences.** ``divergence(record)`` is the one finding type of both
commands: a backend's differences from the reference at a step, and the
known divergence (``policy.divergences``) that explains them, if any.
``Trace.to_case(description)`` turns the steps run so far into a scenario
case whose expectations are the reference's answers, so what the fuzzer
finds is a case ``run`` replays.
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from conformance._backends.calls import (
    BackendCrashError,
    BackendError,
    StepTimeoutError,
    call,
    call_function,
)
from conformance._corpus.case_writer import case_of
from conformance._policy.divergences import KnownDivergence, match_step
from conformance._policy.guards import arm_guards
from conformance.compare import Difference, diff, diff_observations, diff_results
from conformance.protocol import (
    Backend,
    BackendId,
    BatchingBackend,
    Command,
    Observation,
    Result,
    UnknownNameError,
    backend_id,
)

__all__ = [
    "Divergence",
    "Engine",
    "HarnessError",
    "Outcome",
    "Plan",
    "StepRecord",
    "Trace",
    "Track",
    "known_in",
    "outcome_of_break",
    "step_differences",
]


class Outcome(enum.Enum):
    """What a backend's run of a case (or a campaign) came to."""

    PASS = "pass"
    FAIL = "fail"
    XFAIL = "xfail"  # failed as a known divergence says it does
    SKIP = "skip"
    ERROR = "error"  # the backend broke: raised, returned the wrong type
    TIMEOUT = "timeout"  # a call took longer than the step timeout
    CRASH = "crash"  # the backend's process died (a worker backend)


def outcome_of_break(exc: BackendError) -> Outcome:
    """CRASH, TIMEOUT or ERROR: how a backend broke."""
    if isinstance(exc, BackendCrashError):
        return Outcome.CRASH
    return Outcome.TIMEOUT if isinstance(exc, StepTimeoutError) else Outcome.ERROR


@dataclass(frozen=True)
class Plan:
    """One step to run: its command (None: a ``check`` step), observed or not, its label."""

    command: Command | None
    observe: bool = False
    label: str = ""


@dataclass(frozen=True)
class StepRecord:
    """Every backend's answer to one step, by backend name."""

    index: int
    plan: Plan
    results: Mapping[str, Result]
    observations: Mapping[str, Observation | None]
    broken: Mapping[str, BackendError] = field(default_factory=dict)

    @property
    def command(self) -> Command | None:
        return self.plan.command

    @property
    def label(self) -> str:
        return self.plan.label or f"step {self.index + 1}"


@dataclass
class Track:
    """One backend's answers, step by step: a Result per step it answered, the Observation
    after each observed one (None after the others), and the error that ended it early."""

    backend: Backend
    results: list[Result] = field(default_factory=list)
    observations: list[Observation | None] = field(default_factory=list)
    broken: BackendError | None = None

    @property
    def name(self) -> str:
        return self.backend.name

    def covers(self, index: int) -> bool:
        return index < len(self.results)


@dataclass
class Trace:
    """The steps an engine ran since its last reset, and who the reference was."""

    reference: str
    records: list[StepRecord] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.records)

    def __iter__(self) -> Iterator[StepRecord]:
        return iter(self.records)

    def __getitem__(self, index: int) -> StepRecord:
        return self.records[index]

    @classmethod
    def of(
        cls, reference: str, other: str, steps: Iterable[tuple[Command, Result, Result]]
    ) -> Trace:
        """The trace of ``steps``: each command with the reference's and the other's Result."""
        return cls(
            reference,
            [
                StepRecord(i, Plan(command), {reference: mine, other: theirs}, {})
                for i, (command, mine, theirs) in enumerate(steps)
            ],
        )

    def commands(self) -> list[Command]:
        """The commands run (a ``check`` step's too), in order."""
        return [_command(r) for r in self.records]

    def to_case(
        self,
        description: str,
        *,
        other: str | None = None,
        states: Mapping[str, Observation] | None = None,
        releases: tuple[str, str] | None = None,
    ) -> dict[str, Any]:
        """The scenario case of these steps, with the reference's answers as expectations.

        ``states``: the backends' states after the last step (the last step
        expects the reference's). ``other`` and ``releases``: when the
        reference and ``other`` are two Drake releases (reference's, other's),
        where they answered differently each answer holds for its own release
        (``corpus.case_writer``).
        """
        states = states or {}
        sides = [self.reference] if other is None else [self.reference, other]
        return case_of(
            description,
            self.commands(),
            {name: [r.results[name] for r in self.records] for name in sides},
            {name: states.get(name) for name in sides},
            releases=releases,
        )


def _command(record: StepRecord) -> Command:
    return Command("check", {}) if record.command is None else record.command


def known_in(
    trace: Trace,
    backend: BackendId,
    release: str,
    *,
    since: int = 0,
    case: str | None = None,
) -> KnownDivergence | None:
    """The known divergence that a disagreement of ``backend`` at a step of ``trace`` from
    ``since`` on is, for ``release`` (the reference's); the first step one explains."""
    for record in trace.records[since:]:
        if record.command is None or backend.name not in record.results:
            continue
        known = match_step(
            record.command,
            record.results.get(trace.reference),
            record.results[backend.name],
            blamed=backend,
            release=release,
            case=case,
        )
        if known is not None:
            return known
    return None


class Divergence(AssertionError):  # noqa: N818 (a finding, named as users say it)
    """``backend`` differs from the reference at the last step of ``trace``.

    ``differences`` are the reference's value against the backend's (Results
    first, then states); ``known`` is the known divergence that explains
    them, or None; ``states`` the two states when they were compared.
    """

    def __init__(
        self,
        backend: str,
        trace: Trace,
        differences: Sequence[Difference],
        *,
        known: KnownDivergence | None = None,
        states: Mapping[str, Observation] | None = None,
    ) -> None:
        self.backend = backend
        self.trace = trace
        self.differences = tuple(differences)
        self.known = known
        self.states = dict(states or {})
        super().__init__(f"{self.what} after step {len(trace)}: {self.detail}")

    @property
    def record(self) -> StepRecord:
        return self.trace.records[-1]

    @property
    def what(self) -> str:
        return self.differences[0].what if self.differences else "the answers differ"

    @property
    def detail(self) -> str:
        return "; ".join(str(d) for d in self.differences)

    @property
    def reference_state(self) -> Observation | None:
        return self.states.get(self.trace.reference)

    @property
    def backend_state(self) -> Observation | None:
        return self.states.get(self.backend)


class HarnessError(RuntimeError):
    """A backend broke (raised, returned the wrong type, or timed out), not a divergence.

    ``commands`` is the sequence that led there, the breaking command last:
    a reproducer (``conformance._fuzz.regression.write_reproducer``).
    ``outcome`` says how it broke (ERROR, TIMEOUT or CRASH; None: another fault).
    """

    def __init__(
        self, message: str, commands: Sequence[Command] = (), outcome: Outcome | None = None
    ) -> None:
        super().__init__(message)
        self.commands = list(commands)
        self.outcome = outcome


class Engine:
    """Drives ``backends`` in lockstep against ``reference`` (see the module doc).

    ``reference``: the name of the reference backend (default: the first).
    ``step_timeout``: seconds one call may take (None: no limit).
    ``crash_isolated``: only the in-process backends' releases arm guards.
    ``on_answer``: called after each backend's answer to each step (progress).
    """

    def __init__(
        self,
        backends: Sequence[Backend],
        reference: str | None = None,
        *,
        step_timeout: float | None = None,
        crash_isolated: bool = False,
        on_answer: Callable[[], None] | None = None,
    ) -> None:
        if not backends:
            raise ValueError("an engine needs at least one backend")
        self.backends = tuple(backends)
        names = [b.name for b in self.backends]
        self.reference = self.backends[names.index(reference)] if reference else self.backends[0]
        self.step_timeout = step_timeout
        self.on_answer = on_answer
        self.guards = arm_guards(self.backends, crash_isolated=crash_isolated)
        self.trace = Trace(self.reference.name)
        self.tracks = {b.name: Track(b) for b in self.backends}

    # ------------------------------------------------------------- state
    @property
    def live(self) -> list[Backend]:
        """The backends that have not broken since the last reset."""
        return [b for b in self.backends if self.tracks[b.name].broken is None]

    def reset(self) -> None:
        """Resets every backend; the trace starts again. A backend that breaks here is
        recorded as broken (it answers nothing until the next reset)."""
        self.trace = Trace(self.reference.name)
        self.tracks = {b.name: Track(b) for b in self.backends}
        for backend in self.backends:
            try:
                call(backend, "reset", where="reset", returns=object, timeout=self.step_timeout)
            except BackendError as exc:
                self.tracks[backend.name].broken = exc

    # ------------------------------------------------------------- steps
    def step(
        self, command: Command | None, *, observe: bool = False, label: str = ""
    ) -> StepRecord:
        """Runs one step on every live backend."""
        return next(self.run([Plan(command, observe, label)]))

    def run(self, plans: Sequence[Plan]) -> Iterator[StepRecord]:
        """Runs ``plans`` in order, yielding each step's record as soon as all answered.

        Batching backends get the whole sequence at once (see the module doc).
        """
        streams: dict[str, Iterator[tuple[Result, Observation | None]]] = {}
        for backend in self.live:
            if isinstance(backend, BatchingBackend):
                streams[backend.name] = iter(
                    backend.run_steps([(p.command, p.observe) for p in plans])
                )
        for plan in plans:
            index = len(self.trace.records)
            label = plan.label or f"step {index + 1}"
            results: dict[str, Result] = {}
            observations: dict[str, Observation | None] = {}
            broken: dict[str, BackendError] = {}
            for backend in self.live:
                try:
                    result, observation = self._answer(backend, plan, label, streams)
                except BackendError as exc:
                    broken[backend.name] = exc
                    self.tracks[backend.name].broken = exc
                    continue
                except UnknownNameError as exc:
                    exc.where = exc.where or f"{label} ({_op(plan)})"
                    raise
                results[backend.name] = result
                observations[backend.name] = observation
                track = self.tracks[backend.name]
                track.results.append(result)
                track.observations.append(observation)
                if self.on_answer is not None:
                    self.on_answer()
            record = StepRecord(index, plan, results, observations, broken)
            self.trace.records.append(record)
            yield record

    def _answer(
        self,
        backend: Backend,
        plan: Plan,
        label: str,
        streams: Mapping[str, Iterator[tuple[Result, Observation | None]]],
    ) -> tuple[Result, Observation | None]:
        """``backend``'s Result and Observation (if observed) for one step, checked by
        ``backends.calls``."""
        where = f"{label} ({_op(plan)})"
        timeout = self.step_timeout
        stream = streams.get(backend.name)
        if stream is not None:
            answer = call_function(
                backend,
                lambda: next(stream),
                "run_steps",
                where=where,
                returns=tuple,
                timeout=timeout,
            )
            result, observation = answer
            if not isinstance(result, Result) or not isinstance(observation, Observation | None):
                raise BackendError(backend.name, where, "run_steps answered the wrong types")
            return result, observation
        result = Result()
        if plan.command is not None:
            result = call(
                backend, "execute", plan.command, where=where, returns=Result, timeout=timeout
            )
        observation = None
        if plan.observe:
            observation = call(
                backend, "observe", where=f"{where}, observe", returns=Observation, timeout=timeout
            )
        return result, observation

    def observe(self) -> dict[str, Observation]:
        """Every live backend's state now, by name; a backend that breaks is recorded."""
        where = f"observe after step {len(self.trace)}"
        states: dict[str, Observation] = {}
        for backend in self.live:
            try:
                states[backend.name] = call(
                    backend, "observe", where=where, returns=Observation, timeout=self.step_timeout
                )
            except BackendError as exc:
                self.tracks[backend.name].broken = exc
        return states

    # ------------------------------------------------------------- comparing
    def differences(self, record: StepRecord) -> dict[str, list[Difference]]:
        """Each other backend's differences from the reference at ``record`` (see the
        module doc's table), by name; backends that did not answer are left out."""
        ref = self.reference.name
        if ref not in record.results:
            return {}
        return {name: step_differences(record, ref, name) for name in record.results if name != ref}

    def state_differences(self, states: Mapping[str, Observation]) -> dict[str, list[Difference]]:
        """Each other backend's state differences from the reference's, by name."""
        ref = states.get(self.reference.name)
        if ref is None:
            return {}
        return {
            name: diff_observations(ref, state)
            for name, state in states.items()
            if name != self.reference.name
        }

    def known(self, backend: str, since: int = 0) -> KnownDivergence | None:
        """The known divergence that a disagreement of ``backend`` at a step from ``since`` on
        is, for the reference's release (``known_in``)."""
        blamed = backend_id(next(b for b in self.backends if b.name == backend))
        return known_in(self.trace, blamed, self.reference.version(), since=since)


def step_differences(record: StepRecord, reference: str, other: str) -> list[Difference]:
    """``other``'s differences from ``reference`` at ``record`` (both must have answered)."""
    op = _op(record.plan)
    ours, theirs = record.results[reference], record.results[other]
    seen, seen_other = record.observations.get(reference), record.observations.get(other)
    if seen is not None and seen_other is not None:
        return diff((ours, seen), (theirs, seen_other), op=op)
    return diff_results(ours, theirs, op=op)


def _op(plan: Plan) -> str:
    return "check" if plan.command is None else plan.command.op
