"""Rigid transforms, enough to pose geometry (drake/math/rigid_transform.h).

Collision filtering never reads a pose; these types exist so that a pydrake
script that builds poses runs unchanged. They hold numpy arrays and print as
pydrake prints them.
"""

from __future__ import annotations

from typing import Any, overload

import numpy as np
import numpy.typing as npt

from reimpl._overload import Overload, Param, any_of, dispatch, instance_of
from reimpl._template import scalar_template
from reimpl.common.value import register_value_type
from reimpl.math._products import homogeneous, rotate

__all__ = [
    "RigidTransform",
    "RigidTransform_",
    "RollPitchYaw",
    "RollPitchYaw_",
    "RotationMatrix",
    "RotationMatrix_",
]

Vector3 = npt.NDArray[np.float64]

#: Drake's RotationMatrix orthonormality tolerance, 128 ε (the IsNearlyIdentity default).
_ORTHONORMALITY_TOLERANCE = 128 * np.finfo(float).eps


def _is_vector3(value: object) -> bool:
    try:
        return np.asarray(value, dtype=float).shape in {(3,), (3, 1)}
    except (TypeError, ValueError):
        return False


def _is_matrix(shape: tuple[int, ...]) -> Any:
    def check(value: object) -> bool:
        try:
            return np.asarray(value, dtype=float).shape == shape
        except (TypeError, ValueError):
            return False

    check.__name__ = f"numpy.ndarray[{shape}]"
    return check


_is_vector3.__name__ = "numpy.ndarray[3]"


def _rows(matrix: npt.NDArray[np.float64], indent: str) -> str:
    lines = [f"{indent}  [{', '.join(repr(float(x)) for x in row)}]," for row in matrix]
    return "\n".join(lines)


