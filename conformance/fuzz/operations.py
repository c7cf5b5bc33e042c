"""What the lockstep machine can do in one step: the ``OPERATIONS`` table.

Each operation issues one or a few scenario commands on both backends
(``LockstepMachine.step``). Every step of the machine draws four *picks*
(``strategies.picks``: one byte each), and the operation reads the ones it
needs against the names made so far, as ``CHOICES`` says for each kind of
name argument. An operation may also draw more, as its ``arguments`` say
(declaration and set templates, a batch of placements); those are drawn only
when it is the operation chosen.

Together the operations issue every command of the scenario grammar:
registration (sources, frames, geometry batches, Drake-name duplicates),
role changes, removal, apply, apply_transient, remove_declaration, IsActive,
history, CollisionFiltered, contexts, and Activate/Deactivate when both
backends support ``activation``.

To add an operation, subclass the machine with a larger table::

    class Mine(LockstepMachine):
        OPERATIONS = {**LockstepMachine.OPERATIONS, "ping": Operation(ping)}
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from hypothesis import strategies as st

from conformance.fuzz import strategies as cs
from conformance.protocol import ErrorKind, Result

__all__ = [
    "CHOICES",
    "DEFAULT_SOURCE",
    "MAX_CONTEXTS",
    "MAX_SOURCES",
    "OPERATIONS",
    "PICKS_PER_STEP",
    "Choice",
    "Machine",
    "Operation",
]

DEFAULT_SOURCE = "source"
MAX_SOURCES = 3
MAX_CONTEXTS = 3
#: Picks every step draws (the operations read the first ones they need).
PICKS_PER_STEP = 4


class Machine(Protocol):
    """What an operation may use of the machine that runs it (``LockstepMachine`` is one).

    Operations depend on this protocol, not on the state machine, so the
    table sits below the machine in the import graph.
    """

    activation: bool
    sources_made: int
    contexts_made: int
    names: dict[str, list[str]]

    def step(self, op: str, **args: Any) -> Result: ...

    def fresh(self, prefix: str) -> str: ...

    def keep(self, bundle: str, *names: str) -> None: ...

    def keep_if_made(self, bundle: str, name: str, result: Result) -> None: ...

    def name(self, kind: str, pick: int) -> str | None: ...

    def declaration(self, template: cs.DeclarationTemplate) -> dict[str, Any]: ...

    def geometry_set(self, template: cs.SetTemplate) -> dict[str, list[str]]: ...


@dataclass(frozen=True)
class Choice:
    """How a name argument reads a pick: ``strategies.pick(names[bundle], pick, ...)``."""

    bundle: str
    #: Picks below this leave the argument out (it shrinks to being left out).
    none_below: int = 0
    #: Names drawn one time in eight (always, while the bundle is empty).
    rare: tuple[str, ...] = ()


_SPECIAL = (cs.UNKNOWN, cs.FOREIGN)

#: Every kind of name argument the operations take (picks are 0-255).
CHOICES: dict[str, Choice] = {
    "context": Choice("contexts", none_below=128),  # the model half the time
    "owner": Choice("sources", none_below=128),  # the implicit source half the time
    "parent": Choice("frames", none_below=128),  # the world half the time
    "reused_frame": Choice("frames", none_below=192),  # a duplicate name one time in four
    "reused_geometry": Choice("geometries", none_below=192),
    "frame": Choice("frames"),
    "geometry": Choice("geometries"),
    "any_geometry": Choice("geometries", rare=_SPECIAL),  # now and then @unknown/@foreign
    "any_frame": Choice("frames", rare=_SPECIAL),
    "label": Choice("filter_ids", rare=(cs.UNKNOWN,)),
    "origin": Choice("contexts"),
}


def _always(machine: Machine) -> bool:
    return True


@dataclass(frozen=True)
class Operation:
    """One row of ``OPERATIONS``: ``run(machine, picks, *drawn)``.

    ``drawn`` holds one value of each of ``arguments``; ``enabled`` says
    whether the operation can run in the machine's state.
    """

    run: Callable[..., None]
    arguments: tuple[st.SearchStrategy[Any], ...] = ()
    enabled: Callable[[Machine], bool] = _always


# ------------------------------------------------------------ registration
def register_source(m: Machine, picks: bytes) -> None:
    name = m.fresh("s")
    m.sources_made += 1
    m.keep_if_made("sources", name, m.step("register_source", name=name))


def register_frame(m: Machine, picks: bytes) -> None:
    """A new frame; one time in four under another frame's Drake name (a duplicate)."""
    parent, source, reuse = picks[:3]
    name = m.fresh("f")
    result = m.step(
        "register_frame",
        name=name,
        drake_name=m.name("reused_frame", reuse),
        parent=m.name("parent", parent),
        source=m.name("owner", source),
    )
    m.keep_if_made("frames", name, result)


