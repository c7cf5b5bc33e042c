"""Known divergences: each is shown on real pydrake, and each one that acts matches real cases."""

from __future__ import annotations

import fnmatch
from pathlib import Path

import pytest

from conformance._backends.loader import load_backend
from conformance._corpus.loader import Case, load_corpus
from conformance._engine import Outcome
from conformance._policy.divergences import KnownDivergence, known_divergences
from conformance._policy.guards import GUARDS
from conformance._policy.versions import version_in_range
from conformance._run.runner import run_case
from conformance.protocol import BackendId, Command, ErrorInfo, ErrorKind, Result

CASES: dict[str, Case] = {c.qualified_name: c for f in load_corpus() for c in f.cases}
ENTRIES = known_divergences()
ROOT = Path(__file__).resolve().parent.parent


def test_divergence_ids_are_unique() -> None:
    ids = [e.id for e in ENTRIES]
    assert len(ids) == len(set(ids))


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e.id)
def test_divergence_names_existing_evidence(entry: KnownDivergence) -> None:
    assert entry.scenarios or entry.tests
    for name in entry.scenarios:
        assert name in CASES, f"{entry.id}: no scenario {name!r}"
    for path in entry.tests:
        assert (ROOT / path).is_file(), f"{entry.id}: no test file {path}"


@pytest.mark.parametrize("entry", [e for e in ENTRIES if e.xfail is not None], ids=lambda e: e.id)
def test_an_xfail_matcher_names_a_diverging_step_and_existing_cases(entry: KnownDivergence) -> None:
    assert entry.xfail is not None
    assert entry.xfail.steps, "every known divergence matches on the diverging step"
    assert entry.xfail.cases, "and narrows to the cases that show it"
    for pattern in entry.xfail.cases:
        assert fnmatch.filter(CASES, pattern), f"{entry.id}: no case matches {pattern!r}"


def test_the_failed_apply_entry_acts_against_drake_1_52_on_for_backends_that_follow_1_51() -> None:
    entry = next(e for e in ENTRIES if e.id == "failed-apply-leaves-c-unchanged-since-1.52")
    assert entry.release_fact == "failed-apply-leaves-c-unchanged-since-1.52"
    assert entry.xfail is not None
    case = entry.xfail.cases[0]
    reimpl, mutant = BackendId("reimpl", "1.51.1"), BackendId("mutant:x", "1.51.1")

    def matches(blamed: BackendId, release: str) -> bool:
        assert entry.xfail is not None
        return entry.xfail.matches_step(
            APPLY, UNKNOWN, UNKNOWN, blamed=blamed, release=release, case=case
        )

    assert matches(reimpl, "1.58.0")
    assert matches(reimpl, "1.52.0")
    assert matches(mutant, "1.58.0")
    assert not matches(reimpl, "1.51.1")
    # reimpl following 1.58 (reimpl==1.58.0) has 1.58's Apply: no xfail is needed for it.
    assert not matches(BackendId("reimpl==1.58.0", "1.58.0"), "1.58.0")
    assert not matches(BackendId("pydrake", "1.58.0"), "1.58.0")


def test_an_entry_for_reimpl_also_excuses_reimpl_following_a_release() -> None:
    """``backends: ["reimpl"]`` names reimpl however it runs: in-process (``reimpl``) or in a
    release's worker (``reimpl==1.58.0``), where it failed as an unexcused divergence."""
    entry = next(e for e in ENTRIES if e.id == "sphere-distance-last-bits")
    assert entry.xfail is not None
    assert entry.xfail.backends == frozenset({"reimpl"})
    command = Command("compute_signed_distance_pairwise_closest_points", {"max_distance": 2.5})
    at_the_boundary = Result(
        value=[{"pair": ["a", "b"], "shapes": ["sphere", "sphere"], "distance": 2.5}]
    )

    def matches(blamed: BackendId) -> bool:
        assert entry.xfail is not None
        return entry.xfail.matches_step(
            command,
            at_the_boundary,
            Result(value=[]),
            blamed=blamed,
            release="1.58.0",
            case=entry.xfail.cases[0],
        )

    assert matches(BackendId("reimpl", "1.58.0"))
    assert matches(BackendId("reimpl==1.58.0", "1.58.0"))
    assert not matches(BackendId("drake==1.58.0", "1.58.0"))
    assert not matches(BackendId("mutant:reimpl", "1.58.0"))


