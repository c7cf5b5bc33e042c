"""Random kinematic trees and their collision filter groups, rendered as URDF and SDFormat (public).

A ``Model`` is pure data: bodies with geometry, the joints of a tree over
them, and ``<drake:collision_filter_group>`` declarations. ``to_urdf`` and
``to_sdf`` render it with ``xml.etree``; ``kinematic_trees`` draws one.

>>> from conformance.fuzz.models import kinematic_trees, to_sdf, to_urdf
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

=========== ============================ ============ =================== =========
kind        URDF                         SDFormat     Drake's joint       reversible
=========== ============================ ============ =================== =========
revolute    ``<joint type="revolute">``  revolute     RevoluteJoint       yes
continuous  ``<joint type="continuous">`` continuous  RevoluteJoint       yes
prismatic   ``<joint type="prismatic">`` prismatic    PrismaticJoint      yes
fixed       ``<joint type="fixed">``     fixed        WeldJoint           yes
floating    ``<joint type="floating">``  (invalid)    none: the child is  no
                                                      left free (warning)
planar      ``<joint type="planar">``    (invalid)    PlanarJoint         no
ball        ``<drake:joint type="ball">`` ball        BallRpyJoint        no
universal   ``<drake:joint ...>``        universal    UniversalJoint      no
screw       ``<drake:joint ...>`` and    screw        ScrewJoint          no
            ``<drake:screw_thread_pitch>``
=========== ============================ ============ =================== =========

SDFormat wants an ``<axis>`` for revolute, continuous, prismatic and screw,
and ``<axis>`` with ``<axis2>`` for universal; the renderer writes them.

**Geometry.** 0-3 per body: a sphere, box or cylinder, ``<collision>`` or
``<visual>``, named or not. Names are unique per body and element kind (SDFormat
rejects a repeated collision name in a link). URDF leaves an unnamed element
unnamed, and Drake names it after its shape (``Sphere``, ``Box_1``...);
SDFormat requires a name, so ``to_sdf`` writes ``collision<k>`` or
``visual<k>`` (``k``: its position in the body). ``geometry_names`` lists the
names a scenario can refer to without knowing Drake's default-name rule.

**Groups.** ``name``, ``members`` (links), ``member_groups`` and
``ignored`` (``ignored_collision_filter_group``) name other groups, possibly
later ones, the group itself, or groups forming a cycle; ``ignore`` is the
attribute as written. Whether it drops the group depends on the format
(``drops``): URDF honours exactly ``"true"``, SDFormat reads a boolean
(``true``, ``1``, ``True``; measured). A dropped group is gone: a reference to
it is an error (``collision filter group with name 'm::g' not found``). A
valid model therefore refers only to groups that no format it is drawn for
drops, and every kept group has a member or a member group (else
``group 'm::g' has no members``). ``kinematic_trees(invalid=True)`` breaks
one of these rules on purpose (``FAULTS``), for the error paths.
"""

from __future__ import annotations

import enum
import xml.etree.ElementTree as ET
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace

from hypothesis import strategies as st

__all__ = [
    "DRAKE_NAMESPACE",
    "FAULTS",
    "FORMATS",
    "IGNORE_VALUES",
    "JOINT_KINDS",
    "SHAPES",
    "WORLD",
    "Body",
    "Geometry",
    "Group",
    "Joint",
    "JointKind",
    "Model",
    "collision_filter_groups",
    "drops",
    "geometry_names",
    "kinematic_trees",
    "render",
    "to_sdf",
    "to_urdf",
]

DRAKE_NAMESPACE = "http://drake.mit.edu"
WORLD = "world"
FORMATS = ("urdf", "sdf")
SHAPES = ("sphere", "box", "cylinder")
#: Values of a group's ``ignore`` attribute (None: not written).
IGNORE_VALUES: tuple[str | None, ...] = (None, "true", "false", "1", "True")
#: Names a geometry may be given; the shape names meet Drake's default names.
_GEOMETRY_NAMES = ("c0", "c1", "c2", "Sphere", "Box")
#: Names of links and groups that no model defines.
_UNDEFINED_LINKS = ("zz", WORLD)
_UNDEFINED_GROUP = "nope"


