"""The fuzzer's coverage: which state-space features a run reached (conformance._fuzz.coverage).

The books follow real pydrake's results, and the seed-1 campaign of issue 16
reaches every feature of its table at least ten times.
"""

from __future__ import annotations

import io
import json
from pathlib import Path
from typing import Any

import pytest

from conformance._backends.loader import load_backend
from conformance._fuzz.campaign import Campaign
from conformance._fuzz.coverage import Coverage, CoverageBook, campaign_features
from conformance._fuzz.lockstep import LockstepMachine
from conformance._fuzz.operations import issued_ops
from conformance.cli.exit_codes import EXIT_OK
from conformance.cli.main import main
from conformance.protocol import Command

PYDRAKE = load_backend("pydrake")
REIMPL = load_backend("reimpl")


class _Driven:
    """pydrake, run command by command, its results followed by a CoverageBook."""

    def __init__(self) -> None:
        PYDRAKE.reset()
        self.book = CoverageBook()
        self.reached: list[str] = []

    def __call__(self, op: str, **args: Any) -> None:
        command = Command(op, args)
        self.reached += self.book.follow(command, PYDRAKE.execute(command))


def _scene(run: _Driven, geometries: int, frame: str = "f") -> None:
    run("register_frame", name=frame)
    for i in range(geometries):
        run("register_geometry", name=f"{frame}{i}", frame=frame, roles=["proximity"])


def _exclude(a: str, b: str) -> dict[str, Any]:
    statement = {"op": "exclude_between", "a": {"geometries": [a]}, "b": {"geometries": [b]}}
    return {"statements": [statement]}


def test_removing_the_oldest_of_five_active_declarations_is_out_of_order_from_5() -> None:
    run = _Driven()
    _scene(run, 3)
    for label in "abcde":
        run("apply_transient", declaration=_exclude("f0", "f1"), label=label)
    assert run.reached.count("transients>=5") == 1
    run("remove_declaration", label="e")  # the newest: in order
    assert "out_of_order_removal" not in run.reached
    run("remove_declaration", label="a")  # the oldest of four
    assert run.reached.count("out_of_order_removal") == 1
    assert "out_of_order_removal_from_5" not in run.reached
    assert run.book.max_transients == 5


def test_only_growth_after_the_scene_counts_as_proximity_past_16() -> None:
    run = _Driven()
    _scene(run, 17)
    assert "proximity>16" not in run.reached, "the initial scene is not the sequence's growth"
    run = _Driven()
    _scene(run, 16)
    run.book.sequence_started = True
    run("register_geometry", name="late", frame="f", roles=["illustration"])
    assert "proximity>16" not in run.reached, "no proximity role: not counted"
    run("assign_role", geometry="late", role="proximity")
    assert run.reached.count("proximity>16") == 1
    assert run.book.max_proximity == 17


def test_a_clone_with_history_counts_once_edited_in_both_the_clone_and_its_origin() -> None:
    run = _Driven()
    _scene(run, 3)
    run("create_context", name="c1")
    run("apply_transient", declaration=_exclude("f0", "f1"), label="t1", context="c1")
    run("clone_context", name="c2", **{"from": "c1"})
    assert run.reached.count("clone_with_history") == 1
    run("apply_transient", declaration=_exclude("f1", "f2"), label="t2", context="c2")
    assert "edit_in_clone" in run.reached
    assert "clone_with_history_edited_both" not in run.reached
    run("remove_declaration", label="t1", context="c1")
    assert run.reached.count("clone_with_history_edited_both") == 1
    assert {"apply_transient@clone", "remove_declaration@context"} <= set(run.reached)


def test_a_refused_edit_is_an_error_of_its_kind_not_an_edit() -> None:
    run = _Driven()
    _scene(run, 2)
    run("create_context", name="c1")
    run("apply_transient", declaration=_exclude("f0", "f1"), label="t1")
    run("apply", declaration=_exclude("f0", "f1"))  # persistent, with history: refused
    assert run.reached[-1] == "error:transient_history"
    assert "model_edit_after_context" in run.reached  # the transient one was an edit


def test_a_filter_edit_after_roles_removed_and_reassigned_by_frame_is_counted() -> None:
    run = _Driven()
    _scene(run, 2)
    run("remove_role", frame="f", role="proximity")
    run("assign_role", geometry="f0", role="proximity")
    assert "reassigned_by_frame_then_filter" not in run.reached
    run("apply", declaration=_exclude("f0", "f1"))
    assert {"role_by_frame_then_filter", "reassigned_by_frame_then_filter"} <= set(run.reached)


def test_the_table_lists_a_feature_never_reached_as_a_gap() -> None:
    coverage = Coverage()
    coverage.add(["apply@model", "apply@model"])
    table = coverage.table(["apply@model", "apply@clone"])
    assert "  apply@model  " in table
    assert table.splitlines()[2].endswith("GAP")
    assert table.endswith("gaps: apply@clone")
    assert coverage.to_json(["apply@model", "apply@clone"])["features"] == {
        "apply@model": 2,
        "apply@clone": 0,
    }
    assert coverage.to_json(["apply@model", "apply@clone"])["expected"] == [
        "apply@model",
        "apply@clone",
    ]


@pytest.mark.fuzz
def test_the_seed_1_campaign_of_300_examples_reaches_every_feature_ten_times() -> None:
    result = Campaign(
        backend=lambda: REIMPL, reference=lambda: PYDRAKE, seed=1, max_examples=300
    ).run()
    assert not result.divergences
    expected = campaign_features(
        issued_ops(LockstepMachine.OPERATIONS), REIMPL.features() & PYDRAKE.features()
    )
    assert len(expected) >= 50
    assert result.stats.coverage.gaps(expected, at_least=10) == []
    assert result.stats.coverage.max_proximity > 16
    assert result.stats.coverage.max_transients >= 5


def test_fuzz_coverage_prints_the_table_and_json_holds_it(tmp_path: Path) -> None:
    out, err = io.StringIO(), io.StringIO()
    stats = tmp_path / "stats.json"
    argv = ["fuzz", "--seed", "1", "--max-examples", "5", "--coverage", "--json", str(stats)]
    code = main([*argv, "--out", str(tmp_path), "-q"], out=out, err=err)
    assert code == EXIT_OK, err.getvalue()
    table = out.getvalue().split("coverage: ", 1)[1]
    assert "features reached" in table.splitlines()[0]
    assert "  register_geometry@model" in table
    assert table.rstrip().splitlines()[-1].startswith("gaps: ")
    data = json.loads(stats.read_text())
    assert data["examples"] == 5
    assert data["divergences"] == 0
    assert data["coverage"]["features"]["register_geometry@model"] > 0
    assert set(data["coverage"]["gaps"]) == {
        name for name, count in data["coverage"]["features"].items() if count == 0
    }


def test_fuzz_models_prints_the_model_grammar_table(tmp_path: Path) -> None:
    out, err = io.StringIO(), io.StringIO()
    argv = ["fuzz", "--models", "--seed", "1", "--max-examples", "2", "--coverage"]
    argv += ["--without", "packages"]
    code = main([*argv, "--out", str(tmp_path), "-q"], out=out, err=err)
    assert code == EXIT_OK, err.getvalue()
    table = out.getvalue()
    assert "model grammar features reached (each counted once per case)" in table
    assert "  format:urdf " in table
    assert "packages>=2" not in table  # left out with --without packages
    assert "gaps: " in table
