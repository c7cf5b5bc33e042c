"""MuJoCo ``<joint>``, as Drake 1.51.1 reads it (detail_mujoco_parser.cc, measured).

A joint joins its body (the child C) to the parent body P. It takes its class's
defaults (``class``, else the body's ``childclass``, else ``main``), then:

* ``name`` defaults to ``<parent>-<child>``; ``pos`` (in C, default zero) is
  the joint frame J: X_CJ = (I, pos), X_PJ = X_PC·X_CJ; ``axis`` (in C, default
  +z) is normalized; ``damping`` defaults to 0; ``type`` to ``hinge``;
* limits (``range``, 2 numbers, and ``limited``): ``true`` or ``false``; ``auto``
  (the default) is limited when a range is given, if the compiler's
  ``autolimits`` is on, and an error (``The 'range' attribute was specified but
  'autolimits' is disabled.``) if it is off; other text is ``The 'limited'
  attribute must be one of 'true', 'false', or 'auto'.``. A limited joint
  without a range is limited to [0, 0].

==========  =================================================================
 type        what Drake adds (frames ``<name>_parent`` at X_PJ on P and
             ``<name>_child`` at X_CJ on C, then the joint)
==========  =================================================================
 free        nothing: C floats, its default pose X_WC (a ``damping`` is warned
             about: ``Damping was specified for the 'free' joint N, but is not
             supported for free bodies.``)
 ball        BallRpyJoint(damping); a limited range is warned about
 slide       PrismaticJoint(axis, damping) with X_CJ moved by ``ref``·axis; the
             range as position limits; default position ``ref``
 hinge       RevoluteJoint(axis, damping) with X_CJ turned by ``ref`` about the
             axis; ``ref`` and the range in the compiler's angle unit
 other       ``Unknown joint type T``
==========  =================================================================

The joint's constructor checks its axis and damping (with the limits ±∞);
limits with lower > upper then fail set_position_limits (a SystemExit, as
pydrake 1.51.1 reports Drake's joint.h:421). ``armature`` is kept for the
actuators. ``group``, ``springdamper``, ``stiffness``, ``actuatorfrcrange``,
``actuatorfrclimited``, ``actuatorgravcomp``, ``springref``, ``frictionloss``
and ``user`` are warned about.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _mjcf_values as values
from reimpl.multibody.parsing._joint_frame_instance import parent_frame_instance
from reimpl.multibody.parsing._mjcf_context import MjcfContext
from reimpl.multibody.parsing._mjcf_defaults import apply_defaults, class_of
from reimpl.multibody.parsing._mjcf_pose import rotation_from_angle_axis
from reimpl.multibody.parsing._xml import XmlElement
from reimpl.multibody.tree import BallRpyJoint, FixedOffsetFrame, PrismaticJoint, RevoluteJoint

__all__ = ["JointEnds", "read_joint", "read_limits"]

_UNSUPPORTED = (
    "group",
    "springdamper",
    "stiffness",
    "actuatorfrcrange",
    "actuatorfrclimited",
    "actuatorgravcomp",
    "springref",
    "frictionloss",
    "user",
)
_SET_POSITION_LIMITS = (
    "Failure at bazel-out/k8-opt/bin/external/drake+/multibody/tree/_virtual_includes/"
    "multibody_tree_core/drake/multibody/tree/joint.h:421 in set_position_limits(): condition "
    "'(lower_limits.array() <= upper_limits.array()).all()' failed."
)


def read_limits(
    context: MjcfContext, node: XmlElement, range_name: str, limited_name: str
) -> tuple[bool, list[float]]:
    """ParseLimits: (limited, [lower, upper]) with [0, 0] when no range is given."""
    limited_text = node.get(limited_name)
    if limited_text is None:
        limited_text = "auto"
    given = values.vector(node, range_name, 2)
    limits = given if given is not None else [0.0, 0.0]
    if limited_text in ("true", "false"):
        return limited_text == "true", limits
    if limited_text != "auto":
        raise context.d.error(
            node,
            f"The '{limited_name}' attribute must be one of 'true', 'false', or 'auto'.",
        )
    if context.compiler.autolimits:
        return given is not None, limits
    if given is not None:
        raise context.d.error(
            node, f"The '{range_name}' attribute was specified but 'autolimits' is disabled."
        )
    return False, limits


@dataclass(frozen=True)
class JointEnds:
    """The bodies a joint joins: C's pose in the world and in P (X_WC, X_PC)."""

    parent: Any
    child: Any
    X_WC: RigidTransform
    X_PC: RigidTransform


