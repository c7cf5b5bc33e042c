"""SDFormat ``<visual>``, ``<drake:visual>`` and ``<collision>`` geometry (Drake 1.51.1, measured).

A ``<geometry>`` holds its shape as libsdformat reads it: the first of box,
capsule, cone, cylinder, ellipsoid, plane, sphere, mesh, heightmap,
polyline (in that order of preference) or, with none of them, Drake's own
``<drake:capsule>`` (radius, length) or ``<drake:ellipsoid>`` (a, b, c):

================================  ===========================================
 element                           Drake shape
================================  ===========================================
 box (size 1 1 1)                  Box
 sphere (radius 1)                 Sphere
 cylinder (radius 1, length 1)     Cylinder
 capsule (radius 0.5, length 1)    Capsule
 ellipsoid (radii 1 1 1)           Ellipsoid
 plane (normal 0 0 1)              HalfSpace, at HalfSpace::MakePose(normal)
 mesh (uri, scale 1 1 1)           Mesh; Convex with ``<drake:declare_convex/>``
 drake:capsule, drake:ellipsoid    Capsule, Ellipsoid (each measure required)
 cone, heightmap, polyline, empty  nothing is registered
================================  ===========================================

A visual gets the illustration and perception roles, less those whose
``<drake:illustration_properties>``/``<drake:perception_properties>`` says
``enabled="false"``; with neither it is not registered (a ``<visual>``, not
a ``<drake:visual>``, is warned about). ``<drake:visual>`` is a ``<visual>``
all of whose tags carry the ``drake:`` prefix. A collision gets the proximity
role. Unsupported children are warned about, ``drake:`` ones are errors.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from reimpl._release import release
from reimpl.geometry import (
    Box,
    Capsule,
    Convex,
    Cylinder,
    Ellipsoid,
    GeometryInstance,
    HalfSpace,
    IllustrationProperties,
    Mesh,
    PerceptionProperties,
    Rgba,
    Shape,
    Sphere,
)
from reimpl.math import RigidTransform
from reimpl.multibody.parsing._diagnostics import ModelParseError
from reimpl.multibody.parsing._mesh_scale import ANISOTROPIC_MESH, refuses_mesh_scale
from reimpl.multibody.parsing._sdf_document import material_color, sdformat_bool
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = [
    "GEOMETRY_ELEMENTS",
    "Checker",
    "drake_visual_to_visual",
    "first",
    "geometry_shape",
    "visual_instance",
]

#: reports unsupported children: (element, supported names) -> None
Checker = Callable[[XmlElement, frozenset[str]], None]
#: (element, message) -> raises
Raiser = Callable[[XmlElement, str], Exception]

#: what a link's <geometry> may hold (AddRigidLinkFromSpecification)
GEOMETRY_ELEMENTS = frozenset({
    "box", "capsule", "cylinder", "drake:capsule", "drake:ellipsoid", "ellipsoid", "empty",
    "mesh", "plane", "sphere",
})  # fmt: skip
_SHAPE_ELEMENTS = GEOMETRY_ELEMENTS | {"heightmap", "polyline"}
_PREFERENCE = ("box", "capsule", "cone", "cylinder", "ellipsoid", "plane", "sphere", "mesh",
               "heightmap", "polyline")  # fmt: skip
_VISUAL_ELEMENTS = frozenset({
    "drake:perception_properties", "drake:illustration_properties", "geometry", "material",
    "pose", "drake:accepting_renderer",
})  # fmt: skip
_MATERIAL_ELEMENTS = frozenset({"ambient", "diffuse", "drake:diffuse_map", "emissive", "specular"})
#: the material colors Drake keeps, in its order ("phong" group)
_COLORS = ("diffuse", "ambient", "specular", "emissive")


def first(element: XmlElement, tag: str) -> XmlElement | None:
    """``element``'s first ``<tag>`` child, or None."""
    found = children(element, tag)
    return found[0] if found else None


def _values(element: XmlElement, tag: str, default: str) -> list[float]:
    found = children(element, tag)
    text = (found[0].text or "") if found else default
    return [float(v) for v in text.split()] or [float(v) for v in default.split()]