# ------------------------------------------------------------------ joints
@dataclass(frozen=True)
class JointKind:
    """One row of the joint table (see the module doc)."""

    name: str
    #: The URDF element (``joint`` or ``drake:joint``) and its type, or None.
    urdf: tuple[str, str] | None
    #: The SDFormat type, or None if SDFormat has no such joint.
    sdf: str | None
    #: Drake's class for it (None: the child is left free).
    drake: str | None
    #: Axes SDFormat wants (0, 1 or 2).
    axes: int = 0
    #: Drake reverses it when the tree needs (a joint whose child is the world).
    reversible: bool = False


JOINT_KINDS: dict[str, JointKind] = {
    kind.name: kind
    for kind in (
        JointKind("revolute", ("joint", "revolute"), "revolute", "RevoluteJoint", 1, True),
        JointKind("continuous", ("joint", "continuous"), "continuous", "RevoluteJoint", 1, True),
        JointKind("prismatic", ("joint", "prismatic"), "prismatic", "PrismaticJoint", 1, True),
        JointKind("fixed", ("joint", "fixed"), "fixed", "WeldJoint", 0, True),
        JointKind("floating", ("joint", "floating"), None, None),
        JointKind("planar", ("joint", "planar"), None, "PlanarJoint"),
        JointKind("ball", ("drake:joint", "ball"), "ball", "BallRpyJoint"),
        JointKind("universal", ("drake:joint", "universal"), "universal", "UniversalJoint", 2),
        JointKind("screw", ("drake:joint", "screw"), "screw", "ScrewJoint", 1),
    )
}


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


# ------------------------------------------------------------------ model
@dataclass(frozen=True)
class Geometry:
    shape: str  # one of SHAPES
    name: str | None = None  # None: unnamed
    collision: bool = True  # False: a <visual>


@dataclass(frozen=True)
class Body:
    name: str
    geometries: tuple[Geometry, ...] = ()


@dataclass(frozen=True)
class Joint:
    name: str
    kind: str  # a key of JOINT_KINDS
    parent: str  # a body's name or WORLD
    child: str  # a body's name or WORLD


@dataclass(frozen=True)
class Group:
    """A ``<drake:collision_filter_group>``, as written (names unscoped)."""

    name: str
    members: tuple[str, ...] = ()
    member_groups: tuple[str, ...] = ()
    ignored: tuple[str, ...] = ()
    ignore: str | None = None


@dataclass(frozen=True)
class Model:
    """A model; ``nested`` models (SDFormat only) are its children, whose bodies and groups
    its joints and groups name as ``<nested>::<name>``."""

    name: str
    bodies: tuple[Body, ...]
    joints: tuple[Joint, ...] = ()
    groups: tuple[Group, ...] = ()
    nested: tuple[Model, ...] = ()

    def scoped_bodies(self) -> list[tuple[str, Body]]:
        """Every body with its name relative to this model (``l0``, ``n0::l0``)."""
        return [(body.name, body) for body in self.bodies] + [
            (f"{inner.name}::{name}", body)
            for inner in self.nested
            for name, body in inner.scoped_bodies()
        ]


def drops(group: Group, fmt: str) -> bool:
    """Whether the format's parser drops ``group`` for its ``ignore`` attribute (measured).

    URDF: the value is exactly ``"true"``. SDFormat reads a boolean:
    ``true`` or ``1``, in any case.
    """
    if group.ignore is None:
        return False
    if fmt == "urdf":
        return group.ignore == "true"
    return group.ignore.lower() in ("true", "1")


def _default_name(geometry: Geometry, position: int) -> str:
    """The name ``to_sdf`` writes for an unnamed element (none of _GEOMETRY_NAMES)."""
    return f"{'collision' if geometry.collision else 'visual'}{position}"


def geometry_names(model: Model, fmt: str, *, visual: bool = False) -> list[str]:
    """Scoped names (``model::body/name``, ``model::nested::body/name``) of the collision
    geometry whose name is certain.

    Certain: written in the text and unlike Drake's default names (in URDF an
    unnamed sphere is ``Sphere``, and a named ``Sphere`` beside it is renamed).
    With ``visual``, visual elements too.
    """
    defaults = {shape.capitalize() for shape in SHAPES}
    names = []
    for scoped, body in model.scoped_bodies():
        for position, geometry in enumerate(body.geometries):
            if not geometry.collision and not visual:
                continue
            name = geometry.name
            if name is None and fmt == "sdf":
                name = _default_name(geometry, position)
            if name is not None and name not in defaults:
                names.append(f"{model.name}::{scoped}/{name}")
    return names


