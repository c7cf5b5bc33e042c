"""The release matrix, its report, release specs and bisection, on real Drake releases.

The worker tests use Drake 1.58.0 on Python 3.12 (built once and cached, as
``--backend drake==1.58.0`` does). Tests that need other releases run where
their environments are already cached (a matrix run builds them) and skip
elsewhere, saying so.
"""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest

from conformance._backends.env_cache import missing_releases
from conformance._backends.loader import load_backend
from conformance._backends.releases import ReleaseSpecError, expand, releases_between
from conformance._corpus.loader import Case, load_corpus
from conformance._run.bisect import By, Probe, bisect_case
from conformance._run.matrix import Cell, Outcome, outcome_of, run_matrix
from conformance._run.matrix_report import matrix_json, matrix_markdown, write_report
from conformance._run.runner import run_case
from conformance.cli.main import main
from tests.test_worker_backend import RELEASE, needs_312

INDEX = ["1.38.0", "1.39.0", "1.40.0", "1.40.1", "1.41.0", "1.45.0", "1.58.0"]

ANCHORED = (
    "activation/activation > deactivating anchored proximity geometry is refused by the "
    "harness where it aborts pydrake (1.55-1.58)"
)
TABLE_1 = "transient/table1 > Table 1 lines 1-7 hold step by step"


def _case(name: str) -> Case:
    return next(c for f in load_corpus() for c in f.cases if c.qualified_name == name)


def _cached(version: str) -> bool:
    """Whether an environment for ``version`` is built (the tests' cache, or the real one)."""
    return not missing_releases([version])


# ------------------------------------------------------------------ release specs
def test_a_range_names_every_listed_release_between_its_ends_inclusive() -> None:
    assert expand(["1.39..1.41"], releases=INDEX) == ["1.39.0", "1.40.0", "1.40.1", "1.41.0"]
    assert releases_between("1.40", "1.40", INDEX) == ["1.40.0", "1.40.1"]


def test_releases_keep_the_order_given_and_appear_once() -> None:
    assert expand(["1.58.0", "1.40..1.40", "1.40.1"], releases=INDEX) == [
        "1.58.0",
        "1.40.0",
        "1.40.1",
    ]


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("1.30", r"'1\.30' is not a Drake release \(1\.30\.0\) or a range"),
        ("latest", r"'latest' is not a Drake release"),
        ("1.42..1.44", r"'1\.42\.\.1\.44': no Drake release on the index in this range"),
    ],
)
def test_a_bad_release_spec_is_refused_by_name(spec: str, message: str) -> None:
    with pytest.raises(ReleaseSpecError, match=message):
        expand([spec], releases=INDEX)


def test_matrix_exits_two_on_a_bad_spec_or_jobs() -> None:
    err = io.StringIO()
    assert main(["matrix", "--drake", "newest"], out=io.StringIO(), err=err) == 2
    assert "'newest' is not a Drake release" in err.getvalue()
    err = io.StringIO()
    assert main(["matrix", "--drake", "1.58.0", "--jobs", "0"], out=io.StringIO(), err=err) == 2
    assert "--jobs must be at least 1, got 0" in err.getvalue()


# ------------------------------------------------------------------ cells
def test_a_case_needing_a_feature_the_release_lacks_is_unsupported() -> None:
    pydrake = load_backend("pydrake")
    if "activation" in pydrake.features():
        pytest.skip("this pydrake has activation (1.55+)")
    report = run_case(_case(ANCHORED), [pydrake])
    assert outcome_of(report, "pydrake") == Cell(Outcome.SKIP, "needs feature(s) activation")


def test_a_case_that_passes_is_pass() -> None:
    report = run_case(_case(TABLE_1), [load_backend("reimpl")])
    assert outcome_of(report, "reimpl") == Cell(Outcome.PASS)


# ------------------------------------------------------------------ matrix on 1.58
@pytest.fixture(scope="module")
def matrix_1_58():  # type: ignore[no-untyped-def]
    return run_matrix([RELEASE], [_case(TABLE_1), _case(ANCHORED)], jobs=1)


@needs_312
def test_an_unguarded_1_58_worker_answers_anchored_deactivate_as_its_crash_row_records(
    matrix_1_58,  # type: ignore[no-untyped-def]
) -> None:
    """pydrake raises SystemExit('Failure at ...proximity_engine.cc... ApplyActiveStatusChange')
    for the failed DRAKE_DEMAND; the worker answers it as an error of kind 'assertion', the
    answer the crash row deactivate-anchored-aborts records for 1.55-1.58, which the case's
    refusal expectation accepts from an unguarded backend (pass)."""
    cell = matrix_1_58.cell(ANCHORED, RELEASE)
    assert cell == Cell(Outcome.PASS)
    assert matrix_1_58.cell(TABLE_1, RELEASE) == Cell(Outcome.PASS)
    assert matrix_1_58.failing == []


@needs_312
def test_the_report_has_the_documented_shape_and_is_the_same_when_written_twice(
    matrix_1_58,  # type: ignore[no-untyped-def]
    tmp_path: Path,
) -> None:
    document = matrix_json(matrix_1_58)
    assert document["versions"] == [RELEASE]
    assert document["cases"] == {TABLE_1: {RELEASE: "pass"}, ANCHORED: {RELEASE: "pass"}}
    assert document["releases"][RELEASE]["counts"]["pass"] == 2
    first = write_report(matrix_1_58, tmp_path / "a")
    second = write_report(matrix_1_58, tmp_path / "b")
    assert [p.name for p in first] == ["report.json", "report.md", "report.html", "heatmap.png"]
    for a, b in zip(first, second, strict=True):
        assert a.read_bytes() == b.read_bytes(), a.name
    assert first[3].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"| {RELEASE} | " in matrix_markdown(matrix_1_58)