class _Joint:
    """One ``<joint>`` being added between ``ends.parent`` and ``ends.child``."""

    def __init__(self, context: MjcfContext, node: XmlElement, ends: JointEnds, name: str) -> None:
        self.context, self.node, self.name = context, node, name
        self.parent, self.child = ends.parent, ends.child
        pos = values.vector(node, "pos", 3) or [0.0, 0.0, 0.0]
        self.X_CJ = RigidTransform(np.asarray(pos, dtype=float))
        self.X_PJ = ends.X_PC.multiply(self.X_CJ)
        axis = np.asarray(values.vector(node, "axis", 3) or [0.0, 0.0, 1.0], dtype=float)
        norm = math.sqrt(float(axis @ axis))
        self.axis = axis / norm if norm > 0 else axis
        damping = values.scalar(node, "damping")
        self.damping = 0.0 if damping is None else damping

    def _ref(self, in_degrees: bool) -> float:
        ref = values.scalar(self.node, "ref")
        if ref is None:
            return 0.0
        return ref * (math.pi / 180.0) if in_degrees and self.context.compiler.degrees else ref

    def add(self, make: Callable[[Any, Any], Any], limits: list[float] | None = None) -> Any:
        """MultibodyPlant::AddJoint's frames and joint, then set_position_limits."""
        plant, instance = self.context.plant, self.child.model_instance()
        frame_on_parent = plant.AddFrame(
            FixedOffsetFrame(
                f"{self.name}_parent",
                self.parent.body_frame(),
                self.X_PJ,
                parent_frame_instance(instance),
            )
        )
        frame_on_child = plant.AddFrame(
            FixedOffsetFrame(f"{self.name}_child", self.child.body_frame(), self.X_CJ, instance)
        )
        joint = make(frame_on_parent, frame_on_child)
        if limits is not None:
            if not limits[0] <= limits[1]:
                plant.AddJoint(joint)  # N.B. Drake adds it, then fails to limit it.
                raise SystemExit(_SET_POSITION_LIMITS)
            joint = make(frame_on_parent, frame_on_child, *limits)
        return plant.AddJoint(joint)

    def ball(self, limited: bool, limits: list[float]) -> Any:
        joint = self.add(lambda p, c: BallRpyJoint(self.name, p, c, self.damping))
        if limited:
            self.context.d.warn_unsupported_attributes(self.node, ("range",))
        return joint

    def _one_dof(self, kind: type, limited: bool, limits: list[float], ref: float) -> Any:
        def make(p: Any, c: Any, lower: float = -math.inf, upper: float = math.inf) -> Any:
            return kind(self.name, p, c, self.axis, lower, upper, self.damping)

        joint = self.add(make, limits if limited else None)
        joint.set_default_positions(np.array([ref]))
        return joint

    def slide(self, limited: bool, limits: list[float]) -> Any:
        ref = self._ref(in_degrees=False)
        self.X_CJ = self.X_CJ.multiply(RigidTransform(ref * self.axis))
        return self._one_dof(PrismaticJoint, limited, limits, ref)

    def hinge(self, limited: bool, limits: list[float]) -> Any:
        ref = self._ref(in_degrees=True)
        turn = RigidTransform(rotation_from_angle_axis(ref, list(self.axis)), np.zeros(3))
        self.X_CJ = self.X_CJ.multiply(turn)
        if limited and self.context.compiler.degrees:
            limits = [v * (math.pi / 180.0) for v in limits]
        return self._one_dof(RevoluteJoint, limited, limits, ref)


def read_joint(
    context: MjcfContext, node: XmlElement, ends: JointEnds, child_class: str = ""
) -> None:
    """ParseJoint: adds the joint (or floats the child, for a free joint)."""
    name = node.get("name")
    if name is None:
        name = f"{ends.parent.name()}-{ends.child.name()}"
    apply_defaults(context, "joint", class_of(node, child_class), node)
    joint = _Joint(context, node, ends, name)
    kind = node.get("type")
    if kind is None:
        kind = "hinge"
    limited, limits = read_limits(context, node, "range", "limited")
    added: Any = None
    if kind == "free":
        if joint.damping != 0.0:
            context.d.warning(
                node,
                f"Damping was specified for the 'free' joint {name}, but is not supported for "
                "free bodies.",
            )
        context.plant.SetDefaultFloatingBaseBodyPose(ends.child, ends.X_WC)
    elif kind in ("ball", "slide", "hinge"):
        added = getattr(joint, kind)(limited, limits)
    else:
        raise context.d.error(node, f"Unknown joint type {kind}")
    armature = values.scalar(node, "armature") if added is not None else None
    if armature is not None:
        context.armature[int(added.index())] = armature
    context.d.warn_unsupported_attributes(node, _UNSUPPORTED)