class RollPitchYaw:
    """Space-fixed X-Y-Z angles [r, p, y]."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._rpy = np.zeros(3)

        def set_angles(roll: float, pitch: float, yaw: float) -> None:
            self._rpy = np.array([roll, pitch, yaw], dtype=float)

        def set_vector(rpy: Vector3) -> None:
            self._rpy = np.asarray(rpy, dtype=float).reshape(3)

        number = instance_of(int, float)
        dispatch(
            "reimpl.math.RollPitchYaw",
            "__init__",
            (
                Overload((Param("rpy", _is_vector3),), set_vector),
                Overload(
                    (Param("roll", number), Param("pitch", number), Param("yaw", number)),
                    set_angles,
                ),
            ),
            args,
            kwargs,
        )

    def vector(self) -> Vector3:
        return self._rpy.copy()

    def roll_angle(self) -> float:
        return float(self._rpy[0])

    def pitch_angle(self) -> float:
        return float(self._rpy[1])

    def yaw_angle(self) -> float:
        return float(self._rpy[2])

    def ToRotationMatrix(self) -> RotationMatrix:
        """R = Rz(y) · Ry(p) · Rx(r), entry by entry as Drake writes it (c₀ = cos r, s₁ = sin p, …).

        N.B. Bit-equal to pydrake 1.51.1 on 1000 random angles (multiplying the three
        elementary rotations differed in the last bit for 65% of them); near-touching
        proximity queries amplify such bits.
        """
        r, p, y = (float(a) for a in self._rpy)
        c0, c1, c2 = np.cos(r), np.cos(p), np.cos(y)
        s0, s1, s2 = np.sin(r), np.sin(p), np.sin(y)
        c2_s1, s2_s1 = c2 * s1, s2 * s1
        return RotationMatrix(
            np.array(
                [
                    [c2 * c1, c2_s1 * s0 - s2 * c0, c2_s1 * c0 + s2 * s0],
                    [s2 * c1, s2_s1 * s0 + c2 * c0, s2_s1 * c0 - c2 * s0],
                    [-s1, c1 * s0, c1 * c0],
                ]
            )
        )


class RotationMatrix:
    """An orthonormal 3×3 rotation R_AB."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._R = np.eye(3)
        dispatch(
            "reimpl.math.RotationMatrix", "__init__", _ROTATION_INIT, args, kwargs, receiver=self
        )

    def _copy_from(self, other: RotationMatrix) -> None:
        self._R = other._R.copy()

    def _from_matrix(self, R: npt.NDArray[np.float64]) -> None:
        self._R = np.asarray(R, dtype=float).copy()

    def _from_rpy(self, rpy: RollPitchYaw) -> None:
        self._R = rpy.ToRotationMatrix()._R

    @staticmethod
    def _about(axis: int, theta: float) -> RotationMatrix:
        c, s = np.cos(theta), np.sin(theta)
        i, j = [k for k in range(3) if k != axis]
        R = np.eye(3)
        R[i, i], R[i, j], R[j, i], R[j, j] = c, -s, s, c
        if axis == 1:  # y: z × x ordering flips the sign of the sines.
            R[i, j], R[j, i] = s, -s
        return RotationMatrix(R)

    @staticmethod
    def Identity() -> RotationMatrix:
        return RotationMatrix()

    @staticmethod
    def MakeXRotation(theta: float) -> RotationMatrix:
        return RotationMatrix._about(0, theta)

    @staticmethod
    def MakeYRotation(theta: float) -> RotationMatrix:
        return RotationMatrix._about(1, theta)

    @staticmethod
    def MakeZRotation(theta: float) -> RotationMatrix:
        return RotationMatrix._about(2, theta)

    def matrix(self) -> npt.NDArray[np.float64]:
        return self._R.copy()

    def row(self, index: int) -> Vector3:
        """Row ``index`` (pydrake 1.51.1 reads out of bounds unchecked; reimpl raises)."""
        return np.array(self._R[index])

    def col(self, index: int) -> Vector3:
        return np.array(self._R[:, index])

    def inverse(self) -> RotationMatrix:
        return RotationMatrix(self._R.T)

    def transpose(self) -> RotationMatrix:
        return RotationMatrix(self._R.T)

    def InvertAndCompose(self, other: RotationMatrix) -> RotationMatrix:
        """R_BC = R_ABᵀ · R_AC."""
        return RotationMatrix(self._R.T @ other._R)

    def IsExactlyIdentity(self) -> bool:
        return bool(np.array_equal(self._R, np.eye(3)))

    def IsNearlyIdentity(self, tolerance: float = _ORTHONORMALITY_TOLERANCE) -> bool:
        """max |R − I| ≤ tolerance (default 128 ε, Drake's orthonormality tolerance)."""
        return bool(np.abs(self._R - np.eye(3)).max() <= tolerance)

    @overload
    def multiply(self, other: RotationMatrix) -> RotationMatrix: ...
    @overload
    def multiply(self, *args: Any, **kwargs: Any) -> Any: ...

    def multiply(self, *args: Any, **kwargs: Any) -> Any:
        """R_AB·R_BC, or R_AB·v_B for a 3-vector or a 3×n block (``_products.rotate``)."""
        return dispatch(
            "reimpl.math.RotationMatrix", "multiply", _ROTATION_MULTIPLY, args, kwargs,
            receiver=self,
        )  # fmt: skip

    @overload
    def __matmul__(self, other: RotationMatrix) -> RotationMatrix: ...
    @overload
    def __matmul__(self, other: Any) -> Any: ...

    def __matmul__(self, other: Any) -> Any:
        if type(other) is RotationMatrix:  # the common case, without dispatch
            return self._compose(other)
        return self.multiply(other)

    def _compose(self, other: RotationMatrix) -> RotationMatrix:
        return RotationMatrix(self._R @ other._R)

    def _rotate(self, v_B: Any) -> npt.NDArray[np.float64]:
        return rotate(self._R, np.asarray(v_B, dtype=float))

    def __repr__(self) -> str:
        return f"RotationMatrix([\n{_rows(self._R, '')}\n])"


