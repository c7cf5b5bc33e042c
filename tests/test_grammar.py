"""The grammar table is the one statement of the command language; the rest follows it."""

from __future__ import annotations

import json

import pytest

from conformance._backends.scene_graph import SceneGraphBackend
from conformance._engine import Divergence, Trace
from conformance._fuzz.regression import regression_scenario
from conformance._grammar import (
    GRAMMAR,
    ArgKind,
    Comparison,
    NameKind,
    UnknownOpError,
    declared_names,
    referenced_names,
)
from conformance._grammar import spec as command_spec
from conformance._grammar.queries import SHAPES
from conformance._grammar.schema import scenario_schema, schema_path
from conformance.compare import Difference
from conformance.protocol import Command, LocationState, Observation, Result


def test_the_published_schema_is_the_one_generated_from_the_grammar() -> None:
    published = json.loads(schema_path().read_text(encoding="utf-8"))
    assert published == scenario_schema(), "run: python -m conformance schema --write"


def test_the_schema_op_list_equals_the_grammar_table() -> None:
    published = json.loads(schema_path().read_text(encoding="utf-8"))
    assert published["$defs"]["step"]["properties"]["op"]["enum"] == list(GRAMMAR)
    rules = published["$defs"]["step"]["allOf"]
    assert [rule["if"]["properties"]["op"]["const"] for rule in rules] == list(GRAMMAR)


@pytest.mark.parametrize("op", [op for op, c in GRAMMAR.items() if not c.harness_only])
def test_scene_graph_backend_has_a_handler_for_every_op(op: str) -> None:
    handler = GRAMMAR[op].handler
    assert handler == op
    assert callable(getattr(SceneGraphBackend, handler))


def test_check_is_the_only_op_no_backend_executes() -> None:
    assert [op for op, c in GRAMMAR.items() if c.harness_only] == ["check"]


def test_an_unknown_op_names_the_ops_the_grammar_has() -> None:
    with pytest.raises(UnknownOpError, match=r"unknown op 'frobnicate'.*register_source"):
        command_spec("frobnicate")


def test_referenced_names_walk_sets_pairs_and_declarations() -> None:
    args = {
        "declaration": {
            "statements": [
                {"op": "exclude_between", "a": {"geometries": ["g1"]}, "b": {"frames": ["f1"]}}
            ]
        },
        "context": "c1",
    }
    assert sorted(referenced_names("apply", args), key=str) == sorted(
        [
            (NameKind.GEOMETRY, "g1", "declaration.statements[1].a"),
            (NameKind.FRAME, "f1", "declaration.statements[1].b"),
            (NameKind.CONTEXT, "c1", "context"),
        ],
        key=str,
    )
    assert list(referenced_names("collision_filtered", {"pair": ["a", "b"]})) == [
        (NameKind.GEOMETRY, "a", "pair"),
        (NameKind.GEOMETRY, "b", "pair"),
    ]


def test_declared_names_come_from_the_new_name_arguments() -> None:
    assert list(declared_names("apply_transient", {"label": "t1", "declaration": {}})) == [
        (NameKind.LABEL, "t1", "label")
    ]
    assert list(declared_names("clone_context", {"name": "c2", "from": "c1"})) == [
        (NameKind.CONTEXT, "c2", "name")
    ]


def test_regression_files_take_their_feature_tags_from_the_grammar() -> None:
    trace = Trace.of(
        "b",
        "a",
        [
            (Command("create_context", {"name": "c1"}), Result(), Result()),
            (Command("is_active", {"label": "@unknown"}), Result(value=False), Result()),
        ],
    )
    empty = Observation({"model": LocationState(frozenset(), False)})
    scenario = regression_scenario(
        Divergence("a", trace, [Difference("x", "y", "z")], states={"a": empty, "b": empty}),
        backend="a",
        reference="b",
        reference_version="1.51.1",
    )
    assert scenario["features"] == ["contexts", "core", "transient"]


def test_set_poses_refers_to_each_posed_frame_by_name() -> None:
    args = {"poses": {"f1": {"xyz": [1.0, 0.0, 0.0]}, "m::l1": {}}, "context": "c1"}
    assert list(referenced_names("set_poses", args)) == [
        (NameKind.FRAME, "f1", "poses.f1"),
        (NameKind.FRAME, "m::l1", "poses.m::l1"),
        (NameKind.CONTEXT, "c1", "context"),
    ]


def test_the_shape_schema_has_one_rule_per_shape_with_its_pydrake_keywords() -> None:
    shape = scenario_schema()["$defs"]["shape"]
    assert shape["properties"]["type"]["enum"] == [*SHAPES, "mesh", "convex"]
    rules = {rule["if"]["properties"]["type"]["const"]: rule["then"] for rule in shape["allOf"]}
    assert rules["box"]["required"] == ["width", "depth", "height"]
    assert rules["ellipsoid"]["required"] == ["a", "b", "c"]
    assert rules["halfspace"]["required"] == []
    assert rules["mesh"]["required"] == rules["convex"]["required"] == ["path"]
    assert sorted(rules["convex"]["properties"]) == ["path", "scale", "type"]
    assert all(rule["additionalProperties"] is False for rule in rules.values())


def test_register_geometry_takes_a_shape_and_a_pose_and_the_queries_compare_by_tolerance() -> None:
    assert command_spec("register_geometry").arg_kinds["shape"] is ArgKind.SHAPE
    assert command_spec("register_geometry").arg_kinds["pose"] is ArgKind.POSE
    assert {op for op, c in GRAMMAR.items() if c.compare is not Comparison.EXACT} == {
        "compute_point_pair_penetration",
        "compute_signed_distance_pairwise_closest_points",
        "compute_signed_distance_pair_closest_points",
        "compute_signed_distance_to_point",
        "x_wg",
        "x_wf",
        "model_inventory",
    }
