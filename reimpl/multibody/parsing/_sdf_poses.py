"""SDFormat poses, computed as libsdformat computes them (gz::math::Pose3d).

Drake reads every SDFormat pose through libsdformat, which keeps a pose as a
position p and a quaternion q = (w, x, y, z) and composes them with
gz-math 9's formulas. Drake then decides, e.g., whether a joint needs a
``<joint>_parent`` frame by whether the resolved pose is *exactly* the
identity, so the arithmetic here follows gz-math step by step (pydrake 1.51.1
agrees bit for bit on the poses measured):

==============================  ==================================================
 operation                       gz-math 9
==============================  ==================================================
 q from roll, pitch, yaw         half angles, products of sines and cosines,
                                 then divided by ‖q‖ (``SetFromEuler``)
 A ∘ B                           p = p_A + q_A ⊗ (0, p_B) ⊗ q_A⁻¹, q = q_A ⊗ q_B
 A⁻¹                             q⁻¹ = q̄ / ‖q‖², p = q⁻¹ · (−p) (rotated by
                                 v + 2w(u × v) + 2u × (u × v))
==============================  ==================================================

A ``<pose>`` text is ``x y z roll pitch yaw`` (``degrees="true"``: the angles
times π/180) or, with ``rotation_format="quat_xyzw"``, ``x y z qx qy qz qw``
(not normalized). Its ``relative_to`` names the frame the pose is in (empty:
the element's default frame, see _sdf_graph).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from reimpl.math import RigidTransform, RotationMatrix
from reimpl.multibody import kinematics
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["IDENTITY", "GzPose", "PoseTextError", "parse_pose", "read_pose", "rotate"]

Quaternion = tuple[float, float, float, float]
Vector = tuple[float, float, float]

#: std::stod's decimal syntax (a prefix of the token is enough for stod)
_NUMBER = re.compile(
    r"[+-]?(?:\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?\d+)?|inf(?:inity)?|nan)"
)
_SIZES = {"euler_rpy": 6, "quat_xyzw": 7}
_BOOL_TEXT = {"true": True, "1": True, "false": False, "0": False}


def _qmul(a: Quaternion, b: Quaternion) -> Quaternion:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


def _qinv(q: Quaternion) -> Quaternion:
    w, x, y, z = q
    s = w * w + x * x + y * y + z * z
    if abs(s) <= 1e-6:
        return (1.0, 0.0, 0.0, 0.0)
    return (w / s, -x / s, -y / s, -z / s)


def _cross(a: Vector, b: Vector) -> Vector:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rotate(q: Quaternion, v: Vector) -> Vector:
    """gz-math's ``Quaternion * Vector3``: v + 2w(u × v) + 2u × (u × v), u = (x, y, z)."""
    u = (q[1], q[2], q[3])
    uv = _cross(u, v)
    uuv = _cross(u, uv)
    w2 = 2.0 * q[0]
    return (
        v[0] + uv[0] * w2 + uuv[0] * 2.0,
        v[1] + uv[1] * w2 + uuv[1] * 2.0,
        v[2] + uv[2] * w2 + uuv[2] * 2.0,
    )


def _from_euler(roll: float, pitch: float, yaw: float) -> Quaternion:
    phi, the, psi = roll / 2.0, pitch / 2.0, yaw / 2.0
    cphi, sphi = math.cos(phi), math.sin(phi)
    cthe, sthe = math.cos(the), math.sin(the)
    cpsi, spsi = math.cos(psi), math.sin(psi)
    w = cphi * cthe * cpsi + sphi * sthe * spsi
    x = sphi * cthe * cpsi - cphi * sthe * spsi
    y = cphi * sthe * cpsi + sphi * cthe * spsi
    z = cphi * cthe * spsi - sphi * sthe * cpsi
    norm = math.sqrt(w * w + x * x + y * y + z * z)
    if abs(norm) <= 1e-6:
        return (1.0, 0.0, 0.0, 0.0)
    return (w / norm, x / norm, y / norm, z / norm)


