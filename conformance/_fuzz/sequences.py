"""Whole command sequences, drawn by the same ``OPERATIONS`` table the lockstep fuzzer runs.

There is one command generator: ``conformance._fuzz.operations``. The lockstep
machine runs its operations on two backends at once; ``command_sequences``
runs them on a ``Recorder``, which only writes the commands down, and hands
the sequence out as a Hypothesis strategy. A new op's grammar row therefore
reaches both with no further edit.

>>> from conformance._fuzz.sequences import command_sequences
>>> strategy = command_sequences(max_operations=5, contexts=False)

``posed=True`` draws posed sequences, as ``fuzz --poses`` does: a posed
scene, then ``POSED_OPERATIONS`` (shapes, poses, the queries, near touches).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from hypothesis import strategies as st

from conformance._fuzz import strategies as cs
from conformance._fuzz.names import NameBook, register_scene
from conformance._fuzz.operations import (
    OPERATIONS,
    PICKS_PER_STEP,
    POSED_OPERATIONS,
    Operation,
    PoseBook,
    issued_ops,
    planned_operation,
    register_posed_scene,
)
from conformance.protocol import Backend, Command, Result

__all__ = ["CONTEXT_OPS", "Recorder", "command_sequences"]

#: The ops that make or choose contexts (left out with ``contexts=False``).
CONTEXT_OPS = frozenset({"create_context", "clone_context", "set_default_context"})


class Recorder(NameBook):
    """A NameBook that writes down the commands the operations issue.

    With a ``backend``, each command also runs on it (reset first), and a
    name is kept only if the command that made it succeeded there, exactly
    as in the lockstep machine. Without one, every command is taken to
    succeed: each name is kept, which makes a well-formed scenario case, but
    a later command may name something whose making failed (a backend
    reports that as an unknown name).
    """

    def __init__(
        self,
        *,
        backend: Backend | None = None,
        activation: bool = False,
        queries: bool = False,
        special: bool = True,
    ) -> None:
        super().__init__()
        self.backend = backend
        self.activation = activation
        self.queries = queries
        self.special = special
        self.commands: list[Command] = []
        self.poses = PoseBook()
        if backend is not None:
            backend.reset()

    def step(self, op: str, **args: Any) -> Result:
        command = Command(op, {k: v for k, v in args.items() if v is not None})
        self.commands.append(command)
        result = Result() if self.backend is None else self.backend.execute(command)
        self.poses.record(command, result)
        return result


def _without_contexts(operations: Mapping[str, Operation]) -> dict[str, Operation]:
    return {
        name: operation
        for name, operation in operations.items()
        if not issued_ops({name: operation}) & CONTEXT_OPS
    }


@st.composite
def command_sequences(
    draw: st.DrawFn,
    *,
    scene: st.SearchStrategy[cs.Scene] | None = None,
    min_operations: int = 1,
    max_operations: int = 20,
    contexts: bool = True,
    activation: bool = False,
    special: bool = True,
    operations: Mapping[str, Operation] | None = None,
    backend: Backend | None = None,
    posed: bool = False,
) -> list[Command]:
    """A scene's registration, then ``min_operations``-``max_operations`` operations.

    Each operation (a row of ``operations``, ``OPERATIONS`` by default)
    issues one to three commands; it is drawn as the lockstep machine draws
    it: one plan byte among the operations enabled at that point, then its
    picks and arguments. Every name a command uses was made by an earlier
    command, so the sequence is a valid scenario case as it stands.
    ``contexts`` False leaves out the operations that make contexts;
    ``activation`` lets Activate/Deactivate in (Drake ≥ 1.55; anchored
    geometry in their sets is for the backends' guards to refuse);
    ``special`` False never names ``@unknown`` or ``@foreign``. With a
    ``backend`` the sequence is drawn against it (see ``Recorder``), so every
    name it uses was made; arm its guards (``policy.guards.arm_guards``)
    before drawing activation on a release that needs them. ``posed`` draws
    a posed scene and ``POSED_OPERATIONS`` (the default table otherwise is
    ``OPERATIONS``), with the queries.
    """
    recorder = Recorder(backend=backend, activation=activation, queries=posed, special=special)
    drawn_scene = draw(scene if scene is not None else cs.scenes(posed=posed))
    (register_posed_scene if posed else register_scene)(recorder, drawn_scene)
    if operations is None:
        operations = POSED_OPERATIONS if posed else OPERATIONS
    table = dict(operations) if contexts else _without_contexts(operations)
    for _ in range(draw(st.integers(min_value=min_operations, max_value=max_operations))):
        head = draw(cs.picks(1 + PICKS_PER_STEP))
        enabled = [name for name, operation in table.items() if operation.enabled(recorder)]
        name = planned_operation(head[0], enabled)
        if name is None:
            continue
        operation = table[name]
        drawn = tuple(draw(argument) for argument in operation.arguments)
        operation.run(recorder, head[1:], *drawn)
    return recorder.commands
