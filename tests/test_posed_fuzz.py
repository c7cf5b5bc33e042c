"""fuzz --poses: posed scenes, near-touching offsets and the queries, in lockstep with pydrake."""

from __future__ import annotations

import dataclasses
import io
import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conformance._backends.loader import load_backend
from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.reimpl_api import reimpl_api
from conformance._backends.scene_graph import SceneGraphBackend
from conformance._corpus.loader import load_file
from conformance._engine import Divergence
from conformance._fuzz import strategies as cs
from conformance._fuzz.campaign import Campaign
from conformance._fuzz.coverage import QUERY_FEATURES
from conformance._fuzz.lockstep import PosedLockstepMachine
from conformance._fuzz.operations import (
    QUERY_OPS,
    filter_in_clone,
    near_touch,
    register_posed_scene,
)
from conformance._fuzz.sequences import Recorder
from conformance._fuzz.stats import FuzzStats
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.fuzz import fuzz_command
from conformance.cli.main import _parser
from conformance.protocol import MODEL, Result

PYDRAKE = load_backend("pydrake")
REIMPL = load_backend("reimpl")


def fuzz_poses(*argv: str) -> tuple[int, str, str]:
    """``python -m conformance fuzz --poses *argv``."""
    args = _parser().parse_args(["fuzz", "--poses", *argv])
    out, err = io.StringIO(), io.StringIO()
    code = fuzz_command(args, out, err)
    return code, out.getvalue(), err.getvalue()


_SPHERE = {"type": "sphere", "radius": 0.2}
_BOX = {"type": "box", "width": 0.3, "depth": 0.2, "height": 0.4}
#: Two frames, f2 under f1, both posed; g1 anchored, g2 on f1, g3 on f2.
_SCENE = cs.Scene(
    frames=(("f1", None), ("f2", "f1")),
    geometries=(
        cs.GeometrySpec("g1", cs.WORLD, ("proximity",), _BOX, {"xyz": [0.1, 0.0, -0.3]}),
        cs.GeometrySpec("g2", "f1", ("proximity",), _SPHERE, {"rpy": [0.2, 0.0, 0.5]}),
        cs.GeometrySpec("g3", "f2", ("proximity",), _BOX, {"xyz": [0.0, 0.3, 0.1]}),
    ),
    poses=(
        ("f1", {"xyz": [0.5, -0.2, 0.4], "rpy": [0.3, -0.6, 1.2]}),
        ("f2", {"xyz": [-0.1, 0.6, 0.0], "rpy": [-1.0, 0.4, 2.0]}),
    ),
)


@settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))
@given(touch=cs.touches(), in_context=st.booleans())
def test_near_touch_puts_the_pair_at_the_drawn_gap_through_nested_posed_frames(
    touch: cs.Touch, in_context: bool
) -> None:
    """The book's X_WF = X_WP · X_PF is pydrake's: the pair's signed distance is the gap."""
    recorder = Recorder(backend=PYDRAKE, queries=True)
    register_posed_scene(recorder, _SCENE)
    if in_context:  # a context with other poses than the model's
        recorder.step("create_context", name="c")
        recorder.keep("contexts", "c")
        recorder.step("set_poses", poses={"f1": {"xyz": [0.0, 1.0, 0.0]}}, context="c")
    near_touch(recorder, bytes([255 if in_context else 0, 1]), touch)
    query = recorder.commands[-1]
    assert query.op == "compute_signed_distance_pair_closest_points"
    assert query.args.get("context") == ("c" if in_context else None)
    distance = PYDRAKE.execute(query).value["distance"]  # type: ignore[index]
    assert abs(distance - touch.gap) < 1e-12 if touch.gap >= 0 else touch.gap - 1e-12 <= distance


def test_filter_in_clone_filters_the_clone_and_neither_its_origin_nor_the_model() -> None:
    """ExcludeWithin(all three) applied in a clone of c: pydrake's clone has no candidates."""
    recorder = Recorder(backend=PYDRAKE, queries=True)
    register_posed_scene(recorder, _SCENE)
    recorder.step("create_context", name="c")
    recorder.keep("contexts", "c")
    before = len(recorder.commands)
    everything = cs.DeclarationTemplate(
        geometries=(0, 1, 2), frames=(), statements=(("exclude_within", (0b111,)),)
    )
    filter_in_clone(recorder, bytes([0, 2, 0]), everything)  # origin c; has_collisions
    issued = [(c.op, c.args.get("context")) for c in recorder.commands[before:]]
    clone = recorder.commands[before].args["name"]
    assert recorder.commands[before].args["from"] == "c"
    assert issued == [("clone_context", None), ("apply", clone), ("has_collisions", clone)]
    assert recorder.commands[before + 1].args["declaration"] == {
        "statements": [{"op": "exclude_within", "set": {"geometries": ["g3", "g4", "g5"]}}]
    }
    locations = PYDRAKE.observe().locations
    assert locations[clone].candidates == frozenset()
    expected = frozenset({("g3", "g4"), ("g3", "g5"), ("g4", "g5")})
    assert locations["c"].candidates == locations[MODEL].candidates == expected


