"""Mesh and Convex in the proximity role: reimpl's convex hulls and queries against pydrake's.

Each hull is compared with pydrake 1.51.1's ``GetConvexHull()`` on vendored mesh files
(.obj, .gltf, .vtk; planar ones too): the same vertex set (within 1e-12) and the same
polygons, wound the same way. Each query scene is built on both implementations through
the public API and posed at seeded random poses; pair sets and booleans must be equal,
depths and distances within the tolerances of ``conformance._tolerances``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.reimpl_api import reimpl_api
from conformance._backends.scene_graph import Api
from conformance._tolerances import tolerance

ROOT = Path(__file__).resolve().parents[1] / "scenarios" / "real_models"
DRAKE = ROOT / "drake"
MODELS = ROOT / "drake_models"

HULL_FILES = [
    DRAKE / "geometry/test/octahedron.obj",
    DRAKE / "geometry/test/quad_cube.obj",
    DRAKE / "geometry/test/convex.obj",
    DRAKE / "geometry/render_gltf_client/test/tri.obj",  # planar: Drake lifts a point off it
    DRAKE / "geometry/test/one_tetrahedron.vtk",
    DRAKE / "geometry/test/cube_as_volume.vtk",
    DRAKE / "geometry/render/test/meshes/rainbow_box.gltf",
    MODELS / "iiwa_description/meshes/iiwa14/collision/link_7_polytope.obj",
    MODELS / "jaco_description/meshes/arm_half_1.gltf",
]


def _key(v: Any) -> tuple[int, ...]:
    return tuple(int(x) for x in np.round(np.asarray(v, dtype=float) / 1e-12))


def _hull(api: Api, path: Path, scale: float) -> tuple[set[tuple[int, ...]], list[Any]]:
    """(vertex keys, polygons as cyclic key sequences, each starting at its least key)."""
    hull = api.geometry.Convex(str(path), scale).GetConvexHull()
    vertices = [hull.vertex(v) for v in range(hull.num_vertices())]
    polygons = []
    for e in range(hull.num_elements()):
        polygon = hull.element(e)
        keys = [_key(vertices[polygon.vertex(i)]) for i in range(polygon.num_vertices())]
        first = keys.index(min(keys))
        polygons.append(tuple(keys[first:] + keys[:first]))
    return {_key(v) for v in vertices}, sorted(polygons)


@pytest.mark.parametrize("path", HULL_FILES, ids=lambda p: p.name)
@pytest.mark.parametrize("scale", [1.0, 0.37])
def test_a_convex_hull_has_drakes_vertices_and_polygons(path: Path, scale: float) -> None:
    assert _hull(reimpl_api(), path, scale) == _hull(pydrake_api(), path, scale)


def test_a_hull_measures_as_drakes_polygon_mesh() -> None:
    path = str(DRAKE / "geometry/test/octahedron.obj")
    mine = reimpl_api().geometry.Mesh(path, 0.5).GetConvexHull()
    theirs = pydrake_api().geometry.Mesh(path, 0.5).GetConvexHull()
    assert (mine.num_vertices(), mine.num_faces()) == (theirs.num_vertices(), 8)
    assert mine.total_area() == pytest.approx(theirs.total_area(), abs=1e-15)
    assert mine.total_area() == pytest.approx(3.4641016151376003, abs=1e-15)  # 2√3: 8√3 at scale 1
    np.testing.assert_allclose(mine.centroid(), theirs.centroid(), atol=1e-15)
    for got, want in zip(mine.CalcBoundingBox(), theirs.CalcBoundingBox(), strict=True):
        np.testing.assert_array_equal(got, want)


# ------------------------------------------------------------------- queries
OTHERS: dict[str, Any] = {
    "sphere": lambda g: g.Sphere(radius=0.1),
    "box": lambda g: g.Box(width=0.2, depth=0.3, height=0.1),
    "cylinder": lambda g: g.Cylinder(radius=0.05, length=0.2),
    "capsule": lambda g: g.Capsule(radius=0.05, length=0.2),
    "ellipsoid": lambda g: g.Ellipsoid(a=0.05, b=0.1, c=0.15),
    "halfspace": lambda g: g.HalfSpace(),
    "convex": lambda g: g.Convex(
        str(MODELS / "iiwa_description/meshes/iiwa14/collision/link_7_polytope.obj"), 1.0
    ),
    "mesh": lambda g: g.Mesh(str(DRAKE / "geometry/test/octahedron.obj"), 0.1),
}
MESH = str(MODELS / "jaco_description/meshes/arm_half_1.gltf")


def _answers(api: Api, other: str, first: bool, poses: list[Any]) -> list[dict[str, Any]]:
    """Each pose's penetration, HasCollisions, candidates and pair signed distance."""
    g, m = api.geometry, api.math
    scene_graph = g.SceneGraph()
    source = scene_graph.RegisterSource(name="s")
    shapes = [g.Convex(MESH, 1.0), OTHERS[other](g)]
    if not first:
        shapes.reverse()
    frames, ids = [], []
    for i, shape in enumerate(shapes):
        frame = scene_graph.RegisterFrame(
            source_id=source, frame=g.GeometryFrame(frame_name=f"f{i}")
        )
        instance = g.GeometryInstance(X_PG=m.RigidTransform(), shape=shape, name=f"g{i}")
        instance.set_proximity_properties(g.ProximityProperties())
        ids.append(
            scene_graph.RegisterGeometry(source_id=source, frame_id=frame, geometry=instance)
        )
        frames.append(frame)
    names = {
        i.get_value(): n
        for i, n in zip(ids, ("mesh", other) if first else (other, "mesh"), strict=True)
    }
    out = []
    for pose in poses:
        context = scene_graph.CreateDefaultContext()
        vector = g.FramePoseVector()
        for frame, (rpy, xyz) in zip(frames, pose, strict=True):
            vector.set_value(id=frame, value=m.RigidTransform(rpy=m.RollPitchYaw(rpy=rpy), p=xyz))
        scene_graph.get_source_pose_port(source).FixValue(context=context, value=vector)
        query = scene_graph.get_query_output_port().Eval(context)
        answer: dict[str, Any] = {
            "penetration": [
                (names[p.id_A.get_value()], p.depth) for p in query.ComputePointPairPenetration()
            ],
            "collides": query.HasCollisions(),
            "candidates": len(query.FindCollisionCandidates()),
        }
        try:
            pair = query.ComputeSignedDistancePairClosestPoints(
                geometry_id_A=ids[0], geometry_id_B=ids[1]
            )
            answer["distance"] = pair.distance
        except RuntimeError as error:
            answer["distance"] = str(error)
        out.append(answer)
        del context
    return out


