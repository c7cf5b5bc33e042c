"""MuJoCo ``<default>`` classes, as Drake 1.51.1 applies them (detail_mujoco_parser.cc).

A ``<default>`` names its class with ``class`` (the top-level one may omit it:
``main``; a nested one may not: ``The `class` attribute is required for all
`default` elements except at the top-level``). Each of its children named in
``ELEMENTS`` becomes the defaults of (that element, the class), the last such
child winning; a nested class's child first takes every attribute of its
parent class's same-named child that it does not set (so a class without a
``<geom>`` child gives a geom of that class no defaults at all, not even its
parent's). Then the nested ``<default>`` elements are read, depth first.

An element of class C (its ``class``, else the enclosing body's
``childclass``, else ``main``) takes every attribute of (element, C)'s
defaults that it does not set itself, except that an element which sets any
orientation (``quat``, ``axisangle``, ``euler``, ``xyaxes``, ``zaxis``) takes
none of the defaults' orientations. The attributes are added to the element
itself, after its own (which decides the order a message lists them in).
"""

from __future__ import annotations

from reimpl.multibody.parsing._mjcf_context import MjcfContext
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["ELEMENTS", "ORIENTATIONS", "apply_defaults", "class_of", "read_default"]

#: The orientation attributes, in the order Drake checks them.
ORIENTATIONS = ("quat", "axisangle", "euler", "xyaxes", "zaxis")

#: The children of ``<default>`` that hold defaults, in the order Drake reads them.
ELEMENTS = (
    "geom",
    "joint",
    "mesh",
    "equality",
    "material",
    "site",
    "camera",
    "light",
    "pair",
    "tendon",
    "general",
    "motor",
    "position",
    "velocity",
    "cylinder",
    "muscle",
)


def class_of(node: XmlElement, child_class: str = "") -> str:
    """The class an element takes its defaults from."""
    named = node.get("class")
    if named is not None:
        return named
    return child_class or "main"


def apply_defaults(
    context: MjcfContext, element_name: str, class_name: str, node: XmlElement
) -> None:
    """ApplyDefaultAttributes: the class's attributes that ``node`` does not set."""
    default = context.defaults.get((element_name, class_name))
    if default is None:
        return
    oriented = any(node.get(name) is not None for name in ORIENTATIONS)
    for name, value in default.attrib.items():
        if node.get(name) is not None:
            continue
        if oriented and name in ORIENTATIONS:
            continue
        node.set(name, value)


def read_default(context: MjcfContext, node: XmlElement, parent_class: str = "") -> None:
    """ParseDefault: this class's defaults, then its nested classes'."""
    class_name = node.get("class")
    if class_name is None:
        if parent_class:
            raise context.d.error(
                node,
                "The `class` attribute is required for all `default` elements except at the "
                "top-level",
            )
        class_name = "main"
    for element_name in ELEMENTS:
        for child in children(node, element_name):
            context.defaults[(element_name, class_name)] = child
            if parent_class:
                apply_defaults(context, element_name, parent_class, child)
    for nested in children(node, "default"):
        read_default(context, nested, class_name)
