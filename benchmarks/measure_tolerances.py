"""Measures how far reimpl's proximity numbers lie from pydrake's on near-touching scenes.

Scene ``i`` of seed ``s`` (its own generator, ``numpy.random.default_rng([s, i])``): two
shapes of the pair ``PAIRS[i % len(PAIRS)]`` (sphere, box, cylinder, capsule, ellipsoid),
whole-centimetre measures 0.05-0.6 m, random rotations (one scene in five axis-aligned,
for parallel faces); the first at the origin, the second moved along a random direction
(bisection, ``SEARCH_STEPS`` steps) until pydrake's signed distance is a random gap
±[1e-12, 1e-2] (log-uniform magnitude, either sign). Then ComputePointPairPenetration,
ComputeSignedDistancePairwiseClosestPoints, ComputeSignedDistancePairClosestPoints and
HasCollisions on both implementations, the same poses.

Per shape pair the report holds: ``records`` (penetration records both report, and the
two signed-distance records), ``max_dd`` (``|Δd|``, ``d`` the depth or signed distance),
``max_dp_far`` and ``max_dp`` (``‖Δp‖`` of every witness point, where ``|d| ≥ 1e-5`` and
for any ``d``), ``max_dn_far`` (``‖d_ref·n_ref − d·n‖`` where ``|d| ≥ 1e-5``),
``outside`` (records with a number outside ``conformance/_tolerances.py``'s row),
``outside_distance``, ``outside_witness``, ``outside_normal`` (records with that number
outside), ``gap_missed`` (scenes where pydrake's signed distance ended farther than
``GAP_MISS`` from the gap: near contact the iterative solvers' answer is not continuous
to that resolution as the shape moves), ``has_collisions_disagreements`` and
``penetration_set_disagreements`` (a record one implementation reports and the other
does not: pair sets are compared exactly), ``raised`` (scenes where an implementation
raised, in the search or in the queries; ``errors`` counts the messages), ``aborted``
(scenes whose process died; ``errors`` says in which implementation).

FCL's EPA can fail near contact (``validateNearestFeatureOfPolytopeBeingEdge()``):
pydrake raises it as RuntimeError (past a threshold its FCL allows), which is caught and
counted; python-fcl, which reimpl calls, ends the process (``terminate``), and on other
scenes than pydrake's (known divergence ``reimpl-fcl-epa-aborts``). So that an abort loses
one scene, not the run, the scenes run in child processes of this
script, ``CHUNK`` scenes each, which print one JSON line per scene; when a child dies,
the scene it was on is counted as aborted and a new child continues after it.

Usage: python3 benchmarks/measure_tolerances.py [--seed S] [--scenes N] [--json FILE]

The committed report is ``docs/reports/tolerances.json``; docs/queries.md renders it
(``docs/facts.py``: ``tolerance_study_table``). ``benchmarks/measure_hull_tolerances.py``
measures a Mesh or Convex (and a half space against it) with this script's scenes, record
comparison and child processes.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

SHAPES = ("sphere", "box", "cylinder", "capsule", "ellipsoid")
#: Unordered pairs, each once, in a fixed order (scene i gets PAIRS[i % 15]).
PAIRS = tuple((a, b) for i, a in enumerate(SHAPES) for b in SHAPES[i:])
GAP_RANGE = (1e-12, 1e-2)
#: Where witness points and normals are compared in the "far" columns.
FAR = 1e-5
SEARCH_STEPS = 80
#: A scene whose pydrake signed distance ends farther than this (m) from the gap "missed"
#: it: near contact the iterative solvers' answer is not continuous to this resolution as
#: the shape moves; the scene is measured all the same, at the bisection's last offset.
GAP_MISS = 1e-8
CHUNK = 200


def _measures(rng: np.random.Generator, shape: str) -> list[float]:
    count = {"sphere": 1, "box": 3, "cylinder": 2, "capsule": 2, "ellipsoid": 3}[shape]
    return [float(v) / 100 for v in rng.integers(5, 61, count)]


def _make_shape(api: Any, shape: str, m: list[float]) -> Any:
    g = api.geometry
    if shape == "sphere":
        return g.Sphere(radius=m[0])
    if shape == "box":
        return g.Box(width=m[0], depth=m[1], height=m[2])
    if shape == "cylinder":
        return g.Cylinder(radius=m[0], length=m[1])
    if shape == "capsule":
        return g.Capsule(radius=m[0], length=m[1])
    return g.Ellipsoid(a=m[0], b=m[1], c=m[2])


def _bound(shape: str, m: list[float]) -> float:
    """A radius of a ball about the shape's origin that holds it."""
    if shape == "capsule":
        return m[0] + m[1] / 2
    if shape == "cylinder":
        return math.hypot(m[0], m[1] / 2)
    if shape == "box":
        return math.hypot(*m) / 2
    return max(m)


