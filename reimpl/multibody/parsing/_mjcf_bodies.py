"""MuJoCo ``<worldbody>`` and ``<body>``, as Drake 1.51.1 reads them (measured).

``<worldbody>``: with a SceneGraph, its geoms are registered on the world body
(without one they are not read at all); then its cameras, warnings, and its
bodies, each child of the world.

``<body>`` (``name`` defaults to ``body<n>``, n the plant's number of bodies;
``childclass`` is passed on to its elements and nested bodies), in order:

1. its mass: the first ``<inertial>`` (unless the compiler's
   ``inertiafromgeom`` is true); none, with ``inertiafromgeom="false"``, is
   ``B has no inertial tag and inertiafromgeom=false. You must specify an
   inertia.``; else its geoms' (``_mjcf_inertia``);
2. its geoms (``_mjcf_geometry``), then the body, then, with a SceneGraph,
   each geom's visual and collision;
3. its pose X_PB in the parent body (``pos`` and orientation);
4. how it moves: ``<joint>`` elements in order, each but the last to a new
   massless body ``<name><k>`` (k from 0) whose pose is the parent's, the last
   to the body; a free joint is allowed only as the body's one joint (``No
   other joints can be defined in the body B if a free joint is defined.``),
   and stops the reading of further joints. Without ``<joint>``, a
   ``<freejoint>`` floats the body at its default pose; else the body is welded
   to its parent at X_PB (``<parent>_welds_to_<body>``);
5. its cameras, then warnings (``mocap``, ``gravcomp``, ``user``; ``site``,
   ``light``, ``composite``, ``flexcomp``, ``plugin``, ``attach``, ``frame``),
   then its nested bodies.

A ``<camera>``, without a DiagramBuilder given to the Parser, is warned about
(``camera element ignored; ...``); with one, Drake adds an RgbdSensor, which
reimpl does not (a reimpl error).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from reimpl.math import RigidTransform
from reimpl.multibody.parsing._mjcf_context import InertiaFromGeom, MjcfContext, unsupported
from reimpl.multibody.parsing._mjcf_geometry import MujocoGeometry, read_geometry
from reimpl.multibody.parsing._mjcf_inertia import BodyMass, inertial_mass
from reimpl.multibody.parsing._mjcf_joints import JointEnds, read_joint
from reimpl.multibody.parsing._mjcf_pose import parse_transform
from reimpl.multibody.parsing._xml import XmlElement, children
from reimpl.multibody.tree import SpatialInertia

__all__ = ["read_body", "read_worldbody"]

_UNSUPPORTED_ATTRIBUTES = ("mocap", "gravcomp", "user")
_UNSUPPORTED_ELEMENTS = ("site", "light", "composite", "flexcomp", "plugin", "attach", "frame")


def _register(context: MjcfContext, body: Any, geometries: list[MujocoGeometry]) -> None:
    plant = context.plant
    for geom in geometries:
        if geom.register_visual:
            plant.RegisterVisualGeometry(
                body, geom.X_BG, geom.shape, geom.name, np.asarray(geom.rgba)
            )
        if geom.register_collision:
            plant.RegisterCollisionGeometry(body, geom.X_BG, geom.shape, geom.name, geom.friction)


def _cameras(context: MjcfContext, node: XmlElement) -> None:
    """ParseCamera for each ``<camera>``: warned about, unless Drake would add a sensor."""
    for camera in children(node, "camera"):
        if context.parse.builder is None or not context.parse.has_scene_graph():
            context.d.warning(
                camera,
                "camera element ignored; to register cameras, you must pass a DiagramBuilder "
                "to the Parser and the plant must be registered with a scene graph.",
            )
        else:
            raise unsupported(camera, "cameras (Drake adds an RgbdSensor to the builder)")


def _warn_unsupported(context: MjcfContext, node: XmlElement) -> None:
    context.d.warn_unsupported_attributes(node, _UNSUPPORTED_ATTRIBUTES)
    context.d.warn_unsupported_elements(node, _UNSUPPORTED_ELEMENTS)


def read_worldbody(context: MjcfContext, node: XmlElement) -> None:
    """ParseWorldBody."""
    world = context.plant.world_body()
    if context.parse.has_scene_graph():
        geometries: list[MujocoGeometry] = []
        for geom_node in children(node, "geom"):
            geom = read_geometry(context, geom_node, len(geometries), compute_inertia=False)
            if geom.shape is not None:
                _register(context, world, [geom])
                geometries.append(geom)
    _cameras(context, node)
    _warn_unsupported(context, node)
    for body_node in children(node, "body"):
        read_body(context, body_node, world, RigidTransform())


def _mass(context: MjcfContext, node: XmlElement, name: str) -> BodyMass | None:
    """The body's mass from its ``<inertial>``, or None when its geoms give it."""
    inertial = children(node, "inertial")
    from_geom = context.compiler.inertia_from_geom
    if inertial and from_geom != InertiaFromGeom.TRUE:
        mass, com = inertial_mass(context, inertial[0])
        return BodyMass(mass, com)
    if not inertial and from_geom == InertiaFromGeom.FALSE:
        raise context.d.error(
            node,
            f"{name} has no inertial tag and inertiafromgeom=false. You must specify an inertia.",
        )
    return None


