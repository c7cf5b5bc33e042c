"""The operations that compose an order across locations, and the boundary operations
(issue 30): each issues its order, and on pydrake 1.51.1 each answers as the rule says."""

from __future__ import annotations

import math
from typing import Any

from conformance._backends.loader import load_backend
from conformance._fuzz.across_locations import (
    ACROSS_LOCATIONS,
    context_under_history,
    disagreeing_stack,
    frame_named_in_clone,
    model_edit_then_context,
    partial_apply_then_clone,
    reassign_by_frame_in_context,
)
from conformance._fuzz.lockstep import LockstepMachine, PosedLockstepMachine
from conformance._fuzz.operations import (
    OPERATIONS,
    POSED_OPERATIONS,
    query_at_max_distance,
    query_through_filter,
)
from conformance._fuzz.sequences import Recorder
from conformance._policy.release_facts import fact_holds
from conformance.protocol import Command

PYDRAKE = load_backend("pydrake")


class _Fixed:
    """A drawn template that resolves to one fixed declaration or set."""

    def __init__(self, value: dict[str, Any]) -> None:
        self.value = value

    def resolve(self, *_: Any) -> dict[str, Any]:
        return self.value


#: Exclude within a, b and c (all three geometries of ``_recorder``'s scene).
EVERYTHING = _Fixed(
    {"statements": [{"op": "exclude_within", "set": {"geometries": ["a", "b", "c"]}}]}
)


def _register_scene(recorder: Recorder) -> None:
    """Frames fa, fb; proximity spheres a on fa, b and c on fb, kept under their names."""
    recorder.keep("sources", "source")
    recorder.keep("frames", "world")
    for frame in ("fa", "fb"):
        recorder.step("register_frame", name=frame)
        recorder.keep("frames", frame)
    for name, frame in (("a", "fa"), ("b", "fb"), ("c", "fb")):
        recorder.step("register_geometry", name=name, frame=frame, roles=["proximity"])
        recorder.keep("geometries", name)


def _recorder(*, posed: bool = False) -> Recorder:
    """pydrake with frames fa, fb; proximity spheres a on fa, b and c on fb (names no
    ``fresh`` name can take)."""
    recorder = Recorder(backend=PYDRAKE, queries=posed, special=False)
    _register_scene(recorder)
    return recorder


def _ops(recorder: Recorder, since: int) -> list[str]:
    return [c.op for c in recorder.commands[since:]]


def test_the_rows_come_after_every_other_row_of_both_machines() -> None:
    for machine, table in ((LockstepMachine, OPERATIONS), (PosedLockstepMachine, POSED_OPERATIONS)):
        assert list(machine.OPERATIONS) == [*table, *ACROSS_LOCATIONS]


def test_a_model_edit_is_followed_at_once_by_a_new_context() -> None:
    recorder = _recorder()
    since = len(recorder.commands)
    model_edit_then_context(recorder, bytes(4), EVERYTHING)
    assert _ops(recorder, since) == ["apply", "create_context"]
    model_edit_then_context(recorder, bytes([1, 0, 0, 0]), EVERYTHING)
    assert _ops(recorder, since)[2:] == ["apply_transient", "remove_declaration", "create_context"]


def test_a_context_made_under_history_removes_the_inherited_declaration_after_its_own() -> None:
    recorder = _recorder()
    since = len(recorder.commands)
    context_under_history(recorder, bytes(4), EVERYTHING, EVERYTHING)
    commands = recorder.commands[since:]
    assert [c.op for c in commands] == [
        "apply_transient",
        "create_context",
        "apply_transient",
        "remove_declaration",
    ]
    inherited, context = commands[0].args["label"], commands[1].args["name"]
    assert commands[3].args == {"label": inherited, "context": context}
    assert (
        PYDRAKE.execute(
            Command("is_active", {"label": commands[2].args["label"], "context": context})
        ).value
        is True
    )


def test_a_partial_apply_fails_at_its_last_statement_then_its_context_is_cloned() -> None:
    recorder = _recorder()
    recorder.step("create_context", name="c0")
    recorder.keep("contexts", "c0")
    before = PYDRAKE.observe().locations["c0"].candidates
    since = len(recorder.commands)
    partial_apply_then_clone(recorder, bytes([255, 0, 0, 0]), EVERYTHING)
    commands = recorder.commands[since:]
    assert [c.op for c in commands] == ["apply", "clone_context"]
    assert commands[0].args["declaration"]["statements"][-1] == {
        "op": "exclude_within",
        "set": {"geometries": ["@unknown"]},
    }
    clone = commands[1].args["name"]
    state = PYDRAKE.observe().locations[clone]
    assert before  # the scene has candidates for the statements to filter
    if fact_holds("failed-apply-leaves-c-unchanged-since-1.52", PYDRAKE.version()):
        # pydrake 1.58.0: the failing Apply left C as it was, and the clone has c0's.
        assert state.candidates == before
    else:
        # pydrake 1.51.1: the statements before the failing one were applied, and the clone
        # has them.
        assert state.candidates == frozenset()


