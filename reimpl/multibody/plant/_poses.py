"""Kinematics: the poses of bodies and frames at a context's q, and free bodies' poses.

Drake counterpart: MultibodyPlant's pose methods (multibody_plant.h/.cc).
A joint J joins frame F on its parent body P to frame M on its child body C,
and its positions set ``X_FM(q_J)`` (see reimpl.multibody.kinematics):

    X_PC = X_PF · X_FM(q_J) · X_MC            X_WC = X_WP · X_PC

- ``EvalBodyPoseInWorld(B)`` is X_WB, composed down the forest from the
  world (cached in the context while q is unchanged);
  ``CalcRelativeTransform(A, B)`` is X_AB = X_WA⁻¹ · X_WB.
- A free body is one a floating joint (quaternion or rpy) places:
  ``SetFreeBodyPose``/``GetFreeBodyPose`` write and read that joint's X_FM
  in a context; ``SetDefaultFreeBodyPose`` sets the default (kept, and given
  to the floating joint Finalize adds); anything else is ``Body 'B' is not a
  free body.``
"""

from __future__ import annotations

from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.math import RigidTransform, RotationMatrix
from reimpl.multibody import kinematics
from reimpl.multibody._errors import MultibodyPlantError
from reimpl.multibody.plant._positions import Positions
from reimpl.multibody.plant._topology import Topology
from reimpl.multibody.tree import Frame, RigidBody
from reimpl.systems.framework import Context

__all__ = ["Poses", "as_pose", "as_rigid_transform"]

_OWNER = "reimpl.multibody.plant.MultibodyPlant"
#: Where a plant context caches its body poses (Context._values).
_BODY_POSES = "X_WB"


def as_pose(X: RigidTransform) -> kinematics.Pose:
    return X.rotation().matrix(), X.translation()


def as_rigid_transform(X: kinematics.Pose) -> RigidTransform:
    return RigidTransform(RotationMatrix(X[0]), X[1])


class Poses(Positions, Topology):
    """Body and frame poses at a context's q; the free bodies' (default) poses."""

    def __init__(self) -> None:
        super().__init__()
        #: body index -> X_PB given by SetDefaultFreeBodyPose.
        self._default_free_body_poses: dict[int, RigidTransform] = {}

    def _lay_out_positions(self) -> None:
        """And the fixed poses X_PF, X_MC kinematics composes."""
        super()._lay_out_positions()
        self._X_PF = [as_pose(j.frame_on_parent().GetFixedPoseInBodyFrame()) for j in self._joints]
        self._X_MC = [
            kinematics.invert(as_pose(j.frame_on_child().GetFixedPoseInBodyFrame()))
            for j in self._joints
        ]

    def _body_poses(self, context: Context) -> list[kinematics.Pose]:
        """X_WB of every body at the context's q (cached while q is unchanged)."""
        q = self._context_positions(context)
        key = q.tobytes()
        cached = context._values.get(_BODY_POSES)
        if cached is not None and cached[0] == key:
            return cached[1]  # type: ignore[no-any-return]
        assert self._forest is not None
        joints = self._joints

        def joint_X_FM(j: int) -> kinematics.Pose:
            joint = joints[j]
            start = joint.position_start()
            return kinematics.X_FM(joint, q[start : start + joint.num_positions()])

        poses = kinematics.body_poses(
            self._forest, len(self._bodies), joint_X_FM, self._X_PF, self._X_MC
        )
        context._values[_BODY_POSES] = (key, poses)
        return poses

    def EvalBodyPoseInWorld(self, context: Context, body_B: RigidBody) -> RigidTransform:
        """X_WB at the context's positions."""
        return as_rigid_transform(self._body_poses(context)[int(body_B.index())])

    def CalcRelativeTransform(
        self, context: Context, frame_A: Frame, frame_B: Frame
    ) -> RigidTransform:
        """X_AB = X_WA⁻¹ · X_WB."""
        return frame_A.CalcPoseInWorld(context).inverse() @ frame_B.CalcPoseInWorld(context)

    def CalcRelativeRotationMatrix(
        self, context: Context, frame_A: Frame, frame_B: Frame
    ) -> RotationMatrix:
        """R_AB, the rotation part of X_AB."""
        return self.CalcRelativeTransform(context, frame_A, frame_B).rotation()

    def _free_body_joint(self, body: RigidBody) -> Any:
        """The floating joint that places ``body`` (Drake's error if none)."""
        assert self._forest is not None
        index = self._forest.inboard_joint(int(body.index()))
        if index is None or self._joints[index].type_name() not in kinematics.FLOATING_TYPES:
            raise MultibodyPlantError(f"Body '{body.name()}' is not a free body.")
        return self._joints[index]

    def SetFreeBodyPose(self, *args: Any, **kwargs: Any) -> None:
        """Sets X_JpJc, the pose of ``body``'s floating joint (X_WB for a free body).

        N.B. pydrake 1.51.1 also takes the deprecated keyword ``X_PB``.
        """

        def set_pose(context: Context, body: RigidBody, **pose: RigidTransform) -> None:
            self._context_positions(context)
            self._free_body_joint(body).SetPose(context, *pose.values())

        context = Param("context", instance_of(Context))
        body = Param("body", instance_of(RigidBody))
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "SetFreeBodyPose",
            tuple(
                Overload((context, body, Param(name, instance_of(RigidTransform))), set_pose)
                for name in ("X_JpJc", "X_PB")
            ),
            args,
            kwargs,
        )

    def GetFreeBodyPose(self, context: Context, body: RigidBody) -> RigidTransform:
        self._context_positions(context)
        return self._free_body_joint(body).GetPose(context)  # type: ignore[no-any-return]

    def SetDefaultFreeBodyPose(self, body: RigidBody, X_PB: RigidTransform) -> None:
        """The default X_WB of a free body: its floating joint's default positions."""
        self._default_free_body_poses[int(body.index())] = RigidTransform(X_PB)
        if self._forest is not None:
            index = self._forest.inboard_joint(int(body.index()))
            joint: Any = None if index is None else self._joints[index]
            if joint is not None and joint.type_name() in kinematics.FLOATING_TYPES:
                joint._set_default_pose(X_PB)

    def GetDefaultFreeBodyPose(self, body: RigidBody) -> RigidTransform:
        return RigidTransform(
            self._default_free_body_poses.get(int(body.index()), RigidTransform())
        )

    def SetDefaultFloatingBaseBodyPose(self, body: RigidBody, X_WB: RigidTransform) -> None:
        self.SetDefaultFreeBodyPose(body, X_WB)

    def GetDefaultFloatingBaseBodyPose(self, body: RigidBody) -> RigidTransform:
        return self.GetDefaultFreeBodyPose(body)
