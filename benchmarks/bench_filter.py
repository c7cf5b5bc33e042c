"""Times reimpl against pydrake in one run; prints milliseconds and the ratio reimpl/pydrake.

Scene: n frames with one proximity sphere each (|C| = n(n-1)/2). Usage:
    python benchmarks/bench_filter.py [n ...] [--json FILE]      (default: 100 300 1000)

``--json FILE`` writes the rows too (the committed one is ``docs/reports/bench_filter.json``,
whose table docs/performance.md renders).
"""

from __future__ import annotations

import argparse
import json
import random
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.reimpl_api import reimpl_api
from conformance._backends.scene_graph import Api


def scene(api: Api, n: int) -> tuple[Any, list[Any]]:
    g, m = api.geometry, api.math
    sg = g.SceneGraph()
    source = sg.RegisterSource(name="bench")
    ids = []
    for i in range(n):
        frame = sg.RegisterFrame(source_id=source, frame=g.GeometryFrame(frame_name=f"f{i}"))
        gid = sg.RegisterGeometry(
            source_id=source,
            frame_id=frame,
            geometry=g.GeometryInstance(
                X_PG=m.RigidTransform(), shape=g.Sphere(radius=0.1), name=f"g{i}"
            ),
        )
        sg.AssignRole(source_id=source, geometry_id=gid, properties=g.ProximityProperties())
        ids.append(gid)
    return sg, ids


def median_ms(fn: Callable[[], object], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append((time.perf_counter() - start) * 1e3)
    return sorted(times)[len(times) // 2]


def measure(api: Api, n: int) -> dict[str, float]:
    g = api.geometry
    rng = random.Random(0)
    results = {"register scene": median_ms(lambda: scene(api, n), 3)}
    sg, ids = scene(api, n)
    k = max(1, n // 10)

    def declaration() -> Any:
        d = g.CollisionFilterDeclaration()
        a, b = rng.sample(ids, k), rng.sample(ids, k)
        return d.ExcludeBetween(
            set_A=g.GeometrySet(geometry_ids=a), set_B=g.GeometrySet(geometry_ids=b)
        )

    def cycle() -> None:
        manager = sg.collision_filter_manager()
        manager.RemoveDeclaration(filter_id=manager.ApplyTransient(declaration=declaration()))

    results["ApplyTransient+RemoveDeclaration"] = median_ms(cycle, 21)
    results["100 persistent Apply"] = median_ms(
        lambda: [
            sg.collision_filter_manager().Apply(declaration=declaration()) for _ in range(100)
        ],
        3,
    )
    results["GetCollisionCandidates"] = median_ms(sg.model_inspector().GetCollisionCandidates, 5)
    results["CreateDefaultContext"] = median_ms(sg.CreateDefaultContext, 5)
    return results


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sizes", nargs="*", type=int, default=[100, 300, 1000])
    parser.add_argument("--json", type=Path, metavar="FILE", help="write the rows to this file")
    args = parser.parse_args(argv)
    apis = [reimpl_api(), pydrake_api()]
    print(f"{'n':>5}  {'operation':<34} {'reimpl ms':>10} {'pydrake ms':>11} {'ratio':>7}")
    rows: list[dict[str, object]] = []
    for n in args.sizes:
        ours, theirs = (measure(api, n) for api in apis)
        for op in ours:
            ratio = ours[op] / theirs[op]
            print(f"{n:>5}  {op:<34} {ours[op]:>10.3f} {theirs[op]:>11.3f} {ratio:>7.2f}")
            rows.append({"n": n, "operation": op, "reimpl_ms": ours[op], "pydrake_ms": theirs[op]})
        sys.stdout.flush()
    if args.json is not None:
        report = {"pydrake": apis[1].version, "rows": rows}
        args.json.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