def test_a_clone_gets_geometry_on_a_frame_then_a_declaration_naming_the_frame() -> None:
    recorder = _recorder()
    recorder.step("create_context", name="c0")
    recorder.keep("contexts", "c0")
    since = len(recorder.commands)
    frame_named_in_clone(
        recorder,
        bytes([255, 0, 255, 0]),
    )
    assert _ops(recorder, since) == ["clone_context", "register_geometry", "apply"]


def test_a_disagreeing_stack_of_five_has_its_oldest_removed_and_is_checked_at_once() -> None:
    recorder = _recorder()
    since = len(recorder.commands)
    members = _Fixed({"geometries": ["a", "b"]})
    disagreeing_stack(recorder, bytes(4), members)
    commands = recorder.commands[since:]
    ops = [c.op for c in commands]
    assert ops == [*["apply_transient"] * 5, "remove_declaration", "collision_filtered"]
    kinds = [c.args["declaration"]["statements"][0]["op"] for c in commands[:5]]
    assert kinds == ["exclude_within", "allow_within"] * 2 + ["exclude_within"]
    # pydrake 1.51.1 replays the four left oldest first: the newest (Exclude) decides.
    assert PYDRAKE.execute(commands[-1]).value is True
    disagreeing_stack(recorder, bytes([0, 1, 0, 1]), members)
    assert _ops(recorder, since)[7:].count("remove_declaration") == 6


def test_query_through_filter_asks_every_query_after_the_filter_and_after_its_removal() -> None:
    recorder = _recorder(posed=True)
    since = len(recorder.commands)
    query_through_filter(recorder, bytes([0, 0, 1, 0]), EVERYTHING)
    queries = [
        "compute_point_pair_penetration",
        "has_collisions",
        "compute_signed_distance_pairwise_closest_points",
        "find_collision_candidates",
        "compute_signed_distance_pair_closest_points",
    ]
    assert _ops(recorder, since) == ["apply_transient", *queries, "remove_declaration", *queries]


class _Answers(Recorder):
    """A Recorder that keeps pydrake's Result of each command too."""

    def __init__(self) -> None:
        super().__init__(backend=PYDRAKE, queries=True, special=False)
        self.results: list[Any] = []

    def step(self, op: str, **args: Any) -> Any:
        result = super().step(op, **args)
        self.results.append(result)
        return result


def _answering(poses: dict[str, Any] | None = None) -> _Answers:
    """``_recorder(posed=True)``'s scene on an ``_Answers``, fa posed as given."""
    recorder = _Answers()
    _register_scene(recorder)
    if poses:
        recorder.step("set_poses", poses=poses)
    return recorder


_QUERIES = [
    "compute_point_pair_penetration",
    "has_collisions",
    "compute_signed_distance_pairwise_closest_points",
    "find_collision_candidates",
    "compute_signed_distance_pair_closest_points",
]


def _by_op(recorder: _Answers, since: int, op: str) -> list[Any]:
    pairs = zip(recorder.commands[since:], recorder.results[since:], strict=True)
    return [r.value for c, r in pairs if c.op == op]


def test_an_aimed_filter_excludes_every_penetrating_pair_and_has_collisions_turns_false() -> None:
    recorder = _answering()  # a, b, c at the origin: a-b and a-c penetrate (b-c share fb)
    since = len(recorder.commands)
    query_through_filter(recorder, bytes([0, 0, 1, 3]), EVERYTHING)
    ops = _ops(recorder, since)
    assert ops == [
        "compute_point_pair_penetration",
        "apply_transient",
        *_QUERIES,
        "remove_declaration",
        *_QUERIES,
    ]
    statements = recorder.commands[since + 1].args["declaration"]["statements"]
    assert [(s["a"]["geometries"], s["b"]["geometries"]) for s in statements] == [
        (["a"], ["b"]),
        (["a"], ["c"]),
    ]
    # pydrake 1.51.1: filtered, nothing collides, is a candidate or has a distance; then back.
    assert _by_op(recorder, since, "has_collisions") == [False, True]
    assert _by_op(recorder, since, "find_collision_candidates") == [[], [["a", "b"], ["a", "c"]]]
    pairwise = _by_op(recorder, since, "compute_signed_distance_pairwise_closest_points")
    assert [[r["pair"] for r in answer] for answer in pairwise] == [[], [["a", "b"], ["a", "c"]]]


