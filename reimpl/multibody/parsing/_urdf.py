"""URDF: one ``<robot>`` becomes one model instance (Drake 1.51.1, measured).

The text is read as tinyxml2 reads it (``_xml``); a syntax error is ``Failed
to parse XML file: XML_ERROR_...`` for a file, ``... XML string: ...`` for
text, at line 1 (0 for an empty text). The robot is the first top-level
``<robot>`` element (none: ``URDF does not contain a robot tag.``), named by
its ``name`` unless the caller names it. Tag names are matched literally
(``drake:`` needs no xmlns). Then Drake reads, in this order, each step
whole before the next (so the first error in this order is the one raised):

1. ``<robot version>`` warned; the name; the model instance;
2. every ``<material>`` child of the robot (``_urdf_materials``);
3. every ``<link>``: ``drake_ignore="true"`` (exactly) skips it unread;
   ``type`` warned; ``name`` required; ``world`` is the world body (an
   ``<inertial>`` there warned), any other name a new body (its ``<inertial>``
   origin, mass and inertia numbers read); with a SceneGraph, its visuals,
   then its collisions (``_urdf_geometry``);
4. with a SceneGraph, the ``<drake:collision_filter_group>`` elements
   (``_add_group`` below; the old unprefixed tag is silently ignored);
5. ``<joint>`` and ``<drake:joint>`` elements together, in document order
   (``_urdf_joints``), then their ``<mimic>`` elements;
6. ``<transmission>`` elements (``_urdf_transmissions``);
7. a ``<loop_joint>`` anywhere: ``loop joints are not supported in
   MultibodyPlant`` (at the robot's line);
8. ``<frame name link xyz rpy>``: a FixedOffsetFrame on the link;
9. bushings, springs, ball and tendon constraints (``_urdf_constraints``).

A link or frame that names no link of the robot is ``Could not find link
named 'x' with model instance ID n for element 'e'.`` at line 1. A file is
named in messages by ``std::filesystem::absolute`` (the working directory
joined, not normalized), text by ``<literal-string>.urdf``.

Collision filter groups (only with a SceneGraph)::

    <drake:collision_filter_group name="G" [ignore="true"]>
      <drake:member link="L"/> <drake:member_group name="H"/>
      <drake:ignored_collision_filter_group name="K"/>
    </drake:collision_filter_group>

``ignore`` drops the group, unread, only when exactly ``"true"``. An empty
name or link is skipped; a missing one is an error at that element's line.
The ignored groups are read after the group is added, so a group without
members is an error before a nameless ignored group is. The resolver's
errors about a group carry the ``<robot>`` line.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np
import numpy.typing as npt

from reimpl._release import release
from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics, literal_string_name
from reimpl.multibody.parsing._group_tags import GroupSyntax, read_group
from reimpl.multibody.parsing._package_map import UriError, resolve_uri
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext
from reimpl.multibody.parsing._urdf_constraints import ConstraintReader
from reimpl.multibody.parsing._urdf_geometry import GeometryReader
from reimpl.multibody.parsing._urdf_inertia import inertia_warning
from reimpl.multibody.parsing._urdf_inertia_until_1_15 import inertia_error
from reimpl.multibody.parsing._urdf_joints import JointReader
from reimpl.multibody.parsing._urdf_materials import MaterialMap
from reimpl.multibody.parsing._urdf_transmissions import TransmissionReader
from reimpl.multibody.parsing._urdf_values import Values, origin
from reimpl.multibody.parsing._xml import (
    XmlDocument,
    XmlElement,
    XmlSyntaxError,
    children,
    parse_document,
)
from reimpl.multibody.tree import FixedOffsetFrame

__all__ = ["read_urdf"]

_GROUP = "drake:collision_filter_group"
_JOINT_TAGS = frozenset({"joint", "drake:joint"})
_INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def read_urdf(
    context: ParseContext, source: ModelSource, model_name: str | None, parent_scope: str
) -> list[Any]:
    """Adds the robot in ``source`` to the plant; returns its model instance."""
    path = _absolute(source.path) if source.path is not None else None
    diagnostics = Diagnostics(path or literal_string_name("urdf"), context.strict)
    try:
        document = parse_document(_text(source, path), from_file=path is not None)
    except XmlSyntaxError as exc:
        kind = "file" if path is not None else "string"
        raise diagnostics.error(f"Failed to parse XML {kind}: {exc.name}", exc.line) from None
    robots = children(document, "robot")
    if not robots:
        raise diagnostics.error("URDF does not contain a robot tag.", document.line)
    robot = robots[0]
    _warn_unsupported_attribute(diagnostics, robot, "version")
    name = model_name or robot.get("name")
    if name is None:
        raise diagnostics.error(
            "Your robot must have a name attribute or a model name must be specified.", robot.line
        )
    root_dir = os.path.dirname(path) if path is not None else None
    reader = _Robot(context, diagnostics, document, robot, root_dir)
    return [reader.add(scoped.join(parent_scope, name))]


def _text(source: ModelSource, path: str | None) -> str:
    """The model text with its line ends as written (tinyxml2 counts LFs only)."""
    if path is None:
        return source.text
    with open(path, encoding="utf-8", newline="") as stream:
        return stream.read()


def _absolute(path: str) -> str:
    """``std::filesystem::absolute``: the working directory joined, without normalizing."""
    return path if os.path.isabs(path) else os.path.join(os.getcwd(), path)


def _warn_unsupported_attribute(d: Diagnostics, element: XmlElement, attribute: str) -> None:
    if element.get(attribute) is not None:
        d.warning(
            f"The attribute '{attribute}' found in a '{element.tag}' tag is currently "
            "unsupported and will be ignored.",
            element.line,
        )


def _or_zero(value: float | None) -> float:
    return 0.0 if value is None else value


def _matrix(moments: dict[str, float]) -> npt.NDArray[np.float64]:
    """RotationalInertia(ixx, iyy, izz, ixy, ixz, iyz) as a symmetric matrix."""
    m = moments
    return np.array(
        [
            [m["ixx"], m["ixy"], m["ixz"]],
            [m["ixy"], m["iyy"], m["iyz"]],
            [m["ixz"], m["iyz"], m["izz"]],
        ]
    )


def _ignored(element: XmlElement) -> bool:
    """Whether Drake skips ``element``: its ``drake_ignore`` is exactly ``"true"``."""
    return element.get("drake_ignore") == "true"


class _Robot:
    def __init__(
        self,
        context: ParseContext,
        diagnostics: Diagnostics,
        document: XmlDocument,
        robot: XmlElement,
        root_dir: str | None,
    ) -> None:
        self.context, self.diagnostics = context, diagnostics
        self.document, self.robot, self.root_dir = document, robot, root_dir
        self.plant = context.plant
        self.values = Values(diagnostics)
        self.materials = MaterialMap(diagnostics, self._resolve)

    def add(self, name: str) -> Any:
        self.instance = self.context.add_model_instance(name)
        for material in children(self.robot, "material"):
            self.materials.read(material, name_required=True)
        geometry = GeometryReader(self.diagnostics, self._resolve, self.materials)
        for link in children(self.robot, "link"):
            if not _ignored(link):
                self._add_link(link, geometry)
        if self.context.has_scene_graph():
            for group in children(self.robot, _GROUP):
                self._add_group(group)
        joints = JointReader(self.plant, self.instance, self.diagnostics, self._body)
        elements = [e for e in self.robot if e.tag in _JOINT_TAGS and isinstance(e, XmlElement)]
        for element in elements:
            joints.read(element)
        for element in elements:
            joints.read_mimic(element)
        transmissions = TransmissionReader(
            self.plant, self.instance, self.diagnostics, joints.efforts
        )
        for transmission in children(self.robot, "transmission"):
            transmissions.read(transmission)
        if children(self.robot, "loop_joint"):
            raise self.diagnostics.error(
                "loop joints are not supported in MultibodyPlant", self.robot.line
            )
        for frame in children(self.robot, "frame"):
            self._add_frame(frame)
        ConstraintReader(self.plant, self.instance, self.diagnostics).read_all(self.robot)
        return self.instance

    def _required(self, element: XmlElement, attribute: str) -> str:
        value = element.get(attribute)
        if value is None:
            raise self.diagnostics.error(
                f'The tag <{element.tag}> does not specify the required attribute "{attribute}".',
                element.line,
            )
        return value

    def _resolve(self, uri: str, line: int) -> str:
        """Drake's ResolveUri: the existing file ``uri`` names (an error at ``line`` if none)."""
        try:
            return resolve_uri(self.context.package_map, uri, self.root_dir)
        except UriError as exc:
            raise self.diagnostics.error(str(exc), line) from None

    def _body(self, link: str, element_name: str) -> Any:
        """Drake's GetBodyForElement: the world, or a link of this robot."""
        if link == "world":
            return self.plant.world_body()
        if not self.plant.HasBodyNamed(link, self.instance):
            raise self.diagnostics.error(
                f"Could not find link named '{link}' with model instance ID "
                f"{int(self.instance)} for element '{element_name}'.",
                self.document.line,
            )
        return self.plant.GetBodyByName(link, self.instance)

    # ---------------------------------------------------------------- links
    def _add_link(self, link: XmlElement, geometry: GeometryReader) -> None:
        _warn_unsupported_attribute(self.diagnostics, link, "type")
        name = link.get("name")
        if name is None:
            raise self.diagnostics.error("link tag is missing name attribute.", link.line)
        inertials = children(link, "inertial")
        if name == "world":
            body = self.plant.world_body()
            if inertials:
                self.diagnostics.warning(
                    'A URDF file declared the "world" link and then attempted to assign mass '
                    "properties (via the <inertial> tag). Only geometries, <collision> and "
                    "<visual>, can be assigned to the world link. The <inertial> tag is being "
                    "ignored.",
                    link.line,
                )
        else:
            if inertials:
                self._read_inertial(inertials[0])
            body = self.plant.AddRigidBody(name=name, model_instance=self.instance)
        if not self.context.has_scene_graph():
            return
        names: set[str] = set()
        for visual in children(link, "visual"):
            parsed = geometry.visual(visual, name, names)
            if parsed is not None:
                self.plant.RegisterVisualGeometry(body=body, geometry_instance=parsed.instance)
        if release.has("default-geometry-name-underscore-since-1.15"):
            names = set()  # N.B. Names are unique per role; up to 1.14, per link.
        for collision in children(link, "collision"):
            parsed = geometry.collision(collision, name, names)
            instance = parsed.instance
            self.plant.RegisterCollisionGeometry(
                body=body,
                X_BG=instance.pose(),
                shape=instance.shape(),
                name=instance.name(),
                properties=parsed.properties,
            )

    def _read_inertial(self, inertial: XmlElement) -> None:
        """Reads an ``<inertial>``'s numbers and warns where Drake does (``_urdf_inertia``).

        reimpl keeps no mass properties; absent numbers are 0.
        """
        origins = children(inertial, "origin")
        X_BBi = origin(origins[0]) if origins else RigidTransform()
        mass = 0.0
        for node in children(inertial, "mass")[:1]:
            mass = _or_zero(self.values.scalar(node, "value"))
        moments = dict.fromkeys(_INERTIA, 0.0)
        for node in children(inertial, "inertia")[:1]:
            moments = {m: _or_zero(self.values.scalar(node, m)) for m in _INERTIA}
        if release.has("urdf-implausible-inertia-error-until-1.15"):
            R = np.asarray(X_BBi.rotation().matrix(), dtype=float)
            com = tuple(float(v) for v in X_BBi.translation())
            error = inertia_error(mass, (com[0], com[1], com[2]), R @ _matrix(moments) @ R.T)
            if error is not None:
                raise error
            return
        warning = inertia_warning(mass, moments)
        if warning is not None:
            self.diagnostics.warning(warning, inertial.line)

    # --------------------------------------------------------------- frames
    def _add_frame(self, frame: XmlElement) -> None:
        name = frame.get("name")
        if name is None:
            raise self.diagnostics.error("parsing frame name.", frame.line)
        link = frame.get("link")
        if link is None:
            raise self.diagnostics.error(f"missing link name for frame {name}.", frame.line)
        body = self._body(link, name)
        self.plant.AddFrame(FixedOffsetFrame(name, body.body_frame(), origin(frame)))

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
