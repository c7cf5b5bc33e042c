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

**Posed scenes** (``fuzz --poses``): ``POSED_OPERATIONS`` is ``OPERATIONS``
with geometry registered with a drawn shape and pose, and with every op of
the grammar's ``queries`` domain (set_poses and the QueryObject queries, in
the model or a context), plus ``near_touch``: it moves one geometry's frame
so that the geometry sits at a drawn gap of 1e-9 to 1e-3 m from another
(``strategies.Touch``, ``strategies.touching_position``), then queries
there, so the decision between colliding and not is made at the boundary;
and ``filter_in_clone``: a clone of a context, a persistent declaration
applied in it, and a query there (picks alone rarely reach a clone);
``query_through_filter``: a transient declaration (one time in two aimed at
the pairs that penetrate, else at the candidates), every query the filter
decides, its removal, every query again; ``query_at_max_distance``: the
pairwise signed distances with ``max_distance`` at a pair's own distance and
1 ulp either side, the pair one of the scene's or two new spheres.
``PoseBook`` follows the commands to know where everything is: every
frame's parent, every geometry's frame, shape and ``X_FG``, and the poses
``set_poses`` stored at each location. The query ops run only when both
backends have the ``queries`` feature.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from hypothesis import strategies as st

from conformance._fuzz import strategies as cs
from conformance._fuzz.names import CHOICES, DEFAULT_SOURCE, Choice, NameBook, register_scene
from conformance._grammar import GRAMMAR, Arg, ArgKind, CommandSpec, NameKind, ops_of
from conformance._grammar.queries import DEFAULT_SHAPE
from conformance.protocol import MODEL, Command, ErrorKind, Result

__all__ = [
    "CHOICES",
    "DEFAULT_SOURCE",
    "GROW_UP_TO",
    "HAND_WRITTEN",
    "MAX_CONTEXTS",
    "MAX_SOURCES",
    "OPERATIONS",
    "PICKS_PER_STEP",
    "POSED_OPERATIONS",
    "QUERY_OPS",
    "Choice",
    "Machine",
    "Operation",
    "PoseBook",
    "generic_operation",
    "issued_ops",
    "near_touch",
    "planned_operation",
    "register_posed_scene",
]

MAX_SOURCES = 3
MAX_CONTEXTS = 3
#: ``grow_scene`` adds 4-8 geometries while an example has at most this many: enough to
#: take a location past 16 proximity geometries, no more (every comparison costs O(n²)).
GROW_UP_TO = 20
#: Picks every step draws (the operations read the first ones they need).
PICKS_PER_STEP = 4


class Machine(Protocol):
    """What an operation may use of the machine that runs it (``LockstepMachine`` is one).

    Operations depend on this protocol, not on the state machine, so the
    table sits below the machine in the import graph.
    """

    activation: bool
    #: Both sides have the posed queries (the ``queries`` feature).
    queries: bool
    sources_made: int
    contexts_made: int
    names: dict[str, list[str]]
    poses: PoseBook

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


def _register_frame(m: Machine, picks: bytes, drake_name: str | None) -> None:
    parent, source = picks[:2]
    name = m.fresh("f")
    result = m.step(
        "register_frame",
        name=name,
        drake_name=drake_name,
        parent=m.name("parent", parent),
        source=m.name("owner", source),
    )
    m.keep_if_made("frames", name, result)


def register_frame(m: Machine, picks: bytes) -> None:
    """A new frame; one time in four under another frame's Drake name (a duplicate)."""
    _register_frame(m, picks, m.name("reused_frame", picks[2]))


def register_posed_frame(m: Machine, picks: bytes) -> None:
    """``register_frame`` under its own Drake name (never another frame's).

    N.B. pydrake 1.51.1 (and 1.58) leave a frame refused for its duplicate
    name half-registered: every later query raises IndexError
    ``_Map_base::at`` (measured). That is one fact, not something to find
    again in every posed example whose queries would all fail after it;
    the filter campaign still registers duplicates.
    """
    _register_frame(m, picks, None)


def _registered(result: Result) -> bool:
    """The geometry exists after its register_geometry step.

    A failed role assignment leaves it registered (Drake does so too).
    """
    return result.error is None or result.error.kind is ErrorKind.TRANSIENT_HISTORY


