"""The collision-filtering subset of ``pydrake.geometry``, reimplemented.

Import from here exactly as from ``pydrake.geometry``; the names, overloads,
keyword names, return types and error messages are pydrake's.
"""

from __future__ import annotations

from reimpl._release import release
from reimpl.geometry.collision_filter_declaration import CollisionFilterDeclaration
from reimpl.geometry.collision_filter_manager import CollisionFilterManager
from reimpl.geometry.geometry_instance import GeometryFrame, GeometryInstance
from reimpl.geometry.geometry_roles import (
    GeometryProperties,
    IllustrationProperties,
    PerceptionProperties,
    ProximityProperties,
    Role,
    RoleAssign,
)
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.geometry_version import GeometryVersion
from reimpl.geometry.identifier import FilterId, FrameId, GeometryId, SourceId
from reimpl.geometry.mesh import Convex, Mesh, MeshSource
from reimpl.geometry.polygon_surface_mesh import PolygonSurfaceMesh, SurfacePolygon
from reimpl.geometry.query_object import (
    FramePoseVector,
    FramePoseVector_,
    QueryObject,
    QueryObject_,
)
from reimpl.geometry.query_results import (
    PenetrationAsPointPair,
    PenetrationAsPointPair_,
    SignedDistancePair,
    SignedDistancePair_,
    SignedDistanceToPoint,
    SignedDistanceToPoint_,
)
from reimpl.geometry.rgba import Rgba
from reimpl.geometry.scene_graph import SceneGraph, SceneGraph_
from reimpl.geometry.scene_graph_inspector import SceneGraphInspector, SceneGraphInspector_
from reimpl.geometry.shape import (
    Box,
    Capsule,
    Cylinder,
    Ellipsoid,
    HalfSpace,
    MeshcatCone,
    Shape,
    Sphere,
)
from reimpl.geometry.shape_volume import CalcVolume

__all__ = [
    "Box",
    "CalcVolume",
    "Capsule",
    "CollisionFilterDeclaration",
    "CollisionFilterManager",
    "Convex",
    "Cylinder",
    "Ellipsoid",
    "FilterId",
    "FrameId",
    "FramePoseVector",
    "FramePoseVector_",
    "GeometryFrame",
    "GeometryId",
    "GeometryInstance",
    "GeometryProperties",
    "GeometrySet",
    "GeometryVersion",
    "HalfSpace",
    "IllustrationProperties",
    "Mesh",
    "MeshSource",
    "MeshcatCone",
    "PenetrationAsPointPair",
    "PenetrationAsPointPair_",
    "PerceptionProperties",
    "PolygonSurfaceMesh",
    "ProximityProperties",
    "QueryObject",
    "QueryObject_",
    "Rgba",
    "Role",
    "RoleAssign",
    "SceneGraph",
    "SceneGraphInspector",
    "SceneGraphInspector_",
    "SceneGraph_",
    "Shape",
    "SignedDistancePair",
    "SignedDistancePair_",
    "SignedDistanceToPoint",
    "SignedDistanceToPoint_",
    "SourceId",
    "Sphere",
    "SurfacePolygon",
]

if release.has("collision-filter-scope-since-1.42"):  # bound since 1.42 (measured: 1.41.0, 1.42.0)
    from reimpl.geometry.collision_filter_declaration import CollisionFilterScope

    __all__ += ["CollisionFilterScope"]
