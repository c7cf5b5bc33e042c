"""An ``.obj`` file as a one-body model, as Drake 1.51.1 adds it (detail_mesh_parser.cc).

Drake (measured on pydrake 1.51.1) reads the file named by its absolute path
P (not normalized) as a triangle mesh (``_obj_mesh``; its errors, e.g. ``error:
The OBJ data parsed contains no objects; ...``, and its warning, an error under
strict parsing), then:

1. the model's name: the caller's, else the OBJ's object name (its last ``o``
   line), else the file's stem; the model instance is that name in the
   caller's scope (auto-renamed like any);
2. the body's mass properties at 1000 kg/m³ (``_mesh_inertia``); a failure is
   ``error: <message>`` (e.g. the volume message), the model instance already
   added;
3. a body of that name, and with a SceneGraph the mesh (``Mesh(P)``, scale 1)
   registered twice at the body's origin: ``collision`` with empty proximity
   properties, then ``visual`` with default illustration properties (and the
   perception role).

Model text of type ``obj`` is refused before this (``Parser does not yet
support adding models using in-memory OBJ data. ...``, in ``_parser``).
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from reimpl.geometry import (
    GeometryInstance,
    IllustrationProperties,
    Mesh,
    PerceptionProperties,
    ProximityProperties,
)
from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._mesh_inertia import mesh_properties
from reimpl.multibody.parsing._mjcf_assets import stem
from reimpl.multibody.parsing._obj_mesh import read_obj_mesh
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext
from reimpl.multibody.tree import SpatialInertia, UnitInertia

__all__ = ["read_obj_model"]

#: Drake's density for a mesh model's body, about water's (kg/m³).
_DENSITY = 1000.0


def read_obj_model(
    context: ParseContext, source: ModelSource, model_name: str | None, parent_scope: str
) -> list[Any]:
    """AddModelFromMesh: the model instance of the one-body model in the OBJ file."""
    assert source.path is not None
    path = source.path if os.path.isabs(source.path) else os.path.join(os.getcwd(), source.path)
    mesh = read_obj_mesh(path, (1.0, 1.0, 1.0), path)
    if mesh.warning:
        Diagnostics(None, context.strict).warning(mesh.warning)
    name = model_name or mesh.name or stem(path)
    plant = context.plant
    instance = context.add_model_instance(scoped.join(parent_scope, name))
    properties = mesh_properties(mesh, _DENSITY)
    if isinstance(properties, str):
        raise Diagnostics(None, context.strict).error(properties)
    inertia = SpatialInertia(
        properties.mass, np.asarray(properties.com), UnitInertia(), skip_validity_check=True
    )
    body = plant.AddRigidBody(name, instance, inertia)
    if context.has_scene_graph():
        shape = Mesh(path)
        plant.RegisterCollisionGeometry(
            body, RigidTransform(), shape, "collision", ProximityProperties()
        )
        visual = GeometryInstance(X_PG=RigidTransform(), shape=shape, name="visual")
        visual.set_illustration_properties(IllustrationProperties())
        visual.set_perception_properties(PerceptionProperties())
        plant.RegisterVisualGeometry(body, visual)
    return [instance]
