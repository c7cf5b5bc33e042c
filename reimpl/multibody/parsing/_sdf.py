"""SDFormat: each ``<model>`` (nested ones too) becomes a model instance (Drake 1.51.1, measured).

A parse has three stages, as in Drake, whose errors come in this order:

1. libsdformat reads the text and expands ``<include>``s (_sdf_document,
   _sdf_include);
2. libsdformat loads its objects (_sdf_dom; an ``<include>`` of a URDF file
   is parsed into the plant here, _sdf_interface) and builds the frame
   graphs (_sdf_graph), then checks each joint's parent and child;
3. Drake adds the models (this module), per model in this order: the
   ``<drake:visual>``s become visuals, its instance, its nested models, its
   links (geometry only with a SceneGraph), ``__model__`` on the canonical
   link (on the world for a model without one), joints, ``<frame>``s,
   ``<drake:joint>``s, the welds of a ``<static>`` model
   (``sdformat_model_static_world_welds_to_<link>``), then filter groups.

Joint types → Drake kinds: fixed → weld, revolute and continuous → revolute,
prismatic, ball → ball_rpy, universal, screw; ``<drake:joint type="planar">``
→ planar. A joint J between bodies P and C gets the frames ``<J>_parent`` at
X_PJ (none when X_PJ is exactly the identity: then P's body frame) and
``<J>_child`` at X_CJ, both in C's model instance; its axis is expressed in J
(``expressed_in`` E: R_JE·xyz). A universal joint's frames are turned by
R = [a₁ a₂ a₁×a₂]. A ``<frame>`` is a FixedOffsetFrame on what it is attached
to (in that frame's model instance). Links get X_WL as their default pose.

Collision filter groups (only with a SceneGraph) hold text children::

    <drake:collision_filter_group name="G" ignore="false">
      <drake:member>L</drake:member> <drake:member_group>H</drake:member_group>
      <drake:ignored_collision_filter_group>K</drake:ignored_collision_filter_group>
    </drake:collision_filter_group>

``ignore`` is an SDFormat bool (``true``/``1``, any case). Names are relative
to the model; the resolver's errors carry the ``<model>`` line.

Deformable links (``<drake:deformable_properties>``): on a continuous plant,
Drake's own error; on a discrete plant, reimpl raises ModelParseError
``reimpl does not support deformable bodies (...)`` (they are outside the
collision-filtering subset).
"""

from __future__ import annotations

import functools
import logging
from typing import Any

from reimpl._release import release
from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._group_tags import GroupSyntax, read_group
from reimpl.multibody.parsing._package_map import UriError, resolve_uri
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext
from reimpl.multibody.parsing._sdf_deformable import refuse_deformable
from reimpl.multibody.parsing._sdf_document import check_document, scoped_name_error
from reimpl.multibody.parsing._sdf_dom import Frame, Link, Model, World
from reimpl.multibody.parsing._sdf_geometry import (
    GEOMETRY_ELEMENTS,
    drake_visual_to_visual,
    first,
    geometry_shape,
    visual_instance,
)
from reimpl.multibody.parsing._sdf_graph import join
from reimpl.multibody.parsing._sdf_include import Loaded, load_include_hook
from reimpl.multibody.parsing._sdf_joints import JointAdder
from reimpl.multibody.parsing._sdf_load import Document, attached_body, load_document
from reimpl.multibody.parsing._sdf_poses import GzPose, read_pose
from reimpl.multibody.parsing._sdf_proximity import collision_properties
from reimpl.multibody.parsing._sdf_scope import Scope
from reimpl.multibody.parsing._xml import XmlElement, XmlSyntaxError, children, parse_xml
from reimpl.multibody.tree import FixedOffsetFrame, JointIndex, WeldJoint

__all__ = ["read_sdf"]

#: Whether Drake's own SDFormat errors name the file and line (sdf-errors-located-since-1.14).
_LOCATED = release.has("sdf-errors-located-since-1.14")

_LOG = logging.getLogger("drake")
_GROUP = "drake:collision_filter_group"
_ROOT = "__root__"
_WORLD = "world"
_BOOLS = {"true": True, "1": True, "false": False, "0": False}

