"""Measures how far reimpl's proximity numbers lie from pydrake's for convex hulls, near touching.

The companion of ``benchmarks/measure_tolerances.py`` (whose scene machinery, record
comparison and child processes it uses) for a Mesh or Convex, which in the proximity role
is Drake's convex hull of the file (rows ``HULL`` and ``HULL_HALFSPACE`` of
``conformance/_tolerances.py``).

Scene ``i`` of seed ``s`` (its own generator, ``numpy.random.default_rng([s, i])``): shape
A a hull, shape B of ``OTHERS[i % len(OTHERS)]`` (sphere, box, cylinder, capsule,
ellipsoid, another hull, a half space). A hull is one of ``HULLS`` (files the repository
vendors under scenarios/: Drake's jaco and iiwa collision meshes, Drake's octahedron and
cuboctahedron test meshes, the corpus's generated polyhedra; ``.obj``, ``.gltf`` and
``.vtk``), chosen at random, each time as a Mesh or a Convex at random. Random rotations
(one scene in five axis-aligned); the other shapes' measures as in
``measure_tolerances.py``. A hull is placed with the centre of its bounding box (pydrake's
``GetConvexHull().CalcBoundingBox()``, rounded to the millimetre) at the origin of its
search; B starts where A's centre is and moves along a random direction (bisection,
``SEARCH_STEPS`` steps) until pydrake's signed distance is a random gap ±[1e-12, 1e-2]
(log-uniform magnitude, either sign).

A half space has no signed distance to a hull in Drake (both implementations raise), so a
half space moves along its own outward normal; the bisection reads pydrake's penetration
depth to a negative gap, or to the contact and then the gap farther to a positive one, and
only ComputePointPairPenetration and HasCollisions are compared.

The report has the columns of ``measure_tolerances.py``'s (per shape pair: ``records``,
``max_dd``, ``max_dp_far``, ``max_dp``, ``max_dn_far``, ``outside``..., ``gap_missed``,
``has_collisions_disagreements``, ``penetration_set_disagreements``, ``raised``,
``aborted``) plus ``equal_dd`` (records whose ``d`` is equal to the bit), ``max_d_disagreeing`` (the
largest ``|d|`` of pydrake on a scene where ``HasCollisions`` or a pair set disagrees: its
signed distance, else minus its depth, else the gap) and ``hulls`` (how
many scenes each hull file took part in).

Usage: python3 benchmarks/measure_hull_tolerances.py [--seed S] [--scenes N] [--json FILE]

The committed report is ``docs/reports/tolerances_hull.json``; docs/queries.md renders it
(``docs/facts.py``: ``hull_study_summary``, ``hull_study_table``).
"""

from __future__ import annotations

import json
import math
import sys
from functools import cache
from pathlib import Path
from typing import Any

import measure_tolerances as base
import numpy as np

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"
#: (file below scenarios/, scale): the hulls a scene draws from.
HULLS = (
    ("queries/meshes/poly8.obj", 1.0),
    ("queries/meshes/poly12.obj", 1.0),
    ("queries/meshes/two_tets.vtk", 1.0),
    ("real_models/drake/geometry/test/octahedron.obj", 0.1),
    ("real_models/drake/examples/scene_graph/cuboctahedron_with_hole.obj", 0.1),
    ("real_models/drake_models/jaco_description/meshes/arm_half_1.gltf", 1.0),
    ("real_models/drake_models/jaco_description/meshes/hand_3finger.obj", 1.0),
    ("real_models/drake_models/jaco_description/meshes/finger_proximal.obj", 1.0),
    ("real_models/drake_models/iiwa_description/meshes/iiwa14/collision/link_6.obj", 1.0),
    (
        "real_models/drake_models/iiwa_description/meshes/iiwa14/collision/link_7_polytope.obj",
        1.0,
    ),
)
HULL_KINDS = ("mesh", "convex")
#: B's shape kind; scene i gets OTHERS[i % 7].
OTHERS = ("sphere", "box", "cylinder", "capsule", "ellipsoid", "hull", "halfspace")
SEARCH_STEPS = base.SEARCH_STEPS
GAP_RANGE = base.GAP_RANGE


def pair_name(other: str) -> str:
    """The report's row of a hull against ``other``."""
    return f"mesh/convex–{'mesh/convex' if other == 'hull' else other}"


def _pick_hull(rng: np.random.Generator) -> dict[str, Any]:
    path, scale = HULLS[int(rng.integers(len(HULLS)))]
    return {"kind": HULL_KINDS[int(rng.integers(2))], "path": path, "scale": scale}


