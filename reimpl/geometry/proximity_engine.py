"""The proximity engine: FCL objects for one GeometryState, posed, and Drake's narrowphase.

Drake counterpart: drake/geometry/proximity_engine.cc and proximity/*_callback.cc
(Drake 1.51.1 builds on its vendored FCL and libccd). This is the only module
that imports ``fcl`` (python-fcl); everything else sees GeometryIds, numpy
arrays and result objects.

Posing. A pose port holds ``X_PF`` for each frame of its source, F's pose in
its parent P (measured: a frame registered under another frame). Then
``X_WF = X_WP · X_PF`` down the frame tree, ``X_WG = X_WF · X_FG`` for a
geometry on F (rounded as Drake's fused multiply-adds round it), and
``X_WG = X_FG`` for anchored geometry. Posing again moves only the FCL objects
whose ``X_WG`` changed.

Broadphase. Two ``fcl.DynamicAABBTreeCollisionManager``, as in Drake: one for
dynamic geometry (queried against itself) and one for anchored geometry
(queried against the dynamic one, dynamic object first); anchored pairs are
never met. Each met pair is kept only if ``collision_filter.can_collide_with``
(filters and activation). python-fcl hands callbacks new wrappers, so a met
object is named by its translation (see ``_identify``). Per pose the engine
keeps the met pairs, the distance traversal's visits and every narrowphase
answer; the filter is applied at each query, as it may change in between.

Narrowphase, per pair (A, B) with ``id_A < id_B`` (Drake orders the pair
before computing it), as Drake computes it:

* Sphere–{Sphere, Box, Cylinder, Capsule, HalfSpace}: closed forms through the
  signed distance φ_B(Ao) from the sphere's centre Ao to B, its gradient ∇φ_B
  and nearest point N. Penetration ``depth = r_A − φ_B(Ao)`` (reported when
  ``depth ≥ 0``), ``p_WCb = X_WB · p_BN``, ``nhat_BA_W = ∇φ_B``,
  ``p_WCa = p_WA + r_A·(−nhat_BA_W)``; signed distance ``φ = φ_B(Ao) − r_A``,
  ``p_ACa = −r_A · R_AW · ∇φ_B``, ``p_BCb = p_BN``.
* Every other penetration: FCL's single contact (position c, normal n from A to
  B, depth d > ε): ``nhat_BA_W = −n``, ``p_WCa = c − d/2 · nhat_BA_W``,
  ``p_WCb = c + d/2 · nhat_BA_W``. FCL answers Box–Box and X–HalfSpace in closed
  form (python-fcl's own); the rest is libccd's MPR, which Drake runs at
  ``gjk_tolerance = 2e-12`` while python-fcl cannot set it (1e-6), so MPR is
  reimplemented here (``_Mpr``) on FCL's support functions.
  N.B. For Sphere–Ellipsoid with the ellipsoid's id lower, Drake re-labels the
  result after FCL's, so ``id_A`` is the sphere's, the larger (measured).
* Every other signed distance: python-fcl's GJK/EPA signed distance (bit-equal
  to pydrake 1.51.1's, measured), ``nhat_BA_W = (p_WCa − p_WCb) / φ``; when
  ``|φ| < 1e-14``, Drake's touching rules (sphere, box–box) or NaN.
* HalfSpace–HalfSpace penetration, and signed distance between a HalfSpace and
  anything but a Sphere, raise Drake's messages.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple, cast

import fcl
import numpy as np
import numpy.typing as npt

from reimpl.geometry.identifier import FrameId, GeometryId, SourceId
from reimpl.geometry.shape import Box, Capsule, Cylinder, Ellipsoid, HalfSpace, Shape, Sphere

__all__ = ["PairResult", "PoseInput", "ProximityEngine", "WorldPoses", "compose_poses"]

Vec = tuple[float, float, float]
Mat = tuple[Vec, Vec, Vec]
Array = npt.NDArray[np.float64]

#: Machine epsilon, libccd's CCD_EPS and Drake's ε.
_EPS = 2.220446049250313e-16
_NAN = (math.nan, math.nan, math.nan)
_ORIGIN: Vec = (0.0, 0.0, 0.0)


# ============================================================== vector algebra
# Tuples of floats: a 3-vector costs less than a numpy array at this size.
# Sums run left to right, as Eigen evaluates 3-vectors and 3×3 products.
def _add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _scale(a: Vec, k: float) -> Vec:
    return (a[0] * k, a[1] * k, a[2] * k)


def _dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _norm(a: Vec) -> float:
    return math.sqrt(_dot(a, a))


def _unit(a: Vec) -> Vec:
    """``a / |a|`` (Eigen's ``normalized()``: unchanged when ``|a| = 0``)."""
    n = _norm(a)
    return a if n == 0 else (a[0] / n, a[1] / n, a[2] / n)


def _rot(R: Mat, v: Vec) -> Vec:
    """R · v."""
    return (_dot(R[0], v), _dot(R[1], v), _dot(R[2], v))


def _rot_t(R: Mat, v: Vec) -> Vec:
    """Rᵀ · v."""
    return (
        R[0][0] * v[0] + R[1][0] * v[1] + R[2][0] * v[2],
        R[0][1] * v[0] + R[1][1] * v[1] + R[2][1] * v[2],
        R[0][2] * v[0] + R[1][2] * v[1] + R[2][2] * v[2],
    )


def _col(R: Mat, i: int) -> Vec:
    return (R[0][i], R[1][i], R[2][i])


class _Pose(NamedTuple):
    """X_WG as plain floats: rotation rows and translation."""

    R: Mat
    p: Vec

    def apply(self, v: Vec) -> Vec:
        """X_WG · p_G = R · p_G + p."""
        return _add(_rot(self.R, v), self.p)

    def apply_inverse(self, v: Vec) -> Vec:
        """X_WG⁻¹ · p_W = Rᵀ · p_W + Rᵀ · (−p), as Drake's ``X.inverse() * p``."""
        return _add(_rot_t(self.R, v), _rot_t(self.R, _scale(self.p, -1.0)))


# ================================================================ composition
# Drake's Eigen products run on fused multiply-adds: X₁·X₂ has rotation entries
# fma(a₂, b₂, fma(a₁, b₁, a₀·b₀)) and translation fma(a₂, v₂, fma(a₁, v₁, fma(a₀, v₀, p₁)))
# (bit-equal to pydrake 1.51.1's RigidTransform.multiply on 3000 random pairs, measured).
# numpy has no fma; TwoProduct/TwoSum (Dekker, Knuth) emulate it elementwise.
_SPLIT = 134217729.0  # 2²⁷ + 1, Veltkamp's splitter for doubles


def _fma(a: Array, b: Array, c: Array) -> Array:
    """a·b + c with one rounding (error-free product and sum, then one final sum)."""
    product = a * b
    t = _SPLIT * a
    a_hi = t - (t - a)
    a_lo = a - a_hi
    t = _SPLIT * b
    b_hi = t - (t - b)
    b_lo = b - b_hi
    error = ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo
    total = product + c
    virtual = total - product
    rounding = (product - (total - virtual)) + (c - virtual)
    result: Array = total + (rounding + error)
    return result


def compose_poses(R1: Array, p1: Array, R2: Array, p2: Array) -> tuple[Array, Array]:
    """X₁·X₂ = (R₁·R₂, R₁·p₂ + p₁) for stacks (..., 3, 3) and (..., 3), as Drake rounds it."""
    R = _fma(
        R1[..., :, 2:3],
        R2[..., 2:3, :],
        _fma(R1[..., :, 1:2], R2[..., 1:2, :], R1[..., :, 0:1] * R2[..., 0:1, :]),
    )
    p = _fma(
        R1[..., :, 2],
        p2[..., 2:3],
        _fma(R1[..., :, 1], p2[..., 1:2], _fma(R1[..., :, 0], p2[..., 0:1], p1)),
    )
    return R, p


# ===================================================================== shapes
class _ShapeInfo(NamedTuple):
    """How Drake's engine sees a shape: FCL's name for it, its measures, an FCL geometry."""

    name: str
    measures: tuple[float, ...]
    make: Callable[[], Any]


def _shape_info(shape: Shape) -> _ShapeInfo:
    """The FCL view of a supported shape (Drake's ProximityEngine::ImplementGeometry)."""
    if isinstance(shape, Sphere):
        r = shape.radius()
        return _ShapeInfo("Sphere", (r,), lambda: fcl.Sphere(r))
    if isinstance(shape, Box):
        w, d, h = shape.width(), shape.depth(), shape.height()
        return _ShapeInfo("Box", (w / 2.0, d / 2.0, h / 2.0), lambda: fcl.Box(w, d, h))
    if isinstance(shape, Cylinder):
        r, length = shape.radius(), shape.length()
        return _ShapeInfo("Cylinder", (r, length / 2), lambda: fcl.Cylinder(r, length))
    if isinstance(shape, Capsule):
        r, length = shape.radius(), shape.length()
        return _ShapeInfo("Capsule", (r, length / 2), lambda: fcl.Capsule(r, length))
    if isinstance(shape, Ellipsoid):
        abc = (shape.a(), shape.b(), shape.c())
        return _ShapeInfo("Ellipsoid", abc, lambda: fcl.Ellipsoid(*abc))
    if isinstance(shape, HalfSpace):
        # Drake's half space is {z ≤ 0} in its frame: fcl::Halfspace(n = +z, d = 0).
        return _ShapeInfo("Halfspace", (), lambda: fcl.Halfspace(np.array([0.0, 0.0, 1.0]), 0.0))
    raise NotImplementedError(
        f"reimpl's proximity engine supports Sphere, Box, Cylinder, Capsule, Ellipsoid and "
        f"HalfSpace; got {type(shape).__name__}"
    )


# ========================================================= distance to a point
class _PointDistance(NamedTuple):
    """φ_G(Q) with its nearest point N (in G's frame) and its gradient ∇φ_G (in W)."""

    p_GN: Vec
    distance: float
    grad_W: Vec


def _tolerance(size: float) -> float:
    """Drake's DistanceToPointRelativeTolerance: 1e-14 · max(1, size)."""
    return 1e-14 * max(1.0, size)


def _sphere_in_frame(radius: float, p_SQ: Vec) -> tuple[Vec, float, Vec]:
    """Point Q to a sphere centred on S's origin: (p_SN, φ, ∇φ in S).

    ∇φ = p_SQ / |p_SQ| (+x when Q is at the centre), N = r·∇φ, φ = (p_SQ − p_SN)·∇φ.
    """
    dist = _norm(p_SQ)
    grad = (
        (p_SQ[0] / dist, p_SQ[1] / dist, p_SQ[2] / dist)
        if dist > _tolerance(radius)
        else (
            1.0,
            0.0,
            0.0,
        )
    )
    p_SN = _scale(grad, radius)
    return p_SN, _dot(_sub(p_SQ, p_SN), grad), grad


def _sign(x: float) -> float:
    """Drake's Sign(): −1 below zero, else +1."""
    return -1.0 if x < 0 else 1.0


def _box_in_frame(h: Sequence[float], p_GQ: Sequence[float]) -> tuple[list[float], list[float]]:
    """Point Q to the box [−h, h] (2D or 3D) in its frame: (p_GN, ∇φ in G).

    Each coordinate is inside, on the boundary (within Drake's tolerance) or
    outside. Outside: N clamps Q and ∇φ = (Q − N)/|Q − N|; on the boundary:
    ∇φ is the normalised sum of the touched faces' normals; inside: N is Q
    pushed to the nearest face (ties: +x, −x, +y, −y, +z, −z) and ∇φ its normal.
    """
    n = len(h)
    p_GN: list[float] = []
    where: list[int] = []  # 0 inside, 1 boundary, 2 outside
    for i in range(n):
        tol = _tolerance(h[i])
        c = p_GQ[i]
        if abs(c) > h[i] + tol:
            where.append(2)
            p_GN.append(_sign(c) * h[i])
        elif abs(c) >= h[i] - tol:
            where.append(1)
            p_GN.append(_sign(c) * h[i])
        else:
            where.append(0)
            p_GN.append(c)
    grad = [0.0] * n
    if 2 in where:
        diff = [p_GQ[i] - p_GN[i] for i in range(n)]
        length = math.sqrt(_sum_left(d * d for d in diff))
        grad = [d / length for d in diff]
    elif 1 in where:
        for i in range(n):
            if where[i] == 1:
                grad[i] = _sign(p_GN[i])
        length = math.sqrt(_sum_left(g * g for g in grad))
        grad = [g / length for g in grad]
    else:
        axis, best = -1, math.inf
        for i in range(n):
            for bound in (h[i], -h[i]):
                gap = abs(bound - p_GQ[i])
                if gap < best:
                    best, axis = gap, i
        s = _sign(p_GQ[axis])
        p_GN[axis] = s * h[axis]
        grad[axis] = s
    return p_GN, grad


def _sum_left(values: Any) -> float:
    """Σ values, left to right (as Eigen's fixed-size reductions)."""
    total = 0.0
    first = True
    for v in values:
        total = v if first else total + v
        first = False
    return total


def _distance_to_point(kind: str, m: tuple[float, ...], X_WG: _Pose, p_WQ: Vec) -> _PointDistance:
    """Drake's DistanceToPoint for a sphere, box, cylinder, capsule or half space G."""
    p_GQ = X_WG.apply_inverse(p_WQ)
    if kind == "Sphere":
        p_GN, distance, grad_G = _sphere_in_frame(m[0], p_GQ)
        return _PointDistance(p_GN, distance, _rot(X_WG.R, grad_G))
    if kind == "Halfspace":
        # φ = z in the half space's frame; N = (x, y, 0); ∇φ = R_WG · +z.
        return _PointDistance((p_GQ[0], p_GQ[1], 0.0), p_GQ[2], _rot(X_WG.R, (0.0, 0.0, 1.0)))
    if kind == "Capsule":
        radius, half = m
        if p_GQ[2] >= half or p_GQ[2] <= -half:
            # Nearest an end cap: the sphere of that cap.
            p_GS = (0.0, 0.0, half if p_GQ[2] >= half else -half)
            p_SN, distance, grad_G = _sphere_in_frame(radius, _sub(p_GQ, p_GS))
            return _PointDistance(_add(p_GS, p_SN), distance, _rot(X_WG.R, grad_G))
        # Nearest the spine: Q's projection R on the z = 0 plane, to the centre sphere.
        p_GM, distance, grad_G = _sphere_in_frame(radius, (p_GQ[0], p_GQ[1], 0.0))
        return _PointDistance((p_GM[0], p_GM[1], p_GQ[2]), distance, _rot(X_WG.R, grad_G))
    if kind == "Box":
        p_GN_list, grad_list = _box_in_frame(m, p_GQ)
        p_GN = (p_GN_list[0], p_GN_list[1], p_GN_list[2])
        grad_W = _rot(X_WG.R, (grad_list[0], grad_list[1], grad_list[2]))
        return _PointDistance(p_GN, _dot(grad_W, _sub(p_WQ, X_WG.apply(p_GN))), grad_W)
    if kind == "Cylinder":
        # The 2D box [−r, r]×[−h, h] of the cross section through Q and the axis,
        # in (ρ, z) with ρ along v = (x, y)/|(x, y)| (+x when Q is on the axis).
        radius, half = m
        r_Q = math.sqrt(p_GQ[0] * p_GQ[0] + p_GQ[1] * p_GQ[1])
        v = (1.0, 0.0) if r_Q < _tolerance(radius) else (p_GQ[0] / r_Q, p_GQ[1] / r_Q)
        p_BN, grad_B = _box_in_frame((radius, half), (r_Q, p_GQ[2]))
        p_GN = (p_BN[0] * v[0], p_BN[0] * v[1], p_BN[1])
        grad_W = _rot(X_WG.R, (grad_B[0] * v[0], grad_B[0] * v[1], grad_B[1]))
        return _PointDistance(p_GN, _dot(grad_W, _sub(p_WQ, X_WG.apply(p_GN))), grad_W)
    raise AssertionError(kind)


# ================================================================ libccd's MPR
def _is_zero(x: float) -> bool:
    return abs(x) < _EPS


def _ccd_eq(a: float, b: float) -> bool:
    """libccd's ccdEq: equal within ε, relative to the larger magnitude."""
    ab = abs(a - b)
    if ab < _EPS:
        return True
    return ab < _EPS * max(abs(a), abs(b))


def _vec_eq(a: Vec, b: Vec) -> bool:
    return _ccd_eq(a[0], b[0]) and _ccd_eq(a[1], b[1]) and _ccd_eq(a[2], b[2])


def _ccd_sign(x: float) -> float:
    """libccd's ccdSign: 0 within ε of zero."""
    if _is_zero(x):
        return 0.0
    return -1.0 if x < 0 else 1.0


def _ccd_unit(a: Vec) -> Vec:
    """libccd's normalisation: ``a · (1/|a|)``."""
    return _scale(a, 1.0 / math.sqrt(_dot(a, a)))


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


class _Convex:
    """One shape as FCL hands it to libccd: position, quaternion, support mapping."""

    __slots__ = ("kind", "m", "pos", "rot", "rot_inv")

    def __init__(self, kind: str, m: tuple[float, ...], X_WG: _Pose) -> None:
        self.kind, self.m, self.pos = kind, m, X_WG.p
        self.rot = _quaternion(X_WG.R)
        x, y, z, w = self.rot
        inv = 1.0 / (x * x + y * y + z * z + w * w)
        self.rot_inv = (-x * inv, -y * inv, -z * inv, w * inv)

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
            n = _scale(_ccd_unit(d), m[0])
            v = (n[0], n[1], m[1] + n[2]) if d[2] > 0 else (n[0], n[1], -m[1] + n[2])
        elif kind == "Cylinder":
            rho = math.sqrt(d[0] * d[0] + d[1] * d[1])
            if _is_zero(rho):
                v = (0.0, 0.0, _ccd_sign(d[2]) * m[1])
            else:
                k = m[0] / rho
                v = (k * d[0], k * d[1], _ccd_sign(d[2]) * m[1])
        elif kind == "Sphere":
            v = _scale(_scale(d, m[0]), 1.0 / math.sqrt(_dot(d, d)))
        else:  # Ellipsoid
            v = (m[0] * m[0] * d[0], m[1] * m[1] * d[1], m[2] * m[2] * d[2])
            v = _scale(v, 1.0 / math.sqrt(_dot(v, d)))
        return _add(_quat_rotate(self.rot, v), self.pos)


class _Support(NamedTuple):
    """A point of the Minkowski difference A ⊖ B: v = v1 − v2."""

    v: Vec
    v1: Vec
    v2: Vec


class _Mpr:
    """libccd's Minkowski Portal Refinement, as FCL's GJKCollide calls it.

    The portal is a tetrahedron (v0 inside A ⊖ B, v1 v2 v3 a face crossed by the
    ray from v0 to the origin). Refinement moves the face outwards along its
    normal until the origin is inside (intersection) or the face cannot move by
    more than the tolerance (separation). Penetration keeps refining to the
    tolerance; depth is the origin's distance to the final face.
    """

    def __init__(self, a: _Convex, b: _Convex, tolerance: float, max_iterations: int = 500):
        self.a, self.b, self.tolerance, self.max_iterations = a, b, tolerance, max_iterations

    def _support(self, d: Vec) -> _Support:
        v1 = self.a.support(d)
        v2 = self.b.support(_scale(d, -1.0))
        return _Support(_sub(v1, v2), v1, v2)

    def _discover(self, portal: list[_Support]) -> int:
        """−1: origin outside; 1: origin on v1; 2: origin on segment v0–v1; 0: portal built."""
        c1, c2 = self.a.pos, self.b.pos
        v0 = _sub(c1, c2)
        if _vec_eq(v0, _ORIGIN):
            v0 = _add(v0, (_EPS * 10.0, 0.0, 0.0))
        portal[:] = [_Support(v0, c1, c2)]
        d = _ccd_unit(_scale(v0, -1.0))
        portal.append(self._support(d))
        dt = _dot(portal[1].v, d)
        if _is_zero(dt) or dt < 0:
            return -1
        d = _cross(portal[0].v, portal[1].v)
        if _is_zero(_dot(d, d)):
            return 1 if _vec_eq(portal[1].v, _ORIGIN) else 2
        d = _ccd_unit(d)
        portal.append(self._support(d))
        dt = _dot(portal[2].v, d)
        if _is_zero(dt) or dt < 0:
            return -1
        d = _ccd_unit(_cross(_sub(portal[1].v, portal[0].v), _sub(portal[2].v, portal[0].v)))
        if _dot(d, portal[0].v) > 0:
            portal[1], portal[2] = portal[2], portal[1]
            d = _scale(d, -1.0)
        while len(portal) < 4:
            s3 = self._support(d)
            dt = _dot(s3.v, d)
            if _is_zero(dt) or dt < 0:
                return -1
            dt = _dot(_cross(portal[1].v, s3.v), portal[0].v)
            if dt < 0 and not _is_zero(dt):
                portal[2] = s3
            else:
                dt = _dot(_cross(s3.v, portal[2].v), portal[0].v)
                if dt < 0 and not _is_zero(dt):
                    portal[1] = s3
                else:
                    portal.append(s3)
                    continue
            d = _ccd_unit(_cross(_sub(portal[1].v, portal[0].v), _sub(portal[2].v, portal[0].v)))
        return 0

    @staticmethod
    def _direction(portal: list[_Support]) -> Vec:
        return _ccd_unit(_cross(_sub(portal[2].v, portal[1].v), _sub(portal[3].v, portal[1].v)))

    def _reaches_tolerance(self, portal: list[_Support], v4: _Support, d: Vec) -> bool:
        dv4 = _dot(v4.v, d)
        gap = min(dv4 - _dot(portal[1].v, d), dv4 - _dot(portal[2].v, d))
        gap = min(gap, dv4 - _dot(portal[3].v, d))
        return _ccd_eq(gap, self.tolerance) or gap < self.tolerance

    @staticmethod
    def _expand(portal: list[_Support], v4: _Support) -> None:
        v4v0 = _cross(v4.v, portal[0].v)
        if _dot(portal[1].v, v4v0) > 0:
            portal[1 if _dot(portal[2].v, v4v0) > 0 else 3] = v4
        else:
            portal[2 if _dot(portal[3].v, v4v0) > 0 else 1] = v4

    def _refine(self, portal: list[_Support]) -> bool:
        """Whether the origin ends up inside the portal (the shapes intersect)."""
        while True:
            d = self._direction(portal)
            dt = _dot(d, portal[1].v)
            if _is_zero(dt) or dt > 0:
                return True
            v4 = self._support(d)
            dt = _dot(v4.v, d)
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
            pos = _scale(_add(portal[1].v1, portal[1].v2), 0.5)
            if found == 1:
                return 0.0, _ORIGIN, pos
            return _norm(portal[1].v), _ccd_unit(portal[1].v), pos
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
            _dot(_cross(v[1], v[2]), v[3]),
            _dot(_cross(v[3], v[2]), v[0]),
            _dot(_cross(v[0], v[1]), v[3]),
            _dot(_cross(v[2], v[1]), v[0]),
        ]
        total = b[0] + b[1] + b[2] + b[3]
        if _is_zero(total) or total < 0:
            d = self._direction(portal)
            b = [0.0, _dot(_cross(v[2], v[3]), d), _dot(_cross(v[3], v[1]), d)]
            b.append(_dot(_cross(v[1], v[2]), d))
            total = b[1] + b[2] + b[3]
        inv = 1.0 / total
        p1, p2 = _ORIGIN, _ORIGIN
        for i in range(4):
            p1 = _add(p1, _scale(portal[i].v1, b[i]))
            p2 = _add(p2, _scale(portal[i].v2, b[i]))
        return _scale(_add(_scale(p1, inv), _scale(p2, inv)), 0.5)


