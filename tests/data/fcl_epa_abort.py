"""Two shapes a touch apart whose signed distance FCL's EPA fails on (a pydrake script).

Usage: python fcl_epa_abort.py box-capsule | box-ellipsoid

Both shapes are anchored geometry (X_WG = X_PG), posed bit for bit as scenes 5407 and
10313 of ``benchmarks/measure_tolerances.py --seed 1`` left them (pydrake's X_WG, written
with float.hex). The one query is ComputeSignedDistancePairClosestPoints; a RuntimeError
is caught and printed, as a script that guards the query would.

Measured on pydrake 1.51.1 and 1.58.0 (tests/test_fcl_aborts.py):
- box-capsule: pydrake raises RuntimeError, FCL's "validateNearestFeatureOfPolytopeBeingEdge():
  The origin is outside of the polytope by 3.01829e-12, exceeding the threshold 4.44089e-16.
  This should already have been identified as separating.";
- box-ellipsoid: pydrake answers, distance 1.334765759278556e-09.
With its imports switched to ``reimpl.`` the script dies on both (SIGABRT): python-fcl lets
the same FCL failure end the process through std::terminate.
"""

import sys

import numpy as np
from pydrake.geometry import (
    Box,
    Capsule,
    Ellipsoid,
    GeometryInstance,
    ProximityProperties,
    SceneGraph,
)
from pydrake.math import RigidTransform, RotationMatrix

IDENTITY = [
    ["0x1.0p+0", "0x0.0p+0", "0x0.0p+0", "0x0.0p+0"],
    ["0x0.0p+0", "0x1.0p+0", "0x0.0p+0", "0x0.0p+0"],
    ["0x0.0p+0", "0x0.0p+0", "0x1.0p+0", "0x0.0p+0"],
]
#: Each scene: shape A and X_WA, shape B and X_WB (3x4 rows [R | p]).
SCENES = {
    "box-capsule": (
        lambda: Box(width=0.19, depth=0.05, height=0.07),
        IDENTITY,
        lambda: Capsule(radius=0.22, length=0.18),
        [
            ["0x1.0p+0", "0x0.0p+0", "0x0.0p+0", "0x1.fb04db9718b7bp-3"],
            ["0x0.0p+0", "0x1.0p+0", "0x0.0p+0", "0x1.0feee9ee11e2cp-3"],
            ["0x0.0p+0", "0x0.0p+0", "0x1.0p+0", "0x1.edc1068c26af4p-3"],
        ],
    ),
    "box-ellipsoid": (
        lambda: Box(width=0.37, depth=0.09, height=0.56),
        [
            ["0x1.f10b5bf30d7fdp-2", "0x1.8f4c7bc729015p-1", "0x1.94adc1d4c12aap-2", "0x0.0p+0"],
            ["-0x1.5cf289d77304cp-2", "0x1.2b8885324860ap-1", "-0x1.78ce53f5662f0p-1", "0x0.0p+0"],
            ["-0x1.9c3cc43665457p-1", "0x1.c7cb7c621d65cp-3", "0x1.1975e6a67e92ap-1", "0x0.0p+0"],
        ],
        lambda: Ellipsoid(a=0.11, b=0.47, c=0.6),
        [
            [
                "0x1.efa883baa0895p-3",
                "-0x1.ceb155dec46d2p-2",
                "0x1.b79f63a863b62p-1",
                "-0x1.697bb39b3647ep-2",
            ],
            [
                "-0x1.9759c698b751dp-2",
                "-0x1.b4eb7aaf58e6ep-1",
                "-0x1.5907a742781ebp-2",
                "0x1.2a70c0960287dp-2",
            ],
            [
                "0x1.c51b461938f6ep-1",
                "-0x1.0a432c13babf5p-2",
                "-0x1.8b8c47ec71a6cp-2",
                "0x1.124b4cb34d6f9p-1",
            ],
        ],
    ),
}


def pose(rows):
    """The RigidTransform whose 3x4 matrix [R | p] is ``rows`` (float.hex), bit for bit."""
    m = np.array([[float.fromhex(v) for v in row] for row in rows])
    return RigidTransform(R=RotationMatrix(R=m[:, :3]), p=m[:, 3])


def main(name):
    shape_a, rows_a, shape_b, rows_b = SCENES[name]
    scene_graph = SceneGraph()
    source = scene_graph.RegisterSource(name="scene")
    ids = []
    for key, shape, rows in (("a", shape_a, rows_a), ("b", shape_b, rows_b)):
        instance = GeometryInstance(X_PG=pose(rows), shape=shape(), name=key)
        geometry = scene_graph.RegisterAnchoredGeometry(source_id=source, geometry=instance)
        scene_graph.AssignRole(
            source_id=source, geometry_id=geometry, properties=ProximityProperties()
        )
        ids.append(geometry)
    context = scene_graph.CreateDefaultContext()
    query = scene_graph.get_query_output_port().Eval(context)
    try:
        pair = query.ComputeSignedDistancePairClosestPoints(
            geometry_id_A=ids[0], geometry_id_B=ids[1]
        )
    except RuntimeError as exc:
        print(f"RuntimeError: {exc}")
    else:
        print(f"distance: {pair.distance!r}")


if __name__ == "__main__":
    main(sys.argv[1])
