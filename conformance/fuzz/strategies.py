"""Hypothesis strategies for collision-filter scenarios (public API).

Every value is in the scenario grammar (``scenarios/README.md``): names, not
ids. Geometry sets are ``{"geometries": [...], "frames": [...]}``,
declarations ``{"statements": [...]}``, commands ``conformance.protocol.Command``.
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

Names are cheap to draw. A name is a *pick*, one byte read against a list
of names by ``pick``, and the picks a value needs are drawn together as one
fixed-size ``bytes`` choice (``picks(n)``): Hypothesis draws the bytes
uniformly and shrinks each towards 0. ``set_templates`` and
``declaration_templates`` draw whole sets and declarations as one such choice
each, to be resolved later against lists that may have grown since (a state
machine's bundles do; ``conformance.fuzz.lockstep`` uses them so).
``geometry_sets`` and ``declarations`` are those templates resolved at once.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from hypothesis import strategies as st

from conformance.protocol import Command

__all__ = [
    "FOREIGN",
    "PICK_RANGE",
    "ROLES",
    "STATEMENT_OPS",
    "UNKNOWN",
    "WORLD",
    "DeclarationTemplate",
    "GeometrySpec",
    "Names",
    "Picker",
    "Scene",
    "SetTemplate",
    "declaration_templates",
    "declarations",
    "geometry_sets",
    "pick",
    "picks",
    "role_list",
    "roles",
    "scenes",
    "set_spec",
    "set_templates",
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


#: Resolves a pick (0-255) to a name, or None for "left out".
Picker = Callable[[int], str | None]

#: A pick is one byte.
PICK_RANGE = 256
#: Picks from here up stand for a rare name when there are any (1 in 8).
_RARE_FROM = PICK_RANGE - PICK_RANGE // 8


@cache
def picks(count: int = 1) -> st.SearchStrategy[bytes]:
    """``count`` picks as one choice: ``bytes`` of that length (each shrinks towards 0)."""
    return st.binary(min_size=count, max_size=count)


def pick(
    names: Sequence[str], index: int, *, rare: Sequence[str] = (), none_below: int = 0
) -> str | None:
    """The name that a pick (``index``, 0-255) stands for in ``names``.

    ==========================================  =============================
    ``index < none_below``                      None (an optional name left
                                                out; shrinks to this)
    ``index ≥ 224`` and ``rare``, or no names   ``rare[index % len(rare)]``
                                                (None if no ``rare`` either)
    otherwise                                   ``names[index % len(names)]``
    ==========================================  =============================
    """
    if index < none_below:
        return None
    if rare and (index >= _RARE_FROM or not names):
        return rare[index % len(rare)]
    return names[index % len(names)] if names else None


def _picker(draw: st.DrawFn, names: Names, rare: Sequence[str]) -> Picker:
    """A sequence is read by index; a strategy is drawn from (the index is ignored)."""
    if isinstance(names, st.SearchStrategy):
        strategy = _rarely(names, tuple(rare))
        return lambda index: draw(strategy)
    listed = list(names)
    return lambda index: pick(listed, index, rare=rare)


@cache
def _rarely(common: st.SearchStrategy[str], rare: tuple[str, ...]) -> st.SearchStrategy[str]:
    """``common``, or now and then one of ``rare`` (shrinks to ``common``)."""
    if not rare:
        return common
    return st.tuples(st.integers(min_value=0, max_value=7), common, st.sampled_from(rare)).map(
        lambda t: t[2] if t[0] == 7 else t[1]
    )


def _unique(names: Iterable[str | None]) -> list[str]:
    return list(dict.fromkeys(name for name in names if name is not None))


#: Role codes (0-15) by ``roles(proximity=...)``: proximity below 12, 3 codes in 4.
_ROLE_CODES = {None: (0, 15), True: (0, 11), False: (12, 15)}


def role_list(code: int) -> list[str]:
    """The roles of a role code, taken mod 16: 0 is proximity alone, 12 no role at all.

    Proximity is ``code % 16 < 12``; bit 0 adds illustration, bit 1 perception.
    Codes shrink towards 0, so towards the role that decides C.
    """
    code %= 16
    chosen = (code < 12, bool(code & 1), bool(code & 2))
    return [role for role, on in zip(ROLES, chosen, strict=True) if on]


@cache
def _role_codes(proximity: bool | None) -> st.SearchStrategy[int]:
    low, high = _ROLE_CODES[proximity]
    return st.integers(min_value=low, max_value=high)


def roles(*, proximity: bool | None = None) -> st.SearchStrategy[list[str]]:
    """A list of distinct roles; ``proximity`` forces the role in (True) or out (False).

    One choice (a role code, ``role_list``); proximity comes three times in four.
    """
    return _role_codes(proximity).map(role_list)


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
    for index, byte in enumerate(draw(picks(n_frames)), start=1):
        # Pick 0 is "no parent" (the world), so parents shrink away.
        parent = byte % index if nested else 0
        frames.append((f"f{index}", frames[parent - 1][0] if parent else None))
    places = ([WORLD] if anchored or not frames else []) + [name for name, _ in frames]
    n_geometries = draw(st.integers(min_value=min_geometries, max_value=max_geometries))
    layout = draw(picks(2 * n_geometries))  # (place, role code) per geometry
    geometries = [
        GeometrySpec(
            f"g{index}",
            places[layout[2 * index - 2] % len(places)],
            tuple(role_list(code if non_proximity else code % 12)),
        )
        for index, code in enumerate(layout[1::2], start=1)
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


@dataclass(frozen=True)
class SetTemplate:
    """A geometry set drawn as picks; ``resolve`` reads them against names."""

    geometries: tuple[int, ...]
    frames: tuple[int, ...]

    @classmethod
    def decode(cls, data: bytes, *, max_geometries: int = 3, max_frames: int = 2) -> SetTemplate:
        """Byte 0 gives the counts (bits 0-1 geometries, bits 2-3 frames), then the picks."""
        head = data[0] if data else 0
        n_geometries = min(head & 3, max_geometries)
        n_frames = min(head >> 2 & 3, max_frames)
        body = data[1:]
        return cls(tuple(body[:n_geometries]), tuple(body[n_geometries : n_geometries + n_frames]))

    def resolve(self, geometry: Picker, frame: Picker) -> dict[str, list[str]]:
        """``set_spec`` of the picked names (duplicates and Nones dropped)."""
        return set_spec(_unique(map(geometry, self.geometries)), _unique(map(frame, self.frames)))


@cache
def set_templates(
    *, max_geometries: int = 3, max_frames: int = 2
) -> st.SearchStrategy[SetTemplate]:
    """Up to ``max_geometries`` (≤ 3) geometry picks and ``max_frames`` (≤ 3) frame picks.

    One choice: ``bytes`` decoded by ``SetTemplate.decode``.
    """
    if not (0 <= max_geometries <= 3 and 0 <= max_frames <= 3):
        raise ValueError("set_templates: at most 3 geometry picks and 3 frame picks")
    return st.binary(min_size=1, max_size=1 + max_geometries + max_frames).map(
        lambda data: SetTemplate.decode(data, max_geometries=max_geometries, max_frames=max_frames)
    )


#: Bits of a mask: a declaration's pool has at most this many picks.
_MASK_BITS = 6


@dataclass(frozen=True)
class DeclarationTemplate:
    """A declaration drawn as picks: statements whose sets are bitmasks over one pool.

    The pool is the ``geometries`` picks, then the ``frames`` picks; bit i of
    a mask puts pool item i in the set. Drawing sets from one small pool
    makes statements overlap, as in real declarations where a later
    statement refines an earlier one.
    """

    geometries: tuple[int, ...]
    frames: tuple[int, ...]
    #: (op, masks): one mask for ``*_within``, two (a, b) for ``*_between``.
    statements: tuple[tuple[str, tuple[int, ...]], ...]

    @classmethod
    def decode(
        cls, data: bytes, *, pool_size: int = 4, frame_pool_size: int = 2, max_statements: int = 4
    ) -> DeclarationTemplate:
        """The pool's picks, then the statements: one byte each, plus one for ``b``.

        A statement byte holds the op (bits 0-1, ``STATEMENT_OPS``) and the
        first set's mask (bits 2-7); ``*_between`` takes the next byte's low
        six bits as the second set's mask (0, the empty set, if none is left).
        """
        pool = pool_size + frame_pool_size
        stream = iter(data[pool:])
        statements: list[tuple[str, tuple[int, ...]]] = []
        for byte in stream:
            if len(statements) == max_statements:
                break
            op = STATEMENT_OPS[byte & 3]
            masks = (byte >> 2,) if op.endswith("_within") else (byte >> 2, next(stream, 0) & 63)
            statements.append((op, masks))
        return cls(tuple(data[:pool_size]), tuple(data[pool_size:pool]), tuple(statements))

    def resolve(self, geometry: Picker, frame: Picker) -> dict[str, Any]:
        """``{"statements": [...]}`` in the scenario grammar."""
        pool = [geometry(index) for index in self.geometries]
        pool_frames = [frame(index) for index in self.frames]

        def members(mask: int) -> dict[str, list[str]]:
            chosen = [mask >> bit & 1 for bit in range(len(pool) + len(pool_frames))]
            return set_spec(
                _unique(n for n, on in zip(pool, chosen, strict=False) if on),
                _unique(n for n, on in zip(pool_frames, chosen[len(pool) :], strict=False) if on),
            )

        items: list[dict[str, Any]] = []
        for op, masks in self.statements:
            if op.endswith("_within"):
                items.append({"op": op, "set": members(masks[0])})
            else:
                items.append({"op": op, "a": members(masks[0]), "b": members(masks[1])})
        return {"statements": items}


@cache
def declaration_templates(
    *,
    min_statements: int = 1,
    max_statements: int = 4,
    pool_size: int = 4,
    frame_pool_size: int = 2,
) -> st.SearchStrategy[DeclarationTemplate]:
    """``DeclarationTemplate``: 1-4 statements by default, in any order.

    A pool of ``pool_size`` geometry picks and ``frame_pool_size`` frame picks
    (at most 6 in all; repeated picks name one item); each set is a bitmask
    over the pool that shrinks towards the empty set. One choice: ``bytes``
    decoded by ``DeclarationTemplate.decode``.
    """
    pool = pool_size + frame_pool_size
    if pool > _MASK_BITS or not 1 <= min_statements <= max_statements:
        raise ValueError(
            "declaration_templates: at most 6 pool picks and 1 ≤ min_statements ≤ max_statements"
        )
    return st.binary(min_size=pool + min_statements, max_size=pool + 2 * max_statements).map(
        lambda data: DeclarationTemplate.decode(
            data,
            pool_size=pool_size,
            frame_pool_size=frame_pool_size,
            max_statements=max_statements,
        )
    )


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
    templates = set_templates(
        max_geometries=min(max_size, 3), max_frames=min(max(1, max_size - 1), 3)
    )

    @st.composite
    def resolved(draw: st.DrawFn) -> dict[str, list[str]]:
        return draw(templates).resolve(_picker(draw, geometries, rare), _picker(draw, frames, rare))

    return resolved()


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
    """``{"statements": [...]}``: a ``DeclarationTemplate`` resolved against the names.

    1-4 statements by default, in any order, over one pool of up to
    ``pool_size`` geometries and 2 frames (see ``DeclarationTemplate``).
    """
    rare = (UNKNOWN, FOREIGN) if special else ()
    template = draw(
        declaration_templates(
            min_statements=min_statements, max_statements=max_statements, pool_size=pool_size
        )
    )
    return template.resolve(_picker(draw, geometries, rare), _picker(draw, frames, rare))
