"""Writes scenarios/queries/meshes.json: posed cases of Mesh and Convex shapes, with expectations.

Each case template below is run step by step on pydrake (the release installed; the
committed file was made on 1.51.1) through the conformance backend, and each query's
Result is written as the step's ``returns`` or ``error``. Drake answers the signed
distance to a point from a Mesh or Convex since 1.36.0 (drake#21471, "ComputeSignedDistanceToPoint
from meshes"); up to 1.35.0 it leaves them out, so a point-distance step expects the measured
records where release fact mesh-point-distance-since-1.36 holds and the same without the
mesh and convex ones before it (matrix: 1.30.0 passes so). Rerun after changing a case:

    python scenarios/queries/make_mesh_cases.py
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from conformance._backends.loader import load_backend
from conformance.protocol import Command

HERE = Path(__file__).resolve().parent
POLY = "queries/meshes/poly8.obj"
TETS = "queries/meshes/two_tets.vtk"
OCTAHEDRON = "real_models/drake/geometry/test/octahedron.obj"
JACO = "real_models/drake_models/jaco_description/meshes/arm_half_1.gltf"
IIWA = "real_models/drake_models/iiwa_description/meshes/iiwa14/collision/link_7_polytope.obj"
NON_CONVEX = "real_models/drake/geometry/test/non_convex_mesh.obj"

OTHERS: dict[str, dict[str, Any]] = {
    "sphere": {"type": "sphere", "radius": 0.08},
    "box": {"type": "box", "width": 0.2, "depth": 0.15, "height": 0.1},
    "cylinder": {"type": "cylinder", "radius": 0.06, "length": 0.2},
    "capsule": {"type": "capsule", "radius": 0.05, "length": 0.18},
    "ellipsoid": {"type": "ellipsoid", "a": 0.06, "b": 0.09, "c": 0.12},
    "halfspace": {"type": "halfspace"},
    "convex": {"type": "convex", "path": IIWA, "scale": 1.0},
    "mesh": {"type": "mesh", "path": OCTAHEDRON, "scale": 0.1},
}
QUERIES = (
    {"op": "compute_point_pair_penetration"},
    {"op": "has_collisions"},
    {"op": "find_collision_candidates"},
    {"op": "compute_signed_distance_pairwise_closest_points"},
    {"op": "compute_signed_distance_pair_closest_points", "pair": ["m", "o"]},
)


def _geometry(name: str, frame: str, shape: dict[str, Any]) -> dict[str, Any]:
    return {
        "op": "register_geometry",
        "name": name,
        "frame": frame,
        "roles": ["proximity"],
        "shape": shape,
    }


def _pair_case(kind: str, other: str, xyz: list[float], filtered: bool) -> dict[str, Any]:
    """A ``kind`` (mesh or convex) of the generated hull m and one ``other`` shape o, posed
    rotated (no hull face parallel to another: unique witness points)."""
    steps: list[dict[str, Any]] = [
        {"op": "register_frame", "name": "f0"},
        {"op": "register_frame", "name": "f1"},
        _geometry("m", "f0", {"type": kind, "path": POLY, "scale": 1.0}),
        _geometry("o", "f1", OTHERS[other]),
        {
            "op": "set_poses",
            "poses": {
                "f0": {"xyz": [0.0, 0.0, 0.0], "rpy": [0.1, -0.2, 0.3]},
                "f1": {"xyz": xyz, "rpy": [0.25, 0.15, -0.1]},
            },
        },
    ]
    if filtered:
        steps.append(
            {
                "op": "apply",
                "declaration": {
                    "statements": [
                        {
                            "op": "exclude_between",
                            "a": {"geometries": ["m"]},
                            "b": {"geometries": ["o"]},
                        }
                    ]
                },
            }
        )
    steps.extend(dict(q) for q in QUERIES)
    state = "filtered" if filtered else ("penetrating" if xyz[2] < 0.2 else "apart")
    return {
        "description": f"a {kind} (a generated 8-vertex hull) and a {other}, {state}: "
        "every pair query",
        "steps": steps,
    }


def _point_case() -> dict[str, Any]:
    """One geometry of each shape (three mesh files among them), apart, and query points."""
    shapes = {
        **{k: v for k, v in OTHERS.items() if k not in {"convex", "mesh"}},
        "poly": {"type": "convex", "path": POLY},
        "tets": {"type": "mesh", "path": TETS, "scale": 1.5},
        "bowl": {"type": "mesh", "path": NON_CONVEX, "scale": 0.1},
        "jaco": {"type": "convex", "path": JACO},
    }
    steps: list[dict[str, Any]] = []
    poses = {}
    for i, (name, shape) in enumerate(shapes.items()):
        steps.append({"op": "register_frame", "name": f"f{i}"})
        steps.append(_geometry(name, f"f{i}", shape))
        angle = 2 * math.pi * i / len(shapes)
        poses[f"f{i}"] = {
            "xyz": [round(0.6 * math.cos(angle), 3), round(0.6 * math.sin(angle), 3), 0.05],
            "rpy": [0.1 * (i % 3), -0.15, 0.2 * (i % 4)],
        }
    poses["f5"] = {"xyz": [0.0, 0.0, -0.5], "rpy": [0.05, -0.1, 0.0]}  # the half space: a floor
    steps.append({"op": "set_poses", "poses": poses})
    for point in ([0.0, 0.0, 0.0], [0.62, 0.02, 0.07], [0.3, 0.52, 0.06], [-0.58, -0.05, 0.04]):
        steps.append({"op": "compute_signed_distance_to_point", "p_WQ": point})
        steps.append({"op": "compute_signed_distance_to_point", "p_WQ": point, "threshold": 0.1})
    return {
        "description": "the signed distance to points from the six shapes, a convex .obj and "
        ".gltf and a mesh .vtk and non-convex .obj, with and without a threshold",
        "steps": steps,
    }


def _errors_case() -> dict[str, Any]:
    """Drake's answers for meshes it cannot measure to a point, or does not."""
    return {
        "description": "a Mesh of a .gltf is left out of the signed distance to a point (Drake "
        "has no surface for it), while its convex hull collides",
        "steps": [
            {"op": "register_frame", "name": "f0"},
            _geometry("m", "f0", {"type": "mesh", "path": JACO}),
            _geometry("s", "world", {"type": "sphere", "radius": 0.05}),
            {"op": "set_poses", "poses": {"f0": {"xyz": [0.02, 0.01, 0.03]}}},
            {"op": "compute_signed_distance_to_point", "p_WQ": [0.0, 0.0, 0.0]},
            {"op": "compute_point_pair_penetration"},
        ],
    }