# ------------------------------------------------------------------ rendering
_SIZES = {"sphere": {"radius": "0.1"}, "box": {"size": "0.1 0.2 0.3"}}
_CYLINDER = {"radius": "0.1", "length": "0.2"}
_AXES = (("axis", "0 0 1"), ("axis2", "0 1 0"))


def _urdf_shape(parent: ET.Element, shape: str) -> None:
    geometry = ET.SubElement(parent, "geometry")
    ET.SubElement(geometry, shape, _SIZES.get(shape, _CYLINDER))


def _sdf_shape(parent: ET.Element, shape: str) -> None:
    element = ET.SubElement(ET.SubElement(parent, "geometry"), shape)
    for key, value in _SIZES.get(shape, _CYLINDER).items():
        ET.SubElement(element, key).text = value


def _text(parent: ET.Element, tag: str, text: str) -> ET.Element:
    element = ET.SubElement(parent, tag)
    element.text = text
    return element


def _serialize(root: ET.Element) -> str:
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


def to_urdf(model: Model) -> str:
    """The model as URDF text (``xmlns:drake`` declared on ``<robot>``)."""
    if model.nested:
        raise ValueError("URDF has no nested models")
    robot = ET.Element("robot", {"name": model.name, "xmlns:drake": DRAKE_NAMESPACE})
    for body in model.bodies:
        link = ET.SubElement(robot, "link", {"name": body.name})
        for geometry in body.geometries:
            tag = "collision" if geometry.collision else "visual"
            attributes = {"name": geometry.name} if geometry.name is not None else {}
            _urdf_shape(ET.SubElement(link, tag, attributes), geometry.shape)
    for joint in model.joints:
        kind = JOINT_KINDS[joint.kind]
        if kind.urdf is None:
            raise ValueError(f"URDF has no {joint.kind} joint")
        tag, joint_type = kind.urdf
        element = ET.SubElement(robot, tag, {"name": joint.name, "type": joint_type})
        ET.SubElement(element, "parent", {"link": joint.parent})
        ET.SubElement(element, "child", {"link": joint.child})
        if joint.kind == "screw":
            ET.SubElement(element, "drake:screw_thread_pitch", {"value": "0.1"})
    for group in model.groups:
        attributes = {"name": group.name}
        if group.ignore is not None:
            attributes["ignore"] = group.ignore
        element = ET.SubElement(robot, "drake:collision_filter_group", attributes)
        for link_name in group.members:
            ET.SubElement(element, "drake:member", {"link": link_name})
        for name in group.member_groups:
            ET.SubElement(element, "drake:member_group", {"name": name})
        for name in group.ignored:
            ET.SubElement(element, "drake:ignored_collision_filter_group", {"name": name})
    return _serialize(robot)


def to_sdf(model: Model) -> str:
    """The model as SDFormat 1.9 text; unnamed elements get ``collision<k>``/``visual<k>``."""
    sdf = ET.Element("sdf", {"version": "1.9", "xmlns:drake": DRAKE_NAMESPACE})
    _sdf_model(sdf, model)
    return _serialize(sdf)


def _sdf_model(parent: ET.Element, model: Model) -> None:
    """``<model>``: its links, nested models, joints, then groups."""
    root = ET.SubElement(parent, "model", {"name": model.name})
    for body in model.bodies:
        link = ET.SubElement(root, "link", {"name": body.name})
        for position, geometry in enumerate(body.geometries):
            tag = "collision" if geometry.collision else "visual"
            name = geometry.name if geometry.name is not None else _default_name(geometry, position)
            _sdf_shape(ET.SubElement(link, tag, {"name": name}), geometry.shape)
    for inner in model.nested:
        _sdf_model(root, inner)
    for joint in model.joints:
        kind = JOINT_KINDS[joint.kind]
        if kind.sdf is None:
            raise ValueError(f"SDFormat has no {joint.kind} joint")
        element = ET.SubElement(root, "joint", {"name": joint.name, "type": kind.sdf})
        _text(element, "parent", joint.parent)
        _text(element, "child", joint.child)
        for axis, xyz in _AXES[: kind.axes]:
            _text(ET.SubElement(element, axis), "xyz", xyz)
    for group in model.groups:
        attributes = {"name": group.name}
        if group.ignore is not None:
            attributes["ignore"] = group.ignore
        element = ET.SubElement(root, "drake:collision_filter_group", attributes)
        for link_name in group.members:
            _text(element, "drake:member", link_name)
        for name in group.member_groups:
            _text(element, "drake:member_group", name)
        for name in group.ignored:
            _text(element, "drake:ignored_collision_filter_group", name)


