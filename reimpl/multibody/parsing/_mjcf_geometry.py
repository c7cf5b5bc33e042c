"""MuJoCo ``<geom>``: shape, pose, roles and colour, as Drake 1.51.1 reads them (measured).

A geom takes its class's defaults, then is read in this order (``name``
defaults to ``geom<k>``, k counting the geoms of its body, or of its
``<worldbody>``, that got a shape):

1. the pose (``_mjcf_pose``); ``fromto="x0 y0 z0 x1 y1 z1"`` replaces it: the
   midpoint, rotated from +z to the segment (as ``zaxis``);
2. ``type`` (default ``sphere``) and ``size`` (numbers; only as many as the
   shape needs are read): a ``mesh`` attribute on a sphere, capsule, cylinder,
   ellipsoid or box is ``geom N specified type 'T' but also has a mesh
   attribute. ...`` and on another type ``geom N specified a 'mesh', but this
   is not allowed for type 'T'.``; then by type:

   ============  =============================================================
    type          shape
   ============  =============================================================
    plane         HalfSpace
    sphere        Sphere(size[0]); no size: Sphere(0) (and a warning below)
    capsule       Capsule(size[0], 2·size[1]), or with fromto its length
    cylinder      Cylinder(size[0], 2·size[1]), or with fromto its length
    ellipsoid     Ellipsoid(size[0..2]); fromto: warned, no shape
    box           Box(2·size[0..2]); fromto: warned, no shape
    mesh          the ``mesh`` asset's Mesh; no ``mesh``: an error; an unknown
                  one: warned, no shape
    hfield        warned, no shape
    other         ``Unrecognized geom type T``
   ============  =============================================================

   too few sizes are an error (``The size attribute for capsule geom must
   have at least two elements.`` and the like);
3. roles: both, but ``contype="0" conaffinity="0"`` makes it visual only and
   ``group`` > 2 collision only (other contype/conaffinity and a ``condim``
   other than 3 are warned about);
4. the colour: ``rgba`` (4), else the named ``<material>``'s ``rgba``, else
   0.5 0.5 0.5 1; friction: the first ``friction`` number (default 1) as
   static and dynamic, a nonzero second or third warned about;
5. warnings for ``shellinertia``, ``fitscale``, ``fluidshape``, ``fluidcoef``
   and ``user``; then, for a body's geom, its mass (``_mjcf_inertia``).

Each geom's visual (with the colour), then its collision (with the friction),
both under the geom's name, in the order of the geoms; a body's once the body
is added.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from reimpl.geometry import Box, Capsule, Cylinder, Ellipsoid, HalfSpace, Mesh, Sphere
from reimpl.geometry._drake_text import shortest
from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _mjcf_values as values
from reimpl.multibody.parsing._mjcf_context import MjcfContext
from reimpl.multibody.parsing._mjcf_defaults import apply_defaults, class_of
from reimpl.multibody.parsing._mjcf_inertia import geom_mass
from reimpl.multibody.parsing._mjcf_pose import parse_transform, rotation_from_z
from reimpl.multibody.parsing._xml import XmlElement
from reimpl.multibody.plant import CoulombFriction

__all__ = ["MujocoGeometry", "read_geometry"]

_SIZED_TYPES = ("sphere", "capsule", "cylinder", "ellipsoid", "box")
_UNSUPPORTED = ("shellinertia", "fitscale", "fluidshape", "fluidcoef", "user")


@dataclass
class MujocoGeometry:
    """One geom as Drake registers it (``shape`` None: not registered)."""

    name: str
    X_BG: RigidTransform
    shape: Any = None
    rgba: tuple[float, float, float, float] = (0.5, 0.5, 0.5, 1.0)
    friction: CoulombFriction | None = None
    register_collision: bool = True
    register_visual: bool = True
    #: (mass, centre of mass in the body), when the body's mass comes from its geoms
    mass: tuple[float, np.ndarray] | None = None


def _segment(element: XmlElement, fromto: list[float]) -> tuple[RigidTransform, float]:
    """The pose of a ``fromto`` segment (midpoint, +z along it) and its length."""
    start, end = np.asarray(fromto[:3]), np.asarray(fromto[3:])
    direction = end - start
    X = RigidTransform(rotation_from_z(element, [float(v) for v in direction]), (start + end) / 2)
    return X, float(np.linalg.norm(start - end))


class _Shapes:
    """Drake's type switch: each method returns the shape, or None (warned, skipped)."""

    def __init__(
        self, context: MjcfContext, node: XmlElement, name: str, length: float | None
    ) -> None:
        self.context, self.node, self.name, self.length = context, node, name, length
        self.size = values.numbers(node, "size")

    def _need(self, count: int, kind: str, words: str) -> None:
        if len(self.size) < count:
            via = " using fromto" if self.length is not None and count == 1 else ""
            raise self.context.d.error(
                self.node,
                f"The size attribute for {kind} geom{via} must have at least {words}.",
            )

    def _no_fromto(self, kind: str) -> bool:
        if self.length is not None:
            self.context.d.warning(
                self.node,
                f"The fromto tag for {kind} is currently unsupported; geom {self.name} will be "
                "ignored.",
            )
            return False
        return True

    def plane(self) -> Any:
        return HalfSpace()

    def sphere(self) -> Any:
        return Sphere(self.size[0]) if self.size else Sphere(0.0)

    def _round(self, kind: str, make: Any) -> Any:
        if self.length is not None:
            self._need(1, kind, "one element")
            return make(self.size[0], self.length)
        self._need(2, kind, "two elements")
        return make(self.size[0], 2 * self.size[1])

    def capsule(self) -> Any:
        return self._round("capsule", Capsule)

    def cylinder(self) -> Any:
        return self._round("cylinder", Cylinder)

    def ellipsoid(self) -> Any:
        if not self._no_fromto("ellipsoid"):
            return None
        self._need(3, "ellipsoid", "three elements")
        return Ellipsoid(self.size[0], self.size[1], self.size[2])

    def box(self) -> Any:
        if not self._no_fromto("box"):
            return None
        self._need(3, "box", "three elements")
        return Box(self.size[0] * 2.0, self.size[1] * 2.0, self.size[2] * 2.0)

    def mesh(self) -> Any:
        mesh = self.node.get("mesh")
        if mesh is None:
            raise self.context.d.error(
                self.node,
                f"geom {self.name} specified type 'mesh', but did not set the mesh attribute",
            )
        if mesh not in self.context.meshes:
            self.context.d.warning(
                self.node, f"geom {self.name} specified unknown mesh {mesh} and will be ignored"
            )
            return None
        path, scale = self.context.meshes[mesh]
        return Mesh(path, scale3=np.asarray(scale))

    def hfield(self) -> Any:
        self.context.d.warning(
            self.node, "The geom type 'hfield' is currently unsupported and will be ignored."
        )
        return None


