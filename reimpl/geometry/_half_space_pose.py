"""HalfSpace::MakePose (drake/geometry/shape_specification.cc), step for step.

Given a direction ``Hz_dir_F`` and a point ``p_FB`` on the boundary plane:

1. ``norm = |Hz_dir_F|``; DRAKE_THROW_UNLESS(norm >= 1e-10), so NaN fails too
   (see _shape_checks).
2. The axis ``e_i`` of the smallest ``|Hz_dir_F(i)|`` (first one on ties) is the
   most perpendicular to the normal.
3. ``Hz = Hz_dir_F / norm``, ``Hx = normalized(Hz × e_i)``, ``Hy = Hz × Hx``;
   ``R_FH = [Hx Hy Hz]`` (columns).
4. ``p_FH = (Hz · p_FB) Hz``: the boundary point nearest F's origin.

Each operation is Eigen's, in Eigen's order (sums left to right, division by
the norm rather than multiplication by its reciprocal, ``normalized()`` leaving
a zero or NaN vector unchanged), so the result matches pydrake 1.51.1 and 1.58.0
bit for bit, signed zeros included (checked on 380 normals, random and axial).

It is not RotationMatrix::MakeFromOneUnitVector(Hz, 2) (pydrake binds it as
MakeFromOneVector): that picks the same axis but builds Hx = e_i × Hz, so its
Hx and Hy are the negatives of MakePose's (a half turn about Hz). For the
normal +x, MakePose's Hx is +z and MakeFromOneVector's is -z (measured).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from reimpl.geometry._shape_checks import require

__all__ = ["make_pose_columns"]

Vector = tuple[float, float, float]


def _dot(a: Sequence[float], b: Sequence[float]) -> float:
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]


def _cross(a: Sequence[float], b: Sequence[float]) -> Vector:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _normalized(v: Vector) -> Vector:
    squared = _dot(v, v)
    if not squared > 0:
        return v
    norm = math.sqrt(squared)
    return (v[0] / norm, v[1] / norm, v[2] / norm)


def _most_perpendicular_axis(direction: Sequence[float]) -> Vector:
    magnitudes = [abs(x) for x in direction]
    smallest = 0
    for i in (1, 2):
        if magnitudes[i] < magnitudes[smallest]:
            smallest = i
    axis = [0.0, 0.0, 0.0]
    axis[smallest] = 1.0
    return (axis[0], axis[1], axis[2])


def make_pose_columns(
    Hz_dir_F: Sequence[float], p_FB: Sequence[float]
) -> tuple[tuple[Vector, Vector, Vector], Vector]:
    """``((Hx, Hy, Hz), p_FH)``: the columns of R_FH and the translation of X_FH."""
    norm = math.sqrt(_dot(Hz_dir_F, Hz_dir_F))
    require("MakePose", "norm", norm)
    Hz: Vector = (Hz_dir_F[0] / norm, Hz_dir_F[1] / norm, Hz_dir_F[2] / norm)
    Hx = _normalized(_cross(Hz, _most_perpendicular_axis(Hz_dir_F)))
    Hy = _cross(Hz, Hx)
    distance = _dot(Hz, p_FB)
    p_FH: Vector = (distance * Hz[0], distance * Hz[1], distance * Hz[2])
    return (Hx, Hy, Hz), p_FH
