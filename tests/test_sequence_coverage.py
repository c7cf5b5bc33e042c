"""Sequence coverage: pairs of consecutive located events, and the tour that reaches them."""

from __future__ import annotations

import itertools
from collections import Counter

import pytest

from conformance._backends.loader import load_backend
from conformance._fuzz.campaign import Campaign
from conformance._fuzz.lockstep import LockstepMachine
from conformance._fuzz.operations import issued_ops
from conformance._fuzz.sequence_coverage import (
    PRINCIPAL,
    Relation,
    SequenceBook,
    SequenceCoverage,
    expected_pairs,
    sequence_events,
)
from conformance._fuzz.sequence_tour import _ROOM, TOUR, guided, tour, tours, walk_starts
from conformance.protocol import Command

_EXCLUDE_G1_G2 = {"exclude_between": [{"geometries": ["g1"]}, {"geometries": ["g2"]}]}

#: A sequence across the model, a context and its clone, with a read (has_transient_history)
#: that does not separate two events and a registration that does.
SEQUENCE = [
    Command("register_frame", {"name": "f1"}),
    Command("register_geometry", {"name": "g1", "frame": "f1", "roles": ["proximity"]}),
    Command("register_geometry", {"name": "g2", "frame": "world", "roles": ["proximity"]}),
    Command("apply", {"declaration": _EXCLUDE_G1_G2}),
    Command("create_context", {"name": "c1"}),
    Command("has_transient_history", {}),
    Command(
        "apply_transient",
        {"declaration": {"exclude_within": {"geometries": ["g1", "g2"]}}, "label": "t1"}
        | {"context": "c1"},
    ),
    Command("clone_context", {"name": "k1", "from": "c1"}),
    Command("remove_declaration", {"label": "t1", "context": "k1"}),
    Command("remove_role", {"geometry": "g1", "role": "proximity", "context": "k1"}),
    Command("set_default_context", {"context": "c1"}),
    Command("apply", {"declaration": _EXCLUDE_G1_G2}),
    Command("create_context", {"name": "c2"}),
    Command("assign_role", {"geometry": "g1", "role": "proximity", "context": "k1"}),
    Command("register_geometry", {"name": "g3", "frame": "world", "roles": ["proximity"]}),
    Command("apply", {"declaration": _EXCLUDE_G1_G2, "context": "c2"}),
]


@pytest.mark.parametrize("name", ["reimpl", "pydrake"])
def test_consecutive_events_count_as_pairs_with_the_relation_of_their_locations(
    name: str,
) -> None:
    backend = load_backend(name)
    backend.reset()
    book = SequenceBook()
    for command in SEQUENCE:
        result = backend.execute(command)
        assert result.error is None, (command, result.error)
        book.follow(command, result)
    assert book.pairs == Counter(
        {
            ("apply@model", Relation.SAME, "create_context@model"): 2,
            ("create_context@model", Relation.DESCENDANT, "apply_transient@context"): 1,
            ("apply_transient@context", Relation.SAME, "clone_context@context"): 1,
            ("clone_context@context", Relation.DESCENDANT, "remove_declaration@clone"): 1,
            ("remove_declaration@clone", Relation.SAME, "remove_role@clone"): 1,
            ("remove_role@clone", Relation.ORIGIN, "set_default_context@context"): 1,
            ("set_default_context@context", Relation.ORIGIN, "apply@model"): 1,
            ("create_context@model", Relation.DESCENDANT, "assign_role@clone"): 1,
        }
    )
    # the registration of g3 ends the run: its apply starts a new one
    assert not any(b == "apply@context" for _, _, b in book.pairs)
    assert len(book.triples) == 8
    # what each location has: c2 was made before g3, k1 lost g1's role but not g1
    assert book.names["c2"] == {"world", "f1", "g1", "g2"}
    assert book.names["model"] == {"world", "f1", "g1", "g2", "g3"}
    assert book.names["k1"] == {"world", "f1", "g1", "g2"}
    assert book.parent == {"c1": "model", "k1": "c1", "c2": "model"}
    assert book.active == {"model": [], "c1": ["t1"], "k1": [], "c2": []}
    assert book.triples[("apply@model", "create_context@model", "assign_role@clone")] == 1


def test_two_unrelated_contexts_are_an_other_relation_not_a_reachable_pair() -> None:
    book = SequenceBook(parent={"c1": "model", "c2": "model"})
    assert book.relation("c1", "c2") is Relation.OTHER
    assert book.relation("model", "c2") is Relation.DESCENDANT
    assert book.relation("c2", "model") is Relation.ORIGIN
    assert PRINCIPAL[("context", "context")] is Relation.SAME
    assert PRINCIPAL[("clone", "context")] is Relation.ORIGIN