def _point_segment(x0: Vec, b: Vec) -> tuple[float, Vec]:
    """Squared distance from the origin to segment x0–b, and the nearest point."""
    d = _sub(b, x0)
    t = -1.0 * _dot(x0, d) / _dot(d, d)
    if t < 0 or _is_zero(t):
        w = x0
    elif t > 1 or _ccd_eq(t, 1.0):
        w = b
    else:
        w = _add(_scale(d, t), x0)
    return _dot(w, w), w


def _point_triangle(x0: Vec, b: Vec, c: Vec) -> tuple[float, Vec]:
    """Squared distance from the origin to triangle (x0, b, c), and the nearest point.

    T(s, t) = x0 + s·(b − x0) + t·(c − x0); the unconstrained minimiser when it
    lies in the triangle, else the nearest of the three edges.
    """
    d1, d2, a = _sub(b, x0), _sub(c, x0), x0
    v, w = _dot(d1, d1), _dot(d2, d2)
    p, q, r = _dot(a, d1), _dot(a, d2), _dot(d1, d2)
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
        witness = _add(_add(x0, _scale(d1, s)), _scale(d2, t))
        return _dot(witness, witness), witness
    best = _point_segment(x0, b)
    for candidate in (_point_segment(x0, c), _point_segment(b, c)):
        if candidate[0] < best[0]:
            best = candidate
    return best


