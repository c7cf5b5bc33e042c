"""Hypothesis strategies for collision-filter scenarios (public API).

Every value is in the scenario grammar (``scenarios/README.md``): names, not
ids. Geometry sets are ``{"geometries": [...], "frames": [...]}``,
declarations ``{"statements": [...]}``, commands ``conformance.backend.Command``.
So anything drawn here can be sent to any backend, or written to a scenario
file as it is.

Each strategy takes keyword-only options. Wherever a strategy needs names it
accepts either a sequence of names or a strategy of names, such as a stateful
``Bundle``:

>>> from hypothesis import strategies as st
>>> sets = geometry_sets(geometries=["a", "b"], frames=["f"])
>>> decls = declarations(geometries=st.sampled_from(["a", "b"]), frames=["world"])

Special references are drawn rarely and shrink away. They are ``@unknown`` (an
id never issued), ``@foreign`` (an id from another SceneGraph), and ``world``
(the world frame: every anchored proximity geometry). A removed geometry's name
is an ordinary name whose id has gone stale.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from hypothesis import strategies as st

from conformance.backend import Command

__all__ = [
    "FOREIGN",
    "ROLES",
    "STATEMENT_OPS",
    "UNKNOWN",
    "WORLD",
    "GeometrySpec",
    "Names",
    "Scene",
    "command_sequences",
    "declarations",
    "geometry_sets",
    "roles",
    "scenes",
    "set_spec",
    "statements",
]

WORLD = "world"
UNKNOWN = "@unknown"
FOREIGN = "@foreign"
#: The roles a geometry can be registered with (``proximity`` decides C).
ROLES = ("proximity", "illustration", "perception")
STATEMENT_OPS = ("exclude_within", "allow_within", "exclude_between", "allow_between")

#: Names to draw from: a sequence, or a strategy (e.g. a stateful Bundle).
Names = Sequence[str] | st.SearchStrategy[str]


def _elements(names: Names, rare: Sequence[str], max_size: int) -> st.SearchStrategy[list[str]]:
    """Lists of ``names``, now and then (1 in 8) one of ``rare`` instead."""
    if isinstance(names, st.SearchStrategy):
        common: st.SearchStrategy[str] = names
    elif names:
        common = st.sampled_from(list(names))
    else:
        return st.lists(st.sampled_from(list(rare)), max_size=1) if rare else st.just([])
    return st.lists(_rarely(common, rare), max_size=max_size)


@st.composite
def _rarely(draw: st.DrawFn, common: st.SearchStrategy[str], rare: Sequence[str]) -> str:
    """``common``, or with probability 1/8 one of ``rare`` (shrinks to ``common``)."""
    if rare and draw(st.integers(min_value=0, max_value=7)) == 7:
        return draw(st.sampled_from(list(rare)))
    return draw(common)


_OTHER_ROLES = st.lists(st.sampled_from(ROLES[1:]), unique=True, max_size=2)
_PROXIMITY_ROLES = _OTHER_ROLES.map(lambda rs: ["proximity", *rs])
# Proximity decides C, so three geometries in four get it.
_ANY_ROLES = st.tuples(st.integers(min_value=0, max_value=3), _OTHER_ROLES).map(
    lambda t: ["proximity", *t[1]] if t[0] else t[1]
)


def roles(*, proximity: bool | None = None) -> st.SearchStrategy[list[str]]:
    """A list of distinct roles; ``proximity`` forces the role in (True) or out (False)."""
    if proximity is None:
        return _ANY_ROLES
    return _PROXIMITY_ROLES if proximity else _OTHER_ROLES


@cache
def _index(size: int) -> st.SearchStrategy[int]:
    """An index into a list of ``size`` items (strategies are cached: building one costs)."""
    return st.integers(min_value=0, max_value=size - 1)


# ------------------------------------------------------------------ scenes
@dataclass(frozen=True)
class GeometrySpec:
    name: str
    frame: str  # WORLD for anchored geometry
    roles: tuple[str, ...]


@dataclass(frozen=True)
class Scene:
    """Frames (name → parent, None for the world) and geometries, in registration order."""

    frames: tuple[tuple[str, str | None], ...]
    geometries: tuple[GeometrySpec, ...]
    frame_names: tuple[str, ...] = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "frame_names", tuple(name for name, _ in self.frames))

    def commands(self) -> list[Command]:
        """register_frame, then register_geometry commands (on the implicit source)."""
        out: list[Command] = []
        for name, parent in self.frames:
            args: dict[str, Any] = {"name": name}
            if parent is not None:
                args["parent"] = parent
            out.append(Command("register_frame", args))
        for g in self.geometries:
            out.append(
                Command(
                    "register_geometry", {"name": g.name, "frame": g.frame, "roles": [*g.roles]}
                )
            )
        return out

    def to_json(self) -> dict[str, Any]:
        """The scenario file's ``scene`` object."""
        return {
            "frames": [
                {"name": n} if p is None else {"name": n, "parent": p} for n, p in self.frames
            ],
            "geometries": [
                {"name": g.name, "frame": g.frame, "roles": [*g.roles]} for g in self.geometries
            ],
        }


