"""Forward kinematics: the pose X_WB of every body from the positions q.

Drake counterpart: drake/multibody/tree (mobilizers, ``CalcPositionKinematicsCache``).
A joint J joins frame F, fixed on its parent body P (``X_PF``), to frame M,
fixed on its child body C (``X_CM``); its positions q_J set ``X_FM(q_J)``:

    X_PC = X_PF · X_FM(q_J) · X_MC            X_WC = X_WP · X_PC

A tree may meet a joint from its child (a reversed joint); then
``X_WP = X_WC · X_PC⁻¹``. The world is walked depth first, each body's joints
taken in joint order whichever their direction (the floating joints Finalize
adds come last, so a free tree follows every tree joined to the world). The
walk orders the positions: joint J's come at ``position_start(J)``, in visit
order. Measured on pydrake 1.51.1: with world→A (j0), A→B (j1), world→C (j2),
A→D (j3) the positions are j0, j1, j3, j2; a free tree's floating joint
comes after the trees joined to the world (``A ['j1', 'B1', 'j0']``).

``X_FM(q)`` per joint type (``kTypeName``), a being the unit axis:

==================== ============================== ===========================
type                 q                              X_FM = (R_FM, p_FM)
==================== ============================== ===========================
weld                 —                              the joint's X_FM
revolute             [θ]                            (R_a(θ), 0)
prismatic            [x]                            (I, x·a)
screw                [θ]                            (R_a(θ), a·pitch·θ/2π)
ball_rpy             [r, p, y]                      (R_rpy(r, p, y), 0)
universal            [θ₀, θ₁]                       (R_x(θ₀)·R_y(θ₁), 0)
planar               [x, y, θ]                      (R_z(θ), [x, y, 0])
rpy_floating         [r, p, y, x, y, z]             (R_rpy(r, p, y), [x, y, z])
quaternion_floating  [qw, qx, qy, qz, x, y, z]      (R(q/|q|), [x, y, z])
curvilinear          [s]                            the curve's pose at arc length s
==================== ============================== ===========================

Poses here are pairs ``(R, p)`` of numpy arrays; the plant turns them into
RigidTransforms at its boundary.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = [
    "FLOATING_TYPES",
    "X_FM",
    "Forest",
    "Mobilizer",
    "Pose",
    "body_poses",
    "build_forest",
    "compose",
    "identity",
    "invert",
    "quaternion_from_rotation",
    "rotation_about",
    "rotation_from_quaternion",
    "rotation_from_rpy",
    "rpy_from_rotation",
]

Array = npt.NDArray[np.float64]
#: A rigid transform X_AB as (R_AB, p_AoBo_A).
Pose = tuple[Array, Array]

#: Joint types whose X_FM is a whole pose (SetFreeBodyPose may set them).
FLOATING_TYPES = frozenset({"quaternion_floating", "rpy_floating"})


# ------------------------------------------------------------------ poses


def identity() -> Pose:
    return np.eye(3), np.zeros(3)


def compose(X_AB: Pose, X_BC: Pose) -> Pose:
    """X_AC = X_AB · X_BC = (R_AB·R_BC, R_AB·p_BC + p_AB)."""
    R_AB, p_AB = X_AB
    R_BC, p_BC = X_BC
    return R_AB @ R_BC, R_AB @ p_BC + p_AB


def invert(X_AB: Pose) -> Pose:
    """X_BA = X_AB⁻¹ = (R_ABᵀ, −R_ABᵀ·p_AB)."""
    R_BA = X_AB[0].T
    return R_BA, -(R_BA @ X_AB[1])


# -------------------------------------------------------------- rotations


def rotation_about(a: Array, theta: float) -> Array:
    """R_a(θ) for a unit axis a (Eigen's AngleAxis::toRotationMatrix).

    R = c·I + (1 − c)·a·aᵀ + s·[a]×, with c = cos θ, s = sin θ. About ±x, ±y
    or ±z it is the elementary rotation, entry for entry (R_z(θ) has R₂₂ = 1
    exactly, as Drake's MakeZRotation; the general formula gives (1 − c) + c).
    """
    c, s = math.cos(theta), math.sin(theta)
    if np.count_nonzero(a) == 1:
        i = int(np.flatnonzero(a)[0])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = s if a[i] > 0 else -s
        R = np.eye(3)
        R[j, j], R[j, k], R[k, j], R[k, k] = c, -s, s, c
        return R
    sin_axis = s * a
    cos1_axis = (1.0 - c) * a
    R = np.empty((3, 3))
    tmp = cos1_axis[0] * a[1]
    R[0, 1], R[1, 0] = tmp - sin_axis[2], tmp + sin_axis[2]
    tmp = cos1_axis[0] * a[2]
    R[0, 2], R[2, 0] = tmp + sin_axis[1], tmp - sin_axis[1]
    tmp = cos1_axis[1] * a[2]
    R[1, 2], R[2, 1] = tmp - sin_axis[0], tmp + sin_axis[0]
    R[0, 0], R[1, 1], R[2, 2] = cos1_axis * a + c
    return R


def rotation_from_rpy(rpy: Sequence[float] | Array) -> Array:
    """R = R_z(y)·R_y(p)·R_x(r), in Drake's closed form (RollPitchYaw::ToRotationMatrix)."""
    r, p, y = (float(v) for v in rpy)
    c0, c1, c2 = math.cos(r), math.cos(p), math.cos(y)
    s0, s1, s2 = math.sin(r), math.sin(p), math.sin(y)
    c2_s1, s2_s1 = c2 * s1, s2 * s1
    return np.array(
        [
            [c2 * c1, c2_s1 * s0 - s2 * c0, c2_s1 * c0 + s2 * s0],
            [s2 * c1, s2_s1 * s0 + c2 * c0, s2_s1 * c0 - c2 * s0],
            [-s1, c1 * s0, c1 * c0],
        ]
    )


def rotation_from_quaternion(q: Sequence[float] | Array) -> Array:
    """R(q/|q|) for q = [w, x, y, z], not necessarily unit (Drake's QuaternionToRotationMatrix).

    With s = 2/|q|²: R = I − s·(…) term by term, e.g. R₀₀ = 1 − s·(y² + z²).
    """
    w, x, y, z = (float(v) for v in q)
    norm_squared = w * w + x * x + y * y + z * z
    if norm_squared == 0.0:
        raise RuntimeError(
            "QuaternionToRotationMatrix(): All the elements in a quaternion are zero."
        )
    two = 2.0 / norm_squared
    sx, sy, sz = two * x, two * y, two * z
    swx, swy, swz = sx * w, sy * w, sz * w
    sxx, sxy, sxz = sx * x, sy * x, sz * x
    syy, syz, szz = sy * y, sz * y, sz * z
    return np.array(
        [
            [1.0 - syy - szz, sxy - swz, sxz + swy],
            [sxy + swz, 1.0 - sxx - szz, syz - swx],
            [sxz - swy, syz + swx, 1.0 - sxx - syy],
        ]
    )


def quaternion_from_rotation(R: Array) -> Array:
    """The unit quaternion [w, x, y, z] of R with w ≥ 0 (Drake's RotationMatrix::ToQuaternion).

    Branches on the largest of trace(R) and the diagonal, then normalizes.
    Measured: R_x(−3) gives [0.0707372, −0.99749499, 0, 0].
    """
    trace = R[0, 0] + R[1, 1] + R[2, 2]
    if trace >= R[0, 0] and trace >= R[1, 1] and trace >= R[2, 2]:
        q = [1.0 + trace, R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]
    elif R[0, 0] >= R[1, 1] and R[0, 0] >= R[2, 2]:
        q = [R[2, 1] - R[1, 2], 1.0 - (trace - 2 * R[0, 0]), R[0, 1] + R[1, 0], R[0, 2] + R[2, 0]]
    elif R[1, 1] >= R[2, 2]:
        q = [R[0, 2] - R[2, 0], R[0, 1] + R[1, 0], 1.0 - (trace - 2 * R[1, 1]), R[1, 2] + R[2, 1]]
    else:
        q = [R[1, 0] - R[0, 1], R[0, 2] + R[2, 0], R[1, 2] + R[2, 1], 1.0 - (trace - 2 * R[2, 2])]
    quaternion = np.array(q, dtype=float)
    sign = -1.0 if quaternion[0] < 0 else 1.0
    return quaternion * (sign / float(np.linalg.norm(quaternion)))


def rpy_from_rotation(R: Array) -> Array:
    """[r, p, y] of R, each in [−π, π], p in [−π/2, π/2] (Drake's RollPitchYaw(R)).

    p = atan2(−R₂₀, √((R₂₂² + R₂₁² + R₁₀² + R₀₀²)/2)); with q = [e0, e1, e2, e3]
    the quaternion of R, zA = atan2(e1 + e3, e0 − e2), zB = atan2(e3 − e1,
    e0 + e2) (0 when both arguments are within ε of 0), r = zA − zB and
    y = zA + zB, wrapped into [−π, π]. Measured: R_rpy(0.1, π/2, 0.3) gives
    [−0.1, π/2, 0.1].
    """
    r_sum = math.sqrt((R[2, 2] ** 2 + R[2, 1] ** 2 + R[1, 0] ** 2 + R[0, 0] ** 2) / 2)
    pitch = math.atan2(-R[2, 0], r_sum)
    e0, e1, e2, e3 = quaternion_from_rotation(R)
    epsilon = float(np.finfo(float).eps)

    def angle(y: float, x: float) -> float:
        return 0.0 if abs(y) <= epsilon and abs(x) <= epsilon else math.atan2(y, x)

    zA, zB = angle(e1 + e3, e0 - e2), angle(e3 - e1, e0 + e2)
    roll, yaw = _wrap(zA - zB), _wrap(zA + zB)
    return np.array([roll, pitch, yaw])


def _wrap(angle: float) -> float:
    if angle > math.pi:
        return angle - 2 * math.pi
    if angle < -math.pi:
        return angle + 2 * math.pi
    return angle


# ------------------------------------------------------------------ X_FM


def _unit(axis: Array) -> Array:
    return axis / float(np.linalg.norm(axis))


def _no_translation(R: Array) -> Pose:
    return R, np.zeros(3)


def _weld(joint: Any, q: Array) -> Pose:
    X = joint.X_FM()
    return X.rotation().matrix(), X.translation()


def _revolute(joint: Any, q: Array) -> Pose:
    return _no_translation(rotation_about(_unit(joint.revolute_axis()), float(q[0])))


def _prismatic(joint: Any, q: Array) -> Pose:
    return np.eye(3), float(q[0]) * _unit(joint.translation_axis())


def _screw(joint: Any, q: Array) -> Pose:
    a = _unit(joint._axis())
    theta = float(q[0])
    return rotation_about(a, theta), a * (joint.screw_pitch() * theta / (2 * math.pi))


def _universal(joint: Any, q: Array) -> Pose:
    x, y = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    return _no_translation(rotation_about(x, float(q[0])) @ rotation_about(y, float(q[1])))


def _planar(joint: Any, q: Array) -> Pose:
    z = np.array([0.0, 0.0, 1.0])
    return rotation_about(z, float(q[2])), np.array([q[0], q[1], 0.0], dtype=float)


#: kTypeName -> X_FM(joint, q_J).
_X_FM: dict[str, Callable[[Any, Array], Pose]] = {
    "weld": _weld,
    "revolute": _revolute,
    "prismatic": _prismatic,
    "screw": _screw,
    "ball_rpy": lambda joint, q: _no_translation(rotation_from_rpy(q)),
    "universal": _universal,
    "planar": _planar,
    "rpy_floating": lambda joint, q: (rotation_from_rpy(q[:3]), np.array(q[3:6], dtype=float)),
    "quaternion_floating": lambda joint, q: (
        rotation_from_quaternion(q[:4]),
        np.array(q[4:7], dtype=float),
    ),
    "curvilinear": lambda joint, q: joint._X_FM(float(q[0])),
}


def X_FM(joint: Any, q: Array) -> Pose:
    """The pose of ``joint``'s child frame M in its parent frame F at positions ``q``."""
    return _X_FM[joint.type_name()](joint, q)


# ---------------------------------------------------------------- forest


@dataclass(frozen=True)
class Mobilizer:
    """One joint as the walk meets it: from the body already placed to the next one."""

    joint: int
    inboard: int
    outboard: int
    reversed: bool


@dataclass(frozen=True)
class Forest:
    """The joints in walk order, with where each joint's positions and velocities start."""

    mobilizers: tuple[Mobilizer, ...]
    #: position_start[j] for joint index j.
    position_start: tuple[int, ...]
    #: velocity_start[j] for joint index j.
    velocity_start: tuple[int, ...]

    def inboard_joint(self, body: int) -> int | None:
        """The joint that places ``body`` (None for the world)."""
        for mobilizer in self.mobilizers:
            if mobilizer.outboard == body:
                return mobilizer.joint
        return None


def build_forest(num_bodies: int, joints: Sequence[tuple[int, int, int, int]]) -> Forest:
    """Walks (parent, child, num_positions, num_velocities) joints depth first from the world.

    Every body must be reachable from the world, body 0 (Finalize has added
    the floating joints).

    >>> build_forest(3, [(1, 2, 1, 1), (0, 1, 7, 6)]).velocity_start
    (6, 0)
    """
    incident: list[list[int]] = [[] for _ in range(num_bodies)]
    for index, (parent, child, _, _) in enumerate(joints):
        incident[parent].append(index)
        incident[child].append(index)
    used = [False] * len(joints)
    mobilizers: list[Mobilizer] = []
    q_starts, v_starts = [0] * len(joints), [0] * len(joints)
    next_q = next_v = 0
    # An explicit stack of (body, next incident slot): chains may be deeper than
    # Python's recursion limit.
    stack: list[tuple[int, int]] = [(0, 0)]
    while stack:
        body, slot = stack.pop()
        if slot == len(incident[body]):
            continue
        stack.append((body, slot + 1))
        index = incident[body][slot]
        if used[index]:
            continue
        used[index] = True
        parent, child, num_positions, num_velocities = joints[index]
        is_reversed = child == body
        outboard = parent if is_reversed else child
        mobilizers.append(Mobilizer(index, body, outboard, is_reversed))
        q_starts[index], v_starts[index] = next_q, next_v
        next_q, next_v = next_q + num_positions, next_v + num_velocities
        stack.append((outboard, 0))
    return Forest(tuple(mobilizers), tuple(q_starts), tuple(v_starts))


def body_poses(
    forest: Forest,
    num_bodies: int,
    joint_X_FM: Callable[[int], Pose],
    X_PF: Sequence[Pose],
    X_MC: Sequence[Pose],
) -> list[Pose]:
    """X_WB for every body: X_WC = X_WP · X_PF · X_FM(q) · X_MC along the forest.

    ``joint_X_FM(j)`` is joint j's X_FM at the current positions; ``X_PF[j]``
    and ``X_MC[j]`` its fixed frame poses (X_MC = X_CM⁻¹).
    """
    poses: list[Pose] = [identity()] * num_bodies
    for mobilizer in forest.mobilizers:
        j = mobilizer.joint
        X_PC = compose(compose(X_PF[j], joint_X_FM(j)), X_MC[j])
        X_WI = poses[mobilizer.inboard]
        poses[mobilizer.outboard] = compose(X_WI, invert(X_PC) if mobilizer.reversed else X_PC)
    return poses
