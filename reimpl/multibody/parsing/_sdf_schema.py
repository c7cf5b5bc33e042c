"""The SDFormat 1.12 elements libsdformat checks a document against (the part Drake reads).

Data, from libsdformat 16.0.1's ``sdf/1.12/*.sdf`` (the spec Drake 1.51.1 reads
every version up to): per element, its attributes (True where required) and
the children it may hold, with SDFormat's ``required`` code (``"1"`` one,
``"+"`` at least one, ``"0"`` optional, ``"*"`` any number, ``"-1"``
deprecated). Elements not listed here are not checked (e.g. ``<sensor>``).
A name with a ``:`` (``drake:...``) is never an error.
"""

from __future__ import annotations

__all__ = ["SCHEMA", "Description", "description"]

#: (attributes: name -> required, children: name -> required code)
Description = tuple[dict[str, bool], dict[str, str]]

_POSE: Description = ({"relative_to": False, "rotation_format": False, "degrees": False}, {})
_AXIS: Description = ({}, {"xyz": "1", "dynamics": "0", "limit": "1", "mimic": "0"})

SCHEMA: dict[str, Description] = {
    "sdf": (
        {"version": True},
        {
            "world": "*", "model": "0", "actor": "0", "light": "0",
            # Drake's own deprecated element, for its tests (deprecation_unit_testing.patch)
            "_drake_deprecation_unit_test_element": "-1",
        },
    ),
    "world": (
        {"name": True},
        {
            "audio": "0", "wind": "0", "include": "*", "gravity": "1", "magnetic_field": "1",
            "atmosphere": "1", "gui": "0", "physics": "+", "scene": "1", "light": "*",
            "frame": "*", "joint": "*", "model": "*", "actor": "*", "plugin": "*", "road": "*",
            "spherical_coordinates": "0", "state": "*", "population": "*",
        },
    ),
    "model": (
        {"name": True, "canonical_link": False, "placement_frame": False},
        {
            "static": "0", "self_collide": "0", "allow_auto_disable": "0", "frame": "*",
            "pose": "0", "link": "*", "joint": "*", "plugin": "*", "gripper": "*",
            "include": "*", "model": "*", "model_state": "0", "enable_wind": "0",
        },
    ),
    "include": (
        {"merge": False},
        {
            "uri": "1", "model_state": "0", "pose": "0", "plugin": "*", "name": "0",
            "static": "0", "placement_frame": "0",
        },
    ),
    "link": (
        {"name": True},
        {
            "gravity": "0", "enable_wind": "0", "self_collide": "0", "kinematic": "0",
            "must_be_base_link": "0", "velocity_decay": "0", "pose": "0", "inertial": "0",
            "collision": "*", "visual": "*", "sensor": "*", "projector": "*", "audio_sink": "*",
            "audio_source": "*", "battery": "*", "light": "*", "particle_emitter": "*",
        },
    ),
    "joint": (
        {"name": True, "type": True},
        {
            "parent": "1", "child": "1", "gearbox_ratio": "0", "gearbox_reference_body": "0",
            "thread_pitch": "-1", "screw_thread_pitch": "0", "axis": "0", "axis2": "0",
            "physics": "0", "pose": "0", "sensor": "*",
        },
    ),
    "axis": _AXIS,
    "axis2": _AXIS,
    "frame": ({"name": True, "attached_to": False}, {"pose": "0"}),
    "collision": (
        {"name": True},
        {
            "laser_retro": "0", "max_contacts": "0", "density": "0",
            "auto_inertia_params": "0", "pose": "0", "geometry": "1", "surface": "0",
        },
    ),
    "visual": (
        {"name": True},
        {
            "cast_shadows": "0", "laser_retro": "0", "transparency": "0",
            "visibility_flags": "0", "meta": "0", "pose": "0", "material": "0",
            "geometry": "1", "plugin": "*",
        },
    ),
    "geometry": (
        {},
        {
            "empty": "0", "box": "0", "capsule": "0", "cone": "0", "cylinder": "0",
            "ellipsoid": "0", "heightmap": "0", "image": "0", "mesh": "0", "plane": "0",
            "polyline": "0", "sphere": "0",
        },
    ),
    "pose": _POSE,
    "inertial": (
        {"auto": False},
        {
            "mass": "0", "density": "0", "auto_inertia_params": "0", "pose": "0",
            "inertia": "0", "fluid_added_mass": "0",
        },
    ),
    "material": (
        {},
        {
            "script": "0", "shader": "0", "render_order": "0", "lighting": "0", "ambient": "0",
            "diffuse": "0", "specular": "0", "shininess": "0", "emissive": "0",
            "double_sided": "0", "pbr": "0",
        },
    ),
    "mesh": (
        {"optimization": False},
        {"convex_decomposition": "0", "uri": "1", "submesh": "0", "scale": "0"},
    ),
    "box": ({}, {"size": "1"}),
    "sphere": ({}, {"radius": "1"}),
    "cylinder": ({}, {"radius": "1", "length": "1"}),
    "capsule": ({}, {"radius": "1", "length": "1"}),
    "ellipsoid": ({}, {"radii": "1"}),
    "plane": ({}, {"normal": "1", "size": "1"}),
}  # fmt: skip

#: A ``<pose>`` in an ``<inertial>`` has no ``relative_to``.
_INERTIAL_POSE: Description = ({"rotation_format": False, "degrees": False}, {})


def description(tag: str, parent_tag: str | None) -> Description | None:
    """What SDFormat defines for ``<tag>`` under ``<parent_tag>``; None where unchecked."""
    if tag == "pose" and parent_tag == "inertial":
        return _INERTIAL_POSE
    if tag in ("uri", "name", "static", "placement_frame") and parent_tag == "include":
        return ({}, {})
    if tag in ("diffuse", "ambient", "specular", "emissive") and parent_tag == "material":
        return ({}, {})
    return SCHEMA.get(tag)
