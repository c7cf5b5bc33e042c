"""Each known divergence is shown on real pydrake by the scenarios it names."""

from __future__ import annotations

from pathlib import Path

import pytest

from conformance.backends.loader import load_backend
from conformance.corpus.loader import Case, load_corpus
from conformance.policy.divergences import Divergence, known_divergences
from conformance.run.runner import Status, run_case, version_in_range

CASES: dict[str, Case] = {c.qualified_name: c for f in load_corpus() for c in f.cases}
ENTRIES = known_divergences()
ROOT = Path(__file__).resolve().parent.parent


def test_divergence_ids_are_unique() -> None:
    ids = [e.id for e in ENTRIES]
    assert len(ids) == len(set(ids))


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e.id)
def test_divergence_names_existing_evidence(entry: Divergence) -> None:
    assert entry.scenarios or entry.tests
    for name in entry.scenarios:
        assert name in CASES, f"{entry.id}: no scenario {name!r}"
    for path in entry.tests:
        assert (ROOT / path).is_file(), f"{entry.id}: no test file {path}"


@pytest.mark.parametrize(
    ("entry", "scenario"),
    [(e, s) for e in ENTRIES for s in e.scenarios],
    ids=lambda v: v.id if isinstance(v, Divergence) else v.split(" > ")[0],
)
def test_divergence_scenario_holds_on_real_pydrake(entry: Divergence, scenario: str) -> None:
    pydrake = load_backend("pydrake")
    if (
        not version_in_range(pydrake.version(), entry.since, entry.until)
        and entry.kind != "reimpl_vs_drake"
    ):
        pytest.skip(f"{entry.id} concerns Drake {entry.since}..{entry.until}")
    report = run_case(CASES[scenario], [pydrake])
    if report.status["pydrake"] is Status.SKIP:
        pytest.skip(report.skip_reasons["pydrake"])
    assert report.status["pydrake"] is Status.PASS, report.failures
