"""MuJoCo XML (MJCF): one ``<mujoco>`` becomes one model instance (Drake 1.51.1, measured).

Drake reads a subset of MJCF and warns about the documented MuJoCo content it
ignores; reimpl reads the same subset with the same messages, in Drake's order
(``_mjcf_document`` for the text and ``<include>``, then, each step whole
before the next):

1. the model name: the caller's, else ``<mujoco model>`` (neither: ``ERROR:
   Your robot must have a name attribute or a model name must be
   specified.``), and its model instance (the enclosing one when an SDFormat
   file merge-includes the file);
2. every ``<compiler>``, ``<option>`` (``_mjcf_compiler``) and top-level
   ``<default>`` (``_mjcf_defaults``), then every ``<asset>`` (``_mjcf_assets``);
3. every ``<worldbody>``, then every ``<body>`` directly under ``<mujoco>``
   (``_mjcf_bodies``, ``_mjcf_geometry``, ``_mjcf_joints``; masses by
   ``_mjcf_inertia``);
4. every ``<actuator>`` (``_mjcf_actuators``), ``<contact>`` and ``<equality>``
   (``_mjcf_contact``);
5. warnings for ``<statistic>``, ``<deformable>``, ``<tendon>``, ``<sensor>``,
   ``<keyframe>``, ``<visual>`` and ``<extension>`` (``<size>`` and
   ``<custom>`` are ignored silently).

The subset (Drake's; the documented MuJoCo content outside it is warned about
as Drake warns, and what reimpl leaves out of Drake's reading is refused):

=================  ==========================================================
 element            what is read
=================  ==========================================================
 ``<include>``      expanded in place, before anything else
 ``<compiler>``     autolimits, coordinate (local only), angle, assetdir,
                    meshdir, eulerseq, inertiafromgeom
 ``<option>``       gravity (checked; reimpl's plant keeps no gravity)
 ``<default>``      classes (nested) of geom, joint, mesh, equality, pair,
                    motor, position, camera and the other defaultable elements
 ``<asset>``        material (its rgba), mesh (an ``.obj`` file, its scale)
 ``<worldbody>``    geoms on the world, cameras, bodies
 ``<body>``         name, childclass, pose, inertial, geoms, joints (hinge,
                    slide, ball, free; several chained through massless
                    bodies), freejoint, else welded to its parent; cameras
 ``<geom>``         sphere, capsule, cylinder, ellipsoid, box, plane, mesh;
                    fromto; roles from contype/conaffinity and group; colour
                    from rgba or material; friction; mass or density
 ``<actuator>``     motor and position (checked; reimpl keeps no actuators)
 ``<contact>``      pair (unfilters two geometries), exclude (filters two
                    bodies)
 ``<equality>``     connect (checked; reimpl keeps no constraints)
=================  ==========================================================

Masses and centres of mass are kept as Drake computes them. Left out of
Drake's reading (each a reimpl ModelParseError that says so): a camera when the
Parser has a DiagramBuilder (Drake adds an RgbdSensor), a contact pair whose
geom name ends more than one geometry's name, the convex-hull fallback inertia
of a planar mesh, Drake's report of an implausible mesh inertia whose centre of
mass is not the origin, a geom direction within 1e-12 of -z that is not
exactly -z, an ``xyaxes`` whose axes are parallel, and OBJ faces with an index
of 0 or one that names no vertex (``_obj_mesh``).
"""

from __future__ import annotations

import os
from typing import Any

from reimpl._release import release
from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics, literal_string_name
from reimpl.multibody.parsing._mjcf_actuators import read_actuator
from reimpl.multibody.parsing._mjcf_assets import read_asset
from reimpl.multibody.parsing._mjcf_bodies import read_body, read_worldbody
from reimpl.multibody.parsing._mjcf_compiler import read_compiler, read_option
from reimpl.multibody.parsing._mjcf_contact import read_contact, read_equality
from reimpl.multibody.parsing._mjcf_context import MjcfContext, MjcfDiagnostics
from reimpl.multibody.parsing._mjcf_defaults import read_default
from reimpl.multibody.parsing._mjcf_document import (
    expand_includes,
    first_element,
    load_document,
)
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["read_mujoco"]

_UNSUPPORTED = ("statistic", "deformable", "tendon", "sensor", "keyframe", "visual", "extension")


def _world_bodies(context: MjcfContext, node: XmlElement) -> None:
    for worldbody in children(node, "worldbody"):
        read_worldbody(context, worldbody)
    for body in children(node, "body"):
        read_body(context, body, context.plant.world_body(), RigidTransform())


#: The top-level elements Drake reads, in its order: (tag, reader of one element).
_STEPS: tuple[tuple[str, Any], ...] = (
    ("compiler", read_compiler),
    ("option", read_option),
    ("default", read_default),
    ("asset", read_asset),
)
_LATER_STEPS: tuple[tuple[str, Any], ...] = (
    ("actuator", read_actuator),
    ("contact", read_contact),
    ("equality", read_equality),
)


def _text(source: ModelSource) -> str:
    """The model text with its line ends as written (tinyxml2 counts LFs only)."""
    if source.path is None:
        return source.text
    with open(source.path, encoding="utf-8", newline="") as stream:
        return stream.read()


def _absolute(path: str) -> str:
    """``std::filesystem::absolute``: the working folder prefixed, nothing normalized."""
    return path if os.path.isabs(path) else os.path.join(os.getcwd(), path)


def read_mujoco(
    context: ParseContext, source: ModelSource, model_name: str | None, parent_scope: str
) -> list[Any]:
    """Adds the ``<mujoco>`` model in ``source`` to the plant; returns its model instance."""
    path = source.path
    name_in_messages = _absolute(path) if path is not None else literal_string_name("urdf")
    diagnostics = Diagnostics(name_in_messages, context.strict)
    document = load_document(_text(source), path, diagnostics)
    folder = os.path.dirname(path) if path is not None else os.getcwd()
    mjcf = MjcfContext(context, MjcfDiagnostics(diagnostics), folder)
    root = first_element(document, "mujoco")
    if root is None:
        raise diagnostics.error("ERROR: XML does not contain a mujoco tag.", document.line)
    top = first_element(document)
    assert top is not None
    if release.has("mjcf-include-since-1.27"):  # before, <include> is an unsupported tag
        expand_includes(top, folder, diagnostics)
    name = model_name or root.get("model")
    if name is None:
        raise diagnostics.error(
            "ERROR: Your robot must have a name attribute or a model name must be specified.",
            root.line,
        )
    mjcf.instance = context.add_model_instance(scoped.join(parent_scope, name))
    for tag, read in _STEPS:
        for node in children(root, tag):
            read(mjcf, node)
    _world_bodies(mjcf, root)
    for tag, read in _LATER_STEPS:
        for node in children(root, tag):
            read(mjcf, node)
    mjcf.d.warn_unsupported_elements(root, _UNSUPPORTED)
    return [mjcf.instance]
