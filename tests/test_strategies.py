"""conformance._fuzz.strategies draws valid scenario material; pydrake agrees with reimpl on it."""

from __future__ import annotations

import json
from pathlib import Path

from hypothesis import HealthCheck, assume, find, given, settings
from hypothesis import strategies as st

from conformance._backends.loader import load_backend
from conformance._corpus.loader import load_file
from conformance._fuzz import strategies as cs
from conformance._fuzz.operations import OPERATIONS, POSED_OPERATIONS, QUERY_OPS, issued_ops
from conformance._fuzz.sequences import CONTEXT_OPS, command_sequences
from conformance._policy.divergences import match_step
from conformance.compare import diff
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
@given(st.booleans().flatmap(lambda posed: command_sequences(max_operations=12, posed=posed)))
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


def test_posed_command_sequences_reach_every_op_the_posed_operations_issue() -> None:
    assert issued_ops(POSED_OPERATIONS) == issued_ops(OPERATIONS) | set(QUERY_OPS)
    for op in sorted(set(QUERY_OPS) | {"register_geometry"}):
        find(
            command_sequences(max_operations=8, posed=True),
            lambda commands, op=op: op in {c.op for c in commands},
            settings=settings(max_examples=2000, database=None),
        )
    with_capsules = find(
        command_sequences(max_operations=8, posed=True),
        lambda commands: any(
            c.op == "register_geometry" and c.args.get("shape", {}).get("type") == "capsule"
            for c in commands
        ),
        settings=settings(max_examples=2000, database=None),
    )
    assert with_capsules
    # HalfSpaces stay out of posed fuzzing (pydrake's AABB tree crashes on them, see the share).
    assert cs.POSED_HALFSPACE_SHARE == 0
    kinds = {cs.shape_of(bytes([b, 0, 0, 0]), halfspace=0)["type"] for b in range(256)}
    assert kinds == set(cs.SHAPE_TYPES) - {"halfspace"}
    assert cs.shape_of(bytes([255, 0, 0, 0]))["type"] == "halfspace"


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


# ------------------------------------------------------------- posed scenes
def test_shape_bytes_give_the_type_then_whole_centimetres_and_a_halfspace_from_248() -> None:
    assert cs.shape_of(bytes(4)) == {"type": "sphere", "radius": 0.05}
    assert cs.shape_of(bytes([1, 0, 5, 50])) == {
        "type": "box",
        "width": 0.1,
        "depth": 0.15,
        "height": 0.6,
    }
    assert cs.shape_of(bytes([4, 25, 1, 2])) == {
        "type": "ellipsoid",
        "a": 0.3,
        "b": 0.06,
        "c": 0.07,
    }
    assert cs.shape_of(bytes([248, 9, 9, 9])) == {"type": "halfspace"}
    assert cs.shape_of(bytes([248, 9]), halfspace=False) == {
        "type": "capsule",  # 248 % 5; a missing size byte is 0
        "radius": 0.14,
        "length": 0.1,
    }
    assert [cs.shape_of(bytes([t, 0, 0]))["type"] for t in range(5)] == list(cs.SHAPE_TYPES[:5])


def test_pose_bytes_are_signed_steps_of_5_mm_and_0_025_rad_and_zero_parts_are_left_out() -> None:
    assert cs.pose_of(bytes(6)) == {}
    assert cs.pose_of(bytes([1, 2, 0, 0, 0, 0])) == {"xyz": [0.005, -0.005, 0.0]}
    assert cs.pose_of(bytes([0, 0, 0, 3, 4, 255])) == {"rpy": [0.05, -0.05, 3.2]}


@SETTINGS
@given(cs.scenes(min_frames=1, max_geometries=6, posed=True))
def test_posed_scenes_give_every_geometry_a_shape_and_pose_and_pose_only_scene_frames(
    scene: cs.Scene,
) -> None:
    for geometry in scene.geometries:
        assert geometry.shape is not None
        assert geometry.shape["type"] in cs.SHAPE_TYPES
        assert geometry.pose is not None
        assert set(geometry.pose) <= {"xyz", "rpy"}
    assert {name for name, _ in scene.poses} <= set(scene.frame_names)
    (last,) = scene.commands()[-1:]
    assert last.op == "set_poses" if scene.poses else last.op != "set_poses"


def test_rotation_and_transform_products_are_pydrake_s_to_rounding() -> None:
    from pydrake.math import RigidTransform, RollPitchYaw  # noqa: PLC0415

    rpy_a, rpy_b = (0.3, -1.2, 2.9), (-2.0, 0.4, -0.7)
    a = cs.Transform(cs.rotation(rpy_a), (0.1, -0.2, 0.3))
    b = cs.Transform(cs.rotation(rpy_b), (-0.5, 0.25, 1.0))
    want = RigidTransform(RollPitchYaw(rpy_a), [0.1, -0.2, 0.3]) @ RigidTransform(
        RollPitchYaw(rpy_b), [-0.5, 0.25, 1.0]
    )
    got = a * b
    assert (
        max(
            abs(x - y)
            for row, wrow in zip(got.rotation, want.rotation().matrix(), strict=True)
            for x, y in zip(row, wrow, strict=True)
        )
        < 1e-15
    )
    assert max(abs(x - y) for x, y in zip(got.translation, want.translation(), strict=True)) < 1e-15
    assert (
        max(abs(x - y) for x, y in zip(a.local(a.point((1.0, 2.0, 3.0))), (1, 2, 3), strict=True))
        < 1e-15
    )
    assert cs.Transform.of({"xyz": [1, 2, 3]}) == cs.Transform(translation=(1.0, 2.0, 3.0))