_SHAPES = ("plane", "sphere", "capsule", "cylinder", "ellipsoid", "box", "mesh", "hfield")


def _check_mesh_attribute(context: MjcfContext, node: XmlElement, name: str, kind: str) -> None:
    if node.get("mesh") is None or kind == "mesh":
        return
    if kind in _SIZED_TYPES:
        raise context.d.error(
            node,
            f"geom {name} specified type '{kind}' but also has a mesh attribute. The intended "
            "behavior is to compute the size of the shape from the mesh, but this is not "
            "supported yet (#22372).",
        )
    raise context.d.error(
        node, f"geom {name} specified a 'mesh', but this is not allowed for type '{kind}'."
    )


def _roles(context: MjcfContext, node: XmlElement, geom: MujocoGeometry, kind: str) -> None:
    d = context.d
    contype = values.integer(node, "contype")
    conaffinity = values.integer(node, "conaffinity")
    condim = values.integer(node, "condim")
    contype = 1 if contype is None else contype
    conaffinity = 1 if conaffinity is None else conaffinity
    if contype == 0 and conaffinity == 0:
        geom.register_collision = False
    elif contype != 1 or conaffinity != 1:
        d.warning(
            node,
            f"geom {geom.name} specified contype={contype} and conaffinity={conaffinity}; but "
            "collision filter groups are not yet implemented for the mujoco parser.",
        )
    if condim is not None and condim != 3:
        d.warning(
            node,
            f"geom {geom.name} specified condim={condim}, which is not supported. condim=3 will "
            "be used instead.",
        )
    if geom.register_collision and kind == "sphere" and not values.numbers(node, "size"):
        d.warning(
            node,
            "Using zero-radius spheres (MuJoCo's default geometry) for collision geometry may "
            "not be supported by all features in Drake. Consider specifying a non-zero size "
            f"for geom {geom.name}.",
        )
    group = values.integer(node, "group")
    if group is not None and group > 2:
        geom.register_visual = False


def _appearance(context: MjcfContext, node: XmlElement, geom: MujocoGeometry) -> None:
    material = node.get("material")
    if material is not None:
        if material in context.materials:
            rgba = values.vector(context.materials[material], "rgba", 4)
            if rgba is not None:
                geom.rgba = (rgba[0], rgba[1], rgba[2], rgba[3])
        else:
            context.d.warning(
                node, f"geom {geom.name} specified an unrecognized material {material}"
            )
    rgba = values.vector(node, "rgba", 4)
    if rgba is not None:
        geom.rgba = (rgba[0], rgba[1], rgba[2], rgba[3])
    friction = values.numbers(node, "friction")
    mu = friction[0] if friction else 1.0
    if mu < 0:  # N.B. reimpl's CoulombFriction does not check the sign.
        raise RuntimeError(f"The given dynamic friction is negative: {shortest(mu)}")
    geom.friction = CoulombFriction(mu, mu)
    if any(f != 0.0 for f in friction[1:3]):
        context.d.warning(
            node,
            f"The torsional and rolling friction specified in the friction attribute of "
            f"{node.tag} are unsupported and will be ignored.",
        )


def read_geometry(
    context: MjcfContext,
    node: XmlElement,
    num_geom: int,
    compute_inertia: bool,
    child_class: str = "",
) -> MujocoGeometry:
    """ParseGeometry: the geom's shape (None where Drake skips it), roles, colour, mass."""
    apply_defaults(context, "geom", class_of(node, child_class), node)
    name = node.get("name")
    if name is None:
        name = f"geom{num_geom}"
    X_BG = parse_transform(context, node)
    kind = node.get("type")
    if kind is None:
        kind = "sphere"
    fromto = values.vector(node, "fromto", 6)
    length = None
    if fromto is not None:
        X_BG, length = _segment(node, fromto)
    geom = MujocoGeometry(name, X_BG)
    _check_mesh_attribute(context, node, name, kind)
    if kind not in _SHAPES:
        raise context.d.error(node, f"Unrecognized geom type {kind}")
    geom.shape = getattr(_Shapes(context, node, name, length), kind)()
    if geom.shape is None:
        return geom
    if kind == "plane" or (kind == "sphere" and not values.numbers(node, "size")):
        compute_inertia = False
    _roles(context, node, geom, kind)
    _appearance(context, node, geom)
    context.d.warn_unsupported_attributes(node, _UNSUPPORTED)
    if compute_inertia:
        geom.mass = geom_mass(context, node, name, geom.shape, X_BG)
    return geom
