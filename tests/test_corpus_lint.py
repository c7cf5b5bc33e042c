"""The embedded corpus lints itself (after JSON-Schema-Test-Suite's sanity checks)."""

from __future__ import annotations

import re

import pytest

from conformance._corpus.loader import Case, load_corpus

FILES = load_corpus()
CASES = [case for f in FILES for case in f.cases]
TOPICS = {
    "statements/exclude_between",
    "statements/exclude_within",
    "statements/allow_between",
    "statements/allow_within",
    "statements/statement_order",
    "invariants/invariant_pairs",
    "resolution/resolution_time",
    "resolution/proximity_role_timing",
    "transient/table1",
    "transient/history",
    "errors/errors",
    "contexts/contexts",
    "removal/geometry_removal",
    "activation/activation",
}


def test_corpus_has_at_least_sixty_cases() -> None:
    assert len(CASES) >= 60


def test_corpus_has_a_file_per_topic() -> None:
    assert {f.name for f in FILES} >= TOPICS


def test_table_one_covers_all_eight_lines() -> None:
    table = next(f for f in FILES if f.name == "transient/table1")
    text = " ".join((s.comment or "") for c in table.cases for s in c.steps)
    for line in range(1, 9):
        assert f"line {line}" in text


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.qualified_name)
def test_case_description_states_a_fact(case: Case) -> None:
    assert not re.search(r"\bshould\b|\btest that\b", case.description, re.IGNORECASE)


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.qualified_name)
def test_case_has_an_expectation(case: Case) -> None:
    assert any(step.expect for step in case.steps)


def test_activation_cases_are_tagged() -> None:
    for case in CASES:
        if any(s.op in {"activate", "deactivate"} for s in case.steps):
            assert "activation" in case.features, case.qualified_name
