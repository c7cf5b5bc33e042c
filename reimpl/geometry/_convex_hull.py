"""Drake's convex hull of a point cloud (MakeConvexHull), on Qhull through scipy.

Drake counterpart: geometry/proximity/make_convex_hull_mesh_impl.cc. A Mesh or
Convex in the proximity role *is* this hull (FCL gets it as an ``fcl::Convex``),
and ``GetConvexHull()`` returns it as a PolygonSurfaceMesh. The rules, measured
on pydrake 1.51.1:

1. Planarity: with Drake's FindNormal ``n`` (``_proximity_mesh``: v₀, the first
   vᵢ with ‖vᵢ − v₀‖² ≥ 1e-24, the first vⱼ from there spanning a plane with it)
   and ``d = n·v₀``, the cloud is planar when every ``|n·vᵢ − d| ≤ 1e-12``. Qhull
   cannot hull a flat cloud, so Drake adds the point ``c + n`` (``c`` the mean
   vertex) and afterwards moves the hull vertex with ``n·p − d > 0.75`` back to
   ``c``: a flat hull has ``c`` as a vertex and zero-area faces around it.
2. Qhull (2020.2, Drake's; scipy's is the same release) runs with Drake's
   options, none: facets are merged where coplanar within Qhull's precision
   (its default ``C-0``), the coordinates as given (scaled before the hull).
   scipy always adds ``Qt`` (triangulated output); the triangles of one merged
   facet share its hyperplane, so grouping them by hyperplane gives Drake's
   polygons back (the same vertex sets and faces as pydrake's for all 105
   vendored mesh files whose hull pydrake can make).
3. Each polygon is wound right-handed about its facet's outward normal: its
   vertices sorted by ``atan2((u₀ × uᵢ)·n, u₀·uᵢ)``, ``uᵢ`` the unit vector from
   the polygon's centre (the mean of its vertices) to vertex i, Drake's
   OrderPolyVertices.

Not Drake's: the *order* of the hull's vertices. Drake numbers them in Qhull's
internal vertex list, which scipy does not expose; reimpl numbers them in the
order the file lists them. The hull is the same point set with the same faces;
what the order decides is which vertex a support function picks among several
exactly as far along a direction (FCL takes the first), which shows only where
a hull face or edge is exactly perpendicular to that direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import numpy.typing as npt

__all__ = ["Hull", "convex_hull"]

Points = npt.NDArray[np.float64]

#: ``|n·v − d|`` above which a vertex is off the plane (Drake's planarity test).
_PLANAR = 1e-12
#: ``n·p − d`` above which a flat hull's vertex is the lifted point.
_LIFTED = 0.75
#: ‖·‖² below which Drake takes a vector as zero (FindNormal).
_ZERO_SQUARED = 1e-24


@dataclass(frozen=True)
class Hull:
    """A convex hull as Drake builds it: vertices and polygons (indices, wound outwards)."""

    vertices: Points
    polygons: tuple[tuple[int, ...], ...]

    @cached_property
    def face_data(self) -> list[int]:
        """Drake's face encoding: each polygon's vertex count, then its indices."""
        data: list[int] = []
        for polygon in self.polygons:
            data.append(len(polygon))
            data.extend(polygon)
        return data

    @cached_property
    def interior_point(self) -> tuple[float, float, float]:
        """FCL's interior point: Σ vᵢ (in order) times 1/n."""
        total = np.zeros(3)
        for v in self.vertices:
            total = total + v
        mean = total * (1.0 / len(self.vertices))
        return (float(mean[0]), float(mean[1]), float(mean[2]))

    @cached_property
    def neighbors(self) -> tuple[tuple[int, ...], ...]:
        """Each vertex's neighbours along the polygons' edges, ascending (FCL's
        FindVertexNeighbors, a std::set per vertex)."""
        found: list[set[int]] = [set() for _ in self.vertices]
        for polygon in self.polygons:
            previous = polygon[-1]
            for v in polygon:
                found[v].add(previous)
                found[previous].add(v)
                previous = v
        return tuple(tuple(sorted(s)) for s in found)


def _normal(vertices: Points) -> npt.NDArray[np.float64]:
    """Drake's FindNormal (its errors are raised earlier, by ``_proximity_mesh``)."""
    offsets = vertices - vertices[0]
    squared = (offsets**2).sum(axis=1)
    first = int(np.flatnonzero(squared >= _ZERO_SQUARED)[0])
    a = offsets[first] / math.sqrt(squared[first])
    for j in range(first, len(vertices)):
        n = np.cross(a, offsets[j])
        if squared[j] >= _ZERO_SQUARED and n @ n >= _ZERO_SQUARED:
            return n / math.sqrt(n @ n)
    raise AssertionError("collinear vertices reach the hull")


def _wound(
    points: Points,
    indices: list[int],
    centre: npt.NDArray[np.float64],
    normal: npt.NDArray[np.float64],
) -> list[int]:
    """OrderPolyVertices: by angle about ``centre``, right-handed about ``normal``."""

    def unit(v: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return v / math.sqrt(v @ v)

    u0 = unit(points[indices[0]] - centre)
    angles = []
    for i in indices:
        ui = unit(points[i] - centre)
        angles.append(math.atan2(float(np.cross(u0, ui) @ normal), float(u0 @ ui)))
    return [i for _, i in sorted(zip(angles, indices, strict=True), key=lambda pair: pair[0])]


def convex_hull(vertices: Points) -> Hull:
    """The convex hull of ``vertices`` (at least three, not all on a line), as Drake makes it."""
    from scipy.spatial import ConvexHull  # noqa: PLC0415 (heavy; only for meshes)

    n = _normal(vertices)
    d = float(n @ vertices[0])
    planar = bool(np.all(np.abs(vertices[1:] @ n - d) <= _PLANAR))
    total = vertices[0].copy()
    for v in vertices[1:]:
        total = total + v
    centre = total / len(vertices)  # Drake's interior point: Σ vᵢ in order, then / n
    points = np.vstack([vertices, centre + n]) if planar else vertices
    qhull = ConvexHull(points)
    facets: dict[bytes, tuple[npt.NDArray[np.float64], set[int]]] = {}
    for simplex, equation in zip(qhull.simplices, qhull.equations, strict=True):
        facets.setdefault(equation.tobytes(), (equation, set()))[1].update(simplex.tolist())
    mapped = points.copy()
    if planar:
        mapped[mapped @ n - d > _LIFTED] = centre
    used = sorted({i for _, members in facets.values() for i in members})
    number = {old: new for new, old in enumerate(used)}
    polygons = tuple(
        tuple(
            number[i]
            for i in _wound(mapped, sorted(members), points[sorted(members)].mean(axis=0), eq[:3])
        )
        for eq, members in facets.values()
    )
    return Hull(mapped[used], polygons)