def register_geometries(m: Machine, picks: bytes, placements: bytes) -> None:
    """A batch of 1-4; into a context only on a frame (never anchored there).

    A placement is four picks: frame, role code (``strategies.role_list``),
    owner, and now and then another geometry's Drake name to reuse.
    """
    into, names = m.name("context", picks[0]), []
    for at in range(0, len(placements) - 3, 4):
        frame_pick, code, source, reuse = placements[at : at + 4]
        name, frame = m.fresh("g"), m.name("frame", frame_pick)
        result = m.step(
            "register_geometry",
            name=name,
            drake_name=m.name("reused_geometry", reuse),
            frame=frame,
            roles=cs.role_list(code),
            source=m.name("owner", source),
            context=into if frame != cs.WORLD else None,
        )
        # A failed role assignment leaves the geometry registered (Drake does so too).
        if result.error is None or result.error.kind is ErrorKind.TRANSIENT_HISTORY:
            names.append(name)
    m.keep("geometries", *names)


def assign_role(m: Machine, picks: bytes) -> None:
    """AssignRole of a role (``ROLES``), with kReplace one time in two."""
    geometry, how, source, context = picks
    m.step(
        "assign_role",
        geometry=m.name("geometry", geometry),
        role=cs.ROLES[how % 3],
        assign="replace" if how & 128 else None,
        source=m.name("owner", source),
        context=m.name("context", context),
    )


_REMOVABLE_ROLES = (*cs.ROLES, "unassigned")


def remove_role(m: Machine, picks: bytes) -> None:
    """RemoveRole of one geometry, or (one time in four) of every geometry on a frame."""
    which, how, source, context = picks
    kind = "frame" if how & 192 == 192 else "geometry"
    m.step(
        "remove_role",
        role=_REMOVABLE_ROLES[how % 4],
        source=m.name("owner", source),
        context=m.name("context", context),
        **{kind: m.name(kind, which)},
    )


def reassign_proximity(m: Machine, picks: bytes) -> None:
    """Removes the proximity role and assigns it again: the geometry starts unfiltered."""
    name, where = m.name("geometry", picks[0]), m.name("context", picks[1])
    m.step("remove_role", geometry=name, role="proximity", context=where)
    m.step("assign_role", geometry=name, role="proximity", context=where)


def remove_geometry(m: Machine, picks: bytes) -> None:
    geometry, source, context = picks[:3]
    m.step(
        "remove_geometry",
        geometry=m.name("geometry", geometry),
        source=m.name("owner", source),
        context=m.name("context", context),
    )


# ------------------------------------------------------------ declarations
def apply(m: Machine, picks: bytes, declaration: cs.DeclarationTemplate) -> None:
    m.step("apply", declaration=m.declaration(declaration), context=m.name("context", picks[0]))


def apply_transient(m: Machine, picks: bytes, declaration: cs.DeclarationTemplate) -> None:
    label = m.fresh("t")
    result = m.step(
        "apply_transient",
        declaration=m.declaration(declaration),
        label=label,
        context=m.name("context", picks[0]),
    )
    m.keep_if_made("filter_ids", label, result)


def transient_round_trip(m: Machine, picks: bytes, declaration: cs.DeclarationTemplate) -> None:
    """ApplyTransient, then RemoveDeclaration of it: C must be as if never applied.

    Removing the newest declaration also re-derives the pairs it named from
    the base and the older declarations (Table 1, lines 5-7).
    """
    label, where = m.fresh("t"), m.name("context", picks[0])
    result = m.step(
        "apply_transient", declaration=m.declaration(declaration), label=label, context=where
    )
    if result.error is None:
        m.step("remove_declaration", label=label, context=where)