class Scene:
    """Two shapes on two frames of one SceneGraph of ``api``; B's frame moves."""

    def __init__(self, api: Any, spec: dict[str, Any]) -> None:
        g, m = api.geometry, api.math
        self.api = api
        self.spec = spec
        self.sg = g.SceneGraph()
        source = self.sg.RegisterSource(name="tolerances")
        self.frames, self.ids = [], []
        for key in ("a", "b"):
            frame = self.sg.RegisterFrame(
                source_id=source, frame=g.GeometryFrame(frame_name=f"f{key}")
            )
            shape = self.make_shape(key)
            geometry = self.sg.RegisterGeometry(
                source_id=source,
                frame_id=frame,
                geometry=g.GeometryInstance(X_PG=m.RigidTransform(), shape=shape, name=key),
            )
            self.sg.AssignRole(
                source_id=source, geometry_id=geometry, properties=g.ProximityProperties()
            )
            self.frames.append(frame)
            self.ids.append(geometry)
        self.context = self.sg.CreateDefaultContext()
        self.port = self.sg.get_source_pose_port(source)

    def make_shape(self, key: str) -> Any:
        """The shape of role ``key`` ("a" or "b")."""
        return _make_shape(self.api, self.spec[f"shape_{key}"], self.spec[f"m_{key}"])

    def query(self, t: float) -> Any:
        """The QueryObject with B's frame at ``t`` along the scene's direction."""
        m = self.api.math
        vector = self.api.geometry.FramePoseVector()
        for frame, key, p in (
            (self.frames[0], "a", [0.0, 0.0, 0.0]),
            (self.frames[1], "b", [t * u for u in self.spec["direction"]]),
        ):
            rpy = m.RollPitchYaw(rpy=np.array(self.spec[f"rpy_{key}"]))
            vector.set_value(id=frame, value=m.RigidTransform(rpy=rpy, p=np.array(p)))
        self.port.FixValue(self.context, vector)
        return self.sg.get_query_output_port().Eval(self.context)

    def distance(self, t: float) -> float:
        pair = self.query(t).ComputeSignedDistancePairClosestPoints(
            geometry_id_A=self.ids[0], geometry_id_B=self.ids[1]
        )
        return float(pair.distance)


def scene_spec(seed: int, index: int) -> dict[str, Any]:
    rng = np.random.default_rng([seed, index])
    a, b = PAIRS[index % len(PAIRS)]
    spec: dict[str, Any] = {"scene": index, "shape_a": a, "shape_b": b}
    aligned = rng.random() < 0.2
    for key, shape in (("a", a), ("b", b)):
        spec[f"m_{key}"] = _measures(rng, shape)
        spec[f"rpy_{key}"] = [0.0] * 3 if aligned else list(rng.uniform(-np.pi, np.pi, 3))
    direction = rng.normal(size=3)
    spec["direction"] = list(direction / np.linalg.norm(direction))
    magnitude = math.exp(rng.uniform(math.log(GAP_RANGE[0]), math.log(GAP_RANGE[1])))
    spec["gap"] = magnitude if rng.random() < 0.5 else -magnitude
    return spec


def _find_offset(scene: Scene) -> float:
    """Bisection on t ∈ [0, far] for pydrake's signed distance = the scene's gap."""
    gap = scene.spec["gap"]
    lo = 0.0
    hi = _bound(scene.spec["shape_a"], scene.spec["m_a"])
    hi += _bound(scene.spec["shape_b"], scene.spec["m_b"]) + 0.1
    for _ in range(SEARCH_STEPS):
        mid = (lo + hi) / 2
        if scene.distance(mid) < gap:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def _records(scene: Scene, t: float, signed_distance: bool = True) -> dict[str, Any]:
    """Every record of the three queries (the penetration query alone without
    ``signed_distance``), witness points and normal named by role a/b."""
    q = scene.query(t)
    role = {scene.ids[0]: "a", scene.ids[1]: "b"}
    records: dict[str, Any] = {}
    for pair in q.ComputePointPairPenetration():
        swap = role[pair.id_A] == "b"
        pa, pb, n = pair.p_WCa, pair.p_WCb, pair.nhat_BA_W
        records["penetration"] = (
            pair.depth,
            [list(pb), list(pa)] if swap else [list(pa), list(pb)],
            list(-np.asarray(n)) if swap else list(n),
        )
    distances = (
        (
            ("pairwise", next(iter(q.ComputeSignedDistancePairwiseClosestPoints()), None)),
            (
                "pair",
                q.ComputeSignedDistancePairClosestPoints(
                    geometry_id_A=scene.ids[0], geometry_id_B=scene.ids[1]
                ),
            ),
        )
        if signed_distance
        else ()
    )
    for name, pair in distances:
        if pair is None:
            continue
        swap = role[pair.id_A] == "b"
        pa, pb, n = pair.p_ACa, pair.p_BCb, pair.nhat_BA_W
        records[name] = (
            pair.distance,
            [list(pb), list(pa)] if swap else [list(pa), list(pb)],
            list(-np.asarray(n)) if swap else list(n),
        )
    return {"records": records, "has_collisions": bool(q.HasCollisions())}


