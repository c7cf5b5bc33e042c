"""The lockstep state machine: reimpl and real pydrake agree; a faulty backend is caught."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, settings
from hypothesis.stateful import rule, run_state_machine_as_test

from conformance.backend import Command
from conformance.backends import load_backend
from conformance.fuzz import fuzz_settings
from conformance.lockstep import Divergence, FuzzStats, LockstepMachine, lockstep_machine
from conformance.mutants import mutant_backend
from conformance.scene_graph_backend import COMMANDS

SETTINGS = settings(
    max_examples=40,
    stateful_step_count=25,
    deadline=None,
    database=None,
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


def test_the_machine_has_a_rule_for_every_scenario_command() -> None:
    rules = {name for name in dir(LockstepMachine) if not name.startswith("_")}
    covered = {op for op in COMMANDS if op in rules}
    # register_geometry is issued by the register_geometries and scene rules.
    assert covered | {"register_geometry"} == set(COMMANDS)


def test_a_faulty_backend_raises_divergence_with_the_reference_answers() -> None:
    stats = FuzzStats()
    machine = lockstep_machine(
        lambda: mutant_backend("reverse_statement_order"), lambda: PYDRAKE, stats=stats
    )
    with pytest.raises(Divergence) as caught:
        run_state_machine_as_test(machine, settings=fuzz_settings(max_examples=300, steps=25))
    divergence = caught.value
    assert divergence.trace, "the shrunk sequence is not empty"
    assert any(s.command.op in ("apply", "apply_transient") for s in divergence.trace)
    assert "model" in divergence.reference_state.locations
    assert divergence.reference_state != divergence.backend_state or (
        divergence.trace[-1].reference != divergence.trace[-1].backend
    )
    assert stats.best is not None


class CountingMachine(LockstepMachine):
    """A subclass adds a rule; the lockstep checks still run after it."""

    backend_factory = staticmethod(lambda: REIMPL)
    reference_factory = staticmethod(lambda: PYDRAKE)
    stats = FuzzStats()
    _pair = None
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
    assert machine.trace[-1].backend.value is False