# ============================================================ the geometries
class _Poses:
    """The world poses of all proximity geometries for one posing: X_WG rows, and their
    float views, made when a narrowphase call first asks."""

    __slots__ = ("R", "floats", "p", "stale")

    def __init__(self, R: Array, p: Array) -> None:
        self.R, self.p = R, p
        self.floats: list[_Pose | None] = [None] * len(p)
        # Slots whose FCL object still has an older rotation (see ProximityEngine.pose).
        self.stale: set[int] = set()


class _Body:
    """One proximity geometry as the engine holds it."""

    __slots__ = ("dynamic", "frame", "geometry", "id", "kind", "m", "obj", "poses", "slot", "value")

    def __init__(
        self, slot: int, geometry_id: GeometryId, info: _ShapeInfo, dynamic: bool, poses: _Poses
    ):
        self.slot, self.id, self.dynamic = slot, geometry_id, dynamic
        self.kind, self.m = info.name, info.measures
        self.value = geometry_id.get_value()
        self.geometry: Any = info.make()
        self.obj: Any = fcl.CollisionObject(self.geometry, fcl.Transform())
        self.poses = poses
        self.frame = -1

    def fcl_object(self) -> Any:
        """The FCL object, its rotation brought up to date for a narrowphase call."""
        if self.slot in self.poses.stale:
            self.obj.setRotation(self.poses.R[self.slot])
            self.poses.stale.discard(self.slot)
        return self.obj

    @property
    def pose(self) -> _Pose:
        """X_WG as floats."""
        pose = self.poses.floats[self.slot]
        if pose is None:
            R, p = self.poses.R[self.slot].tolist(), self.poses.p[self.slot].tolist()
            pose = _Pose((tuple(R[0]), tuple(R[1]), tuple(R[2])), tuple(p))
            self.poses.floats[self.slot] = pose
        return pose


