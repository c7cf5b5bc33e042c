"""conformance.fuzz.strategies draws valid scenario material; pydrake agrees with reimpl on it."""

from __future__ import annotations

import json
from pathlib import Path

from hypothesis import HealthCheck, assume, find, given, settings
from hypothesis import strategies as st

from conformance.backends.loader import load_backend
from conformance.compare import diff
from conformance.corpus.loader import load_file
from conformance.fuzz import strategies as cs
from conformance.fuzz.operations import OPERATIONS, issued_ops
from conformance.fuzz.sequences import CONTEXT_OPS, command_sequences
from conformance.policy.divergences import match_step
from conformance.protocol import Command, backend_id

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


def test_pick_leaves_out_reads_rare_names_from_224_and_cycles_through_names() -> None:
    names, rare = ["a", "b", "c"], (cs.UNKNOWN, cs.FOREIGN)
    assert cs.pick(names, 0) == "a"
    assert cs.pick(names, 4) == "b"
    assert cs.pick(names, 100, none_below=128) is None
    assert cs.pick(names, 128, none_below=128) == "c"  # 128 % 3 == 2
    assert cs.pick(names, 223, rare=rare) == "b"  # below 224: a name
    assert cs.pick(names, 224, rare=rare) == cs.UNKNOWN  # 224 % 2 == 0
    assert cs.pick(names, 225, rare=rare) == cs.FOREIGN
    assert cs.pick([], 5, rare=rare) == cs.FOREIGN  # no names: always rare
    assert cs.pick([], 5) is None


def test_role_codes_give_proximity_below_12_and_the_other_roles_by_bit() -> None:
    assert cs.role_list(0) == ["proximity"]
    assert cs.role_list(3) == ["proximity", "illustration", "perception"]
    assert cs.role_list(11) == ["proximity", "illustration", "perception"]
    assert cs.role_list(12) == []
    assert cs.role_list(14) == ["perception"]
    assert cs.role_list(16 + 5) == ["proximity", "illustration"]  # taken mod 16


def test_declaration_template_decodes_pool_then_one_byte_per_within_two_per_between() -> None:
    pool = bytes([0, 1, 2, 0, 0, 5])  # geometries a, b, c, a; frames world, f
    exclude_abc = (0b000111 << 2) | 0  # op 0 (exclude_within), mask bits 0-2
    allow_between = (0b100001 << 2) | 3  # op 3 (allow_between), a = {pool 0, pool 5}
    data = pool + bytes([exclude_abc, allow_between, 0b000010])
    template = cs.DeclarationTemplate.decode(data)
    assert template.statements == (
        ("exclude_within", (0b000111,)),
        ("allow_between", (0b100001, 0b000010)),
    )
    names = ["a", "b", "c"]
    frames = ["world", "f"]
    resolved = template.resolve(lambda i: cs.pick(names, i), lambda i: cs.pick(frames, i))
    assert resolved == {
        "statements": [
            {"op": "exclude_within", "set": {"geometries": ["a", "b", "c"]}},
            {
                "op": "allow_between",
                "a": {"geometries": ["a"], "frames": ["f"]},
                "b": {"geometries": ["b"]},
            },
        ]
    }


def test_declaration_template_between_without_a_second_byte_has_an_empty_b() -> None:
    template = cs.DeclarationTemplate.decode(bytes(6) + bytes([(1 << 2) | 2]))
    assert template.statements == (("exclude_between", (1, 0)),)


def test_set_template_reads_counts_from_byte_0_and_drops_repeated_names() -> None:
    template = cs.SetTemplate.decode(bytes([0b0110, 1, 4, 0]))  # 2 geometries, 1 frame
    assert template == cs.SetTemplate(geometries=(1, 4), frames=(0,))
    resolved = template.resolve(lambda i: cs.pick(["a", "b", "c"], i), lambda i: "world")
    assert resolved == {"geometries": ["b"], "frames": ["world"]}  # 1 and 4 both name b


@SETTINGS
@given(command_sequences(max_operations=12))
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


@SETTINGS
@given(command_sequences(max_operations=12, contexts=False, special=False))
def test_command_sequences_without_contexts_never_name_a_context_or_a_special_id(
    commands: list[Command],
) -> None:
    assert not {c.op for c in commands} & CONTEXT_OPS
    assert all("context" not in c.args for c in commands)
    text = json.dumps([c.to_json() for c in commands])
    assert cs.UNKNOWN not in text
    assert cs.FOREIGN not in text


def test_command_sequences_reach_every_op_the_lockstep_operations_issue() -> None:
    """One generator: what the fuzzer's OPERATIONS issue, drawn sequences issue too."""
    for op in sorted(issued_ops(OPERATIONS)):  # find raises NoSuchExample if never drawn
        find(
            command_sequences(max_operations=8, activation=True),
            lambda commands, op=op: op in {c.op for c in commands},
            settings=settings(max_examples=2000, database=None),
        )


REIMPL = load_backend("reimpl")
PYDRAKE = load_backend("pydrake")
#: The sequences are drawn against their own pydrake, so only names that were made are used.
DRAWN_ON = load_backend("pydrake")


@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(command_sequences(max_operations=15, backend=DRAWN_ON))
def test_reimpl_and_pydrake_agree_on_drawn_command_sequences(commands: list[Command]) -> None:
    REIMPL.reset()
    PYDRAKE.reset()
    for command in commands:
        a, b = REIMPL.execute(command), PYDRAKE.execute(command)
        differences = diff((b, PYDRAKE.observe()), (a, REIMPL.observe()), op=command.op)
        # A known divergence for this pydrake release is not a finding (as in the fuzzer).
        known = match_step(command, b, a, blamed=backend_id(REIMPL), release=PYDRAKE.version())
        assume(not differences or known is None)
        assert differences == [], command.to_json()
