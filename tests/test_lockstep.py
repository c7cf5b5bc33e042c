"""The lockstep state machine: reimpl and real pydrake agree; a faulty backend is caught."""

from __future__ import annotations

from typing import Any, ClassVar

import pytest
from hypothesis import HealthCheck, Phase, settings
from hypothesis.stateful import rule, run_state_machine_as_test

from conformance._backends.loader import load_backend
from conformance._engine import Divergence
from conformance._fuzz.campaign import fuzz_settings
from conformance._fuzz.lockstep import LockstepMachine, lockstep_machine
from conformance._fuzz.operations import (
    HAND_WRITTEN,
    OPERATIONS,
    Operation,
    generic_operation,
    issued_ops,
    planned_operation,
)
from conformance._fuzz.stats import FuzzStats
from conformance._fuzz.strategies import DeclarationTemplate, GeometrySpec, Scene
from conformance._grammar import GRAMMAR, ops_of
from conformance._testing.mutants import mutant_backend
from conformance.protocol import Backend, Command, Result

SETTINGS = settings(
    max_examples=40,
    stateful_step_count=25,
    deadline=None,
    database=None,
    derandomize=True,  # a fixed search: coverage of every op must not depend on luck
    suppress_health_check=list(HealthCheck),
)
REIMPL = load_backend("reimpl")
PYDRAKE = load_backend("pydrake")


def test_reimpl_and_pydrake_agree_step_by_step_in_the_lockstep_machine() -> None:
    stats = FuzzStats()
    machine = lockstep_machine(lambda: REIMPL, lambda: PYDRAKE, stats=stats)
    run_state_machine_as_test(machine, settings=SETTINGS)
    assert stats.examples >= 40
    assert stats.steps > stats.examples  # examples are sequences, not single calls
    assert stats.divergences_seen == 0


class RecordingMachine(LockstepMachine):
    """Records the op of every command it issues."""

    backend_factory = staticmethod(lambda: REIMPL)
    reference_factory = staticmethod(lambda: PYDRAKE)
    stats = FuzzStats()
    _shared = None
    issued: ClassVar[set[str]] = set()

    def step(self, op: str, **args: Any) -> Result:
        type(self).issued.add(op)
        return super().step(op, **args)


def test_the_operations_issue_every_scenario_command_but_activation_on_pydrake_1_51() -> None:
    run_state_machine_as_test(RecordingMachine, settings=settings(SETTINGS, max_examples=80))
    activation = "activation" in PYDRAKE.features()
    unsupported = set() if activation else {"activate", "deactivate"}
    assert RecordingMachine.issued == COMMANDS - unsupported


#: The ops the lockstep machine drives: the grammar's SceneGraph ops.
COMMANDS = {op for op in ops_of("scene_graph") if not GRAMMAR[op].harness_only}


def test_the_operations_table_says_it_issues_every_grammar_op() -> None:
    assert issued_ops(OPERATIONS) == COMMANDS
    assert set(HAND_WRITTEN) <= set(OPERATIONS)


class GenericOnlyMachine(RecordingMachine):
    """Only the operations derived from the grammar: what a new op gets with no hand-written one."""

    stats = FuzzStats()
    _shared = None
    issued: ClassVar[set[str]] = set()
    OPERATIONS: ClassVar[dict[str, Operation]] = {
        op: generic_operation(GRAMMAR[op]) for op in sorted(COMMANDS)
    }


def test_operations_derived_from_the_grammar_alone_issue_every_op_and_agree_with_pydrake() -> None:
    run_state_machine_as_test(GenericOnlyMachine, settings=SETTINGS)
    unsupported = set() if "activation" in PYDRAKE.features() else {"activate", "deactivate"}
    assert GenericOnlyMachine.issued == COMMANDS - unsupported
    assert GenericOnlyMachine.stats.divergences_seen == 0


class BundleReadingMachine(LockstepMachine):
    """A subclass rule draws names from the Bundles, as Hypothesis users do."""

    backend_factory = staticmethod(lambda: REIMPL)
    reference_factory = staticmethod(lambda: PYDRAKE)
    stats = FuzzStats()
    _shared = None
    drawn: ClassVar[dict[str, set[str]]] = {"frames": set(), "geometries": set()}

    @rule(frame=LockstepMachine.frames, geometry=LockstepMachine.geometries)
    def query(self, frame: str, geometry: str) -> None:
        assert frame in self.names["frames"]
        assert geometry in self.names["geometries"]
        type(self).drawn["frames"].add(frame)
        type(self).drawn["geometries"].add(geometry)
        self.step("collision_filtered", pair=[geometry, geometry])


def test_the_bundles_hold_the_names_the_operations_make() -> None:
    run_state_machine_as_test(BundleReadingMachine, settings=SETTINGS)
    drawn = BundleReadingMachine.drawn
    assert "world" in drawn["frames"]
    # Scene frames are f1, f2, ...; frames registered by operations come later.
    assert any(name.startswith("f") for name in drawn["frames"])
    assert any(name.startswith("g") for name in drawn["geometries"])
    assert BundleReadingMachine.stats.divergences_seen == 0