@st.composite
def scenes(
    draw: st.DrawFn,
    *,
    min_frames: int = 0,
    max_frames: int = 4,
    min_geometries: int = 1,
    max_geometries: int = 8,
    anchored: bool = True,
    nested: bool = True,
    non_proximity: bool = True,
) -> Scene:
    """A scene: a frame tree and geometry on it.

    Frames are ``f1, f2, ...``; with ``nested`` a frame's parent may be an
    earlier frame. Geometries are ``g1, g2, ...`` on a frame or, with
    ``anchored``, on the world. With ``non_proximity`` some geometries lack
    the proximity role (only illustration/perception, or no role at all).
    """
    n_frames = draw(st.integers(min_value=min_frames, max_value=max_frames))
    frames: list[tuple[str, str | None]] = []
    for index in range(1, n_frames + 1):
        # Index 0 is "no parent" (the world), so parents shrink away.
        parent = draw(_index(index)) if nested else 0
        frames.append((f"f{index}", frames[parent - 1][0] if parent else None))
    places = ([WORLD] if anchored or not frames else []) + [name for name, _ in frames]
    n_geometries = draw(st.integers(min_value=min_geometries, max_value=max_geometries))
    role_lists = roles() if non_proximity else roles(proximity=True)
    geometries = [
        GeometrySpec(f"g{index}", places[draw(_index(len(places)))], tuple(draw(role_lists)))
        for index in range(1, n_geometries + 1)
    ]
    return Scene(tuple(frames), tuple(geometries))


# ---------------------------------------------------------- sets, declarations
def set_spec(geometries: Sequence[str], frames: Sequence[str]) -> dict[str, list[str]]:
    """The scenario grammar's geometry set; an empty list is left out."""
    out: dict[str, list[str]] = {}
    if geometries:
        out["geometries"] = list(geometries)
    if frames:
        out["frames"] = list(frames)
    return out


def geometry_sets(
    *,
    geometries: Names,
    frames: Names = (WORLD,),
    max_size: int = 3,
    special: bool = True,
) -> st.SearchStrategy[dict[str, list[str]]]:
    """``{"geometries": [...], "frames": [...]}``, either list possibly empty or absent.

    With ``special``, an element is now and then ``@unknown`` or ``@foreign``.
    Removed or non-proximity geometry comes from ``geometries`` itself.
    """
    rare = (UNKNOWN, FOREIGN) if special else ()
    g = _elements(geometries, rare, max_size)
    f = _elements(frames, rare, max(1, max_size - 1))

    return st.tuples(g, f).map(lambda parts: set_spec(*parts))


def statements(
    *, geometries: Names, frames: Names = (WORLD,), special: bool = True, max_size: int = 3
) -> st.SearchStrategy[dict[str, Any]]:
    """One statement: ``exclude_within``/``allow_within`` on a set, or ``*_between`` on two."""
    sets = geometry_sets(geometries=geometries, frames=frames, special=special, max_size=max_size)
    within = st.builds(lambda op, s: {"op": op, "set": s}, st.sampled_from(STATEMENT_OPS[:2]), sets)
    between = st.builds(
        lambda op, a, b: {"op": op, "a": a, "b": b}, st.sampled_from(STATEMENT_OPS[2:]), sets, sets
    )
    return within | between


@st.composite
def declarations(
    draw: st.DrawFn,
    *,
    geometries: Names,
    frames: Names = (WORLD,),
    min_statements: int = 1,
    max_statements: int = 4,
    special: bool = True,
    pool_size: int = 4,
) -> dict[str, Any]:
    """``{"statements": [...]}``: 1-4 statements by default, in any order.

    The statements' sets are subsets of one small pool of names (up to
    ``pool_size`` geometries and 2 frames) drawn per declaration, so that
    statements overlap, as in real declarations where a later statement
    refines an earlier one. A subset is one bitmask draw: it shrinks
    towards the empty set.
    """
    rare = (UNKNOWN, FOREIGN) if special else ()
    pool_g = list(dict.fromkeys(draw(_elements(geometries, rare, pool_size))))
    pool_f = list(dict.fromkeys(draw(_elements(frames, rare, 2))))

    def subset_of(pool: list[str]) -> list[str]:
        if not pool:
            return []
        mask = draw(_index(1 << len(pool)))
        return [name for bit, name in enumerate(pool) if mask >> bit & 1]

    def geometry_set() -> dict[str, list[str]]:
        return set_spec(subset_of(pool_g), subset_of(pool_f))

    items: list[dict[str, Any]] = []
    for _ in range(draw(st.integers(min_value=min_statements, max_value=max_statements))):
        op = STATEMENT_OPS[draw(_index(len(STATEMENT_OPS)))]
        if op.endswith("_within"):
            items.append({"op": op, "set": geometry_set()})
        else:
            items.append({"op": op, "a": geometry_set(), "b": geometry_set()})
    return {"statements": items}