def test_the_reachable_pairs_are_every_ordered_pair_of_the_located_events() -> None:
    ops = ["apply", "create_context", "clone_context", "assign_role", "register_geometry"]
    events = sequence_events(ops)
    assert events == [
        "apply@model",
        "apply@context",
        "apply@clone",
        "assign_role@model",
        "assign_role@context",
        "assign_role@clone",
        "clone_context@context",
        "clone_context@clone",
        "create_context@model",
    ]
    assert len(expected_pairs(ops)) == 81
    assert ("clone_context@clone", "clone_context@clone") in expected_pairs(ops)


def test_the_tour_holds_every_ordered_pair_once_as_consecutive_entries() -> None:
    events = tuple(sequence_events(["apply", "create_context", "clone_context", "remove_role"]))
    circuit = tour(events)
    assert len(circuit) == len(events) ** 2 + 1
    assert circuit[0] == circuit[-1]
    pairs = Counter(itertools.pairwise(circuit))
    assert set(pairs) == {(a, b) for a in events for b in events}
    assert set(pairs.values()) == {1}


def test_the_two_tours_hold_every_ordered_pair_once_the_making_one_those_with_a_maker() -> None:
    events = tuple(sequence_events(["apply", "create_context", "clone_context", "remove_role"]))
    making, plain = tours(events)
    makers = {"create_context@model", "clone_context@context", "clone_context@clone"}
    for circuit in (making, plain):
        assert circuit[0] == circuit[-1]
    pairs = Counter(itertools.pairwise(making)) + Counter(itertools.pairwise(plain))
    assert set(pairs) == {(a, b) for a in events for b in events}
    assert set(pairs.values()) == {1}
    assert set(itertools.pairwise(making)) == {
        (a, b) for a in events for b in events if {a, b} & makers
    }
    assert len(making) == 3 * 9 + 6 * 3 + 1  # 9 events, 3 of them makers
    assert len(plain) == 6 * 6 + 1


def _walk_with_room(circuit: tuple[str, ...], start: int, room: int) -> list[tuple[str, str]]:
    """The pairs a walk from ``start`` issues before a maker it has no room for."""
    points, issued = len(circuit) - 1, []
    for i in range(points):
        event = circuit[(start + i) % points]
        if event.rpartition("@")[0] in ("create_context", "clone_context"):
            if room == 0:
                break
            room -= 1
        issued.append(event)
    return list(itertools.pairwise(issued))


def test_walks_from_the_making_starts_with_room_for_three_contexts_reach_every_pair() -> None:
    """Each start of ``making`` is the third maker from the one before, so a walk with
    room for ``_ROOM`` (3) contexts reaches the pair that ends at the next start."""
    events = tuple(sequence_events(["apply", "create_context", "clone_context", "remove_role"]))
    making, plain = tours(events)
    assert _ROOM == 3
    starts = walk_starts(making)
    assert starts[0] == 0
    reached = {pair for s in starts for pair in _walk_with_room(making, s, _ROOM)}
    assert reached == set(itertools.pairwise(making))
    assert not {pair for s in starts for pair in _walk_with_room(making, s, _ROOM - 1)} >= reached
    assert walk_starts(plain) == tuple(range(len(plain) - 1))


def test_the_table_names_the_pairs_never_reached() -> None:
    coverage = SequenceCoverage()
    coverage.pairs[("apply@model", Relation.SAME, "apply@model")] = 3
    coverage.pairs[("apply@model", Relation.OTHER, "apply@model")] = 9  # not principal
    expected = expected_pairs(["apply"])
    gaps = coverage.gaps(expected)
    assert ("apply@model", "apply@model") not in gaps
    assert ("apply@context", "apply@clone") in gaps
    assert len(gaps) == 8
    table = coverage.table(expected)
    assert table.splitlines()[0].startswith("sequence pairs: 1 of 9 reachable pairs reached")
    assert "apply@context -> apply@clone" in table.splitlines()[-1]


def test_a_guided_machine_never_switches_the_tour_off_and_weighs_it_four_times() -> None:
    machine = guided(LockstepMachine)
    assert TOUR in machine.OPERATIONS
    assert TOUR not in LockstepMachine.OPERATIONS
    instance = object.__new__(machine)
    instance.weights = {TOUR: 3, "apply": 2}
    instance.switched_off = frozenset({TOUR, "apply"})
    assert instance.weights == {TOUR: 12, "apply": 2}
    assert instance.switched_off == frozenset({"apply"})


def test_a_guided_campaign_reaches_more_pairs_than_the_plain_one_at_the_same_seed() -> None:
    reimpl, pydrake = load_backend("reimpl"), load_backend("pydrake")
    reached = {}
    for label, base in (("plain", LockstepMachine), ("guided", guided(LockstepMachine))):
        campaign = Campaign(
            backend=lambda: reimpl, reference=lambda: pydrake, seed=1, max_examples=10
        )
        campaign.machine_base = base
        result = campaign.run()
        assert not result.divergences
        ops = issued_ops(LockstepMachine.OPERATIONS) - {"activate", "deactivate"}
        expected = expected_pairs(ops)
        reached[label] = len(expected) - len(result.stats.sequences.gaps(expected))
    assert reached["guided"] > reached["plain"] + 50, reached
