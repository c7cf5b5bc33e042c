"""SDFormat ``<joint>`` and ``<drake:joint>`` into plant joints (Drake 1.51.1, measured).

A joint J joins the links its ``<parent>`` and ``<child>`` frames are attached
to (``world`` is the world body). Its frames, both in the child's model
instance: ``<J>_parent`` at X_PJ on the parent body (none when X_PJ is
*exactly* the identity: then the parent's body frame) and ``<J>_child`` at
X_CJ; for a world parent X_PJ = X_WM·X_MJ. The checks, per type, in Drake's
order (each an error at the ``<joint>``'s line):

=============================  ==================================================
 type → Drake kind               checks, then what is made
=============================  ==================================================
 fixed → weld                    —
 revolute, prismatic             damping ≥ 0, an ``<axis>``, lower ≤ upper,
                                 ``drake:acceleration`` ≥ 0 (at ``<limit>``)
 continuous → revolute           as revolute, no limits on the joint
 screw                           damping ≥ 0, an ``<axis>``; pitch
                                 ``<screw_thread_pitch>`` (1)
 universal                       damping ≥ 0, both axes, orthogonal; its frames
                                 are turned by R = [a₁ a₂ a₁×a₂]
 ball → ball_rpy                 damping ≥ 0 (an axis is warned about)
 gearbox, revolute2              ``Joint type (gearbox) not supported ...``
=============================  ==================================================

An axis is the unit ``<xyz>`` in J (or in its ``expressed_in`` frame E:
R_JE·xyz, as libsdformat computes it). ``<drake:joint type="planar">`` joins
two frames named by ``<drake:parent>`` and ``<drake:child>`` (scoped names
reach into nested models); ``type="curvilinear"`` follows ``<drake:curves>``
(``<drake:line_segment>``s and ``<drake:circular_arc>``s).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from reimpl._release import release
from reimpl.math import RigidTransform, RotationMatrix
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._joint_frame_instance import parent_frame_instance
from reimpl.multibody.parsing._sdf_dom import Joint
from reimpl.multibody.parsing._sdf_graph import Graphs
from reimpl.multibody.parsing._sdf_include import text_of
from reimpl.multibody.parsing._sdf_load import attached_body
from reimpl.multibody.parsing._sdf_poses import GzPose, rotate
from reimpl.multibody.parsing._sdf_scope import Reporter, Scope
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

__all__ = ["JointAdder"]

_WORLD = "world"
_SUPPORTED = frozenset({
    "axis", "axis2", "child", "drake:rotor_inertia", "drake:gear_ratio",
    "drake:controller_gains", "drake:mimic", "parent", "pose", "screw_thread_pitch",
})  # fmt: skip
if not release.has("sdf-controller-gains-since-1.23"):
    # Up to 1.22 <drake:controller_gains> is an unsupported element (an error).
    _SUPPORTED -= {"drake:controller_gains"}
_LIMIT_ELEMENTS = frozenset(
    {"drake:acceleration", "effort", "lower", "stiffness", "upper", "velocity"}
)
_DRAKE_JOINT_ELEMENTS = frozenset({
    "drake:parent", "drake:child", "drake:damping", "drake:initial_tangent",
    "drake:plane_normal", "drake:is_periodic", "drake:curves", "drake:line_segment",
    "drake:circular_arc", "drake:length", "drake:radius", "drake:angle", "pose",
})  # fmt: skip
#: The <drake:joint> elements of a curvilinear joint (curvilinear-joints-since-1.38).
_CURVILINEAR_ELEMENTS = frozenset({
    "drake:initial_tangent", "drake:plane_normal", "drake:is_periodic", "drake:curves",
    "drake:line_segment", "drake:circular_arc", "drake:length", "drake:radius", "drake:angle",
})  # fmt: skip
_DAMPED = frozenset({"revolute", "prismatic", "screw", "universal", "ball", "continuous"})
#: |a₁·a₂| above which universal axes are not orthogonal (RotationMatrix::IsValid)
_ORTHOGONAL = 1e-10


def number(element: XmlElement, tag: str, default: float) -> float:
    """The first number in ``element``'s ``<tag>``, or ``default``."""
    found = children(element, tag)
    if not found or not (found[0].text or "").strip():
        return default
    return float((found[0].text or "").split()[0])


