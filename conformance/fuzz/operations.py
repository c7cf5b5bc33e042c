"""What the lockstep machine can do in one step: the ``OPERATIONS`` table.

Each operation issues one or a few scenario commands on both backends
(``LockstepMachine.step``). Every step of the machine draws four *picks*
(``strategies.picks``: one byte each), and the operation reads the ones it
needs against the names made so far, as ``CHOICES`` says for each kind of
name argument. An operation may also draw more, as its ``arguments`` say
(declaration and set templates, a batch of placements); those are drawn only
when it is the operation chosen.

Together the operations issue every SceneGraph command of the scenario grammar
(its ops of domain ``scene_graph``; the model ops are fuzzed by ``fuzz --models``):
registration (sources, frames, geometry batches, Drake-name duplicates),
role changes, removal, apply, apply_transient, remove_declaration, IsActive,
history, CollisionFiltered, contexts, and Activate/Deactivate when both
backends support ``activation``.

To add an operation, subclass the machine with a larger table::

    class Mine(LockstepMachine):
        OPERATIONS = {**LockstepMachine.OPERATIONS, "ping": Operation(ping)}
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from hypothesis import strategies as st

from conformance.fuzz import strategies as cs
from conformance.fuzz.names import CHOICES, DEFAULT_SOURCE, Choice
from conformance.grammar import GRAMMAR, Arg, ArgKind, CommandSpec, NameKind, ops_of
from conformance.protocol import ErrorKind, Result

__all__ = [
    "CHOICES",
    "DEFAULT_SOURCE",
    "HAND_WRITTEN",
    "MAX_CONTEXTS",
    "MAX_SOURCES",
    "OPERATIONS",
    "PICKS_PER_STEP",
    "Choice",
    "Machine",
    "Operation",
    "generic_operation",
    "issued_ops",
    "planned_operation",
]

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
    #: The ops of the grammar it issues (default: the row's own name).
    issues: frozenset[str] = frozenset()


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

#: The hand-written operations. The first one is where a shrunk step's choice goes.
HAND_WRITTEN: dict[str, Operation] = {
    "has_transient_history": Operation(has_transient_history),
    "is_active": Operation(is_active),
    "remove_declaration": Operation(remove_declaration),
    "collision_filtered": Operation(collision_filtered, enabled=_has("geometries")),
    "register_source": Operation(register_source, enabled=lambda m: m.sources_made < MAX_SOURCES),
    "register_frame": Operation(register_frame),
    "register_geometries": Operation(
        register_geometries, (_PLACEMENTS,), issues=frozenset({"register_geometry"})
    ),
    "assign_role": Operation(assign_role, enabled=_has("geometries")),
    "remove_role": Operation(remove_role, enabled=_has("geometries")),
    "reassign_proximity": Operation(
        reassign_proximity,
        enabled=_has("geometries"),
        issues=frozenset({"remove_role", "assign_role"}),
    ),
    "remove_geometry": Operation(remove_geometry, enabled=_has("geometries")),
    "apply": Operation(apply, (_DECLARATION,)),
    "apply_transient": Operation(apply_transient, (_DECLARATION,)),
    "transient_round_trip": Operation(
        transient_round_trip,
        (_DECLARATION,),
        issues=frozenset({"apply_transient", "remove_declaration"}),
    ),
    "stacked_transients": Operation(
        stacked_transients,
        (_DECLARATION, _DECLARATION),
        issues=frozenset({"apply_transient", "remove_declaration"}),
    ),
    "activate": Operation(activate, (_SET,), enabled=lambda m: m.activation),
    "deactivate": Operation(deactivate, (_SET,), enabled=lambda m: m.activation),
    "create_context": Operation(create_context, enabled=lambda m: m.contexts_made < MAX_CONTEXTS),
    "clone_context": Operation(
        clone_context,
        enabled=lambda m: m.contexts_made < MAX_CONTEXTS and bool(m.names["contexts"]),
    ),
    "set_default_context": Operation(set_default_context, enabled=_has("contexts")),
}


# ------------------------------------------------- derived from the grammar
#: How a generic operation fills an argument of each kind: (CHOICES kind, bundle it declares).
_GENERIC_NAMES: dict[ArgKind, str] = {
    ArgKind.SOURCE: "owner",
    ArgKind.FRAME: "any_frame",
    ArgKind.GEOMETRY: "any_geometry",
    ArgKind.CONTEXT: "context",
    ArgKind.LABEL: "label",
}
_REQUIRED_NAMES: dict[ArgKind, str] = {
    ArgKind.SOURCE: "owner",
    ArgKind.FRAME: "frame",
    ArgKind.GEOMETRY: "geometry",
    ArgKind.CONTEXT: "origin",
    ArgKind.LABEL: "label",
}
_BUNDLE_OF: dict[NameKind, str] = {
    NameKind.SOURCE: "sources",
    NameKind.FRAME: "frames",
    NameKind.GEOMETRY: "geometries",
    NameKind.CONTEXT: "contexts",
    NameKind.LABEL: "filter_ids",
}
_PREFIX: dict[NameKind, str] = {
    NameKind.SOURCE: "s",
    NameKind.FRAME: "f",
    NameKind.GEOMETRY: "g",
    NameKind.CONTEXT: "c",
    NameKind.LABEL: "t",
}
_DRAWN_KINDS: dict[ArgKind, st.SearchStrategy[Any]] = {
    ArgKind.SET: _SET,
    ArgKind.DECLARATION: _DECLARATION,
}


def _name(m: Machine, arg: Arg, pick: int) -> str | None:
    return m.name((_REQUIRED_NAMES if arg.required else _GENERIC_NAMES)[arg.kind], pick)


#: How a generic operation reads each kind of argument: (machine, arg, pick, templates) → value.
_READ: dict[ArgKind, Callable[[Machine, Arg, int, Iterator[Any]], Any]] = {
    **{kind: lambda m, a, p, t: _name(m, a, p) for kind in _GENERIC_NAMES},
    ArgKind.SET: lambda m, a, p, t: m.geometry_set(next(t)),
    ArgKind.DECLARATION: lambda m, a, p, t: m.declaration(next(t)),
    ArgKind.PAIR: lambda m, a, p, t: [m.name("any_geometry", p), m.name("geometry", p // 2)],
    ArgKind.ROLE: lambda m, a, p, t: cs.ROLES[p % 3],
    ArgKind.ROLES: lambda m, a, p, t: [cs.ROLES[p % 3]],
    ArgKind.ANY_ROLE: lambda m, a, p, t: (*cs.ROLES, "unassigned")[p % 4],
    ArgKind.ASSIGN: lambda m, a, p, t: ("new", "replace")[p % 2],
}


def _generic_value(m: Machine, arg: Arg, pick: int, drawn: Iterator[Any]) -> Any:
    """The value of ``arg``: a fresh name if it declares one, else as ``_READ`` says.

    Kinds missing from ``_READ`` (``TEXT``) are left out (None).
    """
    if arg.kind.declares is not None:
        return m.fresh(_PREFIX[arg.kind.declares])
    read = _READ.get(arg.kind)
    return None if read is None else read(m, arg, pick, drawn)


def generic_operation(command: CommandSpec) -> Operation:
    """An operation that issues ``command`` with arguments read from picks by their kinds.

    Names it declares are kept if the command succeeds. Of a ``one_of``
    group it gives the first key. It is enabled once the names its required
    arguments need exist, and for ``activation`` ops only if both backends
    have them. Every op without a hand-written operation gets one, so a new
    op needs only its grammar row and its handler to be fuzzed.
    """
    skipped = {key for group in command.one_of for key in group[1:]}
    args = tuple(arg for arg in command.args if arg.key not in skipped)
    arguments = tuple(_DRAWN_KINDS[a.kind] for a in args if a.kind in _DRAWN_KINDS)
    needs = {
        _BUNDLE_OF[a.kind.refers]
        for a in args
        if a.required and a.kind.refers in (NameKind.GEOMETRY, NameKind.CONTEXT)
    }
    if any(a.kind is ArgKind.PAIR for a in args):
        needs.add("geometries")

    def run(m: Machine, picks: bytes, *drawn: Any) -> None:
        templates = iter(drawn)
        values = {
            arg.key: _generic_value(m, arg, picks[i % len(picks)], templates)
            for i, arg in enumerate(args)
        }
        result = m.step(command.op, **values)
        for arg in args:
            if arg.kind.declares is not None:
                m.keep_if_made(_BUNDLE_OF[arg.kind.declares], values[arg.key], result)

    def enabled(m: Machine) -> bool:
        if command.feature == "activation" and not m.activation:
            return False
        return all(m.names[bundle] for bundle in needs)

    return Operation(run, arguments, enabled, frozenset({command.op}))


def planned_operation(byte: int, enabled: Sequence[str]) -> str | None:
    """The operation a plan byte names.

    0 names none (bytes shrink to 0); any other byte ``enabled[(byte - 1) % len(enabled)]``.
    """
    return enabled[(byte - 1) % len(enabled)] if byte else None


def issued_ops(operations: dict[str, Operation]) -> frozenset[str]:
    """The grammar ops the operations issue (a row issues its own name unless it says)."""
    return frozenset(op for name, o in operations.items() for op in (o.issues or {name}))


#: What a step can do: the hand-written operations, then a generic one for every
#: SceneGraph op of the grammar that none of them issues.
OPERATIONS: dict[str, Operation] = {
    **HAND_WRITTEN,
    **{
        op: generic_operation(GRAMMAR[op])
        for op in ops_of("scene_graph")
        if not GRAMMAR[op].harness_only and op not in issued_ops(HAND_WRITTEN)
    },
}
