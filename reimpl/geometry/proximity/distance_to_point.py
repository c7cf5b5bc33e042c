"""The signed distance from a point to a shape: Drake's DistanceToPoint, closed forms.

Drake counterpart: drake/geometry/proximity/distance_to_point_callback.h. For a
point Q and a shape G posed at X_WG, with ``p_GQ = X_WG⁻¹ · p_WQ``: the signed
distance φ_G(Q), the nearest point N on G's surface (in G's frame) and the
gradient ∇φ_G (in the world frame), each shape's formula in Drake's order:

* Sphere of radius r: ∇φ = p_GQ / |p_GQ| (+x within 1e-14·max(1, r) of the
  centre), N = r·∇φ, φ = (p_GQ − p_GN)·∇φ;
* HalfSpace {z ≤ 0}: φ = z, N = (x, y, 0), ∇φ = R_WG·ẑ;
* Capsule: the sphere of the nearer end cap when |z| ≥ h, else the sphere
  through Q's projection on the z = 0 plane, shifted back by z;
* Box [−h, h]: per coordinate inside, on the boundary (within the tolerance) or
  outside; outside, N clamps Q and ∇φ = (Q − N)/|Q − N|; on the boundary, ∇φ
  is the normalised sum of the touched faces' normals; inside, N is Q pushed to
  the nearest face and ∇φ its normal; φ = ∇φ·(p_WQ − p_WN);
* Cylinder: the 2D box [−r, r]×[−h, h] in the (ρ, z) plane through Q and the axis.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

from reimpl.geometry.proximity.transforms import Pose, Vec, add, dot, norm, rot, scale, sub

__all__ = ["PointDistance", "distance_to_point"]


class PointDistance(NamedTuple):
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
    dist = norm(p_SQ)
    grad = (
        (p_SQ[0] / dist, p_SQ[1] / dist, p_SQ[2] / dist)
        if dist > _tolerance(radius)
        else (
            1.0,
            0.0,
            0.0,
        )
    )
    p_SN = scale(grad, radius)
    return p_SN, dot(sub(p_SQ, p_SN), grad), grad


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


def distance_to_point(kind: str, m: tuple[float, ...], X_WG: Pose, p_WQ: Vec) -> PointDistance:
    """Drake's DistanceToPoint for a sphere, box, cylinder, capsule or half space G."""
    p_GQ = X_WG.apply_inverse(p_WQ)
    if kind == "Sphere":
        p_GN, distance, grad_G = _sphere_in_frame(m[0], p_GQ)
        return PointDistance(p_GN, distance, rot(X_WG.R, grad_G))
    if kind == "Halfspace":
        # φ = z in the half space's frame; N = (x, y, 0); ∇φ = R_WG · +z.
        return PointDistance((p_GQ[0], p_GQ[1], 0.0), p_GQ[2], rot(X_WG.R, (0.0, 0.0, 1.0)))
    if kind == "Capsule":
        radius, half = m
        if p_GQ[2] >= half or p_GQ[2] <= -half:
            # Nearest an end cap: the sphere of that cap.
            p_GS = (0.0, 0.0, half if p_GQ[2] >= half else -half)
            p_SN, distance, grad_G = _sphere_in_frame(radius, sub(p_GQ, p_GS))
            return PointDistance(add(p_GS, p_SN), distance, rot(X_WG.R, grad_G))
        # Nearest the spine: Q's projection R on the z = 0 plane, to the centre sphere.
        p_GM, distance, grad_G = _sphere_in_frame(radius, (p_GQ[0], p_GQ[1], 0.0))
        return PointDistance((p_GM[0], p_GM[1], p_GQ[2]), distance, rot(X_WG.R, grad_G))
    if kind == "Box":
        p_GN_list, grad_list = _box_in_frame(m, p_GQ)
        p_GN = (p_GN_list[0], p_GN_list[1], p_GN_list[2])
        grad_W = rot(X_WG.R, (grad_list[0], grad_list[1], grad_list[2]))
        return PointDistance(p_GN, dot(grad_W, sub(p_WQ, X_WG.apply(p_GN))), grad_W)
    if kind == "Cylinder":
        # The 2D box [−r, r]×[−h, h] of the cross section through Q and the axis,
        # in (ρ, z) with ρ along v = (x, y)/|(x, y)| (+x when Q is on the axis).
        radius, half = m
        r_Q = math.sqrt(p_GQ[0] * p_GQ[0] + p_GQ[1] * p_GQ[1])
        v = (1.0, 0.0) if r_Q < _tolerance(radius) else (p_GQ[0] / r_Q, p_GQ[1] / r_Q)
        p_BN, grad_B = _box_in_frame((radius, half), (r_Q, p_GQ[2]))
        p_GN = (p_BN[0] * v[0], p_BN[0] * v[1], p_BN[1])
        grad_W = rot(X_WG.R, (grad_B[0] * v[0], grad_B[0] * v[1], grad_B[1]))
        return PointDistance(p_GN, dot(grad_W, sub(p_WQ, X_WG.apply(p_GN))), grad_W)
    raise AssertionError(kind)
