"""The posed-scene corpus (scenarios/queries) and the query ops of the grammar.

The cases' expectations were measured on pydrake 1.51.1 (the activation
cases on 1.58.0); the runner holds each backend to them, numbers within the
tolerances of ``conformance._tolerances``, and reimpl to pydrake's answers.
"""

from __future__ import annotations

import itertools
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from conformance._backends.loader import load_backend
from conformance._backends.scene_graph import SceneGraphBackend
from conformance._corpus.loader import (
    Case,
    ScenarioError,
    default_corpus_root,
    load_corpus,
    load_file,
)
from conformance._engine import Outcome
from conformance._grammar import GRAMMAR, Comparison, ops_of
from conformance._grammar.queries import QUERY_COMMANDS, SHAPES
from conformance._run.expectations import check
from conformance._run.runner import run_case
from conformance.cli.exit_codes import EXIT_USAGE
from conformance.cli.main import main
from conformance.protocol import Command, Result

QUERIES = default_corpus_root() / "queries"
FILES = load_corpus([QUERIES])
CASES = [case for f in FILES for case in f.cases]
PYDRAKE = load_backend("pydrake")
REIMPL = load_backend("reimpl")


def _id(case: Case) -> str:
    return case.qualified_name


def _case(file: str, description: str) -> Case:
    return next(
        c for c in CASES if c.file.name == f"queries/{file}" and c.description == description
    )


# ------------------------------------------------------------------ the corpus
def test_the_query_corpus_has_at_least_thirty_cases_in_its_topics() -> None:
    assert len(CASES) >= 30
    assert {f.name for f in FILES} >= {
        "queries/penetration",
        "queries/signed_distance",
        "queries/filters",
        "queries/contexts",
        "queries/frames",
        "queries/removal",
        "queries/models",
        "queries/activation",
    }


@pytest.mark.parametrize("case", CASES, ids=_id)
def test_the_query_case_holds_on_pydrake(case: Case) -> None:
    missing = case.features - PYDRAKE.features()
    if missing:
        pytest.skip(f"pydrake {PYDRAKE.version()} lacks {sorted(missing)}")
    report = run_case(case, [PYDRAKE])
    assert report.status["pydrake"] is Outcome.PASS, report.failures or report.aborted


@pytest.mark.parametrize("case", CASES, ids=_id)
def test_reimpl_agrees_with_pydrake_on_the_query_case(case: Case) -> None:
    missing = case.features - REIMPL.features()
    if missing:
        pytest.skip(f"reimpl lacks {sorted(missing)}")
    report = run_case(case, [REIMPL, PYDRAKE])
    assert report.status["reimpl"] in (Outcome.PASS, Outcome.XFAIL), report.failures


def test_every_query_op_is_exercised_and_every_query_step_expects_something() -> None:
    steps = [step for case in CASES for step in case.steps]
    assert {step.op for step in steps} >= set(ops_of("queries"))
    for step in steps:
        if GRAMMAR[step.op].domain == "queries" and step.op != "set_poses":
            assert step.expect, step


def test_every_pair_of_the_six_shapes_is_posed_to_penetrate() -> None:
    penetration = [c for c in CASES if c.file.name == "queries/penetration"]
    pairs = set()
    for case in penetration:
        shapes = [s.args["shape"]["type"] for s in case.steps if s.op == "register_geometry"]
        pairs.add(frozenset(shapes))
    assert pairs == {frozenset(p) for p in itertools.combinations_with_replacement(SHAPES, 2)}


def test_the_activation_cases_need_activation_and_the_queries_feature() -> None:
    for case in CASES:
        if any(s.op in {"activate", "deactivate"} for s in case.steps):
            assert {"activation", "queries"} <= case.features, case.qualified_name


# ------------------------------------------------------- expectations compare within tolerance
def _penetration_step(case: Case) -> tuple[Any, Any]:
    step = next(s for s in case.steps if s.op == "compute_point_pair_penetration")
    return step, step.expect[0]