#: Bytes of a placement: four picks, then (posed) a shape and a pose.
_PLACEMENT = 4
_POSED_PLACEMENT = _PLACEMENT + cs.SHAPE_BYTES + cs.POSE_BYTES


def _register_batch(m: Machine, picks: bytes, placements: bytes, width: int) -> None:
    into, names = m.name("context", picks[0]), []
    for at in range(0, len(placements) - width + 1, width):
        frame_pick, code, source, reuse = placements[at : at + _PLACEMENT]
        solid = placements[at + _PLACEMENT : at + width]
        name, frame = m.fresh("g"), m.name("frame", frame_pick)
        result = m.step(
            "register_geometry",
            name=name,
            drake_name=m.name("reused_geometry", reuse),
            frame=frame,
            roles=cs.role_list(code),
            source=m.name("owner", source),
            context=into if frame != cs.WORLD else None,
            shape=(
                cs.shape_of(solid[: cs.SHAPE_BYTES], halfspace=cs.POSED_HALFSPACE_SHARE)
                if solid
                else None
            ),
            pose=(cs.pose_of(solid[cs.SHAPE_BYTES :]) or None) if solid else None,
        )
        if _registered(result):
            names.append(name)
    m.keep("geometries", *names)


def register_geometries(m: Machine, picks: bytes, placements: bytes) -> None:
    """A batch of 1-4; into a context only on a frame (never anchored there).

    A placement is four picks: frame, role code (``strategies.role_list``),
    owner, and now and then another geometry's Drake name to reuse.
    """
    _register_batch(m, picks, placements, _PLACEMENT)


def register_posed_geometries(m: Machine, picks: bytes, placements: bytes) -> None:
    """``register_geometries`` whose placements also draw a shape and a pose ``X_FG``.

    A placement is the four picks, ``SHAPE_BYTES`` (``strategies.shape_of``)
    and ``POSE_BYTES`` (``strategies.pose_of``).
    """
    _register_batch(m, picks, placements, _POSED_PLACEMENT)


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
    """Removes the proximity role and assigns it again: the geometry starts unfiltered.

    One time in two the role is removed from every geometry on the geometry's
    frame (RemoveRole by frame), and each of them gets it back. Then, one time
    in two (``picks[3]``), the geometry is excluded from another one and its
    proximity properties are replaced (``_replace_keeps_filters``).
    """
    name, where = m.name("geometry", picks[0]), m.name("context", picks[1])
    placed = m.poses.geometries.get(name or "")
    if placed is None or not picks[2] & 1:
        m.step("remove_role", geometry=name, role="proximity", context=where)
        m.step("assign_role", geometry=name, role="proximity", context=where)
    else:
        m.step("remove_role", frame=placed.frame, role="proximity", context=where)
        for other, at in list(m.poses.geometries.items()):
            if at.frame == placed.frame:
                m.step("assign_role", geometry=other, role="proximity", context=where)
    if picks[3] & 1:
        _replace_keeps_filters(m, name, m.name("geometry", picks[3] >> 1), where)


def _replace_keeps_filters(
    m: Machine, name: str | None, other: str | None, where: str | None
) -> None:
    """A persistent ExcludeBetween of ``name`` and ``other``, then AssignRole(kReplace) of
    ``name``'s proximity properties: the pair must stay filtered (a replacement is no
    removal). Found missing by the blind audit's ``replace_proximity_resets_filters``:
    ``assign_role`` draws kReplace of proximity, but seldom on a geometry that has a
    filtered partner on another frame, with its owner and no transient history there.
    """
    if other is not None and other != name:
        pair = {"op": "exclude_between", "a": {"geometries": [name]}, "b": {"geometries": [other]}}
        m.step("apply", declaration={"statements": [pair]}, context=where)
    m.step("assign_role", geometry=name, role="proximity", assign="replace", context=where)


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


def _can_clone(m: Machine) -> bool:
    """A context exists to clone, and the example may make one more."""
    return m.contexts_made < MAX_CONTEXTS and bool(m.names["contexts"])


