"""Registering a body's geometry: collision (proximity role) and visual (illustration, perception).

Drake counterpart: MultibodyPlant's ``RegisterCollisionGeometry`` and
``RegisterVisualGeometry`` (multibody_plant.cc). Measured on pydrake 1.51.1:

- Only before Finalize, and only on a SceneGraph source. The geometry goes
  on F(B) (anchored for the world body), renamed to its scoped name, then
  gets its roles: collision, the proximity role (its properties, or one
  ``("material", "coulomb_friction")`` property); visual, a diffuse color as
  illustration and perception, or an instance's own visual roles (both,
  default, where it has none). The caller's instance is not changed.
- A duplicate name fails at the role assignment, after the geometry was
  registered: it stays in SceneGraph with no role and is not listed.
- The plant lists, per body, the ids it registered of each kind.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.geometry.geometry_instance import GeometryInstance
from reimpl.geometry.geometry_roles import (
    IllustrationProperties,
    PerceptionProperties,
    ProximityProperties,
)
from reimpl.geometry.identifier import GeometryId
from reimpl.geometry.rgba import Rgba
from reimpl.geometry.shape import Shape
from reimpl.math import RigidTransform
from reimpl.multibody import _link_joint_graph as graph
from reimpl.multibody._errors import NotFoundError
from reimpl.multibody.plant._coulomb_friction import CoulombFriction
from reimpl.multibody.plant._scene_graph_source import SceneGraphSource
from reimpl.multibody.tree import RigidBody

__all__ = ["GeometryRegistration"]

_OWNER = "reimpl.multibody.plant.MultibodyPlant"


def _is_rgba(value: object) -> bool:
    try:
        return np.asarray(value, dtype=float).shape in {(4,), (4, 1)}
    except (TypeError, ValueError):
        return False


_is_rgba.__name__ = "numpy.ndarray[numpy.float64[4, 1]]"


class GeometryRegistration(SceneGraphSource):
    """Collision and visual geometry on bodies' frames."""

    def RegisterCollisionGeometry(self, *args: Any, **kwargs: Any) -> GeometryId:
        """Registers ``shape`` on ``body``'s frame with the proximity role.

        N.B. As in Drake, a duplicate name fails at the role assignment, after
        the geometry was registered: it stays in SceneGraph with no role, and
        is not listed by GetCollisionGeometriesForBody.
        """

        def with_properties(
            body: RigidBody,
            X_BG: RigidTransform,
            shape: Shape,
            name: str,
            properties: ProximityProperties,
        ) -> GeometryId:
            return self._register_collision(
                body, X_BG, shape, name, ProximityProperties(properties)
            )

        def with_friction(
            body: RigidBody,
            X_BG: RigidTransform,
            shape: Shape,
            name: str,
            coulomb_friction: CoulombFriction,
        ) -> GeometryId:
            properties = ProximityProperties()
            properties.AddProperty("material", "coulomb_friction", coulomb_friction)
            return self._register_collision(body, X_BG, shape, name, properties)

        placement = (
            Param("body", instance_of(RigidBody)),
            Param("X_BG", instance_of(RigidTransform)),
            Param("shape", instance_of(Shape)),
            Param("name", instance_of(str)),
        )
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "RegisterCollisionGeometry",
            (
                Overload(
                    (*placement, Param("properties", instance_of(ProximityProperties))),
                    with_properties,
                ),
                Overload(
                    (*placement, Param("coulomb_friction", instance_of(CoulombFriction))),
                    with_friction,
                ),
            ),
            args,
            kwargs,
        )

    def _register_collision(
        self,
        body: RigidBody,
        X_BG: RigidTransform,
        shape: Shape,
        name: str,
        properties: ProximityProperties,
    ) -> GeometryId:
        self._check_not_finalized("RegisterCollisionGeometry")
        scene_graph, source_id = self._registered_scene_graph("RegisterCollisionGeometry")
        instance = GeometryInstance(X_PG=X_BG, shape=shape, name=name)
        geometry_id = self._register_geometry(body, instance)
        scene_graph.AssignRole(source_id=source_id, geometry_id=geometry_id, properties=properties)
        self._collision_geometries[int(body.index())].append(geometry_id)
        return geometry_id

    def RegisterVisualGeometry(self, *args: Any, **kwargs: Any) -> GeometryId:
        """Registers geometry on ``body``'s frame with the illustration and perception roles."""

        def with_color(
            body: RigidBody, X_BG: RigidTransform, shape: Shape, name: str, diffuse_color: Any
        ) -> GeometryId:
            # N.B. Measured: an out-of-range color raises before anything registers.
            r, g, b, a = (float(v) for v in np.asarray(diffuse_color, dtype=float).reshape(4))
            diffuse = Rgba(r, g, b, a)
            illustration, perception = IllustrationProperties(), PerceptionProperties()
            for properties in (illustration, perception):
                properties.AddProperty("phong", "diffuse", diffuse)
            instance = GeometryInstance(X_PG=X_BG, shape=shape, name=name)
            return self._register_visual(body, instance, illustration, perception)

        def with_instance(body: RigidBody, geometry_instance: GeometryInstance) -> GeometryId:
            """Registers a copy of the instance (same id) with the roles it carries.

            Without any visual role it gets both, with default properties. As in
            pydrake (which copies the instance), the caller's instance is unchanged.
            """
            instance = copy.copy(geometry_instance)
            if instance.illustration_properties() is None and (
                instance.perception_properties() is None
            ):
                instance.set_illustration_properties(IllustrationProperties())
                instance.set_perception_properties(PerceptionProperties())
            return self._register_visual(body, instance, None, None)

        body = Param("body", instance_of(RigidBody))
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "RegisterVisualGeometry",
            (
                Overload(
                    (
                        body,
                        Param("X_BG", instance_of(RigidTransform)),
                        Param("shape", instance_of(Shape)),
                        Param("name", instance_of(str)),
                        Param("diffuse_color", _is_rgba),
                    ),
                    with_color,
                ),
                Overload(
                    (body, Param("geometry_instance", instance_of(GeometryInstance))),
                    with_instance,
                ),
            ),
            args,
            kwargs,
        )

    def _register_visual(
        self,
        body: RigidBody,
        instance: GeometryInstance,
        illustration: IllustrationProperties | None,
        perception: PerceptionProperties | None,
    ) -> GeometryId:
        """Registers ``instance`` with its roles, then ``illustration``, then ``perception``.

        N.B. Measured: a duplicate name fails on the illustration role and leaves
        the geometry registered with no role.
        """
        self._check_not_finalized("RegisterVisualGeometry")
        scene_graph, source_id = self._registered_scene_graph("RegisterVisualGeometry")
        geometry_id = self._register_geometry(body, instance)
        for properties in (illustration, perception):
            if properties is not None:
                scene_graph.AssignRole(
                    source_id=source_id, geometry_id=geometry_id, properties=properties
                )
        self._visual_geometries[int(body.index())].append(geometry_id)
        return geometry_id

    def _register_geometry(self, body: RigidBody, instance: GeometryInstance) -> GeometryId:
        """Registers ``instance`` (renamed to its scoped name) on F(body); no role yet."""
        scene_graph, source_id = self._registered_scene_graph("RegisterGeometry")
        if body._plant is not self:
            raise NotFoundError(f"Body '{body.name()}' does not belong to this MultibodyPlant.")
        instance.set_name(self._scoped(body.model_instance(), instance.name()))
        index = int(body.index())
        if index == graph.WORLD:
            return scene_graph.RegisterAnchoredGeometry(source_id=source_id, geometry=instance)
        return scene_graph.RegisterGeometry(
            source_id=source_id, frame_id=self._body_frame_ids[index], geometry=instance
        )

    def num_collision_geometries(self) -> int:
        """How many collision geometries the plant registered, on all its bodies."""
        return sum(len(ids) for ids in self._collision_geometries.values())

    def GetCollisionGeometriesForBody(self, body: RigidBody) -> list[GeometryId]:
        return list(self._collision_geometries[int(body.index())])

    def GetVisualGeometriesForBody(self, body: RigidBody) -> list[GeometryId]:
        return list(self._visual_geometries[int(body.index())])
