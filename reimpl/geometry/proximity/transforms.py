"""3-vectors, rotations and rigid transforms as floats, rounded as Drake's Eigen rounds them.

One concept: the arithmetic the narrowphase and the posing share. A 3-vector is
a tuple of floats (cheaper than a numpy array at this size); sums run left to
right, as Eigen evaluates 3-vectors and 3×3 products:

* ``a·b = a₀b₀ + a₁b₁ + a₂b₂``, ``a × b``, ``|a| = √(a·a)``,
  ``unit(a) = a / |a|`` (unchanged when ``|a| = 0``, as Eigen's ``normalized()``);
* ``R·v`` (rows), ``Rᵀ·v`` (columns), ``X_WG · p_G = R·p_G + p`` and
  ``X_WG⁻¹ · p_W = Rᵀ·p_W + Rᵀ·(−p)`` (Drake's ``X.inverse() * p``);
* for stacked poses, ``X₁·X₂ = (R₁·R₂, R₁·p₂ + p₁)`` with each entry a chain of
  fused multiply-adds, ``fma(a₂, b₂, fma(a₁, b₁, a₀·b₀))``, emulated with
  error-free TwoProduct/TwoSum (``compose_poses``).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

__all__ = [
    "EPS",
    "Array",
    "Mat",
    "Pose",
    "Vec",
    "add",
    "col",
    "compose_poses",
    "cross",
    "dot",
    "norm",
    "rot",
    "rot_t",
    "scale",
    "sub",
    "unit",
]

Vec = tuple[float, float, float]
Mat = tuple[Vec, Vec, Vec]
Array = npt.NDArray[np.float64]

#: Machine epsilon, libccd's CCD_EPS and Drake's ε.
EPS = 2.220446049250313e-16


# ============================================================== vector algebra
# Tuples of floats: a 3-vector costs less than a numpy array at this size.
# Sums run left to right, as Eigen evaluates 3-vectors and 3×3 products.
def add(a: Vec, b: Vec) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a: Vec, k: float) -> Vec:
    return (a[0] * k, a[1] * k, a[2] * k)


def dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a: Vec) -> float:
    return math.sqrt(dot(a, a))


def unit(a: Vec) -> Vec:
    """``a / |a|`` (Eigen's ``normalized()``: unchanged when ``|a| = 0``)."""
    n = norm(a)
    return a if n == 0 else (a[0] / n, a[1] / n, a[2] / n)


def rot(R: Mat, v: Vec) -> Vec:
    """R · v."""
    return (dot(R[0], v), dot(R[1], v), dot(R[2], v))


def rot_t(R: Mat, v: Vec) -> Vec:
    """Rᵀ · v."""
    return (
        R[0][0] * v[0] + R[1][0] * v[1] + R[2][0] * v[2],
        R[0][1] * v[0] + R[1][1] * v[1] + R[2][1] * v[2],
        R[0][2] * v[0] + R[1][2] * v[1] + R[2][2] * v[2],
    )


def col(R: Mat, i: int) -> Vec:
    return (R[0][i], R[1][i], R[2][i])


class Pose(NamedTuple):
    """X_WG as plain floats: rotation rows and translation."""

    R: Mat
    p: Vec

    def apply(self, v: Vec) -> Vec:
        """X_WG · p_G = R · p_G + p."""
        return add(rot(self.R, v), self.p)

    def apply_inverse(self, v: Vec) -> Vec:
        """X_WG⁻¹ · p_W = Rᵀ · p_W + Rᵀ · (−p), as Drake's ``X.inverse() * p``."""
        return add(rot_t(self.R, v), rot_t(self.R, scale(self.p, -1.0)))


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
