"""A ``Model`` (``conformance._fuzz.model_data``) written as URDF or SDFormat text.

The elements, measured on pydrake 1.51.1 (each parses as drawn):

=============== ===================================== ====================================
shape           URDF                                  SDFormat
=============== ===================================== ====================================
sphere, box,    ``<sphere radius=>`` ...              ``<sphere><radius>`` ...
cylinder
capsule         ``<capsule radius= length=>``         ``<capsule><radius><length>``
drake:capsule   ``<drake:capsule radius= length=>``   ``<drake:capsule><radius><length>``
ellipsoid       (none)                                ``<ellipsoid><radii>``
drake:ellipsoid ``<drake:ellipsoid a= b= c=>``        ``<drake:ellipsoid><a><b><c>``
plane           (none)                                ``<plane><normal><size>``: HalfSpace
cone, polyline  (none)                                no geometry (Drake ignores them)
mesh            ``<mesh filename= [scale=]>``         ``<mesh><uri>[<scale>]``
convex          the mesh, ``<drake:declare_convex/>`` the mesh, ``<drake:declare_convex/>``
=============== ===================================== ====================================

A mesh's URI is ``mesh_base`` (default ``package://pkg/meshes/``) and its
file. A URDF joint writes ``<limit lower= upper= effort= velocity=>`` and
``<dynamics damping=>``; an SDFormat joint the same inside its first
``<axis>``. A URDF screw joint gets its ``<drake:screw_thread_pitch>``, a
curvilinear joint a line segment and an arc (``<drake:curves>``), which
Drake requires (in SDFormat, Drake rejects ``<drake:screw_thread_pitch>``:
"Unsupported SDFormat element in joint", measured).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping

from conformance._fuzz.model_data import (
    DRAKE_NAMESPACE,
    FORMATS,
    JOINT_KINDS,
    SHAPE_KINDS,
    Frame,
    Geometry,
    Group,
    Include,
    Joint,
    Model,
    default_geometry_name,
)

__all__ = ["MESH_BASE", "render", "to_sdf", "to_urdf"]

#: Where a mesh's file is, unless the renderer is told otherwise.
MESH_BASE = "package://pkg/meshes/"

_RADIUS, _LENGTH = {"radius": "0.1"}, {"radius": "0.1", "length": "0.2"}
_ELLIPSOID = {"a": "0.1", "b": "0.2", "c": "0.3"}
#: shape → the attributes (URDF) or child elements (SDFormat) of a primitive.
_SIZES: Mapping[str, Mapping[str, str]] = {
    "sphere": _RADIUS,
    "box": {"size": "0.1 0.2 0.3"},
    "cylinder": _LENGTH,
    "capsule": _LENGTH,
    "drake:capsule": _LENGTH,
    "drake:ellipsoid": _ELLIPSOID,
    "ellipsoid": {"radii": "0.1 0.2 0.3"},
    "plane": {"normal": "0 0 1", "size": "1 1"},
    "cone": _LENGTH,
}
_AXES = (("axis", "0 0 1"), ("axis2", "0 1 0"))
_POSE = "0 0 0.1 0 0 0"


def _text(parent: ET.Element, tag: str, text: str) -> ET.Element:
    element = ET.SubElement(parent, tag)
    element.text = text
    return element


def _serialize(root: ET.Element) -> str:
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


# ------------------------------------------------------------------ URDF
def _urdf_mesh(geometry: ET.Element, shape: Geometry, mesh_base: str) -> None:
    attributes = {"filename": f"{mesh_base}{shape.mesh}"}
    if shape.scale is not None:
        attributes["scale"] = shape.scale
    mesh = ET.SubElement(geometry, "mesh", attributes)
    if shape.shape == "convex":
        ET.SubElement(mesh, "drake:declare_convex")


def _urdf_geometry(parent: ET.Element, shape: Geometry, mesh_base: str) -> None:
    geometry = ET.SubElement(parent, "geometry")
    if SHAPE_KINDS[shape.shape].mesh:
        _urdf_mesh(geometry, shape, mesh_base)
    else:
        ET.SubElement(geometry, shape.shape, dict(_SIZES[shape.shape]))


def _urdf_joint(robot: ET.Element, joint: Joint) -> None:
    kind = JOINT_KINDS[joint.kind]
    if kind.urdf is None:
        raise ValueError(f"URDF has no {joint.kind} joint")
    tag, joint_type = kind.urdf
    element = ET.SubElement(robot, tag, {"name": joint.name, "type": joint_type})
    ET.SubElement(element, "parent", {"link": joint.parent})
    ET.SubElement(element, "child", {"link": joint.child})
    if joint.limits is not None:
        lower, upper = joint.limits
        attributes = {"lower": lower, "upper": upper, "effort": "10", "velocity": "1"}
        ET.SubElement(element, "limit", attributes)
    if joint.damping is not None:
        ET.SubElement(element, "dynamics", {"damping": joint.damping})
    if joint.kind == "screw":
        ET.SubElement(element, "drake:screw_thread_pitch", {"value": "0.1"})
    if joint.kind == "curvilinear":
        curves = ET.SubElement(element, "drake:curves")
        ET.SubElement(curves, "drake:line_segment", {"length": "1"})
        ET.SubElement(curves, "drake:circular_arc", {"radius": "1", "angle": "1"})


def _urdf_frame(robot: ET.Element, frame: Frame) -> None:
    attributes = {"name": frame.name, "link": frame.attached_to}
    if frame.relative_to is not None:  # URDF has no relative_to: an offset instead
        attributes["xyz"] = "0 0 0.1"
    ET.SubElement(robot, "frame", attributes)


#: Writes a reference of a group: (element, tag, URDF attribute, value).
_Reference = Callable[[ET.Element, str, str, str], None]


def _groups(parent: ET.Element, groups: tuple[Group, ...], reference: _Reference) -> None:
    for group in groups:
        attributes = {"name": group.name}
        if group.ignore is not None:
            attributes["ignore"] = group.ignore
        element = ET.SubElement(parent, "drake:collision_filter_group", attributes)
        for link_name in group.members:
            reference(element, "drake:member", "link", link_name)
        for name in group.member_groups:
            reference(element, "drake:member_group", "name", name)
        for name in group.ignored:
            reference(element, "drake:ignored_collision_filter_group", "name", name)


def _attribute(parent: ET.Element, tag: str, key: str, value: str) -> None:
    ET.SubElement(parent, tag, {key: value})


def _element_text(parent: ET.Element, tag: str, key: str, value: str) -> None:
    _text(parent, tag, value)


def to_urdf(model: Model, *, mesh_base: str = MESH_BASE) -> str:
    """The model as URDF text (``xmlns:drake`` declared on ``<robot>``)."""
    if model.nested or model.includes:
        raise ValueError("URDF has no nested models")
    robot = ET.Element("robot", {"name": model.name, "xmlns:drake": DRAKE_NAMESPACE})
    for body in model.bodies:
        link = ET.SubElement(robot, "link", {"name": body.name})
        for geometry in body.geometries:
            tag = "collision" if geometry.collision else "visual"
            attributes = {"name": geometry.name} if geometry.name is not None else {}
            _urdf_geometry(ET.SubElement(link, tag, attributes), geometry, mesh_base)
    for joint in model.joints:
        _urdf_joint(robot, joint)
    for frame in model.frames:
        _urdf_frame(robot, frame)
    _groups(robot, model.groups, _attribute)
    return _serialize(robot)


# ------------------------------------------------------------------ SDFormat
def _sdf_geometry(parent: ET.Element, shape: Geometry, mesh_base: str) -> None:
    geometry = ET.SubElement(parent, "geometry")
    if SHAPE_KINDS[shape.shape].mesh:
        mesh = ET.SubElement(geometry, "mesh")
        _text(mesh, "uri", f"{mesh_base}{shape.mesh}")
        if shape.scale is not None:
            _text(mesh, "scale", shape.scale)
        if shape.shape == "convex":
            ET.SubElement(mesh, "drake:declare_convex")
        return
    element = ET.SubElement(geometry, shape.shape)
    if shape.shape == "polyline":
        for point in ("0 0", "0.1 0", "0 0.1"):
            _text(element, "point", point)
        _text(element, "height", "0.1")
    for key, value in _SIZES.get(shape.shape, {}).items():
        _text(element, key, value)


def _sdf_joint(root: ET.Element, joint: Joint) -> None:
    kind = JOINT_KINDS[joint.kind]
    if kind.sdf is None:
        raise ValueError(f"SDFormat has no {joint.kind} joint")
    element = ET.SubElement(root, "joint", {"name": joint.name, "type": kind.sdf})
    _text(element, "parent", joint.parent)
    _text(element, "child", joint.child)
    for position, (axis, xyz) in enumerate(_AXES[: kind.axes]):
        axis_element = ET.SubElement(element, axis)
        _text(axis_element, "xyz", xyz)
        if position == 0 and joint.limits is not None:
            limit = ET.SubElement(axis_element, "limit")
            _text(limit, "lower", joint.limits[0])
            _text(limit, "upper", joint.limits[1])
        if position == 0 and joint.damping is not None:
            _text(ET.SubElement(axis_element, "dynamics"), "damping", joint.damping)


def _sdf_frame(root: ET.Element, frame: Frame) -> None:
    attributes = {"name": frame.name}
    if frame.attached_to:
        attributes["attached_to"] = frame.attached_to
    element = ET.SubElement(root, "frame", attributes)
    if frame.relative_to is not None:
        _text(element, "pose", _POSE).set("relative_to", frame.relative_to)


def _sdf_include(root: ET.Element, include: Include) -> None:
    element = ET.SubElement(root, "include", {"merge": "true"} if include.merge else {})
    _text(element, "uri", include.uri)
    if include.name is not None:
        _text(element, "name", include.name)
    if include.pose:
        _text(element, "pose", _POSE)


def _sdf_model(parent: ET.Element, model: Model, mesh_base: str) -> None:
    """``<model>``: its links, nested models, includes, frames, joints, then groups."""
    root = ET.SubElement(parent, "model", {"name": model.name})
    for body in model.bodies:
        link = ET.SubElement(root, "link", {"name": body.name})
        for position, geometry in enumerate(body.geometries):
            tag = "collision" if geometry.collision else "visual"
            name = geometry.name or default_geometry_name(geometry, position)
            _sdf_geometry(ET.SubElement(link, tag, {"name": name}), geometry, mesh_base)
    for inner in model.nested:
        _sdf_model(root, inner, mesh_base)
    for include in model.includes:
        _sdf_include(root, include)
    for frame in model.frames:
        _sdf_frame(root, frame)
    for joint in model.joints:
        _sdf_joint(root, joint)
    _groups(root, model.groups, _element_text)


def to_sdf(model: Model, *, mesh_base: str = MESH_BASE) -> str:
    """The model as SDFormat 1.9 text; unnamed elements get ``collision<k>``/``visual<k>``."""
    sdf = ET.Element("sdf", {"version": "1.9", "xmlns:drake": DRAKE_NAMESPACE})
    _sdf_model(sdf, model, mesh_base)
    return _serialize(sdf)


def render(model: Model, fmt: str, *, mesh_base: str = MESH_BASE) -> str:
    """``to_urdf`` or ``to_sdf`` by ``fmt`` (``"urdf"`` or ``"sdf"``)."""
    if fmt == "urdf":
        return to_urdf(model, mesh_base=mesh_base)
    if fmt == "sdf":
        return to_sdf(model, mesh_base=mesh_base)
    raise ValueError(f"unknown model format {fmt!r} (have {', '.join(FORMATS)})")
