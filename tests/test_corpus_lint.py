"""The embedded corpus lints itself (after JSON-Schema-Test-Suite's sanity checks)."""

from __future__ import annotations

import re
from collections.abc import Callable

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


# One test per rule over every case, naming each offender (a test per case made 1252
# items whose collection and scheduling cost more than the checks).
def _offenders(rule: Callable[[Case], bool]) -> list[str]:
    return [case.qualified_name for case in CASES if not rule(case)]


#: Words of a wish, not a fact ("should", "test that").
WISH = re.compile(r"\bshould\b|\btest that\b", re.IGNORECASE)


def test_every_case_description_states_a_fact() -> None:
    assert _offenders(lambda case: not WISH.search(case.description)) == []


def test_every_case_has_an_expectation() -> None:
    assert _offenders(lambda case: any(step.expect for step in case.steps)) == []


@pytest.mark.parametrize(
    ("description", "states_a_fact"),
    [("allow_between leaves within-set pairs filtered", True), ("it should filter", False)],
)
def test_the_description_rule_tells_a_fact_from_a_wish(
    description: str, states_a_fact: bool
) -> None:
    assert (WISH.search(description) is None) == states_a_fact


def test_activation_cases_are_tagged() -> None:
    for case in CASES:
        if any(s.op in {"activate", "deactivate"} for s in case.steps):
            assert "activation" in case.features, case.qualified_name
