"""compare.diff is the one agreement check: its rules, stated as facts."""

from __future__ import annotations

from typing import Any

from conformance._tolerances import (
    CLOSED,
    ITERATIVE,
    POSE_TOLERANCE,
    TOLERANCES,
    shape_pair,
    tolerance,
)
from conformance.compare import (
    CHOICE,
    Difference,
    comparable_message,
    diff,
    diff_observations,
    diff_results,
    value_differences,
)
from conformance.protocol import (
    ErrorInfo,
    ErrorKind,
    LocationState,
    Observation,
    Result,
    classify_error,
)


def state(*pairs: tuple[str, str], history: bool = False, **active: bool) -> Observation:
    return Observation({"model": LocationState(frozenset(pairs), history, active)})


def error(kind: ErrorKind, message: str) -> Result:
    return Result(error=ErrorInfo(kind, message))


def test_equal_values_agree_and_different_values_differ() -> None:
    assert diff_results(Result(value=True), Result(value=True)) == []
    assert diff_results(Result(value=True), Result(value=False), op="is_active") == [
        Difference("is_active result", {"value": True}, {"value": False})
    ]


def test_errors_agree_only_with_the_same_kind_and_message() -> None:
    a = error(ErrorKind.UNKNOWN_GEOMETRY, "Referenced geometry # has not been registered.")
    assert diff_results(a, a) == []
    assert diff_results(a, error(ErrorKind.UNKNOWN_GEOMETRY, "other words")) != []
    assert diff_results(a, error(ErrorKind.OTHER, a.error.message if a.error else "")) != []
    assert diff_results(a, Result()) != []


def test_errors_that_share_a_first_line_differ_in_their_further_lines() -> None:
    """Drake 1.13.0 and 1.51.1 word a redefined material's report differently after the same
    first line (measured: 6 significant digits, then the file's 11)."""
    first = "robot.urdf:6: error: Material 'brown' was previously defined."
    old = RuntimeError(f"{first}\n  - existing definition: RGBA: 0.933333 0.796078 0.678431 1")
    new = RuntimeError(f"{first}\n  - existing definition: RGBA: 0.93333333333 0.79607843137 1")
    a, b = classify_error(old), classify_error(new)
    assert a.message == b.message == first
    assert a.detail == "- existing definition: RGBA: #.# #.# #.# #"
    assert diff_results(Result(error=a), Result(error=a)) == []
    assert diff_results(Result(error=a), Result(error=b)) != []
    assert ErrorInfo.from_json(a.to_json()) == a
    assert "detail" not in classify_error(RuntimeError(first)).to_json()


def test_binding_errors_agree_by_kind_whatever_pybind11_says() -> None:
    assert diff_results(error(ErrorKind.BINDING, "x"), error(ErrorKind.BINDING, "y")) == []


def test_candidates_are_compared_as_sets_and_reported_by_side() -> None:
    (difference,) = diff_observations(state(("a", "b"), ("a", "c")), state(("a", "b"), ("b", "c")))
    assert difference == Difference("candidates at model (only in one side)", ["a-c"], ["b-c"])


def test_history_activity_and_locations_are_compared() -> None:
    assert [d.what for d in diff_observations(state(history=True), state())] == [
        "has_transient_history at model"
    ]
    assert [d.what for d in diff_observations(state(t=True), state(t=False))] == [
        "IsActive at model"
    ]
    assert [d.what for d in diff_observations(state(), Observation({}))] == [
        "location model exists"
    ]


def test_diff_lists_the_result_before_the_state() -> None:
    whats = [d.what for d in diff((Result(value=1), state()), (Result(value=2), state(("a", "b"))))]
    assert whats == ["command result", "candidates at model (only in one side)"]


# ------------------------------------------------------- query values (within tolerances)
#: ComputePointPairPenetration on pydrake 1.51.1: a unit box (a) posed at xyz (0.8, 0.05, 0.12),
#: rpy (0.1, 0.2, 0.3), and a sphere of radius 0.5 (b) at the origin.
BOX_SPHERE = {
    "pair": ["a", "b"],
    "shapes": ["box", "sphere"],
    "depth": 0.24045722186726592,
    "p_WCa": [0.24300818073188513, 0.07517123925205882, -0.051563190044321416],
    "p_WCb": [0.4681466817920996, 0.14481473881275778, -0.09933466539753061],
    "nhat_BA_W": [0.9362933635841992, 0.28962947762551555, -0.19866933079506122],
}
#: Two unit spheres 1.5 apart on x (exact values: depth 0.5, witnesses on the x axis).
SPHERES = {
    "pair": ["s1", "s2"],
    "shapes": ["sphere", "sphere"],
    "depth": 0.5,
    "p_WCa": [1.0, 0.0, 0.0],
    "p_WCb": [0.5, 0.0, 0.0],
    "nhat_BA_W": [-1.0, 0.0, 0.0],
}
PENETRATION = "compute_point_pair_penetration"