APPLY = Command("apply", {"declaration": {"statements": []}})
UNKNOWN = Result(error=ErrorInfo(ErrorKind.UNKNOWN_FRAME, "Referenced frame # has not been"))


def test_every_release_guard_names_a_known_divergence_of_kind_drake_crash() -> None:
    kinds = {e.id: e.kind for e in ENTRIES}
    assert {kinds[key] for key in GUARDS} == {"drake_crash"}


@pytest.mark.parametrize(
    ("entry", "scenario"),
    [(e, s) for e in ENTRIES for s in e.scenarios],
    ids=lambda v: v.id if isinstance(v, KnownDivergence) else v.split(" > ")[0],
)
def test_divergence_scenario_holds_on_real_pydrake(entry: KnownDivergence, scenario: str) -> None:
    pydrake = load_backend("pydrake")
    if (
        not version_in_range(pydrake.version(), entry.since, entry.until)
        and entry.kind != "reimpl_vs_drake"
    ):
        pytest.skip(f"{entry.id} concerns Drake {entry.releases}")
    report = run_case(CASES[scenario], [pydrake])
    if report.status["pydrake"] is Outcome.SKIP:
        pytest.skip(report.skip_reasons["pydrake"])
    assert report.status["pydrake"] is Outcome.PASS, report.failures


def test_the_failed_apply_step_pattern_needs_both_sides_to_raise_an_unknown_id_error() -> None:
    entry = next(e for e in ENTRIES if e.id == "failed-apply-leaves-c-unchanged-since-1.52")
    assert entry.xfail is not None
    reimpl = BackendId("reimpl", "1.51.1")
    history = Result(error=ErrorInfo(ErrorKind.TRANSIENT_HISTORY, "You cannot attempt to"))
    on = {"blamed": reimpl, "release": "1.58.0"}
    assert entry.xfail.matches_step(APPLY, UNKNOWN, UNKNOWN, **on)
    # A backend that does not raise where Drake refuses is a real bug, not this divergence.
    assert not entry.xfail.matches_step(APPLY, UNKNOWN, Result(), **on)
    assert not entry.xfail.matches_step(APPLY, history, history, **on)
    # A case the entry does not name is not narrowed in; the fuzzer (no case) is not narrowed.
    assert not entry.xfail.matches_step(APPLY, UNKNOWN, UNKNOWN, **on, case="x > y")
    assert entry.xfail.matches_step(APPLY, UNKNOWN, UNKNOWN, **on, case=None)


def test_the_failed_apply_entry_names_every_backend_that_claims_1_51_or_before() -> None:
    entry = next(e for e in ENTRIES if e.id == "failed-apply-leaves-c-unchanged-since-1.52")
    assert entry.xfail is not None
    case = entry.xfail.cases[0]

    def matches(blamed: BackendId) -> bool:
        assert entry.xfail is not None
        return entry.xfail.matches_step(
            APPLY, UNKNOWN, UNKNOWN, blamed=blamed, release="1.58.0", case=case
        )

    for blamed in (
        BackendId("drake==1.30.0", "1.30.0"),
        BackendId("pydrake", "1.51.1"),
        BackendId("reimpl", "1.51.1"),
        BackendId("reimpl==1.30.0", "1.30.0"),
    ):
        assert matches(blamed)
    assert not matches(BackendId("drake==1.52.0", "1.52.0"))
    assert not matches(BackendId("reimpl==1.52.0", "1.52.0"))


def test_a_crash_entry_matches_the_step_where_the_release_broke_or_failed_its_assertion() -> None:
    entry = next(e for e in ENTRIES if e.id == "undefined-ignored-group-aborts")
    assert entry.xfail is not None
    add = Command("add_models", {"file_name": "x.urdf"})
    blamed, abort = BackendId("drake==1.30.0", "1.30.0"), ErrorInfo(ErrorKind.ASSERTION, "Failure")
    on = {"blamed": blamed, "release": "1.30.0"}
    assert entry.xfail.matches_step(add, None, None, **on), "broke (crashed) at the step"
    assert entry.xfail.matches_step(add, None, Result(error=abort), **on)
    assert not entry.xfail.matches_step(add, None, Result(), **on)