@pytest.mark.parametrize("other", list(OTHERS))
@pytest.mark.parametrize("first", [True, False], ids=["mesh-first", "mesh-second"])
def test_a_convex_hull_answers_as_pydrakes_against_each_shape(other: str, first: bool) -> None:
    rng = np.random.default_rng(7)
    poses = [
        [(rng.uniform(-3, 3, 3).tolist(), rng.uniform(-0.12, 0.12, 3).tolist()) for _ in range(2)]
        for _ in range(40)
    ]
    reference = pydrake_api()
    theirs = _answers(reference, other, first, poses)
    mine = _answers(reimpl_api(), other, first, poses)
    rule = tolerance("convex", other if other != "mesh" else "convex")
    # Known divergence rotated-aabb-tight-since-1.58: reimpl's broadphase boxes are those of
    # Drake's FCL up to 1.57 (measured: the same candidates as pydrake 1.51.1 at all 640
    # poses of this test); pydrake 1.58.0 bounds a rotated box by |R|·h and differs at 82 of
    # them (76 pairs reimpl still has, 6 rotated-sphere pairs it lacks). There, only a
    # penetrating pair must be a candidate.
    same_boxes = tuple(int(x) for x in reference.version.split(".")[:2]) < (1, 58)
    collided = 0
    for got, want in zip(mine, theirs, strict=True):
        assert got["collides"] == want["collides"]
        if same_boxes:
            assert got["candidates"] == want["candidates"]
        else:
            assert got["candidates"] >= len(got["penetration"])
        assert [name for name, _ in got["penetration"]] == [name for name, _ in want["penetration"]]
        for (_, a), (_, b) in zip(got["penetration"], want["penetration"], strict=True):
            assert abs(a - b) <= rule.distance
        collided += bool(want["penetration"])
        if isinstance(want["distance"], str):
            assert got["distance"] == want["distance"]
        else:
            assert abs(got["distance"] - want["distance"]) <= rule.distance
    assert collided > 2  # the poses do reach contact
