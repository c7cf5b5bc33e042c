"""A Hypothesis state machine that drives two backends in lockstep.

``LockstepMachine`` sends every command to the backend under test and to the
reference backend. It compares the two Results after each command, and an
``@invariant`` compares the whole canonical state (``Backend.observe()``: C
for the model and for every context, IsActive of every declaration label,
``has_transient_history()``) after every step. Any disagreement raises
``Divergence``, which carries the command sequence so far and the reference's
answers, so a shrunk failure can be written out as a scenario case
(``conformance.fuzz.regression``).

Each Hypothesis step runs ``operations_per_step`` (2) rows of the
``OPERATIONS`` table (``conformance.fuzz.operations``), chosen among those enabled
at the start of the step, through the one rule ``command``; the state is
compared after each operation. Every scenario command is issued by some
operation. An operation byte of 0 plans no operation, so the shrinker can drop
one operation of a step. Each example starts with ``scene``, which registers a
drawn scene and switches off a drawn share of the operations for the whole
example (swarm testing, as Hypothesis does for rules; it shrinks to all on).

Bundles hold *names*, exactly as the scenario grammar uses them:

========== ============================================================
sources    ``source`` (the implicit source) and further sources
frames     ``world`` and registered frames
geometries registered geometries; a removed one stays (its id goes stale)
filter_ids labels of transient declarations (the FilterIds behind them)
contexts   contexts made by create_context / clone_context
========== ============================================================

``self.names`` holds the same names, in the same order, and ``keep`` files a
new name in both. The operations read names from ``self.names`` by picks;
rules a subclass adds may take the Bundles as arguments as usual.

Why one rule over a table, picks rather than Bundle draws, and two
operations per step: Hypothesis, not the backends, was the fuzz loop's main
cost. Choosing among 22 rules costs it 5-20 choices per step (swarm flags and
rejection sampling), a Bundle argument four nested draws, an optional one
(``st.none() | bundle``) more still, and each step has a fixed cost on top.
Here a step is a few choices: its operations and their picks in one ``bytes``
choice, plus a declaration or set template where an operation needs one.
``benchmarks/bench_fuzz.py`` measures the result.

Subclass it to fuzz other pairs, to add operations (extend ``OPERATIONS``)
or to add rules; ``lockstep_machine()`` makes a subclass for two backend
factories.

``PosedLockstepMachine`` (``fuzz --poses``) is the same machine on posed
scenes: its initial scene gives every geometry a drawn shape (the six of
the grammar, a HalfSpace one time in 32) and pose, and every frame a pose
(``strategies.scenes(posed=True)``), and it runs ``POSED_OPERATIONS``: the
operations above, registration with shapes and poses, set_poses, every
QueryObject query in the model or a context, and near-touching offsets
(``operations.near_touch``). A query's value is compared as its grammar row
says (``CommandSpec.compare``: pair sets exactly, numbers within the
tolerances of ``conformance.tolerances``). Every machine follows the
commands in a ``PoseBook`` (``self.poses``); the unposed machine draws
exactly what it drew before posed scenes existed, so its seeds still
reproduce earlier findings.
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any, ClassVar, TypeVar

from hypothesis import note, reject, target
from hypothesis import strategies as st
from hypothesis.control import current_build_context
from hypothesis.errors import InvalidArgument
from hypothesis.stateful import Bundle, RuleBasedStateMachine, initialize, invariant, rule

from conformance.backends.calls import BackendError, Where, call
from conformance.backends.loader import load_backend
from conformance.compare import Difference, diff_observations, diff_results
from conformance.fuzz import operations as ops
from conformance.fuzz import strategies as cs
from conformance.fuzz.coverage import Coverage, CoverageBook
from conformance.fuzz.names import NameBook, register_scene
from conformance.fuzz.operations import PoseBook, planned_operation, register_posed_scene
from conformance.policy.divergences import match_step
from conformance.policy.guards import arm_guards
from conformance.protocol import (
    Backend,
    Command,
    Observation,
    Result,
    UnknownNameError,
    backend_id,
)

__all__ = [
    "Divergence",
    "FuzzStats",
    "HarnessAbort",
    "HarnessError",
    "LockstepMachine",
    "PosedLockstepMachine",
    "ShrinkTimeUp",
    "TraceStep",
    "interrupt_requested",
    "lockstep_machine",
    "planned_operation",
    "stop_point",
]

T = TypeVar("T")

#: Bytes of the swarm draw: a threshold, then one byte per operation (mod 31).
_SWARM_BYTES = 32


def _is_final_run() -> bool:
    """True while Hypothesis replays the example it reports (False outside a run)."""
    try:
        return bool(current_build_context().is_final)
    except InvalidArgument:
        return False


def _file(machine: RuleBasedStateMachine, bundle: str, values: Sequence[str]) -> None:
    """Adds ``values`` to the Hypothesis Bundle ``bundle`` from inside any rule.

    Hypothesis has no public call for this: only a rule's return value feeds
    the Bundle it targets, and one rule runs every operation here. So this
    uses the method that return path calls, ``_add_results_to_targets``
    (Hypothesis ≥ 6.132, the floor in pyproject.toml);
    ``tests/test_lockstep.py`` checks that the Bundles fill.
    """
    add: Callable[..., None] = machine._add_results_to_targets
    add((bundle,), list(values))


@dataclass(frozen=True)
class TraceStep:
    """One command and what each side returned."""

    command: Command
    reference: Result
    backend: Result


class Divergence(AssertionError):  # noqa: N818 (a finding, named as users say it)
    """The backend and the reference disagree after the last step of ``trace``."""

    def __init__(
        self,
        what: str,
        detail: str,
        trace: list[TraceStep],
        reference_state: Observation,
        backend_state: Observation,
    ) -> None:
        super().__init__(f"{what} after step {len(trace)}: {detail}")
        self.what = what
        self.detail = detail
        self.trace = list(trace)
        self.reference_state = reference_state
        self.backend_state = backend_state


class HarnessError(RuntimeError):
    """A backend broke (raised, returned the wrong type, or timed out), not a divergence.

    ``commands`` is the sequence that led there, the breaking command last:
    a reproducer (``conformance.fuzz.regression.write_reproducer``).
    """

    def __init__(self, message: str, commands: Sequence[Command] = ()) -> None:
        super().__init__(message)
        self.commands = list(commands)


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
    #: Seconds shrinking may take after the first divergence; None: no bound.
    shrink_seconds: float | None = None
    #: The state-space features reached (``conformance.fuzz.coverage``).
    coverage: Coverage = field(default_factory=Coverage)
    on_step: Callable[[FuzzStats], None] | None = field(default=None, repr=False)
    #: Called with every new ``best`` at once (for writing the finding before shrinking ends).
    on_best: Callable[[Divergence], None] | None = field(default=None, repr=False)

    def record(self, divergence: Divergence) -> None:
        """Counts ``divergence``; it becomes ``best`` if no longer than the best so far."""
        self.divergences_seen += 1
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


@cache
def _scenes(
    frames: tuple[int, int], geometries: tuple[int, int], posed: bool
) -> st.SearchStrategy[cs.Scene]:
    return cs.scenes(
        min_frames=frames[0],
        max_frames=frames[1],
        min_geometries=geometries[0],
        max_geometries=geometries[1],
        posed=posed,
    )


#: Bytes per operation in a step's draw: which operation, then its picks.
_SLOT = 1 + ops.PICKS_PER_STEP
_RUNNER = st.runner()  # built once: building a strategy on every draw costs

#: A step's plan: (operation, picks, drawn) for each of its operations.
Plan = list[tuple[str, bytes, tuple[Any, ...]]]


@st.composite
def _steps(draw: st.DrawFn) -> Plan:
    """The plan of one step: ``operations_per_step`` operations with their arguments.

    One ``bytes`` choice holds, per operation, which one (a byte: 0 is none,
    where it shrinks to; otherwise an index into the operations enabled at
    the start of the step) and its picks. The operations' own ``arguments``
    follow, drawn only for the operations chosen.
    """
    machine: LockstepMachine = draw(_RUNNER)
    head = draw(cs.picks(machine.operations_per_step * _SLOT))
    enabled = machine.enabled_operations()
    plan: Plan = []
    for at in range(0, len(head), _SLOT):
        name = planned_operation(head[at], enabled, machine.weights)
        if name is not None:
            drawn = tuple(draw(argument) for argument in machine.OPERATIONS[name].arguments)
            plan.append((name, head[at + 1 : at + _SLOT], drawn))
    return plan


class LockstepMachine(NameBook, RuleBasedStateMachine):
    """Runs the same commands on ``backend`` and ``reference``; see the module doc."""

    #: Zero-argument factories; a subclass sets them (``lockstep_machine`` does).
    backend_factory: ClassVar[Callable[[], Backend]] = staticmethod(lambda: load_backend("reimpl"))
    reference_factory: ClassVar[Callable[[], Backend]] = staticmethod(
        lambda: load_backend("pydrake")
    )
    stats: ClassVar[FuzzStats] = FuzzStats()
    #: Bounds (inclusive) on the initial scene's frames and geometries.
    scene_frames: ClassVar[tuple[int, int]] = (1, 4)
    scene_geometries: ClassVar[tuple[int, int]] = (2, 8)
    #: What a step can do (``conformance.fuzz.operations``); extend it in a subclass.
    OPERATIONS: ClassVar[dict[str, ops.Operation]] = ops.OPERATIONS
    #: The initial scene has shapes and poses (``PosedLockstepMachine``).
    posed: ClassVar[bool] = False
    #: Operations per Hypothesis step (each is compared on its own).
    operations_per_step: ClassVar[int] = 2
    _pair: ClassVar[tuple[Backend, Backend] | None] = None
    #: Report known divergences (``policy.divergences``) as divergences too.
    strict_divergences: ClassVar[bool] = False
    #: Seconds one backend call may take (``backends.calls``); None: no limit.
    step_timeout: ClassVar[float | None] = None

    sources = Bundle("sources")
    frames = Bundle("frames")
    geometries = Bundle("geometries")
    filter_ids = Bundle("filter_ids")
    contexts = Bundle("contexts")

    def __init__(self) -> None:
        stop_point(type(self).stats)
        super().__init__()
        self.backend, self.reference = self._backends()
        self.trace: list[TraceStep] = []
        start = time.perf_counter()
        self._call(self.backend, "reset", returns=object, where="reset")
        self._call(self.reference, "reset", returns=object, where="reset")
        type(self).stats.backend_seconds += time.perf_counter() - start
        #: How many commands of ``trace`` the last state comparison covered.
        self._agreed_upto = 0
        shared = self.backend.features() & self.reference.features()
        #: Both backends have Activate/Deactivate.
        self.activation = "activation" in shared
        #: Both backends have the posed queries.
        self.queries = "queries" in shared
        #: Where every frame and geometry is (``operations.PoseBook``).
        self.poses = PoseBook()
        #: What the example reached (``coverage.CoverageBook``).
        self.coverage = CoverageBook()
        #: Operations switched off for this example (swarm testing).
        self.switched_off: frozenset[str] = frozenset()
        #: Each operation's weight for this example (swarm testing).
        self.weights: dict[str, int] = {}
        self._noting = _is_final_run()  # Hypothesis shows only the final replay's notes.
        type(self).stats.examples += 1

    @classmethod
    def _backends(cls) -> tuple[Backend, Backend]:
        """One backend pair per class, reset for every example."""
        if cls.__dict__.get("_pair") is None:
            cls._pair = (cls.backend_factory(), cls.reference_factory())
            arm_guards(cls._pair)
        assert cls._pair is not None
        return cls._pair

    # ------------------------------------------------------------- names
    def keep(self, bundle: str, *names: str) -> None:
        """Files ``names`` in ``self.names[bundle]`` and in the Bundle of that name."""
        if names:
            super().keep(bundle, *names)
            _file(self, bundle, names)

    def enabled_operations(self) -> list[str]:
        """The operations that can run now and are not switched off (all that can, if none)."""
        ready = [name for name, op in self.OPERATIONS.items() if op.enabled(self)]
        if not ready:
            raise HarnessError(f"{type(self).__name__}: no operation is enabled")
        return [name for name in ready if name not in self.switched_off] or ready

    # ------------------------------------------------------------- steps
    def _call(
        self,
        backend: Backend,
        method: str,
        *args: Any,
        returns: type[T],
        where: Where,
        command: Command | None = None,
    ) -> T:
        """``backends.calls.call``; a broken backend aborts the run (``HarnessAbort``)."""
        try:
            return call(
                backend, method, *args, where=where, returns=returns, timeout=self.step_timeout
            )
        except (BackendError, UnknownNameError) as exc:
            commands = [item.command for item in self.trace]
            if command is not None:
                commands.append(command)
            raise HarnessAbort(HarnessError(str(exc), commands)) from exc

    def _execute(self, backend: Backend, command: Command) -> Result:
        number = len(self.trace) + 1

        def where() -> str:  # formatted only if the call goes wrong
            return f"step {number} ({json.dumps(command.to_json())})"

        return self._call(backend, "execute", command, returns=Result, where=where, command=command)

    def step(self, op: str, **args: Any) -> Result:
        """Runs one command on both backends; raises Divergence if the Results differ."""
        command = Command(op, {k: v for k, v in args.items() if v is not None})
        if self._noting:
            note(json.dumps(command.to_json()))
        stats = type(self).stats
        start = time.perf_counter()
        got = self._execute(self.backend, command)
        want = self._execute(self.reference, command)
        stats.backend_seconds += time.perf_counter() - start
        stats.steps += 1
        self.trace.append(TraceStep(command, want, got))
        self.poses.record(command, want)
        stats.coverage.add(self.coverage.follow(command, want))
        differences = diff_results(want, got, op=op)
        if differences:
            self._diverge(differences, *self._observe())
        if stats.on_step is not None:
            stats.on_step(stats)
        return want

    def _observe(self) -> tuple[Observation, Observation]:
        stats = type(self).stats
        start = time.perf_counter()
        where = f"observe after step {len(self.trace)}"
        got = self._call(self.backend, "observe", returns=Observation, where=where)
        want = self._call(self.reference, "observe", returns=Observation, where=where)
        stats.backend_seconds += time.perf_counter() - start
        return got, want

    def _diverge(self, differences: list[Difference], got: Observation, want: Observation) -> None:
        """Raises Divergence; or, for a known divergence, rejects the example.

        A disagreement that a known divergence describes for the reference's
        release (``policy.divergences.match_step``) is counted in
        ``stats.known`` and the example is rejected, so the search goes on
        for unknown ones; ``strict_divergences`` makes it a Divergence.
        """
        stats = type(self).stats
        if not self.strict_divergences:
            # Any command since the state last agreed may be the one that diverged.
            for item in self.trace[self._agreed_upto :]:
                known = match_step(
                    item.command,
                    item.reference,
                    item.backend,
                    blamed=backend_id(self.backend),
                    release=self.reference.version(),
                )
                if known is not None:
                    stats.known[known.id] = stats.known.get(known.id, 0) + 1
                    reject()
        detail = "; ".join(str(d) for d in differences)
        divergence = Divergence(differences[0].what, detail, self.trace, want, got)
        stats.record(divergence)
        raise divergence

    @invariant()
    def same_state(self) -> None:
        """The whole canonical state agrees, for the model and every context."""
        got, want = self._observe()
        differences = diff_observations(want, got)
        if differences:
            self._diverge(differences, got, want)
        self._agreed_upto = len(self.trace)

    # ------------------------------------------------------------- rules
    @initialize(
        scene=_RUNNER.flatmap(
            lambda machine: _scenes(machine.scene_frames, machine.scene_geometries, machine.posed)
        ),
        swarm=cs.picks(_SWARM_BYTES),
    )
    def scene(self, scene: cs.Scene, swarm: bytes) -> None:
        """Registers a scene (``scene_frames``/``scene_geometries`` bound its size; posed
        scenes through ``operations.register_posed_scene``).

        ``swarm`` weighs the operations for the example (swarm testing): byte
        0 is a threshold, and operation i, whose byte is ``b = swarm[1 + i mod
        31]``, is off when ``b`` is below it, else has the weight ``1 + b // 64``
        (1-4; ``planned_operation``). Both shrink towards 0, so towards every
        operation on, all of weight 1.
        """
        threshold = swarm[0]
        weights = {
            name: swarm[1 + i % (_SWARM_BYTES - 1)] for i, name in enumerate(self.OPERATIONS)
        }
        self.switched_off = frozenset(name for name, b in weights.items() if b < threshold)
        self.weights = {name: 1 + b // 64 for name, b in weights.items()}
        (register_posed_scene if self.posed else register_scene)(self, scene)
        self.coverage.sequence_started = True

    def teardown(self) -> None:
        """Takes the example's maxima into the run's coverage, and steers towards the rare.

        ``hypothesis.target`` (the ``target`` phase) then favours examples
        that crowd a location, stack transient declarations, and reach the
        compound features (``CoverageBook.targets``).
        """
        book = self.coverage
        type(self).stats.coverage.close(book)
        for label, score in book.targets().items():
            target(score, label=label)

    @rule(plan=_steps())
    def command(self, plan: Plan) -> None:
        """Runs the step's operations (``OPERATIONS``), comparing the state after each.

        An operation that an earlier one of the step disabled is left out.
        """
        for i, (name, picks, drawn) in enumerate(plan):
            if i:
                self.same_state()
            operation = self.OPERATIONS[name]
            if operation.enabled(self):
                operation.run(self, picks, *drawn)


class PosedLockstepMachine(LockstepMachine):
    """The lockstep machine on posed scenes, with the query ops (see the module doc)."""

    OPERATIONS: ClassVar[dict[str, ops.Operation]] = ops.POSED_OPERATIONS
    posed: ClassVar[bool] = True


def lockstep_machine(
    backend: Callable[[], Backend],
    reference: Callable[[], Backend],
    *,
    stats: FuzzStats | None = None,
    base: type[LockstepMachine] = LockstepMachine,
    scene_frames: tuple[int, int] | None = None,
    scene_geometries: tuple[int, int] | None = None,
    strict_divergences: bool = False,
    step_timeout: float | None = None,
    name: str = "Lockstep",
) -> type[LockstepMachine]:
    """A subclass of ``base`` for two backend factories, with its own stats.

    ``scene_frames`` and ``scene_geometries`` bound the initial scene (default:
    ``base``'s bounds); ``strict_divergences`` reports known divergences too;
    ``step_timeout`` bounds each backend call.
    """
    namespace: dict[str, Any] = {
        "backend_factory": staticmethod(backend),
        "reference_factory": staticmethod(reference),
        "stats": stats if stats is not None else FuzzStats(),
        "_pair": None,
        "strict_divergences": strict_divergences,
        "step_timeout": step_timeout,
    }
    if scene_frames is not None:
        namespace["scene_frames"] = scene_frames
    if scene_geometries is not None:
        namespace["scene_geometries"] = scene_geometries
    return type(name, (base,), namespace)
