"""benchmarks/measure_tolerances.py measures real differences and survives FCL's aborts.

Measured on pydrake 1.51.1 and 1.58.0 with the python-fcl of constraints.txt: scene 775
of seed 1 (a cylinder and a capsule a touch apart) passes pydrake's bisection and
queries, then python-fcl, which reimpl calls, ends the process with FCL's
``validateNearestFeatureOfPolytopeBeingEdge()`` ``std::logic_error`` (SIGABRT); the
closed-form pairs of the first 30 scenes agree to rounding.
"""

from __future__ import annotations

from types import ModuleType

import pytest

from tests.dropin import benchmark_module

pytest.importorskip("pydrake")


def _script() -> ModuleType:
    return benchmark_module("measure_tolerances")


def test_the_closed_form_pairs_agree_to_rounding_on_near_touching_scenes() -> None:
    report = _script().measure(seed=1, scenes=30)
    closed = ("sphere–sphere", "sphere–box", "sphere–cylinder", "sphere–capsule", "box–box")
    for pair in closed:
        row = report["pairs"][pair]
        assert row["scenes"] == 2
        assert row["records"] >= 4
        assert row["max_dd"] <= 1e-15
        assert row["max_dp"] <= 1e-15
        assert row["outside"] == row["has_collisions_disagreements"] == 0


def test_an_fcl_abort_in_reimpl_loses_one_scene_not_the_run() -> None:
    lines = list(_script()._scene_lines(1, 777, start=775))
    assert [line.get("scene", line.get("aborted")) for line in lines] == [775, 776]
    aborted = lines[0]
    assert (aborted["side"], aborted["phase"]) == ("reimpl", "queries")
    assert aborted["message"].startswith(
        "validateNearestFeatureOfPolytopeBeingEdge(): The origin is outside of the polytope."
    )
    assert "pydrake" in lines[1]
    assert "reimpl" in lines[1]
