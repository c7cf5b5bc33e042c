"""SDFormat: each ``<model>`` (nested ones too) becomes a model instance (Drake 1.51.1, measured).

A model ``top`` holding ``<model name="inner">`` gives instances ``top`` and
``top::inner``; an ``<include>`` (a URI through the package map, ``<name>``
overriding the included model's) is a nested model too, SDFormat or URDF. A
``<world>`` holds top-level models. Per model, in Drake's order: nested models
and includes, links (geometry only with a SceneGraph), the ``__model__`` frame
on the canonical link, joints, ``<frame>``s, the welds of a ``<static>``
model (``sdformat_model_static_world_welds_to_<link>``), then groups.

Joint types → Drake kinds: fixed → weld, revolute and continuous → revolute,
prismatic, ball → ball_rpy, universal, screw. A joint's frame on the child is
a FixedOffsetFrame ``<joint>_child``; on the parent, the parent body's frame,
unless a ``<pose>`` may move it (then ``<joint>_parent``). Parent and child may
name links or frames, scoped into nested models (``inner::x``).

Poses (see _sdf_poses): a link's default pose is X_WL (SetDefaultFreeBodyPose,
for every link, as Drake does); a joint J's frames are ``<joint>_parent`` at
X_PJ and ``<joint>_child`` at X_CJ, its axis expressed in J (``expressed_in``
another frame E: R_JE·xyz); a universal joint's frames are turned by
R = [a₁ a₂ a₁×a₂] so that its axes are their x and y; a ``<frame>`` is a
FixedOffsetFrame on the frame it is attached to; a geometry is at X_LG; a
static model's weld has X_FM = X_WL; ``__model__`` sits at X_LM on the
canonical link (pydrake 1.51.1 within 1e-12).

Collision filter groups (only with a SceneGraph) hold text children::

    <drake:collision_filter_group name="G" ignore="false">
      <drake:member>L</drake:member> <drake:member_group>H</drake:member_group>
      <drake:ignored_collision_filter_group>K</drake:ignored_collision_filter_group>
    </drake:collision_filter_group>

``ignore`` is an SDFormat bool (``true``/``1``, any case). Names are relative
to the model; the resolver's errors carry the ``<model>`` line. The old
unprefixed ``<collision_filter_group>`` is an SDFormat error (see _sdf_document).
"""

from __future__ import annotations

import logging
import os
from collections.abc import Callable
from typing import Any

import numpy as np

from reimpl.multibody import kinematics
from reimpl.multibody.kinematics import Pose
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._group_tags import GroupSyntax, read_group
from reimpl.multibody.parsing._model_builder import (
    JOINT_TYPES,
    GeometryNamer,
    JointSpec,
    register_geometry,
)
from reimpl.multibody.parsing._package_map import UriError, resolve_uri
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext
from reimpl.multibody.parsing._sdf_document import check_document, scoped_name_error, xml_path
from reimpl.multibody.parsing._sdf_geometry import read_shape_spec, text_of, values_of
from reimpl.multibody.parsing._sdf_poses import WORLD, PoseGraph, read_pose, transform
from reimpl.multibody.parsing._xml import XmlElement, XmlSyntaxError, children, parse_xml
from reimpl.multibody.tree import FixedOffsetFrame, WeldJoint

__all__ = ["read_sdf"]

_LOG = logging.getLogger("drake")
_JOINT_KINDS = {
    "fixed": "weld",
    "revolute": "revolute",
    "continuous": "revolute",
    "prismatic": "prismatic",
    "ball": "ball_rpy",
    "universal": "universal",
    "screw": "screw",
}
_UNSUPPORTED_JOINTS = {"gearbox", "revolute2"}
_NEEDS_AXIS = {"revolute", "continuous", "prismatic", "screw"}
_GROUP = "drake:collision_filter_group"
#: element -> the drake: children Drake reads there
_DRAKE_ELEMENTS = {
    "model": {_GROUP, "drake:joint", "drake:linear_bushing_rpy", "drake:ball_constraint"},
    "link": set(),
    "world": set(),
    "sdf": set(),
}
_BOOLS = {"true": True, "1": True, "false": False, "0": False}


