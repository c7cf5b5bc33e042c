"""Times posed proximity queries, reimpl against pydrake in one run; prints ms and ratios.

Scene: n spheres (radius r) on n frames posed at random in a cube of side L
(rotations random too); with the defaults (n = 1000, r = 0.3, L = 10) a few
hundred pairs overlap. Both implementations get the same poses; the pair counts
are printed to show they answer alike. Two timings per query, each the median
of ``repeat`` runs, pydrake's and reimpl's runs interleaved:

* "same poses": the query again on the QueryObject of a posed context (both
  implementations cache the poses; reimpl also keeps the broadphase's pairs and
  the narrowphase answers per pose, so this is its cheapest case);
* "new poses": FixValue of the other of two FramePoseVectors, then the query
  (pose update, broadphase and narrowphase from scratch on both sides).

Mesh scene (``mesh``): n copies of a real robot's collision mesh, Drake's
Jaco forearm (``drake_models/jaco_description/meshes/forearm.obj``, 0.08 x 0.25
x 0.06 m, its convex hull in the proximity role), posed the same way in a cube of
side L (defaults n = 200, L = 2).

Usage: python benchmarks/bench_queries.py [n [r [L]]] [--json FILE]
       python benchmarks/bench_queries.py mesh [n [L]] [--json FILE]

``--json FILE`` writes the medians too (the committed ones are
``docs/reports/bench_queries.json`` and ``bench_queries_mesh.json``, whose tables
docs/performance.md renders).
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.reimpl_api import reimpl_api
from conformance._backends.scene_graph import Api

MAX_DISTANCE = 0.05
#: The mesh scene's shape: a Jaco arm link's collision mesh from Drake's drake_models.
MESH = (
    Path(__file__).resolve().parents[1]
    / "scenarios/real_models/drake_models/jaco_description/meshes/forearm.obj"
)


def sphere(radius: float) -> Callable[[Api], Any]:
    return lambda api: api.geometry.Sphere(radius=radius)


def mesh(api: Api) -> Any:
    return api.geometry.Mesh(filename=str(MESH), scale=1.0)


class Posed:
    """n proximity shapes on n frames, with two FramePoseVectors to alternate between."""

    def __init__(self, api: Api, n: int, shape: Callable[[Api], Any], side: float) -> None:
        g, m = api.geometry, api.math
        self.sg = g.SceneGraph()
        self.source = self.sg.RegisterSource(name="bench")
        frames = []
        for i in range(n):
            frame = self.sg.RegisterFrame(
                source_id=self.source, frame=g.GeometryFrame(frame_name=f"f{i}")
            )
            geometry = self.sg.RegisterGeometry(
                source_id=self.source,
                frame_id=frame,
                geometry=g.GeometryInstance(
                    X_PG=m.RigidTransform(), shape=shape(api), name=f"g{i}"
                ),
            )
            self.sg.AssignRole(
                source_id=self.source, geometry_id=geometry, properties=g.ProximityProperties()
            )
            frames.append(frame)
        rng = np.random.default_rng(0)
        self.vectors = []
        for _ in range(2):
            vector = g.FramePoseVector()
            for frame in frames:
                rpy = m.RollPitchYaw(rpy=rng.uniform(-np.pi, np.pi, 3))
                vector.set_value(
                    id=frame, value=m.RigidTransform(rpy=rpy, p=rng.uniform(0, side, 3))
                )
            self.vectors.append(vector)
        self.context = self.sg.CreateDefaultContext()
        self.port = self.sg.get_source_pose_port(self.source)
        self.port.FixValue(self.context, self.vectors[0])
        self.query = self.sg.get_query_output_port().Eval(self.context)
        self.turn = 0

    def repose(self) -> Any:
        """Fixes the other pose vector; returns the QueryObject, evaluated again."""
        self.turn = 1 - self.turn
        self.port.FixValue(self.context, self.vectors[self.turn])
        return self.sg.get_query_output_port().Eval(self.context)


QUERIES: dict[str, Callable[[Any], Any]] = {
    "ComputePointPairPenetration": lambda q: q.ComputePointPairPenetration(),
    "HasCollisions": lambda q: q.HasCollisions(),
    "FindCollisionCandidates": lambda q: q.FindCollisionCandidates(),
    f"SignedDistance(max {MAX_DISTANCE})": lambda q: q.ComputeSignedDistancePairwiseClosestPoints(
        max_distance=MAX_DISTANCE
    ),
}


def run(call: Callable[[Any], Any], scene: Posed, query: Any) -> Any:
    """The query on ``query``, or (None) on the scene re-posed and evaluated again."""
    return call(scene.repose() if query is None else query)


def elapsed_ms(fn: Callable[[], object]) -> float:
    start = time.perf_counter()
    fn()
    return (time.perf_counter() - start) * 1e3


def median(values: list[float]) -> float:
    return sorted(values)[len(values) // 2]


def main(n: int, shape: Callable[[Api], Any], side: float, title: str) -> dict[str, Any]:
    reference = pydrake_api()
    pydrake_version = reference.version
    scenes = {
        "pydrake": Posed(reference, n, shape, side),
        "reimpl": Posed(reimpl_api(), n, shape, side),
    }
    print(f"n = {n} {title}, cube side {side}")
    rows: list[dict[str, Any]] = []
    for name, call in QUERIES.items():
        counts = {k: call(s.query) for k, s in scenes.items()}
        sizes = {k: v if isinstance(v, bool) else len(v) for k, v in counts.items()}
        print(f"\n{name}: pydrake {sizes['pydrake']}, reimpl {sizes['reimpl']}")
        row: dict[str, Any] = {"query": name, "answers": sizes}
        rows.append(row)
        for how, repeat in (("same poses", 41), ("new poses", 11)):
            times: dict[str, list[float]] = {k: [] for k in scenes}
            for _ in range(repeat):
                for key, scene in scenes.items():
                    query = scene.query if how == "same poses" else None
                    times[key].append(elapsed_ms(partial(run, call, scene, query)))
            pd, rm = median(times["pydrake"]), median(times["reimpl"])
            print(f"  {how:10s}  pydrake {pd:9.4f} ms   reimpl {rm:9.4f} ms   ratio {rm / pd:6.2f}")
            row[how] = {"pydrake_ms": pd, "reimpl_ms": rm}
    version = pydrake_version
    return {"n": n, "scene": title, "side": side, "pydrake": version, "rows": rows}


if __name__ == "__main__":
    args = sys.argv[1:]
    json_path = None
    if "--json" in args:
        at = args.index("--json")
        json_path, args = Path(args[at + 1]), args[:at] + args[at + 2 :]
    if args[:1] == ["mesh"]:
        report = main(
            int(args[1]) if len(args) > 1 else 200,
            mesh,
            float(args[2]) if len(args) > 2 else 2.0,
            f"meshes ({MESH.name}, its convex hull)",
        )
    else:
        radius = float(args[1]) if len(args) > 1 else 0.3
        report = main(
            int(args[0]) if args else 1000,
            sphere(radius),
            float(args[2]) if len(args) > 2 else 10.0,
            f"spheres, r = {radius}",
        )
    if json_path is not None:
        json_path.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
