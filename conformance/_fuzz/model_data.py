"""The data of a random model: bodies, geometry, joints, frames, includes and filter groups.

Pure data (frozen dataclasses) and the tables that say what each joint kind
and shape is in URDF, in SDFormat and in Drake. ``conformance._fuzz.model_render``
writes a ``Model`` as text; ``conformance._fuzz.models`` draws one.

Names inside a model are relative to it: a body ``l1``, a body of a nested
model or of an included model that is not merged ``n0::l1``, a body of a
merged include ``i0l1`` (merged models share their parent's scope, so their
names carry their own prefix). ``Model.scoped_bodies`` lists them all.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

__all__ = [
    "DRAKE_NAMESPACE",
    "FORMATS",
    "IGNORE_VALUES",
    "JOINT_KINDS",
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
    "default_geometry_name",
    "drops",
    "geometry_names",
]

DRAKE_NAMESPACE = "http://drake.mit.edu"
WORLD = "world"
FORMATS = ("urdf", "sdf")
#: Values of a group's ``ignore`` attribute (None: not written).
IGNORE_VALUES: tuple[str | None, ...] = (None, "true", "false", "1", "True")


# ------------------------------------------------------------------ joints
@dataclass(frozen=True)
class JointKind:
    """One row of the joint table (``conformance._fuzz.models`` has it as a table)."""

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
    #: URDF reads ``<limit lower= upper=>`` for it.
    limits: bool = False
    #: URDF reads ``<dynamics damping=>`` (one value) for it; SDFormat reads
    #: ``<axis><dynamics><damping>`` for a kind with an axis.
    damping: bool = False


JOINT_KINDS: dict[str, JointKind] = {
    kind.name: kind
    for kind in (
        JointKind(
            "revolute", ("joint", "revolute"), "revolute", "RevoluteJoint", 1, True, True, True
        ),
        JointKind(
            "continuous",
            ("joint", "continuous"),
            "continuous",
            "RevoluteJoint",
            1,
            True,
            False,
            True,
        ),
        JointKind(
            "prismatic", ("joint", "prismatic"), "prismatic", "PrismaticJoint", 1, True, True, True
        ),
        JointKind("fixed", ("joint", "fixed"), "fixed", "WeldJoint", 0, True),
        JointKind("floating", ("joint", "floating"), None, None),
        JointKind("planar", ("joint", "planar"), None, "PlanarJoint"),
        JointKind("drake_planar", ("drake:joint", "planar"), None, "PlanarJoint"),
        JointKind("ball", ("drake:joint", "ball"), "ball", "BallRpyJoint", damping=True),
        JointKind(
            "universal",
            ("drake:joint", "universal"),
            "universal",
            "UniversalJoint",
            2,
            damping=True,
        ),
        JointKind("screw", ("drake:joint", "screw"), "screw", "ScrewJoint", 1, damping=True),
        JointKind("curvilinear", ("drake:joint", "curvilinear"), None, "CurvilinearJoint"),
    )
}


# ------------------------------------------------------------------ shapes
@dataclass(frozen=True)
class ShapeKind:
    """One shape as a model file writes it (``model_render`` has the elements).

    ``drake`` is the class of Drake's geometry, the default name of an
    unnamed URDF geometry too; None: Drake registers no geometry for it
    (SDFormat's ``<cone>`` and ``<polyline>``, measured on pydrake 1.51.1).
    ``mesh``: it names a mesh file (``<mesh>``).
    """

    name: str
    drake: str | None
    urdf: bool
    sdf: bool
    mesh: bool = False


SHAPE_KINDS: dict[str, ShapeKind] = {
    kind.name: kind
    for kind in (
        ShapeKind("sphere", "Sphere", True, True),
        ShapeKind("box", "Box", True, True),
        ShapeKind("cylinder", "Cylinder", True, True),
        ShapeKind("capsule", "Capsule", True, True),  # URDF <capsule>, SDFormat's own
        ShapeKind("drake:capsule", "Capsule", True, True),
        ShapeKind("ellipsoid", "Ellipsoid", False, True),  # SDFormat's own
        ShapeKind("drake:ellipsoid", "Ellipsoid", True, True),
        ShapeKind("plane", "HalfSpace", False, True),
        ShapeKind("cone", None, False, True),
        ShapeKind("polyline", None, False, True),
        ShapeKind("mesh", "Mesh", True, True, mesh=True),
        ShapeKind("convex", "Convex", True, True, mesh=True),  # <mesh> with <drake:declare_convex/>
    )
}
#: The shapes ``kinematic_trees`` draws unless told otherwise.
SHAPES = ("sphere", "box", "cylinder")


# ------------------------------------------------------------------ model
@dataclass(frozen=True)
class Geometry:
    shape: str  # a key of SHAPE_KINDS
    name: str | None = None  # None: unnamed
    collision: bool = True  # False: a <visual>
    #: A mesh's scale as written (URDF: one value or three; SDFormat: three); None: none.
    scale: str | None = None
    #: A mesh's file, below the renderer's mesh folder.
    mesh: str = "mesh.obj"


@dataclass(frozen=True)
class Body:
    name: str
    geometries: tuple[Geometry, ...] = ()


@dataclass(frozen=True)
class Joint:
    name: str
    kind: str  # a key of JOINT_KINDS
    parent: str  # a body's (or, in SDFormat, a frame's) name, or WORLD
    child: str
    #: ``(lower, upper)`` as written, or None.
    limits: tuple[str, str] | None = None
    #: The damping as written, or None.
    damping: str | None = None


@dataclass(frozen=True)
class Frame:
    """A ``<frame>``: URDF ``<frame name= link=>``, SDFormat ``<frame name= attached_to=>``.

    ``attached_to`` is a link, an earlier frame, or (SDFormat) a child model
    or its body (``n0``, ``n0::l1``); ``""`` writes none (the model frame).
    ``relative_to`` (SDFormat) writes ``<pose relative_to=>``.
    """

    name: str
    attached_to: str
    relative_to: str | None = None


@dataclass(frozen=True)
class Group:
    """A ``<drake:collision_filter_group>``, as written (names unscoped)."""

    name: str
    members: tuple[str, ...] = ()
    member_groups: tuple[str, ...] = ()
    ignored: tuple[str, ...] = ()
    ignore: str | None = None


@dataclass(frozen=True)
class Include:
    """An SDFormat ``<include>`` of ``model``'s file at ``uri``.

    ``name`` overrides the model's name (``<name>``), ``pose`` writes a
    ``<pose>``, and ``merge`` (``merge="true"``) puts the model's links,
    frames, joints and groups into the including model.
    """

    model: Model
    uri: str
    name: str | None = None
    pose: bool = False
    merge: bool = False

    @property
    def scope(self) -> str:
        """The prefix of its names in the including model: ``""`` merged, else ``name::``."""
        return "" if self.merge else f"{self.name or self.model.name}::"


@dataclass(frozen=True)
class Model:
    """A model; ``nested`` models and ``includes`` (SDFormat only) are its children, whose
    bodies and groups its joints, frames and groups name as ``<scope><name>``."""

    name: str
    bodies: tuple[Body, ...]
    joints: tuple[Joint, ...] = ()
    groups: tuple[Group, ...] = ()
    nested: tuple[Model, ...] = ()
    frames: tuple[Frame, ...] = ()
    includes: tuple[Include, ...] = ()

    def children(self) -> Iterator[tuple[str, Model]]:
        """``(scope, model)`` of each nested and included model (scope ``n0::``, or ``""``
        for a merged include)."""
        for inner in self.nested:
            yield f"{inner.name}::", inner
        for include in self.includes:
            yield include.scope, include.model

    def scoped_bodies(self) -> list[tuple[str, Body]]:
        """Every body with its name relative to this model (``l0``, ``n0::l0``, ``i0l0``)."""
        return [(body.name, body) for body in self.bodies] + [
            (f"{scope}{name}", body)
            for scope, inner in self.children()
            for name, body in inner.scoped_bodies()
        ]

    def all_groups(self) -> list[tuple[str, Group]]:
        """Every group with its name relative to this model (``g0``, ``n0::g0``).

        N.B. Not those of a merged include: Drake drops them, without a word
        (``collision filter group with name 'm::i0g0' not found``, and its
        members stay unfiltered; measured on pydrake 1.51.1).
        """
        return [(group.name, group) for group in self.groups] + [
            (f"{scope}{name}", group)
            for scope, inner in self.children()
            if scope
            for name, group in inner.all_groups()
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


def default_geometry_name(geometry: Geometry, position: int) -> str:
    """The name ``to_sdf`` writes for an unnamed element (SDFormat requires one)."""
    return f"{'collision' if geometry.collision else 'visual'}{position}"


def geometry_names(model: Model, fmt: str, *, visual: bool = False) -> list[str]:
    """Scoped names (``model::body/name``, ``model::nested::body/name``) of the collision
    geometry whose name is certain.

    Certain: Drake registers a geometry for the shape, and its name is written
    in the text and unlike Drake's default names (in URDF an unnamed sphere is
    ``Sphere``, and a named ``Sphere`` beside it is renamed). With
    ``visual``, visual elements too.
    """
    defaults = {kind.drake for kind in SHAPE_KINDS.values() if kind.drake is not None}
    names = []
    for scoped, body in model.scoped_bodies():
        for position, geometry in enumerate(body.geometries):
            if (not geometry.collision and not visual) or SHAPE_KINDS[geometry.shape].drake is None:
                continue
            name = geometry.name
            if name is None and fmt == "sdf":
                name = default_geometry_name(geometry, position)
            if name is not None and name not in defaults:
                names.append(f"{model.name}::{scoped}/{name}")
    return names