def read_sdf(
    context: ParseContext, source: ModelSource, model_name: str | None, parent_scope: str
) -> list[Any]:
    """Adds the model (or the world's models) in ``source``; returns their instances."""
    diagnostics = source.diagnostics(context.strict)
    try:
        root = parse_xml(source.text)
    except XmlSyntaxError as exc:
        raise Diagnostics(None).error(
            f"Error parsing XML from string: Error={exc.name} ErrorID={exc.error_id} "
            f"(0x{exc.error_id:x}) Line number={exc.line}"
        ) from None
    if root.tag != "sdf" or root.get("version") is None:
        raise Diagnostics(None).error(f"Unable to read SDF string: {source.text}")
    check_document(root, source.label or source.path or "<data-string>")
    if model_name is not None and "::" in model_name:
        for model in children(root, "model"):
            model.set("name", model_name)
            raise scoped_name_error(model)
    return _Document(context, source, diagnostics, root).add(root, model_name, parent_scope)


class _Document:
    def __init__(
        self,
        context: ParseContext,
        source: ModelSource,
        diagnostics: Diagnostics,
        root: XmlElement,
    ) -> None:
        self.context, self.source, self.diagnostics = context, source, diagnostics
        self.plant = context.plant
        self.instances: list[Any] = []
        self.poses = PoseGraph()
        #: scoped <frame> (or __model__) name -> the scoped name it is attached to
        self.attached_to: dict[str, str] = {}
        self.parents: dict[XmlElement, XmlElement] = {
            child: parent  # type: ignore[misc]
            for parent in root.iter()
            for child in parent
        }

    def _parent_path(self, element: XmlElement) -> str:
        """libsdformat's XML path of ``element``'s parent."""
        chain: list[XmlElement] = []
        while element in self.parents:
            element = self.parents[element]
            chain.insert(0, element)
        return xml_path(chain[-1], chain[:-1])

    def _check_drake_elements(self, element: XmlElement) -> None:
        for child in element:
            tag = child.tag
            if ":" not in tag or tag in _DRAKE_ELEMENTS.get(element.tag, {tag}):
                continue
            message = f"SDFormat element in {element.tag}: {tag}"
            if tag.startswith("drake:"):
                raise self.diagnostics.error(f"Unsupported {message}")
            self.diagnostics.warning(f"Ignoring unsupported {message}")

    def add(self, root: XmlElement, model_name: str | None, scope: str) -> list[Any]:
        self._check_drake_elements(root)
        models, worlds = children(root, "model"), children(root, "world")
        if len(models) + len(worlds) != 1:
            if len(models) > 1:
                raise Diagnostics(None).error(
                    "Root object can only contain one model. Using the first one found"
                )
            raise self.diagnostics.error(
                "File must have exactly one <model> or exactly one <world>, but instead has "
                f"{len(models)} models and {len(worlds)} worlds",
                root.line,
            )
        if worlds:
            self._check_drake_elements(worlds[0])
            for element in worlds[0]:
                if element.tag == "model" and isinstance(element, XmlElement):
                    self._add_model(element, None, scope, WORLD)
                elif element.tag == "include" and isinstance(element, XmlElement):
                    self._include(element, scope)
        else:
            self._add_model(models[0], model_name, scope, WORLD)
        return self.instances

    # --------------------------------------------------------------- models
    def _include(self, include: XmlElement, scope: str) -> None:
        uri = text_of(include, "uri", "")
        try:
            if os.path.isabs(uri) and os.path.isfile(uri):  # libsdformat takes plain paths
                path = uri
            else:
                path = resolve_uri(self.context.package_map, uri, self.source.root_dir)
        except UriError:
            label = self.source.label or self.source.path or "<data-string>"
            parent = self.parents[include]
            index = children(parent, "include").index(include)
            raise ModelParseError(
                f"{label}:{include.line}: error: At XML path {self._parent_path(include)}"
                f"/include[{index}]/uri: Unable to find uri[{uri}]"
            ) from None
        name = text_of(include, "name", "") or None
        self.instances += self.context.read_file(self.context, path, name, scope)

    def _add_model(
        self, model: XmlElement, model_name: str | None, scope: str, parent_frame: str
    ) -> None:
        """Adds ``model``, whose pose is by default in ``parent_frame`` (the world, or the
        enclosing model's frame)."""
        self._check_drake_elements(model)
        name = scoped.join(scope, model_name or model.get("name") or "")
        instance = self.context.add_model_instance(name)
        instance_name = self.plant.GetModelInstanceName(instance)
        self.instances.append(instance)
        targets = self._add_poses(model, instance_name, parent_frame, scope)
        for element in model:
            if element.tag == "model" and isinstance(element, XmlElement):
                self._add_model(element, None, instance_name, f"{instance_name}::__model__")
            elif element.tag == "include" and isinstance(element, XmlElement):
                self._include(element, instance_name)
        for target, kind, element_name in targets:
            self._check_pose_target(target, kind, element_name, model)
        links = children(model, "link")
        if not links and not children(model, "model") and not children(model, "include"):
            raise Diagnostics(None).error("A model must have at least one link.")
        bodies = {
            link.get("name", ""): self._add_link(link, instance, instance_name) for link in links
        }
        self._add_model_frame(model, instance, bodies)
        for frame in children(model, "frame"):
            target = frame.get("attached_to") or "__model__"
            self.attached_to[scoped.join(instance_name, frame.get("name", ""))] = scoped.join(
                instance_name, target
            )
        for joint in children(model, "joint"):
            self._add_joint(joint, model, instance_name)
        for frame in children(model, "frame"):
            self._add_frame(frame, instance, instance_name)
        if _bool(text_of(model, "static", "false")):
            world = self.plant.world_frame()
            for link_name, body in bodies.items():
                X_WL = self.poses.X_W(scoped.join(instance_name, link_name))
                self.plant.AddJoint(
                    WeldJoint(
                        f"sdformat_model_static_world_welds_to_{link_name}",
                        world,
                        body.body_frame(),
                        transform(X_WL),
                    )
                )
        if self.context.has_scene_graph():
            for group in children(model, _GROUP):
                self._add_group(group, model, instance_name)

    def _add_poses(
        self, model: XmlElement, instance_name: str, parent_frame: str, scope: str
    ) -> list[tuple[str, str, str]]:
        """Registers the poses of the model frame and of its links, joints and frames.

        Returns each explicit ``relative_to`` (frame, element kind, element name), to be
        checked once the nested models are read.
        """
        targets: list[tuple[str, str, str]] = []
        model_frame = f"{instance_name}::__model__"
        relative_to, X = read_pose(model)
        R = parent_frame if relative_to is None else self._pose_frame(scope, relative_to)
        self.poses.add(model_frame, R, X)
        self.poses.add(instance_name, model_frame, kinematics.identity())
        defaults: dict[str, Callable[[XmlElement], str]] = {
            "link": lambda e: "__model__",
            "joint": lambda e: text_of(e, "child", ""),
            "frame": lambda e: e.get("attached_to") or "__model__",
        }
        for kind, default in defaults.items():
            for element in children(model, kind):
                relative_to, X = read_pose(element)
                target = relative_to if relative_to is not None else default(element)
                full = self._pose_frame(instance_name, target)
                if relative_to is not None:
                    targets.append((full, kind, element.get("name", "")))
                self.poses.add(scoped.join(instance_name, element.get("name", "")), full, X)
        return targets

    def _pose_frame(self, scope: str, name: str) -> str:
        return WORLD if name == WORLD else scoped.join(scope, name)

    def _check_pose_target(self, target: str, kind: str, name: str, model: XmlElement) -> None:
        if not self.poses.has(target):
            raise Diagnostics(None).error(
                f"relative_to name[{scoped.split(target)[1]}] specified by {kind} with "
                f"name[{name}] does not match a nested model, link, joint, or frame name in "
                f"model with name[{model.get('name')}]."
            )

    def _X(self, frame: str, element: str) -> Pose:
        """X_FE between two registered frames (exact when E is posed in F)."""
        return self.poses.X_AB(frame, element)

    def _add_model_frame(self, model: XmlElement, instance: Any, bodies: dict[str, Any]) -> None:
        canonical = model.get("canonical_link")
        if canonical is not None and canonical in bodies:
            body = bodies[canonical]
        elif bodies:
            body = next(iter(bodies.values()))
        else:
            indices = self.plant.GetBodyIndices(instance) or self._nested_bodies(instance)
            if not indices:
                return
            body = self.plant.get_body(indices[0])
        instance_name = self.plant.GetModelInstanceName(instance)
        body_instance = self.plant.GetModelInstanceName(body.model_instance())
        X_LM = self._X(scoped.join(body_instance, body.name()), f"{instance_name}::__model__")
        frame = FixedOffsetFrame("__model__", body.body_frame(), transform(X_LM), instance)
        self.plant.AddFrame(frame)
        self.attached_to[scoped.join(instance_name, "__model__")] = scoped.join(
            body_instance, body.name()
        )

    def _nested_bodies(self, instance: Any) -> list[Any]:
        prefix = self.plant.GetModelInstanceName(instance) + "::"
        for other in self.instances:
            if self.plant.GetModelInstanceName(other).startswith(prefix):
                indices = self.plant.GetBodyIndices(other)
                if indices:
                    return list(indices)
        return []

    # ---------------------------------------------------------------- links
    def _add_link(self, link: XmlElement, instance: Any, instance_name: str) -> Any:
        self._check_drake_elements(link)
        body = self.plant.AddRigidBody(name=link.get("name", ""), model_instance=instance)
        link_frame = scoped.join(instance_name, link.get("name", ""))
        self.plant.SetDefaultFreeBodyPose(body, transform(self.poses.X_W(link_frame)))
        if not self.context.has_scene_graph():
            return body
        for role in ("visual", "collision"):
            namer = GeometryNamer()
            for element in children(link, role):
                relative_to, X = read_pose(element)
                if relative_to is not None:
                    X = kinematics.compose(
                        self._X(link_frame, self._pose_frame(instance_name, relative_to)), X
                    )
                spec = read_shape_spec(element, self._resolve, transform(X))
                if spec is not None:
                    register_geometry(self.plant, body, spec, namer.name(spec, self.diagnostics))
        return body

    def _resolve(self, uri: str) -> str:
        try:
            return resolve_uri(self.context.package_map, uri, self.source.root_dir)
        except UriError as exc:
            raise self.diagnostics.error(str(exc)) from None

    # --------------------------------------------------------------- frames
    def _frame(self, name: str, scope: str, joint: str, end: str, model: XmlElement) -> Any:
        """The frame a joint end names: a link's body frame, or a <frame>, maybe nested."""
        if name == "world":
            if end == "child":
                raise Diagnostics(None).error(
                    f"Joint with name[{joint}] specified invalid child link [world]."
                )
            return self.plant.world_frame()
        full_name = scoped.join(scope, name)
        while full_name in self.attached_to:  # a <frame>: the link it is attached to
            full_name = self.attached_to[full_name]
        namespace, element = scoped.split(full_name)
        plant = self.plant
        if plant.HasModelInstanceNamed(namespace):
            instance = plant.GetModelInstanceByName(namespace)
            if plant.HasBodyNamed(element, instance):
                return plant.GetBodyByName(element, instance).body_frame()
        word = "parent" if end == "parent" else "Child"
        raise Diagnostics(None).error(
            f"{word} frame with name[{name}] specified by joint with name[{joint}] not found in "
            f"model with name[{model.get('name')}]."
        )

    def _add_frame(self, frame: XmlElement, instance: Any, scope: str) -> None:
        attached_to = frame.get("attached_to") or "__model__"
        namespace, element = scoped.split(scoped.join(scope, attached_to))
        target_instance = self.plant.GetModelInstanceByName(namespace)
        if self.plant.HasBodyNamed(element, target_instance):
            parent = self.plant.GetBodyByName(element, target_instance).body_frame()
        else:
            parent = self.plant.GetFrameByName(element, target_instance)
        X_PF = self._X(scoped.join(namespace, element), scoped.join(scope, frame.get("name", "")))
        self.plant.AddFrame(
            FixedOffsetFrame(frame.get("name", ""), parent, transform(X_PF), instance)
        )

    # --------------------------------------------------------------- joints
    def _add_joint(self, joint: XmlElement, model: XmlElement, scope: str) -> None:
        name, joint_type = joint.get("name", ""), joint.get("type", "")
        parent_name = text_of(joint, "parent", "")
        child_name = text_of(joint, "child", "")
        if joint_type not in _JOINT_KINDS and joint_type not in _UNSUPPORTED_JOINTS:
            raise Diagnostics(None).error(
                f"Joint type of {joint_type} is invalid. Refer to the SDF documentation for a "
                "list of valid joint types"
            )
        frame_on_parent = self._frame(parent_name, scope, name, "parent", model)
        frame_on_child = self._frame(child_name, scope, name, "child", model)
        if joint_type in _UNSUPPORTED_JOINTS:
            raise self.diagnostics.error(
                f"Joint type ({joint_type}) not supported for joint '{name}'.", joint.line
            )
        axes = children(joint, "axis")
        if joint_type in _NEEDS_AXIS and not axes:
            raise self.diagnostics.error(
                f"An axis must be specified for joint '{name}'", joint.line
            )
        if joint_type == "universal" and (not axes or not children(joint, "axis2")):
            raise self.diagnostics.error(
                f"Both axis and axis2 must be specified for joint '{name}'", joint.line
            )
        joint_frame = scoped.join(scope, name)
        xyz = self._axis(axes[0], joint_frame, name, model) if axes else [0.0, 0.0, 1.0]
        pitch = float(text_of(joint, "screw_thread_pitch", "1"))
        spec = JointSpec(
            name, _JOINT_KINDS[joint_type], parent_name, child_name, joint.line,
            (xyz[0], xyz[1], xyz[2]), pitch,
        )  # fmt: skip
        if joint_type == "universal":
            self.diagnostics.warning(
                "Actuation (via non-zero effort limits) for universal joint "
                f"'{name}' is not implemented yet and will be ignored.",
                joint.line,
            )
        child_instance = frame_on_child.model_instance()
        X_PJ = self._X(self._body_pose_frame(frame_on_parent), joint_frame)
        X_CJ = self._X(self._body_pose_frame(frame_on_child), joint_frame)
        if joint_type == "universal":
            R = self._universal_rotation(joint, joint_frame, model, np.array(xyz))
            X_PJ, X_CJ = kinematics.compose(X_PJ, R), kinematics.compose(X_CJ, R)
        identity = kinematics.identity()
        moved = not (np.array_equal(X_PJ[0], identity[0]) and not X_PJ[1].any())
        # N.B. Measured: a universal joint always gets a parent frame too.
        if (
            joint_type == "universal"
            or moved
            or _moves_parent_frame(joint, model, parent_name, child_name)
        ):
            frame_on_parent = self.plant.AddFrame(
                FixedOffsetFrame(f"{name}_parent", frame_on_parent, transform(X_PJ), child_instance)
            )
        frame_on_child = self.plant.AddFrame(
            FixedOffsetFrame(f"{name}_child", frame_on_child, transform(X_CJ), child_instance)
        )
        self.plant.AddJoint(JOINT_TYPES[spec.kind](spec, frame_on_parent, frame_on_child))

    def _body_pose_frame(self, frame: Any) -> str:
        """The pose graph's name for a body frame of the plant (the world's is the world)."""
        if frame.body().index() == 0:
            return WORLD
        body = frame.body()
        return scoped.join(self.plant.GetModelInstanceName(body.model_instance()), body.name())

    def _axis(
        self, axis: XmlElement, joint_frame: str, joint: str, model: XmlElement
    ) -> list[float]:
        """``<xyz>`` in the joint frame J: R_JE·xyz for ``expressed_in`` E (J by default)."""
        xyz = values_of(axis, "xyz", "0 0 1")
        expressed_in = next((x.get("expressed_in") for x in children(axis, "xyz")), None)
        if not expressed_in:
            return xyz
        frame = self._pose_frame(scoped.split(joint_frame)[0], expressed_in)
        if not self.poses.has(frame):
            raise Diagnostics(None).error(
                f"axis xyz expressed-in frame with name[{expressed_in}] specified by joint with "
                f"name[{joint}] not found in model with name[{model.get('name')}]."
            )
        R_JE = self._X(joint_frame, frame)[0]
        return [float(v) for v in R_JE @ np.array(xyz)]

    def _universal_rotation(
        self, joint: XmlElement, joint_frame: str, model: XmlElement, a1: Any
    ) -> Pose:
        """R = [a₁ a₂ a₁×a₂] (unit axes in J), so that the joint's x and y are its axes."""
        a2 = np.array(self._axis(children(joint, "axis2")[0], joint_frame, "", model))
        a1, a2 = a1 / np.linalg.norm(a1), a2 / np.linalg.norm(a2)
        if abs(float(a1 @ a2)) > 1e-10:
            raise self.diagnostics.error(
                f"axis and axis2 must be orthogonal for joint '{joint.get('name', '')}'",
                joint.line,
            )
        return np.column_stack([a1, a2, np.cross(a1, a2)]), np.zeros(3)

    # --------------------------------------------------------------- groups
    def _group_name(self, group: XmlElement) -> str:
        name = group.get("name")
        if name is None:
            raise self.diagnostics.error(
                f'The tag <{_GROUP}> is missing the required attribute "name"'
            )
        return name

    def _group_value(self, element: XmlElement, _: str) -> str:
        value = (element.text or "").strip()
        if not value:
            raise self.diagnostics.error(
                f"The tag <{element.tag}> is missing a required string value."
            )
        return value

    def _add_group(self, group: XmlElement, model: XmlElement, scope: str) -> None:
        """One group, read in Drake's order (see _group_tags); ``ignore`` is an
        SDFormat bool."""
        syntax = GroupSyntax(
            is_ignored=lambda element: _bool(element.get("ignore", "false")),
            name=self._group_name,
            value=self._group_value,
        )
        read_group(
            group,
            syntax,
            self.context.resolver,
            self.diagnostics,
            line=model.line,
            scope=scope,
        )


def _bool(text: str) -> bool:
    """SDFormat's bool: ``true``/``1`` or ``false``/``0`` in any case; else an error, False."""
    value = _BOOLS.get(text.strip().lower())
    if value is None:
        _LOG.error("SDFormat Error [Element.hh:1054] Invalid boolean value")
        return False
    return value


def _spec(name: str, kind: str) -> JointSpec:
    return JointSpec(name, kind, "", "", 0)


def _pose_text(element: XmlElement | None) -> str:
    return " ".join(text_of(element, "pose", "").split()) if element is not None else ""


def _moves_parent_frame(joint: XmlElement, model: XmlElement, parent: str, child: str) -> bool:
    """Whether ``<pose>``s may put the joint frame off the parent link's frame."""
    links = {link.get("name"): link for link in children(model, "link")}
    zero = {"", "0 0 0 0 0 0"}
    joint_pose = _pose_text(joint)
    parent_pose, child_pose = _pose_text(links.get(parent)), _pose_text(links.get(child))
    return joint_pose not in zero or (
        parent_pose != child_pose and {parent_pose, child_pose} != zero
    )
