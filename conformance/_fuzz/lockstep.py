"""A Hypothesis state machine that drives two backends in lockstep.

``LockstepMachine`` sends every command to the backend under test and to the
reference backend. It compares the two Results after each command, and an
``@invariant`` compares the whole canonical state (``Backend.observe()``: C
for the model and for every context, IsActive of every declaration label,
``has_transient_history()``) after every step. Any disagreement raises
``Divergence``, which carries the command sequence so far and the reference's
answers, so a shrunk failure can be written out as a scenario case
(``conformance._fuzz.regression``).

Each Hypothesis step runs ``operations_per_step`` (2) rows of the
``OPERATIONS`` table (``conformance._fuzz.operations``), chosen among those enabled
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
operations per step: see ``conformance._fuzz.step_draws``.

Both machines also run the rows of ``across_locations`` (an order of events
across the model, contexts and clones, as one operation), after their own.

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
tolerances of ``conformance._tolerances``). Every machine follows the
commands in a ``PoseBook`` (``self.poses``); the unposed machine draws
exactly what it drew before posed scenes existed, so its seeds still
reproduce earlier findings.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import replace
from typing import Any, ClassVar

from hypothesis import note, reject, target
from hypothesis import strategies as st
from hypothesis.stateful import Bundle, RuleBasedStateMachine, initialize, invariant, rule

from conformance._backends.loader import load_backend
from conformance._engine import Divergence, Engine, HarnessError, Trace, outcome_of_break
from conformance._fuzz import operations as ops
from conformance._fuzz import strategies as cs
from conformance._fuzz.across_locations import with_orders
from conformance._fuzz.branch_coverage import example_feedback
from conformance._fuzz.coverage import CoverageBook
from conformance._fuzz.names import NameBook, register_scene
from conformance._fuzz.operations import PoseBook, register_posed_scene
from conformance._fuzz.sequence_coverage import SequenceBook
from conformance._fuzz.stats import FuzzStats, HarnessAbort, stop_point
from conformance._fuzz.step_draws import (
    SWARM_BYTES,
    StepPlan,
    file_in_bundle,
    is_final_run,
    scenes_of,
    step_plans,
)
from conformance._grammar import features_of
from conformance.compare import Difference
from conformance.protocol import Backend, Command, Observation, Result, UnknownNameError

__all__ = ["LockstepMachine", "PosedLockstepMachine", "lockstep_machine"]


def _supported(operations: dict[str, ops.Operation], shared: frozenset[str]) -> frozenset[str]:
    """The operations whose grammar ops (``issues``) need only features in ``shared``."""
    return frozenset(
        name for name, op in operations.items() if features_of(op.issues or {name}) <= shared
    )


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
    #: What a step can do (``conformance._fuzz.operations``); extend it in a subclass.
    OPERATIONS: ClassVar[dict[str, ops.Operation]] = with_orders(ops.OPERATIONS)
    #: The initial scene has shapes and poses (``PosedLockstepMachine``).
    posed: ClassVar[bool] = False
    #: Operations per Hypothesis step (each is compared on its own).
    operations_per_step: ClassVar[int] = 2
    _shared: ClassVar[Engine | None] = None
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
        self.engine = self._engine()
        self.backend, self.reference = self.engine.backends
        start = time.perf_counter()
        self.engine.reset()
        type(self).stats.backend_seconds += time.perf_counter() - start
        self._abort_if_broken(None)
        #: How many steps of the trace the last state comparison covered.
        self._agreed_upto = 0
        shared = self.backend.features() & self.reference.features()
        #: The operations whose grammar ops need only features both backends have (a backend
        #: with fewer features, such as an ``exec:`` one, is fuzzed on what it has).
        self.supported = _supported(type(self).OPERATIONS, shared)
        #: Both backends have Activate/Deactivate.
        self.activation = "activation" in shared
        #: Both backends have the posed queries.
        self.queries = "queries" in shared
        #: Where every frame and geometry is (``operations.PoseBook``).
        self.poses = PoseBook()
        #: What the example reached (``coverage.CoverageBook``).
        self.coverage = CoverageBook()
        #: Its consecutive located events (``sequence_coverage.SequenceBook``).
        self.sequence = SequenceBook()
        #: Operations switched off for this example (swarm testing).
        self.switched_off: frozenset[str] = frozenset()
        #: Each operation's weight for this example (swarm testing).
        self.weights: dict[str, int] = {}
        self._noting = is_final_run()  # Hypothesis shows only the final replay's notes.
        type(self).stats.examples += 1

    @classmethod
    def _engine(cls) -> Engine:
        """One engine (and backend pair) per class, reset for every example; every guard
        either backend's release needs is armed, as the fuzzer needs both alive."""
        if cls.__dict__.get("_shared") is None:
            backend, reference = cls.backend_factory(), cls.reference_factory()
            cls._shared = Engine(
                [backend, reference], reference.name, step_timeout=cls.step_timeout
            )
        assert cls._shared is not None
        return cls._shared

    @property
    def trace(self) -> Trace:
        """The commands run in this example, with both backends' answers."""
        return self.engine.trace

    # ------------------------------------------------------------- names
    def keep(self, bundle: str, *names: str) -> None:
        """Files ``names`` in ``self.names[bundle]`` and in the Bundle of that name."""
        if names:
            super().keep(bundle, *names)
            file_in_bundle(self, bundle, names)

    def enabled_operations(self) -> list[str]:
        """The operations that can run now and are not switched off (all that can, if none)."""
        ready = [
            name
            for name, op in self.OPERATIONS.items()
            if name in self.supported and op.enabled(self)
        ]
        if not ready:
            raise HarnessError(f"{type(self).__name__}: no operation is enabled")
        return [name for name in ready if name not in self.switched_off] or ready

    # ------------------------------------------------------------- steps
    def _abort_if_broken(self, command: Command | None) -> None:
        """A backend that broke ends the run at once (``HarnessAbort``, not a divergence)."""
        broken = [t.broken for t in self.engine.tracks.values() if t.broken is not None]
        if broken:
            error = broken[0]
            commands = self.trace.commands()
            if command is not None and (not commands or commands[-1] is not command):
                commands.append(command)
            raise HarnessAbort(HarnessError(str(error), commands, outcome_of_break(error)))

    def step(self, op: str, **args: Any) -> Result:
        """Runs one command on both backends; raises Divergence if the Results differ."""
        command = Command(op, {k: v for k, v in args.items() if v is not None})
        if self._noting:
            note(json.dumps(command.to_json()))
        stats = type(self).stats
        start = time.perf_counter()
        try:
            record = self.engine.step(command)
        except UnknownNameError as exc:
            commands = [*self.trace.commands(), command]
            raise HarnessAbort(HarnessError(str(exc), commands)) from exc
        stats.backend_seconds += time.perf_counter() - start
        self._abort_if_broken(command)
        stats.steps += 1
        want = record.results[self.reference.name]
        self.poses.record(command, want)
        stats.coverage.add(self.coverage.follow(command, want))
        self.sequence.follow(command, want)
        differences = self.engine.differences(record)[self.backend.name]
        if differences:
            self._diverge(differences, self._observe())
        if stats.on_step is not None:
            stats.on_step(stats)
        return want

    def _observe(self) -> dict[str, Observation]:
        stats = type(self).stats
        start = time.perf_counter()
        states = self.engine.observe()
        stats.backend_seconds += time.perf_counter() - start
        self._abort_if_broken(None)
        return states

    def _diverge(self, differences: list[Difference], states: dict[str, Observation]) -> None:
        """Raises Divergence; or, for a known divergence, rejects the example.

        A disagreement that a known divergence describes for the reference's
        release (``Engine.known``: any step since the state last agreed may be
        the one that diverged) is counted in ``stats.known`` and the example
        is rejected, so the search goes on for unknown ones;
        ``strict_divergences`` makes it a Divergence.
        """
        stats = type(self).stats
        if not self.strict_divergences:
            known = self.engine.known(self.backend.name, self._agreed_upto)
            if known is not None:
                stats.known[known.id] = stats.known.get(known.id, 0) + 1
                reject()
        divergence = Divergence(
            self.backend.name,
            replace(self.trace, records=list(self.trace.records)),
            differences,
            states=states,
        )
        stats.record(divergence)
        raise divergence

    @invariant()
    def same_state(self) -> None:
        """The whole canonical state agrees, for the model and every context."""
        states = self._observe()
        differences = self.engine.state_differences(states)[self.backend.name]
        if differences:
            self._diverge(differences, states)
        self._agreed_upto = len(self.trace)

    # ------------------------------------------------------------- rules
    @initialize(
        scene=st.runner().flatmap(
            lambda machine: scenes_of(machine.scene_frames, machine.scene_geometries, machine.posed)
        ),
        swarm=cs.picks(SWARM_BYTES),
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
        weights = {name: swarm[1 + i % (SWARM_BYTES - 1)] for i, name in enumerate(self.OPERATIONS)}
        self.switched_off = frozenset(name for name, b in weights.items() if b < threshold)
        self.weights = {name: 1 + b // 64 for name, b in weights.items()}
        (register_posed_scene if self.posed else register_scene)(self, scene)
        self.coverage.sequence_started = True

    def teardown(self) -> None:
        """Takes the example's maxima into the run's coverage, and steers towards the rare.

        ``hypothesis.target`` (the ``target`` phase) then favours examples
        that crowd a location, stack transient declarations, and reach the
        compound features (``CoverageBook.targets``); in a measuring campaign
        also the examples that take new reimpl branches
        (``branch_coverage.example_feedback``).
        """
        book = self.coverage
        type(self).stats.coverage.close(book)
        type(self).stats.sequences.close(self.sequence)
        for label, score in book.targets().items():
            target(score, label=label)
        example_feedback()

    @rule(plan=step_plans())
    def command(self, plan: StepPlan) -> None:
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

    OPERATIONS: ClassVar[dict[str, ops.Operation]] = with_orders(ops.POSED_OPERATIONS)
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
        "_shared": None,
        "strict_divergences": strict_divergences,
        "step_timeout": step_timeout,
    }
    if scene_frames is not None:
        namespace["scene_frames"] = scene_frames
    if scene_geometries is not None:
        namespace["scene_geometries"] = scene_geometries
    return type(name, (base,), namespace)