def test_an_aimed_filter_where_nothing_penetrates_excludes_a_candidate_pair() -> None:
    # a 0.212 from b and c: no penetration, but the boxes overlap (a-b, a-c are candidates).
    recorder = _answering({"fa": {"xyz": [0.15, 0.15, 0.0]}})
    since = len(recorder.commands)
    query_through_filter(recorder, bytes([0, 0, 1, 1]), EVERYTHING)
    assert _ops(recorder, since)[:3] == [
        "compute_point_pair_penetration",
        "find_collision_candidates",
        "apply_transient",
    ]
    statements = recorder.commands[since + 2].args["declaration"]["statements"]
    assert [(s["a"]["geometries"], s["b"]["geometries"]) for s in statements] == [(["a"], ["b"])]
    # pydrake 1.51.1: the filter takes a-b out of the candidates and the pairwise distances.
    candidates = _by_op(recorder, since, "find_collision_candidates")
    assert candidates == [[["a", "b"], ["a", "c"]], [["a", "c"]], [["a", "b"], ["a", "c"]]]
    pairwise = _by_op(recorder, since, "compute_signed_distance_pairwise_closest_points")
    assert [[r["pair"] for r in answer] for answer in pairwise] == [
        [["a", "c"]],
        [["a", "b"], ["a", "c"]],
    ]
    assert _by_op(recorder, since, "has_collisions") == [False, False]


def test_query_at_max_distance_aims_at_a_scene_pairs_own_distance() -> None:
    answers = []
    for aim in range(3):
        recorder = _answering({"fa": {"xyz": [0.15, 0.15, 0.0]}})
        since = len(recorder.commands)
        query_at_max_distance(recorder, bytes([0, 1, aim, 1]))
        assert _ops(recorder, since) == ["compute_signed_distance_pairwise_closest_points"] * 2
        first, aimed = _by_op(recorder, since, "compute_signed_distance_pairwise_closest_points")
        assert [r["pair"] for r in first] == [["a", "b"], ["a", "c"]]
        distance = first[1]["distance"]  # a-c, drawn by picks[1]
        assert (
            recorder.commands[-1].args["max_distance"]
            == [
                distance,
                math.nextafter(distance, -math.inf),
                math.nextafter(distance, math.inf),
            ][aim]
        )
        answers.append([r["pair"] for r in aimed])
    # pydrake 1.51.1: a-b and a-c are equally far (0.01213203435596423): both in, out, in.
    assert answers == [[["a", "b"], ["a", "c"]], [], [["a", "b"], ["a", "c"]]]


def test_query_at_max_distance_aims_at_the_pairs_own_distance_and_one_ulp_either_side() -> None:
    answers = []
    for aim in range(3):
        recorder = _recorder(posed=True)
        query_at_max_distance(recorder, bytes([0, 0, aim, 0]))
        first, aimed = recorder.commands[-2], recorder.commands[-1]
        assert first.op == aimed.op == "compute_signed_distance_pairwise_closest_points"
        made = [c.args["name"] for c in recorder.commands if c.op == "register_geometry"]
        pair = sorted(made[-2:])
        distance = next(r["distance"] for r in PYDRAKE.execute(first).value if r["pair"] == pair)
        assert (
            aimed.args["max_distance"]
            == [
                distance,
                math.nextafter(distance, -math.inf),
                math.nextafter(distance, math.inf),
            ][aim]
        )
        answers.append([r["pair"] for r in PYDRAKE.execute(aimed).value if r["pair"] == pair])
    # pydrake 1.51.1: at exactly φ the pair is in, 1 ulp below it is out, 1 ulp above in.
    assert [bool(a) for a in answers] == [True, False, True]


def test_a_frame_filtered_at_the_model_is_reassigned_by_frame_in_a_new_context() -> None:
    recorder = _recorder()
    since = len(recorder.commands)
    reassign_by_frame_in_context(recorder, bytes([1, 0, 0, 0]), _Fixed({"geometries": ["a"]}))
    commands = recorder.commands[since:]
    assert [c.op for c in commands] == [
        "apply",
        "create_context",
        "remove_role",
        "assign_role",
        "assign_role",
    ]
    context = commands[1].args["name"]
    # pydrake 1.51.1: b and c start unfiltered in the context; the model keeps a-b, a-c filtered.
    state = PYDRAKE.observe()
    assert state.locations[context].candidates == frozenset({("a", "b"), ("a", "c")})
    assert state.locations["model"].candidates == frozenset()
