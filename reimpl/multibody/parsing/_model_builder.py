"""Adding what a model file declares to a MultibodyPlant, with Drake's names.

Used by the SDFormat reader, which turns elements into the small specs below
(the URDF reader follows Drake's URDF code path in its own ``_urdf_*``
modules); this module decides names and plant calls:

* Geometry is registered only when the plant has a SceneGraph, collision
  geometry with the proximity role, visual geometry with illustration and
  perception (pydrake 1.51.1 measured; SceneGraph scopes the names ``m::x``).
* A geometry without a name is named after its shape
  (``Sphere``, ``Box``, ``Cylinder``, ``Capsule``, ``Ellipsoid``, ``Mesh``).
  Within one link and role a taken name gets the first free suffix ``_1``,
  ``_2``, ...; an explicit name that is renamed is warned about (measured:
  ``collision name 'x' has already been used, renaming to 'x_1' instead``).
* Joints are made through ``JOINT_TYPES``, keyed by Drake's joint kind.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from reimpl.geometry import ProximityProperties, Shape
from reimpl.math import RigidTransform
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.tree import (
    BallRpyJoint,
    Frame,
    Joint,
    PlanarJoint,
    PrismaticJoint,
    RevoluteJoint,
    ScrewJoint,
    UniversalJoint,
    WeldJoint,
)

__all__ = ["JOINT_TYPES", "GeometryNamer", "GeometrySpec", "JointSpec", "register_geometry"]


@dataclass(frozen=True)
class GeometrySpec:
    """One ``<collision>`` or ``<visual>``: ``name`` None when the file gives none."""

    role: str  # "collision" | "visual"
    name: str | None
    shape: Shape
    X_BG: RigidTransform
    line: int


@dataclass(frozen=True)
class JointSpec:
    """One joint, by Drake kind (a key of JOINT_TYPES) and link names."""

    name: str
    kind: str
    parent: str
    child: str
    line: int
    axis: tuple[float, float, float] = (1.0, 0.0, 0.0)
    screw_pitch: float = 0.0


@dataclass
class GeometryNamer:
    """Drake's names for one link's geometries of one role."""

    used: set[str] = field(default_factory=set)

    def name(self, spec: GeometrySpec, diagnostics: Diagnostics) -> str:
        base = spec.name if spec.name is not None else type(spec.shape).__name__
        name, suffix = base, 0
        while name in self.used:
            suffix += 1
            name = f"{base}_{suffix}"
        if name != base and spec.name is not None:
            diagnostics.warning(
                f"{spec.role} name '{base}' has already been used, renaming to '{name}' instead",
                spec.line,
            )
        self.used.add(name)
        return name


def register_geometry(plant: Any, body: Any, spec: GeometrySpec, name: str) -> None:
    """Registers ``spec`` on ``body`` under ``name`` with its role's properties.

    As Drake's GeometryInstance does, the name is trimmed of whitespace first.
    """
    if not name.strip():
        raise RuntimeError(
            f"GeometryInstance given the name '{name}' which is an empty canonical string"
        )
    name = name.strip()
    if spec.role == "collision":
        plant.RegisterCollisionGeometry(
            body=body, X_BG=spec.X_BG, shape=spec.shape, name=name, properties=ProximityProperties()
        )
    else:
        plant.RegisterVisualGeometry(
            body=body,
            X_BG=spec.X_BG,
            shape=spec.shape,
            name=name,
            diffuse_color=np.array([0.9, 0.9, 0.9, 1.0]),
        )


JointMaker = Callable[[JointSpec, Frame, Frame], Joint]

#: Drake joint kind -> how to construct it between two frames.
JOINT_TYPES: dict[str, JointMaker] = {
    "weld": lambda j, p, c: WeldJoint(j.name, p, c, RigidTransform()),
    "revolute": lambda j, p, c: RevoluteJoint(j.name, p, c, np.array(j.axis), 0.0),
    "prismatic": lambda j, p, c: PrismaticJoint(j.name, p, c, np.array(j.axis)),
    "ball_rpy": lambda j, p, c: BallRpyJoint(j.name, p, c, 0.0),
    "universal": lambda j, p, c: UniversalJoint(j.name, p, c, 0.0),
    "planar": lambda j, p, c: PlanarJoint(j.name, p, c, np.zeros(3)),
    "screw": lambda j, p, c: ScrewJoint(j.name, p, c, np.array(j.axis), j.screw_pitch, 0.0),
}
