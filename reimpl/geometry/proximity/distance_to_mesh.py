"""The signed distance from a point to a closed triangle surface: Drake's MeshDistanceBoundary.

Drake counterpart: drake/geometry/proximity/mesh_distance_boundary.cc and
calc_signed_distance_to_surface_mesh.cc (ComputeSignedDistanceToPoint of a Mesh
or Convex). A surface M (vertices, triangles wound outwards) gets, once:

* face normals ``n_f = normalized((B − A) × (C − A))``;
* feature normals (FeatureNormalSet): a vertex's is ``normalized(Σ θ_f·n_f)`` over
  its triangles, θ_f the triangle's angle at the vertex; an edge's is the sum of
  its triangles' normals, normalized each time a triangle adds to it. A vertex
  sum with ``‖·‖² < 3e-6`` (a needle, or a vertex no triangle uses) and an edge
  sum below it (a knife edge) make the whole surface unusable: each query of it
  raises ``DistanceToPoint from meshes: FeatureNormalSet: <why>``.

For a point Q (in M's frame), each triangle's nearest point N is the projection
of Q on its plane if all three barycentric coordinates are positive (feature:
the face), else the nearest point of its three edges, each clamped to its end
points (feature: the edge, or the vertex at a clamp). The nearest of all
triangles (the first in index order among equals) gives
``φ = ±|Q − N|``, + where ``(Q − N)·n_feature ≥ 0``, and ``∇φ = ±(Q − N)/|Q − N|``
(``n_feature`` where Q is on the surface). Drake visits the triangles through a
bounding-volume tree; the nearest distance is the same, and among exactly equal
ones a shared feature gives the same normal either way.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["MeshBoundary", "MeshPointDistance"]

Array = npt.NDArray[np.float64]

#: ‖·‖² below which a vertex or edge normal cannot be computed (Drake's kToleranceSquaredNorm).
_TOLERANCE_SQUARED = 3e-6
#: A triangle's edges as Drake walks them: (v2, v0), (v0, v1), (v1, v2).
_EDGES = ((2, 0), (0, 1), (1, 2))
_NEEDLE = (
    "FeatureNormalSet: Cannot compute a vertex normal because the triangles sharing the "
    "vertex form a very pointy needle."
)
_KNIFE = (
    "FeatureNormalSet: Cannot compute an edge normal because the two triangles sharing "
    "the edge make a very sharp edge."
)


@dataclass(frozen=True)
class MeshPointDistance:
    """φ(Q) to a surface, its nearest point N and gradient, in the surface's frame M."""

    distance: float
    p_MN: Array
    gradient: Array


def _unit(v: Array) -> Array:
    length = np.sqrt((v * v).sum(axis=-1, keepdims=True))
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(length > 0, v / length, v)