def cases() -> list[dict[str, Any]]:
    out = [_pair_case("convex", other, [0.05, 0.04, 0.1], False) for other in OTHERS]
    out += [_pair_case("mesh", other, [0.04, -0.03, 0.12], False) for other in OTHERS]
    out += [_pair_case("convex", other, [0.1, 0.05, 0.45], False) for other in ("box", "convex")]
    out += [_pair_case("mesh", other, [0.05, 0.04, 0.1], True) for other in ("sphere", "box")]
    out += [_point_case(), _errors_case()]
    return out


def _measured(case: dict[str, Any]) -> dict[str, Any]:
    """The case with each query step's pydrake Result as its expectation."""
    backend = load_backend("pydrake")
    backend.reset()
    steps = []
    for template in case["steps"]:
        args = {k: v for k, v in template.items() if k != "op"}
        result = backend.execute(Command(template["op"], args))
        if template["op"].startswith(("compute_", "has_", "find_")):
            outcome = (
                {"error": result.error.to_json()}
                if result.error is not None
                else {"returns": result.value}
            )
            steps.append({**template, "expect": _by_release(template["op"], outcome)})
            continue
        if result.error is not None:
            raise RuntimeError(f"{case['description']}: {template} failed: {result.error}")
        steps.append(template)
    return {**case, "steps": steps}


#: The first release whose ComputeSignedDistanceToPoint measures to meshes (drake#21471).
#: The release fact (conformance/_policy/release_facts.json) that splits a point-distance step.
MESH_POINT_FACT = "mesh-point-distance-since-1.36"


def _by_release(op: str, outcome: dict[str, Any]) -> dict[str, Any] | list[dict[str, Any]]:
    """A point-distance step's expectation, split at ``MESH_POINT_FACT``; others as measured."""
    if op != "compute_signed_distance_to_point" or "returns" not in outcome:
        return outcome
    primitives = [r for r in outcome["returns"] if r["shape"] not in ("mesh", "convex")]
    if primitives == outcome["returns"]:
        return outcome
    return [
        {"release_fact": MESH_POINT_FACT, **outcome},
        {
            "release_fact": f"before {MESH_POINT_FACT}",
            "comment": "before drake#21471 a Mesh or Convex has no signed distance to a point",
            "returns": primitives,
        },
    ]


def main() -> None:
    document = {
        "description": "Mesh and Convex shapes (Drake's convex hull in the proximity role) "
        "against every shape, and the signed distance to a point from every shape",
        "features": ["core", "queries"],
        "drake_refs": [
            "proximity_engine.cc: ImplementGeometry(Mesh/Convex)",
            "query_object.h: ComputeSignedDistanceToPoint",
        ],
        "cases": [_measured(case) for case in cases()],
    }
    path = HERE / "meshes.json"
    path.write_text(json.dumps(document, indent=1) + "\n")
    print(f"wrote {path} ({len(document['cases'])} cases)")


if __name__ == "__main__":
    main()
