"""Scale: one corpus-style case from n = 10 to 50,000 geometries, on reimpl and two pydrakes.

The case (the same calls on every implementation, through the harness's ``Api``):

1. register a house welded into the world: blocks of up to 10 proximity
   geometries per frame, a few anchored ones (the floor), and a robot of one
   geometry per frame;
2. 20 persistent declarations: ExcludeWithin(every house frame and the world),
   the house welded (MultibodyPlant's welded-subgraph filter; drake#24246's
   scene), then robot × house excludes, robot allows and house × house allows;
3. 5 transient cycles, ApplyTransient(ExcludeBetween(A, B)) then
   RemoveDeclaration, with |A| = 5 robot geometries and B = 2 house frames
   (20 geometries) for every n ≥ 100: a cycle touches |A|·|B| = 100 pairs;
4. 2 contexts (CreateDefaultContext), one edited through its own manager;
5. CollisionFiltered on 10,000 random pairs, then the candidate count
   (``len(GetCollisionCandidates())``).

Each (implementation, n) runs in its own process, under an address-space cap
(``--memory-gib``, RLIMIT_AS) and a timeout, so the peak RSS is that process's
own and a dense table that cannot fit fails cleanly: the failure (MemoryError,
a signal, a timeout) is the result. reimpl and pydrake 1.51.1 run on this
Python; pydrake 1.58 on ``--python312``. An implementation that fails at one
n is not run at larger n.

Prints a table and the ratios (reimpl / pydrake, time and peak RSS), writes
``docs/img/scale.json`` and the log-log plot ``docs/img/scale.png``.

Usage: python benchmarks/bench_scale.py [--sizes N ...] [--memory-gib G] [--timeout S]
                                        [--python312 PATH] [--only reimpl|1.51|1.58 ...]
"""

from __future__ import annotations

import argparse
import json
import os
import random
import resource
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "img"
SIZES = (10, 30, 100, 300, 1000, 3000, 10000, 30000, 50000)


@dataclass(frozen=True)
class Implementation:
    label: str
    api: str  # "reimpl" or "pydrake"
    python: str


@dataclass
class Run:
    """One (implementation, n): seconds per stage, the cycle's ms, peak RSS, or the failure."""

    label: str
    n: int
    ok: bool = False
    failure: str = ""
    stage: str = ""
    version: str = ""
    seconds: dict[str, float] = field(default_factory=dict)
    cycle_ms: float = 0.0
    filtered: int = 0
    candidates: int = 0
    import_rss_mb: float = 0.0
    peak_rss_mb: float = 0.0
    wall_s: float = 0.0


