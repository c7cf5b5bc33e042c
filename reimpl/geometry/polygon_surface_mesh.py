"""PolygonSurfaceMesh and SurfacePolygon: what ``Mesh/Convex.GetConvexHull()`` returns.

Drake counterpart: geometry/proximity/polygon_surface_mesh.{h,cc}, as pydrake
1.51.1 binds it. A mesh is vertices (positions in the mesh frame M) and
``face_data``, the polygons encoded one after another as ``[count, i₀, i₁, …]``.
Each polygon's quantities are Drake's triangle fan about its first vertex A:
for the triangles (A, B, C) of the fan, ``cross = (B − A) × (C − A)``,

* ``area = Σ |cross| / 2``, ``face_normal = normalized(Σ cross)`` (zero if the
  area is zero);
* ``element_centroid = Σ |cross|·(A + B + C) / 6 / area`` (the mean vertex when
  the area is zero);
* ``total_area = Σ area``; ``centroid`` the area-weighted mean of the polygon
  centroids, accumulated polygon by polygon as Drake does.

``CalcBoundingBox()`` is ``(centre, size)`` of the vertices' axis-aligned box;
``Equal`` compares vertices and face data exactly.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["PolygonSurfaceMesh", "SurfacePolygon"]

Vector3 = npt.NDArray[np.float64]


class SurfacePolygon:
    """One polygon of a PolygonSurfaceMesh: its vertex indices."""

    __slots__ = ("_indices",)

    def __init__(self, indices: Sequence[int]) -> None:
        self._indices = tuple(int(i) for i in indices)

    def num_vertices(self) -> int:
        return len(self._indices)

    def vertex(self, i: int) -> int:
        return self._indices[i]


class PolygonSurfaceMesh:
    """A surface mesh of planar convex polygons (see the module doc)."""

    def __init__(
        self, face_data: Sequence[int] = (), vertices: Sequence[Any] | Vector3 = ()
    ) -> None:
        self._face_data = [int(x) for x in face_data]
        self._vertices = [np.array(v, dtype=float).reshape(3) for v in vertices]
        self._starts: list[int] = []
        at = 0
        while at < len(self._face_data):
            self._starts.append(at)
            at += self._face_data[at] + 1
        self._areas: list[float] = []
        self._normals: list[Vector3] = []
        self._centroids: list[Vector3] = []
        self._total_area = 0.0
        self._centroid = np.zeros(3)
        for start in self._starts:
            self._add_polygon(start)

    def _polygon(self, start: int) -> list[int]:
        return self._face_data[start + 1 : start + 1 + self._face_data[start]]

    def _add_polygon(self, start: int) -> None:
        """Drake's CalcAreaNormalAndCentroid for the polygon at ``start``."""
        indices = self._polygon(start)
        A = self._vertices[indices[0]]
        scaled_centroid, normal, double_area = np.zeros(3), np.zeros(3), 0.0
        for b, c in itertools.pairwise(indices[1:]):
            B, C = self._vertices[b], self._vertices[c]
            cross = np.cross(B - A, C - A)
            normal = normal + cross
            magnitude = float(np.sqrt(cross @ cross))
            double_area += magnitude
            scaled_centroid = scaled_centroid + magnitude * (A + B + C)
        area = double_area / 2
        self._areas.append(area)
        length = float(np.sqrt(normal @ normal))
        self._normals.append(normal / length if length > 0 else normal)
        area_scaled = scaled_centroid / 6
        if area != 0.0:
            self._centroids.append(area_scaled / area)
        else:
            self._centroids.append(np.mean([self._vertices[i] for i in indices], axis=0))
        old_area = self._total_area
        self._total_area += area
        if self._total_area != 0.0:
            self._centroid = (self._centroid * old_area + area_scaled) / self._total_area
        else:
            self._centroid = self._centroids[-1]

    # ------------------------------------------------------------- access
    def num_vertices(self) -> int:
        return len(self._vertices)

    def num_faces(self) -> int:
        return len(self._starts)

    def num_elements(self) -> int:
        return len(self._starts)

    def vertex(self, v: int) -> Vector3:
        return self._vertices[v].copy()

    def element(self, e: int) -> SurfacePolygon:
        return SurfacePolygon(self._polygon(self._starts[e]))

    def face_data(self) -> list[int]:
        return list(self._face_data)

    def area(self, f: int) -> float:
        return self._areas[f]

    def total_area(self) -> float:
        return self._total_area

    def face_normal(self, f: int) -> Vector3:
        return self._normals[f].copy()

    def element_centroid(self, e: int) -> Vector3:
        return self._centroids[e].copy()

    def centroid(self) -> Vector3:
        return np.array(self._centroid, dtype=float)

    def CalcBoundingBox(self) -> tuple[Vector3, Vector3]:
        """(centre, size) of the vertices' axis-aligned bounding box, in M."""
        low = np.full(3, np.finfo(float).max)
        high = np.full(3, np.finfo(float).min)
        for v in self._vertices:
            low, high = np.minimum(low, v), np.maximum(high, v)
        return (high + low) / 2.0, high - low

    def Equal(self, mesh: PolygonSurfaceMesh) -> bool:
        if mesh is self:
            return True
        return (
            self.num_faces() == mesh.num_faces()
            and self.num_vertices() == mesh.num_vertices()
            and all(
                np.array_equal(a, b) for a, b in zip(self._vertices, mesh._vertices, strict=True)
            )
            and self._face_data == mesh._face_data
        )
