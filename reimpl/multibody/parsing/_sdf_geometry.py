"""SDFormat ``<collision>``/``<visual>`` shapes (Drake 1.51.1, measured).

A missing measure takes SDFormat's default (a sphere's radius is 1); a
collision or visual with no shape registers nothing. Shapes: box, sphere,
cylinder, capsule, ellipsoid, plane (a HalfSpace), mesh (through the URI
rules of ``_package_map``).
"""

from __future__ import annotations

from collections.abc import Callable

from reimpl.geometry import Box, Capsule, Cylinder, Ellipsoid, HalfSpace, Mesh, Shape, Sphere
from reimpl.math import RigidTransform
from reimpl.multibody.parsing._model_builder import GeometrySpec
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["read_shape_spec", "text_of", "values_of"]


def text_of(element: XmlElement, tag: str, default: str) -> str:
    """The stripped text of ``element``'s first ``tag`` child, or ``default``."""
    found = children(element, tag)
    return (found[0].text or "").strip() if found else default


def values_of(element: XmlElement, tag: str, default: str) -> list[float]:
    return [float(v) for v in text_of(element, tag, default).split()]


def _mesh(e: XmlElement, resolve: Callable[[str], str]) -> Shape:
    scale = values_of(e, "scale", "1 1 1")
    return Mesh(filename=resolve(text_of(e, "uri", "")), scale3=scale)


_SHAPES: dict[str, Callable[[XmlElement, Callable[[str], str]], Shape]] = {
    "box": lambda e, _: Box(*values_of(e, "size", "1 1 1")),
    "sphere": lambda e, _: Sphere(*values_of(e, "radius", "1")),
    "cylinder": lambda e, _: Cylinder(*values_of(e, "radius", "1"), *values_of(e, "length", "1")),
    "capsule": lambda e, _: Capsule(*values_of(e, "radius", "0.5"), *values_of(e, "length", "1")),
    "ellipsoid": lambda e, _: Ellipsoid(*values_of(e, "radii", "1 1 1")),
    "plane": lambda e, _: HalfSpace(),
    "mesh": _mesh,
}


def read_shape_spec(
    element: XmlElement, resolve: Callable[[str], str], X_BG: RigidTransform | None = None
) -> GeometrySpec | None:
    """The named ``<collision>`` or ``<visual>`` at X_BG, or None when it has no shape."""
    for geometry in children(element, "geometry"):
        for shape_element in geometry:
            make = _SHAPES.get(shape_element.tag)
            if make is not None and isinstance(shape_element, XmlElement):
                shape = make(shape_element, resolve)
                return GeometrySpec(
                    element.tag, element.get("name"), shape, X_BG or RigidTransform(), element.line
                )
    return None