def _ping(machine: LockstepMachine, picks: bytes) -> None:
    PingMachine.pings += 1
    machine.step("is_active", label=machine.name("label", picks[0]))


class PingMachine(LockstepMachine):
    """A subclass adds an operation to the table."""

    backend_factory = staticmethod(lambda: REIMPL)
    reference_factory = staticmethod(lambda: PYDRAKE)
    stats = FuzzStats()
    _shared = None
    OPERATIONS: ClassVar[dict[str, Operation]] = {
        **LockstepMachine.OPERATIONS,
        "ping": Operation(_ping),
    }
    pings = 0


def test_a_subclass_can_add_operations() -> None:
    run_state_machine_as_test(PingMachine, settings=SETTINGS)
    assert PingMachine.pings > 0
    assert PingMachine.stats.divergences_seen == 0


def _started(backend: Backend) -> LockstepMachine:
    """A machine on ``backend`` and pydrake with one frame and two geometries on it."""
    machine = lockstep_machine(lambda: backend, lambda: PYDRAKE)()
    scene = Scene(
        frames=(("f1", None),),
        geometries=(
            GeometrySpec("g1", "f1", ("proximity",)),
            GeometrySpec("g2", "f1", ("proximity",)),
        ),
    )
    machine.scene(scene, swarm=bytes(32))
    return machine


def test_a_step_compares_the_state_after_each_of_its_operations() -> None:
    machine = _started(mutant_backend("allow_clears_invariants"))
    # Both geometries sit on f1: the pair is filtered by Drake's invariant.
    allow_all = DeclarationTemplate(
        geometries=(0, 1), frames=(), statements=(("allow_within", (0b11,)),)
    )
    with pytest.raises(Divergence) as caught:
        machine.command(
            [("apply", bytes(4), (allow_all,)), ("has_transient_history", bytes(4), ())]
        )
    ops = [step.command.op for step in caught.value.trace]
    assert ops[-1] == "apply", "caught before the step's second operation ran"


def test_operation_byte_zero_is_no_operation_and_others_cycle_through_the_enabled() -> None:
    enabled = ["is_active", "apply", "create_context"]
    assert planned_operation(0, enabled) is None
    assert [planned_operation(b, enabled) for b in (1, 2, 3, 4, 255)] == [
        "is_active",
        "apply",
        "create_context",
        "is_active",
        "create_context",  # 254 % 3 == 2
    ]


def test_a_faulty_backend_raises_divergence_with_the_reference_answers() -> None:
    stats = FuzzStats()
    machine = lockstep_machine(
        lambda: mutant_backend("reverse_statement_order"), lambda: PYDRAKE, stats=stats
    )
    # Not shrunk: this mutant's divergence shrinks for minutes, and shrinking is
    # the mutant tests' subject (tests/test_fuzz_mutants.py), not this one's.
    unshrunk = settings(
        fuzz_settings(max_examples=300, steps=25),
        phases=(Phase.explicit, Phase.reuse, Phase.generate, Phase.target),
    )
    with pytest.raises(Divergence) as caught:
        run_state_machine_as_test(machine, settings=unshrunk)
    divergence = caught.value
    assert divergence.trace, "the shrunk sequence is not empty"
    assert any(s.command.op in ("apply", "apply_transient") for s in divergence.trace)
    assert "model" in divergence.reference_state.locations
    assert divergence.reference_state != divergence.backend_state or (
        len(set(map(str, divergence.trace[-1].results.values()))) > 1
    )
    assert stats.best is not None


class CountingMachine(LockstepMachine):
    """A subclass adds a rule; the lockstep checks still run after it."""

    backend_factory = staticmethod(lambda: REIMPL)
    reference_factory = staticmethod(lambda: PYDRAKE)
    stats = FuzzStats()
    _shared = None
    extra_calls = 0

    @rule()
    def check_everything(self) -> None:
        type(self).extra_calls += 1
        self.step("has_transient_history")


def test_a_subclass_can_add_rules_that_run_in_lockstep() -> None:
    run_state_machine_as_test(CountingMachine, settings=SETTINGS)
    assert CountingMachine.extra_calls > 0
    assert CountingMachine.stats.divergences_seen == 0


def test_step_records_the_command_and_both_results() -> None:
    machine = lockstep_machine(lambda: REIMPL, lambda: PYDRAKE)()
    result = machine.step("remove_declaration", label="@unknown")
    assert result.value is False
    assert machine.trace[-1].command == Command("remove_declaration", {"label": "@unknown"})
    assert machine.trace[-1].results[machine.backend.name].value is False
    assert machine.trace[-1].results[machine.reference.name].value is False