def test_a_returned_depth_1e_13_off_meets_the_expectation_and_1e_3_off_does_not() -> None:
    case = _case("penetration", "sphere a and sphere b overlap: one penetration record, a-b")
    step, expectation = _penetration_step(case)
    (record,) = expectation["returns"]
    assert record["shapes"] == ["sphere", "sphere"]
    observation = PYDRAKE.observe()

    def failures(by: float) -> list[tuple[str, Any, Any]]:
        value = [{**record, "depth": record["depth"] + by}]
        return [
            f
            for f in check(step, expectation, Result(value=value), observation)
            if "at" not in f[0]
        ]

    assert [f for f in failures(1e-13) if f[0].startswith("return value")] == []
    (what, _, _) = next(f for f in failures(1e-3) if f[0].startswith("return value"))
    assert (
        what == "return value (a-b depth: |Δ| = 0.001 > 1e-12 (sphere-sphere distance tolerance))"
    )


def test_the_query_ops_say_how_their_values_compare() -> None:
    compare = {command.op: command.compare for command in QUERY_COMMANDS}
    assert compare == {
        "set_poses": Comparison.EXACT,
        "compute_point_pair_penetration": Comparison.PROXIMITY,
        "has_collisions": Comparison.EXACT,
        "find_collision_candidates": Comparison.EXACT,
        "compute_signed_distance_pairwise_closest_points": Comparison.PROXIMITY,
        "compute_signed_distance_pair_closest_points": Comparison.PROXIMITY,
        "compute_signed_distance_to_point": Comparison.PROXIMITY,
        "x_wg": Comparison.POSE,
        "x_wf": Comparison.POSE,
    }


# ------------------------------------------------------------ the backend on pydrake
def run(backend: SceneGraphBackend, *steps: dict[str, Any]) -> Result:
    """Runs the steps from a reset; returns the last Result."""
    backend.reset()
    result = Result()
    for step in steps:
        args = {k: v for k, v in step.items() if k != "op"}
        result = backend.execute(Command(step["op"], args))
    return result


SPHERE = {"type": "sphere", "radius": 0.5}
TWO = (
    {"op": "register_frame", "name": "f0"},
    {"op": "register_frame", "name": "f1"},
    {
        "op": "register_geometry",
        "name": "b",
        "frame": "f0",
        "roles": ["proximity"],
        "shape": SPHERE,
    },
    {
        "op": "register_geometry",
        "name": "a",
        "frame": "f1",
        "roles": ["proximity"],
        "shape": SPHERE,
    },
)


def test_x_wg_is_the_parent_pose_times_the_frame_pose_times_the_geometry_pose() -> None:
    """X_WG = X_WP · X_PF · X_FG, checked against numpy on pydrake's answer."""
    backend = SceneGraphBackend(PYDRAKE.api)  # type: ignore[attr-defined]
    result = run(
        backend,
        {"op": "register_frame", "name": "p"},
        {"op": "register_frame", "name": "f", "parent": "p"},
        {
            "op": "register_geometry",
            "name": "g",
            "frame": "f",
            "pose": {"xyz": [0, 0, 1], "rpy": [0.3, 0, 0]},
        },
        {"op": "set_poses", "poses": {"p": {"xyz": [1, 0, 0], "rpy": [0, 0, np.pi / 2]}}},
        {"op": "set_poses", "poses": {"f": {"xyz": [0, 2, 0]}}},
        {"op": "x_wg", "geometry": "g"},
    )
    assert result.error is None
    c, s = np.cos(0.3), np.sin(0.3)
    R_WP = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    R_FG = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    p_WG = np.array([1.0, 0.0, 0.0]) + R_WP @ (
        np.array([0.0, 2.0, 0.0]) + np.array([0.0, 0.0, 1.0])
    )
    assert np.allclose(result.value["xyz"], p_WG, atol=1e-15)
    assert p_WG.tolist() == pytest.approx([-1.0, 0.0, 1.0])
    assert np.allclose(result.value["rotation"], R_WP @ R_FG, atol=1e-15)


