"""Per-call cost in small scenes: reimpl against the installed pydrake, in one run.

Each call is timed as a user writes it: the GeometrySets, the declaration and
a fresh ``collision_filter_manager()`` are built inside the timed call. The
scene has n frames with one proximity sphere each. Prints microseconds per call
(the median of ``--repeat`` batches) and the ratio reimpl/pydrake; the target
is at most 3 at n = 10 and n = 100.

Usage: python benchmarks/bench_calls.py [n ...] [--repeat R] [--json FILE]   (default: 10 100)

``--json FILE`` writes the rows too (the committed one is ``docs/reports/bench_calls.json``,
whose table docs/performance.md renders).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

# n frames with one proximity sphere each: bench_filter's scene (run from benchmarks/).
from bench_filter import scene

from conformance._backends.api import Api
from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.reimpl_api import reimpl_api

#: The five operations of issue 15, in the order they are printed.
OPERATIONS = (
    "Apply (one ExcludeBetween)",
    "ApplyTransient + RemoveDeclaration",
    "GetCollisionCandidates",
    "CollisionFiltered",
    "CreateDefaultContext",
)

#: Roughly 20 ms of work per batch on pydrake at n = 10.
_CALLS_PER_BATCH = {op: 2000 for op in OPERATIONS} | {
    "GetCollisionCandidates": 300,
    "CollisionFiltered": 20000,
    "CreateDefaultContext": 300,
}


def calls(api: Api, n: int) -> dict[str, Callable[[], object]]:
    """The five operations on a fresh n-geometry scene, each as one user call."""
    g = api.geometry
    sg, ids = scene(api, n)
    a, b = ids[0], ids[-1]
    inspector = sg.model_inspector()

    def declaration() -> Any:
        return g.CollisionFilterDeclaration().ExcludeBetween(
            set_A=g.GeometrySet(geometry_id=a), set_B=g.GeometrySet(geometry_id=b)
        )

    def apply() -> None:
        sg.collision_filter_manager().Apply(declaration=declaration())

    def transient_cycle() -> None:
        manager = sg.collision_filter_manager()
        manager.RemoveDeclaration(filter_id=manager.ApplyTransient(declaration=declaration()))

    return dict(
        zip(
            OPERATIONS,
            (
                apply,
                transient_cycle,
                inspector.GetCollisionCandidates,
                lambda: inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b),
                sg.CreateDefaultContext,
            ),
            strict=True,
        )
    )


def batch_us(fn: Callable[[], object], number: int) -> float:
    """One batch of ``number`` calls, in µs per call."""
    start = time.perf_counter()
    for _ in range(number):
        fn()
    return (time.perf_counter() - start) / number * 1e6


def measure(apis: list[Api], n: int, repeat: int) -> dict[str, list[float]]:
    """µs per call (the median batch) for each operation and api.

    The apis alternate batch by batch, so a slow moment of the machine costs
    both alike.
    """
    ops = [calls(api, n) for api in apis]
    scale = 10 / max(n, 10)  # bigger scenes: fewer calls per batch
    out: dict[str, list[float]] = {}
    for op in OPERATIONS:
        number = max(20, int(_CALLS_PER_BATCH[op] * scale))
        batches: list[list[float]] = [[] for _ in apis]
        for _ in range(repeat):
            for timings, o in zip(batches, ops, strict=True):
                timings.append(batch_us(o[op], number))
        out[op] = [statistics.median(timings) for timings in batches]
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sizes", nargs="*", type=int, default=[10, 100])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--json", type=Path, metavar="FILE", help="write the rows to this file")
    args = parser.parse_args(argv)
    apis = [reimpl_api(), pydrake_api()]
    print(f"reimpl against pydrake {apis[1].version}, µs per call, median of {args.repeat}")
    header = f"{'n':>5}  {'operation':<36} {'reimpl':>9} {'pydrake':>9} {'ratio':>6}"
    print(header)
    print("-" * len(header))
    worst = 0.0
    rows: list[dict[str, object]] = []
    for n in args.sizes:
        for op, (ours, theirs) in measure(apis, n, args.repeat).items():
            ratio = ours / theirs
            worst = max(worst, ratio)
            print(f"{n:>5}  {op:<36} {ours:>9.2f} {theirs:>9.2f} {ratio:>6.2f}")
            rows.append({"n": n, "operation": op, "reimpl_us": ours, "pydrake_us": theirs})
        sys.stdout.flush()
    print(f"worst ratio: {worst:.2f} (target: at most 3)")
    if args.json is not None:
        report = {"pydrake": apis[1].version, "repeat": args.repeat, "rows": rows}
        args.json.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