def render(model: Model, fmt: str) -> str:
    """``to_urdf`` or ``to_sdf`` by ``fmt`` (``"urdf"`` or ``"sdf"``)."""
    if fmt == "urdf":
        return to_urdf(model)
    if fmt == "sdf":
        return to_sdf(model)
    raise ValueError(f"unknown model format {fmt!r} (have {', '.join(FORMATS)})")


# ------------------------------------------------------------------ strategies
class _Root(enum.Enum):
    """How a root body meets the world."""

    FREE = "free"
    PARENT_WORLD = "parent_world"  # a joint from the world to it
    CHILD_WORLD = "child_world"  # a joint from it to the world (URDF, reversible kinds)


@st.composite
def _geometries(draw: st.DrawFn, max_geometries: int) -> tuple[Geometry, ...]:
    drawn = draw(
        st.lists(
            st.builds(
                Geometry,
                shape=st.sampled_from(SHAPES),
                name=st.none() | st.sampled_from(_GEOMETRY_NAMES),
                collision=st.booleans().map(lambda visual: not visual),
            ),
            max_size=max_geometries,
        )
    )
    seen: set[tuple[bool, str]] = set()
    out = []
    for geometry in drawn:  # names unique per body and element kind
        key = (geometry.collision, geometry.name or "")
        out.append(replace(geometry, name=None) if key in seen else geometry)
        if geometry.name is not None:
            seen.add(key)
    return tuple(out)


FAULTS = (
    "unknown_link",  # a member link no body has (or the world)
    "undefined_member_group",
    "undefined_ignored_group",
    "empty_group",  # no members, no member groups
    "duplicate_group",
    "scoped_group_name",
)


def _fault(draw: st.DrawFn, groups: list[Group], bodies: Sequence[str]) -> list[Group]:
    """``groups`` with one rule broken (``FAULTS``)."""
    fault = draw(st.sampled_from(FAULTS))
    if not groups:
        groups = [Group("g0", members=(bodies[0],), ignored=("g0",))]
    at = draw(st.integers(0, len(groups) - 1))
    group = groups[at] = replace(groups[at], ignore=None)  # a dropped group would hide it
    if fault == "unknown_link":
        link = draw(st.sampled_from(_UNDEFINED_LINKS))
        groups[at] = replace(group, members=(*group.members, link))
    elif fault == "undefined_member_group":
        groups[at] = replace(group, member_groups=(*group.member_groups, _UNDEFINED_GROUP))
    elif fault == "undefined_ignored_group":
        groups[at] = replace(group, ignored=(*group.ignored, _UNDEFINED_GROUP))
    elif fault == "empty_group":
        groups[at] = replace(group, members=(), member_groups=())
    elif fault == "duplicate_group":
        # The copy is of the kept group at ``at``: a copy of a group some format drops
        # (URDF ignore="true") is no duplicate there, and Drake accepts it (measured).
        groups.append(group)
    else:
        groups[at] = replace(group, name=f"x::{group.name}")
    return groups


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


def _kept(groups: Iterable[Group], formats: Sequence[str]) -> list[str]:
    """The names of the groups that no format of ``formats`` drops."""
    return [g.name for g in groups if not any(drops(g, fmt) for fmt in formats)]


