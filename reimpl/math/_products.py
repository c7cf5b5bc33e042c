"""Drake's 3×3 rotation times 3-vectors, to the bit (measured on pydrake 1.51.1 and 1.58.0).

``RotationMatrix.multiply(v_B)`` and ``RigidTransform.multiply(p_BoQ_B)`` evaluate
each row of R·v as Eigen's vectorised product does: rows 0 and 1 (one packet of
two rows) as ``(R₀₀·v₀ + R₀₁·v₁) + R₀₂·v₂``, row 2 as ``(R₂₁·v₁ + R₂₂·v₂) + R₂₀·v₀``.
Measured: 0 of 5000 random rotations times random 3-vectors and 3×n blocks
differ from this on 1.51.1 and on 1.58.0, while numpy's ``R @ v`` differs in
about 30% of them (row 2). A rotation times a rotation is numpy's product
(0 of 5000 differ). A 4-vector (x, y, z, w) is a point for w = 1 (R·v + p) and
a direction for w = 0 (R·v, nothing added), any other w is Drake's error.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

__all__ = ["homogeneous", "rotate"]

Array = npt.NDArray[np.float64]


def rotate(R: Array, v: Array) -> Array:
    """R·v for a 3-vector or a 3×n block ``v``, summed in Eigen's order (module doc)."""
    return np.stack(
        [
            (R[0, 0] * v[0] + R[0, 1] * v[1]) + R[0, 2] * v[2],
            (R[1, 0] * v[0] + R[1, 1] * v[1]) + R[1, 2] * v[2],
            (R[2, 1] * v[1] + R[2, 2] * v[2]) + R[2, 0] * v[0],
        ]
    )


def _shortest(value: float) -> str:
    """fmt's ``{}`` of a double: round-trip digits without a trailing ``.0``."""
    text = "nan" if math.isnan(value) else repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def homogeneous(R: Array, p: Array, vec: Array) -> Array:
    """X·vec for X = (R, p) and a 4-vector (or 4×1) ``vec`` whose last element is 0 or 1."""
    w = float(vec[3].item() if vec.ndim == 2 else vec[3])
    if w not in (0.0, 1.0):
        listed = ", ".join(_shortest(float(x)) for x in vec.ravel())
        raise RuntimeError(
            f"The 4th element in vector [{listed}] passed to RigidTransform::operator* "
            "is not 0 or 1."
        )
    moved = rotate(R, vec[:3])
    if w == 1.0:
        moved = moved + (p if vec.ndim == 1 else p[:, None])
    return np.concatenate([moved, vec[3:]])
