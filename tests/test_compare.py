"""compare.diff is the one agreement check: its rules, stated as facts."""

from __future__ import annotations

from conformance.compare import Difference, diff, diff_observations, diff_results
from conformance.protocol import ErrorInfo, ErrorKind, LocationState, Observation, Result


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