def _kind(geometry: XmlElement) -> str:
    """sdf::Geometry's type: the preferred shape element, else ``empty``."""
    for tag in _PREFERENCE:
        if children(geometry, tag):
            return tag
    return "empty"


@dataclass(frozen=True)
class _Context:
    check: Checker
    error: Raiser
    resolve: Callable[[str], str]


def _mesh(element: XmlElement, context: _Context) -> Shape:
    uris = children(element, "uri")
    uri = " ".join((uris[0].text or "").split()) if uris else "__default__"
    if uri == "__default__":
        raise context.error(
            element,
            f"The <mesh> tag on line {element.line} is missing the required 'uri' attribute.",
        )
    filename = context.resolve(uri)
    scale = _values(element, "scale", "1 1 1")
    if refuses_mesh_scale(scale):
        if not release.has("sdf-errors-located-since-1.14"):
            # Up to 1.13 the geometry code throws it bare (measured on 1.12.0, 1.13.0).
            raise ModelParseError(ANISOTROPIC_MESH)
        raise context.error(element, ANISOTROPIC_MESH)
    kind = Convex if children(element, "drake:declare_convex") else Mesh
    return kind(filename=filename, scale3=scale)


def _required(element: XmlElement, tag: str, context: _Context) -> float:
    found = children(element, tag)
    if not found:
        raise context.error(element, f"Element <{tag}> is required within element <{element.tag}>.")
    return float((found[0].text or "").split()[0])


def _drake_shape(geometry: XmlElement, context: _Context) -> Shape | None:
    for capsule in children(geometry, "drake:capsule")[:1]:
        context.check(capsule, frozenset({"radius", "length"}))
        return Capsule(_required(capsule, "radius", context), _required(capsule, "length", context))
    for ellipsoid in children(geometry, "drake:ellipsoid")[:1]:
        context.check(ellipsoid, frozenset({"a", "b", "c"}))
        a, b, c = (_required(ellipsoid, axis, context) for axis in "abc")
        return Ellipsoid(a, b, c)
    return None


_SHAPES: dict[str, Callable[[XmlElement, _Context], Shape]] = {
    "box": lambda e, _: Box(*_values(e, "size", "1 1 1")),
    "sphere": lambda e, _: Sphere(*_values(e, "radius", "1")),
    "cylinder": lambda e, _: Cylinder(*_values(e, "radius", "1"), *_values(e, "length", "1")),
    "capsule": lambda e, _: Capsule(*_values(e, "radius", "0.5"), *_values(e, "length", "1")),
    "ellipsoid": lambda e, _: Ellipsoid(*_values(e, "radii", "1 1 1")),
    "plane": lambda e, _: HalfSpace(),
    "mesh": _mesh,
}


def geometry_shape(
    geometry: XmlElement, check: Checker, error: Raiser, resolve: Callable[[str], str]
) -> tuple[Shape | None, RigidTransform]:
    """MakeShapeFromSdfGeometry: the shape and X_GC (a half space's pose), or None."""
    context = _Context(check, error, resolve)
    check(geometry, _SHAPE_ELEMENTS)
    kind = _kind(geometry)
    if kind == "empty":
        return _drake_shape(geometry, context), RigidTransform()
    make = _SHAPES.get(kind)
    if make is None:
        return None, RigidTransform()
    element = children(geometry, kind)[0]
    shape = make(element, context)
    X_GC = RigidTransform()
    if kind == "plane":
        normal = np.array(_values(element, "normal", "0 0 1"))
        X_GC = HalfSpace.MakePose(normal / np.linalg.norm(normal), np.zeros(3))
    return shape, X_GC


def _enabled(element: XmlElement | None, error: Raiser) -> bool:
    if element is None or "enabled" not in element.attrib:
        return True
    value = sdformat_bool(element.get("enabled", ""))
    if value is None:
        raise error(
            element,
            f"The `{element.tag}` element has an 'enabled' attribute with the wrong value "
            "type; it should be a boolean value.",
        )
    return value