class MeshBoundary:
    """A triangle surface with Drake's feature normals (or why it has none)."""

    def __init__(self, vertices: Array, triangles: npt.NDArray[np.intp]) -> None:
        self.vertices = np.asarray(vertices, dtype=float)
        self.triangles = np.asarray(triangles, dtype=np.intp).reshape(-1, 3)
        V, T = self.vertices, self.triangles
        A, B, C = V[T[:, 0]], V[T[:, 1]], V[T[:, 2]]
        self.face_normals = _unit(np.cross(B - A, C - A))
        self.error: str | None = None
        self.vertex_normals = np.zeros_like(V)
        self.edge_normals: dict[tuple[int, int], Array] = {}
        self._feature_normals()
        #: Each triangle's edge normals in Drake's edge order (see ``_EDGES``).
        self._edges = np.zeros((len(T), 3, 3))
        if self.error is None:
            for e, (previous, i) in enumerate(_EDGES):
                for k, (a, b) in enumerate(
                    zip(T[:, previous].tolist(), T[:, i].tolist(), strict=False)
                ):
                    self._edges[k, e] = self.edge_normals[(min(a, b), max(a, b))]

    def _feature_normals(self) -> None:
        """Drake's FeatureNormalSet::MaybeCreate, triangle by triangle."""
        V = self.vertices
        for f, triangle in enumerate(self.triangles.tolist()):
            n = self.face_normals[f]
            edges = [_unit(V[triangle[(i + 1) % 3]] - V[triangle[i]]) for i in range(3)]
            for i in range(3):
                angle = np.arccos(float(edges[i] @ -edges[(i + 2) % 3]))
                self.vertex_normals[triangle[i]] += angle * n
            for i in range(3):
                a, b = triangle[i], triangle[(i + 1) % 3]
                key = (min(a, b), max(a, b))
                found = self.edge_normals.get(key)
                if found is None:
                    self.edge_normals[key] = n.copy()
                    continue
                found = found + n
                if float(found @ found) < _TOLERANCE_SQUARED:
                    self.error = _KNIFE
                    return
                self.edge_normals[key] = found / np.sqrt(found @ found)
        squared = (self.vertex_normals**2).sum(axis=1)
        if np.any(squared < _TOLERANCE_SQUARED):
            self.error = _NEEDLE
            return
        self.vertex_normals = self.vertex_normals / np.sqrt(squared)[:, None]

    def signed_distance(self, p_MQ: Array) -> MeshPointDistance:
        """φ(Q), N and ∇φ (see the module doc); raises Drake's message for an unusable one."""
        if self.error is not None:
            raise RuntimeError(f"DistanceToPoint from meshes: {self.error}")
        V, T = self.vertices, self.triangles
        Q = np.asarray(p_MQ, dtype=float)
        P = V[T]  # (t, 3 vertices, 3)
        # The face: the projection of Q on the triangle's plane, by least squares in its edges.
        e1, e2, q = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], Q - P[:, 0]
        d11, d12, d22 = (e1 * e1).sum(1), (e1 * e2).sum(1), (e2 * e2).sum(1)
        q1, q2 = (q * e1).sum(1), (q * e2).sum(1)
        det = d11 * d22 - d12 * d12
        with np.errstate(invalid="ignore", divide="ignore"):
            b1 = (d22 * q1 - d12 * q2) / det
            b2 = (d11 * q2 - d12 * q1) / det
        b0 = 1.0 - b1 - b2
        inside = (b0 > 0) & (b1 > 0) & (b2 > 0)
        best_d = np.full(len(T), np.inf)
        best_p = np.zeros((len(T), 3))
        feature = np.zeros((len(T), 3))
        face_p = P[:, 0] * b0[:, None] + P[:, 1] * b1[:, None] + P[:, 2] * b2[:, None]
        face_d = ((Q - face_p) ** 2).sum(1)
        best_d[inside], best_p[inside] = face_d[inside], face_p[inside]
        feature[inside] = self.face_normals[inside]
        # The edges, in Drake's order: (v2, v0), (v0, v1), (v1, v2).
        outside = np.flatnonzero(~inside)
        for e, (previous, i) in enumerate(_EDGES):
            a, b = P[outside, previous], P[outside, i]
            ab = b - a
            t = (ab * (Q - a)).sum(1) / (ab * ab).sum(1)
            point = (1.0 - t)[:, None] * a + t[:, None] * b
            normal = self._edges[outside, e].copy()
            low, high = t <= 0, t >= 1
            point[low], normal[low] = a[low], self.vertex_normals[T[outside[low], previous]]
            point[high], normal[high] = b[high], self.vertex_normals[T[outside[high], i]]
            d = ((Q - point) ** 2).sum(1)
            better = d < best_d[outside]
            rows = outside[better]
            best_d[rows], best_p[rows], feature[rows] = d[better], point[better], normal[better]
        k = int(np.argmin(best_d))
        p_MN, n = best_p[k], feature[k]
        p_NQ = Q - p_MN
        sign = 1.0 if float(p_NQ @ n) >= 0 else -1.0
        distance = float(np.sqrt(best_d[k]))
        gradient = n if distance == 0 else sign * p_NQ / np.sqrt(p_NQ @ p_NQ)
        return MeshPointDistance(sign * distance, p_MN, gradient)
