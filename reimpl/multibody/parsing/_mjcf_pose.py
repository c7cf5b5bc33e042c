"""MuJoCo poses: ``pos`` and one orientation, as Drake 1.51.1 reads them (measured).

``pos`` (3 numbers, default zero) is read first; then more than one of the
orientation attributes is an error naming them all::

    Element geom has more than one orientation attribute specified. There must be no
    more than one instance of `quat`, `axisangle`, `euler`, `xyaxes`, or `zaxis`.
    Attributes: [name="a" quat="0 1 0 0" euler="1 2 3" ]

(each attribute as ``name="value"`` with a space after it, in the element's
order). The first orientation present, in the table's order, gives R:

=============  =================================================================
 attribute      rotation
=============  =================================================================
 ``quat``       w x y z, not necessarily unit: R(q/|q|) (all zero: Drake's
                ``QuaternionToRotationMatrix(): All the elements in a quaternion
                are zero.``)
 ``axisangle``  x y z θ: about the normalized axis (θ in the compiler's unit)
 ``euler``      three angles (compiler's unit) about the axes of the compiler's
                ``eulerseq``: a lowercase axis is a moving one (q = q·qᵢ), an
                uppercase one fixed (q = qᵢ·q)
 ``xyaxes``     x then y: x normalized, y made orthogonal to it and normalized,
                z = x × y; an x or y shorter than 1e-12 is ``The x axis in the
                'xyaxes' attribute 'T' is too small.`` (y alike)
 ``zaxis``      the smallest rotation taking +z to the axis (Eigen's
                Quaternion::FromTwoVectors)
=============  =================================================================

Not modelled (a reimpl error): Eigen's FromTwoVectors for a direction within
1e-12 of -z (cosine below -1 + 1e-12) that is not exactly -z, where Eigen takes
the axis from an SVD (exactly -z is a half turn about +x, as Drake gives,
measured); an ``xyaxes`` whose y axis is parallel to its x axis (Drake makes a
singular "rotation").
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from reimpl.math import RigidTransform, RotationMatrix
from reimpl.multibody import kinematics
from reimpl.multibody.parsing import _mjcf_values as values
from reimpl.multibody.parsing._mjcf_context import MjcfContext, unsupported
from reimpl.multibody.parsing._mjcf_defaults import ORIENTATIONS
from reimpl.multibody.parsing._xml import XmlElement

__all__ = [
    "Quaternion",
    "parse_transform",
    "quaternion_from_two_vectors",
    "rotation_from_angle_axis",
]

#: Eigen's NumTraits<double>::dummy_precision().
_DUMMY_PRECISION = 1e-12

Quaternion = tuple[float, float, float, float]


def _normalized(v: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Eigen's normalized(): unchanged when its norm is zero."""
    norm_squared = float(v @ v)
    return v / math.sqrt(norm_squared) if norm_squared > 0 else v.copy()


def rotation_from_angle_axis(theta: float, axis: list[float]) -> RotationMatrix:
    """Drake's RotationMatrix(AngleAxis): R = (1 − c)·λλᵀ + c·I + s·[λ]× for λ = axis/|axis|."""
    x, y, z = (float(v) for v in _normalized(np.asarray(axis, dtype=float)))
    s, c = math.sin(theta), math.cos(theta)
    t = 1 - c
    tx, ty, tz = t * x, t * y, t * z
    R = np.array(
        [
            [tx * x + c, tx * y - s * z, tx * z + s * y],
            [tx * y + s * z, ty * y + c, ty * z - s * x],
            [tx * z - s * y, ty * z + s * x, tz * z + c],
        ]
    )
    return RotationMatrix(R)


