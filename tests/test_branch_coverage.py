"""Branch coverage of reimpl during a campaign: the gaps by function, and ``fuzz --coverage``."""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

import pytest

from conformance._backends.loader import load_backend
from conformance._fuzz.branch_coverage import BranchCoverage, _ranges
from conformance._fuzz.campaign import Campaign
from conformance.cli.main import EXIT_OK, main


def test_a_filter_campaign_never_calls_the_parser_and_runs_the_collision_filter() -> None:
    """The lockstep campaign drives SceneGraph only: reimpl's Parser is never called, while
    the collision filter's apply runs (both measured at seed 1, 3 examples)."""
    reimpl, pydrake = load_backend("reimpl"), load_backend("pydrake")
    branches = BranchCoverage()
    with branches.measuring():
        result = Campaign(
            backend=lambda: reimpl, reference=lambda: pydrake, seed=1, max_examples=3
        ).run()
    assert not result.divergences
    report = branches.report()
    parser = report.function("Parser.__init__")
    assert parser is not None
    assert parser.file == "reimpl/multibody/parsing/_parser.py"
    assert parser.never_called
    assert parser.missing_lines
    apply = report.function("CollisionFilter.apply")
    assert apply is None or not apply.never_called  # run: covered, or only partly missing
    assert 0 < report.covered_branches < report.branches
    assert 0 < report.covered_lines < report.statements
    table = report.table(limit=3)
    assert table.startswith("reimpl branches: ")
    assert "reimpl/multibody/parsing/_parser.py: " in table
    assert "Parser.__init__" in table


def test_only_one_measurement_runs_at_a_time() -> None:
    first, second = BranchCoverage(), BranchCoverage()
    with (
        first.measuring(),
        pytest.raises(RuntimeError, match="already being measured"),
        second.measuring(),
    ):
        pass


def test_line_numbers_are_shown_as_ranges() -> None:
    assert _ranges((1, 2, 3, 7, 9, 10)) == "1-3, 7, 9-10"
    assert _ranges(()) == ""


def test_fuzz_coverage_prints_the_branches_and_the_pair_table(tmp_path: Path) -> None:
    out, err = io.StringIO(), io.StringIO()
    stats = tmp_path / "stats.json"
    argv = ["fuzz", "--seed", "1", "--max-examples", "3", "--coverage", "--json", str(stats)]
    code = main([*argv, "--out", str(tmp_path), "-q"], out=out, err=err)
    assert code == EXIT_OK, err.getvalue()
    text = out.getvalue()
    assert "\nreimpl branches: " in text
    assert "\nsequence pairs: " in text
    assert "of 400 reachable pairs reached" in text  # 20 events: activation is not shared
    assert "\npair gaps: " in text
    data = json.loads(stats.read_text())
    assert len(data["sequences"]["pairs"]) == 400
    assert data["sequences"]["pairs"]["create_context@model -> clone_context@context"] > 0
    assert data["branches"]["covered_branches"] > 0
    assert any(f["function"] == "Parser.__init__" for f in data["branches"]["functions"])


def test_fuzz_models_coverage_has_one_reachable_pair(tmp_path: Path) -> None:
    """A model case issues ``apply`` (at the model) and no other sequence op."""
    out, err = io.StringIO(), io.StringIO()
    argv = ["fuzz", "--models", "--seed", "1", "--max-examples", "2", "--coverage"]
    code = main([*argv, "--out", str(tmp_path), "-q"], out=out, err=err)
    assert code == EXIT_OK, err.getvalue()
    text = out.getvalue()
    assert "of 1 reachable pairs reached" in text
    assert "\nreimpl branches: " in text


@pytest.mark.fuzz
@pytest.mark.skipif(
    load_backend("pydrake").version() != load_backend("reimpl").version(),
    reason="reimpl answers as 1.51.1; the campaign would find the release's changes",
)
@pytest.mark.parametrize(
    "mode",
    [
        pytest.param((), id="default"),
        pytest.param(("--poses",), id="poses"),
        pytest.param(("--models",), id="models"),
    ],
)
def test_fuzz_coverage_reaches_every_reachable_pair_at_seed_1_in_300_examples(
    mode: tuple[str, ...], tmp_path: Path
) -> None:
    """The done-when of issue 30's sequence coverage, for each campaign (2-8 min each): the
    command itself, in a process of its own, as a user runs it (in this process the default
    campaign drew otherwise: 119,629 steps against the command's 95,614, measured at seed 1,
    and left pairs unreached; what in a test process changes its draws is not known yet)."""
    argv = ["fuzz", *mode, "--seed", "1", "--max-examples", "300", "--coverage", "-q"]
    done = subprocess.run(
        [sys.executable, "-m", "conformance", *argv, "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        check=False,
    )
    assert done.returncode == EXIT_OK, done.stdout + done.stderr
    assert "\nreimpl branches: " in done.stdout
    gaps = done.stdout[done.stdout.find("pair gaps:") :].split("\n\n")[0]
    assert "\npair gaps: none\n" in done.stdout, gaps
