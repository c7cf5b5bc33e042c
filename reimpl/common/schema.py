"""The deterministic subset of ``pydrake.common.schema``: Rotation and Transform.

Model directives place frames and welds with ``schema.Transform``: an optional
``base_frame`` name, a ``translation`` and a ``rotation``, written in YAML as

    X_PF:
      base_frame: world
      translation: [1, 2, 3]
      rotation: !Rpy { deg: [10, 20, 30] }

A rotation is one of ``Rotation.Identity()`` (the default, YAML ``{}`` or
``!Identity {}``), ``Rotation.Rpy(deg=[r, p, y])`` (roll, pitch, yaw in
degrees), ``Rotation.AngleAxis(angle_deg=a, axis=[x, y, z])`` (the axis is
normalized) or ``Rotation.Uniform()`` (a random rotation: not deterministic).
Only deterministic transforms have a value, ``GetDeterministicValue()``;
asking a random one for it ends the program, as in pydrake 1.51.1 (SystemExit).

N.B. reimpl does not sample distributions: ``Rotation.Uniform`` exists so that
model directives can be checked (a random ``X_PF`` is invalid there) but has
no ``Sample``/``Mean``; a translation is always a plain 3-vector; there is no
``Transform(RigidTransform)`` nor ``Rotation(RotationMatrix)`` (reimpl.math has
no matrix-to-RPY conversion).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from reimpl.common._drake_demand import failed_demand
from reimpl.common._struct import Field, Struct, as_vector, optional_of, string, vector
from reimpl.math import RigidTransform, RollPitchYaw, RotationMatrix

__all__ = ["Rotation", "Transform"]

_MODULE = "reimpl.common.schema"
_VECTOR3 = "numpy.ndarray[numpy.float64[3, 1]]"


class _Identity(Struct):
    MODULE = _MODULE
    QUALNAME = "Rotation.Identity"
    FIELDS = ()


class _Rpy(Struct):
    MODULE = _MODULE
    QUALNAME = "Rotation.Rpy"
    FIELDS = (Field("deg", _VECTOR3, vector(3), lambda: np.zeros(3), as_vector),)


class _AngleAxis(Struct):
    MODULE = _MODULE
    QUALNAME = "Rotation.AngleAxis"
    FIELDS = (
        Field("angle_deg", "float", lambda v: isinstance(v, int | float), lambda: 0.0, float),
        Field(
            "axis",
            _VECTOR3,
            vector(3),
            lambda: np.array([0.0, 0.0, 1.0]),
            as_vector,
        ),
    )


class _Uniform(Struct):
    MODULE = _MODULE
    QUALNAME = "Rotation.Uniform"
    FIELDS = ()


_VARIANTS = (_Identity, _Rpy, _AngleAxis, _Uniform)


def _is_variant(value: object) -> bool:
    return isinstance(value, _VARIANTS)


class Rotation(Struct):
    """A rotation given as one of the variants (see the module docstring)."""

    MODULE = _MODULE
    Identity = _Identity
    Rpy = _Rpy
    AngleAxis = _AngleAxis
    Uniform = _Uniform
    FIELDS = (
        Field(
            "value",
            "Union[Identity, Rpy, AngleAxis, Uniform]",
            _is_variant,
            _Identity,
            lambda v: v,
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if len(args) == 1 and not kwargs and isinstance(args[0], RollPitchYaw):
            super().__init__()
            self.set_rpy_deg(np.asarray(args[0].vector()) * 180 / math.pi)
            return
        if len(args) == 1 and not kwargs and isinstance(args[0], Rotation):
            super().__init__(value=args[0].__deepcopy__({}).value)
            return
        super().__init__(*args, **kwargs)

    def set_rpy_deg(self, rpy_deg: Any) -> None:
        self.value = _Rpy(deg=rpy_deg)

    def IsDeterministic(self) -> bool:
        return not isinstance(self.value, _Uniform)

    def GetDeterministicValue(self) -> RotationMatrix:
        value = self.value
        if isinstance(value, _Rpy):
            return RotationMatrix(RollPitchYaw(value.deg * (math.pi / 180.0)))
        if isinstance(value, _AngleAxis):
            return _angle_axis(value.angle_deg * (math.pi / 180.0), value.axis)
        if isinstance(value, _Uniform):
            raise failed_demand("Rotation.GetDeterministicValue")
        return RotationMatrix()


def _angle_axis(angle: float, axis: Any) -> RotationMatrix:
    """Eigen's ``AngleAxis::toRotationMatrix()`` about the normalized ``axis``,
    term for term (so the last bits agree with Drake's)."""
    x, y, z = (float(v) for v in axis)
    norm = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / norm, y / norm, z / norm
    s, c = math.sin(angle), math.cos(angle)
    sx, sy, sz = s * x, s * y, s * z
    cx, cy, cz = (1 - c) * x, (1 - c) * y, (1 - c) * z
    xy, xz, yz = cx * y, cx * z, cy * z
    return RotationMatrix(
        np.array(
            [
                [cx * x + c, xy - sz, xz + sy],
                [xy + sz, cy * y + c, yz - sx],
                [xz - sy, yz + sx, cz * z + c],
            ]
        )
    )


def _is_rotation(value: object) -> bool:
    return isinstance(value, Rotation) or _is_variant(value)


def _as_rotation(value: Any) -> Rotation:
    return value if isinstance(value, Rotation) else Rotation(value=value)


class Transform(Struct):
    """A pose: ``base_frame``, ``translation`` and ``rotation``."""

    MODULE = _MODULE
    FIELDS = (
        Field("base_frame", "Optional[str]", optional_of(string), lambda: None),
        Field(
            "translation",
            _VECTOR3,
            vector(3),
            lambda: np.zeros(3),
            as_vector,
        ),
        Field("rotation", "pydrake.common.schema.Rotation", _is_rotation, Rotation, _as_rotation),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if len(args) == 1 and not kwargs and isinstance(args[0], Transform):
            super().__init__()
            for name, value in args[0].__deepcopy__({})._values():
                object.__setattr__(self, "_" + name, value)
            return
        super().__init__(*args, **kwargs)

    def set_rotation_rpy_deg(self, rpy_deg: Any) -> None:
        self.rotation.set_rpy_deg(rpy_deg)

    def IsDeterministic(self) -> bool:
        return bool(self.rotation.IsDeterministic())

    def GetDeterministicValue(self) -> RigidTransform:
        if not self.IsDeterministic():
            raise failed_demand("Transform.GetDeterministicValue")
        return RigidTransform(self.rotation.GetDeterministicValue(), self.translation)
