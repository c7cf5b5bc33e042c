"""What a lockstep step draws: its plan of operations, the example's scene, and the glue
that files names into Hypothesis Bundles from inside the one rule.

Why one rule over a table, picks rather than Bundle draws, and two
operations per step: Hypothesis, not the backends, was the fuzz loop's main
cost. Choosing among 22 rules costs it 5-20 choices per step (swarm flags and
rejection sampling), a Bundle argument four nested draws, an optional one
(``st.none() | bundle``) more still, and each step has a fixed cost on top.
Here a step is a few choices: its operations and their picks in one ``bytes``
choice, plus a declaration or set template where an operation needs one.
``benchmarks/bench_fuzz.py`` measures the result.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import cache
from typing import Any

from hypothesis import strategies as st
from hypothesis.control import current_build_context
from hypothesis.errors import InvalidArgument
from hypothesis.stateful import RuleBasedStateMachine

from conformance._fuzz import operations as ops
from conformance._fuzz import strategies as cs
from conformance._fuzz.operations import planned_operation

__all__ = ["SWARM_BYTES", "StepPlan", "file_in_bundle", "is_final_run", "scenes_of", "step_plans"]


#: Bytes of the swarm draw: a threshold, then one byte per operation (mod 31).
SWARM_BYTES = 32


def is_final_run() -> bool:
    """True while Hypothesis replays the example it reports (False outside a run)."""
    try:
        return bool(current_build_context().is_final)
    except InvalidArgument:
        return False


def file_in_bundle(machine: RuleBasedStateMachine, bundle: str, values: Sequence[str]) -> None:
    """Adds ``values`` to the Hypothesis Bundle ``bundle`` from inside any rule.

    Hypothesis has no public call for this: only a rule's return value feeds
    the Bundle it targets, and one rule runs every operation here. So this
    uses the method that return path calls, ``_add_results_to_targets``
    (Hypothesis ≥ 6.132, the floor in pyproject.toml);
    ``tests/test_lockstep.py`` checks that the Bundles fill.
    """
    add: Callable[..., None] = machine._add_results_to_targets
    add((bundle,), list(values))


@cache
def scenes_of(
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
StepPlan = list[tuple[str, bytes, tuple[Any, ...]]]


@st.composite
def step_plans(draw: st.DrawFn) -> StepPlan:
    """The plan of one step: ``operations_per_step`` operations with their arguments.

    One ``bytes`` choice holds, per operation, which one (a byte: 0 is none,
    where it shrinks to; otherwise an index into the operations enabled at
    the start of the step) and its picks. The operations' own ``arguments``
    follow, drawn only for the operations chosen.
    """
    machine: Any = draw(_RUNNER)  # the running LockstepMachine
    head = draw(cs.picks(machine.operations_per_step * _SLOT))
    enabled = machine.enabled_operations()
    plan: StepPlan = []
    for at in range(0, len(head), _SLOT):
        name = planned_operation(head[at], enabled, machine.weights)
        if name is not None:
            drawn = tuple(draw(argument) for argument in machine.OPERATIONS[name].arguments)
            plan.append((name, head[at + 1 : at + _SLOT], drawn))
    return plan
