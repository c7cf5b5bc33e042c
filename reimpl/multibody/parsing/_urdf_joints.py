"""URDF ``<joint>`` and ``<drake:joint>``, and their ``<mimic>`` (Drake 1.51.1, measured).

A joint element reads, in Drake's order (the first error stops the parse):

1. ``drake_ignore="true"`` (exactly): skipped unread (its ``<mimic>`` is still
   read, see below); ``<calibration>`` and ``<safety_controller>`` warned.
2. ``name`` and ``type`` attributes, ``<parent link>``, ``<child link>``
   (``joint tag is missing name attribute``, ``joint 'j' is missing type
   attribute``, ``joint 'j' doesn't have a parent node!``, ``joint j's parent
   does not have a link attribute!`` at the ``<parent>`` line, ...). If any of
   the four is empty the joint is skipped silently.
3. Both links must be in the robot or be ``world`` (``Could not find link
   named 'x' with model instance ID 2 for element 'j'.``, at line 1).
4. ``<origin>`` (X_PF); ``<axis xyz>`` (default x), for every type but fixed,
   floating and ball: a norm below 1e-8 is ``Joint 'j' axis is zero.  Don't
   do that.`` at the ``<axis>`` line; then normalized.
5. The type, by the table below: the element must be ``<joint>`` for a
   standard type and ``<drake:joint>`` for a custom one (planar may be
   either); an unknown type is ``Joint 'j' has unrecognized type: 't'``.

===========  ========  ===============================================  ==============
 type         element   reads                                            Drake joint
===========  ========  ===============================================  ==============
 revolute     joint     ``<limit>`` lower, upper, velocity,              revolute
 continuous             ``drake:acceleration``, effort; ``<dynamics>``
 prismatic    joint     the same                                         prismatic
 fixed        joint     --                                               weld
 floating     joint     -- (a warning; the child stays free)             none
 ball         custom    ``<dynamics>``                                   ball_rpy
 universal    custom    ``<dynamics>``                                   universal
 planar       either    ``<dynamics damping>`` (three numbers)           planar
 screw        custom    ``<dynamics>``, ``<drake:screw_thread_pitch>``   screw
 curvilinear  custom    ``<dynamics>``, ``<drake:initial_tangent>``,     curvilinear
                        ``<drake:plane_normal>``, ``<drake:is_periodic>``,
                        ``<drake:curves>``
===========  ========  ===============================================  ==============

Limits default to ±∞ and damping to 0; they go to the joint's constructor
(position limits, damping), then velocity limits ±velocity and acceleration
limits ±acceleration are set (a negative one fails Drake's DRAKE_DEMAND:
SystemExit). ``<dynamics>`` warns of a non-zero ``friction`` and of any
``coulomb_window``. Each joint gets a frame ``<name>_parent`` at X_PF on the
parent body, in the child's model instance (since 1.55 only where X_PF is not
exactly the identity); a planar joint also turns both its
frames so that z is the axis (``<name>_child`` on the child), see
``planar_rotation``.

Then every ``<joint>``/``<drake:joint>``'s ``<mimic joint>`` is read in
document order (ignored or skipped joints included): the mimicked joint must
exist and differ from this one, ``multiplier`` and ``offset`` are numbers; a
joint that was not made (floating) or has several dofs is warned about and
ignored; a mismatch of dofs is an error. (reimpl's plant has no coupler
constraints: a valid mimic adds nothing.) Up to 1.50 a ``<mimic>`` is read only on a
discrete plant whose contact solver is SAP (the default since 1.37); elsewhere it is
warned about and ignored (``mimic_ignored``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from reimpl._release import release
from reimpl.math import RigidTransform, RotationMatrix
from reimpl.multibody.kinematics import rotation_about
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._joint_frame_instance import parent_frame_instance
from reimpl.multibody.parsing._urdf_values import Values, origin, vector
from reimpl.multibody.parsing._xml import XmlElement, children
from reimpl.multibody.tree import (
    BallRpyJoint,
    CurvilinearJoint,
    FixedOffsetFrame,
    PiecewiseConstantCurvatureTrajectory,
    PlanarJoint,
    PrismaticJoint,
    RevoluteJoint,
    ScrewJoint,
    UniversalJoint,
    WeldJoint,
)

__all__ = ["JointReader", "planar_rotation"]

_ZERO_AXIS = 1e-8  # Measured: |axis| = 1e-8 passes, 1e-9 is "zero".
#: Types whose <axis> Drake does not read.
_NO_AXIS = frozenset({"fixed", "floating", "ball"})
_JOINT_H = (
    "Failure at bazel-out/k8-opt/bin/external/drake+/multibody/tree/_virtual_includes/"
    "multibody_tree_core/drake/multibody/tree/joint.h"
)
#: Joint method -> (line in joint.h, as pydrake 1.51.1 reports its DRAKE_DEMAND).
_LIMIT_SETTERS = {"set_velocity_limits": 435, "set_acceleration_limits": 449}


def planar_rotation(axis: tuple[float, float, float]) -> RotationMatrix:
    """R with R·z = n = axis/|axis|: about z × n by the angle from z to n (about x if n = ±z).

    Drake's MakeClosestRotationToIdentityFromUnitZ (measured within 6e-16 for
    twelve axes).
    """
    n = np.array(axis, dtype=float) / math.hypot(*axis)
    cross = np.array([-n[1], n[0], 0.0])  # z × n
    sine = float(np.linalg.norm(cross))
    about = cross / sine if sine > 0 else np.array([1.0, 0.0, 0.0])
    return RotationMatrix(rotation_about(about, math.atan2(sine, n[2])))


@dataclass
class _Joint:
    """One joint element being read: its names, bodies, pose and axis."""

    element: XmlElement
    name: str
    type: str
    child_link: str
    parent: Any
    child: Any
    X_PF: RigidTransform
    axis: tuple[float, float, float]
    damping: float = 0.0
    effort: float = math.inf


@dataclass(frozen=True)
class _Limits:
    lower: float = -math.inf
    upper: float = math.inf
    velocity: float = math.inf
    acceleration: float = math.inf
    effort: float = math.inf


class JointReader:
    """Reads one robot's joints into ``plant`` (``instance``); ``body`` finds a link."""

    def __init__(
        self,
        plant: Any,
        instance: Any,
        diagnostics: Diagnostics,
        body: Callable[[str, str], Any],
    ) -> None:
        self.plant, self.instance, self.diagnostics = plant, instance, diagnostics
        self.values = Values(diagnostics)
        self.body = body
        #: joint name -> effort limit, for the transmissions
        self.efforts: dict[str, float] = {}

    # ------------------------------------------------------------ the joint
    def read(self, element: XmlElement) -> None:
        if element.get("drake_ignore") == "true":
            return
        for tag in ("calibration", "safety_controller"):
            warn_unsupported_child(self.diagnostics, element, tag)
        keys = self._key_params(element)
        if keys is None:
            return
        name, joint_type, parent_link, child_link = keys
        parent = self.body(parent_link, name)
        child = self.body(child_link, name)
        origins = children(element, "origin")
        X_PF = origin(origins[0]) if origins else RigidTransform()
        joint = _Joint(
            element, name, joint_type, child_link, parent, child, X_PF, self._axis(element, keys)
        )
        kind = _KINDS.get(joint_type)
        if joint_type == "curvilinear" and not release.has("curvilinear-joints-since-1.38"):
            kind = None
        if kind is None:
            raise self.diagnostics.error(
                f"Joint '{name}' has unrecognized type: '{joint_type}'", element.line
            )
        self._check_element(joint, kind.custom)
        kind.add(self, joint)
        self.efforts[name] = joint.effort

    def _key_params(self, element: XmlElement) -> tuple[str, str, str, str] | None:
        """Drake's ParseJointKeyParams; None when one of the four is empty."""
        d = self.diagnostics
        name = element.get("name")
        if name is None:
            raise d.error("joint tag is missing name attribute", element.line)
        joint_type = element.get("type")
        if joint_type is None:
            raise d.error(f"joint '{name}' is missing type attribute", element.line)
        links = []
        for end in ("parent", "child"):
            nodes = children(element, end)
            if not nodes:
                raise d.error(f"joint '{name}' doesn't have a {end} node!", element.line)
            link = nodes[0].get("link")
            if link is None:
                raise d.error(
                    f"joint {name}'s {end} does not have a link attribute!", nodes[0].line
                )
            links.append(link)
        keys = (name, joint_type, links[0], links[1])
        return keys if all(keys) else None

    def _axis(
        self, element: XmlElement, keys: tuple[str, str, str, str]
    ) -> tuple[float, float, float]:
        name, joint_type = keys[0], keys[1]
        axes = children(element, "axis")
        if not axes or joint_type in _NO_AXIS:
            return (1.0, 0.0, 0.0)
        xyz = vector(axes[0], "xyz", 3) or [1.0, 0.0, 0.0]
        norm = math.hypot(*xyz)
        if norm < _ZERO_AXIS:
            raise self.diagnostics.error(
                f"Joint '{name}' axis is zero.  Don't do that.", axes[0].line
            )
        x, y, z = (v / norm for v in xyz)
        return (x, y, z)

    def _check_element(self, joint: _Joint, custom: bool | None) -> None:
        """A standard type must be a <joint>, a custom one a <drake:joint> (None: either)."""
        is_custom = joint.element.tag == "drake:joint"
        if custom is None or custom == is_custom:
            return
        kind = "custom" if custom else "standard"
        element = "<drake:joint>" if custom else "<joint>"
        raise self.diagnostics.error(
            f"Joint {joint.name} of type {joint.type} is a {kind} joint type, and should be a "
            f"{element}",
            joint.element.line,
        )

    # --------------------------------------------------------- sub-elements
    def _limits(self, element: XmlElement) -> _Limits:
        nodes = children(element, "limit")
        if not nodes:
            return _Limits()
        read = self.values.scalar
        defaults = _Limits()
        values = [
            read(nodes[0], attribute)
            for attribute in ("lower", "upper", "velocity", "drake:acceleration", "effort")
        ]
        fallback = (
            defaults.lower,
            defaults.upper,
            defaults.velocity,
            defaults.acceleration,
            defaults.effort,
        )
        return _Limits(*(v if v is not None else f for v, f in zip(values, fallback, strict=True)))

    def _dynamics(self, element: XmlElement) -> float:
        """Drake's ParseJointDynamics: the damping (0 by default), with its warnings."""
        nodes = children(element, "dynamics")
        if not nodes:
            return 0.0
        node, d = nodes[0], self.diagnostics
        damping = self.values.scalar(node, "damping")
        friction = self.values.scalar(node, "friction")
        if friction is not None and friction != 0.0:
            d.warning(
                "A joint has specified a non-zero value for the 'friction' attribute of a "
                "joint/dynamics tag. MultibodyPlant does not currently support non-zero joint "
                "friction.",
                node.line,
            )
        if self.values.scalar(node, "coulomb_window") is not None:
            d.warning(
                "A joint has specified a value for the 'coulomb_window' attribute of a <joint> "
                "tag. Drake no longer makes use of that attribute; all instances will be "
                "ignored.",
                node.line,
            )
        return damping if damping is not None else 0.0

    # ------------------------------------------------------------- the kinds
    def _add(
        self,
        joint: _Joint,
        make: Callable[[Any, Any], Any],
        X_BM: RigidTransform | None = None,
        X_PF: RigidTransform | None = None,
    ) -> Any:
        """MultibodyPlant::AddJoint: the ``_parent`` (and ``_child``) frames, then the joint.

        Since 1.55 (urdf-identity-joint-frame-elided-since-1.55) a joint whose X_PF is
        exactly the identity is made on the parent body's frame, with no ``_parent`` frame.
        """
        instance = joint.child.model_instance()
        X_PF = X_PF or joint.X_PF
        frame_on_parent = joint.parent.body_frame()
        elided = X_PF.IsExactlyIdentity()  # drake#24687
        if not (elided and release.has("urdf-identity-joint-frame-elided-since-1.55")):
            frame_on_parent = FixedOffsetFrame(
                f"{joint.name}_parent", frame_on_parent, X_PF, parent_frame_instance(instance)
            )
            self.plant.AddFrame(frame_on_parent)
        frame_on_child = joint.child.body_frame()
        if X_BM is not None:
            frame_on_child = FixedOffsetFrame(f"{joint.name}_child", frame_on_child, X_BM, instance)
            self.plant.AddFrame(frame_on_child)
        return self.plant.AddJoint(make(frame_on_parent, frame_on_child))

    def _one_dof(self, joint: _Joint, kind: type) -> None:
        """Revolute (and continuous) or prismatic: limits, dynamics, then the joint."""
        limits = self._limits(joint.element)
        joint.damping = self._dynamics(joint.element)
        joint.effort = limits.effort
        self._add(
            joint,
            lambda p, c: kind(
                name=joint.name,
                frame_on_parent=p,
                frame_on_child=c,
                axis=np.array(joint.axis),
                pos_lower_limit=limits.lower,
                pos_upper_limit=limits.upper,
                damping=joint.damping,
            ),
        )
        for setter, bound in (
            ("set_velocity_limits", limits.velocity),
            ("set_acceleration_limits", limits.acceleration),
        ):
            if not -bound <= bound:  # N.B. Drake sets (-bound, bound).
                raise SystemExit(
                    f"{_JOINT_H}:{_LIMIT_SETTERS[setter]} in {setter}(): condition "
                    "'(lower_limits.array() <= upper_limits.array()).all()' failed."
                )

    def _revolute(self, joint: _Joint) -> None:
        self._one_dof(joint, RevoluteJoint)

    def _prismatic(self, joint: _Joint) -> None:
        self._one_dof(joint, PrismaticJoint)

    def _fixed(self, joint: _Joint) -> None:
        self._add(
            joint,
            lambda p, c: WeldJoint(
                name=joint.name, frame_on_parent_F=p, frame_on_child_M=c, X_FM=RigidTransform()
            ),
        )

    def _floating(self, joint: _Joint) -> None:
        self.diagnostics.warning(
            f"Joint '{joint.name}' specified as type floating which is not supported by "
            f"MultibodyPlant.  Leaving '{joint.child_link}' as a free body.",
            joint.element.line,
        )

    def _ball(self, joint: _Joint) -> None:
        damping = self._dynamics(joint.element)
        self._add(
            joint,
            lambda p, c: BallRpyJoint(
                name=joint.name, frame_on_parent=p, frame_on_child=c, damping=damping
            ),
        )

    def _universal(self, joint: _Joint) -> None:
        damping = self._dynamics(joint.element)
        self._add(
            joint,
            lambda p, c: UniversalJoint(
                name=joint.name, frame_on_parent=p, frame_on_child=c, damping=damping
            ),
        )

    def _planar(self, joint: _Joint) -> None:
        nodes = children(joint.element, "dynamics")
        damping = (vector(nodes[0], "damping", 3) if nodes else None) or [0.0, 0.0, 0.0]
        make = lambda p, c: PlanarJoint(  # noqa: E731
            name=joint.name, frame_on_parent=p, frame_on_child=c, damping=np.array(damping)
        )
        if not release.has("urdf-planar-axis-since-1.16"):
            # Up to 1.15 the axis is not read: F at the joint origin, M = B (no _child frame).
            self._add(joint, make)
            return
        X_BM = RigidTransform(planar_rotation(joint.axis))
        self._add(joint, make, X_BM=X_BM, X_PF=joint.X_PF @ X_BM)

    def _screw(self, joint: _Joint) -> None:
        damping = self._dynamics(joint.element)
        pitch = self._screw_pitch(joint.element)
        self._add(
            joint,
            lambda p, c: ScrewJoint(
                name=joint.name,
                frame_on_parent=p,
                frame_on_child=c,
                axis=np.array(joint.axis),
                screw_pitch=pitch,
                damping=damping,
            ),
        )

    def _screw_pitch(self, element: XmlElement) -> float:
        nodes = children(element, "drake:screw_thread_pitch")
        if not nodes:
            raise self.diagnostics.error(
                "A screw joint is missing the <drake:screw_thread_pitch> tag.", element.line
            )
        pitch = self.values.scalar(nodes[0], "value")
        if pitch is None:
            raise self.diagnostics.error(
                "A screw joint has a <drake:screw_thread_pitch> tag that is missing the 'value' "
                "attribute.",
                nodes[0].line,
            )
        return pitch

    def _curvilinear(self, joint: _Joint) -> None:
        element = joint.element
        damping = self._dynamics(element)
        tangent = self._child_vector(element, "drake:initial_tangent", [1.0, 0.0, 0.0])
        normal = self._child_vector(element, "drake:plane_normal", [0.0, 0.0, 1.0])
        periodic_nodes = children(element, "drake:is_periodic")
        periodic = bool(periodic_nodes) and periodic_nodes[0].get("value", "") == "true"
        breaks, rates = self._curves(element)
        path = PiecewiseConstantCurvatureTrajectory(
            breaks, rates, tangent, normal, initial_position=[0.0, 0.0, 0.0], is_periodic=periodic
        )
        self._add(
            joint,
            lambda p, c: CurvilinearJoint(
                name=joint.name,
                frame_on_parent=p,
                frame_on_child=c,
                curvilinear_path=path,
                damping=damping,
            ),
        )

    @staticmethod
    def _child_vector(element: XmlElement, tag: str, default: list[float]) -> list[float]:
        nodes = children(element, tag)
        return (vector(nodes[0], "xyz", 3) if nodes else None) or default

    def _curves(self, element: XmlElement) -> tuple[list[float], list[float]]:
        """Drake's ParseCurvilinearJointCurves: breaks (from 0) and turning rates."""
        d = self.diagnostics
        roots = children(element, "drake:curves")
        if not roots:
            raise d.error("A curvilinear joint is missing the <drake:curves> list.", element.line)
        root = roots[0]
        breaks, rates = [0.0], []
        for curve in root:
            assert isinstance(curve, XmlElement)
            reader = _CURVES.get(curve.tag)
            if reader is None:
                raise d.error(
                    f"A curvilinear joint contains an invalid curve node <{curve.tag}>.",
                    root.line,
                )
            length, angle = reader(self, curve)
            breaks.append(breaks[-1] + length)
            rates.append(angle / length if length else math.nan)
        if len(breaks) == 1:
            raise d.error("A curvilinear joint contains an empty curves list.", root.line)
        return breaks, rates

    def _curve_value(self, curve: XmlElement, attribute: str, positive: bool) -> float:
        value = self.values.scalar(curve, attribute)
        name = curve.tag
        if value is None:
            raise self.diagnostics.error(
                f"A curvilinear joint contains a <{name}> that is missing the '{attribute}' "
                "attribute.",
                curve.line,
            )
        if positive and value <= 0.0:
            raise self.diagnostics.error(
                f"A curvilinear joint contains a <{name}> with a zero or negative '{attribute}' "
                "attribute.",
                curve.line,
            )
        return value

    def _line_segment(self, curve: XmlElement) -> tuple[float, float]:
        return self._curve_value(curve, "length", positive=True), 0.0

    def _circular_arc(self, curve: XmlElement) -> tuple[float, float]:
        radius = self._curve_value(curve, "radius", positive=True)
        angle = self._curve_value(curve, "angle", positive=False)
        return abs(angle) * radius, angle

    # ---------------------------------------------------------------- mimic
    def read_mimic(self, element: XmlElement) -> None:
        """Drake's ParseMimicTag (reimpl's plant holds no coupler constraint)."""
        nodes = children(element, "mimic")
        if not nodes:
            return
        mimic, d = nodes[0], self.diagnostics
        name = element.get("name", "")
        if mimic_ignored(self.plant.time_step()):
            d.warning(
                f"Joint '{name}' specifies a mimic element that will be ignored. Mimic "
                "elements are currently only supported by MultibodyPlant with a discrete time "
                "step and using DiscreteContactSolver::kSap.",
                mimic.line,
            )
            return
        other = mimic.get("joint")
        if other is None:
            raise d.error(
                f"Joint '{name}' mimic element is missing the required 'joint' attribute.",
                mimic.line,
            )
        if not self.plant.HasJointNamed(other, self.instance):
            raise d.error(
                f"Joint '{name}' mimic element specifies joint '{other}' which does not exist.",
                mimic.line,
            )
        if other == name:
            raise d.error(
                f"Joint '{name}' mimic element specifies joint '{other}'. Joints cannot mimic "
                "themselves.",
                mimic.line,
            )
        self.values.scalar(mimic, "multiplier")
        self.values.scalar(mimic, "offset")
        if not self.plant.HasJointNamed(name, self.instance):
            d.warning(
                "Drake only supports the mimic element for single-dof joints. The mimic element "
                f"in joint '{name}' will be ignored.",
                mimic.line,
            )
            return
        dofs = self.plant.GetJointByName(name, self.instance).num_velocities()
        other_dofs = self.plant.GetJointByName(other, self.instance).num_velocities()
        if dofs != other_dofs:
            raise d.error(
                f"Joint '{name}' which has {dofs} DOF cannot mimic joint '{other}' which has "
                f"{other_dofs} DOF.",
                mimic.line,
            )
        if dofs != 1:
            d.warning(
                "Drake only supports the mimic element for single-dof joints. The joint "
                f"'{name}' (with {dofs} dofs) is attempting to mimic joint '{other}' (with "
                f"{other_dofs} dofs). The mimic element will be ignored.",
                mimic.line,
            )