def shifted(record: dict[str, Any], key: str, by: float) -> dict[str, Any]:
    value = record[key]
    moved = value + by if isinstance(value, float) else [value[0] + by, *value[1:]]
    return {**record, key: moved}


def test_query_numbers_1e_13_apart_agree_for_a_closed_form_pair() -> None:
    for key in ("depth", "p_WCa", "p_WCb", "nhat_BA_W"):
        near = [shifted(BOX_SPHERE, key, 1e-13)]
        assert value_differences(PENETRATION, [BOX_SPHERE], near) == []
        assert diff_results(Result(value=[BOX_SPHERE]), Result(value=near), op=PENETRATION) == []


def test_a_sphere_sphere_depth_1e_3_off_disagrees_and_says_by_how_much() -> None:
    off = shifted(SPHERES, "depth", 1e-3)
    assert value_differences(PENETRATION, [SPHERES], [off]) == [
        "s1-s2 depth: |Δ| = 0.001 > 1e-12 (sphere-sphere distance tolerance)"
    ]
    (difference,) = diff_results(Result(value=[SPHERES]), Result(value=[off]), op=PENETRATION)
    assert difference.what.startswith(f"{PENETRATION} result (s1-s2 depth: |Δ| = 0.001")


def test_a_swapped_pair_disagrees_even_with_its_points_and_normal_swapped() -> None:
    swapped = {
        **SPHERES,
        "pair": ["s2", "s1"],
        "p_WCa": SPHERES["p_WCb"],
        "p_WCb": SPHERES["p_WCa"],
        "nhat_BA_W": [1.0, 0.0, 0.0],
    }
    assert value_differences(PENETRATION, [SPHERES], [swapped]) == [
        "pairs [['s1', 's2']] vs [['s2', 's1']]"
    ]


def test_pair_lists_are_compared_exactly_whatever_the_numbers() -> None:
    assert value_differences(PENETRATION, [SPHERES], []) == ["pairs [['s1', 's2']] vs []"]
    assert value_differences(PENETRATION, [], []) == []
    shapes = {**SPHERES, "shapes": ["sphere", "box"]}
    assert value_differences(PENETRATION, [SPHERES], [shapes]) != []


def test_an_ellipsoid_pair_is_compared_within_the_iterative_tolerance() -> None:
    ellipsoid = {**SPHERES, "shapes": ["ellipsoid", "sphere"]}
    assert tolerance("sphere", "ellipsoid").distance == tolerance("ellipsoid", "sphere").distance
    allowed = tolerance("ellipsoid", "sphere").distance
    assert allowed > 1e-9
    assert (
        value_differences(PENETRATION, [ellipsoid], [shifted(ellipsoid, "depth", allowed / 2)])
        == []
    )
    assert value_differences(PENETRATION, [ellipsoid], [shifted(ellipsoid, "depth", 2 * allowed)])


def test_a_signed_distance_pair_record_is_compared_alone() -> None:
    op = "compute_signed_distance_pair_closest_points"
    record = {
        "pair": ["b", "a"],
        "shapes": ["sphere", "box"],
        "distance": -0.24045722186726592,
        "p_ACa": [0.4681466817920996, 0.14481473881275778, -0.09933466539753061],
        "p_BCb": [-0.5, 0.17029855566198823, -0.2923360863848727],
        "nhat_BA_W": [-0.9362933635841992, -0.28962947762551555, 0.19866933079506122],
    }
    assert value_differences(op, record, shifted(record, "p_BCb", 1e-13)) == []
    assert value_differences(op, record, shifted(record, "p_BCb", 1e-6)) == [
        "b-a p_BCb: |Δ| = 1e-06 > 1e-12 (sphere-box witness tolerance)"
    ]