# -------------------------------------------------------------- sequences
@dataclass
class _Known:
    """The names a sequence has introduced so far."""

    geometries: list[str]
    anchored: set[str]
    frames: list[str]
    labels: list[str] = field(default_factory=list)
    contexts: list[str] = field(default_factory=list)

    def geometry(self, draw: st.DrawFn) -> str:
        return draw(st.sampled_from(self.geometries or [UNKNOWN]))


_ArgBuilder = Callable[[st.DrawFn, _Known, int, bool], dict[str, Any] | None]


def _declaration_args(draw: st.DrawFn, known: _Known, index: int, special: bool) -> dict[str, Any]:
    names = known.geometries or [UNKNOWN]
    return {
        "declaration": draw(declarations(geometries=names, frames=known.frames, special=special))
    }


def _apply_transient_args(
    draw: st.DrawFn, known: _Known, index: int, special: bool
) -> dict[str, Any]:
    known.labels.append(f"t{index}")
    return {**_declaration_args(draw, known, index, special), "label": f"t{index}"}


def _register_geometry_args(
    draw: st.DrawFn, known: _Known, index: int, special: bool
) -> dict[str, Any]:
    name, frame = f"n{index}", draw(st.sampled_from(known.frames))
    known.geometries.append(name)
    if frame == WORLD:
        known.anchored.add(name)
    return {"name": name, "frame": frame, "roles": draw(roles())}


def _create_context_args(
    draw: st.DrawFn, known: _Known, index: int, special: bool
) -> dict[str, Any]:
    known.contexts.append(f"c{index}")
    return {"name": f"c{index}"}


def _clone_context_args(
    draw: st.DrawFn, known: _Known, index: int, special: bool
) -> dict[str, Any] | None:
    if not known.contexts:
        return None
    origin = draw(st.sampled_from(known.contexts))
    known.contexts.append(f"c{index}")
    return {"name": f"c{index}", "from": origin}


def _activation_args(draw: st.DrawFn, known: _Known, index: int, special: bool) -> dict[str, Any]:
    movable = [g for g in known.geometries if g not in known.anchored]
    dynamic = [f for f in known.frames if f != WORLD]
    return {"set": draw(geometry_sets(geometries=movable, frames=dynamic, special=False))}


#: op → (builder of its arguments, whether it may target a context).
_SEQUENCE_OPS: dict[str, tuple[_ArgBuilder, bool]] = {
    "apply": (_declaration_args, True),
    "apply_transient": (_apply_transient_args, True),
    "remove_declaration": (
        lambda d, k, i, s: {"label": d(st.sampled_from([*k.labels, UNKNOWN]))},
        True,
    ),
    "is_active": (lambda d, k, i, s: {"label": d(st.sampled_from([*k.labels, UNKNOWN]))}, True),
    "has_transient_history": (lambda d, k, i, s: {}, True),
    "collision_filtered": (lambda d, k, i, s: {"pair": [k.geometry(d), k.geometry(d)]}, True),
    "assign_role": (
        lambda d, k, i, s: {"geometry": k.geometry(d), "role": d(st.sampled_from(ROLES))},
        True,
    ),
    "remove_role": (
        lambda d, k, i, s: {"geometry": k.geometry(d), "role": d(st.sampled_from(ROLES))},
        True,
    ),
    "remove_geometry": (lambda d, k, i, s: {"geometry": k.geometry(d)}, True),
    "register_geometry": (_register_geometry_args, False),
    "create_context": (_create_context_args, False),
    "clone_context": (_clone_context_args, False),
    "set_default_context": (
        lambda d, k, i, s: {"context": d(st.sampled_from(k.contexts))} if k.contexts else None,
        False,
    ),
    "activate": (_activation_args, True),
    "deactivate": (_activation_args, True),
}


@st.composite
def command_sequences(
    draw: st.DrawFn,
    *,
    scene: st.SearchStrategy[Scene] | None = None,
    min_commands: int = 1,
    max_commands: int = 20,
    contexts: bool = True,
    activation: bool = False,
    special: bool = True,
) -> list[Command]:
    """A whole command sequence: a scene's registration, then commands over its names.

    Every name a command uses was introduced by an earlier command, so the
    sequence can be written as a scenario case as it is. Contexts (with
    ``contexts``) and Activate/Deactivate (with ``activation``; Drake ≥ 1.55)
    are optional. Anchored geometry is never (de)activated: that aborts
    pydrake 1.55-1.58.
    """
    the_scene = draw(scene if scene is not None else scenes())
    commands = the_scene.commands()
    known = _Known(
        geometries=[g.name for g in the_scene.geometries],
        anchored={g.name for g in the_scene.geometries if g.frame == WORLD},
        frames=[WORLD, *the_scene.frame_names],
    )
    ops = sorted(
        op
        for op in _SEQUENCE_OPS
        if (contexts or "context" not in op) and (activation or "activate" not in op)
    )
    for index in range(1, draw(st.integers(min_commands, max_commands)) + 1):
        op = draw(st.sampled_from(ops))
        build, locatable = _SEQUENCE_OPS[op]
        args = build(draw, known, index, special)
        if args is None:
            continue
        if locatable and known.contexts and draw(st.booleans()):
            args["context"] = draw(st.sampled_from(known.contexts))
        commands.append(Command(op, args))
    return commands