@dataclass(frozen=True)
class _Kind:
    """A URDF joint type: custom (True), standard (False) or either (None), and its reader."""

    custom: bool | None
    add: Callable[[JointReader, _Joint], None]


#: URDF joint type -> how Drake reads it.
_KINDS: dict[str, _Kind] = {
    "revolute": _Kind(False, JointReader._revolute),
    "continuous": _Kind(False, JointReader._revolute),
    "fixed": _Kind(False, JointReader._fixed),
    "prismatic": _Kind(False, JointReader._prismatic),
    "floating": _Kind(False, JointReader._floating),
    "ball": _Kind(True, JointReader._ball),
    # Up to 1.12 planar is custom only (urdf-planar-joint-element-since-1.13).
    "planar": _Kind(
        None if release.has("urdf-planar-joint-element-since-1.13") else True,
        JointReader._planar,
    ),
    "screw": _Kind(True, JointReader._screw),
    "universal": _Kind(True, JointReader._universal),
    "curvilinear": _Kind(True, JointReader._curvilinear),
}

#: <drake:curves> child -> (length, angle) reader.
_CURVES: dict[str, Callable[[JointReader, XmlElement], tuple[float, float]]] = {
    "drake:line_segment": JointReader._line_segment,
    "drake:circular_arc": JointReader._circular_arc,
}


def warn_unsupported_child(d: Diagnostics, element: XmlElement, tag: str) -> None:
    """Drake's WarnUnsupportedElement: a warning at the first ``tag`` child, if any."""
    nodes = children(element, tag)
    if nodes:
        d.warning(
            f"The tag '{tag}' found as a child of '{element.tag}' is currently unsupported and "
            "will be ignored.",
            nodes[0].line,
        )


def mimic_ignored(time_step: float) -> bool:
    """Whether Drake ignores (with a warning) a ``<mimic>`` on a plant of ``time_step``.

    Up to 1.50 Drake reads it only on a discrete plant using DiscreteContactSolver::kSap,
    a discrete plant's default since 1.37 (reimpl's plant has no solver setting): a
    continuous plant ignores it up to 1.50 (urdf-mimic-continuous-since-1.51) and a
    discrete one up to 1.36 (urdf-mimic-discrete-since-1.37).
    """
    if time_step == 0.0:
        return not release.has("urdf-mimic-continuous-since-1.51")
    return not release.has("urdf-mimic-discrete-since-1.37")