# ------------------------------------------------------------------ the case
@dataclass(frozen=True)
class Shape:
    """How n geometries split into anchored, house blocks and robot."""

    anchored: int
    robot: int
    house_blocks: tuple[int, ...]

    @classmethod
    def of(cls, n: int) -> Shape:
        anchored = max(1, min(10, n // 10))
        robot = max(2, min(20, n // 5))
        house = n - anchored - robot
        blocks = [10] * (house // 10) + ([house % 10] if house % 10 else [])
        return cls(anchored, robot, tuple(blocks))


class Case:
    """The case's state on one ``Api``; each method is one stage of the module doc."""

    def __init__(self, api: Any, n: int) -> None:
        self.g, self.m = api.geometry, api.math
        self.shape = Shape.of(n)
        self.rng = random.Random(n)
        self.sg = self.g.SceneGraph()
        self.source = self.sg.RegisterSource(name="house")
        self.everything: list[Any] = []
        self.house_frames: list[Any] = []
        self.robot: list[Any] = []

    def _instance(self, name: str) -> Any:
        g = self.g
        return g.GeometryInstance(
            X_PG=self.m.RigidTransform(), shape=g.Sphere(radius=0.1), name=name
        )

    def _add(self, frame: Any, name: str) -> Any:
        sg, source = self.sg, self.source
        gid = sg.RegisterGeometry(source_id=source, frame_id=frame, geometry=self._instance(name))
        sg.AssignRole(source_id=source, geometry_id=gid, properties=self.g.ProximityProperties())
        return gid

    def register(self) -> None:
        sg, g, source = self.sg, self.g, self.source
        for i in range(self.shape.anchored):
            gid = sg.RegisterAnchoredGeometry(
                source_id=source, geometry=self._instance(f"floor{i}")
            )
            sg.AssignRole(source_id=source, geometry_id=gid, properties=g.ProximityProperties())
            self.everything.append(gid)
        for b, size in enumerate(self.shape.house_blocks):
            frame = sg.RegisterFrame(source_id=source, frame=g.GeometryFrame(frame_name=f"h{b}"))
            self.house_frames.append(frame)
            self.everything += [self._add(frame, f"h{b}_{j}") for j in range(size)]
        for r in range(self.shape.robot):
            frame = sg.RegisterFrame(source_id=source, frame=g.GeometryFrame(frame_name=f"r{r}"))
            self.robot.append(self._add(frame, f"r{r}"))
        self.everything += self.robot

    def _geometries(self, k: int) -> Any:
        return self.g.GeometrySet(geometry_ids=self.rng.sample(self.robot, min(k, len(self.robot))))

    def _frames(self, k: int) -> Any:
        frames = self.rng.sample(self.house_frames, min(k, len(self.house_frames)))
        return self.g.GeometrySet(frame_ids=frames)

    def _declaration(self, i: int) -> Any:
        d = self.g.CollisionFilterDeclaration()
        kind = i % 4
        if kind == 0:
            return d.ExcludeBetween(set_A=self._geometries(3), set_B=self._frames(3))
        if kind == 1:
            return d.AllowBetween(set_A=self._geometries(2), set_B=self._geometries(2))
        if kind == 2:
            return d.ExcludeWithin(geometry_set=self._geometries(3))
        return d.AllowBetween(set_A=self._frames(2), set_B=self._frames(2))

    def declare(self) -> None:
        """The house welded (ExcludeWithin of its frames and the world), then 19 more."""
        g, sg = self.g, self.sg
        welded = g.GeometrySet(frame_ids=[*self.house_frames, sg.world_frame_id()])
        sg.collision_filter_manager().Apply(
            declaration=g.CollisionFilterDeclaration().ExcludeWithin(geometry_set=welded)
        )
        for i in range(19):
            sg.collision_filter_manager().Apply(declaration=self._declaration(i))

    def transient_cycle(self) -> float:
        """One ApplyTransient + RemoveDeclaration of 5 robot geometries × 2 house frames (s)."""
        a_set, b_set = self._geometries(5), self._frames(2)
        start = time.perf_counter()
        manager = self.sg.collision_filter_manager()
        declaration = self.g.CollisionFilterDeclaration().ExcludeBetween(set_A=a_set, set_B=b_set)
        manager.RemoveDeclaration(filter_id=manager.ApplyTransient(declaration=declaration))
        return time.perf_counter() - start

    def contexts(self) -> None:
        contexts = [self.sg.CreateDefaultContext() for _ in range(2)]
        self.sg.collision_filter_manager(contexts[0]).Apply(declaration=self._declaration(0))

    def filtered(self) -> int:
        """How many of 10,000 random pairs CollisionFiltered says are filtered."""
        inspector = self.sg.model_inspector()
        pairs = [self.rng.sample(self.everything, 2) for _ in range(10_000)]
        return sum(inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b) for a, b in pairs)

    def candidates(self) -> int:
        return len(self.sg.model_inspector().GetCollisionCandidates())


def run_case(api: Any, n: int, report: Callable[[str, float], None]) -> tuple[float, int, int]:
    """The case on one ``Api``; returns (median cycle ms, filtered count, candidate count)."""

    def timed(stage: str, fn: Callable[[], Any]) -> Any:
        start = time.perf_counter()
        value = fn()
        report(stage, time.perf_counter() - start)
        return value

    case = Case(api, n)
    timed("register", case.register)
    timed("20 declarations", case.declare)
    cycles = timed("5 transient cycles", lambda: [case.transient_cycle() for _ in range(5)])
    timed("2 contexts", case.contexts)
    filtered = timed("CollisionFiltered x 10,000", case.filtered)
    candidates = timed("candidate count", case.candidates)
    return 1e3 * statistics.median(cycles), filtered, candidates


def peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def worker(api_name: str, n: int, memory_gib: float) -> None:
    """Runs the case in this process and prints one JSON line per stage, then the result."""
    cap = int(memory_gib * 2**30)
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
    if api_name == "reimpl":
        from conformance._backends.reimpl_api import reimpl_api as make  # noqa: PLC0415
    else:
        from conformance._backends.pydrake_api import pydrake_api as make  # noqa: PLC0415
    api = make()
    version = api.version if api_name == "pydrake" else "reimpl"
    print(json.dumps({"version": version, "import_rss_mb": peak_rss_mb()}), flush=True)

    def report(stage: str, seconds: float) -> None:
        print(json.dumps({"stage": stage, "seconds": seconds}), flush=True)

    try:
        cycle_ms, filtered, candidates = run_case(api, n, report)
    except BaseException:
        # A failure (MemoryError from a cap, std::bad_alloc) still reports the peak.
        print(json.dumps({"peak_rss_mb": peak_rss_mb()}), flush=True)
        raise
    print(
        json.dumps(
            {
                "cycle_ms": cycle_ms,
                "filtered": filtered,
                "candidates": candidates,
                "peak_rss_mb": peak_rss_mb(),
            }
        ),
        flush=True,
    )


# --------------------------------------------------------------- the driver
def measure(impl: Implementation, n: int, memory_gib: float, timeout: float) -> Run:
    """One worker process; its stdout lines fill the Run, its end says ok or how it failed."""
    run = Run(impl.label, n)
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    command = [impl.python, __file__, "--worker", impl.api, str(n), str(memory_gib)]
    start = time.perf_counter()
    try:
        done = subprocess.run(
            command, env=env, capture_output=True, text=True, timeout=timeout, check=False
        )
        stdout, stderr, code = done.stdout, done.stderr, done.returncode
    except subprocess.TimeoutExpired as expired:
        stdout = expired.stdout.decode() if isinstance(expired.stdout, bytes) else ""
        stderr, code = "", None
    run.wall_s = time.perf_counter() - start
    for line in stdout.splitlines():
        record = json.loads(line)
        if "stage" in record:
            run.seconds[record["stage"]] = record["seconds"]
            run.stage = record["stage"]
        else:
            for key, value in record.items():
                setattr(run, key, value)
    if code is None:
        run.failure = f"timeout after {timeout:.0f} s"
    elif code < 0:
        run.failure = f"killed by signal {-code}"
    elif code != 0:
        last = [line for line in stderr.splitlines() if line.strip()]
        run.failure = last[-1][:200] if last else f"exit {code}"
    run.ok = code == 0
    if not run.ok:
        run.failure += f" (after stage: {run.stage or 'import'})"
    return run


def total_s(run: Run) -> float:
    return sum(run.seconds.values())


def print_table(runs: list[Run], labels: list[str]) -> None:
    by = {(r.label, r.n): r for r in runs}
    sizes = sorted({r.n for r in runs})
    print(
        f"{'n':>6}  {'implementation':<16} {'case s':>8} {'cycle ms':>9} {'peak MB':>8} "
        f"{'|C|':>9}  result"
    )
    for n in sizes:
        for label in labels:
            run = by.get((label, n))
            if run is None:
                continue
            if run.ok:
                print(
                    f"{n:>6}  {label:<16} {total_s(run):>8.2f} {run.cycle_ms:>9.3f} "
                    f"{run.peak_rss_mb:>8.0f} {run.candidates:>9}  ok"
                )
            else:
                print(
                    f"{n:>6}  {label:<16} {'':>8} {'':>9} {run.peak_rss_mb:>8.0f} {'':>9}  "
                    f"{run.failure}"
                )
    print("\nratios reimpl / pydrake (same run): case time, transient cycle, peak RSS")
    for n in sizes:
        ours = by.get(("reimpl", n))
        for label in labels[1:]:
            theirs = by.get((label, n))
            if ours and theirs and ours.ok and theirs.ok:
                print(
                    f"{n:>6}  vs {label:<16} {total_s(ours) / total_s(theirs):>7.3f} "
                    f"{ours.cycle_ms / theirs.cycle_ms:>7.3f} "
                    f"{ours.peak_rss_mb / theirs.peak_rss_mb:>7.3f}"
                )


def plot(runs: list[Run], labels: list[str], path: Path) -> None:
    import matplotlib  # noqa: PLC0415 (only the driver draws)

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415

    # (title, value, whether a failed run's value means something: a peak at the cap does)
    panels = (
        ("whole case (s)", total_s, False),
        ("one transient cycle (ms)", lambda r: r.cycle_ms, False),
        ("peak RSS (MB)", lambda r: r.peak_rss_mb, True),
    )
    figure, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    for axis, (title, value, failed_value) in zip(axes, panels, strict=True):
        for label, marker in zip(labels, "os^", strict=False):
            ok = sorted((r.n, value(r)) for r in runs if r.label == label and r.ok)
            failed = sorted((r.n, value(r)) for r in runs if r.label == label and not r.ok)
            name = label + (f" (fails at n = {failed[0][0]:,})" if failed else "")
            if ok:
                (line,) = axis.plot(*zip(*ok, strict=True), marker=marker, label=name)
                for n, recorded in failed:  # an x at its recorded value, else at the line's last
                    y = recorded if failed_value and recorded > 0 else ok[-1][1]
                    axis.plot([n], [y], marker="x", markersize=10, color=line.get_color())
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_xlabel("n (proximity geometries)")
        axis.set_title(title)
        axis.grid(True, which="both", linewidth=0.3)
    axes[0].legend()
    figure.suptitle(
        "bench_scale: register, 20 declarations, 5 transient cycles, 2 contexts, "
        "10,000 CollisionFiltered, |C|"
    )
    figure.tight_layout()
    figure.savefig(path, dpi=110)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="*", default=list(SIZES))
    parser.add_argument("--memory-gib", type=float, default=18.0)
    parser.add_argument("--timeout", type=float, default=1200.0)
    parser.add_argument("--python312", default="/work/venv312/bin/python")
    parser.add_argument("--only", nargs="*", default=["reimpl", "1.51", "1.58"])
    parser.add_argument("--out", type=Path, default=OUT)
    parser.add_argument("--worker", nargs=3, metavar=("API", "N", "GIB"), help=argparse.SUPPRESS)
    parser.add_argument("--plot-only", type=Path, help="redraw the plot from a scale.json")
    args = parser.parse_args(argv)
    if args.plot_only:
        saved = json.loads(args.plot_only.read_text())["runs"]
        runs = [Run(**r) for r in saved]
        labels = list(dict.fromkeys(r.label for r in runs))
        plot(runs, labels, args.plot_only.with_suffix(".png"))
        return 0
    if args.worker:
        worker(args.worker[0], int(args.worker[1]), float(args.worker[2]))
        return 0
    implementations = [
        impl
        for impl in (
            Implementation("reimpl", "reimpl", sys.executable),
            Implementation("pydrake 1.51.1", "pydrake", sys.executable),
            Implementation("pydrake 1.58", "pydrake", args.python312),
        )
        if any(key in impl.label for key in args.only)
    ]
    labels = [impl.label for impl in implementations]
    runs: list[Run] = []
    failed: set[str] = set()
    for n in args.sizes:
        for impl in implementations:
            if impl.label in failed:
                continue
            run = measure(impl, n, args.memory_gib, args.timeout)
            runs.append(run)
            status = "ok" if run.ok else run.failure
            print(
                f"  n={n:>6} {impl.label:<16} {total_s(run):8.2f} s  "
                f"{run.peak_rss_mb:8.0f} MB  {status}",
                flush=True,
            )
            if not run.ok:
                failed.add(impl.label)
    print()
    print_table(runs, labels)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "scale.json").write_text(
        json.dumps(
            {
                "memory_cap_gib": args.memory_gib,
                "timeout_s": args.timeout,
                "runs": [asdict(r) for r in runs],
            },
            indent=1,
        )
        + "\n"
    )
    plot(runs, labels, args.out / "scale.png")
    print(f"\nwrote {args.out / 'scale.json'} and {args.out / 'scale.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
