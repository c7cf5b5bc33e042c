"""The model instance of the ``<joint>_parent`` frame a parser makes for a joint.

A joint whose frame on its parent body is offset gets a FixedOffsetFrame named
``<joint>_parent`` (MultibodyTree::AddJoint). Since Drake 1.19 that frame
belongs to the joint's model instance (its child body's); up to 1.18 it belongs
to the parent body's, so a URDF joint from the world makes
``WorldModelInstance::<joint>_parent`` (joint-parent-frame-in-joint-instance-
since-1.19: measured on pydrake 1.17.0/1.18.0 and 1.19.0; Drake #19724).
The ``<joint>_child`` frame is on the child body, in the joint's instance, on
every release.
"""

from __future__ import annotations

from typing import Any

from reimpl._release import release

__all__ = ["parent_frame_instance"]

_IN_JOINT_INSTANCE = release.has("joint-parent-frame-in-joint-instance-since-1.19")


def parent_frame_instance(joint_instance: Any) -> Any:
    """The instance to give ``<joint>_parent``: the joint's, or None (the parent body's)."""
    return joint_instance if _IN_JOINT_INSTANCE else None