def _worker(seed: int, start: int, stop: int) -> None:
    """Prints one JSON line per scene: both implementations' records."""
    from conformance._backends.pydrake_api import pydrake_api  # noqa: PLC0415
    from conformance._backends.reimpl_api import reimpl_api  # noqa: PLC0415

    reference, other = pydrake_api(), reimpl_api()
    for index in range(start, stop):
        spec = scene_spec(seed, index)
        line: dict[str, Any] = {"scene": index, "gap": spec["gap"], "version": reference.version}
        ref_scene = Scene(reference, spec)
        print(json.dumps({"at": index, "side": "pydrake", "phase": "search"}), flush=True)
        try:
            t = _find_offset(ref_scene)
        except RuntimeError as exc:
            line["raised"] = {"phase": "search", "side": "pydrake", "message": _first(exc)}
            print(json.dumps(line), flush=True)
            continue
        for side, scene in (("pydrake", ref_scene), ("reimpl", Scene(other, spec))):
            print(json.dumps({"at": index, "side": side, "phase": "queries"}), flush=True)
            try:
                line[side] = _records(scene, t)
            except RuntimeError as exc:
                line["raised"] = {"phase": "queries", "side": side, "message": _first(exc)}
                break
        print(json.dumps(line), flush=True)


def _first(exc: Exception) -> str:
    """The first line of an error's message, FCL's location and numbers cut off."""
    lines = str(exc).splitlines()
    text = next((line for line in lines if "(): " in line), lines[0] if lines else "")
    text = re.sub(r"^.*\(\d+\)\: ", "", text)
    return re.sub(r" by [-+.e\d]+, exceeding the threshold [-+.e\d]+\.", ".", text)


def _scene_lines(
    seed: int, scenes: int, start: int = 0, script: str = __file__
) -> Iterator[dict[str, Any]]:
    """Each scene's line from child processes of ``script`` (``--worker``); a scene whose
    process died gives ``{"aborted": i, "side": ..., "phase": ..., "message": ...}`` (the
    side and phase the child last announced, FCL's original error message from its stderr,
    else its last line)."""
    while start < scenes:
        stop = min(start + CHUNK, scenes)
        child = subprocess.run(
            [sys.executable, script, "--worker", str(seed), str(start), str(stop)],
            capture_output=True,
            text=True,
            check=False,
        )
        lines = [json.loads(line) for line in child.stdout.splitlines() if line[:1] == "{"]
        done = [line for line in lines if "scene" in line]
        yield from done
        start += len(done)
        if child.returncode != 0:
            if not lines:  # pragma: no cover - a child that cannot start
                raise RuntimeError(child.stderr)
            last = lines[-1]
            err = child.stderr.strip().splitlines() or [""]
            what = next((line for line in err if "Original error message" in line), err[-1])
            message = re.sub(r"^.*\(\d+\)\: ", "", what)
            print(f"scene {start}: the process died in {last['side']} ({message})")
            yield {
                "aborted": start,
                "side": last["side"],
                "phase": last["phase"],
                "message": f"{message} (exit {child.returncode})",
            }
            start += 1
        print(f"{start}/{scenes} scenes", file=sys.stderr, flush=True)


def _norm(u: Any, v: Any) -> float:
    return float(np.linalg.norm(np.asarray(u, dtype=float) - np.asarray(v, dtype=float)))