class PairResult:
    """A narrowphase answer in Drake's labelling: A and B, a value, two points and a normal.

    For a penetration ``value`` is the depth and the rows of ``vectors`` are
    p_WCa, p_WCb, nhat_BA_W; for a signed distance, φ and p_ACa, p_BCb, nhat_BA_W.
    """

    __slots__ = ("id_A", "id_B", "value", "vectors")

    def __init__(self, id_A: GeometryId, id_B: GeometryId, value: float, vectors: Array):
        self.id_A, self.id_B, self.value, self.vectors = id_A, id_B, value, vectors

    @classmethod
    def of(
        cls, ids: tuple[GeometryId, GeometryId], value: float, points: tuple[Vec, Vec], nhat: Vec
    ) -> PairResult:
        return cls(ids[0], ids[1], value, np.array((points[0], points[1], nhat), dtype=float))

    def swapped(self) -> PairResult:
        """(A, B) → (B, A): the points trade places and ``nhat_AB_W = −nhat_BA_W``."""
        vectors = self.vectors[[1, 0, 2]]
        vectors[2] = -vectors[2]
        return PairResult(self.id_B, self.id_A, self.value, vectors)


_PENETRATION_UNSUPPORTED = (
    "Penetration queries between shapes '{}' and '{}' are not supported for scalar type double. "
    "See the documentation for QueryObject::ComputePointPairPenetration() for the full status "
    "of supported geometries."
)
_DISTANCE_UNSUPPORTED = (
    "Signed distance queries between shapes '{}' and '{}' are not supported for scalar type "
    "double. See the documentation for "
    "QueryObject::ComputeSignedDistancePairwiseClosestPoints() for the full status of "
    "supported geometries."
)

#: Sphere–X pairs Drake answers in closed form (X the other shape).
_CLOSED_FORM = frozenset({"Sphere", "Box", "Cylinder", "Capsule", "Halfspace"})
#: Penetration pairs FCL answers in closed form (no MPR, no tolerance).
_FCL_CLOSED = frozenset(
    {
        ("Box", "Box"),
        *((k, "Halfspace") for k in ("Box", "Capsule", "Cylinder", "Ellipsoid")),
        *(("Halfspace", k) for k in ("Box", "Capsule", "Cylinder", "Ellipsoid")),
    }
)
#: Boolean collision pairs FCL answers in closed form (with any HalfSpace pair).
_FCL_BOOLEAN = frozenset(
    frozenset(pair)
    for pair in (
        ("Sphere", "Sphere"),
        ("Sphere", "Box"),
        ("Sphere", "Capsule"),
        ("Sphere", "Cylinder"),
        ("Box", "Box"),
    )
)
#: Drake's gjk_tolerance for penetration and HasCollisions.
_GJK_TOLERANCE = 2e-12


def distance_supported(kind_A: str, kind_B: str) -> bool:
    """Signed distance: anything but a HalfSpace with a shape other than a Sphere."""
    return (kind_A != "Halfspace" or kind_B == "Sphere") and (
        kind_B != "Halfspace" or kind_A == "Sphere"
    )


