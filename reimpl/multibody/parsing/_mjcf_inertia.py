"""MuJoCo mass properties, where they decide whether Drake 1.51.1 parses (measured).

reimpl's SpatialInertia keeps a mass and a centre of mass; these are computed
as Drake computes them, and every check Drake makes on the way raises Drake's
error. The unit inertias are computed only where their validity is checked.

``<inertial>`` (``pos`` and orientation as any pose): ``mass`` is required
(``The inertial tag must include the mass attribute.``), then ``diaginertia``
(3, re-expressed by the orientation) or else ``fullinertia`` (xx yy zz xy xz
yz; ``The inertial tag must include either the diaginertia or fullinertia
attribute.``). Drake's MakeFromCentralInertia then demands mass > 0 (a
SystemExit, unit_inertia.h:104) and a physically valid inertia about the
centre of mass (RuntimeError with SpatialInertia's report).

A geom's volume, at unit density, by shape (Drake's Solid*WithDensity, each
checking its sizes and then the mass as ``F(): name is not positive and
finite: V.``): sphere 4/3·π·r³ (a radius of 0 fails here, though Sphere(0)
exists), box w·d·h, capsule π·r²·L + 4/3·π·r²·r, cylinder π·r²·L, ellipsoid
4/3·π·a·b·c; a mesh by ``_mesh_inertia`` (falling back to its convex hull with
two warnings), once per mesh asset. The geom's mass is ``mass``, else
``density`` (1000) times the volume; a mass that is negative or not finite is
``geom NAME Spatial inertia fails SpatialInertia::IsPhysicallyValid().\\nmass =
M is negative or not finite.\\n``. A body's mass sums its geoms' positive
masses, its centre of mass their mass-weighted centres (SpatialInertia's +=).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from reimpl.geometry import Box, Capsule, Cylinder, Ellipsoid, Mesh, Sphere
from reimpl.geometry._drake_text import shortest
from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _mjcf_values as values
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._mesh_inertia import (
    MassProperties,
    convex_hull_properties,
    invalidity,
    mesh_properties,
)
from reimpl.multibody.parsing._mjcf_context import MjcfContext
from reimpl.multibody.parsing._mjcf_pose import parse_transform
from reimpl.multibody.parsing._obj_mesh import read_obj_mesh
from reimpl.multibody.parsing._urdf_inertia import _UNIT_INERTIA_DEMAND
from reimpl.multibody.parsing._xml import XmlElement
from reimpl.multibody.tree import SpatialInertia, UnitInertia

__all__ = ["BodyMass", "geom_mass", "inertial_mass"]

_FOUR_THIRDS_PI = (4.0 / 3.0) * math.pi


def _positive(value: float, name: str, function: str) -> None:
    """Drake's ThrowUnlessValueIsPositiveFinite."""
    if not (math.isfinite(value) and value > 0):
        raise RuntimeError(f"{function}(): {name} is not positive and finite: {shortest(value)}.")


def _solid(function: str, sizes: tuple[tuple[str, float], ...], volume: float) -> float:
    """Solid<Shape>WithDensity(1, ...): its size checks, then WithMass's mass check."""
    for name, size in sizes:
        _positive(size, name, f"{function}WithDensity")
    _positive(volume, "mass", f"{function}WithMass")
    return volume


def _sphere(shape: Sphere) -> float:
    r = shape.radius()
    return _solid("SolidSphere", (("radius", r),), _FOUR_THIRDS_PI * r * r * r)


def _box(shape: Box) -> float:
    w, d, h = shape.width(), shape.depth(), shape.height()
    return _solid("SolidBox", (("x-length", w), ("y-length", d), ("z-length", h)), w * d * h)


def _capsule(shape: Capsule) -> float:
    r, length = shape.radius(), shape.length()
    pi_r_squared = math.pi * r * r
    volume = pi_r_squared * length + (4.0 / 3.0) * pi_r_squared * r
    return _solid("SolidCapsule", (("radius", r), ("length", length)), volume)


def _cylinder(shape: Cylinder) -> float:
    r, length = shape.radius(), shape.length()
    return _solid("SolidCylinder", (("radius", r), ("length", length)), math.pi * r * r * length)


def _ellipsoid(shape: Ellipsoid) -> float:
    a, b, c = shape.a(), shape.b(), shape.c()
    sizes = (("semi-axis a", a), ("semi-axis b", b), ("semi-axis c", c))
    return _solid("SolidEllipsoid", sizes, _FOUR_THIRDS_PI * a * b * c)


#: shape type -> its volume at unit density (centroid at the origin)
_PRIMITIVE_VOLUMES: dict[type, Any] = {
    Sphere: _sphere,
    Box: _box,
    Capsule: _capsule,
    Cylinder: _cylinder,
    Ellipsoid: _ellipsoid,
}