def test_penetration_names_its_pair_in_order_and_the_pair_query_keeps_the_given_order() -> None:
    """b has the smaller id (registered first), a the smaller name: the record is swapped."""
    backend = SceneGraphBackend(PYDRAKE.api)  # type: ignore[attr-defined]
    poses = {"op": "set_poses", "poses": {"f1": {"xyz": [0.9, 0.0, 0.0]}}}
    (record,) = run(backend, *TWO, poses, {"op": "compute_point_pair_penetration"}).value
    assert record["pair"] == ["a", "b"]
    assert record["depth"] == pytest.approx(0.1, abs=1e-15)
    assert record["p_WCa"] == pytest.approx([0.4, 0.0, 0.0])  # a's point deepest in b
    assert record["p_WCb"] == pytest.approx([0.5, 0.0, 0.0])
    assert record["nhat_BA_W"] == pytest.approx([1.0, 0.0, 0.0])  # from b into a
    pair = run(
        backend,
        *TWO,
        poses,
        {"op": "compute_signed_distance_pair_closest_points", "pair": ["b", "a"]},
    ).value
    assert pair["pair"] == ["b", "a"]
    assert pair["distance"] == pytest.approx(-0.1, abs=1e-15)
    assert pair["nhat_BA_W"] == pytest.approx([-1.0, 0.0, 0.0])  # from a into b


def test_set_poses_merges_and_a_clone_inherits_its_source_s_poses() -> None:
    backend = SceneGraphBackend(PYDRAKE.api)  # type: ignore[attr-defined]
    steps = (
        *TWO,
        {"op": "create_context", "name": "c"},
        {"op": "set_poses", "context": "c", "poses": {"f0": {"xyz": [5.0, 0.0, 0.0]}}},
        {"op": "set_poses", "context": "c", "poses": {"f1": {"xyz": [0.0, 7.0, 0.0]}}},
        {"op": "clone_context", "name": "d", "from": "c"},
    )
    assert run(backend, *steps, {"op": "x_wf", "frame": "f0", "context": "d"}).value["xyz"] == [
        5.0,
        0.0,
        0.0,
    ]
    assert run(backend, *steps, {"op": "x_wf", "frame": "f1", "context": "d"}).value["xyz"] == [
        0.0,
        7.0,
        0.0,
    ]
    assert run(backend, *steps, {"op": "x_wf", "frame": "f1"}).value["xyz"] == [0.0, 0.0, 0.0]


@pytest.mark.parametrize("shape", list(SHAPES))
def test_the_backend_makes_each_grammar_shape_on_both_implementations(shape: str) -> None:
    spec = {"type": shape, **{key: 0.5 for key in SHAPES[shape][1]}}
    for backend in (SceneGraphBackend(PYDRAKE.api), SceneGraphBackend(REIMPL.api)):  # type: ignore[attr-defined]
        made = backend.shape(spec)
        assert type(made).__name__ == SHAPES[shape][0]


# --------------------------------------------------------------- bad input: exit 2
BAD_STEPS = {
    "a shape without its radius": (
        {"op": "register_geometry", "name": "g", "frame": "f0", "shape": {"type": "sphere"}},
        "step 1, field .shape: 'radius' is a required property",
    ),
    "a pose of two numbers": (
        {"op": "set_poses", "poses": {"f0": {"xyz": [1, 2]}}},
        "step 1, field .poses.f0.xyz: [1, 2] is too short",
    ),
    "an undeclared frame": (
        {"op": "set_poses", "poses": {"nope": {}}},
        "step 1, field poses.nope: unknown frame name 'nope'",
    ),
    "the world frame": ({"op": "set_poses", "poses": {"world": {}}}, "step 1, field .poses"),
    "a negative radius": (
        {
            "op": "register_geometry",
            "name": "g",
            "frame": "f0",
            "shape": {"type": "sphere", "radius": -1},
        },
        "field .shape.radius: -1 is less than or equal to the minimum of 0",
    ),
}


@pytest.mark.parametrize("bad", list(BAD_STEPS))
def test_a_malformed_shape_pose_or_frame_is_an_input_error_naming_file_case_and_step(
    bad: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    step, message = BAD_STEPS[bad]
    path = tmp_path / "bad.json"
    scenario = {
        "description": "bad input",
        "cases": [
            {
                "description": "c",
                "scene": {"frames": [{"name": "f0"}]},
                "steps": [step, {"op": "has_collisions", "expect": {"returns": False}}],
            }
        ],
    }
    path.write_text(json.dumps(scenario), encoding="utf-8")
    with pytest.raises(ScenarioError) as caught:
        load_file(path)
    assert str(caught.value).startswith(f"{path}: case 'c': ")
    assert message in str(caught.value)
    assert main(["run", "-q", "--backend", "pydrake", str(path)]) == EXIT_USAGE
    assert message in capsys.readouterr().err