def _clone(m: Machine, origin: str | None) -> str | None:
    """clone_context of ``origin`` under a fresh name: the name, kept, if it was made."""
    name = m.fresh("c")
    m.contexts_made += 1
    result = m.step("clone_context", name=name, **{"from": origin})
    m.keep_if_made("contexts", name, result)
    return name if result.error is None else None


def clone_context(m: Machine, picks: bytes) -> None:
    _clone(m, m.name("origin", picks[0]))


def clone_with_history(
    m: Machine, picks: bytes, first: cs.DeclarationTemplate, second: cs.DeclarationTemplate
) -> None:
    """A transient declaration in a context, a clone of it, then edits in both.

    The clone inherits the history (the declaration, and its FilterId); both
    sides then apply one more and remove the inherited one, the clone first
    or the origin first as a pick says. Each must go on as if alone.
    """
    origin = m.name("origin", picks[0])
    label, clone = m.fresh("t"), m.fresh("c")
    result = m.step(
        "apply_transient", declaration=m.declaration(first), label=label, context=origin
    )
    m.keep_if_made("filter_ids", label, result)
    m.contexts_made += 1
    cloned = m.step("clone_context", name=clone, **{"from": origin})
    m.keep_if_made("contexts", clone, cloned)
    sides = (clone, origin) if picks[1] & 1 else (origin, clone)
    for where in sides if cloned.error is None else (origin,):
        more = m.fresh("t")
        made = m.step(
            "apply_transient", declaration=m.declaration(second), label=more, context=where
        )
        m.keep_if_made("filter_ids", more, made)
        m.step("remove_declaration", label=label, context=where)


def set_default_context(m: Machine, picks: bytes) -> None:
    m.step("set_default_context", context=m.name("origin", picks[0]))


# ---------------------------------------------------------------- poses
@dataclass(frozen=True)
class Placed:
    """A registered geometry: its frame, its SHAPE and ``X_FG``."""

    frame: str
    shape: dict[str, Any]
    pose: cs.Transform


class PoseBook:
    """Where everything is, as the commands so far put it (the reference's results decide).

    ``record`` reads every command after it ran: register_frame (a frame's
    parent), register_geometry (frame, shape, ``X_FG``), set_poses (each
    frame's ``X_PF``, at the model or a context, merged with earlier ones),
    create_context (no poses: identity) and clone_context (the source's
    poses), as ``backends.queries`` keeps them. A frame's world pose is
    ``X_WF = X_WP · X_PF`` and a geometry's ``X_WG = X_WF · X_FG``.
    """

    def __init__(self) -> None:
        #: frame → parent frame (the world frame has none).
        self.parents: dict[str, str] = {}
        self.geometries: dict[str, Placed] = {}
        #: location → frame → X_PF.
        self.stored: dict[str, dict[str, cs.Transform]] = {MODEL: {}}

    def record(self, command: Command, result: Result) -> None:
        """Follows ``command``, which answered ``result`` (on the reference)."""
        follow = _FOLLOW.get(command.op)
        if follow is not None:
            follow(self, command.args, result)

    def _frame(self, args: Mapping[str, Any], result: Result) -> None:
        if result.error is None:
            self.parents[args["name"]] = args.get("parent", cs.WORLD)

    def _geometry(self, args: Mapping[str, Any], result: Result) -> None:
        if _registered(result):
            shape = dict(args.get("shape", DEFAULT_SHAPE))
            placed = Placed(args.get("frame", cs.WORLD), shape, cs.Transform.of(args.get("pose")))
            self.geometries[args["name"]] = placed

    def _poses(self, args: Mapping[str, Any], result: Result) -> None:
        if result.error is None:
            stored = self.stored.setdefault(args.get("context", MODEL), {})
            stored.update({name: cs.Transform.of(pose) for name, pose in args["poses"].items()})

    def _new_context(self, args: Mapping[str, Any], result: Result) -> None:
        if result.error is None:
            self.stored[args["name"]] = {}

    def _clone(self, args: Mapping[str, Any], result: Result) -> None:
        if result.error is None:
            self.stored[args["name"]] = dict(self.stored.get(args["from"], {}))

    def lineage(self, frame: str) -> list[str]:
        """``frame`` and its ancestors, up to (without) the world frame."""
        chain = []
        while frame in self.parents:
            chain.append(frame)
            frame = self.parents[frame]
        return chain

    def frame_pose(self, frame: str, location: str) -> cs.Transform:
        """``X_WF`` at ``location`` (a frame with no stored pose: identity in its parent)."""
        stored = self.stored.get(location, {})
        pose = cs.Transform()
        for name in reversed(self.lineage(frame)):
            pose = pose * stored.get(name, cs.Transform())
        return pose

    def geometry_pose(self, geometry: str, location: str) -> cs.Transform:
        """``X_WG = X_WF · X_FG`` at ``location``."""
        placed = self.geometries[geometry]
        return self.frame_pose(placed.frame, location) * placed.pose