def test_poses_agree_within_the_pose_tolerance_only() -> None:
    pose = {
        "xyz": [0.8, 0.05, 0.02],
        "rotation": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    }
    near = {**pose, "xyz": [0.8 + 1e-15, 0.05, 0.02]}
    far = {**pose, "rotation": [[1.0, 1e-6, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]}
    assert value_differences("x_wg", pose, near) == []
    assert value_differences("x_wf", pose, far) == [
        f"pose entries differ by up to 1e-06 > {POSE_TOLERANCE:g}"
    ]


def test_bools_and_candidate_lists_stay_exact() -> None:
    assert value_differences("has_collisions", True, False) == ["values differ"]
    assert value_differences("find_collision_candidates", [["a", "b"]], [["a", "b"]]) == []
    assert diff_results(Result(value=1.0), Result(value=1.0 + 1e-15), op="is_active") != []


def test_every_pair_of_the_eight_shapes_and_every_shape_with_a_point_has_a_row() -> None:
    shapes = ("sphere", "box", "cylinder", "capsule", "ellipsoid", "halfspace", "mesh", "convex")
    rows = {shape_pair(a, b) for a in shapes for b in (*shapes, "point")}
    assert rows == set(TOLERANCES)
    assert all(row.reason for row in TOLERANCES.values())
    assert tolerance("sphere", "capsule") is CLOSED
    assert tolerance("capsule", "capsule") is ITERATIVE  # FCL's MPR, not a closed form


#: ComputeSignedDistancePairClosestPoints, capsule A along cylinder B, nearly touching.
TOUCH = {
    "pair": ["k", "y"],
    "shapes": ["capsule", "cylinder"],
    "distance": 1e-11,
    "p_ACa": [0.1, 0.0, 0.2],
    "p_BCb": [0.3, 0.0, 0.1],
    "nhat_BA_W": [0.0, 0.0, 1.0],
}
PAIR = "compute_signed_distance_pair_closest_points"


def test_at_a_touch_only_the_distance_is_compared() -> None:
    """Below the row's touching distance the witness points and the normal are not unique."""
    elsewhere = {
        **TOUCH,
        "p_ACa": [0.16, 0.0, 0.2],
        "p_BCb": [0.36, 0.0, 0.1],
        "nhat_BA_W": [0.0, 0.0, -1.0],
    }
    assert value_differences(PAIR, TOUCH, elsewhere) == []
    assert value_differences(PAIR, TOUCH, {**elsewhere, "distance": 1e-4}) != []
    apart = {**TOUCH, "distance": 0.01}
    assert value_differences(PAIR, apart, {**elsewhere, "distance": 0.01}) == [
        "k-y distance·nhat_BA_W: |Δ| = 0.02 > 5e-05 (capsule-cylinder normal tolerance)",
        "k-y p_ACa: |Δ| = 0.06 > 1e-05 (capsule-cylinder witness tolerance)",
        "k-y p_BCb: |Δ| = 0.06 > 1e-05 (capsule-cylinder witness tolerance)",
    ]


def test_a_normal_is_compared_through_the_separation_vector() -> None:
    """‖d·n − d′·n′‖: a normal 1e-3 off is within 5e-5 at d = 0.01, not at d = 0.1."""
    tilted = [0.0, 1e-3, (1 - 1e-6) ** 0.5]
    near = {**TOUCH, "distance": 0.01}
    assert value_differences(PAIR, near, {**near, "nhat_BA_W": tilted}) == []
    far = {**TOUCH, "distance": 0.1}
    (difference,) = value_differences(PAIR, far, {**far, "nhat_BA_W": tilted})
    assert difference.startswith("k-y distance·nhat_BA_W: |Δ| = 0.0001 > 5e-05")


def test_a_nan_normal_agrees_only_with_a_nan_normal() -> None:
    nan = float("nan")
    record = {**SPHERES, "nhat_BA_W": [nan, nan, nan]}
    assert value_differences(PENETRATION, [record], [dict(record)]) == []
    assert value_differences(PENETRATION, [record], [SPHERES]) != []


def test_a_pairwise_signed_distance_error_agrees_whatever_unsupported_pair_it_names() -> None:
    """Drake names the first unsupported pair its broadphase meets, in no specified order."""
    op = "compute_signed_distance_pairwise_closest_points"
    message = (
        "Signed distance queries between shapes '{}' and '{}' are not supported for scalar "
        "type double. See the documentation for "
        "QueryObject::ComputeSignedDistancePairwiseClosestPoints() for the full status of "
        "supported geometries."
    )
    box = error(ErrorKind.OTHER, message.format("Box", "Halfspace"))
    capsule = error(ErrorKind.OTHER, message.format("Halfspace", "Capsule"))
    assert diff_results(box, capsule, op=op) == []
    assert comparable_message(op, message.format("Box", "Halfspace")) == (
        f"Signed distance queries {CHOICE} are not supported for scalar type double. See the "
        "documentation for QueryObject::ComputeSignedDistancePairwiseClosestPoints() for the "
        "full status of supported geometries."
    )
    assert diff_results(box, capsule, op="compute_signed_distance_pair_closest_points") != []
    assert diff_results(box, error(ErrorKind.OTHER, "Signed distance queries"), op=op) != []
