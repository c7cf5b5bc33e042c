"""Every observable is in the state: sampled CollisionFiltered, the inspector's counts, and
the group report after every parse (issue 30, deliverable 4).

Expected values measured on pydrake 1.51.1 (the same on 1.58.0: the worker test below).
"""

from __future__ import annotations

from typing import Any

import pytest

from conformance._backends.loader import load_backend
from conformance._backends.scene_graph import SceneGraphBackend
from conformance._testing.model_mutants import model_mutant_backend
from conformance.compare import diff_observations
from conformance.protocol import MODEL, Command, LocationState, Observation, sample_pairs

#: Proximity g0 on f0, anchored proximity g1, illustration-only g2 on f0, g3 removed.
SCENE: tuple[dict[str, Any], ...] = (
    {"op": "register_frame", "name": "f0"},
    {"op": "register_geometry", "name": "g0", "frame": "f0", "roles": ["proximity"]},
    {"op": "register_geometry", "name": "g1", "roles": ["proximity"]},
    {"op": "register_geometry", "name": "g2", "frame": "f0", "roles": ["illustration"]},
    {"op": "register_geometry", "name": "g3", "frame": "f0", "roles": ["proximity"]},
    {"op": "remove_geometry", "geometry": "g3"},
    {"op": "create_context", "name": "c"},
)

_STATUS = "error: Can't report collision filter status between geometries {} and {}; {} "
NO_ROLE = _STATUS + "does not have a proximity role"
INVALID = _STATUS + "is not a valid geometry"

#: pydrake 1.51.1's answers for SCENE (validity is checked before the role: g2-g3).
FILTERED = {
    ("g0", "g1"): False,
    ("g0", "g3"): INVALID.format("g0", "g3", "g3"),
    ("g1", "g2"): NO_ROLE.format("g1", "g2", "g2"),
    ("g2", "g3"): INVALID.format("g2", "g3", "g3"),
}
COUNTS = {
    "anchored": 1,
    "dynamic": 2,
    "frame f0": 2,
    "frame f0 proximity": 1,
    "frame world": 1,
    "frame world proximity": 1,
    "frames": 2,
    "geometries": 3,
    "role illustration": 1,
    "role perception": 0,
    "role proximity": 2,
    "source source frames": 1,
    "sources": 2,
}


def test_the_sample_is_the_ring_of_sorted_names() -> None:
    assert sample_pairs(["d", "b", "a", "c"]) == [("a", "b"), ("b", "c"), ("c", "d"), ("a", "d")]
    assert sample_pairs(["b", "a"]) == [("a", "b")]
    assert sample_pairs(["a"]) == []
    assert len(sample_pairs([f"g{i}" for i in range(100)])) == 32


def test_every_name_of_up_to_32_is_in_the_sample() -> None:
    names = [f"g{i}" for i in range(32)]
    assert {n for pair in sample_pairs(names) for n in pair} == set(names)


@pytest.fixture(params=["reimpl", "pydrake"])
def backend(request: pytest.FixtureRequest) -> Any:
    return load_backend(request.param)


def _observe(backend: SceneGraphBackend, steps: tuple[dict[str, Any], ...]) -> Observation:
    backend.reset()
    for step in steps:
        result = backend.execute(Command.from_json(step))
        assert result.error is None, (step, result)
    return backend.observe()


def test_removed_non_proximity_and_world_geometry_are_sampled_with_their_errors(
    backend: SceneGraphBackend,
) -> None:
    state = _observe(backend, SCENE)
    for location in (MODEL, "c"):
        assert state.locations[location].filtered == FILTERED
        assert state.locations[location].counts == COUNTS
    assert state.locations[MODEL].filter_groups is None  # no parse yet
    assert state.locations["c"].filter_groups is None


def test_a_filter_changes_the_sampled_answer_in_its_location_only(
    backend: SceneGraphBackend,
) -> None:
    declaration = {
        "statements": [
            {"op": "exclude_between", "a": {"geometries": ["g0"]}, "b": {"geometries": ["g1"]}}
        ]
    }
    state = _observe(backend, (*SCENE, {"op": "apply", "context": "c", "declaration": declaration}))
    assert state.locations["c"].filtered is not None
    assert state.locations["c"].filtered[("g0", "g1")] is True
    assert state.locations[MODEL].filtered == FILTERED