def _add_material(
    visual: XmlElement,
    properties: IllustrationProperties | PerceptionProperties,
    check: Checker,
    resolve: Callable[[str], str],
) -> None:
    """The ``<material>``'s colors and ``<drake:diffuse_map>`` as "phong" properties."""
    for material in children(visual, "material")[:1]:
        check(material, _MATERIAL_ELEMENTS)
        for diffuse_map in children(material, "drake:diffuse_map")[:1]:
            path = resolve(" ".join((diffuse_map.text or "").split()))
            properties.AddProperty("phong", "diffuse_map", path)
        for name in _COLORS:
            for color in children(material, name)[:1]:
                properties.AddProperty("phong", name, Rgba(*material_color(color.text or "", name)))


def visual_instance(
    visual: XmlElement,
    X_LG: RigidTransform,
    *,
    drake_visual: bool,
    check: Checker,
    error: Raiser,
    warn: Callable[[XmlElement, str], None],
    resolve: Callable[[str], str],
) -> GeometryInstance | None:
    """MakeGeometryInstanceFromSdfVisual: the visual's instance with its roles, or None."""
    check(visual, _VISUAL_ELEMENTS)
    geometry = first(visual, "geometry")
    if geometry is None:
        return None
    if _kind(geometry) == "empty" and not (
        children(geometry, "drake:capsule") or children(geometry, "drake:ellipsoid")
    ):
        return None
    shape, X_GC = geometry_shape(geometry, check, error, resolve)
    if shape is None:
        return None
    instance = GeometryInstance(X_PG=X_LG.multiply(X_GC), shape=shape, name=visual.get("name", ""))
    gets_perception = _enabled(first(visual, "drake:perception_properties"), error)
    gets_illustration = _enabled(first(visual, "drake:illustration_properties"), error)
    if not (gets_perception or gets_illustration):
        if not drake_visual:
            warn(
                visual,
                f'The <visual name="{visual.get("name", "")}"> tag had all visual roles turned '
                "off for Drake; this model may appear very different in Drake from other sdformat "
                "loaders.",
            )
        return None
    # The material goes to illustration (copied to perception) or, without it, to perception.
    properties = IllustrationProperties() if gets_illustration else PerceptionProperties()
    _add_material(visual, properties, check, resolve)
    if gets_illustration:
        assert isinstance(properties, IllustrationProperties)
        instance.set_illustration_properties(properties)
    perception = PerceptionProperties(properties) if gets_perception else None
    for accepting in children(visual, "drake:accepting_renderer"):
        if perception is None:
            warn(
                visual,
                "<drake:accepting_renderer> specified for a <visual> with a disabled perception "
                "role.",
            )
            break
        if not (accepting.text or "").strip():
            raise error(accepting, "<drake:accepting_renderer> tag given without any name")
    names = {(a.text or "").strip() for a in children(visual, "drake:accepting_renderer")}
    if perception is not None:
        if names:
            perception.AddProperty("renderer", "accepting", names)
        instance.set_perception_properties(perception)
    return instance


def drake_visual_to_visual(element: XmlElement, error: Raiser) -> XmlElement:
    """DrakeVisualToSdfVisual: a ``<drake:visual>`` as a ``<visual>`` (tags unprefixed).

    The copies have no line (0): libsdformat keeps none for elements it does not define.
    """

    def convert(node: XmlElement) -> XmlElement:
        if not node.tag.startswith("drake:"):
            # N.B. libsdformat keeps no line for what it copies from unknown elements.
            raise error(
                element,
                "All tags under a drake-namespaced tag must likewise be drake-namespaced.",
            )
        copy = XmlElement(node.tag, dict(node.attrib))
        copy.line, copy.text = 0, node.text
        if node.tag in ("drake:perception_properties", "drake:illustration_properties"):
            copy.extend(list(node))
            return copy
        copy.tag = node.tag.removeprefix("drake:")
        for child in node:
            assert isinstance(child, XmlElement)
            copy.append(convert(child))
        return copy

    return convert(element)