def scene_spec(seed: int, index: int) -> dict[str, Any]:
    """Scene ``index`` of ``seed``: shapes, measures (a hull's file), rotations, gap."""
    rng = np.random.default_rng([seed, index])
    other = OTHERS[index % len(OTHERS)]
    spec: dict[str, Any] = {"scene": index, "other": other}
    aligned = rng.random() < 0.2
    spec["hull_a"] = _pick_hull(rng)
    spec["shape_a"], spec["m_a"] = spec["hull_a"]["kind"], []
    if other == "hull":
        spec["hull_b"] = _pick_hull(rng)
        spec["shape_b"], spec["m_b"] = spec["hull_b"]["kind"], []
    else:
        spec["shape_b"] = other
        spec["m_b"] = [] if other == "halfspace" else base._measures(rng, other)
    for key in ("a", "b"):
        spec[f"rpy_{key}"] = [0.0] * 3 if aligned else list(rng.uniform(-np.pi, np.pi, 3))
    direction = rng.normal(size=3)
    spec["direction"] = list(direction / np.linalg.norm(direction))
    magnitude = math.exp(rng.uniform(math.log(GAP_RANGE[0]), math.log(GAP_RANGE[1])))
    spec["gap"] = magnitude if rng.random() < 0.5 else -magnitude
    return spec


@cache
def _hull_box(path: str, scale: float) -> tuple[tuple[float, ...], float]:
    """pydrake's hull of the file: its bounding box's centre rounded to the millimetre (in
    the shape's frame) and the radius of a ball about that centre that holds the hull."""
    from pydrake.geometry import Mesh  # noqa: PLC0415

    hull = Mesh(filename=str(SCENARIOS / path), scale=scale).GetConvexHull()
    centre, size = hull.CalcBoundingBox()
    rounded = tuple(round(float(v), 3) for v in centre)
    return rounded, float(np.linalg.norm(size)) / 2 + 0.01


def _rotation(rpy: list[float]) -> np.ndarray:
    from pydrake.math import RollPitchYaw  # noqa: PLC0415

    return np.asarray(RollPitchYaw(rpy=np.array(rpy)).ToRotationMatrix().matrix())


def placed_spec(spec: dict[str, Any]) -> dict[str, Any]:
    """``spec`` with the frames' positions, A at ``p_a`` and B at ``p_b0 + t·u`` (a hull's
    bounding-box centre at the origin at ``t = 0``), and the bisection's far end ``far``,
    from pydrake's hulls; a half space's direction ``u`` is its inward normal (minus the +z
    axis of its frame), so that a larger ``t`` separates."""
    spec = dict(spec)
    radius = 0.1
    for key in ("a", "b"):
        hull = spec.get(f"hull_{key}")
        position = np.zeros(3)
        if hull is not None:
            centre, hull_radius = _hull_box(hull["path"], hull["scale"])
            position = -_rotation(spec[f"rpy_{key}"]) @ np.array(centre)
            radius += hull_radius
        elif spec["shape_b"] != "halfspace":
            radius += base._bound(spec["shape_b"], spec["m_b"])
        spec["p_a" if key == "a" else "p_b0"] = [float(v) for v in position]
    if spec["shape_b"] == "halfspace":
        normal = _rotation(spec["rpy_b"]) @ np.array([0.0, 0.0, 1.0])
        spec["direction"] = [float(-v) for v in normal]
    spec["far"] = radius
    return spec


class HullScene(base.Scene):
    """``measure_tolerances.Scene`` with hulls and a half space, A and B at their start
    positions."""

    def make_shape(self, key: str) -> Any:
        g = self.api.geometry
        shape = self.spec[f"shape_{key}"]
        if shape == "halfspace":
            return g.HalfSpace()
        if shape in HULL_KINDS:
            hull = self.spec[f"hull_{key}"]
            make = g.Mesh if shape == "mesh" else g.Convex
            return make(filename=str(SCENARIOS / hull["path"]), scale=hull["scale"])
        return super().make_shape(key)

    def query(self, t: float) -> Any:
        m = self.api.math
        vector = self.api.geometry.FramePoseVector()
        p_b = [p + t * u for p, u in zip(self.spec["p_b0"], self.spec["direction"], strict=True)]
        for frame, key, p in (
            (self.frames[0], "a", self.spec["p_a"]),
            (self.frames[1], "b", p_b),
        ):
            rpy = m.RollPitchYaw(rpy=np.array(self.spec[f"rpy_{key}"]))
            vector.set_value(id=frame, value=m.RigidTransform(rpy=rpy, p=np.array(p)))
        self.port.FixValue(self.context, vector)
        return self.sg.get_query_output_port().Eval(self.context)

    def distance(self, t: float) -> float:
        """pydrake's signed distance; against a half space, minus the penetration depth
        (``inf`` where the two do not penetrate)."""
        if self.spec["other"] != "halfspace":
            return super().distance(t)
        pairs = self.query(t).ComputePointPairPenetration()
        return -float(pairs[0].depth) if pairs else math.inf


def _find_offset(scene: HullScene) -> float:
    """Bisection on t ∈ [0, far] for pydrake's signed distance = the gap (a half space: to
    the gap if negative, else to the contact, then the gap farther)."""
    gap = scene.spec["gap"]
    beyond = 0.0
    if scene.spec["other"] == "halfspace" and gap > 0:
        gap, beyond = 0.0, gap
    lo, hi = 0.0, scene.spec["far"]
    for _ in range(SEARCH_STEPS):
        mid = (lo + hi) / 2
        if scene.distance(mid) < gap:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2 + beyond


