"""URDF: one ``<robot>`` becomes one model instance (Drake 1.51.1, measured).

Elements are read in Drake's order (measured by which error comes first):
links (visuals, then collisions, only with a SceneGraph), collision filter
groups, then ``<joint>``s and ``<drake:joint>``s together in document order
(a, b, c for ``<joint a>``, ``<drake:joint b>``, ``<joint c>``; found by
``fuzz --models``); a group error thus leaves no joint.
Tag names are matched literally (``drake:`` needs no xmlns).

Joints (``<joint type>`` → Drake kind): fixed → weld, revolute and continuous
→ revolute, prismatic, planar; ``floating`` adds no joint (a warning; the
child stays free). ``<drake:joint type>``: ball → ball_rpy, universal,
planar, screw. Each joint's frame on the parent is a FixedOffsetFrame
``<joint>_parent`` in the child's model instance at the joint's ``<origin>``
(X_PJ); on the child, the body frame. A planar joint moves in its frames'
xy-plane, so Drake turns both frames by R, the rotation taking z to the unit
``<axis>`` n (about z × n, by the angle between them; about x by π for
n = −z): ``<joint>_parent`` is X_PJ · R and ``<joint>_child`` is R on the
child body (measured on pydrake 1.51.1, within 6e-16 for twelve axes).

``drake_ignore="true"`` (exactly; "1", "True", " true" do not count) on a
``<link>``, ``<joint>`` or ``<drake:joint>`` skips the element unread: no body
(nor geometry, even for ``world``), no joint, no check of its name, type or
geometry, no warning. A joint end or group member naming a skipped link is
then an error as for a link never written (measured).

A joint whose ``name`` is empty is skipped silently and unread. An
``<axis xyz>`` of norm below 1e-8 is an error at the ``<axis>`` line for every
kind but weld, ball and floating (checked after the links, before a screw's
pitch).

Collision filter groups (only with a SceneGraph; the old unprefixed
``<collision_filter_group>`` is silently ignored)::

    <drake:collision_filter_group name="G" [ignore="true"]>
      <drake:member link="L"/> <drake:member_group name="H"/>
      <drake:ignored_collision_filter_group name="K"/>
    </drake:collision_filter_group>

``ignore`` drops the group only when exactly ``"true"``. An empty name or link
is skipped; a missing one is an error at that element's line. The resolver's
errors about a group carry the ``<robot>`` line.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from reimpl.math import RigidTransform, RotationMatrix
from reimpl.multibody.kinematics import rotation_about
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._group_tags import GroupSyntax, read_group
from reimpl.multibody.parsing._model_builder import (
    JOINT_TYPES,
    GeometryNamer,
    JointSpec,
    register_geometry,
)
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext
from reimpl.multibody.parsing._urdf_geometry import read_geometry, read_origin, read_vector3
from reimpl.multibody.parsing._xml import XmlElement, XmlSyntaxError, children, parse_xml
from reimpl.multibody.tree import FixedOffsetFrame

__all__ = ["read_urdf"]

_JOINT_KINDS = {
    "fixed": "weld",
    "revolute": "revolute",
    "continuous": "revolute",
    "prismatic": "prismatic",
    "planar": "planar",
    "floating": None,
}
_DRAKE_JOINT_KINDS = {"ball": "ball_rpy", "universal": "universal", "planar": "planar"}
_DRAKE_ONLY = {"ball", "universal", "screw"}
_GROUP = "drake:collision_filter_group"
_JOINT_TAGS = frozenset({"joint", "drake:joint"})
_AXIS_KINDS = {"revolute", "prismatic", "planar", "universal", "screw"}
_ZERO_AXIS = 1e-8  # Measured: |axis| = 1e-8 passes, 1e-9 is "zero".


def _planar_rotation(axis: tuple[float, float, float]) -> RotationMatrix:
    """R with R·z = n = axis/|axis|: about z × n by the angle from z to n (about x if n = ±z)."""
    n = np.array(axis, dtype=float) / math.hypot(*axis)
    cross = np.array([-n[1], n[0], 0.0])  # z × n
    sine = float(np.linalg.norm(cross))
    about = cross / sine if sine > 0 else np.array([1.0, 0.0, 0.0])
    return RotationMatrix(rotation_about(about, math.atan2(sine, n[2])))


def _ignored(element: XmlElement) -> bool:
    """Whether Drake skips ``element``: its ``drake_ignore`` is exactly ``"true"``."""
    return element.get("drake_ignore") == "true"


def read_urdf(
    context: ParseContext, source: ModelSource, model_name: str | None, parent_scope: str
) -> list[Any]:
    """Adds the robot in ``source`` to the plant; returns its model instance."""
    diagnostics = source.diagnostics(context.strict)
    try:
        document = parse_xml(source.text)
    except XmlSyntaxError as exc:
        raise diagnostics.error(f"Failed to parse XML string: {exc.name}", exc.line) from None
    robot = document if document.tag == "robot" else None
    if robot is None:
        raise diagnostics.error("URDF does not contain a robot tag.", document.line)
    if robot.get("version") is not None:  # Drake's WarnUnsupportedAttribute (measured)
        diagnostics.warning(
            "The attribute 'version' found in a 'robot' tag is currently unsupported and "
            "will be ignored.",
            robot.line,
        )
    name = model_name or robot.get("name")
    if name is None:
        raise diagnostics.error(
            "Your robot must have a name attribute or a model name must be specified.", robot.line
        )
    return [_Robot(context, source, diagnostics, robot).add(scoped.join(parent_scope, name))]


class _Robot:
    def __init__(
        self,
        context: ParseContext,
        source: ModelSource,
        diagnostics: Diagnostics,
        robot: XmlElement,
    ) -> None:
        self.context, self.source, self.diagnostics, self.robot = (
            context,
            source,
            diagnostics,
            robot,
        )
        self.plant = context.plant

    def add(self, name: str) -> Any:
        self.instance = self.context.add_model_instance(name)
        for link in children(self.robot, "link"):
            if not _ignored(link):
                self._add_link(link)
        if self.context.has_scene_graph():
            for group in children(self.robot, _GROUP):
                self._add_group(group)
        for joint in self.robot:  # <joint> and <drake:joint> in document order
            if joint.tag in _JOINT_TAGS and isinstance(joint, XmlElement) and not _ignored(joint):
                self._add_joint(joint, drake_joint=joint.tag == "drake:joint")
        return self.instance

    def _required(self, element: XmlElement, attribute: str) -> str:
        value = element.get(attribute)
        if value is None:
            raise self.diagnostics.error(
                f'The tag <{element.tag}> does not specify the required attribute "{attribute}".',
                element.line,
            )
        return value

    # ---------------------------------------------------------------- links
    def _add_link(self, link: XmlElement) -> None:
        name = link.get("name")
        if name is None:
            raise self.diagnostics.error("link tag is missing name attribute.", link.line)
        if name == "world":
            body = self.plant.world_body()
        else:
            body = self.plant.AddRigidBody(name=name, model_instance=self.instance)
        if not self.context.has_scene_graph():
            return
        for role in ("visual", "collision"):
            namer = GeometryNamer()
            for element in children(link, role):
                spec = read_geometry(
                    element,
                    name,
                    self.diagnostics,
                    self.context.package_map,
                    self.source.root_dir,
                )
                register_geometry(self.plant, body, spec, namer.name(spec, self.diagnostics))

    # --------------------------------------------------------------- joints
    def _link_name(self, joint: XmlElement, name: str, end: str) -> str:
        ends = children(joint, end)
        if not ends:
            raise self.diagnostics.error(f"joint '{name}' doesn't have a {end} node!", joint.line)
        link = ends[0].get("link")
        if link is None:
            raise self.diagnostics.error(
                f"joint {name}'s {end} does not have a link attribute!", joint.line
            )
        return link

    def _body(self, link: str, joint_name: str) -> Any:
        if link == "world":
            return self.plant.world_body()
        if not self.plant.HasBodyNamed(link, self.instance):
            raise self.diagnostics.error(
                f"Could not find link named '{link}' with model instance ID "
                f"{int(self.instance)} for element '{joint_name}'.",
                1,
            )
        return self.plant.GetBodyByName(link, self.instance)

    def _add_joint(self, joint: XmlElement, drake_joint: bool) -> None:
        d = self.diagnostics
        name = joint.get("name")
        if name is None:
            raise d.error("joint tag is missing name attribute", joint.line)
        if not name:  # N.B. Measured: skipped unread and silently, like drake_ignore.
            return
        joint_type = joint.get("type")
        if joint_type is None:
            raise d.error(f"joint '{name}' is missing type attribute", joint.line)
        parent_link = self._link_name(joint, name, "parent")
        child_link = self._link_name(joint, name, "child")
        parent, child = self._body(parent_link, name), self._body(child_link, name)
        kind = self._kind(joint, name, joint_type, drake_joint)
        if kind is None:
            d.warning(
                f"Joint '{name}' specified as type floating which is not supported by "
                f"MultibodyPlant.  Leaving '{child_link}' as a free body.",
                joint.line,
            )
            return
        xyz = self._axis(joint, name, kind)
        spec = JointSpec(name, kind, parent_link, child_link, joint.line, xyz)
        if kind == "screw":
            spec = self._with_pitch(joint, spec)
        X_PF = read_origin(joint)
        X_CM = RigidTransform()
        if kind == "planar":  # N.B. Measured: Drake orients a planar joint's frames.
            X_CM = RigidTransform(_planar_rotation(xyz))
            X_PF = X_PF @ X_CM
        frame_on_parent = FixedOffsetFrame(
            f"{name}_parent", parent.body_frame(), X_PF, child.model_instance()
        )
        self.plant.AddFrame(frame_on_parent)
        frame_on_child = child.body_frame()
        if kind == "planar":
            frame_on_child = FixedOffsetFrame(
                f"{name}_child", frame_on_child, X_CM, child.model_instance()
            )
            self.plant.AddFrame(frame_on_child)
        self.plant.AddJoint(JOINT_TYPES[kind](spec, frame_on_parent, frame_on_child))

    def _axis(self, joint: XmlElement, name: str, kind: str) -> tuple[float, float, float]:
        """The first ``<axis xyz>`` (default x); nearly zero is an error where it is used."""
        axes = children(joint, "axis")
        if not axes:
            return (1.0, 0.0, 0.0)
        x, y, z = read_vector3(axes[0], "xyz", "1 0 0")
        if kind in _AXIS_KINDS and math.hypot(x, y, z) < _ZERO_AXIS:
            raise self.diagnostics.error(
                f"Joint '{name}' axis is zero.  Don't do that.", axes[0].line
            )
        return (x, y, z)

    def _kind(self, joint: XmlElement, name: str, joint_type: str, drake_joint: bool) -> str | None:
        d = self.diagnostics
        if drake_joint:
            if joint_type in _DRAKE_JOINT_KINDS or joint_type == "screw":
                return _DRAKE_JOINT_KINDS.get(joint_type, "screw")
            if joint_type in _JOINT_KINDS:
                raise d.error(
                    f"Joint {name} of type {joint_type} is a standard joint type, and should be "
                    "a <joint>",
                    joint.line,
                )
        else:
            if joint_type in _JOINT_KINDS:
                return _JOINT_KINDS[joint_type]
            if joint_type in _DRAKE_ONLY:
                raise d.error(
                    f"Joint {name} of type {joint_type} is a custom joint type, and should be a "
                    "<drake:joint>",
                    joint.line,
                )
        raise d.error(f"Joint '{name}' has unrecognized type: '{joint_type}'", joint.line)

    def _with_pitch(self, joint: XmlElement, spec: JointSpec) -> JointSpec:
        pitches = children(joint, "drake:screw_thread_pitch")
        if not pitches:
            raise self.diagnostics.error(
                "A screw joint is missing the <drake:screw_thread_pitch> tag.", joint.line
            )
        pitch = float(self._required(pitches[0], "value"))
        return JointSpec(spec.name, spec.kind, spec.parent, spec.child, spec.line, spec.axis, pitch)

    # --------------------------------------------------------------- groups
    def _add_group(self, group: XmlElement) -> None:
        """One group, read in Drake's order (see _group_tags); ``ignore`` counts
        only when it is exactly ``true``."""
        syntax = GroupSyntax(
            is_ignored=lambda element: element.get("ignore") == "true",
            name=lambda element: self._required(element, "name"),
            value=self._required,
        )
        scope = self.plant.GetModelInstanceName(self.instance)
        read_group(
            group,
            syntax,
            self.context.resolver,
            self.diagnostics,
            line=self.robot.line,
            scope=scope,
        )