@needs_312
def test_matrix_command_writes_the_report_and_exits_zero_when_the_release_answers_as_recorded(
    tmp_path: Path,
) -> None:
    out, err = io.StringIO(), io.StringIO()
    code = main(
        ["matrix", "--drake", RELEASE, "--case", "*anchored*", "--report", str(tmp_path)],
        out=out,
        err=err,
    )
    assert code == 0, err.getvalue()
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["cases"][ANCHORED] == {RELEASE: "pass"}
    assert f"drake=={RELEASE} (Python" in err.getvalue()  # progress, per release


# ------------------------------------------------------------------ implementation columns
def test_reimpl_at_a_release_is_a_column_beside_the_releases_and_outside_their_changes() -> None:
    """reimpl==1.30.0 runs alone on each case in its worker, like a release: it lacks
    Activate (activation-since-1.55), so the anchored case is unsupported there, and it
    passes Table 1; the changes between consecutive releases do not count its column."""
    matrix = run_matrix([], [_case(TABLE_1), _case(ANCHORED)], extra=["reimpl==1.30.0"])
    assert matrix.versions == ["reimpl==1.30.0"]
    assert matrix.release_columns == []
    assert matrix.cell(TABLE_1, "reimpl==1.30.0") == Cell(Outcome.PASS)
    assert matrix.cell(ANCHORED, "reimpl==1.30.0") == Cell(
        Outcome.SKIP, "needs feature(s) activation"
    )
    assert matrix.runs["reimpl==1.30.0"].error is None


def test_matrix_names_an_unknown_implementation_column_as_an_error_of_that_column() -> None:
    matrix = run_matrix([], [_case(TABLE_1)], extra=["reimpl==1.11.0"])
    error = matrix.runs["reimpl==1.11.0"].error
    assert error is not None
    assert "reimpl==1.11.0" in error


# ------------------------------------------------------------------ bisection
def _probe(outcomes: dict[str, Outcome], probed: list[str]):  # type: ignore[no-untyped-def]
    def probe(version: str) -> Probe:
        probed.append(version)
        return Probe(version, Cell(outcomes[version]), None)

    return probe


def test_bisection_finds_the_first_changed_release_in_about_log2_probes() -> None:
    releases = [f"1.{n}.0" for n in range(20, 52)]  # 32 releases
    outcomes = {v: Outcome.PASS if v < "1.37.0" else Outcome.FAIL for v in releases}
    probed: list[str] = []
    result = bisect_case(_case(TABLE_1), releases, probe=_probe(outcomes, probed))
    assert (result.last_good, result.first_bad) == ("1.36.0", "1.37.0")
    assert len(probed) == 2 + 5  # both ends, then log2(32) halvings
    assert result.differences[0].what == "outcome"


def test_bisection_reports_no_change_when_the_ends_agree() -> None:
    releases = ["1.40.0", "1.41.0", "1.42.0"]
    probed: list[str] = []
    outcomes = dict.fromkeys(releases, Outcome.PASS)
    result = bisect_case(_case(TABLE_1), releases, probe=_probe(outcomes, probed))
    assert result.first_bad is None
    assert probed == ["1.40.0", "1.42.0"]


@pytest.mark.skipif(
    not (_cached("1.56.0") and _cached("1.57.0")), reason="needs cached Drake 1.56.0 and 1.57.0"
)
def test_bisect_finds_that_1_57_stopped_a_failed_apply_writing_the_persistent_base() -> None:
    out, err = io.StringIO(), io.StringIO()
    code = main(
        ["bisect", "*failing apply keeps its earlier statement*", "--good", "1.56.0",
         "--bad", "1.57.0", "--by", By.BEHAVIOUR.value],
        out=out,
        err=err,
    )  # fmt: skip
    assert code == 0, err.getvalue()
    assert "first release that differs by behaviour: 1.57.0 (last that agrees: 1.56.0)" in (
        out.getvalue()
    )


@pytest.mark.skipif(
    not (_cached("1.51.1") and _cached("1.52.0")), reason="needs cached Drake 1.51.1 and 1.52.0"
)
def test_the_report_lists_the_1_52_filter_store_change_as_a_behaviour_change() -> None:
    name = (
        "errors/errors > a failing apply keeps its earlier statement's effect in C up to "
        "Drake 1.51 and changes nothing since 1.52"
    )
    matrix = run_matrix(["1.51.1", "1.52.0"], [_case(name)], jobs=2)
    assert matrix.cell(name, "1.51.1") == matrix.cell(name, "1.52.0") == Cell(Outcome.PASS)
    change = matrix_json(matrix)["changes"][0]["behaviour"]
    assert change == [
        {
            "case": name,
            "step": "step 1",
            "what": "candidates at model (only in one side)",
            "from": [],
            "to": ["g0-g1"],
            # 6 since observations carry CollisionFiltered samples and the inspector's counts
            # (measured on 1.51.1 and 1.52.0 workers; 3 before).
            "differences": 6,
        }
    ]
