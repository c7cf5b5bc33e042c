"""The rule that sets aside pairwise answers differing only in pairs at ``max_distance``.

The records are pydrake 1.51.1's answers in scenarios/queries/max_distance.json (the
nested-frames case: φ = 2.53119217057012, reimpl's 1 ulp above).
"""

from __future__ import annotations

import math
from typing import Any

from conformance._policy.at_max_distance import PAIRWISE, differs_only_at_max_distance
from conformance._policy.divergences import divergence
from conformance.protocol import BackendId, Command, ErrorInfo, ErrorKind, Result

PHI = 2.53119217057012
AB: dict[str, Any] = {
    "pair": ["a", "b"],
    "shapes": ["sphere", "sphere"],
    "distance": PHI,
    "p_ACa": [0.02580788667731824, 0.08909739721869539, 0.03735782105670395],
    "p_BCb": [-0.037242349451508484, -0.021596764969494052, -0.025428077988400157],
    "nhat_BA_W": [-0.25807886677318237, -0.8909739721869538, -0.37357821056703955],
}
NEAR: dict[str, Any] = {**AB, "pair": ["a", "c"], "distance": 0.5}


def _at(max_distance: float) -> Command:
    return Command(PAIRWISE, {"max_distance": max_distance})


def test_a_pair_at_max_distance_missing_from_one_answer_is_at_the_boundary() -> None:
    assert differs_only_at_max_distance(_at(PHI), Result([NEAR, AB]), Result([NEAR]))
    assert differs_only_at_max_distance(_at(PHI), Result([NEAR]), Result([NEAR, AB]))


def test_a_pair_farther_from_max_distance_than_its_tolerance_is_a_real_difference() -> None:
    assert not differs_only_at_max_distance(_at(PHI + 1e-9), Result([AB]), Result([]))


def test_equal_answers_are_no_boundary_difference() -> None:
    assert not differs_only_at_max_distance(_at(PHI), Result([AB]), Result([AB]))


def test_a_boundary_pair_does_not_excuse_a_difference_in_the_common_pairs() -> None:
    moved = {**NEAR, "distance": 0.5 + 1e-6}
    assert not differs_only_at_max_distance(_at(PHI), Result([NEAR, AB]), Result([moved]))


def test_only_a_pairwise_query_with_a_finite_max_distance_qualifies() -> None:
    assert not differs_only_at_max_distance(Command(PAIRWISE, {}), Result([AB]), Result([]))
    assert not differs_only_at_max_distance(_at(math.inf), Result([AB]), Result([]))
    other = Command("compute_point_pair_penetration", {"max_distance": PHI})
    assert not differs_only_at_max_distance(other, Result([AB]), Result([]))
    error = Result(error=ErrorInfo(ErrorKind.OTHER, "x"))
    assert not differs_only_at_max_distance(_at(PHI), Result([AB]), error)


def test_the_last_bits_entry_sets_aside_reimpls_boundary_pair_on_1_51_and_1_58() -> None:
    entry = divergence("sphere-distance-last-bits")
    assert entry.kind == "reimpl_vs_drake"
    assert entry.xfail is not None
    for release in ("1.51.1", "1.58.0"):
        assert entry.xfail.matches_step(
            _at(PHI),
            Result([AB]),
            Result([]),
            blamed=BackendId("reimpl", "1.51.1"),
            release=release,
        )
    assert not entry.xfail.matches_step(
        _at(PHI + 1e-9),
        Result([AB]),
        Result([]),
        blamed=BackendId("reimpl", "1.51.1"),
        release="1.51.1",
    )


def test_the_boundary_entries_set_aside_reimpls_answers_only_not_a_mutants() -> None:
    """A mutant that is one ulp wide or strict at max_distance differs exactly at the
    boundary; the entries excuse reimpl's arithmetic and tree, so a mutant stays a finding
    (the mutant proofs pairwise_one_ulp_wide and pairwise_strict_at_max_distance)."""
    for name in ("sphere-distance-last-bits", "pairwise-prunes-ties-at-max-distance"):
        entry = divergence(name)
        assert entry.xfail is not None
        args = (_at(PHI), Result([AB]), Result([]))
        reimpl = BackendId("reimpl", "1.51.1")
        mutant = BackendId("mutant:pairwise_one_ulp_wide", "1.51.1")
        assert entry.xfail.matches_step(*args, blamed=reimpl, release="1.51.1")
        assert not entry.xfail.matches_step(*args, blamed=mutant, release="1.51.1")