#: element -> the children Drake reads there (others: a warning, or an error if drake:)
_MODEL_ELEMENTS = frozenset({
    "drake:joint", "drake:linear_bushing_rpy", "drake:linear_spring_damper",
    "drake:ball_constraint", "drake:tendon_constraint", _GROUP, "frame", "include", "joint",
    "link", "model", "pose", "static",
})  # fmt: skip
_LINK_ELEMENTS = frozenset(
    {"drake:visual", "collision", "gravity", "inertial", "kinematic", "pose", "visual"}
)
_WORLD_ELEMENTS = frozenset({"frame", "include", "joint", "model"})


def read_sdf(
    context: ParseContext, source: ModelSource, model_name: str | None, parent_scope: str
) -> list[Any]:
    """Adds the model (or the world's models) in ``source``; returns their instances."""
    try:
        root = parse_xml(source.text)
    except XmlSyntaxError as exc:
        where = "from string" if source.path is None else f"in file [{source.label or source.path}]"
        raise Diagnostics(None).error(f"Error parsing XML {where}: {exc.message}") from None
    if root.tag != "sdf" or root.get("version") is None:
        raise Diagnostics(None).error(f"Unable to read SDF string: {source.text}")
    loaded = Loaded()
    label = source.label or source.path or "<data-string>"
    includes = load_include_hook(context.package_map, loaded, context.strict)
    check_document(root, label, includes, context.strict)
    if model_name is not None and "::" in model_name:
        for model in children(root, "model"):
            model.set("name", model_name)
            raise scoped_name_error(model)
    document = load_document(context, loaded, root)
    builder = _Builder(context, source, loaded, document)
    return builder.add(root, model_name, parent_scope)


