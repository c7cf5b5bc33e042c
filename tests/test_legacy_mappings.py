"""reimpl.legacy.mappings: every mapping filters exactly the pairs it was given.

Property tests on random pair sets and random bitmask groups over up to 60
elements; equality is of the whole filtered-pair set.
"""

from __future__ import annotations

import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from reimpl.legacy import (
    UNIVERSAL,
    CollisionFilterGroups,
    MappingInputError,
    TooManyGroupsError,
    clique_cover_lower_bound,
    group_lower_bound,
    groups_to_cliques,
    to_cliques,
    to_groups,
)

MAX_ELEMENTS = 60
SETTINGS = settings(max_examples=100, deadline=None)

PairSet = set[frozenset[int]]


@st.composite
def pair_sets(draw: st.DrawFn) -> tuple[PairSet, list[int]]:
    """Elements 0..n-1 (n ≤ 60) and a pair set: drawn pair by pair for small n (so it
    shrinks), or from a seeded density for large n."""
    n = draw(st.integers(0, MAX_ELEMENTS))
    elements = list(range(n))
    if n <= 12:
        all_pairs = [frozenset((a, b)) for a in elements for b in elements if a < b]
        chosen = draw(st.sets(st.sampled_from(all_pairs))) if all_pairs else set()
        return set(chosen), elements
    density = draw(st.sampled_from([0.02, 0.1, 0.3, 0.6, 0.9, 1.0]))
    rng = random.Random(draw(st.integers(0, 2**32 - 1)))
    pairs = {
        frozenset((a, b)) for a in elements for b in elements if a < b and rng.random() < density
    }
    return pairs, elements


@st.composite
def filter_groups(draw: st.DrawFn) -> tuple[CollisionFilterGroups[int], list[int]]:
    """Up to 10 groups with random members among up to 60 elements, random ignores (self,
    others, the universal group, names never defined)."""
    n = draw(st.integers(0, MAX_ELEMENTS))
    elements = list(range(n))
    k = draw(st.integers(1, 10))
    rng = random.Random(draw(st.integers(0, 2**32 - 1)))
    size = draw(st.sampled_from([0.05, 0.2, 0.5]))
    groups: CollisionFilterGroups[int] = CollisionFilterGroups()
    names = [f"G{i}" for i in range(k)]
    for name in names:
        groups.define_group(name)
        for e in elements:
            if rng.random() < size:
                groups.add_member(name, e)
    for name in names:
        for target in names:
            if rng.random() < 0.25:
                groups.ignore(name, target)
        if rng.random() < 0.05:
            groups.ignore(name, UNIVERSAL)
        if rng.random() < 0.1:
            groups.ignore(name, "undefined")
    groups.end_session()
    return groups, elements


class TestCliqueMappingsAreExact:
    """Seed 003: "there is no filtering scenario that can be represented by one that cannot
    be represented by the other"; each mapping filters exactly F."""

    @SETTINGS
    @given(pair_sets())
    def test_to_cliques_greedy_and_cover(self, case: tuple[PairSet, list[int]]) -> None:
        pairs, elements = case
        greedy = to_cliques(pairs, elements, "greedy")
        cover = to_cliques(pairs, elements, "cover")
        assert greedy.filtered_pairs(elements) == pairs
        assert cover.filtered_pairs(elements) == pairs
        assert greedy.num_cliques == len(pairs)
        bound = clique_cover_lower_bound(pairs, elements)
        assert bound <= cover.num_cliques <= greedy.num_cliques
        assert (bound == 0) == (not pairs)

    @SETTINGS
    @given(filter_groups())
    def test_groups_to_cliques_greedy_and_cover(
        self, case: tuple[CollisionFilterGroups[int], list[int]]
    ) -> None:
        groups, elements = case
        pairs = groups.filtered_pairs(elements)
        greedy = groups_to_cliques(groups, elements, "greedy")
        cover = groups_to_cliques(groups, elements, "cover")
        assert greedy.filtered_pairs(elements) == pairs
        assert cover.filtered_pairs(elements) == pairs
        assert clique_cover_lower_bound(pairs, elements) <= cover.num_cliques


class TestGroupMappingIsExact:
    """to_groups: any pair set to at most 127 user groups, exactly, or a clear error."""

    @SETTINGS
    @given(pair_sets())
    def test_to_groups_of_any_pair_set(self, case: tuple[PairSet, list[int]]) -> None:
        pairs, elements = case
        groups = to_groups(pairs, elements)
        assert groups.filtered_pairs(elements) == pairs
        assert group_lower_bound(pairs, elements) <= groups.num_groups <= 127

    @SETTINGS
    @given(filter_groups())
    def test_to_groups_round_trip_of_groups(
        self, case: tuple[CollisionFilterGroups[int], list[int]]
    ) -> None:
        groups, elements = case
        pairs = groups.filtered_pairs(elements)
        again = to_groups(pairs, elements)
        assert again.filtered_pairs(elements) == pairs

    def test_a_modern_candidate_sets_complement_maps_to_groups(self) -> None:
        """F = all pairs − C, for C a SceneGraph's candidates (here: a ring of 40)."""
        elements = list(range(40))
        candidates = {frozenset((i, (i + 1) % 40)) for i in elements}
        everything = {frozenset((a, b)) for a in elements for b in elements if a < b}
        filtered = everything - candidates
        groups = to_groups(filtered, elements)
        assert groups.filtered_pairs(elements) == filtered
        cliques = to_cliques(filtered, elements)
        assert cliques.filtered_pairs(elements) == filtered

    def test_more_than_127_groups_raise_with_the_lower_bound(self) -> None:
        """130 disjoint pairs: a fooling set of 130, so any encoding needs ≥ 129 groups."""
        elements = list(range(260))
        pairs = {frozenset((2 * i, 2 * i + 1)) for i in range(130)}
        assert group_lower_bound(pairs, elements) == 129
        with pytest.raises(
            TooManyGroupsError, match=r"needs 130 user groups .* at least 129\), .* holds 127"
        ):
            to_groups(pairs, elements)
        assert to_cliques(pairs, elements).num_cliques == 130  # Cliques have no such limit.

    def test_invisible_elements_share_one_group_ignoring_bit_0(self) -> None:
        elements = list(range(10))
        pairs = {frozenset((0, e)) for e in elements[1:]}  # 0 is filtered against all.
        groups = to_groups(pairs, elements)
        assert groups.num_groups == 1
        assert groups.name_of(1) == "invisible"
        assert groups.ignored_bits(1) == (UNIVERSAL,)


class TestMappingInput:
    def test_bad_pairs_and_methods_are_input_errors(self) -> None:
        with pytest.raises(MappingInputError, match="two distinct elements"):
            to_cliques([frozenset((1,))], [1])
        with pytest.raises(MappingInputError, match="not among the elements"):
            to_groups([frozenset((1, 9))], [1, 2])
        with pytest.raises(MappingInputError, match="unknown method 'best'"):
            to_cliques([], [], "best")  # type: ignore[arg-type]

    def test_a_complete_set_is_one_clique_and_one_group(self) -> None:
        elements = list(range(8))
        pairs = {frozenset((a, b)) for a in elements for b in elements if a < b}
        assert to_cliques(pairs, elements).num_cliques == 1
        assert to_groups(pairs, elements).num_groups == 1
        assert clique_cover_lower_bound(pairs, elements) == 1
