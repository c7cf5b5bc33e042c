"""libccd's Minkowski Portal Refinement (MPR), as FCL's GJKCollide runs it for Drake.

Drake runs MPR at ``gjk_tolerance = 2e-12`` and python-fcl cannot set it (its
default is 1e-6), so the algorithm is ported here on FCL's support functions:
pure Python, step for step as libccd's src/mpr.c and ccd/vec3.h.

* Each shape is posed by a quaternion (Eigen's ``Quaternion(R)``) and rotated
  as ``ccdQuatRotVec``: ``v + 2·q⃗ × (q⃗ × v + w·v)``; its support point along d
  is FCL's (box corner, capsule cap, cylinder rim, sphere, ellipsoid
  ``diag(a², b², c²)·d / √(d·diag(a², b², c²)·d)``, and a convex hull's
  extreme vertex, ``Convex::findExtremeVertex``: the first vertex of largest
  ``d·v`` for up to 32 vertices, else a walk from vertex 0 along the hull's
  edges to any neighbour at least as far, until none is).
* A support point of A ⊖ B is ``v = s_A(d) − s_B(−d)``; the portal is v0 (the
  centres' difference: a shape's centre is its origin, a hull's FCL's interior
  point, the mean vertex) and a face v1 v2 v3 crossed by the ray from v0 to the
  origin; refinement pushes the face out along its normal until the origin is
  inside or the face moves less than the tolerance.
* Penetration keeps refining to the tolerance: depth is the origin's distance
  to the final face (``_point_triangle``), direction its unit witness, and the
  position the origin's barycentric weights in the portal applied on A and B.
* Comparisons are libccd's: zero within ε, ``ccdEq`` relative to the larger.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

from reimpl.geometry.proximity.transforms import (
    EPS,
    Mat,
    Pose,
    Vec,
    add,
    cross,
    dot,
    norm,
    scale,
    sub,
)

if TYPE_CHECKING:
    from reimpl.geometry._convex_hull import Hull

__all__ = ["Convex", "Mpr"]

#: Above this many vertices FCL finds a hull's extreme vertex by walking its edges.
_EDGE_WALKING_FROM = 32

_ORIGIN: Vec = (0.0, 0.0, 0.0)


def _is_zero(x: float) -> bool:
    return abs(x) < EPS


def _ccd_eq(a: float, b: float) -> bool:
    """libccd's ccdEq: equal within ε, relative to the larger magnitude."""
    ab = abs(a - b)
    if ab < EPS:
        return True
    return ab < EPS * max(abs(a), abs(b))


def _vec_eq(a: Vec, b: Vec) -> bool:
    return _ccd_eq(a[0], b[0]) and _ccd_eq(a[1], b[1]) and _ccd_eq(a[2], b[2])


def _ccd_sign(x: float) -> float:
    """libccd's ccdSign: 0 within ε of zero."""
    if _is_zero(x):
        return 0.0
    return -1.0 if x < 0 else 1.0


def _ccd_unit(a: Vec) -> Vec:
    """libccd's normalisation: ``a · (1/|a|)``."""
    return scale(a, 1.0 / math.sqrt(dot(a, a)))


Quat = tuple[float, float, float, float]


def _quaternion(R: Mat) -> Quat:
    """Eigen's Quaternion(R) as (x, y, z, w): the trace branch, else the largest diagonal."""
    t = R[0][0] + R[1][1] + R[2][2]
    if t > 0:
        t = math.sqrt(t + 1.0)
        w = 0.5 * t
        t = 0.5 / t
        return ((R[2][1] - R[1][2]) * t, (R[0][2] - R[2][0]) * t, (R[1][0] - R[0][1]) * t, w)
    i = 0
    if R[1][1] > R[0][0]:
        i = 1
    if R[2][2] > R[i][i]:
        i = 2
    j, k = (i + 1) % 3, (i + 2) % 3
    t = math.sqrt(R[i][i] - R[j][j] - R[k][k] + 1.0)
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = 0.5 * t
    t = 0.5 / t
    q[3] = (R[k][j] - R[j][k]) * t
    q[j] = (R[j][i] + R[i][j]) * t
    q[k] = (R[k][i] + R[i][k]) * t
    return (q[0], q[1], q[2], q[3])