class _Builder:
    """Drake's AddModelsFromSpecification, over the loaded document."""

    def __init__(
        self, context: ParseContext, source: ModelSource, loaded: Loaded, document: Document
    ) -> None:
        self.context, self.source, self.loaded = context, source, loaded
        self.document, self.graphs = document, document.graphs
        self.plant = context.plant
        self.instances: list[Any] = []
        self.diagnostics = source.diagnostics(context.strict)
        self.joints = JointAdder(self.plant, self.graphs, self)

    # ---------------------------------------------------------- diagnostics
    def _diagnostics(self, element: XmlElement | None) -> Diagnostics:
        label = self.loaded.origins.get(element) if element is not None else None
        if label is None or ":" in (element.tag if element is not None else ""):
            return self.source.diagnostics(self.context.strict)
        return Diagnostics(label, self.context.strict)

    def _line(self, element: XmlElement) -> int | None:
        """Drake's line for an element: none for one libsdformat does not define (or copied)."""
        return None if ":" in element.tag or not element.line else element.line

    def error(self, element: XmlElement, message: str) -> ModelParseError:
        """Drake's error about ``element``; up to 1.13 its SDFormat parser names neither
        the file nor the line (sdf-errors-located-since-1.14: measured on pydrake 1.12.0
        and 1.14.0 with negative_damping_joint.sdf)."""
        if not _LOCATED:
            return Diagnostics(None, self.context.strict).error(message)
        return self._diagnostics(element).error(message, self._line(element))

    def thrown(self, element: XmlElement, message: str) -> ModelParseError:
        """An error that Drake up to 1.13 threw as a plain exception: the bare message then
        (sdf-errors-located-since-1.14: measured on pydrake 1.12.0, 1.13.0 and 1.14.0 with
        a file of neither a model nor a world), ``error`` since."""
        if not _LOCATED:
            return ModelParseError(message)
        return self.error(element, message)

    def warn(self, element: XmlElement, message: str) -> None:
        if not _LOCATED:
            Diagnostics(None, self.context.strict).warning(message)
            return
        self._diagnostics(element).warning(message, self._line(element))

    def check_supported(self, element: XmlElement, supported: frozenset[str]) -> None:
        """CheckSupportedElements: unsupported ``drake:`` children are errors, others warnings."""
        for child in element:
            assert isinstance(child, XmlElement)
            if child.tag in supported:
                continue
            message = f"SDFormat element in {element.tag}: {child.tag}"
            if not _LOCATED:  # up to 1.13 these name the file, not the line (1.12.0)
                if child.tag.startswith("drake:"):
                    raise self._diagnostics(child).error(f"Unsupported {message}")
                self._diagnostics(child).warning(f"Ignoring unsupported {message}")
                continue
            if child.tag.startswith("drake:"):
                raise self.error(child, f"Unsupported {message}")
            self.warn(child, f"Ignoring unsupported {message}")

    def check_value(self, element: XmlElement, tag: str, expected: str) -> None:
        """CheckSupportedElementValue: a bool element set to other than ``expected``."""
        for child in children(element, tag)[:1]:
            value = _BOOLS.get((child.text or "").strip().lower())
            text = ("true" if value else "false") if value is not None else (child.text or "")
            if text != expected:
                self.warn(child, f"Unsupported value for SDFormat element {tag}: {text}")

    def resolve_file(self, element: XmlElement, uri: str) -> str:
        try:
            return resolve_uri(self.context.package_map, uri, self.source.root_dir)
        except UriError as exc:
            raise self.error(element, str(exc)) from None

    # ----------------------------------------------------------- document
    def add(self, root: XmlElement, model_name: str | None, parent_scope: str) -> list[Any]:
        document = self.document
        if model_name is not None:
            model = document.model
            if model is None and len(document.worlds) == 1 and len(document.worlds[0].models) == 1:
                model = document.worlds[0].models[0]
            if model is None:
                raise self.thrown(root, "File must have a single <model> element.")
            name = self._model_name(model_name or model.name, parent_scope)
            self._add_model(model, name, RigidTransform(), model.name, _ROOT)
            return self.instances[:1]
        models = 1 if document.model is not None else 0
        if models + len(document.worlds) != 1:
            raise self.thrown(
                root,
                "File must have exactly one <model> or exactly one <world>, but instead has "
                f"{models} models and {len(document.worlds)} worlds",
            )
        if document.model is not None:
            name = self._model_name(document.model.name, parent_scope)
            self._add_model(document.model, name, RigidTransform(), document.model.name, _ROOT)
        else:
            self._add_world(document.worlds[0], parent_scope)
        return self.instances

    def _model_name(self, name: str, parent_scope: str) -> str:
        """MakeModelName: the parent's scope, then the first free ``_1``, ``_2``... if renaming."""
        full = scoped.join(parent_scope, name)
        if self.context.auto_renaming and self.plant.HasModelInstanceNamed(full):
            suffix = 1
            while self.plant.HasModelInstanceNamed(f"{full}_{suffix}"):
                suffix += 1
            full = f"{full}_{suffix}"
        return full

    def _instance(self, name: str) -> Any:
        """AddModelInstanceIfReusable: the Interface API may have made it already."""
        if self.plant.HasModelInstanceNamed(name):
            instance = self.plant.GetModelInstanceByName(name)
            if int(instance) in self.document.interface_instances:
                return instance
        return self.plant.AddModelInstance(name)

    def _add_world(self, world: World, parent_scope: str) -> None:
        self.check_supported(world.element, _WORLD_ELEMENTS)
        for model in world.models:
            name = self._model_name(model.name, parent_scope)
            self._add_model(model, name, RigidTransform(), model.name, _WORLD)
        world_instance = self.plant.world_body().model_instance()
        scope = Scope(self.plant, world_instance, "", "", RigidTransform(), world=True)
        for frame in world.frames:
            self._add_frame(frame, scope, self.plant.world_frame())
        kinds = {self.joints.add(joint, scope) for joint in world.joints}
        if kinds - {"fixed"}:
            raise self.thrown(world.element, "Only fixed joints are permitted in world joints.")

    # -------------------------------------------------------------- model
    def _add_model(
        self, model: Model, name: str, X_WP: RigidTransform, vertex: str, parent_frame: str
    ) -> None:
        drake_visuals = {
            id(link): [
                drake_visual_to_visual(v, self.error)
                for v in children(link.element, "drake:visual")
            ]
            for link in model.links
        }
        instance = self._instance(name)
        self.instances.append(instance)
        self.check_supported(model.element, _MODEL_ELEMENTS)
        X_PM = self.graphs.resolve(parent_frame, vertex, parent_frame).transform()
        scope = Scope(self.plant, instance, name, vertex, X_WP.multiply(X_PM))
        for nested in model.models:
            self._add_model(
                nested, scoped.join(name, nested.name), scope.X_WM, join(vertex, nested.name),
                scope.frame_scope,
            )  # fmt: skip
        bodies = []
        for link in model.links:
            deformable = children(link.element, "drake:deformable_properties")
            if deformable and release.has("sdf-deformable-links-since-1.41"):
                refuse_deformable(
                    link.element,
                    self,
                    functools.partial(self.resolve_file, link.element),
                    has_scene_graph=self.context.has_scene_graph(),
                    plant=self.plant,
                )
                continue
            bodies.append(self._add_link(link, scope, drake_visuals[id(link)]))
        model_frame = self._add_model_frame(model, scope, parent_frame)
        kinds = {self.joints.add(joint, scope) for joint in model.joints}
        for frame in model.frames:
            self._add_frame(frame, scope, model_frame)
        for drake_joint in children(model.element, "drake:joint"):
            self.joints.add_drake_joint(drake_joint, scope)
        if model.static:
            if kinds - {"fixed"}:
                raise self.thrown(
                    model.element, "Only fixed joints are permitted in static models."
                )
            self._weld_static(bodies)
        if self.context.has_scene_graph():
            saved = self.diagnostics
            self.diagnostics = self._diagnostics(model.element)
            try:
                for group in children(model.element, _GROUP):
                    self._add_group(group, model.element, name)
            finally:
                self.diagnostics = saved

    def _weld_static(self, bodies: list[tuple[Any, RigidTransform]]) -> None:
        welded = self._welded_to_world()
        world = self.plant.world_frame()
        for body, X_WL in bodies:
            if int(body.index()) in welded:
                continue
            self.plant.AddJoint(
                WeldJoint(
                    f"sdformat_model_static_{world.name()}_welds_to_{body.name()}",
                    world,
                    body.body_frame(),
                    X_WL,
                )
            )

    def _welded_to_world(self) -> set[int]:
        """The bodies welded (through weld joints) to the world body."""
        links: dict[int, set[int]] = {}
        for index in range(self.plant.num_joints()):
            joint = self.plant.get_joint(JointIndex(index))
            if joint.type_name() == "weld":
                a, b = int(joint.parent_body().index()), int(joint.child_body().index())
                links.setdefault(a, set()).add(b)
                links.setdefault(b, set()).add(a)
        seen, stack = {0}, [0]
        while stack:
            for other in links.get(stack.pop(), set()) - seen:
                seen.add(other)
                stack.append(other)
        return seen

    # --------------------------------------------------------------- links
    def _add_link(
        self, link: Link, scope: Scope, drake_visuals: list[XmlElement]
    ) -> tuple[Any, RigidTransform]:
        element = link.element
        self.check_supported(element, _LINK_ELEMENTS)
        self.check_value(element, "kinematic", "false")
        self.check_value(element, "gravity", "true")
        body = self.plant.AddRigidBody(name=link.name, model_instance=scope.instance)
        link_vertex = join(scope.vertex, link.name)
        X_ML = self.graphs.resolve(scope.frame_scope, link_vertex, scope.frame_scope).transform()
        X_WL = scope.X_WM.multiply(X_ML)
        self.plant.SetDefaultFloatingBaseBodyPose(body, X_WL)
        if not self.context.has_scene_graph():
            return body, X_WL
        resolve = lambda uri: self.resolve_file(element, uri)  # noqa: E731
        for visual in _visuals(element, drake_visuals):
            geometry = first(visual, "geometry")
            if geometry is not None:
                self.check_supported(geometry, GEOMETRY_ELEMENTS)
            instance = visual_instance(
                visual,
                self._X_LG(visual, scope, link_vertex).transform(),
                drake_visual=visual not in children(element, "visual"),
                check=self.check_supported,
                error=self.error,
                warn=self.warn,
                resolve=resolve,
            )
            if instance is not None:
                self.plant.RegisterVisualGeometry(body=body, geometry_instance=instance)
        for collision in children(element, "collision"):
            geometry = first(collision, "geometry")
            if geometry is None:
                continue
            self.check_supported(geometry, GEOMETRY_ELEMENTS)
            shape, X_GC = geometry_shape(geometry, self.check_supported, self.error, resolve)
            if shape is None:
                continue
            X_LC = self._X_LG(collision, scope, link_vertex).transform().multiply(X_GC)
            properties = collision_properties(
                collision, self.check_supported, self.error, self.warn
            )
            self.plant.RegisterCollisionGeometry(
                body=body,
                X_BG=X_LC,
                shape=shape,
                name=collision.get("name", ""),
                properties=properties,
            )
        return body, X_WL

    def _X_LG(self, element: XmlElement, scope: Scope, link_vertex: str) -> GzPose:
        """A visual's or collision's pose in its link (its SemanticPose, as libsdformat has it)."""
        relative_to, X = read_pose(element)
        source = join(scope.vertex, relative_to) if relative_to else link_vertex
        return self.graphs.resolve(scope.frame_scope, source, link_vertex) * X

    # -------------------------------------------------------------- frames
    def _add_model_frame(self, model: Model, scope: Scope, parent_frame: str) -> Any:
        link, canonical = model.canonical()
        if link is not None and not children(link.element, "drake:deformable_properties"):
            instance, local = scope.instance_and_local(canonical)
            frame = self.plant.GetFrameByName(local, instance)
            X_LcM = self.graphs.resolve(parent_frame, scope.vertex, join(scope.vertex, canonical))
            return self.plant.AddFrame(
                FixedOffsetFrame("__model__", frame, X_LcM.transform(), scope.instance)
            )
        return self.plant.AddFrame(
            FixedOffsetFrame("__model__", self.plant.world_frame(), scope.X_WM, scope.instance)
        )

    def _add_frame(self, frame: Frame, scope: Scope, default: Any) -> None:
        """AddFrameFromSpecification: on what ``attached_to`` names (a model: its __model__)."""
        vertex = join(scope.vertex, frame.name)
        attached_to = frame.attached_to
        target = join(scope.vertex, attached_to) if attached_to else scope.frame_scope
        X_PF = self.graphs.resolve(scope.frame_scope, vertex, target).transform()
        if not attached_to:
            parent = default
        elif self.plant.HasModelInstanceNamed(scoped.join(scope.name, attached_to)):
            instance = self.plant.GetModelInstanceByName(scoped.join(scope.name, attached_to))
            parent = self.plant.GetFrameByName("__model__", instance)
        else:
            instance, local = scope.instance_and_local(attached_to)
            if self.plant.HasFrameNamed(local, instance):
                parent = self.plant.GetFrameByName(local, instance)
            else:
                body = attached_body(self.graphs, scope.vertex, frame.name)
                namespace, local = scoped.split(scoped.join(scope.name, body))
                instance = self.plant.GetModelInstanceByName(namespace)
                parent = self.plant.GetFrameByName(local, instance)
        self.plant.AddFrame(FixedOffsetFrame(frame.name, parent, X_PF))

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
        SDFormat bool. Its errors name the file and the model's line since 1.14; up to
        1.13 they name neither (group-error-file-line-since-1.14: measured on pydrake
        1.13.0 and 1.14.0; URDF's name both on 1.12.0 already)."""
        located = release.has("group-error-file-line-since-1.14")
        syntax = GroupSyntax(
            is_ignored=lambda element: _bool(element.get("ignore", "false")),
            name=self._group_name,
            value=self._group_value,
        )
        read_group(
            group,
            syntax,
            self.context.resolver,
            self.diagnostics if located else Diagnostics(None, self.context.strict),
            line=model.line if located else None,
            scope=scope,
        )


def _bool(text: str) -> bool:
    """SDFormat's bool: ``true``/``1`` or ``false``/``0`` in any case; else an error, False."""
    value = _BOOLS.get(text.strip().lower())
    if value is None:
        _LOG.error("SDFormat Error [Element.hh:1054] Invalid boolean value")
        return False
    return value


def _visuals(link: XmlElement, drake_visuals: list[XmlElement]) -> list[XmlElement]:
    """The visuals, then the ``<drake:visual>``s whose name is not taken (Link::AddVisual)."""
    visuals = children(link, "visual")
    names = {visual.get("name") for visual in visuals}
    for visual in drake_visuals:
        if visual.get("name") not in names:
            names.add(visual.get("name"))
            visuals.append(visual)
    return visuals