def _groups(
    specs: Sequence[_GroupSpec],
    bodies: Sequence[str],
    formats: Sequence[str],
    nested: Sequence[Model] = (),
) -> list[Group]:
    """The groups of ``specs`` over ``bodies``, valid in every format of ``formats``; their
    member and ignored groups may be the kept groups of ``nested`` models too."""
    names = [f"g{i}" for i in range(len(specs))]
    kept = _kept((Group(n, ignore=spec[0]) for n, spec in zip(names, specs, strict=True)), formats)
    kept += [f"{inner.name}::{name}" for inner in nested for name in _kept(inner.groups, formats)]

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

    Valid in every format of ``formats`` unless ``invalid``: then one of ``FAULTS``.
    Each group is one list element, so the shrinker deletes whole groups.
    """
    groups = _groups(draw(_group_specs(max_groups, max_members, ignore_values)), bodies, formats)
    if invalid:
        groups = _fault(draw, groups, bodies)
    return tuple(groups)


#: A body as drawn: its geometry, then its parent pick (0: a root; k: body (k - 1) mod i),
#: its joint kind pick, whether the joint is reversed, and (a root) how it meets the world.
_BodySpec = tuple[tuple[Geometry, ...], int, int, bool, _Root]


def _joints(specs: Sequence[_BodySpec], bodies: Sequence[str], kinds: Sequence[str]) -> list[Joint]:
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
    for i, (_, parent, kind_pick, reverse, root) in enumerate(specs):
        body, name, kind = bodies[i], f"j{len(joints)}", kinds[kind_pick]
        if parent and i:
            at = (parent - 1) % i
            other = bodies[at]
            anchored.append(anchored[at] and kind != "floating")
            if reverse and kind in reversible and anchored[at]:
                joints.append(Joint(name, kind, body, other))
            else:
                joints.append(Joint(name, kind, other, body))
            continue
        anchored.append(root is not _Root.FREE and kind != "floating")
        if root is _Root.PARENT_WORLD:
            joints.append(Joint(name, kind, WORLD, body))
        elif root is _Root.CHILD_WORLD:
            kind = kind if kind in reversible else reversible[kind_pick % len(reversible)]
            anchored[-1] = True
            joints.append(Joint(name, kind, body, WORLD))
    return joints


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
) -> Model:
    """A random tree that renders in every format of ``formats`` (see the module doc).

    ``joint_kinds`` limits the kinds (default: every kind all ``formats`` have).
    ``invalid`` breaks one rule of the groups on purpose (``FAULTS``). Each body
    is one list element, and everything shrinks towards free roots, so a shrunk
    model keeps only the bodies and joints a finding needs.
    """
    if min_bodies < 1:
        raise ValueError("a model needs a body (SDFormat: 'A model must have at least one link')")
    if max_nested and "urdf" in formats:
        raise ValueError("URDF has no nested models")
    kinds = _kinds_for(formats, joint_kinds)
    reversible = [k for k in kinds if JOINT_KINDS[k].reversible]
    roots = [_Root.FREE]
    if attach_to_world:
        roots.append(_Root.PARENT_WORLD)
    if attach_to_world and "sdf" not in formats and reversible:  # SDFormat: "invalid child"
        roots.append(_Root.CHILD_WORLD)
    # Nested models first, each with the pick of the body whose joint holds its first
    # link (0: none) and that joint's kind.
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
                ),
                st.integers(0, max_bodies),
                st.integers(0, len(kinds) - 1),
            ),
            max_size=max_nested,
        )
    )
    # Joint names differ from the parent model's: Drake adds a frame '<joint>_child' to the
    # child's model instance, so a joint j0 into n0 would clash with n0's own j0 (measured).
    nested = tuple(
        replace(
            inner,
            name=f"n{i}",
            joints=tuple(replace(j, name=f"n{i}{j.name}") for j in inner.joints),
        )
        for i, (inner, _, _) in enumerate(nested_specs)
    )
    # The groups' picks first: drawn after the bodies, they would keep the shrinker
    # from deleting bodies (see conformance.fuzz.model_campaign).
    group_specs = draw(_group_specs(max_groups, 3, ignore_values))
    specs: list[_BodySpec] = draw(
        st.lists(
            st.tuples(
                _geometries(max_geometries),
                st.integers(0, max_bodies),
                st.integers(0, len(kinds) - 1),
                st.integers(0, 4).map(lambda x: x == 4),  # reversed, 1 in 5
                st.sampled_from(roots),
            ),
            min_size=min_bodies,
            max_size=max_bodies,
        )
    )
    bodies = tuple(Body(f"l{i}", spec[0]) for i, spec in enumerate(specs))
    joints = _joints(specs, [b.name for b in bodies], kinds)
    for inner, (_, parent, kind_pick) in zip(nested, nested_specs, strict=True):
        if parent:
            other = bodies[(parent - 1) % len(bodies)].name
            child = f"{inner.name}::{inner.bodies[0].name}"
            joints.append(Joint(f"j{len(joints)}", kinds[kind_pick], other, child))
    model = Model("", bodies, tuple(joints), nested=nested)
    names = [name for name, _ in model.scoped_bodies()]
    groups = _groups(group_specs, names, formats, nested)
    if invalid:
        groups = _fault(draw, groups, names)
    name = draw(st.sampled_from(model_names))
    return replace(model, name=name, groups=tuple(groups))