def _penetration(a: _Body, b: _Body) -> PairResult | None:
    """A's and B's penetration (A's id lower), as Drake computes it; None if separated."""
    if a.kind == "Halfspace" and b.kind == "Halfspace":
        raise RuntimeError(_PENETRATION_UNSUPPORTED.format("Halfspace", "Halfspace"))
    a_sphere = a.kind == "Sphere"
    if (a_sphere or b.kind == "Sphere") and (b.kind if a_sphere else a.kind) in _CLOSED_FORM:
        s, o = (a, b) if a_sphere else (b, a)
        r = s.m[0]
        near = _distance_to_point(o.kind, o.m, o.pose, s.pose.p)
        depth = r - near.distance
        if depth < 0:
            return None
        result = PairResult.of(
            (s.id, o.id),
            depth,
            (_sub(s.pose.p, _scale(near.grad_W, r)), o.pose.apply(near.p_GN)),
            near.grad_W,
        )
        return result if a_sphere else result.swapped()
    contact = _contact(a, b)
    if contact is None or contact[0] <= _EPS:
        return None
    depth, normal, pos = contact
    nhat = _scale(normal, -1.0)
    result = PairResult.of(
        (a.id, b.id),
        depth,
        (_sub(pos, _scale(nhat, 0.5 * depth)), _add(pos, _scale(nhat, 0.5 * depth))),
        nhat,
    )
    # N.B. Drake's sphere–ellipsoid path re-labels FCL's (A, B) answer when A is
    # not the sphere, so the larger id ends up as id_A (measured on 1.51.1).
    return result.swapped() if b.kind == "Sphere" and not a_sphere else result


def _contact(a: _Body, b: _Body) -> tuple[float, Vec, Vec] | None:
    """FCL's single contact (depth, normal from A to B, position) for a non-closed-form pair."""
    if (a.kind, b.kind) in _FCL_CLOSED:
        result = fcl.CollisionResult()
        fcl.collide(
            a.fcl_object(),
            b.fcl_object(),
            fcl.CollisionRequest(num_max_contacts=1, enable_contact=True),
            result,
        )
        if not result.is_collision or not result.contacts:
            return None
        c = result.contacts[0]
        n, pos = c.normal, c.pos
        return (
            float(c.penetration_depth),
            (float(n[0]), float(n[1]), float(n[2])),
            (float(pos[0]), float(pos[1]), float(pos[2])),
        )
    mpr = _Mpr(_Convex(a.kind, a.m, a.pose), _Convex(b.kind, b.m, b.pose), _GJK_TOLERANCE)
    return mpr.penetration()


def _collides(a: _Body, b: _Body) -> bool:
    """FCL's boolean test at Drake's tolerance (HasCollisions): FCL's closed forms, and
    MPR at ``gjk_tolerance = 2e-12`` for the rest."""
    if frozenset((a.kind, b.kind)) in _FCL_BOOLEAN or "Halfspace" in (a.kind, b.kind):
        return bool(fcl.collide(a.fcl_object(), b.fcl_object(), fcl.CollisionRequest()) > 0)
    mpr = _Mpr(_Convex(a.kind, a.m, a.pose), _Convex(b.kind, b.m, b.pose), _GJK_TOLERANCE)
    return mpr.intersect()


def _signed_distance(a: _Body, b: _Body) -> PairResult:
    """φ(A, B) with witnesses (A's id lower), as Drake computes it."""
    a_sphere = a.kind == "Sphere"
    if (a_sphere or b.kind == "Sphere") and (b.kind if a_sphere else a.kind) in _CLOSED_FORM:
        s, o = (a, b) if a_sphere else (b, a)
        r = s.m[0]
        near = _distance_to_point(o.kind, o.m, o.pose, s.pose.p)
        result = PairResult.of(
            (s.id, o.id),
            near.distance - r,
            (_scale(_rot_t(s.pose.R, near.grad_W), -r), near.p_GN),
            near.grad_W,
        )
        return result if a_sphere else result.swapped()
    request = fcl.DistanceRequest(enable_nearest_points=True, enable_signed_distance=True)
    answer = fcl.DistanceResult()
    fcl.distance(a.fcl_object(), b.fcl_object(), request, answer)
    p_WCa = tuple(float(x) for x in answer.nearest_points[0])
    p_WCb = tuple(float(x) for x in answer.nearest_points[1])
    distance = float(answer.min_distance)
    p_ACa = a.pose.apply_inverse(p_WCa)  # type: ignore[arg-type]
    p_BCb = b.pose.apply_inverse(p_WCb)  # type: ignore[arg-type]
    if abs(distance) < 1e-14:
        nhat = _touching_gradient(a, b, p_ACa, p_BCb)
    else:
        diff = _sub(p_WCa, p_WCb)  # type: ignore[arg-type]
        nhat = (diff[0] / distance, diff[1] / distance, diff[2] / distance)
    return PairResult.of((a.id, b.id), distance, (p_ACa, p_BCb), nhat)


# ---------------------------------------------------- touching: Drake's rules
def _touching_gradient(a: _Body, b: _Body, p_ACa: Vec, p_BCb: Vec) -> Vec:
    """nhat_BA_W when φ ≈ 0: from a sphere's witness, Drake's box–box rules, else NaN."""
    if a.kind == "Sphere":
        return _rot(a.pose.R, _scale(_unit(p_ACa), -1.0))
    if b.kind == "Sphere":
        return _rot(b.pose.R, _unit(p_BCb))
    if a.kind == "Box" and b.kind == "Box":
        return _box_box_gradient(a, b, p_ACa, p_BCb)
    return _NAN


def _on_boundary(p: Vec, h: tuple[float, ...]) -> list[bool]:
    return [abs(h[i] - abs(p[i])) <= 1e-14 for i in range(3)]


def _box_box_gradient(a: _Body, b: _Body, p_ACa: Vec, p_BCb: Vec) -> Vec:
    """Two touching boxes: a face normal if a witness lies strictly inside a face, else a
    separating axis among the edge/vertex candidates (Drake's BoxBoxGradient)."""
    on_A, on_B = _on_boundary(p_ACa, a.m), _on_boundary(p_BCb, b.m)
    R_A, R_B = a.pose.R, b.pose.R
    if sum(on_A) == 1:
        i = on_A.index(True)
        return _scale(_col(R_A, i), -1.0 if p_ACa[i] > 0 else 1.0)
    if sum(on_B) == 1:
        i = on_B.index(True)
        return _scale(_col(R_B, i), 1.0 if p_BCb[i] > 0 else -1.0)
    axis_A = on_A.index(False) if sum(on_A) == 2 else -1
    axis_B = on_B.index(False) if sum(on_B) == 2 else -1
    A = [_col(R_A, i) for i in range(3)]
    B = [_col(R_B, i) for i in range(3)]
    candidates: list[Vec]
    if axis_A != -1 and axis_B != -1:
        cross = _cross(A[axis_A], B[axis_B])
        candidates = [cross] if _norm(cross) > 1e-14 else [A[(axis_A + 1) % 3], A[(axis_A + 2) % 3]]
    elif axis_A != -1 and all(on_B):
        candidates = [_cross(A[axis_A], B[i]) for i in range(3)]
    elif axis_B != -1 and all(on_A):
        candidates = [_cross(B[axis_B], A[i]) for i in range(3)]
    else:
        found = _separating(a, b, A + B)
        if found is not None:
            return found
        candidates = [_cross(A[i], B[j]) for i in range(3) for j in range(3)]
    found = _separating(a, b, candidates)
    return _NAN if found is None else found


def _projected(body: _Body, axis: Vec) -> tuple[float, float]:
    values = [
        _dot(axis, body.pose.apply((x, y, z)))
        for x in (body.m[0], -body.m[0])
        for y in (body.m[1], -body.m[1])
        for z in (body.m[2], -body.m[2])
    ]
    return min(values), max(values)


def _separating(a: _Body, b: _Body, candidates: list[Vec]) -> Vec | None:
    """The first candidate axis that separates A from B, pointing from B to A."""
    for v in candidates:
        if _norm(v) < 1e-14:
            continue
        axis = _unit(v)
        min_A, max_A = _projected(a, axis)
        min_B, max_B = _projected(b, axis)
        if max_A < min_B + 1e-14:
            return _scale(axis, -1.0)
        if max_B < min_A + 1e-14:
            return axis
    return None