def _product(a: Quaternion, b: Quaternion) -> Quaternion:
    """The Hamilton product a·b (w, x, y, z)."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by + ay * bw + az * bx - ax * bz,
        aw * bz + az * bw + ax * by - ay * bx,
    )


def _rotation(q: Quaternion) -> RotationMatrix:
    return RotationMatrix(kinematics.rotation_from_quaternion(q))


def _euler(angles: list[float], sequence: str) -> RotationMatrix:
    q: Quaternion = (1.0, 0.0, 0.0, 0.0)
    for angle, axis in zip(angles, sequence, strict=True):
        half = angle / 2.0
        sa = math.sin(half)
        vector = [0.0, 0.0, 0.0]
        vector["xyz".index(axis.lower())] = sa
        step: Quaternion = (math.cos(half), vector[0], vector[1], vector[2])
        q = _product(q, step) if axis.islower() else _product(step, q)
    return _rotation(q)


def quaternion_from_two_vectors(element: XmlElement, a: list[float], b: list[float]) -> Quaternion:
    """Eigen's Quaternion::FromTwoVectors(a, b) (w, x, y, z), but for Eigen's SVD case."""
    v0 = _normalized(np.asarray(a, dtype=float))
    v1 = _normalized(np.asarray(b, dtype=float))
    c = float(v1 @ v0)
    if c < -1.0 + _DUMMY_PRECISION:
        if not (v0[0] == 0 and v0[1] == 0 and v1[0] == 0 and v1[1] == 0):
            raise unsupported(element, "a direction within 1e-12 of -z that is not exactly -z")
        # N.B. The plane's null space is the xy plane; Eigen's SVD picks +x (measured).
        w2 = (1.0 + max(c, -1.0)) * 0.5
        s = math.sqrt(1.0 - w2)
        return (math.sqrt(w2), s, 0.0, 0.0)
    axis = np.cross(v0, v1)
    s = math.sqrt((1.0 + c) * 2.0)
    inverse = 1.0 / s
    return (s * 0.5, float(axis[0] * inverse), float(axis[1] * inverse), float(axis[2] * inverse))


def rotation_from_z(element: XmlElement, direction: list[float]) -> RotationMatrix:
    """The smallest rotation taking +z to ``direction``."""
    return _rotation(quaternion_from_two_vectors(element, [0.0, 0.0, 1.0], direction))


#: fmt's ``{:?}`` escapes (the characters an attribute value can hold after tinyxml2).
_ESCAPES = {"\\": "\\\\", '"': '\\"', "\n": "\\n", "\r": "\\r", "\t": "\\t"}


def _debug_string(text: str) -> str:
    """fmt's debug format of a string: quoted; backslash, quote, LF, CR and tab escaped."""
    return '"' + "".join(_ESCAPES.get(ch, ch) for ch in text) + '"'


def _check_one_orientation(context: MjcfContext, node: XmlElement) -> None:
    """ErrorIfMoreThanOneOrientation."""
    if sum(node.get(name) is not None for name in ORIENTATIONS) <= 1:
        return
    listed = "".join(f"{name}={_debug_string(value)} " for name, value in node.attrib.items())
    raise context.d.error(
        node,
        f"Element {node.tag} has more than one orientation attribute specified. There must be "
        "no more than one instance of `quat`, `axisangle`, `euler`, `xyaxes`, or `zaxis`. "
        f"Attributes: [{listed}]",
    )


def _xyaxes(context: MjcfContext, node: XmlElement, xyaxes: list[float]) -> RotationMatrix:
    x, y = np.asarray(xyaxes[:3]), np.asarray(xyaxes[3:])
    for axis, vector in (("x", x), ("y", y)):
        if float(np.linalg.norm(vector)) < 1e-12:
            raise context.d.error(
                node,
                f"The {axis} axis in the 'xyaxes' attribute '{node.get('xyaxes')}' is too small.",
            )
    col0 = _normalized(x)
    col1 = _normalized(y - float(col0 @ y) * col0)
    if not float(col1 @ col1) > 0:
        raise unsupported(node, "an 'xyaxes' whose y axis is parallel to its x axis")
    col2 = _normalized(np.cross(col0, col1))
    return RotationMatrix(np.column_stack([col0, col1, col2]))


def _angle(context: MjcfContext, value: float) -> float:
    return value * (math.pi / 180.0) if context.compiler.degrees else value


def _orientation(context: MjcfContext, node: XmlElement) -> RotationMatrix | None:
    """The rotation of the first orientation attribute present, or None."""
    if node.get("quat") is not None:
        quat = values.vector(node, "quat", 4)
        assert quat is not None
        return _rotation((quat[0], quat[1], quat[2], quat[3]))
    axisangle = values.vector(node, "axisangle", 4)
    if axisangle is not None:
        return rotation_from_angle_axis(_angle(context, axisangle[3]), axisangle[:3])
    euler = values.vector(node, "euler", 3)
    if euler is not None:
        return _euler([_angle(context, e) for e in euler], context.compiler.eulerseq)
    xyaxes = values.vector(node, "xyaxes", 6)
    if xyaxes is not None:
        return _xyaxes(context, node, xyaxes)
    zaxis = values.vector(node, "zaxis", 3)
    if zaxis is not None:
        return rotation_from_z(node, zaxis)
    return None


def parse_transform(context: MjcfContext, node: XmlElement) -> RigidTransform:
    """ParseTransform: ``pos`` and the orientation (identity when none is given)."""
    pos = values.vector(node, "pos", 3) or [0.0, 0.0, 0.0]
    _check_one_orientation(context, node)
    rotation = _orientation(context, node)
    return RigidTransform(rotation or RotationMatrix(), np.asarray(pos, dtype=float))