def _quat_rotate(q: Quat, v: Vec) -> Vec:
    """libccd's ccdQuatRotVec: v + 2·q⃗ × (q⃗ × v + w·v)."""
    x, y, z, w = q
    vx, vy, vz = v
    c1x = y * vz - z * vy + w * vx
    c1y = z * vx - x * vz + w * vy
    c1z = x * vy - y * vx + w * vz
    return (
        vx + 2 * (y * c1z - z * c1y),
        vy + 2 * (z * c1x - x * c1z),
        vz + 2 * (x * c1y - y * c1x),
    )


class Convex:
    """One shape as FCL hands it to libccd: position, quaternion, centre, support mapping."""

    __slots__ = ("center", "hull", "kind", "m", "pos", "rot", "rot_inv", "vertices")

    def __init__(
        self, kind: str, m: tuple[float, ...], X_WG: Pose, hull: Hull | None = None
    ) -> None:
        self.kind, self.m, self.pos, self.hull = kind, m, X_WG.p, hull
        self.rot = _quaternion(X_WG.R)
        x, y, z, w = self.rot
        inv = 1.0 / (x * x + y * y + z * z + w * w)
        self.rot_inv = (-x * inv, -y * inv, -z * inv, w * inv)
        self.center = self.pos
        self.vertices: list[Vec] = []
        if hull is not None:
            self.vertices = [(float(v[0]), float(v[1]), float(v[2])) for v in hull.vertices]
            self.center = add(_quat_rotate(self.rot, hull.interior_point), self.pos)

    def _extreme_vertex(self, d: Vec) -> Vec:
        """FCL's Convex::findExtremeVertex along ``d`` (in the hull's frame)."""
        vertices = self.vertices
        best, value = 0, dot(d, vertices[0])
        if len(vertices) <= _EDGE_WALKING_FROM:
            for i in range(1, len(vertices)):
                candidate = dot(d, vertices[i])
                if candidate > value:
                    best, value = i, candidate
            return vertices[best]
        assert self.hull is not None
        neighbors = self.hull.neighbors
        visited = [False] * len(vertices)
        searching = True
        while searching:
            searching = False
            for n in neighbors[best]:
                if visited[n]:
                    continue
                visited[n] = True
                candidate = dot(d, vertices[n])
                if candidate >= value:
                    searching, best, value = True, n, candidate
        return vertices[best]

    def support(self, d_W: Vec) -> Vec:
        """The point of the shape farthest along d (FCL's support functions)."""
        d = _quat_rotate(self.rot_inv, d_W)
        m, kind = self.m, self.kind
        if kind == "Box":
            # N.B. Drake's FCL picks a corner even for a zero component (±1, never 0).
            v = (
                (1.0 if d[0] >= 0 else -1.0) * m[0],
                (1.0 if d[1] >= 0 else -1.0) * m[1],
                (1.0 if d[2] >= 0 else -1.0) * m[2],
            )
        elif kind == "Capsule":
            n = scale(_ccd_unit(d), m[0])
            v = (n[0], n[1], m[1] + n[2]) if d[2] > 0 else (n[0], n[1], -m[1] + n[2])
        elif kind == "Cylinder":
            rho = math.sqrt(d[0] * d[0] + d[1] * d[1])
            if _is_zero(rho):
                v = (0.0, 0.0, _ccd_sign(d[2]) * m[1])
            else:
                k = m[0] / rho
                v = (k * d[0], k * d[1], _ccd_sign(d[2]) * m[1])
        elif kind == "Sphere":
            v = scale(scale(d, m[0]), 1.0 / math.sqrt(dot(d, d)))
        elif kind == "Convex":
            v = self._extreme_vertex(d)
        else:  # Ellipsoid
            v = (m[0] * m[0] * d[0], m[1] * m[1] * d[1], m[2] * m[2] * d[2])
            v = scale(v, 1.0 / math.sqrt(dot(v, d)))
        return add(_quat_rotate(self.rot, v), self.pos)


class _Support(NamedTuple):
    """A point of the Minkowski difference A ⊖ B: v = v1 − v2."""

    v: Vec
    v1: Vec
    v2: Vec


