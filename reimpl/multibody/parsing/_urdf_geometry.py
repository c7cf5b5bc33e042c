"""URDF ``<origin>``, ``<collision>``/``<visual>`` and their shapes (Drake 1.51.1, measured).

A ``<geometry>`` uses its first shape in this order, whatever the document
order: box, sphere, cylinder, capsule, drake:capsule, drake:ellipsoid, mesh.
Missing or malformed measures give Drake's messages, at the shape's line:
``Missing sphere attribute: radius``, ``Missing ellipsoid attribute: 'a'``,
``Expected single value for attribute 'radius' got 'x'``. A vector of the
wrong length is a ValueError without a source, as in pydrake:
``Expected 3 values for attribute size got 1 2``.
"""

from __future__ import annotations

from collections.abc import Callable

from reimpl.geometry import Box, Capsule, Cylinder, Ellipsoid, Mesh, Shape, Sphere
from reimpl.math import RigidTransform, RollPitchYaw
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._model_builder import GeometrySpec
from reimpl.multibody.parsing._package_map import PackageMap, UriError, resolve_uri
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["read_geometry", "read_origin", "read_vector3"]


def read_vector3(element: XmlElement, attribute: str, default: str = "0 0 0") -> list[float]:
    text = element.get(attribute, default)
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        values = []
    if len(values) != 3:
        raise ValueError(f"Expected 3 values for attribute {attribute} got {text}")
    return values


def read_origin(element: XmlElement) -> RigidTransform:
    """The pose in ``element``'s ``<origin xyz rpy>`` child (identity if absent)."""
    for origin in children(element, "origin"):
        rpy = RollPitchYaw(read_vector3(origin, "rpy"))
        return RigidTransform(rpy, read_vector3(origin, "xyz"))
    return RigidTransform()


class _ShapeReader:
    """Reads one shape element's scalar measures with Drake's messages."""

    def __init__(self, element: XmlElement, diagnostics: Diagnostics, quote: bool = False):
        self.element, self.diagnostics, self.quote = element, diagnostics, quote

    def scalar(self, attribute: str) -> float:
        shape = self.element.tag.removeprefix("drake:")
        text = self.element.get(attribute)
        if text is None:
            shown = f"'{attribute}'" if self.quote else attribute
            raise self.diagnostics.error(f"Missing {shape} attribute: {shown}", self.element.line)
        try:
            (value,) = (float(v) for v in text.split())
        except ValueError:
            raise self.diagnostics.error(
                f"Expected single value for attribute '{attribute}' got '{text}'",
                self.element.line,
            ) from None
        return value


def _box(e: XmlElement, d: Diagnostics, _: Callable[[str], str]) -> Shape:
    if e.get("size") is None:
        raise d.error("Missing box attribute: size", e.line)
    return Box(*read_vector3(e, "size"))


def _sphere(e: XmlElement, d: Diagnostics, _: Callable[[str], str]) -> Shape:
    return Sphere(_ShapeReader(e, d).scalar("radius"))


def _cylinder(e: XmlElement, d: Diagnostics, _: Callable[[str], str]) -> Shape:
    r = _ShapeReader(e, d)
    return Cylinder(r.scalar("radius"), r.scalar("length"))


def _capsule(e: XmlElement, d: Diagnostics, _: Callable[[str], str]) -> Shape:
    r = _ShapeReader(e, d)
    return Capsule(r.scalar("radius"), r.scalar("length"))


def _ellipsoid(e: XmlElement, d: Diagnostics, _: Callable[[str], str]) -> Shape:
    r = _ShapeReader(e, d, quote=True)
    return Ellipsoid(r.scalar("a"), r.scalar("b"), r.scalar("c"))


def _mesh(e: XmlElement, d: Diagnostics, resolve: Callable[[str], str]) -> Shape:
    filename = e.get("filename")
    if filename is None:
        raise d.error("Missing mesh attribute: filename", e.line)
    try:
        path = resolve(filename)
    except UriError as exc:
        raise d.error(str(exc), e.line) from None
    scale = read_vector3(e, "scale", "1 1 1")
    return Mesh(filename=path, scale3=scale)


ShapeMaker = Callable[[XmlElement, Diagnostics, Callable[[str], str]], Shape]

#: Shape tags in the order Drake looks for them.
_SHAPES: tuple[tuple[str, ShapeMaker], ...] = (
    ("box", _box),
    ("sphere", _sphere),
    ("cylinder", _cylinder),
    ("capsule", _capsule),
    ("drake:capsule", _capsule),
    ("drake:ellipsoid", _ellipsoid),
    ("mesh", _mesh),
)

#: role -> (Drake's message for a missing <geometry>, given the link name)
_NO_GEOMETRY: dict[str, Callable[[str], str]] = {
    "collision": lambda link: f"Link '{link}' has a collision element without geometry",
    "visual": lambda link: f"Link {link} has a visual element without geometry.",
}


def read_geometry(
    element: XmlElement,
    link: str,
    diagnostics: Diagnostics,
    package_map: PackageMap,
    root_dir: str | None,
) -> GeometrySpec:
    """One ``<collision>`` or ``<visual>`` element of link ``link``."""
    role = element.tag
    geometries = children(element, "geometry")
    if not geometries:
        raise diagnostics.error(_NO_GEOMETRY[role](link), element.line)
    geometry = geometries[0]

    def resolve(uri: str) -> str:
        return resolve_uri(package_map, uri, root_dir)

    for tag, make in _SHAPES:
        for shape_element in children(geometry, tag):
            shape = make(shape_element, diagnostics, resolve)
            X_BG = read_origin(element)
            return GeometrySpec(role, element.get("name"), shape, X_BG, element.line)
    raise diagnostics.error(
        "Warning: geometry element does not have a recognizable shape type", geometry.line
    )