def _mesh_unit(
    context: MjcfContext, node: XmlElement, mesh_name: str, shape: Mesh
) -> tuple[float, tuple[float, float, float]]:
    """The InertiaCalculator's mesh case: (volume, centroid), cached by mesh asset name."""
    cached = context.mesh_inertia.get(mesh_name)
    if cached is not None:
        return cached
    path = str(shape.source().path())
    scale = tuple(float(s) for s in shape.scale3())
    mesh = read_obj_mesh(path, (scale[0], scale[1], scale[2]), path)
    if mesh.warning:  # N.B. Drake reads the mesh with its default policy: never strict.
        Diagnostics(None).warning(mesh.warning)
    result: MassProperties | str = mesh_properties(mesh, 1.0)
    fell_back = isinstance(result, str)
    if isinstance(result, str):
        context.d.warning(node, result)
        result = convex_hull_properties(mesh.vertices, 1.0, path)
        if isinstance(result, str):
            raise context.d.error(
                node,
                f"Failed to compute spatial inertia even for the convex hull of {path}.\n{result}",
            )
    context.mesh_inertia[mesh_name] = (result.mass, result.com)
    if fell_back:
        context.d.warning(
            node,
            f"CalcSpatialInertia() failed to compute a physically valid inertia for mesh "
            f"{mesh_name} (probably the mesh is not watertight). The spatial inertia was "
            "computed using its convex hull as a fallback.",
        )
    return result.mass, result.com


def geom_mass(
    context: MjcfContext,
    node: XmlElement,
    name: str,
    shape: Any,
    X_BG: RigidTransform,
) -> tuple[float, np.ndarray]:
    """The geom's (mass, centre of mass in the body), or Drake's error."""
    if isinstance(shape, Mesh):
        volume, centroid = _mesh_unit(context, node, node.get("mesh") or "", shape)
    else:
        volume, centroid = _PRIMITIVE_VOLUMES[type(shape)](shape), (0.0, 0.0, 0.0)
    mass = values.scalar(node, "mass")
    if mass is None:
        density = values.scalar(node, "density")
        mass = volume * (1000.0 if density is None else density)
    if not (math.isfinite(mass) and mass >= 0):
        report = invalidity(mass, centroid, np.zeros((3, 3)))
        raise context.d.error(node, f"geom {name} {report}")
    p_BG = X_BG.rotation().matrix() @ np.asarray(centroid) + X_BG.translation()
    return mass, p_BG


def _dot(u: list[float], v: list[float]) -> float:
    """A dot product summed left to right, as Eigen sums a short one."""
    total = u[0] * v[0]
    for a, b in zip(u[1:], v[1:], strict=True):
        total += a * b
    return total


def _re_express(diagonal: list[float], R: np.ndarray) -> np.ndarray:
    """RotationalInertia(Ixx, Iyy, Izz).ReExpress(R), in Drake's operations (so that a
    report prints the same digits): rotational_inertia.cc's ReExpressInPlace."""
    a, b, c = diagonal
    d = e = f = 0.0
    L = [[a - c, d], [d, b - c], [2 * e, 2 * f]]
    rt = [[R[0, 0], R[1, 0], R[2, 0]], [R[0, 1], R[1, 1], R[2, 1]]]
    rv = [e * rt[1][k] - f * rt[0][k] for k in range(3)]
    columns = [[L[0][j], L[1][j], L[2][j]] for j in range(2)]
    Y = [[_dot(list(R[i]), columns[j]) for j in range(2)] for i in (1, 2)]
    z11 = _dot(Y[0], [rt[0][1], rt[1][1]])
    z22 = _dot(Y[1], [rt[0][2], rt[1][2]])
    z00 = (L[0][0] + L[1][1]) - (z11 + z22)
    z10 = _dot(Y[0], [rt[0][0], rt[1][0]])
    z20 = _dot(Y[1], [rt[0][0], rt[1][0]])
    z21 = _dot(Y[1], [rt[0][1], rt[1][1]])
    xx, xy, yy = z00 + c, z10 + rv[2], z11 + c
    xz, yz, zz = z20 - rv[1], z21 + rv[0], c + z22
    return np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])


def inertial_mass(context: MjcfContext, node: XmlElement) -> tuple[float, np.ndarray]:
    """ParseInertial: the body's (mass, centre of mass), or Drake's error."""
    X_BF = parse_transform(context, node)
    mass = values.scalar(node, "mass")
    if mass is None:
        raise context.d.error(node, "The inertial tag must include the mass attribute.")
    diagonal = values.vector(node, "diaginertia", 3)
    if diagonal is not None:
        inertia = _re_express(diagonal, X_BF.rotation().matrix())
    else:
        full = values.vector(node, "fullinertia", 6)
        if full is None:
            raise context.d.error(
                node,
                "The inertial tag must include either the diaginertia or fullinertia attribute.",
            )
        xx, yy, zz, xy, xz, yz = full
        inertia = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    if not mass > 0:
        raise SystemExit(_UNIT_INERTIA_DEMAND)
    report = invalidity(mass, (0.0, 0.0, 0.0), inertia / mass)
    if report is not None:
        raise RuntimeError(report)
    return mass, X_BF.translation()


@dataclass
class BodyMass:
    """A body's mass and centre of mass, summed as SpatialInertia's += sums them."""

    mass: float = 0.0
    com: np.ndarray | None = None

    def add(self, mass: float, com: np.ndarray) -> None:
        own = self.com if self.com is not None else np.zeros(3)
        total = self.mass + mass
        this_mass, other_mass = (1.0, 1.0) if total == 0 else (self.mass, mass)
        scale = 1.0 / (total if total != 0 else 2.0)
        self.com = (this_mass * scale) * own + (other_mass * scale) * np.asarray(com)
        self.mass = total

    def spatial_inertia(self) -> SpatialInertia:
        com = self.com if self.com is not None else np.zeros(3)
        return SpatialInertia(self.mass, com, UnitInertia(), skip_validity_check=True)