def _axis_element(joint: XmlElement, index: int, tag: str | None) -> XmlElement:
    """The joint's ``<axis>`` (index 0) or ``<axis2>``, or its ``tag`` child (empty if none)."""
    axes = children(joint, ("axis", "axis2")[index])
    if not axes:
        return XmlElement("none")
    if tag is None:
        return axes[0]
    found = children(axes[0], tag)
    return found[0] if found else XmlElement("none")


def _effort(joint: XmlElement, index: int) -> float:
    """GetEffortLimit: ``<limit><effort>`` (∞ by default; 0 without the axis)."""
    if not children(joint, ("axis", "axis2")[index]):
        return 0.0
    return number(_axis_element(joint, index, "limit"), "effort", np.inf)


def _fmt(value: float) -> str:
    """fmt's ``{}`` of a double: the shortest repr (``0.1``, ``2``)."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _is_exactly_identity(X: RigidTransform) -> bool:
    return bool(np.array_equal(X.GetAsMatrix4(), np.eye(4)))


@dataclass(frozen=True)
class _Ends:
    """The bodies a joint joins, and its frame J in each (X_PJ None: P's body frame)."""

    parent: Any
    X_PJ: RigidTransform | None
    child: Any
    X_CJ: RigidTransform


class JointAdder:
    """AddJointFromSpecification and AddDrakeJointFromSpecification."""

    def __init__(self, plant: Any, graphs: Graphs, reporter: Reporter) -> None:
        self.plant, self.graphs, self.reporter = plant, graphs, reporter

    def add(self, joint: Joint, scope: Scope) -> str:
        """Adds ``joint``; returns its SDFormat type."""
        self.reporter.check_supported(joint.element, _SUPPORTED)
        ends = self._ends(joint, scope)
        kind = joint.type
        if kind in ("gearbox", "revolute2"):
            raise self.reporter.error(
                joint.element, f"Joint type ({kind}) not supported for joint '{joint.name}'."
            )
        damping = self._damping(joint) if kind in _DAMPED else 0.0
        _KINDS[kind](self, joint, scope, ends, damping)
        return kind

    def _ends(self, joint: Joint, scope: Scope) -> _Ends:
        parent_link = (
            _WORLD
            if joint.parent == _WORLD
            else attached_body(self.graphs, scope.vertex, joint.parent)
        )
        parent = scope.body(parent_link)
        child = scope.body(attached_body(self.graphs, scope.vertex, joint.child))
        vertex = scope.vertex_of(joint.name)

        def pose_in(body: Any) -> GzPose:
            target = scope.vertex_of(scope.relative_body_name(body))
            return self.graphs.resolve(scope.frame_scope, vertex, target)

        X_CJ = pose_in(child).transform()
        X_PJ: RigidTransform | None
        if int(parent.index()) == 0:
            X_MJ = self.graphs.resolve(scope.frame_scope, vertex, scope.frame_scope)
            X_PJ = scope.X_WM.multiply(X_MJ.transform())
            if _is_exactly_identity(X_PJ):
                X_PJ = None
        else:
            X = pose_in(parent)
            X_PJ = None if X.is_exactly_identity() else X.transform()
        return _Ends(parent, X_PJ, child, X_CJ)

    def _make(self, joint_class: Any, joint: Joint, ends: _Ends, *arguments: Any) -> Any:
        """MultibodyPlant::AddJoint with bodies: ``<J>_parent`` (if X_PJ) and ``<J>_child``."""
        instance = ends.child.model_instance()
        frame_on_parent = ends.parent.body_frame()
        if ends.X_PJ is not None:
            frame_on_parent = self.plant.AddFrame(
                FixedOffsetFrame(
                    f"{joint.name}_parent",
                    frame_on_parent,
                    ends.X_PJ,
                    parent_frame_instance(instance),
                )
            )
        frame_on_child = self.plant.AddFrame(
            FixedOffsetFrame(f"{joint.name}_child", ends.child.body_frame(), ends.X_CJ, instance)
        )
        return self.plant.AddJoint(
            joint_class(joint.name, frame_on_parent, frame_on_child, *arguments)
        )

    # ------------------------------------------------------------- by kind
    def _fixed(self, joint: Joint, scope: Scope, ends: _Ends, damping: float) -> None:
        self._make(WeldJoint, joint, ends, RigidTransform())

    def _revolute(self, joint: Joint, scope: Scope, ends: _Ends, damping: float) -> None:
        axis = self._axis(joint, scope, 0)
        lower, upper = self._limits(joint)
        if joint.type == "continuous":
            self._make(RevoluteJoint, joint, ends, axis, damping)
        else:
            self._make(RevoluteJoint, joint, ends, axis, lower, upper, damping)
        self._one_axis_warnings(joint)

    def _prismatic(self, joint: Joint, scope: Scope, ends: _Ends, damping: float) -> None:
        axis = self._axis(joint, scope, 0)
        lower, upper = self._limits(joint)
        self._make(PrismaticJoint, joint, ends, axis, lower, upper, damping)
        self._one_axis_warnings(joint)
        dynamics = _axis_element(joint.element, 0, "dynamics")
        if number(dynamics, "spring_stiffness", 0.0) < 0:
            raise self.reporter.error(
                joint.element,
                f"The stiffness specified for joint '{joint.name}' must be non-negative.",
            )

    def _screw(self, joint: Joint, scope: Scope, ends: _Ends, damping: float) -> None:
        """The pitch is ``<screw_thread_pitch>``, else −2π/``<thread_pitch>``, else 1."""
        pitch = number(joint.element, "screw_thread_pitch", np.nan)
        if np.isnan(pitch):
            thread_pitch = number(joint.element, "thread_pitch", np.nan)
            pitch = 1.0 if np.isnan(thread_pitch) else -2 * np.pi / thread_pitch
        axis = self._axis(joint, scope, 0)
        self._make(ScrewJoint, joint, ends, axis, pitch, damping)
        self._one_axis_warnings(joint)

    def _ball(self, joint: Joint, scope: Scope, ends: _Ends, damping: float) -> None:
        self._make(BallRpyJoint, joint, ends, damping)
        element, name = joint.element, joint.name
        if children(element, "axis"):
            self.reporter.warn(
                element,
                "A ball joint axis will be ignored. Only the dynamic parameters and limits will "
                "be considered.",
            )
            if _effort(element, 0) != 0:
                self.reporter.warn(
                    element,
                    f"Actuation (via non-zero effort limits) for ball joint '{name}' is not "
                    "implemented yet and will be ignored.",
                )
        if children(element, "axis2"):
            self.reporter.warn(
                element,
                f"An axis2 may not be specified for ball joint '{name}' and will be ignored",
            )

    def _universal(self, joint: Joint, scope: Scope, ends: _Ends, damping: float) -> None:
        """Frames turned by R_JI = [a₁ a₂ a₁×a₂], so that the joint's x and y are its axes."""
        element = joint.element
        if not (children(element, "axis") and children(element, "axis2")):
            raise self.reporter.error(
                element, f"Both axis and axis2 must be specified for joint '{joint.name}'"
            )
        a1, a2 = self._axis(joint, scope, 0), self._axis(joint, scope, 1)
        a1, a2 = a1 / np.linalg.norm(a1), a2 / np.linalg.norm(a2)
        if abs(float(a1 @ a2)) > _ORTHOGONAL:
            raise self.reporter.error(
                element, f"axis and axis2 must be orthogonal for joint '{joint.name}'"
            )
        R_JI = RotationMatrix(np.column_stack([a1, a2, np.cross(a1, a2)]))
        X_JI = RigidTransform(R_JI, np.zeros(3))
        X_PI = ends.X_PJ.multiply(X_JI) if ends.X_PJ is not None else X_JI
        turned = _Ends(ends.parent, X_PI, ends.child, ends.X_CJ.multiply(X_JI))
        self._make(UniversalJoint, joint, turned, damping)
        if _effort(element, 0) != 0 or _effort(element, 1) != 0:
            self.reporter.warn(
                element,
                f"Actuation (via non-zero effort limits) for universal joint '{joint.name}' is "
                "not implemented yet and will be ignored.",
            )

    # ---------------------------------------------------------- properties
    def _damping(self, joint: Joint) -> float:
        """ParseJointDamping: ``<axis><dynamics><damping>`` (0 without an axis), not negative."""
        element = joint.element
        if not children(element, "axis"):
            return 0.0
        damping = number(_axis_element(element, 0, "dynamics"), "damping", 0.0)
        if damping < 0:
            raise self.reporter.error(
                element,
                f"Joint damping is negative for joint '{joint.name}'. Joint damping must be a "
                "non-negative number.",
            )
        if children(element, "axis2"):
            damping2 = number(_axis_element(element, 1, "dynamics"), "damping", 0.0)
            if damping2 != damping:
                self.reporter.warn(
                    element,
                    f"Joint damping must be equal for both axes for joint {joint.name}. The "
                    f"damping coefficient for 'axis' ({_fmt(damping)}) is used. The value for "
                    f"'axis2' ({_fmt(damping2)}) is ignored. The damping coefficient for 'axis2' "
                    f"should be explicitly defined as {_fmt(damping)} to match that for 'axis'.",
                )
        return damping

    def _axis(self, joint: Joint, scope: Scope, index: int) -> np.ndarray[Any, Any]:
        """The unit axis in J (ResolveXyz: R_JE·xyz/|xyz|); an error without ``<axis>``."""
        axes = children(joint.element, ("axis", "axis2")[index])
        if not axes:
            raise self.reporter.error(
                joint.element, f"An axis must be specified for joint '{joint.name}'"
            )
        xyz_elements = children(axes[0], "xyz")
        text = (xyz_elements[0].text or "") if xyz_elements else ""
        x, y, z = [float(v) for v in text.split()] or [0.0, 0.0, 1.0]
        norm = float(np.sqrt(x * x + y * y + z * z))
        expressed_in = joint.expressed_in[index] if index < len(joint.expressed_in) else ""
        vertex = scope.vertex_of(joint.name)
        source = scope.vertex_of(expressed_in) if expressed_in else vertex
        X_JE = self.graphs.resolve(scope.frame_scope, source, vertex)
        return np.array(rotate(X_JE.q, (x / norm, y / norm, z / norm)))

    def _limits(self, joint: Joint) -> tuple[float, float]:
        """ParseJointLimits: lower ≤ upper (±∞ by default); ``drake:acceleration`` ≥ 0."""
        element = joint.element
        if not children(element, "axis"):
            raise self.reporter.error(
                element, f"An axis must be specified for joint '{joint.name}'"
            )
        limit = _axis_element(element, 0, "limit")
        lower, upper = number(limit, "lower", -np.inf), number(limit, "upper", np.inf)
        if lower > upper:
            raise self.reporter.error(
                element,
                "The lower limit must be lower (or equal) than the upper limit for joint "
                f"'{joint.name}'.",
            )
        if children(_axis_element(element, 0, None), "limit"):
            self.reporter.check_supported(limit, _LIMIT_ELEMENTS)
            if number(limit, "drake:acceleration", 0.0) < 0:
                raise self.reporter.error(
                    limit,
                    f"Acceleration limit is negative for joint '{joint.name}'. Aceleration limit "
                    "must be a non-negative number.",
                )
        return lower, upper

    def _one_axis_warnings(self, joint: Joint) -> None:
        gains = children(joint.element, "drake:controller_gains")
        if gains and _effort(joint.element, 0) != 0 and {"p", "d"} <= set(gains[0].attrib):
            # The joint's actuator is PD controlled (reimpl keeps no actuator: the plant
            # counts them for Finalize, continuous-pd-actuators-refused-until-1.50).
            self.plant._pd_controlled_actuators += 1
        if children(joint.element, "axis2"):
            self.reporter.warn(
                joint.element,
                f"An axis2 may not be specified for 1-dof joint '{joint.name}' and will be ignored",
            )

    # ---------------------------------------------------------- drake:joint
    def add_drake_joint(self, element: XmlElement, scope: Scope) -> None:
        """AddDrakeJointFromSpecification: ``<drake:joint type="planar">``."""
        supported = _DRAKE_JOINT_ELEMENTS
        if not release.has("curvilinear-joints-since-1.38"):
            supported = _DRAKE_JOINT_ELEMENTS - _CURVILINEAR_ELEMENTS
        self.reporter.check_supported(element, supported)
        joint_type = element.get("type")
        if joint_type is None:
            raise self.reporter.error(
                element, "<drake:joint>: Unable to find the 'type' attribute."
            )
        name = element.get("name")
        if name is None:
            raise self.reporter.error(
                element, "<drake:joint>: Unable to find the 'name' attribute."
            )
        if children(element, "pose"):
            raise self.reporter.error(
                element, "<drake:joint> does not yet support the <pose> child tag."
            )
        parent = self._frame(element, scope, "drake:parent")
        child = self._frame(element, scope, "drake:child")
        if joint_type == "planar":
            damping = self._vector3(element, "drake:damping")
            self.plant.AddJoint(PlanarJoint(name, parent, child, damping))
        elif joint_type == "curvilinear":
            self._add_curvilinear(element, name, parent, child)
        else:
            raise self.reporter.error(
                element,
                f"ERROR: <drake:joint> '{name}' has unrecognized value for 'type' attribute: "
                f"{joint_type}",
            )

    def _add_curvilinear(self, element: XmlElement, name: str, parent: Any, child: Any) -> None:
        """A curvilinear joint along ``<drake:curves>``; optional ``<drake:plane_normal>``
        and ``<drake:initial_tangent>`` (``<xyz>``), ``<drake:is_periodic>`` (exactly
        ``true`` or ``false``) and ``<drake:damping>`` (≥ 0)."""
        normal = self._optional_vector(element, "drake:plane_normal", [0.0, 0.0, 1.0])
        tangent = self._optional_vector(element, "drake:initial_tangent", [1.0, 0.0, 0.0])
        periodic = False
        for node in children(element, "drake:is_periodic")[:1]:
            value = text_of(node)
            if value not in ("true", "false"):
                raise self.reporter.error(
                    element,
                    f"<drake:is_periodic>: boolean node contains non-boolean value '{value}'.",
                )
            periodic = value == "true"
        damping = 0.0
        if children(element, "drake:damping"):
            damping = self._double(element, element, "drake:damping")
            if damping < 0:
                raise self.reporter.error(
                    element,
                    f"ERROR: <drake:joint> '{name}' has negative value for 'damping' attribute: "
                    f"{damping:.6f}",
                )
        breaks, rates = self._curves(element)
        if len(breaks) == 1:
            # N.B. Drake's SDFormat reader does not check for an empty list; the trajectory's
            # constructor then fails so (measured on pydrake 1.51.1; URDF checks first).
            raise RuntimeError("Segment number -1 out of range [0, 0)\n")
        path = PiecewiseConstantCurvatureTrajectory(
            breaks, rates, tangent, normal, initial_position=[0.0, 0.0, 0.0], is_periodic=periodic
        )
        self.plant.AddJoint(
            CurvilinearJoint(
                name=name,
                frame_on_parent=parent,
                frame_on_child=child,
                curvilinear_path=path,
                damping=damping,
            )
        )

    def _optional_vector(self, element: XmlElement, tag: str, default: list[float]) -> Any:
        found = children(element, tag)
        return self._vector3(found[0], "xyz") if found else np.array(default)

    def _double(self, element: XmlElement, node: XmlElement, tag: str) -> float:
        """ParseDouble: ``node``'s ``<tag>`` (missing: an error at ``node``)."""
        found = children(node, tag)
        if not found:
            raise self.reporter.error(node, f"<{node.tag}>: Unable to find the <{tag}> child tag.")
        return float(text_of(found[0]).split()[0])

    def _curves(self, element: XmlElement) -> tuple[list[float], list[float]]:
        """ParseDrakeCurves: the breaks (from 0) and turning rates of ``<drake:curves>``."""
        curves = children(element, "drake:curves")
        if not curves:
            raise self.reporter.error(
                element, f"<{element.tag}>: Unable to find the <drake:curves> child node."
            )
        breaks, rates = [0.0], []
        for curve in curves[0]:
            assert isinstance(curve, XmlElement)
            angle = 0.0
            if curve.tag == "drake:line_segment":
                length = self._double(element, curve, "drake:length")
                if length <= 0.0:
                    raise self.reporter.error(
                        element,
                        f"<{curve.tag}>: A drake:line_segment node has a 0 or negative "
                        "drake:length.",
                    )
            elif curve.tag == "drake:circular_arc":
                radius = self._double(element, curve, "drake:radius")
                if radius <= 0.0:
                    raise self.reporter.error(
                        element,
                        f"<{curve.tag}>: A drake:circular_arc node has a 0 or negative "
                        "drake:radius.",
                    )
                angle = self._double(element, curve, "drake:angle")
                length = abs(angle) * radius
            else:
                raise self.reporter.error(
                    element,
                    f"<{element.tag}>: drake:curves node contains an invalid child node "
                    f"<{curve.tag}>.",
                )
            breaks.append(breaks[-1] + length)
            rates.append(angle / length if length else float("nan"))
        return breaks, rates

    def _frame(self, element: XmlElement, scope: Scope, tag: str) -> Any:
        """ParseFrame: a frame by name, maybe scoped into a nested model."""
        found = children(element, tag)
        if not found:
            raise self.reporter.error(
                element, f"<{element.tag}>: Unable to find the <{tag}> child tag."
            )
        frame_name = text_of(found[0])
        namespace, local = scoped.split(scoped.join(scope.name, frame_name))
        if not self.plant.HasModelInstanceNamed(namespace):
            raise self.reporter.error(
                element,
                f"<{element.tag}>: Model instance name '{namespace}' (implied by frame name "
                f"'{frame_name}' in <{tag}> within model instance '{scope.name}') does not exist "
                "in the model.",
            )
        instance = self.plant.GetModelInstanceByName(namespace)
        if not self.plant.HasFrameNamed(local, instance):
            raise self.reporter.error(
                element,
                f"<{element.tag}>: Frame '{frame_name}' specified for <{tag}> does not exist in "
                "the model.",
            )
        return self.plant.GetFrameByName(local, instance)

    def _vector3(self, element: XmlElement, tag: str) -> np.ndarray[Any, Any]:
        found = children(element, tag)
        if not found:
            raise self.reporter.error(
                element, f"<{element.tag}>: Unable to find the <{tag}> child tag."
            )
        return np.array([float(v) for v in (found[0].text or "").split()])


_Kind = Callable[[JointAdder, Joint, Scope, _Ends, float], None]
#: SDFormat joint type -> how Drake adds it
_KINDS: dict[str, _Kind] = {
    "fixed": JointAdder._fixed,
    "revolute": JointAdder._revolute,
    "continuous": JointAdder._revolute,
    "prismatic": JointAdder._prismatic,
    "screw": JointAdder._screw,
    "ball": JointAdder._ball,
    "universal": JointAdder._universal,
}