def test_touch_bytes_give_a_unit_direction_a_frame_rotation_and_a_gap_from_1e_9_to_1e_3() -> None:
    assert cs.Touch.decode(bytes(cs.TOUCH_BYTES)) == cs.Touch(
        0, 0, (0.0, 0.0, 1.0), (0.0, 0.0, 0.0), 5e-4
    )
    touch = cs.Touch.decode(bytes([3, 4, 1, 0, 0, 3, 0, 0, 1 | 2 * 3, 128]))
    assert touch.direction == (1.0, 0.0, 0.0)
    assert touch.rpy == (0.05, 0.0, 0.0)
    assert touch.gap == -1e-6 * 1.5  # sign bit, scale GAP_SCALES[3], mantissa 128
    gaps = [cs.Touch.decode(bytes([0] * 8 + [b, m])).gap for b in range(256) for m in (0, 255)]
    assert min(map(abs, gaps)) == 1e-9
    assert max(map(abs, gaps)) < 1e-3


#: pydrake's shapes for the grammar's SHAPE values.
def _pydrake_shape(shape: dict[str, object]) -> object:
    from pydrake import geometry  # noqa: PLC0415

    from conformance._grammar.queries import SHAPES  # noqa: PLC0415

    class_name, keys = SHAPES[str(shape["type"])]
    return getattr(geometry, class_name)(**{key: shape[key] for key in keys})


_PYDRAKE_SCENES: list[object] = []  # a QueryObject needs its SceneGraph and context alive


def _pydrake_signed_distance(
    shapes: tuple[dict[str, object], dict[str, object]],
    poses: tuple[cs.Transform, cs.Transform],
) -> tuple[float, int]:
    """pydrake's signed distance of the two shapes at the two world poses, and how many
    penetration pairs it reports."""
    from pydrake.geometry import (  # noqa: PLC0415
        FramePoseVector,
        GeometryFrame,
        GeometryInstance,
        ProximityProperties,
        SceneGraph,
    )
    from pydrake.math import RigidTransform, RotationMatrix  # noqa: PLC0415

    scene_graph = SceneGraph()
    source = scene_graph.RegisterSource(name="s")
    poses_vector, ids = FramePoseVector(), []
    for i, (shape, pose) in enumerate(zip(shapes, poses, strict=True)):
        frame = scene_graph.RegisterFrame(source_id=source, frame=GeometryFrame(f"f{i}"))
        instance = GeometryInstance(
            X_PG=RigidTransform(), shape=_pydrake_shape(shape), name=f"g{i}"
        )
        ids.append(
            scene_graph.RegisterGeometry(source_id=source, frame_id=frame, geometry=instance)
        )
        scene_graph.AssignRole(
            source_id=source, geometry_id=ids[-1], properties=ProximityProperties()
        )
        X = RigidTransform(
            RotationMatrix([list(row) for row in pose.rotation]), list(pose.translation)
        )
        poses_vector.set_value(id=frame, value=X)
    context = scene_graph.CreateDefaultContext()
    scene_graph.get_source_pose_port(source).FixValue(context, poses_vector)
    _PYDRAKE_SCENES.append((scene_graph, context))
    query = scene_graph.get_query_output_port().Eval(context)
    distance = query.ComputeSignedDistancePairClosestPoints(
        geometry_id_A=ids[0], geometry_id_B=ids[1]
    ).distance
    return distance, len(query.ComputePointPairPenetration())


#: Pairs whose signed distance pydrake computes in closed form (exact to rounding).
_CLOSED_FORM = (
    ("sphere", "sphere"),
    ("sphere", "box"),
    ("box", "sphere"),
    ("box", "box"),
    ("capsule", "sphere"),
    ("sphere", "cylinder"),
    ("halfspace", "sphere"),
    ("sphere", "halfspace"),
)


def _shape_of_type(kind: str) -> st.SearchStrategy[dict[str, object]]:
    """A drawn shape of one type (its type byte fixed, its sizes drawn)."""
    head = 255 if kind == "halfspace" else cs.SHAPE_TYPES.index(kind)
    return cs.picks(cs.SHAPE_BYTES - 1).map(lambda sizes: cs.shape_of(bytes([head]) + sizes))


@settings(max_examples=80, deadline=None, suppress_health_check=list(HealthCheck))
@given(
    shapes=st.sampled_from(_CLOSED_FORM).flatmap(
        lambda kinds: st.tuples(_shape_of_type(kinds[0]), _shape_of_type(kinds[1]))
    ),
    pose=cs.poses(),
    rpy=cs.poses(),
    touch=cs.touches(),
)
def test_touching_position_puts_closed_form_pairs_at_the_gap_pydrake_measures(
    shapes: tuple[dict[str, object], dict[str, object]],
    pose: dict[str, list[float]],
    rpy: dict[str, list[float]],
    touch: cs.Touch,
) -> None:
    X_WA = cs.Transform.of(pose)
    R_WB = cs.Transform.of({"rpy": rpy.get("rpy", [0.0, 0.0, 0.0])}).rotation
    p_WB = cs.touching_position(
        shapes[0], X_WA, shapes[1], R_WB, direction=touch.direction, gap=touch.gap
    )
    assert p_WB is not None
    distance, penetrating = _pydrake_signed_distance(shapes, (X_WA, cs.Transform(R_WB, p_WB)))
    assert abs(distance - touch.gap) < 1e-12 if touch.gap >= 0 else touch.gap - 1e-12 <= distance
    if abs(touch.gap) > 1e-12:
        assert penetrating == (touch.gap < 0)
