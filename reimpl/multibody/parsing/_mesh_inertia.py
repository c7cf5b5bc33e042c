"""A mesh's mass properties where they decide whether Drake 1.51.1 parses a model.

Drake's CalcSpatialInertia of a closed triangle mesh (geometry_spatial_inertia.cc)
sums, over the triangles (p, q, r), the tetrahedra with the origin:
6V = Σ p·(q × r), the centroid Σ (p + q + r)·6Vᵢ / (4·6V), and the covariance
(for the unit inertia G). It fails, with a message instead of a result, when

* V ≤ 1e-14: ``CalcSpatialInertia(): The calculated volume of a triangle surface
  mesh is V whereas a reasonable positive value of at least 1e-14 was expected.
  The mesh may have bad geometry, e.g., it is an open mesh or the winding (order
  of vertices) of at least one face does not produce an outward normal.`` (V as
  fmt prints a double, summed in Drake's order so that it prints to the digit);
* the spatial inertia fails IsPhysicallyValid() (``invalidity`` below).

The MuJoCo parser then falls back to the mesh's convex hull. reimpl computes
the hull of a vertex cloud that spans 3D (its own incremental hull: the same
polytope as Drake's qhull, its volume and centroid up to rounding); a hull
that fails too is left out (a reimpl error), and so is Drake's hull of a planar
cloud, a flattened pyramid whose volume reimpl does not reproduce.

``invalidity`` gives SpatialInertia::CreateInvalidityReport: a mass that is
negative or not finite (``\\nmass = M is negative or not finite.\\n``), a centre
of mass that is not finite, or a rotational inertia about the centre of mass
that could not be physical; that last report (the inertia about the origin,
then its principal moments) is reproduced when the centre of mass is the
origin, and left out (a reimpl error) otherwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from reimpl.geometry._drake_text import shortest
from reimpl.multibody.parsing._diagnostics import ModelParseError
from reimpl.multibody.parsing._obj_mesh import ObjMesh, Triangle, Vertex
from reimpl.multibody.parsing._urdf_inertia import (
    _invalidity,
    _matrix_text,
    _principal_moments,
)

__all__ = [
    "MassProperties",
    "convex_hull_properties",
    "invalidity",
    "mesh_properties",
    "volume_message",
]

_Matrix = npt.NDArray[np.float64]
#: CalcSpatialInertiaImpl's smallest volume.
_MIN_VOLUME = 1.0e-14
#: The covariance of the canonical tetrahedron (0, e₀, e₁, e₂) of unit density.
_C_CANONICAL = np.array(
    [
        [1 / 60.0, 1 / 120.0, 1 / 120.0],
        [1 / 120.0, 1 / 60.0, 1 / 120.0],
        [1 / 120.0, 1 / 120.0, 1 / 60.0],
    ]
)
_REPORT_HEADER = "Spatial inertia fails SpatialInertia::IsPhysicallyValid()."


@dataclass(frozen=True)
class MassProperties:
    """Mass, centroid (about the mesh's origin) and unit inertia G about the origin."""

    mass: float
    com: tuple[float, float, float]
    G: _Matrix


def volume_message(volume: float) -> str:
    return (
        f"CalcSpatialInertia(): The calculated volume of a triangle surface mesh is "
        f"{shortest(volume)} whereas a reasonable positive value of at least 1e-14 was "
        "expected. The mesh may have bad geometry, e.g., it is an open mesh or the winding "
        "(order of vertices) of at least one face does not produce an outward normal."
    )


def _point_mass(p: _Matrix) -> _Matrix:
    """UnitInertia::PointMass(p): [p]×ᵀ[p]×."""
    x, y, z = (float(v) for v in p)
    return np.array(
        [
            [y * y + z * z, -x * y, -x * z],
            [-x * y, x * x + z * z, -y * z],
            [-x * z, -y * z, x * x + y * y],
        ]
    )


def invalidity(mass: float, com: tuple[float, float, float], G: _Matrix) -> str | None:
    """SpatialInertia(mass, com, G).CreateInvalidityReport(), or None when it is valid."""
    if not (math.isfinite(mass) and mass >= 0):
        return f"{_REPORT_HEADER}\nmass = {shortest(mass)} is negative or not finite.\n"
    if not all(math.isfinite(c) for c in com):
        x, y, z = (shortest(c) for c in com)
        return f"{_REPORT_HEADER}\nPosition vector [{x}  {y}  {z}] has non-finite elements.\n"
    p = np.asarray(com, dtype=float)
    central = (G - _point_mass(p)) * mass
    if np.isfinite(central).all() and _invalidity(central) is None:
        return None
    if p.any() or not np.isfinite(central).all():
        raise ModelParseError(
            "reimpl does not write Drake's report of an implausible inertia whose centre of "
            "mass is not the origin (or is not finite)"
        )
    about_origin = G * mass
    a, b, c = _principal_moments(about_origin)
    return (
        f"{_REPORT_HEADER}\n mass = {shortest(mass)}\n Center of mass = [0  0  0]\n"
        f" Inertia about point P, I_BP =\n{_matrix_text(about_origin)}"
        " Principal moments of inertia about Bcm (center of mass) =\n"
        f"[{shortest(a)}  {shortest(b)}  {shortest(c)}]\n"
    )


def _triangles_properties(
    vertices: list[Vertex], triangles: list[Triangle], density: float
) -> MassProperties | str:
    """CalcSpatialInertiaImpl(TriangleSurfaceMesh, density)."""
    vol_times_six = 0.0
    accum = [0.0, 0.0, 0.0]
    C = np.zeros((3, 3))
    for i, j, k in triangles:
        p, q, r = vertices[i], vertices[j], vertices[k]
        cross = (
            p[1] * q[2] - p[2] * q[1],
            p[2] * q[0] - p[0] * q[2],
            p[0] * q[1] - p[1] * q[0],
        )
        tet = cross[0] * r[0] + cross[1] * r[1] + cross[2] * r[2]
        A = np.array([p, q, r], dtype=float)
        C += A.T @ _C_CANONICAL @ A * tet
        vol_times_six += tet
        for axis in range(3):
            accum[axis] += (p[axis] + q[axis] + r[axis]) * tet
    volume = vol_times_six / 6.0
    if volume <= _MIN_VOLUME:
        return volume_message(volume)
    mass = density * volume
    com = (
        accum[0] / (vol_times_six * 4),
        accum[1] / (vol_times_six * 4),
        accum[2] / (vol_times_six * 4),
    )
    C /= volume
    G = np.trace(C) * np.eye(3) - C
    report = invalidity(mass, com, G)
    return report if report is not None else MassProperties(mass, com, G)


def mesh_properties(mesh: ObjMesh, density: float) -> MassProperties | str:
    """The mass properties of a triangle mesh of ``density``, or Drake's message why not."""
    return _triangles_properties(mesh.vertices, mesh.triangles, density)


# ------------------------------------------------------------- convex hull


def _far_from(vertices: _Matrix, description: str) -> tuple[_Matrix, bool]:
    """Drake's ReadVertices: the plane normal through v₀, and whether the cloud is planar."""
    offsets = vertices - vertices[0]
    squared = (offsets**2).sum(axis=1)
    far = np.flatnonzero(squared >= 1e-24)
    if far.size == 0:
        raise RuntimeError(
            "MakeConvexHull failed because all vertices in the mesh were within a sphere with "
            f"radius 1e-12 for geometry: {description}."
        )
    a = offsets[far[0]] / math.sqrt(float(squared[far[0]]))
    for v in range(int(far[0]), len(vertices)):
        n = np.cross(a, offsets[v])
        if squared[v] >= 1e-24 and float(n @ n) >= 1e-24:
            n = n / math.sqrt(float(n @ n))
            planar = bool((np.abs(vertices @ n - float(n @ vertices[0])) <= 1e-12).all())
            return n, planar
    raise RuntimeError(
        "MakeConvexHull failed because all vertices in the mesh appear to be co-linear for "
        f"file: {description}."
    )


def _initial_tetrahedron(points: _Matrix) -> list[Triangle]:
    """Four points spanning 3D, as four outward-wound triangles."""
    first = 0
    second = int(np.argmax(((points - points[first]) ** 2).sum(axis=1)))
    line = points[second] - points[first]
    third = int(np.argmax((np.cross(line, points - points[first]) ** 2).sum(axis=1)))
    normal = np.cross(line, points[third] - points[first])
    fourth = int(np.argmax(np.abs((points - points[first]) @ normal)))
    a, b, c = first, second, third
    if float((points[fourth] - points[first]) @ normal) > 0:
        b, c = c, b
    return [(a, b, c), (a, c, fourth), (c, b, fourth), (b, a, fourth)]


def _sees(points: _Matrix, face: Triangle, index: int, tolerance: float) -> bool:
    """Whether ``points[index]`` lies outside ``face``'s plane (by more than ``tolerance``)."""
    p, q, r = (points[i] for i in face)
    n = np.cross(q - p, r - p)
    return float(n @ (points[index] - p)) > tolerance * float(np.linalg.norm(n))


def _hull_faces(points: _Matrix) -> list[Triangle]:
    """An incremental convex hull: outward-wound triangles over ``points`` (which span 3D)."""
    tolerance = 1e-12 * (float(np.abs(points).max()) or 1.0)
    faces = _initial_tetrahedron(points)
    corners = {i for face in faces for i in face}
    for index in range(len(points)):
        if index in corners:
            continue
        visible = [face for face in faces if _sees(points, face, index, tolerance)]
        if not visible:
            continue
        edges = {(f[i], f[(i + 1) % 3]) for f in visible for i in range(3)}
        horizon = [(u, v) for u, v in edges if (v, u) not in edges]
        faces = [f for f in faces if f not in visible] + [(u, v, index) for u, v in horizon]
    return faces


def convex_hull_properties(
    vertices: list[Vertex], density: float, description: str
) -> MassProperties | str:
    """The mass properties of the convex hull of ``vertices`` (Drake's fallback)."""
    points = np.asarray(vertices, dtype=float)
    if len(points) < 3:
        raise RuntimeError(
            "MakeConvexHull() cannot be used on a mesh with fewer than three vertices; found "
            f"{len(points)} vertices in geometry data: {description}."
        )
    _, planar = _far_from(points, description)
    if planar:
        raise ModelParseError(
            f"reimpl does not compute Drake's convex hull of the planar mesh {description}"
        )
    hull: list[Vertex] = [(float(x), float(y), float(z)) for x, y, z in points]
    return _triangles_properties(hull, _hull_faces(points), density)