#: What ``PoseBook.record`` follows, by op.
_FOLLOW: dict[str, Callable[[PoseBook, Mapping[str, Any], Result], None]] = {
    "register_frame": PoseBook._frame,
    "register_geometry": PoseBook._geometry,
    "set_poses": PoseBook._poses,
    "create_context": PoseBook._new_context,
    "clone_context": PoseBook._clone,
}


def register_posed_scene(m: NameBook, scene: cs.Scene) -> None:
    """``names.register_scene`` for a posed scene (``strategies.scenes(posed=True)``).

    The frames go through ``register_scene``; then each geometry is
    registered with its shape and ``X_FG``, and the frames' poses are set at
    the model (one set_poses).
    """
    register_scene(m, cs.Scene(scene.frames, ()))
    made = m.names["frames"][len(m.names["frames"]) - len(scene.frames) :]
    frames = dict(zip(scene.frame_names, made, strict=True))
    names = []
    for geometry in scene.geometries:
        name = m.fresh("g")
        arguments = {**geometry.arguments(), "name": name}
        result = m.step(
            "register_geometry", frame=frames.get(geometry.frame, cs.WORLD), **arguments
        )
        if _registered(result):
            names.append(name)
    m.keep("geometries", *names)
    if scene.poses:
        m.step("set_poses", poses={frames[name]: pose for name, pose in scene.poses})


def _posable(m: Machine) -> list[str]:
    """The frames a pose can be set for (all but the world frame)."""
    return [name for name in m.names["frames"] if name != cs.WORLD]


#: The query that follows a near touch, by pick (mod 4).
_TOUCH_QUERIES = (
    "compute_point_pair_penetration",
    "compute_signed_distance_pair_closest_points",
    "has_collisions",
    "compute_signed_distance_pairwise_closest_points",
)


def _movable(book: PoseBook, a: str, b: str) -> bool:
    """Moving b's frame leaves a where it is: b is on a frame that is no ancestor of a's."""
    frame = book.geometries[b].frame
    return frame != cs.WORLD and frame not in book.lineage(book.geometries[a].frame)


def near_touch(m: Machine, picks: bytes, touch: cs.Touch) -> None:
    """Moves geometry B's frame so that B sits at ``touch.gap`` from geometry A; then a query.

    A and B are two geometries the book knows (B must be movable without
    moving A: else they swap, else nothing happens). B's
    frame F gets the drawn rotation ``R_PF`` in its parent P and the
    translation that puts B where ``strategies.touching_position`` says:
    ``p_WF = p_WB − R_WF p_FB``, ``p_PF = R_WPᵀ (p_WF − p_WP)``. The
    set_poses and the query (penetration, the pair's signed distance,
    HasCollisions or the pairwise signed distances, by pick) run at the
    picked location.
    """
    book = m.poses
    known = [name for name in m.names["geometries"] if name in book.geometries]
    if len(known) < 2:
        return
    first = touch.a % len(known)
    a, b = known[first], known[(first + 1 + touch.b % (len(known) - 1)) % len(known)]
    if not _movable(book, a, b):
        a, b = b, a
        if not _movable(book, a, b):
            return
    where = m.name("context", picks[0])
    location = where or MODEL
    frame = book.geometries[b].frame
    X_WP = book.frame_pose(book.parents[frame], location)
    R_WF = (X_WP * cs.Transform(cs.rotation(touch.rpy))).rotation
    X_FB = book.geometries[b].pose
    p_WB = cs.touching_position(
        book.geometries[a].shape,
        book.geometry_pose(a, location),
        book.geometries[b].shape,
        (cs.Transform(R_WF) * X_FB).rotation,
        direction=touch.direction,
        gap=touch.gap,
    )
    if p_WB is None:
        return
    offset = cs.Transform(R_WF).point(X_FB.translation)  # R_WF p_FB
    p_WF = (p_WB[0] - offset[0], p_WB[1] - offset[1], p_WB[2] - offset[2])
    p_PF = X_WP.local(p_WF)
    m.step("set_poses", poses={frame: {"xyz": list(p_PF), "rpy": list(touch.rpy)}}, context=where)
    query = _TOUCH_QUERIES[picks[1] % len(_TOUCH_QUERIES)]
    pair = {"pair": [a, b]} if query == "compute_signed_distance_pair_closest_points" else {}
    m.step(query, context=where, **pair)