class Mpr:
    """libccd's Minkowski Portal Refinement, as FCL's GJKCollide calls it.

    The portal is a tetrahedron (v0 inside A ⊖ B, v1 v2 v3 a face crossed by the
    ray from v0 to the origin). Refinement moves the face outwards along its
    normal until the origin is inside (intersection) or the face cannot move by
    more than the tolerance (separation). Penetration keeps refining to the
    tolerance; depth is the origin's distance to the final face.
    """

    def __init__(self, a: Convex, b: Convex, tolerance: float, max_iterations: int = 500):
        self.a, self.b, self.tolerance, self.max_iterations = a, b, tolerance, max_iterations

    def _support(self, d: Vec) -> _Support:
        v1 = self.a.support(d)
        v2 = self.b.support(scale(d, -1.0))
        return _Support(sub(v1, v2), v1, v2)

    def _discover(self, portal: list[_Support]) -> int:
        """−1: origin outside; 1: origin on v1; 2: origin on segment v0–v1; 0: portal built."""
        c1, c2 = self.a.center, self.b.center
        v0 = sub(c1, c2)
        if _vec_eq(v0, _ORIGIN):
            v0 = add(v0, (EPS * 10.0, 0.0, 0.0))
        portal[:] = [_Support(v0, c1, c2)]
        d = _ccd_unit(scale(v0, -1.0))
        portal.append(self._support(d))
        dt = dot(portal[1].v, d)
        if _is_zero(dt) or dt < 0:
            return -1
        d = cross(portal[0].v, portal[1].v)
        if _is_zero(dot(d, d)):
            return 1 if _vec_eq(portal[1].v, _ORIGIN) else 2
        d = _ccd_unit(d)
        portal.append(self._support(d))
        dt = dot(portal[2].v, d)
        if _is_zero(dt) or dt < 0:
            return -1
        d = _ccd_unit(cross(sub(portal[1].v, portal[0].v), sub(portal[2].v, portal[0].v)))
        if dot(d, portal[0].v) > 0:
            portal[1], portal[2] = portal[2], portal[1]
            d = scale(d, -1.0)
        while len(portal) < 4:
            s3 = self._support(d)
            dt = dot(s3.v, d)
            if _is_zero(dt) or dt < 0:
                return -1
            dt = dot(cross(portal[1].v, s3.v), portal[0].v)
            if dt < 0 and not _is_zero(dt):
                portal[2] = s3
            else:
                dt = dot(cross(s3.v, portal[2].v), portal[0].v)
                if dt < 0 and not _is_zero(dt):
                    portal[1] = s3
                else:
                    portal.append(s3)
                    continue
            d = _ccd_unit(cross(sub(portal[1].v, portal[0].v), sub(portal[2].v, portal[0].v)))
        return 0

    @staticmethod
    def _direction(portal: list[_Support]) -> Vec:
        return _ccd_unit(cross(sub(portal[2].v, portal[1].v), sub(portal[3].v, portal[1].v)))

    def _reaches_tolerance(self, portal: list[_Support], v4: _Support, d: Vec) -> bool:
        dv4 = dot(v4.v, d)
        gap = min(dv4 - dot(portal[1].v, d), dv4 - dot(portal[2].v, d))
        gap = min(gap, dv4 - dot(portal[3].v, d))
        return _ccd_eq(gap, self.tolerance) or gap < self.tolerance

    @staticmethod
    def _expand(portal: list[_Support], v4: _Support) -> None:
        v4v0 = cross(v4.v, portal[0].v)
        if dot(portal[1].v, v4v0) > 0:
            portal[1 if dot(portal[2].v, v4v0) > 0 else 3] = v4
        else:
            portal[2 if dot(portal[3].v, v4v0) > 0 else 1] = v4

    def _refine(self, portal: list[_Support]) -> bool:
        """Whether the origin ends up inside the portal (the shapes intersect)."""
        while True:
            d = self._direction(portal)
            dt = dot(d, portal[1].v)
            if _is_zero(dt) or dt > 0:
                return True
            v4 = self._support(d)
            dt = dot(v4.v, d)
            if not (_is_zero(dt) or dt > 0) or self._reaches_tolerance(portal, v4, d):
                return False
            self._expand(portal, v4)

    def intersect(self) -> bool:
        """libccd's ccdMPRIntersect."""
        portal: list[_Support] = []
        found = self._discover(portal)
        if found != 0:
            return found > 0
        return self._refine(portal)

    def penetration(self) -> tuple[float, Vec, Vec] | None:
        """libccd's ccdMPRPenetration: (depth, direction from A to B, position), or None."""
        portal: list[_Support] = []
        found = self._discover(portal)
        if found < 0:
            return None
        if found in (1, 2):
            pos = scale(add(portal[1].v1, portal[1].v2), 0.5)
            if found == 1:
                return 0.0, _ORIGIN, pos
            return norm(portal[1].v), _ccd_unit(portal[1].v), pos
        if not self._refine(portal):
            return None
        iterations = 0
        while True:
            d = self._direction(portal)
            v4 = self._support(d)
            if self._reaches_tolerance(portal, v4, d) or iterations > self.max_iterations:
                dist2, witness = _point_triangle(portal[1].v, portal[2].v, portal[3].v)
                depth = math.sqrt(dist2)
                direction = _ORIGIN if _is_zero(depth) else _ccd_unit(witness)
                return depth, direction, self._position(portal)
            self._expand(portal, v4)
            iterations += 1

    def _position(self, portal: list[_Support]) -> Vec:
        """The contact point: barycentric weights of the origin in the portal, on A and B."""
        v = [s.v for s in portal]
        b = [
            dot(cross(v[1], v[2]), v[3]),
            dot(cross(v[3], v[2]), v[0]),
            dot(cross(v[0], v[1]), v[3]),
            dot(cross(v[2], v[1]), v[0]),
        ]
        total = b[0] + b[1] + b[2] + b[3]
        if _is_zero(total) or total < 0:
            d = self._direction(portal)
            b = [0.0, dot(cross(v[2], v[3]), d), dot(cross(v[3], v[1]), d)]
            b.append(dot(cross(v[1], v[2]), d))
            total = b[1] + b[2] + b[3]
        inv = 1.0 / total
        p1, p2 = _ORIGIN, _ORIGIN
        for i in range(4):
            p1 = add(p1, scale(portal[i].v1, b[i]))
            p2 = add(p2, scale(portal[i].v2, b[i]))
        return scale(add(scale(p1, inv), scale(p2, inv)), 0.5)


