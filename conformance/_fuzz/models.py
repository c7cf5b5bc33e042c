"""Random kinematic trees and their collision filter groups, rendered as URDF and SDFormat (public).

A ``Model`` is pure data (``conformance._fuzz.model_data``): bodies with
geometry, the joints of a tree over them, frames, SDFormat nested models and
includes, and ``<drake:collision_filter_group>`` declarations. ``to_urdf``
and ``to_sdf`` (``conformance._fuzz.model_render``) render it;
``kinematic_trees`` draws one. ``conformance._fuzz.model_scenes`` puts
models into files, packages and model directives.

>>> from conformance._fuzz.models import kinematic_trees, to_sdf, to_urdf
>>> model = kinematic_trees(formats=("urdf", "sdf")).example()  # doctest: +SKIP
>>> text = to_urdf(model)  # doctest: +SKIP

**The tree.** Body ``l0`` and each later body either is a root or hangs from
an earlier body, so the joints form a forest over the bodies. A root is free
(Finalize gives it a QuaternionFloatingJoint to the world), or joined to the
world by a joint whose parent is the world, or, in URDF only, by a joint
whose *child* is the world (a reversed joint: Drake accepts it for the kinds
it can reverse, which ``JOINT_KINDS`` marks). A joint between two bodies may
be reversed too (the later body is its parent). What each kind is in each
format was measured on pydrake 1.51.1:

============ ============================== ============ =================== =========
kind         URDF                           SDFormat     Drake's joint       reversible
============ ============================== ============ =================== =========
revolute     ``<joint type="revolute">``    revolute     RevoluteJoint       yes
continuous   ``<joint type="continuous">``  continuous   RevoluteJoint       yes
prismatic    ``<joint type="prismatic">``   prismatic    PrismaticJoint      yes
fixed        ``<joint type="fixed">``       fixed        WeldJoint           yes
floating     ``<joint type="floating">``    (invalid)    none: the child is  no
                                                         left free (warning)
planar       ``<joint type="planar">``      (invalid)    PlanarJoint         no
drake_planar ``<drake:joint type="planar">`` (invalid)   PlanarJoint         no
ball         ``<drake:joint type="ball">``  ball         BallRpyJoint        no
universal    ``<drake:joint ...>``          universal    UniversalJoint      no
screw        ``<drake:joint ...>`` and      screw        ScrewJoint          no
             ``<drake:screw_thread_pitch>``
curvilinear  ``<drake:joint ...>`` and      (invalid)    CurvilinearJoint    no
             ``<drake:curves>``
============ ============================== ============ =================== =========

SDFormat wants an ``<axis>`` for revolute, continuous, prismatic and screw,
and ``<axis>`` with ``<axis2>`` for universal; the renderer writes them. With
``joint_attributes``, revolute and prismatic joints may have limits
(lower ≤ upper) and every kind Drake reads a damping for may have one (≥ 0).

**Geometry.** 0-3 per body, of ``shapes`` (default: sphere, box, cylinder;
``SHAPE_KINDS`` has Drake's capsule and ellipsoid, SDFormat's own shapes and
meshes), ``<collision>`` or ``<visual>``, named or not. Names are unique per
body and element kind (SDFormat rejects a repeated collision name in a
link). URDF leaves an unnamed element unnamed, and Drake names it after its
shape (``Sphere``, ``Box_1``...); SDFormat requires a name, so ``to_sdf``
writes ``collision<k>`` or ``visual<k>`` (``k``: its position in the body).
``geometry_names`` lists the names a scenario can refer to without knowing
Drake's default-name rule. A ``plane`` is always a ``<visual>``: Drake's
HalfSpace on a moving body crashes FCL's broadphase (Drake issue #19263;
pydrake 1.51.1 and 1.58.0 segfault with 8 such bodies). A mesh (``mesh``, or ``convex``: with
``<drake:declare_convex/>``) names ``mesh.obj`` (a visual one may name
``mesh.stl``) and may be scaled: in URDF by one value or three, in
SDFormat by three (one is an SDFormat error, measured).

**Frames.** With ``max_frames``, ``<frame>`` elements: in URDF on a link or
the world; in SDFormat attached to a link, an earlier frame, a nested or
included model, or a body inside one (``n0::l1``), some with a pose
``relative_to`` a link or an earlier frame; and a joint between two of the
model's own links may name, as its parent or child, a frame on that link.

**Groups.** ``name``, ``members`` (links), ``member_groups`` and
``ignored`` (``ignored_collision_filter_group``) name other groups, possibly
later ones, the group itself, or groups forming a cycle; ``ignore`` is the
attribute as written. Whether it drops the group depends on the format
(``drops``): URDF honours exactly ``"true"``, SDFormat reads a boolean
(``true``, ``1``, ``True``; measured). A dropped group is gone: a reference to
it is an error (``collision filter group with name 'm::g' not found``). A
valid model therefore refers only to groups that no format it is drawn for
drops, and every kept group has a member or a member group (else
``group 'm::g' has no members``).

**Faults.** ``kinematic_trees(invalid=True)`` breaks one rule on purpose:
one of ``FAULTS`` that every format drawn has (the groups' rules above, a
joint to an unknown link, a link or frame named ``world`` in SDFormat, a
negative damping, a lower limit above the upper, a ``.stl`` collision mesh,
a URDF scale of two values, a frame on an unknown link or in a cycle), each
refused by pydrake 1.51.1 (measured).
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from typing import TypeVar

from hypothesis import strategies as st

from conformance._fuzz.model_data import (
    DRAKE_NAMESPACE,
    FORMATS,
    IGNORE_VALUES,
    JOINT_KINDS,
    SHAPE_KINDS,
    SHAPES,
    WORLD,
    Body,
    Frame,
    Geometry,
    Group,
    Include,
    Joint,
    JointKind,
    Model,
    ShapeKind,
    drops,
    geometry_names,
)
from conformance._fuzz.model_render import MESH_BASE, render, to_sdf, to_urdf

__all__ = [
    "DRAKE_NAMESPACE",
    "FAULTS",
    "FORMATS",
    "GROUP_FAULTS",
    "IGNORE_VALUES",
    "JOINT_KINDS",
    "MESH_BASE",
    "SHAPES",
    "SHAPE_KINDS",
    "WORLD",
    "Body",
    "Frame",
    "Geometry",
    "Group",
    "Include",
    "Joint",
    "JointKind",
    "Model",
    "ShapeKind",
    "collision_filter_groups",
    "drops",
    "faults_for",
    "free_roots",
    "geometry_names",
    "kinematic_trees",
    "render",
    "spread",
    "to_sdf",
    "to_urdf",
]

T = TypeVar("T")
#: Names a geometry may be given; the shape names meet Drake's default names.
_GEOMETRY_NAMES = ("c0", "c1", "c2", "Sphere", "Box")
#: Names of links and groups that no model defines.
_UNDEFINED_LINKS = ("zz", WORLD)
_UNDEFINED_GROUP = "nope"
#: Valid joint attributes as written: limits (lower ≤ upper) and dampings (≥ 0).
_LIMITS = (("-1", "1"), ("0", "0.5"))
_DAMPINGS = ("0", "0.1")
#: Shapes drawn as visual geometry only: a HalfSpace for proximity on a moving body can
#: crash Drake (Drake issue #19263: a segfault in FCL's broadphase; measured on pydrake
#: 1.51.1 and 1.58.0 with 8 or more such bodies, each with a sphere beside it).
_VISUAL_ONLY = frozenset({"plane"})
#: Mesh scales: URDF reads one value or three, SDFormat three.
_SCALES = {"urdf": (None, "2", "1 2 3"), "sdf": (None, "1 2 3")}


def spread(items: Sequence[T]) -> st.SearchStrategy[T]:
    """One of ``items``, about evenly: a wide integer modulo their number.

    N.B. Hypothesis draws ``sampled_from`` and small ``integers`` far from
    evenly over a few hundred examples (measured at seed 1: a joint kind of
    eleven never drawn in 300 cases, a fault of five never in 25 draws), so
    the model grammar's categorical choices are drawn this way. It still
    shrinks to the first item.
    """
    return st.integers(0, 1 << 16).map(lambda i: items[i % len(items)])


def _kinds_for(formats: Sequence[str], kinds: Iterable[str] | None) -> tuple[str, ...]:
    """The joint kinds every format in ``formats`` has (among ``kinds``, if given)."""
    allowed = tuple(kinds) if kinds is not None else tuple(JOINT_KINDS)
    out = tuple(
        name
        for name in allowed
        if all(getattr(JOINT_KINDS[name], fmt) is not None for fmt in formats)
    )
    if not out:
        raise ValueError(f"no joint kind of {allowed} exists in every format of {formats}")
    return out


def _shapes_for(formats: Sequence[str], shapes: Iterable[str]) -> tuple[str, ...]:
    """The shapes of ``shapes`` that every format in ``formats`` has."""
    out = tuple(s for s in shapes if all(getattr(SHAPE_KINDS[s], fmt) for fmt in formats))
    if not out:
        raise ValueError(f"no shape of {tuple(shapes)} exists in every format of {formats}")
    return out


def free_roots(model: Model) -> list[str]:
    """The root of each tree of the model's top-level bodies that no joint joins to the
    world: a body that is no joint's child, in a tree without a world joint. Welding one
    to anything makes no loop (a URDF floating joint joins nothing: Drake drops it)."""
    bodies = [b.name for b in model.bodies]
    parent: dict[str, str] = {name: name for name, _ in model.scoped_bodies()}
    parent[WORLD] = WORLD

    def find(name: str) -> str:
        while parent[name] != name:
            name = parent[name]
        return name

    children: set[str] = set()
    for joint in model.joints:
        if joint.kind == "floating":
            continue
        ends = [
            _body_of(end, model.frames, list(parent)) or end for end in (joint.parent, joint.child)
        ]
        if not all(end in parent for end in ends):
            continue
        children.add(ends[1])
        parent[find(ends[0])] = find(ends[1])
    grounded = find(WORLD)
    return [b for b in bodies if b not in children and find(b) != grounded]


# ------------------------------------------------------------------ geometry
class _Root(enum.Enum):
    """How a root body meets the world."""

    FREE = "free"
    PARENT_WORLD = "parent_world"  # a joint from the world to it
    CHILD_WORLD = "child_world"  # a joint from it to the world (URDF, reversible kinds)


def _geometry(
    shapes: Sequence[str], formats: Sequence[str], one_value_scale: bool = True
) -> st.SearchStrategy[Geometry]:
    """One geometry; a mesh gets a scale every format reads (one value only if
    ``one_value_scale``), and a visual one may name .stl."""
    scales = [s for s in _SCALES["urdf"] if all(s in _SCALES[fmt] for fmt in formats)]
    if not one_value_scale:
        scales = [s for s in scales if s is None or " " in s]

    def mesh(geometry: Geometry) -> st.SearchStrategy[Geometry]:
        if geometry.shape in _VISUAL_ONLY:
            return st.just(replace(geometry, collision=False))
        if not SHAPE_KINDS[geometry.shape].mesh:
            return st.just(geometry)
        files = ("mesh.obj",) if geometry.collision else ("mesh.obj", "mesh.stl")
        return st.builds(
            replace,
            st.just(geometry),
            scale=st.sampled_from(scales),
            mesh=st.sampled_from(files),
        )

    return st.builds(
        Geometry,
        shape=spread(shapes),
        name=st.none() | st.sampled_from(_GEOMETRY_NAMES),
        collision=st.booleans().map(lambda visual: not visual),
    ).flatmap(mesh)


@st.composite
def _geometries(
    draw: st.DrawFn,
    max_geometries: int,
    shapes: Sequence[str],
    formats: Sequence[str],
    one_value_scale: bool = True,
) -> tuple[Geometry, ...]:
    drawn = draw(st.lists(_geometry(shapes, formats, one_value_scale), max_size=max_geometries))
    seen: set[tuple[bool, str]] = set()
    out = []
    for geometry in drawn:  # names unique per body and element kind
        key = (geometry.collision, geometry.name or "")
        out.append(replace(geometry, name=None) if key in seen else geometry)
        if geometry.name is not None:
            seen.add(key)
    return tuple(out)


# ------------------------------------------------------------------ groups
#: A group as drawn: its ``ignore`` attribute, then picks of its members, member groups and
#: ignored groups (resolved once all groups and bodies are drawn).
_GroupSpec = tuple[str | None, list[int], list[int], list[int]]


def _group_specs(
    max_groups: int, max_members: int, ignore_values: Sequence[str | None]
) -> st.SearchStrategy[list[_GroupSpec]]:
    """Groups as drawn: ``ignore``, then picks of members, member groups and ignored groups."""
    references = st.lists(st.integers(0, max(max_groups - 1, 0)), max_size=2)
    return st.lists(
        st.tuples(
            # ``ignore`` is written rarely; None (not written) is where it shrinks to.
            st.integers(0, 3).flatmap(
                lambda x: st.sampled_from(ignore_values) if x == 3 else st.just(None)
            ),
            st.lists(st.integers(0, 255), max_size=max_members),
            references,
            references,
        ),
        max_size=max_groups,
    )


def _kept(groups: Iterable[tuple[str, Group]], formats: Sequence[str]) -> list[str]:
    """The names of the groups that no format of ``formats`` drops."""
    return [name for name, g in groups if not any(drops(g, fmt) for fmt in formats)]


def _groups(
    specs: Sequence[_GroupSpec],
    bodies: Sequence[str],
    formats: Sequence[str],
    children: Sequence[tuple[str, Model]] = (),
    prefix: str = "",
) -> list[Group]:
    """The groups of ``specs`` over ``bodies``, valid in every format of ``formats``; their
    member and ignored groups may be the kept groups of ``children`` (scope, model) too."""
    names = [f"{prefix}g{i}" for i in range(len(specs))]
    own = [(n, Group(n, ignore=spec[0])) for n, spec in zip(names, specs, strict=True)]
    kept = _kept(own, formats)
    kept += [
        f"{scope}{name}"
        for scope, inner in children
        if scope  # a merged include's groups are dropped (model_data.Model.all_groups)
        for name in _kept(inner.all_groups(), formats)
    ]

    def resolve(picks: Sequence[int], among: Sequence[str]) -> tuple[str, ...]:
        return tuple(among[pick % len(among)] for pick in picks) if among else ()

    groups: list[Group] = []
    for name, (ignore, members, member_groups, ignored) in zip(names, specs, strict=True):
        group = Group(
            name,
            resolve(members, bodies),
            resolve(member_groups, kept),
            resolve(ignored, kept),
            ignore,
        )
        if not group.members and not group.member_groups:
            group = replace(group, members=(bodies[0],))
        groups.append(group)
    return groups


@st.composite
def collision_filter_groups(
    draw: st.DrawFn,
    bodies: Sequence[str],
    *,
    formats: Sequence[str] = FORMATS,
    max_groups: int = 4,
    max_members: int = 3,
    ignore_values: Sequence[str | None] = IGNORE_VALUES,
    invalid: bool = False,
) -> tuple[Group, ...]:
    """Groups ``g0``, ``g1``... over ``bodies`` (names of links): members, member groups
    (cycles and forward references included), ignored groups (the group itself included),
    ``ignore`` attributes.

    Valid in every format of ``formats`` unless ``invalid``: then one of the
    group faults of ``FAULTS``. Each group is one list element, so the
    shrinker deletes whole groups.
    """
    groups = _groups(draw(_group_specs(max_groups, max_members, ignore_values)), bodies, formats)
    if invalid:
        fault = draw(st.sampled_from(_GROUP_FAULTS))
        model = _GROUP_FAULT_FUNCTIONS[fault](draw, Model("m", (Body(bodies[0]),)), groups, bodies)
        groups = list(model.groups)
    return tuple(groups)


# ------------------------------------------------------------------ frames
#: A frame as drawn: picks of what it is attached to and (None: no pose) relative to.
_FrameSpec = tuple[int, int | None]


def _frame_targets(model: Model, fmt_sdf: bool, into_children: bool) -> list[str]:
    """What a frame may be attached to: the model's bodies, in SDFormat also (with
    ``into_children``) its children (not merged includes) and their bodies; in URDF also
    the world."""
    bodies = [b.name for b in model.bodies]
    if not fmt_sdf:
        return [*bodies, WORLD]
    if not into_children:
        return bodies
    children = [scope.removesuffix("::") for scope, _ in model.children() if scope]
    inner = [name for name, _ in model.scoped_bodies() if name not in bodies]
    return [*bodies, *children, *inner]


def _frames(
    specs: Sequence[_FrameSpec], model: Model, sdf: bool, prefix: str, into_children: bool
) -> list[Frame]:
    """The frames of ``specs``: each on a target or (SDFormat) an earlier frame, some with
    a pose relative to a body or an earlier frame (SDFormat only)."""
    targets = _frame_targets(model, sdf, into_children)
    bodies = [b.name for b in model.bodies]
    frames: list[Frame] = []
    for i, (attach, relative) in enumerate(specs):
        earlier = [f.name for f in frames] if sdf else []
        among = [*targets, *earlier]
        relative_to = None
        if relative is not None:
            relatives = [*bodies, *earlier]
            relative_to = relatives[relative % len(relatives)]
        frames.append(Frame(f"{prefix}f{i}", among[attach % len(among)], relative_to))
    return frames


def _body_of(frame: str, frames: Sequence[Frame], bodies: Sequence[str]) -> str | None:
    """The model's own body a frame's chain of ``attached_to`` ends at (None: elsewhere)."""
    by_name = {f.name: f for f in frames}
    seen: set[str] = set()
    while frame in by_name and frame not in seen:
        seen.add(frame)
        frame = by_name[frame].attached_to
    return frame if frame in bodies else None


def _through_frames(
    joints: Sequence[Joint], frames: Sequence[Frame], bodies: Sequence[str], picks: Sequence[int]
) -> list[Joint]:
    """SDFormat: joints whose parent or child is, by ``picks``, a frame on that body (each
    joint one of them, where a frame is on it)."""
    on: dict[str, list[str]] = {}
    for frame in frames:
        body = _body_of(frame.name, frames, bodies)
        if body is not None:
            on.setdefault(body, []).append(frame.name)
    out = []
    for joint, pick in zip(joints, [*picks, *[0] * len(joints)], strict=False):
        parent, child = joint.parent, joint.child
        if pick % 2 == 0 and parent in on:
            parent = on[parent][pick // 2 % len(on[parent])]
        elif child in on:
            child = on[child][pick // 2 % len(on[child])]
        out.append(replace(joint, parent=parent, child=child))
    return out


# ------------------------------------------------------------------ faults
def _extra_body(model: Model, prefix: str) -> str:
    return f"{prefix}lx"


def _group_fault(
    draw: st.DrawFn, groups: list[Group], bodies: Sequence[str]
) -> tuple[list[Group], int, Group]:
    """The groups (one made if none), the index of the one to break, and it, kept."""
    groups = list(groups)
    if not groups:
        groups = [Group("g0", members=(bodies[0],), ignored=("g0",))]
    at = draw(st.integers(0, len(groups) - 1))
    group = groups[at] = replace(groups[at], ignore=None)  # a dropped group would hide it
    return groups, at, group


def _unknown_link(
    draw: st.DrawFn, model: Model, groups: list[Group], bodies: Sequence[str]
) -> Model:
    groups, at, group = _group_fault(draw, groups, bodies)
    link = draw(st.sampled_from(_UNDEFINED_LINKS))
    groups[at] = replace(group, members=(*group.members, link))
    return replace(model, groups=tuple(groups))


def _undefined_member_group(
    draw: st.DrawFn, model: Model, groups: list[Group], bodies: Sequence[str]
) -> Model:
    groups, at, group = _group_fault(draw, groups, bodies)
    groups[at] = replace(group, member_groups=(*group.member_groups, _UNDEFINED_GROUP))
    return replace(model, groups=tuple(groups))


def _undefined_ignored_group(
    draw: st.DrawFn, model: Model, groups: list[Group], bodies: Sequence[str]
) -> Model:
    groups, at, group = _group_fault(draw, groups, bodies)
    groups[at] = replace(group, ignored=(*group.ignored, _UNDEFINED_GROUP))
    return replace(model, groups=tuple(groups))


def _empty_group(
    draw: st.DrawFn, model: Model, groups: list[Group], bodies: Sequence[str]
) -> Model:
    groups, at, group = _group_fault(draw, groups, bodies)
    groups[at] = replace(group, members=(), member_groups=())
    return replace(model, groups=tuple(groups))


def _duplicate_group(
    draw: st.DrawFn, model: Model, groups: list[Group], bodies: Sequence[str]
) -> Model:
    # The copy is of the kept group at ``at``: a copy of a group some format drops
    # (URDF ignore="true") is no duplicate there, and Drake accepts it (measured).
    groups, _, group = _group_fault(draw, groups, bodies)
    return replace(model, groups=(*groups, group))


def _scoped_group_name(
    draw: st.DrawFn, model: Model, groups: list[Group], bodies: Sequence[str]
) -> Model:
    groups, at, group = _group_fault(draw, groups, bodies)
    groups[at] = replace(group, name=f"x::{group.name}")
    return replace(model, groups=tuple(groups))


_GroupFault = Callable[[st.DrawFn, Model, list[Group], Sequence[str]], Model]
_GROUP_FAULT_FUNCTIONS: dict[str, _GroupFault] = {
    "unknown_link": _unknown_link,  # a member link no body has (or the world)
    "undefined_member_group": _undefined_member_group,
    "undefined_ignored_group": _undefined_ignored_group,
    "empty_group": _empty_group,  # no members, no member groups
    "duplicate_group": _duplicate_group,
    "scoped_group_name": _scoped_group_name,
}
_GROUP_FAULTS = tuple(_GROUP_FAULT_FUNCTIONS)


def _joint_to_unknown_link(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    joint = Joint(f"{prefix}jx", "fixed", model.bodies[0].name, "zz")
    return replace(model, joints=(*model.joints, joint))


def _world_link(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    return replace(model, bodies=(*model.bodies, Body(WORLD)))


def _world_frame(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    return replace(model, frames=(*model.frames, Frame(WORLD, model.bodies[0].name)))


def _faulty_joint(model: Model, prefix: str, joint: Joint) -> Model:
    body = Body(_extra_body(model, prefix), (Geometry("sphere", "c0"),))
    return replace(model, bodies=(*model.bodies, body), joints=(*model.joints, joint))


def _negative_damping(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    kinds = [
        k.name
        for k in JOINT_KINDS.values()
        if k.damping and getattr(k, fmt) is not None and (fmt == "urdf" or k.axes)
    ]
    kind = draw(spread(kinds))
    joint = Joint(f"{prefix}jx", kind, model.bodies[0].name, _extra_body(model, prefix))
    return _faulty_joint(model, prefix, replace(joint, damping="-1"))


def _inverted_limits(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    kind = draw(st.sampled_from([k.name for k in JOINT_KINDS.values() if k.limits]))
    joint = Joint(f"{prefix}jx", kind, model.bodies[0].name, _extra_body(model, prefix))
    return _faulty_joint(model, prefix, replace(joint, limits=("1", "-1")))


def _stl_collision(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    shape = draw(st.sampled_from(("mesh", "convex")))
    geometry = Geometry(shape, "c0", mesh="mesh.stl")
    return replace(model, bodies=(*model.bodies, Body(_extra_body(model, prefix), (geometry,))))


def _two_value_scale(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    geometry = Geometry("mesh", "c0", scale="1 2")
    return replace(model, bodies=(*model.bodies, Body(_extra_body(model, prefix), (geometry,))))


def _frame_on_unknown_link(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    return replace(model, frames=(*model.frames, Frame(f"{prefix}fx", "zz")))


def _frame_cycle(draw: st.DrawFn, model: Model, prefix: str, fmt: str) -> Model:
    cycle = (Frame(f"{prefix}fx", f"{prefix}fy"), Frame(f"{prefix}fy", f"{prefix}fx"))
    return replace(model, frames=(*model.frames, *cycle))


_ModelFault = Callable[[st.DrawFn, Model, str, str], Model]
#: fault → (the formats it exists in, how it breaks the model).
_MODEL_FAULTS: dict[str, tuple[tuple[str, ...], _ModelFault]] = {
    "joint_to_unknown_link": (FORMATS, _joint_to_unknown_link),
    "world_link": (("sdf",), _world_link),
    "world_frame": (("sdf",), _world_frame),
    "negative_damping": (FORMATS, _negative_damping),
    "inverted_limits": (FORMATS, _inverted_limits),
    "stl_collision": (FORMATS, _stl_collision),
    "two_value_scale": (("urdf",), _two_value_scale),
    "frame_on_unknown_link": (FORMATS, _frame_on_unknown_link),
    "frame_cycle": (("sdf",), _frame_cycle),
}
#: Every way ``kinematic_trees(invalid=True)`` breaks a model.
FAULTS = (*_GROUP_FAULTS, *_MODEL_FAULTS)
#: The faults that break a model's collision filter groups.
GROUP_FAULTS = _GROUP_FAULTS


def faults_for(fmt: str) -> tuple[str, ...]:
    """The faults a model of format ``fmt`` can have (``FAULTS``)."""
    return (*_GROUP_FAULTS, *(f for f, (formats, _) in _MODEL_FAULTS.items() if fmt in formats))


def _fault(
    draw: st.DrawFn,
    model: Model,
    formats: Sequence[str],
    faults: Sequence[str],
    prefix: str,
) -> Model:
    """``model`` with one of ``faults`` that every format of ``formats`` has."""
    usable = [
        f
        for f in faults
        if f in _GROUP_FAULT_FUNCTIONS or all(fmt in _MODEL_FAULTS[f][0] for fmt in formats)
    ]
    fault = draw(spread(usable))
    if fault in _GROUP_FAULT_FUNCTIONS:
        names = [name for name, _ in model.scoped_bodies()]
        return _GROUP_FAULT_FUNCTIONS[fault](draw, model, list(model.groups), names)
    return _MODEL_FAULTS[fault][1](draw, model, prefix, formats[0])


# ------------------------------------------------------------------ joints
#: A body as drawn: its geometry, then its parent pick (0: a root; k: body (k - 1) mod i),
#: its joint kind pick, whether the joint is reversed, how a root meets the world, and the
#: picks of its joint's limits and damping (0: none).
_BodySpec = tuple[tuple[Geometry, ...], int, int, bool, _Root, int, int]


def _attributes(joint: Joint, limits: int, damping: int, formats: Sequence[str]) -> Joint:
    """The joint with the limits and damping its picks name, where its kind reads them."""
    kind = JOINT_KINDS[joint.kind]
    if limits and kind.limits:
        joint = replace(joint, limits=_LIMITS[(limits - 1) % len(_LIMITS)])
    if damping and kind.damping and ("sdf" not in formats or kind.axes):
        joint = replace(joint, damping=_DAMPINGS[(damping - 1) % len(_DAMPINGS)])
    return joint


def _joints(
    specs: Sequence[_BodySpec],
    bodies: Sequence[str],
    kinds: Sequence[str],
    formats: Sequence[str],
    prefix: str = "",
) -> list[Joint]:
    """The joints of the tree the body specs describe (see ``_BodySpec``).

    N.B. A joint is reversed only in a tree joined to the world (through no URDF
    floating joint, which Drake drops). Finalize walks such a tree from the
    world, so exactly the reversed joints are walked child to parent, and their
    kinds are ones Drake reverses. A free tree is walked from a base body Drake
    chooses (the parent of the most joints among the bodies that are no joint's
    child), which a reversed joint could make a body whose walk reverses a
    ball or planar joint: Finalize then throws (measured).
    """
    reversible = [k for k in kinds if JOINT_KINDS[k].reversible]
    joints: list[Joint] = []
    anchored: list[bool] = []  # joined to the world, walked from it
    for i, (_, parent, kind_pick, reverse, root, limits, damping) in enumerate(specs):
        body, name, kind = bodies[i], f"{prefix}j{len(joints)}", kinds[kind_pick]
        joint: Joint | None = None
        if parent and i:
            at = (parent - 1) % i
            other = bodies[at]
            anchored.append(anchored[at] and kind != "floating")
            if reverse and kind in reversible and anchored[at]:
                joint = Joint(name, kind, body, other)
            else:
                joint = Joint(name, kind, other, body)
        else:
            anchored.append(root is not _Root.FREE and kind != "floating")
            if root is _Root.PARENT_WORLD:
                joint = Joint(name, kind, WORLD, body)
            elif root is _Root.CHILD_WORLD:
                kind = kind if kind in reversible else reversible[kind_pick % len(reversible)]
                anchored[-1] = True
                joint = Joint(name, kind, body, WORLD)
        if joint is not None:
            joints.append(_attributes(joint, limits, damping, formats))
    return joints


# ------------------------------------------------------------------ trees
@st.composite
def kinematic_trees(
    draw: st.DrawFn,
    *,
    formats: Sequence[str] = FORMATS,
    model_names: Sequence[str] = ("m", "robot"),
    min_bodies: int = 1,
    max_bodies: int = 6,
    max_geometries: int = 3,
    joint_kinds: Iterable[str] | None = None,
    max_groups: int = 4,
    ignore_values: Sequence[str | None] = IGNORE_VALUES,
    invalid: bool = False,
    max_nested: int = 0,
    attach_to_world: bool = True,
    shapes: Iterable[str] = SHAPES,
    max_frames: int = 0,
    joint_attributes: bool = False,
    includes: Sequence[Include] = (),
    faults: Sequence[str] = FAULTS,
    prefix: str = "",
    frames_into_children: bool = True,
    joints_into_includes: bool = True,
    one_value_scale: bool = True,
    reversed_joints: bool = True,
) -> Model:
    """A random tree that renders in every format of ``formats`` (see the module doc).

    ``joint_kinds`` limits the kinds and ``shapes`` the shapes (default: every
    kind all ``formats`` have; sphere, box and cylinder). ``includes``
    (SDFormat) are the model's includes, which its joints, frames and groups
    may name. ``prefix`` starts every name the model defines (bodies
    ``<prefix>l0``, joints, frames, groups, nested models), for a model that
    is merged into another. ``invalid`` breaks one rule on purpose (one of
    ``faults``). ``frames_into_children`` lets frames attach to nested and
    included models and their bodies, ``joints_into_includes`` lets joints
    hold an included model's first body, ``one_value_scale`` lets a URDF mesh
    be scaled by one value, ``reversed_joints`` lets a joint's child be the
    world or an earlier body (Finalize reverses it). Each body is one list
    element, and everything shrinks towards free roots, so a shrunk model
    keeps only the bodies and joints a finding needs.
    """
    if min_bodies < 1:
        raise ValueError("a model needs a body (SDFormat: 'A model must have at least one link')")
    if (max_nested or includes) and "urdf" in formats:
        raise ValueError("URDF has no nested models")
    kinds = _kinds_for(formats, joint_kinds)
    shape_kinds = _shapes_for(formats, shapes)
    sdf = "sdf" in formats
    reversible = [k for k in kinds if JOINT_KINDS[k].reversible] if reversed_joints else []
    roots = [_Root.FREE]
    if attach_to_world:
        roots.append(_Root.PARENT_WORLD)
    if attach_to_world and not sdf and reversible:  # SDFormat: "invalid child"
        roots.append(_Root.CHILD_WORLD)
    # Nested models first, each with the pick of the body whose joint holds its first
    # link (0: none) and that joint's kind; the includes' picks likewise.
    nested_specs = draw(
        st.lists(
            st.tuples(
                kinematic_trees(
                    formats=formats,
                    min_bodies=1,
                    max_bodies=3,
                    max_geometries=max_geometries,
                    joint_kinds=kinds,
                    max_groups=2,
                    ignore_values=ignore_values,
                    attach_to_world=False,
                    shapes=shape_kinds,
                ),
                st.integers(0, max_bodies),
                spread(range(len(kinds))),
            ),
            max_size=max_nested,
        )
    )
    include_picks = [
        draw(st.tuples(st.integers(0, max_bodies), spread(range(len(kinds))))) for _ in includes
    ]
    # Joint names differ from the parent model's: Drake adds a frame '<joint>_child' to the
    # child's model instance, so a joint j0 into n0 would clash with n0's own j0 (measured).
    nested = tuple(
        replace(
            inner,
            name=f"{prefix}n{i}",
            joints=tuple(replace(j, name=f"{prefix}n{i}{j.name}") for j in inner.joints),
        )
        for i, (inner, _, _) in enumerate(nested_specs)
    )
    # The picks of groups and frames first: drawn after the bodies, they would keep the
    # shrinker from deleting bodies (see conformance._fuzz.model_campaign).
    group_specs = draw(_group_specs(max_groups, 3, ignore_values))
    frame_specs: list[_FrameSpec] = draw(
        st.lists(
            st.tuples(st.integers(0, 255), st.none() | st.integers(0, 255)),
            max_size=max_frames,
        )
    )
    if not sdf:  # URDF frames have no pose relative to another frame
        frame_specs = [(attach, None) for attach, _ in frame_specs]
    via_frames: list[int] = (
        draw(st.lists(st.integers(0, 255), max_size=max_bodies)) if (sdf and max_frames) else []
    )
    attribute = st.integers(0, 2) if joint_attributes else st.just(0)
    specs: list[_BodySpec] = draw(
        st.lists(
            st.tuples(
                _geometries(max_geometries, shape_kinds, formats, one_value_scale),
                st.integers(0, max_bodies),
                spread(range(len(kinds))),
                st.integers(0, 4).map(lambda x: x == 4),  # reversed, 1 in 5
                st.sampled_from(roots),
                attribute,
                attribute,
            ),
            min_size=min_bodies,
            max_size=max_bodies,
        )
    )
    bodies = tuple(Body(f"{prefix}l{i}", spec[0]) for i, spec in enumerate(specs))
    body_names = [b.name for b in bodies]
    if not reversed_joints:
        specs = [(*spec[:3], False, *spec[4:]) for spec in specs]
    joints = _joints(specs, body_names, kinds, formats, prefix)
    children = [*((f"{n.name}::", n) for n in nested), *((i.scope, i.model) for i in includes)]
    picks = [(p, k) for _, p, k in nested_specs] + include_picks
    jointed = len(nested) + (len(includes) if joints_into_includes else 0)
    for (scope, inner), (parent, kind_pick) in zip(children[:jointed], picks, strict=False):
        if parent:
            other = body_names[(parent - 1) % len(body_names)]
            child = f"{scope}{inner.bodies[0].name}"
            joints.append(Joint(f"{prefix}j{len(joints)}", kinds[kind_pick], other, child))
    model = Model("", bodies, tuple(joints), nested=nested, includes=tuple(includes))
    frames = _frames(frame_specs, model, sdf, prefix, frames_into_children)
    if via_frames:
        joints = _through_frames(joints, frames, body_names, via_frames)
    names = [name for name, _ in model.scoped_bodies()]
    groups = _groups(group_specs, names, formats, children, prefix)
    model = replace(model, joints=tuple(joints), frames=tuple(frames), groups=tuple(groups))
    if invalid:
        model = _fault(draw, model, formats, faults, prefix)
    name = draw(st.sampled_from(model_names))
    return replace(model, name=name)
