"""Posed scenes and proximity queries: shapes, poses, ``set_poses`` and the QueryObject ops.

One row per op, as in ``grammar.scene_graph``; ``backends.queries`` has one
method per op. Every op has the feature tag ``queries`` and the domain
``queries`` (the lockstep fuzzer adds them on its own terms).

Values:

- a shape (``SHAPES``): ``{"type": "sphere", "radius": r}``, ``box``
  (``width, depth, height``), ``cylinder`` and ``capsule`` (``radius,
  length``), ``ellipsoid`` (``a, b, c``), ``{"type": "halfspace"}``: the
  pydrake class called with these keywords; and a mesh file (``MESH_SHAPES``),
  ``{"type": "mesh" | "convex", "path": p, "scale": s}``: ``Mesh(filename=,
  scale=)`` or ``Convex(filename=, scale=)`` of the file at ``p`` below the
  corpus folder ``scenarios/`` (``mesh_root()``: the vendored real models'
  ``real_models/drake/...`` and ``real_models/drake_models/...``, the queries'
  own ``queries/meshes/...``), ``scale`` 1 if left out;
- a point: ``[x, y, z]`` in the world frame;
- a pose: ``{"xyz": [x, y, z], "rpy": [r, p, y]}``, both optional (zero), is
  ``RigidTransform(rpy=RollPitchYaw(rpy=rpy), p=xyz)``;
- poses: ``{frame name: pose}``, each the frame's pose in its parent frame,
  ``X_PF``, as a ``FramePoseVector`` holds it; SceneGraph composes
  ``X_WF = X_WP · X_PF``, and a geometry's ``X_WG = X_WF · X_FG``.

Queries at a location (the model, or a context): before each one the
backend fixes, on every source with frames, a ``FramePoseVector`` with the
location's stored pose of each frame (identity if none), then evaluates
the query output port. At the model each query uses a fresh
``CreateDefaultContext()``. Results name geometries, never ids; a pair's
names are sorted (A < B): where Drake's ``id_A`` has the larger name the
record swaps its points (``p_WCa`` ↔ ``p_WCb``, ``p_ACa`` ↔ ``p_BCb``) and
negates ``nhat_BA_W``. ``compute_signed_distance_pair_closest_points`` keeps
the order it was given.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from conformance._corpus_root import corpus_root
from conformance._grammar.spec import Arg, ArgKind, CommandSpec, Comparison

__all__ = [
    "DEFAULT_SHAPE",
    "DEFINITIONS",
    "MESH_SHAPES",
    "QUERY_COMMANDS",
    "SHAPES",
    "SHAPE_OF_CLASS",
    "UNSUPPORTED_PAIR",
]

K = ArgKind

#: Shape type → (the pydrake.geometry class, its constructor's keyword names, in order).
SHAPES: Mapping[str, tuple[str, tuple[str, ...]]] = {
    "sphere": ("Sphere", ("radius",)),
    "box": ("Box", ("width", "depth", "height")),
    "cylinder": ("Cylinder", ("radius", "length")),
    "capsule": ("Capsule", ("radius", "length")),
    "ellipsoid": ("Ellipsoid", ("a", "b", "c")),
    "halfspace": ("HalfSpace", ()),
}

#: Mesh-file shape type → the pydrake.geometry class (keywords ``filename``, ``scale``).
MESH_SHAPES: Mapping[str, str] = {"mesh": "Mesh", "convex": "Convex"}


def mesh_root() -> Path:
    """The folder a mesh shape's ``path`` is below: the corpus, ``scenarios/`` (looked up
    when a mesh is made, so a worker without the corpus still starts)."""
    return corpus_root()


#: The shape type of each class name (how query results name a geometry's shape).
SHAPE_OF_CLASS: Mapping[str, str] = {
    **{cls: shape for shape, (cls, _) in SHAPES.items()},
    **{cls: shape for shape, cls in MESH_SHAPES.items()},
}

#: A geometry registered without a ``shape``.
DEFAULT_SHAPE: Mapping[str, Any] = {"type": "sphere", "radius": 0.1}

_MEASURE = {"type": "number", "exclusiveMinimum": 0, "description": "A length (m), positive."}
_VECTOR = {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3}


_MESH_FILE = {
    "then": {
        "required": ["path"],
        "properties": {
            "type": True,
            "path": {
                "type": "string",
                "pattern": r"^(?!/)(?!.*(^|/)\.\.(/|$)).+\.(obj|vtk|gltf|OBJ|VTK|GLTF)$",
                "description": "A mesh file below the corpus folder scenarios/, e.g. "
                "real_models/drake/geometry/test/octahedron.obj.",
            },
            "scale": {
                "type": "number",
                "not": {"const": 0},
                "description": "The uniform scale (Drake: |scale| >= 1e-8); 1 if left out.",
            },
        },
        "additionalProperties": False,
    }
}


def _shape_schema() -> dict[str, Any]:
    """One object per shape type: ``type`` and exactly that type's measures (a mesh file:
    ``path`` and ``scale``)."""
    return {
        "description": "A shape: its pydrake class's keyword arguments, and its type. "
        "Generated from conformance._grammar.queries.SHAPES and MESH_SHAPES.",
        "type": "object",
        "required": ["type"],
        "properties": {"type": {"enum": [*SHAPES, *MESH_SHAPES]}},
        "allOf": [
            *(
                {
                    "if": {"properties": {"type": {"const": shape}}},
                    "then": {
                        "required": list(keys),
                        "properties": {"type": True, **{key: _MEASURE for key in keys}},
                        "additionalProperties": False,
                    },
                }
                for shape, (_, keys) in SHAPES.items()
            ),
            *(
                {"if": {"properties": {"type": {"const": shape}}}, **_MESH_FILE}
                for shape in MESH_SHAPES
            ),
        ],
    }


#: The schema's ``$defs`` for the value kinds of this module (``grammar.schema`` adds them).
DEFINITIONS: Mapping[str, Mapping[str, Any]] = {
    "shape": _shape_schema(),
    "pose": {
        "description": "RigidTransform(rpy=RollPitchYaw(rpy=rpy), p=xyz); each defaults to zero.",
        "type": "object",
        "additionalProperties": False,
        "properties": {"xyz": _VECTOR, "rpy": {**_VECTOR, "description": "radians"}},
    },
    "point": {**_VECTOR, "description": "A point [x, y, z] in the world frame (m)."},
    "poses": {
        "description": "Frame name → its pose in its parent frame (X_PF). The world frame "
        "has no pose to set.",
        "type": "object",
        "propertyNames": {
            "pattern": "^[A-Za-z_][A-Za-z0-9_.:/-]*$",
            "not": {"const": "world"},
        },
        "additionalProperties": {"$ref": "#/$defs/pose"},
    },
}

_CONTEXT = Arg("context", K.CONTEXT)


def _query(
    op: str,
    doc: str,
    *args: Arg,
    compare: Comparison = Comparison.EXACT,
    binding: str | None = None,
    error_choice: str | None = None,
) -> CommandSpec:
    return CommandSpec(
        op,
        (*args, _CONTEXT),
        "queries",
        doc,
        domain="queries",
        compare=compare,
        binding=binding,
        error_choice=error_choice,
    )


#: The unsupported shape pair a pairwise signed distance error names: the first the
#: broadphase meets, in an order Drake does not specify (the fuzzer saw pydrake 1.51.1 name
#: four different pairs in twelve replays of one scene).
UNSUPPORTED_PAIR = r"between shapes '\w+' and '\w+'"


QUERY_COMMANDS: tuple[CommandSpec, ...] = (
    _query(
        "set_poses",
        "Stores each frame's pose X_PF at the location (merged with earlier ones); the "
        "queries there fix them on the sources' pose ports (FramePoseVector.set_value(id=, "
        "value=), FixValue(context=, value=))",
        Arg("poses", K.POSES, True),
    ),
    _query(
        "compute_point_pair_penetration",
        "QueryObject.ComputePointPairPenetration(); returns the sorted list of "
        '{"pair", "shapes", "depth", "p_WCa", "p_WCb", "nhat_BA_W"}',
        compare=Comparison.PROXIMITY,
    ),
    _query("has_collisions", "QueryObject.HasCollisions(); returns a bool"),
    _query(
        "find_collision_candidates",
        "QueryObject.FindCollisionCandidates(); returns the sorted list of sorted name pairs "
        "(before 1.48 pydrake cannot convert its result: a binding gap)",
        binding="find-collision-candidates-since-1.48",
    ),
    _query(
        "compute_signed_distance_pairwise_closest_points",
        "QueryObject.ComputeSignedDistancePairwiseClosestPoints([max_distance=]); returns the "
        'sorted list of {"pair", "shapes", "distance", "p_ACa", "p_BCb", "nhat_BA_W"}',
        Arg("max_distance", K.DISTANCE),
        compare=Comparison.PROXIMITY,
        error_choice=UNSUPPORTED_PAIR,
    ),
    _query(
        "compute_signed_distance_pair_closest_points",
        "QueryObject.ComputeSignedDistancePairClosestPoints(geometry_id_A=, geometry_id_B=) "
        "(filters ignored); returns one record, in the pair's order",
        Arg("pair", K.PAIR, True),
        compare=Comparison.PROXIMITY,
    ),
    _query(
        "compute_signed_distance_to_point",
        "QueryObject.ComputeSignedDistanceToPoint(p_WQ=[, threshold=]) (filters do not apply); "
        'returns the list of {"geometry", "shape", "distance", "p_GN", "grad_W"} sorted by '
        "geometry name",
        Arg("p_WQ", K.POINT, True),
        Arg("threshold", K.DISTANCE),
        compare=Comparison.PROXIMITY,
    ),
    _query(
        "x_wg",
        'QueryObject.GetPoseInWorld(geometry_id=); returns {"xyz": [3], "rotation": [3][3]}',
        Arg("geometry", K.GEOMETRY, True),
        compare=Comparison.POSE,
    ),
    _query(
        "x_wf",
        'QueryObject.GetPoseInWorld(frame_id=); returns {"xyz": [3], "rotation": [3][3]}',
        Arg("frame", K.FRAME, True),
        compare=Comparison.POSE,
    ),
)