def query_through_filter(m: Machine, picks: bytes, template: cs.DeclarationTemplate) -> None:
    """A transient declaration, every query there, its removal, then every query again.

    Filters exist to shape what the queries return: this asks each query
    the filter decides (``_FILTER_QUERIES``, and a pair's signed distance)
    right after the filter changes the answer, and again once it is gone, at
    the picked location. One time in two the declaration is aimed
    (``_answering_pairs``): it excludes (``ExcludeBetween({A}, {B})``) one of
    the pairs that penetrate there now, or (one time in two of those) every
    one of them, so that ``HasCollisions`` turns false where the only
    overlapping pairs are filtered; where none penetrate, the same of the
    collision candidates, which leave the candidates and the pairwise signed
    distances. Else the declaration is the drawn one.
    """
    label, where = m.fresh("t"), m.name("context", picks[0])
    pairs = _answering_pairs(m, where) if picks[3] & 1 else []
    pair: tuple[str, str] | None = None
    if pairs:
        chosen = pairs if picks[3] & 2 else [pairs[picks[3] // 4 % len(pairs)]]
        pair = chosen[0]
        declaration: dict[str, Any] = {
            "statements": [
                {"op": "exclude_between", "a": {"geometries": [a]}, "b": {"geometries": [b]}}
                for a, b in chosen
            ]
        }
    else:
        declaration = m.declaration(template)
    result = m.step("apply_transient", declaration=declaration, label=label, context=where)
    _every_query(m, picks, where, pair)
    if result.error is None:
        m.step("remove_declaration", label=label, context=where)
        _every_query(m, picks, where, pair)


def _pairs_of(result: Result) -> list[tuple[str, str]]:
    """The name pairs of a penetration or candidates answer (none if it failed)."""
    if result.error is not None or not isinstance(result.value, list):
        return []
    pairs = [r.get("pair") if isinstance(r, Mapping) else r for r in result.value]
    return [(str(p[0]), str(p[1])) for p in pairs if isinstance(p, list) and len(p) == 2]


def _answering_pairs(m: Machine, where: str | None) -> list[tuple[str, str]]:
    """The pairs that penetrate at ``where`` now (asked), else its collision candidates."""
    penetrating = _pairs_of(m.step("compute_point_pair_penetration", context=where))
    return penetrating or _pairs_of(m.step("find_collision_candidates", context=where))


#: The queries a filter decides (``query_through_filter`` asks each, and a pair's distance).
_FILTER_QUERIES = (
    "compute_point_pair_penetration",
    "has_collisions",
    "compute_signed_distance_pairwise_closest_points",
    "find_collision_candidates",
)


def _every_query(m: Machine, picks: bytes, where: str | None, pair: tuple[str, str] | None) -> None:
    """Each of ``_FILTER_QUERIES`` at ``where``, then the signed distance of ``pair`` (or of
    a picked pair: ``signed_distance_pair``)."""
    for query in _FILTER_QUERIES:
        m.step(query, context=where)
    if pair is None:
        signed_distance_pair(m, picks[2:] + picks[:1])
    else:
        m.step("compute_signed_distance_pair_closest_points", pair=list(pair), context=where)


#: Radii and gaps (m) of ``query_at_max_distance``'s spheres.
_EXACT_RADII = (0.05, 0.1, 0.275)
_EXACT_GAPS = (0.125, 0.25, 0.5, 1.0)
_PAIRWISE = "compute_signed_distance_pairwise_closest_points"


def _distances(result: Result) -> list[float]:
    """The distances of a pairwise answer, in its order (none if it failed)."""
    if result.error is not None or not isinstance(result.value, list):
        return []
    found = [r.get("distance") for r in result.value if isinstance(r, Mapping)]
    return [d for d in found if isinstance(d, float) and math.isfinite(d)]


def _aim(distance: float, pick: int) -> float:
    """``distance``, or 1 ulp below or above it, by pick (mod 3)."""
    aims = (distance, math.nextafter(distance, -math.inf), math.nextafter(distance, math.inf))
    return aims[pick % len(aims)]


def query_at_max_distance(m: Machine, picks: bytes) -> None:
    """The pairwise signed distances, then again with ``max_distance`` aimed at a pair's
    own distance φ: exactly φ, or 1 ulp below or above it (by pick).

    φ is the reference's answer in the first (unbounded) query. One time in
    two (``picks[3]``) the pair is one of the scene's at the picked location
    (``picks[1]`` draws it from the first answer): Drake then reports a pair at
    ``φ = max_distance`` unless its broadphase pruned it, and reimpl's φ may
    differ from Drake's in the last bits; an answer that differs only in pairs
    within their distance tolerance of ``max_distance`` is the known
    divergences ``pairwise-prunes-ties-at-max-distance`` and
    ``sphere-distance-last-bits`` (``scenarios/queries/max_distance.json``,
    measured on pydrake 1.51.1 and 1.58.0), which the campaign sets aside.
    Else it is a pair of two new spheres (``_sphere_pair``), made so that
    both sides compute φ to the same double and no broadphase ties it: there
    a pair at ``φ = max_distance`` is in the answer, 1 ulp beyond it is not
    (measured on pydrake 1.51.1: 108 of 108 radius, gap and offset triples,
    324 of 324 aims).
    """
    if picks[3] & 1:
        where = m.name("context", picks[0])
        distances = _distances(m.step(_PAIRWISE, context=where))
        if distances:
            distance = distances[picks[1] % len(distances)]
            m.step(_PAIRWISE, max_distance=_aim(distance, picks[2]), context=where)
        return
    names = _sphere_pair(m, picks)
    if names is None:
        return
    result = m.step(_PAIRWISE)
    records = result.value if result.error is None and isinstance(result.value, list) else []
    pair = sorted(names)
    found = [r["distance"] for r in records if isinstance(r, Mapping) and r.get("pair") == pair]
    if found and isinstance(found[0], float):
        m.step(_PAIRWISE, max_distance=_aim(found[0], picks[2]))


def _sphere_pair(m: Machine, picks: bytes) -> tuple[str, str] | None:
    """Two new spheres on new frames of the world, on a diagonal: their names, or None.

    Identity rotations, centres ``(a, 10, 0)`` and ``(a + x, 10 + x, 0)``,
    ``a`` apart from every other such pair. On a diagonal, not an axis: there
    the gap between the spheres' bounding boxes is φ too, and the
    broadphase's pruning at exactly ``max_distance`` decides
    (``pairwise-prunes-ties-at-max-distance``).
    """
    frames, names = (m.fresh("f"), m.fresh("f")), (m.fresh("g"), m.fresh("g"))
    radii = (_EXACT_RADII[picks[0] % 3], _EXACT_RADII[picks[0] // 3 % 3])
    for frame, name, radius in zip(frames, names, radii, strict=True):
        made = m.step("register_frame", name=frame)
        m.keep_if_made("frames", frame, made)
        sphere = {"type": "sphere", "radius": radius}
        result = m.step(
            "register_geometry", name=name, frame=frame, roles=["proximity"], shape=sphere
        )
        if made.error is not None or not _registered(result):
            return None
        m.keep("geometries", name)
    x = (radii[0] + radii[1] + _EXACT_GAPS[picks[1] % len(_EXACT_GAPS)]) / 2
    at = 10.0 + 2.0 * len(m.names["frames"])  # each pair apart from the scene and the others
    poses = {frames[0]: {"xyz": [at, 10.0, 0.0]}, frames[1]: {"xyz": [at + x, 10.0 + x, 0.0]}}
    m.step("set_poses", poses=poses)
    return names


#: The queries ``filter_in_clone`` asks in the clone (none needs a pair of its own).
_CLONE_QUERIES = (
    "x_wg",
    *(q for q in _TOUCH_QUERIES if q != "compute_signed_distance_pair_closest_points"),
)


def filter_in_clone(m: Machine, picks: bytes, template: cs.DeclarationTemplate) -> None:
    """A clone of a context, a persistent declaration applied in it, then a query there.

    The clone carries its origin's poses and filters; what is applied in it
    must shape its own queries and candidates, and neither its origin's nor
    the model's (the invariant compares every location). The query is
    ``x_wg`` of a picked geometry (a clone keeps its origin's poses) or one
    of the touching queries over all pairs. Picks alone rarely land there:
    contexts are few, clones fewer, and most steps of a posed example are
    queries.
    """
    clone = _clone(m, m.name("origin", picks[0]))
    if clone is None:
        return
    m.step("apply", declaration=m.declaration(template), context=clone)
    query = _CLONE_QUERIES[picks[1] % len(_CLONE_QUERIES)]
    geometry = {"geometry": m.name("geometry", picks[2])} if query == "x_wg" else {}
    m.step(query, context=clone, **geometry)


def signed_distance_pair(m: Machine, picks: bytes) -> None:
    """compute_signed_distance_pair_closest_points of two different geometries, in either order.

    Now and then the first is ``@unknown`` or ``@foreign``. A geometry is
    never paired with itself: for a shape against itself the witness points
    and the normal are arbitrary, and two pydrake SceneGraphs answer
    differently for GJK pairs (cylinder-cylinder, measured: witness points
    0.1 m and normals 0.2 apart).
    """
    names = m.names["geometries"]
    first, second = m.name("any_geometry", picks[0]), m.name("geometry", picks[1])
    if second is None or first == second:
        second = names[(names.index(first) + 1) % len(names)] if first in names else second
    if first is None or first == second:
        return
    m.step(
        "compute_signed_distance_pair_closest_points",
        pair=[first, second],
        context=m.name("context", picks[2]),
    )


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
    "grow_scene": Operation(
        register_geometries,
        (st.binary(min_size=4 * _PLACEMENT, max_size=8 * _PLACEMENT),),
        enabled=lambda m: len(m.names["geometries"]) <= GROW_UP_TO,
        issues=frozenset({"register_geometry"}),
    ),
    "assign_role": Operation(assign_role, enabled=_has("geometries")),
    "remove_role": Operation(remove_role, enabled=_has("geometries")),
    "reassign_proximity": Operation(
        reassign_proximity,
        enabled=_has("geometries"),
        issues=frozenset({"remove_role", "assign_role", "apply"}),
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
        enabled=_can_clone,
    ),
    "clone_with_history": Operation(
        clone_with_history,
        (_DECLARATION, _DECLARATION),
        enabled=_can_clone,
        issues=frozenset({"apply_transient", "clone_context", "remove_declaration"}),
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
    ArgKind.SHAPE: cs.shapes(),
    ArgKind.POSE: cs.poses(),
    ArgKind.POSES: cs.poses(),
    ArgKind.POINT: cs.points(),
}
#: A ``max_distance`` read from a pick of 128 or more (below: left out, infinite).
_DISTANCES = (0.0, 1e-3, 0.01, 0.1, 0.5)


def _distance(pick: int) -> float | None:
    return _DISTANCES[pick % len(_DISTANCES)] if pick >= cs.PICK_RANGE // 2 else None


def _frame_poses(m: Machine, pick: int, pose: dict[str, list[float]]) -> dict[str, Any]:
    """One frame's pose (the pick's frame, never the world), or none while only the world is."""
    frames = _posable(m)
    return {frames[pick % len(frames)]: pose} if frames else {}


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
    ArgKind.SHAPE: lambda m, a, p, t: next(t),
    ArgKind.POSE: lambda m, a, p, t: next(t) or None,
    ArgKind.POSES: lambda m, a, p, t: _frame_poses(m, p, next(t)),
    ArgKind.DISTANCE: lambda m, a, p, t: _distance(p),
    ArgKind.POINT: lambda m, a, p, t: next(t),
}

#: Features an op may need beyond SceneGraph's core, and whether both backends have it.
_FEATURES: dict[str, Callable[[Machine], bool]] = {
    "activation": lambda m: m.activation,
    "queries": lambda m: m.queries,
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
    arguments need exist, and for ``activation`` and ``queries`` ops only if
    both backends have them (``_FEATURES``). Every op without a hand-written
    operation gets one, so a new op needs only its grammar row and its
    handler to be fuzzed.
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

    feature = _FEATURES.get(command.feature)

    def enabled(m: Machine) -> bool:
        if feature is not None and not feature(m):
            return False
        return all(m.names[bundle] for bundle in needs)

    return Operation(run, arguments, enabled, frozenset({command.op}))


def planned_operation(
    byte: int, enabled: Sequence[str], weights: Mapping[str, int] | None = None
) -> str | None:
    """The operation a plan byte names.

    0 names none (bytes shrink to 0). Without ``weights``, any other byte
    names ``enabled[(byte - 1) % len(enabled)]``. With them (swarm testing:
    a weight per operation, drawn per example), operation i of ``enabled``
    owns ``weights[i]`` consecutive values of ``(byte - 1) % Σ weights``.
    """
    if not byte:
        return None
    if weights is None:
        return enabled[(byte - 1) % len(enabled)]
    at = (byte - 1) % sum(weights.get(name, 1) for name in enabled)
    for name in enabled:
        at -= weights.get(name, 1)
        if at < 0:
            return name
    raise AssertionError("unreachable: the weights cover every value")


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

#: The ops of the grammar's ``queries`` domain: set_poses and the QueryObject queries.
QUERY_OPS = ops_of("queries")


def _pairs_queryable(m: Machine) -> bool:
    return m.queries and len(m.names["geometries"]) > 1


#: ``fuzz --poses``: ``OPERATIONS`` with shapes and poses in every registration, a
#: generic operation for every query op, and ``near_touch`` (see the module doc).
POSED_OPERATIONS: dict[str, Operation] = {
    **OPERATIONS,
    "register_frame": Operation(register_posed_frame),
    "register_geometries": Operation(
        register_posed_geometries,
        (st.binary(min_size=_POSED_PLACEMENT, max_size=4 * _POSED_PLACEMENT),),
        issues=frozenset({"register_geometry"}),
    ),
    "grow_scene": Operation(
        register_posed_geometries,
        (st.binary(min_size=4 * _POSED_PLACEMENT, max_size=8 * _POSED_PLACEMENT),),
        enabled=lambda m: len(m.names["geometries"]) <= GROW_UP_TO,
        issues=frozenset({"register_geometry"}),
    ),
    "near_touch": Operation(
        near_touch,
        (cs.touches(),),
        enabled=_pairs_queryable,
        issues=frozenset({"set_poses", *_TOUCH_QUERIES}),
    ),
    **{op: generic_operation(GRAMMAR[op]) for op in QUERY_OPS},
    "compute_signed_distance_pair_closest_points": Operation(
        signed_distance_pair, enabled=_pairs_queryable
    ),
    "query_through_filter": Operation(
        query_through_filter,
        (_DECLARATION,),
        enabled=_pairs_queryable,
        issues=frozenset(
            {
                "apply_transient",
                "remove_declaration",
                "compute_signed_distance_pair_closest_points",
                *_FILTER_QUERIES,
            }
        ),
    ),
    "filter_in_clone": Operation(
        filter_in_clone,
        (_DECLARATION,),
        enabled=lambda m: _pairs_queryable(m) and _can_clone(m),
        issues=frozenset({"clone_context", "apply", *_CLONE_QUERIES}),
    ),
    "query_at_max_distance": Operation(
        query_at_max_distance,
        enabled=lambda m: m.queries,
        issues=frozenset({"register_frame", "register_geometry", "set_poses", _PAIRWISE}),
    ),
}