def _point_segment(x0: Vec, b: Vec) -> tuple[float, Vec]:
    """Squared distance from the origin to segment x0–b, and the nearest point."""
    d = sub(b, x0)
    t = -1.0 * dot(x0, d) / dot(d, d)
    if t < 0 or _is_zero(t):
        w = x0
    elif t > 1 or _ccd_eq(t, 1.0):
        w = b
    else:
        w = add(scale(d, t), x0)
    return dot(w, w), w


def _point_triangle(x0: Vec, b: Vec, c: Vec) -> tuple[float, Vec]:
    """Squared distance from the origin to triangle (x0, b, c), and the nearest point.

    T(s, t) = x0 + s·(b − x0) + t·(c − x0); the unconstrained minimiser when it
    lies in the triangle, else the nearest of the three edges.
    """
    d1, d2, a = sub(b, x0), sub(c, x0), x0
    v, w = dot(d1, d1), dot(d2, d2)
    p, q, r = dot(a, d1), dot(a, d2), dot(d1, d2)
    det = w * v - r * r
    if _is_zero(det):
        s = t = -1.0
    else:
        s = (q * r - w * p) / det
        t = (-s * r - q) / w
    if (
        (_is_zero(s) or s > 0)
        and (_ccd_eq(s, 1.0) or s < 1)
        and (_is_zero(t) or t > 0)
        and (_ccd_eq(t, 1.0) or t < 1)
        and (_ccd_eq(t + s, 1.0) or t + s < 1)
    ):
        witness = add(add(x0, scale(d1, s)), scale(d2, t))
        return dot(witness, witness), witness
    best = _point_segment(x0, b)
    for candidate in (_point_segment(x0, c), _point_segment(b, c)):
        if candidate[0] < best[0]:
            best = candidate
    return best