def _empty() -> dict[str, Any]:
    return {
        "scenes": 0,
        "records": 0,
        "max_dd": 0.0,
        "max_dp_far": 0.0,
        "max_dp": 0.0,
        "max_dn_far": 0.0,
        "outside": 0,
        "outside_distance": 0,
        "outside_witness": 0,
        "outside_normal": 0,
        "gap_missed": 0,
        "has_collisions_disagreements": 0,
        "penetration_set_disagreements": 0,
        "raised": 0,
        "aborted": 0,
    }


def _compare(row: dict[str, Any], ref: Any, other: Any, tol: Any) -> None:
    """Folds one record's differences into ``row``; NaN agrees only with NaN."""
    d_ref, points_ref, n_ref = ref
    d, points, n = other
    row["records"] += 1
    dd = abs(d_ref - d) if not (math.isnan(d_ref) and math.isnan(d)) else 0.0
    dp = max(_norm(p, q) for p, q in zip(points_ref, points, strict=True))
    dn = _norm(np.multiply(d_ref, n_ref), np.multiply(d, n))
    if math.isnan(dn) and all(math.isnan(x) for x in (*n_ref, *n)):
        dn = 0.0
    row["max_dd"] = max(row["max_dd"], dd) if not math.isnan(dd) else math.inf
    row["max_dp"] = max(row["max_dp"], dp)
    far = abs(d_ref) >= FAR
    if far:
        row["max_dp_far"] = max(row["max_dp_far"], dp)
        row["max_dn_far"] = max(row["max_dn_far"], dn)
    beyond = {"distance": not dd <= tol.distance}
    if abs(d_ref) >= tol.touching:
        beyond["witness"] = not dp <= tol.witness
        beyond["normal"] = not dn <= tol.normal
    for name, out in beyond.items():
        row[f"outside_{name}"] += int(out)
    row["outside"] += int(any(beyond.values()))


def measure(seed: int, scenes: int) -> dict[str, Any]:
    from conformance._tolerances import tolerance  # noqa: PLC0415

    rows = {f"{a}–{b}": _empty() for a, b in PAIRS}
    version = None
    errors: dict[str, int] = {}
    for line in _scene_lines(seed, scenes):
        if "aborted" in line:
            a, b = PAIRS[line["aborted"] % len(PAIRS)]
            rows[f"{a}–{b}"]["aborted"] += 1
            key = f"{line['side']} ({line['phase']}), aborted: {line['message']}"
            errors[key] = errors.get(key, 0) + 1
            continue
        a, b = PAIRS[line["scene"] % len(PAIRS)]
        row, tol = rows[f"{a}–{b}"], tolerance(a, b)
        version = line["version"]
        if "raised" in line:
            raised = line["raised"]
            row["raised"] += 1
            key = f"{raised['side']} ({raised['phase']}): {raised['message'].strip()}"
            errors[key] = errors.get(key, 0) + 1
            continue
        row["scenes"] += 1
        ref, other = line["pydrake"], line["reimpl"]
        reached = ref["records"]["pair"][0]
        row["gap_missed"] += not abs(reached - line["gap"]) <= GAP_MISS
        row["has_collisions_disagreements"] += ref["has_collisions"] != other["has_collisions"]
        for kind in ("penetration", "pairwise", "pair"):
            present = (kind in ref["records"], kind in other["records"])
            if present[0] != present[1]:
                row["penetration_set_disagreements"] += 1
            elif present[0]:
                _compare(row, ref["records"][kind], other["records"][kind], tol)
    return {
        "command": f"python3 benchmarks/measure_tolerances.py --seed {seed} --scenes {scenes}",
        "pydrake": version,
        "seed": seed,
        "scenes": scenes,
        "gap_range": list(GAP_RANGE),
        "far": FAR,
        "gap_miss": GAP_MISS,
        "pairs": rows,
        "errors": errors,
    }


def cli(
    argv: list[str],
    *,
    doc: str,
    worker: Callable[[int, int, int], None],
    study: Callable[[int, int], dict[str, Any]],
    scenes: int,
) -> None:
    """A study's command line: ``--worker SEED START STOP`` (a child process), else
    ``[--seed S] [--scenes N] [--json FILE]``, printing the report."""
    if argv[:1] == ["--worker"]:
        worker(*(int(v) for v in argv[1:4]))
        return
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--scenes", type=int, default=scenes)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)
    text = json.dumps(study(args.seed, args.scenes), indent=1) + "\n"
    if args.json is not None:
        args.json.write_text(text, encoding="utf-8")
    print(text)


def main(argv: list[str]) -> None:
    cli(argv, doc=__doc__, worker=_worker, study=measure, scenes=1500)


if __name__ == "__main__":
    main(sys.argv[1:])
