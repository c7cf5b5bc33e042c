"""SDFormat poses: where every named frame of a document is in the world.

SDFormat 1.9 pose frame semantics, as Drake 1.51.1 reads them (measured):
every ``<pose>`` is X_RF, the pose of its element's frame F in the frame R
that ``relative_to`` names, or by default

==========================  ===========================================
element                     default R
==========================  ===========================================
top-level ``<model>``       the world
nested ``<model>``          the enclosing model's frame ``__model__``
``<link>``                  the model frame ``__model__``
``<joint>``                 the joint's child link (or frame)
``<frame>``                 the frame it is ``attached_to`` (``__model__``)
``<collision>``/``<visual>``  its link
==========================  ===========================================

so that ``X_WF = X_WR · X_RF`` (names scoped like ``m::inner::L``; a nested
model's name stands for its model frame). A pose's text is ``x y z roll pitch
yaw`` (``degrees="true"`` for degrees) or, with ``rotation_format="quat_xyzw"``,
``x y z qx qy qz qw``.
"""

from __future__ import annotations

import math

import numpy as np

from reimpl.math import RigidTransform, RotationMatrix
from reimpl.multibody import kinematics
from reimpl.multibody.kinematics import Pose
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["PoseGraph", "read_pose", "transform"]

WORLD = "world"


def read_pose(element: XmlElement) -> tuple[str | None, Pose]:
    """(relative_to, X_RF) of ``element``'s first ``<pose>`` (None and identity without one)."""
    poses = children(element, "pose")
    if not poses:
        return None, kinematics.identity()
    pose = poses[0]
    values = [float(v) for v in (pose.text or "").split()] or [0.0] * 6
    p = np.array(values[:3], dtype=float)
    if pose.get("rotation_format") == "quat_xyzw":
        x, y, z, w = values[3:7]
        R = kinematics.rotation_from_quaternion([w, x, y, z])
    else:
        rpy = values[3:6]
        if pose.get("degrees", "false").strip().lower() in {"true", "1"}:
            rpy = [math.radians(angle) for angle in rpy]
        R = kinematics.rotation_from_rpy(rpy)
    return pose.get("relative_to") or None, (R, p)


def transform(X: Pose) -> RigidTransform:
    return RigidTransform(RotationMatrix(X[0]), X[1])


class PoseGraph:
    """Named frames, each posed in another: X_WF = X_WR · X_RF, resolved on demand."""

    def __init__(self) -> None:
        #: frame -> (R, X_RF, what names it, for messages)
        self._edges: dict[str, tuple[str, Pose]] = {}
        self._world: dict[str, Pose] = {WORLD: kinematics.identity()}

    def add(self, name: str, relative_to: str, X_RF: Pose) -> None:
        self._edges[name] = (relative_to, X_RF)

    def has(self, name: str) -> bool:
        return name in self._edges or name in self._world

    def X_W(self, name: str) -> Pose:
        """X_WF: the chain of ``relative_to`` frames down to the world.

        A chain that returns to a frame is libsdformat's cycle error.
        """
        chain: list[str] = []
        while name not in self._world:
            if name in chain:
                model = scoped.split(name)[0]
                raise Diagnostics(None).error(
                    f"PoseRelativeToGraph cycle detected, already visited vertex "
                    f"[{scoped.join(model, scoped.split(name)[1])}]."
                )
            chain.append(name)
            name = self._edges[name][0]
        X_WR = self._world[name]
        for frame in reversed(chain):
            X_WR = kinematics.compose(X_WR, self._edges[frame][1])
            self._world[frame] = X_WR
        return X_WR

    def X_AB(self, a: str, b: str) -> Pose:
        """X_AB = X_WA⁻¹ · X_WB."""
        return kinematics.compose(kinematics.invert(self.X_W(a)), self.X_W(b))
