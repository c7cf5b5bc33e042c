"""The signed-distance gradient of two touching shapes: Drake's rules for φ ≈ 0.

Drake counterpart: drake/geometry/proximity/distance_to_shape_touching.cc
(CalcGradientWhenTouching, BoxBoxGradient). When |φ| < 1e-14 the witnesses
coincide and ``(p_WCa − p_WCb) / φ`` means nothing; nhat_BA_W (the unit
direction in which φ grows fastest, from B to A) comes instead from:

* a sphere A: ``nhat_BA_W = −R_WA · unit(p_ACa)``; a sphere B:
  ``nhat_BA_W = R_WB · unit(p_BCb)``;
* two boxes: if a witness lies on exactly one face (``|h_i − |p_i|| ≤ 1e-14`` for
  one i), that face's normal from B to A: ``−s·R_WA·êᵢ`` on A's face (s the sign
  of ``p_ACa,i``), ``s·R_WB·êᵢ`` on B's (s the sign of ``p_BCb,i``); else the first
  candidate axis v that separates them (the corners' projections on
  ``unit(v)`` overlapping by less than 1e-14), pointing from B to A: edge ×
  edge (or A's other two axes when the edges are parallel), A's edge × B's
  axes, B's edge × A's axes, or else A's and B's axes, then their nine cross
  products;
* anything else: NaN.
"""

from __future__ import annotations

import math
from typing import Protocol

from reimpl.geometry.proximity.transforms import Pose, Vec, col, cross, dot, norm, rot, scale, unit

__all__ = ["PosedShape", "touching_gradient"]

_NAN = (math.nan, math.nan, math.nan)


class PosedShape(Protocol):
    """A posed shape as these rules read it: FCL's name for its kind, its measures
    (a box's half sizes) and X_WG."""

    @property
    def kind(self) -> str: ...

    @property
    def m(self) -> tuple[float, ...]: ...

    @property
    def pose(self) -> Pose: ...


def touching_gradient(a: PosedShape, b: PosedShape, p_ACa: Vec, p_BCb: Vec) -> Vec:
    """nhat_BA_W when φ ≈ 0: from a sphere's witness, Drake's box–box rules, else NaN."""
    if a.kind == "Sphere":
        return rot(a.pose.R, scale(unit(p_ACa), -1.0))
    if b.kind == "Sphere":
        return rot(b.pose.R, unit(p_BCb))
    if a.kind == "Box" and b.kind == "Box":
        return _box_box_gradient(a, b, p_ACa, p_BCb)
    return _NAN


def _on_boundary(p: Vec, h: tuple[float, ...]) -> list[bool]:
    return [abs(h[i] - abs(p[i])) <= 1e-14 for i in range(3)]


def _box_box_gradient(a: PosedShape, b: PosedShape, p_ACa: Vec, p_BCb: Vec) -> Vec:
    """Two touching boxes: a face normal if a witness lies strictly inside a face, else a
    separating axis among the edge/vertex candidates (Drake's BoxBoxGradient)."""
    on_A, on_B = _on_boundary(p_ACa, a.m), _on_boundary(p_BCb, b.m)
    R_A, R_B = a.pose.R, b.pose.R
    if sum(on_A) == 1:
        i = on_A.index(True)
        return scale(col(R_A, i), -1.0 if p_ACa[i] > 0 else 1.0)
    if sum(on_B) == 1:
        i = on_B.index(True)
        return scale(col(R_B, i), 1.0 if p_BCb[i] > 0 else -1.0)
    axis_A = on_A.index(False) if sum(on_A) == 2 else -1
    axis_B = on_B.index(False) if sum(on_B) == 2 else -1
    A = [col(R_A, i) for i in range(3)]
    B = [col(R_B, i) for i in range(3)]
    candidates: list[Vec]
    if axis_A != -1 and axis_B != -1:
        edges_normal = cross(A[axis_A], B[axis_B])
        candidates = (
            [edges_normal]
            if norm(edges_normal) > 1e-14
            else [A[(axis_A + 1) % 3], A[(axis_A + 2) % 3]]
        )
    elif axis_A != -1 and all(on_B):
        candidates = [cross(A[axis_A], B[i]) for i in range(3)]
    elif axis_B != -1 and all(on_A):
        candidates = [cross(B[axis_B], A[i]) for i in range(3)]
    else:
        found = _separating(a, b, A + B)
        if found is not None:
            return found
        candidates = [cross(A[i], B[j]) for i in range(3) for j in range(3)]
    found = _separating(a, b, candidates)
    return _NAN if found is None else found


def _projected(body: PosedShape, axis: Vec) -> tuple[float, float]:
    values = [
        dot(axis, body.pose.apply((x, y, z)))
        for x in (body.m[0], -body.m[0])
        for y in (body.m[1], -body.m[1])
        for z in (body.m[2], -body.m[2])
    ]
    return min(values), max(values)


def _separating(a: PosedShape, b: PosedShape, candidates: list[Vec]) -> Vec | None:
    """The first candidate axis that separates A from B, pointing from B to A."""
    for v in candidates:
        if norm(v) < 1e-14:
            continue
        axis = unit(v)
        min_A, max_A = _projected(a, axis)
        min_B, max_B = _projected(b, axis)
        if max_A < min_B + 1e-14:
            return scale(axis, -1.0)
        if max_B < min_A + 1e-14:
            return axis
    return None