class PenetrationIgnoresFilters(SceneGraphBackend):
    """pydrake, except that ComputePointPairPenetration ignores the declared filters.

    It queries a copy of the location's context in which every proximity
    geometry was allowed with every other (``ApplyTransient(AllowWithin(all))``;
    the invariant filters stay, as AllowWithin cannot clear them). The other
    queries and the observed state are pydrake's own.
    """

    def __init__(self) -> None:
        self._blind = False
        super().__init__(
            dataclasses.replace(pydrake_api(), name="mutant:penetration_ignores_filters")
        )

    def compute_point_pair_penetration(self, args: Mapping[str, Any]) -> list[dict[str, Any]]:
        self._blind = True
        try:
            return super().compute_point_pair_penetration(args)
        finally:
            self._blind = False

    def _posed(self, args: Mapping[str, Any]) -> tuple[Any, Any]:
        if not self._blind:
            return super()._posed(args)
        g = self.api.geometry
        location, context = self._location(args)
        if context is None:
            context = self.scene_graph.CreateDefaultContext()
        else:
            self._fix_poses(context, location)  # pydrake clones a context only so
            context = context.Clone()
        self._fix_poses(context, location)
        ids = self._inspector(context).GetAllGeometryIds(role=g.Role.kProximity)
        allow_all = g.CollisionFilterDeclaration().AllowWithin(g.GeometrySet(geometry_ids=ids))
        self.scene_graph.collision_filter_manager(context).ApplyTransient(declaration=allow_all)
        return context, self.scene_graph.get_query_output_port().Eval(context)


def penetration_ignores_filters() -> SceneGraphBackend:
    """The mutant as a backend spec: ``tests.test_posed_fuzz:penetration_ignores_filters``."""
    return PenetrationIgnoresFilters()


class _Recording(PosedLockstepMachine):
    """Records the op of every command (and counts the queries that found pairs)."""

    backend_factory = staticmethod(lambda: REIMPL)
    reference_factory = staticmethod(lambda: PYDRAKE)
    stats = FuzzStats()
    _shared = None
    issued: dict[str, int] = {}  # noqa: RUF012 (shared on purpose: one run's counts)
    found_pairs = 0

    def step(self, op: str, **args: Any) -> Result:
        result = super().step(op, **args)
        type(self).issued[op] = type(self).issued.get(op, 0) + 1
        if op == "compute_point_pair_penetration" and result.value:
            _Recording.found_pairs += 1
        return result


@pytest.mark.fuzz
def test_a_bounded_posed_campaign_of_reimpl_against_pydrake_issues_every_query_and_agrees() -> None:
    campaign = Campaign(
        backend=lambda: REIMPL,
        reference=lambda: PYDRAKE,
        seed=1,
        max_examples=100,
        machine_base=_Recording,
    )
    result = campaign.run()
    assert not result.divergences, _explained(result.divergences[0])
    assert result.stats.examples >= 60
    assert set(QUERY_OPS) <= set(_Recording.issued)
    assert _Recording.found_pairs > 10, "penetration queries find pairs, not only empty sets"
    # Meshes and convex hulls are drawn: each query answers with records of both.
    assert result.stats.coverage.gaps(list(QUERY_FEATURES), at_least=1) == []


@pytest.mark.mutant_proof
def test_a_mutant_ignoring_filters_in_penetration_is_found_and_written_as_a_case(
    tmp_path: Path,
) -> None:
    code, out, err = fuzz_poses(
        "--backend",
        "tests.test_posed_fuzz:penetration_ignores_filters",
        "--seed",
        "1",
        "--max-examples",
        "300",
        # Bounded, as the mutant tests are: unbounded, this one shrinks for 200 s.
        "--shrink-time",
        "20",
        "--out",
        str(tmp_path),
        "--quiet",
    )
    assert code == EXIT_FAILURE, out + err
    assert "fuzz --poses:" in err
    (path,) = tmp_path.glob("poses-*.json")
    assert "compute_point_pair_penetration result" in out
    assert "(reproduces)" in out
    scenario = load_file(path, root=tmp_path)
    assert "fuzz --poses" in json.loads(path.read_text())["comment"]
    (case,) = scenario.cases
    last = case.steps[-1]
    assert last.op == "compute_point_pair_penetration"
    assert any(step.op in {"apply_transient", "apply"} for step in case.steps)
    # The case passes on pydrake itself, and on reimpl; the mutant fails it.
    for backend in (PYDRAKE, REIMPL):
        code, out, err = _run(path, backend.name)
        assert code == EXIT_OK, out + err
    code, out, err = _run(path, "tests.test_posed_fuzz:penetration_ignores_filters")
    assert code == EXIT_FAILURE, out + err


def _explained(divergence: Divergence) -> str:
    steps = "\n".join(json.dumps(item.command.to_json()) for item in divergence.trace)
    return f"{divergence}\n{steps}"


def _run(path: Path, backend: str) -> tuple[int, str, str]:
    from conformance.cli.main import main  # noqa: PLC0415

    out, err = io.StringIO(), io.StringIO()
    code = main(["run", str(path), "--backend", backend], out=out, err=err)
    return code, out.getvalue(), err.getvalue()


class _WithoutQueries(SceneGraphBackend):
    """reimpl, claiming no ``queries`` feature (as an older Drake release's worker)."""

    def features(self) -> frozenset[str]:
        return super().features() - {"queries"}


def without_queries() -> SceneGraphBackend:
    """A backend spec for the test: ``tests.test_posed_fuzz:without_queries``."""
    return _WithoutQueries(dataclasses.replace(reimpl_api(), name="reimpl-without-queries"))


def test_fuzz_poses_exits_2_naming_a_backend_without_the_queries() -> None:
    code, _, err = fuzz_poses("--backend", "tests.test_posed_fuzz:without_queries")
    assert code == EXIT_USAGE
    assert err == (
        "error: --poses needs the posed queries (feature 'queries'), which "
        "reimpl-without-queries lack\n"
    )


def test_fuzz_poses_with_models_exits_2() -> None:
    code, _, err = fuzz_poses("--models", "--max-examples", "1")
    assert code == EXIT_USAGE
    assert "--models and --poses are two different campaigns" in err