GROUPS_URDF = """<robot name="r">
  <link name="a"><collision><geometry><sphere radius="1"/></geometry></collision></link>
  <link name="b"><collision><geometry><sphere radius="1"/></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
  <drake:collision_filter_group name="ga"><drake:member link="a"/></drake:collision_filter_group>
  <drake:collision_filter_group name="gb"><drake:member link="b"/>
    <drake:ignored_collision_filter_group name="ga"/></drake:collision_filter_group>
</robot>"""


def test_the_group_report_is_observed_after_every_parse(backend: SceneGraphBackend) -> None:
    parse = {"op": "add_models", "text": GROUPS_URDF, "format": "urdf"}
    state = _observe(backend, (parse,))
    assert state.locations[MODEL].filter_groups == {
        "groups": {"r::ga": ["r::a"], "r::gb": ["r::b"]},
        "pairs": [["r::ga", "r::gb"]],
    }


def _state(**extras: Any) -> Observation:
    return Observation({MODEL: LocationState(frozenset(), False, {}, **extras)})


def test_a_different_sampled_answer_count_or_group_report_is_a_difference() -> None:
    assert [
        d.what
        for d in diff_observations(
            _state(filtered={("a", "b"): True}), _state(filtered={("a", "b"): False})
        )
    ] == ["CollisionFiltered at model"]
    assert [
        d.what
        for d in diff_observations(_state(counts={"frames": 2}), _state(counts={"frames": 3}))
    ] == ["inspector counts at model"]
    groups = {"groups": {"g": ["m::a"]}, "pairs": []}
    assert [
        d.what
        for d in diff_observations(
            _state(filter_groups=groups), _state(filter_groups={**groups, "pairs": [["g", "g"]]})
        )
    ] == ["collision filter groups at model"]


def test_a_backend_that_does_not_report_an_observable_is_not_compared_on_it() -> None:
    assert diff_observations(_state(filtered={("a", "b"): True}), _state()) == []
    assert diff_observations(_state(counts={"frames": 2}), _state(counts={"sources": 1})) == []
    assert diff_observations(_state(filter_groups={"groups": {}, "pairs": []}), _state()) == []


def test_the_observables_survive_the_wire() -> None:
    state = _state(
        filtered={("a", "b"): "error: x"},
        counts={"frames": 2},
        filter_groups={"groups": {}, "pairs": []},
    )
    assert Observation.from_json(state.to_json()) == state


# ------------------------------------------- the group report's model mutants (issue 30)
def _urdf(name: str) -> str:
    return GROUPS_URDF.replace('name="r"', f'name="{name}"').replace(
        '<drake:ignored_collision_filter_group name="ga"/>',
        '<drake:ignored_collision_filter_group name="gb"/>',
    )


#: r1, then r2 by the same Parser: each with ga = {a} and gb = {b} ignoring itself.
TWO_PARSES = (
    {"op": "add_models", "text": _urdf("r1"), "format": "urdf"},
    {"op": "add_models", "text": _urdf("r2"), "format": "urdf", "reuse_parser": True},
)
#: pydrake 1.51.1's report after TWO_PARSES: both parses' groups, and gb's self-exclusion.
TWO_REPORTS = {
    "groups": {
        "r1::ga": ["r1::a"],
        "r1::gb": ["r1::b"],
        "r2::ga": ["r2::a"],
        "r2::gb": ["r2::b"],
    },
    "pairs": [["r1::gb", "r1::gb"], ["r2::gb", "r2::gb"]],
}


@pytest.mark.parametrize(
    ("mutant", "mutated"),
    [
        (
            "group_report_drops_self_exclusion",
            {**TWO_REPORTS, "pairs": []},
        ),
        (
            "group_report_of_last_parse",
            {
                "groups": {"r2::ga": ["r2::a"], "r2::gb": ["r2::b"]},
                "pairs": [["r2::gb", "r2::gb"]],
            },
        ),
    ],
)
def test_a_group_report_mutant_differs_from_pydrake_in_the_observed_report_alone(
    mutant: str, mutated: dict[str, Any]
) -> None:
    oracle = _observe(load_backend("pydrake"), TWO_PARSES)
    plain = _observe(load_backend("reimpl"), TWO_PARSES)
    wrong = _observe(model_mutant_backend(mutant), TWO_PARSES)
    assert oracle.locations[MODEL].filter_groups == TWO_REPORTS
    assert plain.locations[MODEL].filter_groups == TWO_REPORTS
    assert wrong.locations[MODEL].filter_groups == mutated
    assert [d.what for d in diff_observations(oracle, wrong)] == [
        "collision filter groups at model"
    ]