def _joints(
    context: MjcfContext, node: XmlElement, ends: JointEnds, X_WP: RigidTransform, child_class: str
) -> None:
    """The body's ``<joint>`` elements (dummy bodies between them), else freejoint or weld."""
    plant, parent, body = context.plant, ends.parent, ends.child
    name, X_PB = body.name(), ends.X_PC
    joints = children(node, "joint")
    if not joints:
        freejoints = children(node, "freejoint")
        if freejoints:
            context.d.warn_unsupported_elements(freejoints[0], ("name", "group"))
            plant.SetDefaultFloatingBaseBodyPose(body, ends.X_WC)
        else:
            plant.WeldFrames(parent.body_frame(), body.body_frame(), X_PB)
        return
    last_body, dummies = parent, 0
    for k, joint in enumerate(joints):
        if k + 1 < len(joints):
            dummy = plant.AddRigidBody(f"{name}{dummies}", context.instance, SpatialInertia.Zero())
            dummies += 1
            between = JointEnds(last_body, dummy, X_WP, RigidTransform())
            read_joint(context, joint, between, child_class)
            last_body = dummy
        else:
            read_joint(context, joint, replace(ends, parent=last_body), child_class)
        if joint.get("type") == "free":
            if dummies > 0:
                raise context.d.error(
                    node,
                    f"No other joints can be defined in the body {name} if a free joint is "
                    "defined.",
                )
            break


def read_body(
    context: MjcfContext,
    node: XmlElement,
    parent: Any,
    X_WP: RigidTransform,
    parent_class: str = "",
) -> None:
    """ParseBody, then its nested bodies."""
    plant = context.plant
    name = node.get("name")
    if name is None:
        name = f"body{plant.num_bodies()}"
    child_class = node.get("childclass")
    if child_class is None:
        child_class = parent_class
    inertial = _mass(context, node, name)
    from_geoms = BodyMass()
    geometries: list[MujocoGeometry] = []
    for geom_node in children(node, "geom"):
        geom = read_geometry(context, geom_node, len(geometries), inertial is None, child_class)
        if geom.shape is None:
            continue
        if geom.mass is not None and geom.mass[0] > 0:
            from_geoms.add(*geom.mass)
        geometries.append(geom)
    mass = inertial if inertial is not None else from_geoms
    body = plant.AddRigidBody(name, context.instance, mass.spatial_inertia())
    if context.parse.has_scene_graph():
        _register(context, body, geometries)
    X_PB = parse_transform(context, node)
    ends = JointEnds(parent, body, X_WP.multiply(X_PB), X_PB)
    _joints(context, node, ends, X_WP, child_class)
    _cameras(context, node)
    _warn_unsupported(context, node)
    for child in children(node, "body"):
        read_body(context, child, body, X_WP.multiply(X_PB), child_class)