class RigidTransform:
    """A pose X_AB = (R_AB, p_AoBo_A)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._R = RotationMatrix()
        self._p = np.zeros(3)
        dispatch(
            "reimpl.math.RigidTransform", "__init__", _TRANSFORM_INIT, args, kwargs, receiver=self
        )

    def _set_pose(self, R: RotationMatrix | None = None, p: Vector3 | None = None) -> None:
        if R is not None:
            self._R = RotationMatrix(R)
        if p is not None:
            self._p = np.asarray(p, dtype=float).reshape(3).copy()

    def _copy_from(self, other: RigidTransform) -> None:
        self._set_pose(other._R, other._p)

    def _from_rpy(self, rpy: RollPitchYaw, p: Vector3) -> None:
        self._set_pose(rpy.ToRotationMatrix(), p)

    def _from_matrix(self, pose: npt.NDArray[np.float64]) -> None:
        m = np.asarray(pose, dtype=float)
        self._set_pose(RotationMatrix(m[:3, :3]), m[:3, 3])

    @staticmethod
    def Identity() -> RigidTransform:
        return RigidTransform()

    def rotation(self) -> RotationMatrix:
        return RotationMatrix(self._R)

    def translation(self) -> Vector3:
        return self._p.copy()

    def set_translation(self, p: Vector3) -> None:
        self._p = np.asarray(p, dtype=float).reshape(3).copy()

    def set_rotation(self, R: RotationMatrix) -> None:
        self._R = RotationMatrix(R)

    def set(self, R: RotationMatrix, p: Vector3) -> None:
        self._set_pose(R, p)

    def SetIdentity(self) -> RigidTransform:
        """Sets X to the identity; returns this transform (as pydrake does)."""
        self._set_pose(RotationMatrix(), np.zeros(3))
        return self

    def GetAsMatrix4(self) -> npt.NDArray[np.float64]:
        m = np.eye(4)
        m[:3, :3] = self._R.matrix()
        m[:3, 3] = self._p
        return m

    def GetAsMatrix34(self) -> npt.NDArray[np.float64]:
        return self.GetAsMatrix4()[:3]

    def IsExactlyIdentity(self) -> bool:
        return bool((self._p == 0).all()) and self._R.IsExactlyIdentity()

    def IsNearlyIdentity(self, translation_tolerance: float) -> bool:
        """max |p| ≤ translation_tolerance and R nearly the identity (default tolerance)."""
        return bool(np.abs(self._p).max() <= translation_tolerance) and self._R.IsNearlyIdentity()

    def IsExactlyEqualTo(self, other: RigidTransform) -> bool:
        return bool((self.GetAsMatrix34() == other.GetAsMatrix34()).all())

    def GetMaximumAbsoluteDifference(self, other: RigidTransform) -> float:
        """max |X₃ₓ₄ − Y₃ₓ₄|, over rotation and translation entries."""
        return float(np.abs(self.GetAsMatrix34() - other.GetAsMatrix34()).max())

    def GetMaximumAbsoluteTranslationDifference(self, other: RigidTransform) -> float:
        return float(np.abs(self._p - other._p).max())

    def IsNearlyEqualTo(self, other: RigidTransform, tolerance: float) -> bool:
        return self.GetMaximumAbsoluteDifference(other) <= tolerance

    def InvertAndCompose(self, other: RigidTransform) -> RigidTransform:
        """X_BC = X_AB⁻¹ · X_AC = (R_ABᵀ·R_AC, R_ABᵀ·(p_AC − p_AB))."""
        R_BA = self._R.matrix().T
        return RigidTransform(RotationMatrix(R_BA @ other._R.matrix()), R_BA @ (other._p - self._p))

    def inverse(self) -> RigidTransform:
        R_inv = self._R.inverse()
        return RigidTransform(R_inv, -(R_inv.matrix() @ self._p))

    @overload
    def multiply(self, other: RigidTransform) -> RigidTransform: ...
    @overload
    def multiply(self, *args: Any, **kwargs: Any) -> Any: ...

    def multiply(self, *args: Any, **kwargs: Any) -> Any:
        """X_AB·X_BC, X_AB·p_BoQ_B (a 3-vector or a 3×n block), or X_AB·vec_B (a 4-vector
        whose last element is 0 or 1); see ``_products``."""
        return dispatch(
            "reimpl.math.RigidTransform", "multiply", _TRANSFORM_MULTIPLY, args, kwargs,
            receiver=self,
        )  # fmt: skip

    @overload
    def __matmul__(self, other: RigidTransform) -> RigidTransform: ...
    @overload
    def __matmul__(self, other: Any) -> Any: ...

    def __matmul__(self, other: Any) -> Any:
        if type(other) is RigidTransform:  # the common case, without dispatch
            return self._compose(other)
        return self.multiply(other)

    def _compose(self, other: RigidTransform) -> RigidTransform:
        # N.B. Drake's translation is an FMA chain, fma(R₂₂p₂, fma(R₂₁p₁, fma(R₂₀p₀, t)))
        # per row (0 of 600 random pairs differ on pydrake 1.51.1); numpy's R·p + t differs
        # in the last bit for most pairs. Python 3.11 has no fused multiply-add.
        return RigidTransform(self._R @ other._R, self._R.matrix() @ other._p + self._p)

    def _move(self, p_BoQ_B: Any) -> npt.NDArray[np.float64]:
        p = np.asarray(p_BoQ_B, dtype=float)
        moved = rotate(self._R.matrix(), p)
        return moved + (self._p if p.ndim == 1 else self._p[:, None])

    def _move_homogeneous(self, vec_B: Any) -> npt.NDArray[np.float64]:
        return homogeneous(self._R.matrix(), self._p, np.asarray(vec_B, dtype=float))

    def __repr__(self) -> str:
        R = _rows(self._R.matrix(), "  ")
        p = ", ".join(repr(float(x)) for x in self._p)
        return f"RigidTransform(\n  R=RotationMatrix([\n{R}\n  ]),\n  p=[{p}],\n)"


# The constructors' overload sets, in pydrake's order, built once.
_ROTATION_INIT = (
    Overload((), lambda self: None),
    Overload((Param("other", instance_of(RotationMatrix)),), RotationMatrix._copy_from),
    Overload((Param("R", _is_matrix((3, 3))),), RotationMatrix._from_matrix),
    Overload((Param("rpy", instance_of(RollPitchYaw)),), RotationMatrix._from_rpy),
)
_ROTATION = instance_of(RotationMatrix)
_TRANSFORM_INIT = (
    Overload((), lambda self: None),
    Overload((Param("other", instance_of(RigidTransform)),), RigidTransform._copy_from),
    Overload((Param("R", _ROTATION), Param("p", _is_vector3)), RigidTransform._set_pose),
    Overload(
        (Param("rpy", instance_of(RollPitchYaw)), Param("p", _is_vector3)),
        RigidTransform._from_rpy,
    ),
    Overload((Param("R", _ROTATION),), RigidTransform._set_pose),
    Overload((Param("p", _is_vector3),), RigidTransform._set_pose),
    Overload(
        (Param("pose", any_of(_is_matrix((4, 4)), _is_matrix((3, 4)))),),
        RigidTransform._from_matrix,
    ),
)


def _is_block(rows: int) -> Any:
    """A rows×n array (n ≥ 0), as pybind11 takes ``numpy.float64[rows, n]``."""

    def check(value: object) -> bool:
        try:
            shape = np.asarray(value, dtype=float).shape
        except (TypeError, ValueError):
            return False
        return len(shape) == 2 and shape[0] == rows

    check.__name__ = f"numpy.ndarray[numpy.float64[{rows}, n]]"
    return check


def _is_column(rows: int) -> Any:
    """A ``rows``-vector, flat or a column, as pybind11 takes ``numpy.float64[rows, 1]``."""

    def check(value: object) -> bool:
        try:
            return np.asarray(value, dtype=float).shape in {(rows,), (rows, 1)}
        except (TypeError, ValueError):
            return False

    check.__name__ = f"numpy.ndarray[numpy.float64[{rows}, 1]]"
    return check


# The multiply overload sets, in pydrake's order (1.51.1 and 1.58.0).
_ROTATION_MULTIPLY = (
    Overload((Param("other", _ROTATION),), RotationMatrix._compose),
    Overload((Param("v_B", _is_column(3)),), RotationMatrix._rotate),
    Overload((Param("v_B", _is_block(3)),), RotationMatrix._rotate),
)
_TRANSFORM_MULTIPLY = (
    Overload((Param("other", instance_of(RigidTransform)),), RigidTransform._compose),
    Overload((Param("p_BoQ_B", _is_column(3)),), RigidTransform._move),
    Overload((Param("vec_B", _is_column(4)),), RigidTransform._move_homogeneous),
    Overload((Param("p_BoQ_B", _is_block(3)),), RigidTransform._move),
)

RigidTransform_ = scalar_template("reimpl.math", "RigidTransform_", RigidTransform)
RotationMatrix_ = scalar_template("reimpl.math", "RotationMatrix_", RotationMatrix)
RollPitchYaw_ = scalar_template("reimpl.math", "RollPitchYaw_", RollPitchYaw)
register_value_type(RigidTransform, "drake::math::RigidTransform<double>")
register_value_type(RotationMatrix, "drake::math::RotationMatrix<double>")