def _worker(seed: int, start: int, stop: int) -> None:
    """Prints one JSON line per scene: both implementations' records."""
    from conformance._backends.pydrake_api import pydrake_api  # noqa: PLC0415
    from conformance._backends.reimpl_api import reimpl_api  # noqa: PLC0415

    reference, other = pydrake_api(), reimpl_api()
    for index in range(start, stop):
        spec = placed_spec(scene_spec(seed, index))
        line: dict[str, Any] = {"scene": index, "gap": spec["gap"], "version": reference.version}
        line["hulls"] = [spec[k]["path"] for k in ("hull_a", "hull_b") if k in spec]
        signed_distance = spec["other"] != "halfspace"
        ref_scene = HullScene(reference, spec)
        print(json.dumps({"at": index, "side": "pydrake", "phase": "search"}), flush=True)
        try:
            t = _find_offset(ref_scene)
        except RuntimeError as exc:
            line["raised"] = {"phase": "search", "side": "pydrake", "message": base._first(exc)}
            print(json.dumps(line), flush=True)
            continue
        for side, scene in (("pydrake", ref_scene), ("reimpl", HullScene(other, spec))):
            print(json.dumps({"at": index, "side": side, "phase": "queries"}), flush=True)
            try:
                line[side] = base._records(scene, t, signed_distance=signed_distance)
            except RuntimeError as exc:
                line["raised"] = {"phase": "queries", "side": side, "message": base._first(exc)}
                break
        print(json.dumps(line), flush=True)


def _reached(line: dict[str, Any], other: str) -> float | None:
    """pydrake's signed distance at the scene's offset (a half space: minus the depth,
    where the gap is negative; None where the gap is positive)."""
    records = line["pydrake"]["records"]
    if other != "halfspace":
        return float(records["pair"][0])
    if line["gap"] > 0:
        return None
    return -float(records["penetration"][0]) if "penetration" in records else math.inf


def _pydrake_d(line: dict[str, Any]) -> float:
    """pydrake's signed distance at the scene's offset, else minus its penetration depth
    (a half space), else the scene's gap (a half space beyond contact)."""
    records = line["pydrake"]["records"]
    if "pair" in records:
        return float(records["pair"][0])
    if "penetration" in records:
        return -float(records["penetration"][0])
    return float(line["gap"])


def measure(seed: int, scenes: int) -> dict[str, Any]:
    from conformance._tolerances import tolerance  # noqa: PLC0415

    rows = {
        pair_name(o): {**base._empty(), "equal_dd": 0, "max_d_disagreeing": 0.0} for o in OTHERS
    }
    hulls = {path: 0 for path, _ in HULLS}
    version = None
    errors: dict[str, int] = {}
    script = str(Path(__file__).resolve())
    for line in base._scene_lines(seed, scenes, script=script):
        if "aborted" in line:
            other = OTHERS[line["aborted"] % len(OTHERS)]
            rows[pair_name(other)]["aborted"] += 1
            key = f"{line['side']} ({line['phase']}), aborted: {line['message']}"
            errors[key] = errors.get(key, 0) + 1
            continue
        other = OTHERS[line["scene"] % len(OTHERS)]
        row = rows[pair_name(other)]
        tol = tolerance("mesh", "mesh" if other == "hull" else other)
        version = line["version"]
        for path in line["hulls"]:
            hulls[path] += 1
        if "raised" in line:
            raised = line["raised"]
            row["raised"] += 1
            key = f"{raised['side']} ({raised['phase']}): {raised['message'].strip()}"
            errors[key] = errors.get(key, 0) + 1
            continue
        row["scenes"] += 1
        ref, new = line["pydrake"], line["reimpl"]
        reached = _reached(line, other)
        if reached is not None:
            row["gap_missed"] += not abs(reached - line["gap"]) <= base.GAP_MISS
        disagrees = ref["has_collisions"] != new["has_collisions"]
        row["has_collisions_disagreements"] += disagrees
        for kind in ("penetration", "pairwise", "pair"):
            present = (kind in ref["records"], kind in new["records"])
            if present[0] != present[1]:
                row["penetration_set_disagreements"] += 1
                disagrees = True
            elif present[0]:
                base._compare(row, ref["records"][kind], new["records"][kind], tol)
                row["equal_dd"] += ref["records"][kind][0] == new["records"][kind][0]
        if disagrees:
            row["max_d_disagreeing"] = max(row["max_d_disagreeing"], abs(_pydrake_d(line)))
    return {
        "command": f"python3 benchmarks/measure_hull_tolerances.py --seed {seed} --scenes {scenes}",
        "pydrake": version,
        "seed": seed,
        "scenes": scenes,
        "gap_range": list(GAP_RANGE),
        "far": base.FAR,
        "gap_miss": base.GAP_MISS,
        "hulls": hulls,
        "pairs": rows,
        "errors": errors,
    }


def main(argv: list[str]) -> None:
    base.cli(argv, doc=__doc__, worker=_worker, study=measure, scenes=3500)


if __name__ == "__main__":
    main(sys.argv[1:])