def stacked_transients(
    m: Machine,
    picks: bytes,
    first: cs.DeclarationTemplate,
    second: cs.DeclarationTemplate,
) -> None:
    """Two transient declarations, then the first removed: the second must be replayed.

    Table 1, lines 5-7: removing a declaration re-derives C from the base and
    every declaration still active, in order.
    """
    labels, where = (m.fresh("t"), m.fresh("t")), m.name("context", picks[0])
    results = [
        m.step("apply_transient", declaration=m.declaration(d), label=label, context=where)
        for d, label in zip((first, second), labels, strict=True)
    ]
    m.step("remove_declaration", label=labels[0], context=where)
    m.keep_if_made("filter_ids", labels[1], results[1])


def remove_declaration(m: Machine, picks: bytes) -> None:
    m.step(
        "remove_declaration",
        label=m.name("label", picks[0]),
        context=m.name("context", picks[1]),
    )


def is_active(m: Machine, picks: bytes) -> None:
    m.step("is_active", label=m.name("label", picks[0]), context=m.name("context", picks[1]))


def has_transient_history(m: Machine, picks: bytes) -> None:
    m.step("has_transient_history", context=m.name("context", picks[0]))


def collision_filtered(m: Machine, picks: bytes) -> None:
    a, b, context = picks[:3]
    m.step(
        "collision_filtered",
        pair=[m.name("any_geometry", a), m.name("geometry", b)],
        context=m.name("context", context),
    )


def deactivate(m: Machine, picks: bytes, geometry_set: cs.SetTemplate) -> None:
    m.step("deactivate", set=m.geometry_set(geometry_set), context=m.name("context", picks[0]))


def activate(m: Machine, picks: bytes, geometry_set: cs.SetTemplate) -> None:
    m.step("activate", set=m.geometry_set(geometry_set), context=m.name("context", picks[0]))


# ---------------------------------------------------------------- contexts
def create_context(m: Machine, picks: bytes) -> None:
    name = m.fresh("c")
    m.contexts_made += 1
    m.keep_if_made("contexts", name, m.step("create_context", name=name))


def clone_context(m: Machine, picks: bytes) -> None:
    name = m.fresh("c")
    m.contexts_made += 1
    result = m.step("clone_context", name=name, **{"from": m.name("origin", picks[0])})
    m.keep_if_made("contexts", name, result)


def set_default_context(m: Machine, picks: bytes) -> None:
    m.step("set_default_context", context=m.name("origin", picks[0]))


# ------------------------------------------------------------------- table
def _has(bundle: str) -> Callable[[Machine], bool]:
    return lambda m: bool(m.names[bundle])


_DECLARATION = cs.declaration_templates()
_SET = cs.set_templates()
#: register_geometries: 1-4 placements of four picks each.
_PLACEMENTS = st.binary(min_size=4, max_size=16)

#: Operation name → Operation. The first one is where a shrunk step's choice goes.
OPERATIONS: dict[str, Operation] = {
    "has_transient_history": Operation(has_transient_history),
    "is_active": Operation(is_active),
    "remove_declaration": Operation(remove_declaration),
    "collision_filtered": Operation(collision_filtered, enabled=_has("geometries")),
    "register_source": Operation(register_source, enabled=lambda m: m.sources_made < MAX_SOURCES),
    "register_frame": Operation(register_frame),
    "register_geometries": Operation(register_geometries, (_PLACEMENTS,)),
    "assign_role": Operation(assign_role, enabled=_has("geometries")),
    "remove_role": Operation(remove_role, enabled=_has("geometries")),
    "reassign_proximity": Operation(reassign_proximity, enabled=_has("geometries")),
    "remove_geometry": Operation(remove_geometry, enabled=_has("geometries")),
    "apply": Operation(apply, (_DECLARATION,)),
    "apply_transient": Operation(apply_transient, (_DECLARATION,)),
    "transient_round_trip": Operation(transient_round_trip, (_DECLARATION,)),
    "stacked_transients": Operation(stacked_transients, (_DECLARATION, _DECLARATION)),
    "activate": Operation(activate, (_SET,), enabled=lambda m: m.activation),
    "deactivate": Operation(deactivate, (_SET,), enabled=lambda m: m.activation),
    "create_context": Operation(create_context, enabled=lambda m: m.contexts_made < MAX_CONTEXTS),
    "clone_context": Operation(
        clone_context,
        enabled=lambda m: m.contexts_made < MAX_CONTEXTS and bool(m.names["contexts"]),
    ),
    "set_default_context": Operation(set_default_context, enabled=_has("contexts")),
}