# ================================================================== the poses
class PoseInput(NamedTuple):
    """A source's frames as its pose port must cover them."""

    source_id: SourceId
    name: str
    frames: tuple[FrameId, ...]
    #: The frames' id values, to recognise a FramePoseVector filled in the same order.
    values: tuple[int, ...]


class WorldPoses(NamedTuple):
    """X_WF of every frame (row = frame index) as rotations and translations."""

    R: Array
    p: Array


# ================================================================= the engine
Slot = int
_Met = tuple[Slot, Slot]


class ProximityEngine:
    """FCL objects for the proximity geometries of one GeometryState, and the queries.

    Built from plain data (the caller reads the state): every non-world frame
    with its parent, the sources with frames, and the proximity geometries with
    their frame, shape and X_FG. ``pose()`` takes each source's FramePoseVector;
    the queries then run on those poses until the next ``pose()``.
    """

    def __init__(
        self,
        frames: Sequence[tuple[FrameId, FrameId | None]],
        sources: Sequence[PoseInput],
        geometries: Sequence[tuple[GeometryId, FrameId | None, Shape, Array]],
    ) -> None:
        """``frames``: (frame, parent or None for the world), parents first.
        ``geometries``: (id, frame or None if anchored, shape, X_FG as a 4×4 matrix)."""
        self._frame_index = {f: i for i, (f, _) in enumerate(frames)}
        self._frames = [f for f, _ in frames]
        self._parent = [-1 if p is None else self._frame_index[p] for _, p in frames]
        self._nested = [i for i, p in enumerate(self._parent) if p >= 0]
        self._sources = list(sources)
        self._source_rows = [
            np.array([self._frame_index[f] for f in s.frames], dtype=np.intp) for s in sources
        ]
        self._bodies: list[_Body] = []
        self._slot_of: dict[GeometryId, Slot] = {}
        holder = _Poses(np.zeros((0, 3, 3)), np.zeros((0, 3)))
        frame_rows, X_FG = [], []
        for geometry_id, frame_id, shape, X in geometries:
            body = _Body(
                len(self._bodies), geometry_id, _shape_info(shape), frame_id is not None, holder
            )
            body.frame = -1 if frame_id is None else self._frame_index[frame_id]
            self._slot_of[geometry_id] = body.slot
            self._bodies.append(body)
            frame_rows.append(body.frame)
            X_FG.append(X)
        self._body_frame = np.array(frame_rows, dtype=np.intp)
        self._values = [body.value for body in self._bodies]
        X_FG_all = np.array(X_FG, dtype=float).reshape(-1, 4, 4)
        self._R_FG, self._p_FG = X_FG_all[:, :3, :3], X_FG_all[:, :3, 3]
        dynamic = self._body_frame >= 0
        identity = np.all(X_FG_all == np.eye(4), axis=(1, 2))
        self._on_frame_origin = np.flatnonzero(dynamic & identity)
        self._off_frame_origin = np.flatnonzero(dynamic & ~identity)
        self._R_WG = np.full_like(self._R_FG, np.nan)
        self._p_WG = np.full_like(self._p_FG, np.nan)
        holder.R, holder.p = self._R_WG, self._p_WG
        self._poses = holder
        self._objects = [body.obj for body in self._bodies]
        self._is_sphere = np.array([body.kind == "Sphere" for body in self._bodies], dtype=bool)
        # Whether each FCL object's rotation is the identity now (FCL starts them so).
        self._fcl_unrotated = np.ones(len(self._bodies), dtype=bool)
        self._has_dynamic_half_space = any(
            body.dynamic and body.kind == "Halfspace" for body in self._bodies
        )
        self._X_PF = np.tile(np.eye(4), (len(self._frames), 1, 1))
        self.world = WorldPoses(
            np.zeros((len(self._frames), 3, 3)), np.zeros((len(self._frames), 3))
        )
        self._pose_key: tuple[object, ...] | None = None
        self._dynamic = fcl.DynamicAABBTreeCollisionManager()
        self._anchored = fcl.DynamicAABBTreeCollisionManager()
        self._registered = False
        self._balanced = False
        self._by_translation: dict[bytes, Slot | list[Slot]] = {}
        self._clear_caches()

    # ------------------------------------------------------------- caches
    def _clear_caches(self) -> None:
        self._met: list[_Met] | None = None
        self._penetrations: dict[_Met, PairResult | None] = {}
        self._distances: dict[_Met, PairResult] = {}
        self._collisions: dict[_Met, bool] = {}
        self._visits: dict[float, list[_Met]] = {}

    def slot(self, geometry_id: GeometryId) -> Slot | None:
        return self._slot_of.get(geometry_id)

    def kind(self, slot: Slot) -> str:
        return self._bodies[slot].kind

    # -------------------------------------------------------------- poses
    @property
    def sources(self) -> list[PoseInput]:
        return self._sources

    def pose(self, key: tuple[object, ...], blocks: Callable[[], Sequence[Array]]) -> None:
        """Poses every frame and geometry from the sources' X_PF.

        ``key`` identifies the pose ports' contents (unchanged: nothing to do);
        ``blocks()`` gives each source's X_PF stacked in its frames' order.
        X_WF = X_WP · X_PF, parents first; X_WG = X_WF · X_FG; only the FCL
        objects whose X_WG changed move.
        """
        if key == self._pose_key:
            return
        X_PF = self._X_PF
        for rows, block in zip(self._source_rows, blocks(), strict=True):
            X_PF[rows] = block
        R_WF, p_WF = X_PF[:, :3, :3].copy(), X_PF[:, :3, 3].copy()
        for i in self._nested:
            parent = self._parent[i]
            R_WF[i], p_WF[i] = compose_poses(R_WF[parent], p_WF[parent], R_WF[i], p_WF[i])
        self.world = WorldPoses(R_WF, p_WF)
        R_WG, p_WG = self._R_FG.copy(), self._p_FG.copy()
        # X_FG = I: X_WG = X_WF, which Drake's product gives too (adding exact zeros).
        on_origin, offset = self._on_frame_origin, self._off_frame_origin
        R_WG[on_origin], p_WG[on_origin] = (
            R_WF[self._body_frame[on_origin]],
            p_WF[self._body_frame[on_origin]],
        )
        if len(offset):
            frame = self._body_frame[offset]
            R_WG[offset], p_WG[offset] = compose_poses(
                R_WF[frame], p_WF[frame], self._R_FG[offset], self._p_FG[offset]
            )
        moved = np.flatnonzero(
            ~(np.all(R_WG == self._R_WG, axis=(1, 2)) & np.all(p_WG == self._p_WG, axis=1))
        )
        # N.B. A sphere's AABB in FCL is a cube around its centre, of half-width r when its
        # rotation is the identity (Eigen's isIdentity, within 1e-12) and r·√3 otherwise;
        # so a sphere staying rotated (or unrotated) moves by its translation alone, its
        # rotation set later, if a narrowphase call reads it.
        identity = np.all(np.abs(R_WG - np.eye(3)) <= 1e-12, axis=(1, 2))
        is_moved = np.zeros(len(R_WG), dtype=bool)
        is_moved[moved] = True
        rotate = is_moved & (~self._is_sphere | (identity != self._fcl_unrotated))
        self._fcl_unrotated[rotate] = identity[rotate]
        rotated = np.flatnonzero(rotate).tolist()
        objects = self._objects
        for slot, R in zip(rotated, R_WG[rotate], strict=True):
            objects[slot].setRotation(R)
        for slot, p in zip(moved.tolist(), p_WG[moved], strict=True):
            objects[slot].setTranslation(p)
        poses = self._poses
        poses.R, poses.p, poses.floats = R_WG, p_WG, [None] * len(R_WG)
        poses.stale.update(np.flatnonzero(is_moved & ~rotate).tolist())
        poses.stale.difference_update(rotated)
        self._R_WG, self._p_WG = R_WG, p_WG
        self._pose_key = key
        if len(moved) or not self._registered:
            self._index_translations()
            self._refit_managers()
            self._clear_caches()

    def _refit_managers(self) -> None:
        """Refits the trees to the new poses (Drake's update); the first time, registers.

        N.B. A refit keeps the tree's topology; after poses move far, that tree
        overlaps itself everywhere (measured with python-fcl on 1000 spheres moved at
        random: collide 9.9 ms after a refit, 0.6 ms on a tree built at the poses, 0.5
        ms to build). A query that visits every overlapping pair rebuilds the tree
        first (``_balanced``); HasCollisions, which stops at the first, does not.
        """
        if not self._registered:
            for body in self._bodies:
                (self._dynamic if body.dynamic else self._anchored).registerObject(body.obj)
            self._anchored.update()
            self._registered = True
        self._dynamic.update()
        self._balanced = False

    def _balance(self) -> None:
        """Rebuilds the dynamic tree at the current poses, if a refit left it unbalanced.

        FCL's bulk build is used unless a dynamic HalfSpace is present (its infinite
        box crashes it); then sequential insertion in registration order meets two
        dynamic objects newest first, as pydrake 1.51.1 does (measured with a Box and
        a HalfSpace). The order among more is the tree's and differs from Drake's; it
        shows only in which of several unsupported pairs an error names.
        """
        if self._balanced:
            return
        self._dynamic = fcl.DynamicAABBTreeCollisionManager()
        dynamic = [body.obj for body in self._bodies if body.dynamic]
        if self._has_dynamic_half_space:
            for obj in dynamic:
                self._dynamic.registerObject(obj)
            self._dynamic.update()
        elif dynamic:
            self._dynamic.registerObjects(dynamic)  # FCL's balanced bulk build
            self._dynamic.setup()
        self._balanced = True

    def _index_translations(self) -> None:
        """translation bytes → slot (or the slots sharing that translation)."""
        rows = np.ascontiguousarray(self._p_WG).view(np.dtype((np.void, 24))).ravel()
        keys = cast("list[bytes]", rows.tolist())
        index: dict[bytes, Slot | list[Slot]] = dict(zip(keys, range(len(keys)), strict=True))
        if len(index) < len(keys):
            shared: dict[bytes, list[Slot]] = {}
            for slot, key in enumerate(keys):
                shared.setdefault(key, []).append(slot)
            index.update({k: v for k, v in shared.items() if len(v) > 1})
        self._by_translation = index

    def X_WF(self, frame_id: FrameId) -> tuple[Array, Array] | None:
        """(R_WF, p_WF) of a non-world frame, or None if the engine does not know it."""
        i = self._frame_index.get(frame_id)
        return None if i is None else (self.world.R[i], self.world.p[i])

    def X_PF(self, frame_id: FrameId) -> tuple[Array, Array] | None:
        """(R_PF, p_PF) as the frame's pose port gave it, or None."""
        i = self._frame_index.get(frame_id)
        return None if i is None else (self._X_PF[i, :3, :3], self._X_PF[i, :3, 3])

    def X_WG_arrays(self, slot: Slot) -> tuple[Array, Array]:
        """(R_WG, p_WG) of a proximity geometry."""
        return self._R_WG[slot], self._p_WG[slot]

    # ---------------------------------------------------- identification
    def _identify(self, obj: Any) -> Slot | tuple[Slot, ...]:
        """Which geometry (or group of identical ones) an FCL callback object is.

        python-fcl hands callbacks new wrappers; X_WG's translation names the
        geometry. Geometries with the same translation are told apart by
        rotation and shape, then by asking FCL (``distance`` reports the
        geometry object); fully identical ones (same shape, same X_WG) are
        interchangeable and come back as a group.
        """
        hit = self._by_translation[obj.getTranslation().tobytes()]
        if not isinstance(hit, list):
            return hit
        for slot in hit:
            self._bodies[slot].fcl_object()
        R = obj.getRotation().tobytes()
        node = obj.getNodeType()
        same = [
            s
            for s in hit
            if self._R_WG[s].tobytes() == R and self._bodies[s].obj.getNodeType() == node
        ]
        if len(same) == 1:
            return same[0]
        shapes = {(self._bodies[s].kind, self._bodies[s].m) for s in same}
        if len(shapes) == 1:
            return tuple(same)
        return self._identify_by_geometry(obj, same)

    def _identify_by_geometry(self, obj: Any, candidates: list[Slot]) -> Slot:
        """FCL's distance result names the python geometry object behind ``obj``."""
        probe = fcl.DistanceResult()
        fcl.distance(obj, obj, fcl.DistanceRequest(), probe)
        for slot in candidates:
            if self._bodies[slot].geometry is probe.o1:
                return slot
        raise AssertionError("an FCL object the engine does not hold")

    @staticmethod
    def _expand(a: Slot | tuple[Slot, ...], b: Slot | tuple[Slot, ...]) -> list[_Met]:
        if isinstance(a, int) and isinstance(b, int):
            return [(a, b)]
        group_a = (a,) if isinstance(a, int) else a
        group_b = (b,) if isinstance(b, int) else b
        if group_a == group_b:
            return [(x, y) for i, x in enumerate(group_a) for y in group_a[i + 1 :]]
        return [(x, y) for x in group_a for y in group_b if x != y]

    def _pair_callback(
        self, visit: Callable[[Slot, Slot], bool], failure: list[BaseException]
    ) -> Callable[[Any, Any], bool]:
        """An FCL callback body: names both objects, hands each pair to ``visit``, and
        returns whether to stop. Exceptions cannot cross FCL's C++: they stop the
        traversal and wait in ``failure``."""
        index = self._by_translation
        seen: set[_Met] = set()

        def on_pair(o1: Any, o2: Any) -> bool:
            try:
                hit_a = index[o1.getTranslation().tobytes()]
                hit_b = index[o2.getTranslation().tobytes()]
                if type(hit_a) is int and type(hit_b) is int:
                    return visit(hit_a, hit_b)
                a, b = self._identify(o1), self._identify(o2)
                pairs = [p for p in self._expand(a, b) if (min(p), max(p)) not in seen]
                seen.update((min(p), max(p)) for p in pairs)
                return any(visit(x, y) for x, y in pairs)
            except BaseException as error:
                failure.append(error)
                return True

        return on_pair

    def _traverse(self, visit: Callable[[Slot, Slot], bool]) -> None:
        """Every pair whose AABBs overlap, as FCL meets them (dynamic × dynamic, then
        dynamic × anchored), until ``visit`` returns True."""
        failure: list[BaseException] = []
        stopped = [False]
        on_pair = self._pair_callback(visit, failure)

        def callback(o1: Any, o2: Any, _data: Any) -> bool:
            stopped[0] = on_pair(o1, o2)
            return stopped[0]

        self._dynamic.collide(None, callback)
        if not stopped[0]:
            self._dynamic.collide(self._anchored, None, callback)
        if failure:
            raise failure[0]

    def met_pairs(self) -> list[_Met]:
        """Every pair of geometries whose AABBs overlap, in the order FCL meets them."""
        if self._met is None:
            met: list[_Met] = []

            def keep(a: Slot, b: Slot) -> bool:
                met.append((a, b))
                return False

            self._balance()
            self._traverse(keep)
            self._met = met
        return self._met

    def distance_pairs(self, max_distance: float) -> list[_Met]:
        """Pairs FCL's distance traversal visits when it prunes at ``max(max_distance, ε/10)``
        (Drake's callback keeps resetting the bound so), in the order it visits them."""
        prune = max(max_distance, _EPS / 10)
        if prune not in self._visits:
            visited: list[_Met] = []
            failure: list[BaseException] = []

            def keep(a: Slot, b: Slot) -> bool:
                visited.append((a, b))
                return False

            on_pair = self._pair_callback(keep, failure)

            def callback(o1: Any, o2: Any, _data: Any) -> tuple[bool, float]:
                return on_pair(o1, o2), prune

            self._balance()
            self._dynamic.distance(None, callback)
            if not failure:
                self._dynamic.distance(self._anchored, None, callback)
            if failure:
                raise failure[0]
            self._visits[prune] = visited
        return self._visits[prune]

    # ------------------------------------------------------------ queries
    def candidates(self, can_collide: Callable[[GeometryId, GeometryId], bool]) -> list[_Met]:
        """Met pairs the filter lets through."""
        bodies = self._bodies
        return [(a, b) for a, b in self.met_pairs() if can_collide(bodies[a].id, bodies[b].id)]

    def ordered(self, a: Slot, b: Slot) -> _Met:
        """(a, b) with the lower GeometryId first, as Drake's callbacks order a pair."""
        return (a, b) if self._bodies[a].value < self._bodies[b].value else (b, a)

    def penetrations(self, pairs: Sequence[_Met]) -> list[PairResult | None]:
        """Each pair's penetration (A the lower id), in order; raises at the first
        HalfSpace–HalfSpace pair. Sphere–sphere pairs are computed together."""
        v = self._values
        ordered = [(a, b) if v[a] < v[b] else (b, a) for a, b in pairs]
        memo = self._penetrations
        bodies = self._bodies
        spheres = [
            p
            for p in ordered
            if p not in memo and bodies[p[0]].kind == "Sphere" == bodies[p[1]].kind
        ]
        if spheres:
            memo.update(zip(spheres, self._sphere_sphere(spheres, penetration=True), strict=True))
        for pair in ordered:
            if pair not in memo:
                memo[pair] = _penetration(bodies[pair[0]], bodies[pair[1]])
        return [memo[p] for p in ordered]

    def collides(self, a: Slot, b: Slot) -> bool:
        pair = self.ordered(a, b)
        if pair not in self._collisions:
            self._collisions[pair] = _collides(self._bodies[pair[0]], self._bodies[pair[1]])
        return self._collisions[pair]

    def signed_distances(self, pairs: Sequence[_Met]) -> list[PairResult]:
        """φ of each pair (A the lower id), in order; raises Drake's message at the first
        unsupported pair, its shapes named in the order given. Sphere–sphere pairs are
        computed together."""
        bodies = self._bodies
        for a, b in pairs:
            if not distance_supported(bodies[a].kind, bodies[b].kind):
                raise RuntimeError(_DISTANCE_UNSUPPORTED.format(bodies[a].kind, bodies[b].kind))
        v = self._values
        ordered = [(a, b) if v[a] < v[b] else (b, a) for a, b in pairs]
        memo = self._distances
        spheres = [
            p
            for p in ordered
            if p not in memo and bodies[p[0]].kind == "Sphere" == bodies[p[1]].kind
        ]
        if spheres:
            found = self._sphere_sphere(spheres, penetration=False)
            memo.update(zip(spheres, found, strict=True))  # type: ignore[arg-type]
        for pair in ordered:
            if pair not in memo:
                memo[pair] = _signed_distance(bodies[pair[0]], bodies[pair[1]])
        return [memo[p] for p in ordered]

    def signed_distance(self, a: Slot, b: Slot) -> PairResult:
        """φ(a, b) (A the lower id); raises Drake's message, shapes named a then b."""
        return self.signed_distances([(a, b)])[0]

    def _sphere_sphere(self, pairs: list[_Met], *, penetration: bool) -> list[PairResult | None]:
        """Drake's sphere–sphere closed forms for many pairs at once, A the lower id.

        With Q = Ao and G = B: p_GQ = R_BWᵀ·p_WQ + R_BWᵀ·(−p_WB), ∇φ_G = p_GQ/|p_GQ|
        (+x within 1e-14·max(1, r_B) of the centre), N = r_B·∇φ_G,
        φ_B(Q) = (p_GQ − N)·∇φ_G, ∇φ_W = R_WB·∇φ_G. The same operations, in the
        same order, as the one-pair path (so the same bits).
        """
        a = np.array([p[0] for p in pairs])
        b = np.array([p[1] for p in pairs])
        r_A = np.array([self._bodies[i].m[0] for i in a])
        r_B = np.array([self._bodies[i].m[0] for i in b])
        R, pB, pA = self._R_WG[b], self._p_WG[b], self._p_WG[a]

        def rot_t(v: Array) -> list[Array]:
            return [
                R[:, 0, j] * v[:, 0] + R[:, 1, j] * v[:, 1] + R[:, 2, j] * v[:, 2] for j in range(3)
            ]

        q1, q2 = rot_t(pA), rot_t(pB * -1.0)
        q = np.stack([q1[j] + q2[j] for j in range(3)], axis=1)
        dist = np.sqrt(q[:, 0] * q[:, 0] + q[:, 1] * q[:, 1] + q[:, 2] * q[:, 2])
        inside = ~(dist > np.maximum(1.0, r_B) * 1e-14)
        with np.errstate(invalid="ignore", divide="ignore"):
            grad = q / dist[:, None]
        grad[inside] = (1.0, 0.0, 0.0)
        N = grad * r_B[:, None]
        d = q - N
        phi = d[:, 0] * grad[:, 0] + d[:, 1] * grad[:, 1] + d[:, 2] * grad[:, 2]
        grad_W = np.stack(
            [
                R[:, i, 0] * grad[:, 0] + R[:, i, 1] * grad[:, 1] + R[:, i, 2] * grad[:, 2]
                for i in range(3)
            ],
            axis=1,
        )
        ids = [(self._bodies[i].id, self._bodies[j].id) for i, j in pairs]
        if penetration:
            depth = r_A - phi
            p_WCa = pA - grad_W * r_A[:, None]
            RN = np.stack(
                [
                    R[:, i, 0] * N[:, 0] + R[:, i, 1] * N[:, 1] + R[:, i, 2] * N[:, 2]
                    for i in range(3)
                ],
                axis=1,
            )
            vectors = np.stack([p_WCa, RN + pB, grad_W], axis=1)
            values = depth.tolist()
            return [
                None if value < 0 else PairResult(id_A, id_B, value, vectors[k])
                for k, ((id_A, id_B), value) in enumerate(zip(ids, values, strict=True))
            ]
        RA = self._R_WG[a]
        p_ACa = np.stack(
            [
                (
                    RA[:, 0, j] * grad_W[:, 0]
                    + RA[:, 1, j] * grad_W[:, 1]
                    + RA[:, 2, j] * grad_W[:, 2]
                )
                * -r_A
                for j in range(3)
            ],
            axis=1,
        )
        vectors = np.stack([p_ACa, N, grad_W], axis=1)
        values = (phi - r_A).tolist()
        return [
            PairResult(id_A, id_B, value, vectors[k])
            for k, ((id_A, id_B), value) in enumerate(zip(ids, values, strict=True))
        ]

    def has_collisions(self, can_collide: Callable[[GeometryId, GeometryId], bool]) -> bool:
        """Whether any unfiltered pair collides; stops at the first that does."""
        bodies = self._bodies
        if self._met is not None:
            return any(
                can_collide(bodies[a].id, bodies[b].id) and self.collides(a, b)
                for a, b in self._met
            )
        found = [False]

        def check(a: Slot, b: Slot) -> bool:
            if can_collide(bodies[a].id, bodies[b].id) and self.collides(a, b):
                found[0] = True
            return found[0]

        self._traverse(check)
        return found[0]

    def body_id(self, slot: Slot) -> GeometryId:
        return self._bodies[slot].id