@dataclass(frozen=True)
class GzPose:
    """A pose X_AB as gz::math::Pose3d holds it: position p and quaternion q = (w, x, y, z)."""

    q: Quaternion = (1.0, 0.0, 0.0, 0.0)
    p: Vector = (0.0, 0.0, 0.0)

    @staticmethod
    def from_rpy(xyz: Vector, rpy: Vector) -> GzPose:
        return GzPose(_from_euler(*rpy), xyz)

    def __mul__(self, other: GzPose) -> GzPose:
        """X_AC = X_AB ∘ X_BC (gz-math's ``operator*``)."""
        moved = _qmul(self.q, _qmul((0.0, *other.p), _qinv(self.q)))
        p = (self.p[0] + moved[1], self.p[1] + moved[2], self.p[2] + moved[3])
        return GzPose(_qmul(self.q, other.q), p)

    def inverse(self) -> GzPose:
        inverse = _qinv(self.q)
        return GzPose(inverse, rotate(inverse, (self.p[0] * -1, self.p[1] * -1, self.p[2] * -1)))

    def transform(self) -> RigidTransform:
        """Drake's ``ToRigidTransform``: the rotation of q/‖q‖, and p."""
        R = kinematics.rotation_from_quaternion(self.q)
        return RigidTransform(RotationMatrix(R), np.array(self.p, dtype=float))

    def is_exactly_identity(self) -> bool:
        """Whether ``transform()`` is exactly the identity (RigidTransform::IsExactlyIdentity)."""
        R = kinematics.rotation_from_quaternion(self.q)
        return bool(np.array_equal(R, np.eye(3)) and not any(self.p))


IDENTITY = GzPose()


class PoseTextError(ValueError):
    """A ``<pose>`` libsdformat cannot read; ``str()`` is its logged message."""

    def __init__(self, message: str, attribute: str | None = None) -> None:
        super().__init__(message)
        #: the attribute at fault (``degrees``), or None for the text
        self.attribute = attribute


def parse_pose(text: str, rotation_format: str | None, degrees: str | None) -> GzPose:
    """The pose a ``<pose>`` text means; raises PoseTextError with libsdformat's message."""
    parse_degrees = False
    if degrees is not None:
        flag = _BOOL_TEXT.get(degrees.strip().lower())
        if flag is None:
            raise PoseTextError("Invalid boolean value", "degrees")
        parse_degrees = flag
    form = rotation_format if rotation_format is not None else "euler_rpy"
    if form not in _SIZES:
        raise PoseTextError(
            f"Undefined attribute //pose[@rotation_format='{form}'], only 'euler_rpy' and "
            "'quat_xyzw' is supported."
        )
    if form == "quat_xyzw" and parse_degrees:
        raise PoseTextError(
            "The attribute //pose[@degrees='true'] does not apply when parsing quaternions, "
            "//pose[@rotation_format='quat_xyzw']."
        )
    tokens = text.split()
    if not tokens:
        return IDENTITY
    size = _SIZES[form]
    values: list[float] = []
    for token in tokens:
        match = _NUMBER.match(token.lower())
        if match is None:
            raise PoseTextError(f"Invalid argument. Unable to set value [{text}] for key [pose].")
        value = float(match.group())
        if not math.isfinite(value):
            raise PoseTextError("Pose values must be finite.")
        if len(values) >= size:
            raise PoseTextError(
                f"The value for //pose[@rotation_format='{form}'] must have {size} values, but "
                f"more than that were found in '{text}'."
            )
        values.append(value)
    if len(values) != size:
        raise PoseTextError(
            f"The value for //pose[@rotation_format='{form}'] must have {size} values, but "
            f"{len(values)} were found instead in '{text}'."
        )
    xyz = (values[0], values[1], values[2])
    if form == "quat_xyzw":
        return GzPose((values[6], values[3], values[4], values[5]), xyz)
    rpy = values[3:6]
    if parse_degrees:
        rpy = [angle * math.pi / 180 for angle in rpy]
    return GzPose.from_rpy(xyz, (rpy[0], rpy[1], rpy[2]))


def read_pose(element: XmlElement) -> tuple[str, GzPose]:
    """``(relative_to, X)`` of ``element``'s first ``<pose>``: ``("", identity)`` without one.

    The text was checked when the document was read (_sdf_document).
    """
    poses = children(element, "pose")
    if not poses:
        return "", IDENTITY
    pose = poses[0]
    X = parse_pose(pose.text or "", pose.get("rotation_format"), pose.get("degrees"))
    return pose.get("relative_to") or "", X
