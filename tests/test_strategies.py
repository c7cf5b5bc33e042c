"""conformance.strategies draws valid scenario material; real pydrake agrees with reimpl on it."""

from __future__ import annotations

import json
from pathlib import Path

from hypothesis import HealthCheck, find, given, settings
from hypothesis import strategies as st

from conformance import strategies as cs
from conformance.backend import Command
from conformance.backends import load_backend
from conformance.corpus import load_file
from conformance.runner import results_agree

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))


@SETTINGS
@given(cs.scenes(min_frames=1, max_frames=5, max_geometries=10))
def test_scene_frames_have_earlier_parents_and_geometry_sits_on_known_frames(
    scene: cs.Scene,
) -> None:
    seen: set[str] = set()
    for name, parent in scene.frames:
        assert parent is None or parent in seen
        seen.add(name)
    assert 1 <= len(scene.frames) <= 5
    for geometry in scene.geometries:
        assert geometry.frame in seen | {cs.WORLD}
        assert set(geometry.roles) <= set(cs.ROLES)
        assert len(set(geometry.roles)) == len(geometry.roles)


def test_scenes_reach_nested_frames_anchored_geometry_and_roleless_geometry() -> None:
    nested = find(cs.scenes(), lambda s: any(p is not None for _, p in s.frames))
    assert nested.frames[-1][1] is not None
    anchored = find(cs.scenes(), lambda s: any(g.frame == cs.WORLD for g in s.geometries))
    assert any(g.frame == cs.WORLD for g in anchored.geometries)
    roleless = find(cs.scenes(), lambda s: any("proximity" not in g.roles for g in s.geometries))
    assert any("proximity" not in g.roles for g in roleless.geometries)


@SETTINGS
@given(cs.scenes(anchored=False, non_proximity=False, min_frames=1))
def test_scene_options_exclude_anchored_and_non_proximity_geometry(scene: cs.Scene) -> None:
    assert all(g.frame != cs.WORLD for g in scene.geometries)
    assert all("proximity" in g.roles for g in scene.geometries)


@SETTINGS
@given(cs.geometry_sets(geometries=["a", "b"], frames=["f", cs.WORLD], special=False))
def test_geometry_sets_name_only_the_given_names_without_specials(
    geometry_set: dict[str, list[str]],
) -> None:
    assert set(geometry_set) <= {"geometries", "frames"}
    assert set(geometry_set.get("geometries", [])) <= {"a", "b"}
    assert set(geometry_set.get("frames", [])) <= {"f", cs.WORLD}


def test_geometry_sets_reach_unknown_and_foreign_ids() -> None:
    sets = cs.geometry_sets(geometries=["a"], frames=["f"])
    for special in (cs.UNKNOWN, cs.FOREIGN):
        found = find(sets, lambda s, x=special: x in s.get("geometries", []))
        assert found == {"geometries": [special]}


@SETTINGS
@given(cs.declarations(geometries=st.sampled_from(["a", "b", "c"])))
def test_declarations_have_one_to_four_statements(declaration: dict[str, object]) -> None:
    statements = declaration["statements"]
    assert isinstance(statements, list)
    assert 1 <= len(statements) <= 4
    for statement in statements:
        assert statement["op"] in cs.STATEMENT_OPS
        keys = {"op", "set"} if statement["op"].endswith("_within") else {"op", "a", "b"}
        assert set(statement) == keys


@SETTINGS
@given(cs.command_sequences(max_commands=12))
def test_command_sequences_are_valid_scenario_cases(
    tmp_path_factory: object, commands: list[Command]
) -> None:
    directory = Path(tmp_path_factory.mktemp("sequence"))  # type: ignore[attr-defined]
    scenario = {
        "description": "a drawn sequence",
        "cases": [
            {
                "description": "drawn",
                "steps": [c.to_json() for c in commands] + [{"op": "check", "expect": {}}],
            }
        ],
    }
    path = directory / "drawn.json"
    path.write_text(json.dumps(scenario))
    loaded = load_file(path, root=directory)  # raises ScenarioError if invalid
    assert len(loaded.cases[0].steps) == len(commands) + 1


REIMPL = load_backend("reimpl")
PYDRAKE = load_backend("pydrake")


@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(cs.command_sequences(max_commands=15))
def test_reimpl_and_pydrake_agree_on_drawn_command_sequences(commands: list[Command]) -> None:
    REIMPL.reset()
    PYDRAKE.reset()
    for command in commands:
        a, b = REIMPL.execute(command), PYDRAKE.execute(command)
        assert results_agree(a, b), (command.to_json(), a.to_json(), b.to_json())
        assert REIMPL.observe() == PYDRAKE.observe(), command.to_json()
