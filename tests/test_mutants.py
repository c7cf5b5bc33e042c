"""The mutants of conformance._testing.mutants: each one is caught, and none leaks into reimpl.

Every mutant has a witness: a short command sequence on which real pydrake
(the oracle) and plain reimpl agree, and the mutant reports something else.
Each witness asserts the exact value pydrake gives and the exact value the
mutant gives, so a mutant that stops injecting its bug fails here.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

import conformance._testing.mutants
import conformance._testing.mutants_basic
import conformance._testing.mutants_blind
import conformance._testing.mutants_boundary
import conformance._testing.mutants_order
import conformance._testing.mutants_report
import conformance._testing.mutants_state
import reimpl.geometry
import reimpl.math
import reimpl.systems.framework
from conformance._backends.loader import load_backend
from conformance._backends.multibody import model_features
from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.reimpl_api import reimpl_api
from conformance._backends.scene_graph import SceneGraphBackend
from conformance._testing.mutants import MUTANTS, MutantBackend, mutant_backend
from conformance.protocol import MODEL, Command, ErrorKind, Observation, Result

Run = tuple[list[Result], Observation]


# ------------------------------------------------------------ command sugar
def frame(name: str) -> Command:
    return Command("register_frame", {"name": name})


def geometry(name: str, frame: str, roles: Sequence[str] = ("proximity",)) -> Command:
    return Command("register_geometry", {"name": name, "frame": frame, "roles": list(roles)})


def on_own_frames(*names: str) -> list[Command]:
    """``a`` on frame ``f_a``, and so on, each with the proximity role."""
    return [c for n in names for c in (frame(f"f_{n}"), geometry(n, f"f_{n}"))]


def gset(*geometries: str, frames: Sequence[str] = ()) -> dict[str, list[str]]:
    return {"geometries": list(geometries), "frames": list(frames)}


def exclude_within(s: dict[str, list[str]]) -> dict[str, Any]:
    return {"op": "exclude_within", "set": s}


def allow_within(s: dict[str, list[str]]) -> dict[str, Any]:
    return {"op": "allow_within", "set": s}


def exclude_between(a: dict[str, list[str]], b: dict[str, list[str]]) -> dict[str, Any]:
    return {"op": "exclude_between", "a": a, "b": b}


def allow_between(a: dict[str, list[str]], b: dict[str, list[str]]) -> dict[str, Any]:
    return {"op": "allow_between", "a": a, "b": b}


def apply(*statements: dict[str, Any], **args: str) -> Command:
    return Command("apply", {"declaration": {"statements": list(statements)}, **args})


def apply_transient(label: str, *statements: dict[str, Any]) -> Command:
    declaration = {"statements": list(statements)}
    return Command("apply_transient", {"declaration": declaration, "label": label})


def remove_declaration(label: str) -> Command:
    return Command("remove_declaration", {"label": label})


# -------------------------------------------------------------- observation
def run(backend: SceneGraphBackend, commands: Sequence[Command]) -> Run:
    return [backend.execute(c) for c in commands], backend.observe()


def candidates(location: str = MODEL) -> Callable[[Run], set[str]]:
    """C at ``location`` as ``a-b`` strings."""
    return lambda r: {"-".join(pair) for pair in r[1].locations[location].candidates}


def history(r: Run) -> bool:
    return r[1].locations[MODEL].has_transient_history


def last_error_and_candidates(r: Run) -> tuple[ErrorKind | None, set[str]]:
    error = r[0][-1].error
    return (None if error is None else error.kind), candidates()(r)


def both_locations(r: Run) -> tuple[set[str], set[str]]:
    return candidates()(r), candidates("c")(r)


def count(fact: Callable[[Run], set[str]]) -> Callable[[Run], int]:
    return lambda r: len(fact(r))


def active(label: str, location: str = MODEL) -> Callable[[Run], bool]:
    """IsActive(``label``) at ``location``."""
    return lambda r: r[1].locations[location].active[label]


def in_context(context: str, command: Command) -> Command:
    return Command(command.op, {**command.args, "context": context})


#: 17 geometries: one past a 16-wide word.
CROWD = [f"g{i:02}" for i in range(17)]


# ------------------------------------------------ posed scenes (boundaries)
def ball(name: str, frame: str) -> list[Command]:
    """A sphere of radius 0.5 named ``name``, alone on a new frame ``frame``."""
    return [
        Command("register_frame", {"name": frame}),
        Command(
            "register_geometry",
            {
                "name": name,
                "frame": frame,
                "roles": ["proximity"],
                "shape": {"type": "sphere", "radius": 0.5},
            },
        ),
    ]


def last_pairs(r: Run) -> list[list[str]]:
    """The pairs of the last step's query records."""
    return [rec["pair"] for rec in r[0][-1].value]


def last_value(r: Run) -> Any:
    return r[0][-1].value


#: Spheres a and c of radius 0.5, exactly 0.5 apart.
APART = [
    *ball("a", "f_a"),
    *ball("c", "f_c"),
    Command("set_poses", {"poses": {"f_c": {"xyz": [0.0, 1.5, 0.0]}}}),
]
#: Spheres a and b overlapping by 0.2, the pair excluded by transient t1.
OVERLAP = [
    *ball("a", "f_a"),
    *ball("b", "f_b"),
    Command("set_poses", {"poses": {"f_b": {"xyz": [0.8, 0.0, 0.0]}}}),
    apply_transient("t1", exclude_within(gset("a", "b"))),
]


# ------------------------------------------------- reports only observe has
def filtered(a: str, b: str, location: str = MODEL) -> Callable[[Run], object]:
    """The sampled CollisionFiltered answer of ``(a, b)`` at ``location``."""
    return lambda r: (r[1].locations[location].filtered or {})[(a, b)]


STATUS_ERROR = "error: Can't report collision filter status between geometries a and b; "


def count_of(key: str, location: str = MODEL) -> Callable[[Run], object]:
    """The inspector's count ``key`` at ``location``."""
    return lambda r: (r[1].locations[location].counts or {})[key]


# ---------------------------------------------------------------- witnesses
@dataclass(frozen=True)
class Witness:
    mutant: str
    commands: list[Command]
    #: What is compared: a function of the step results and the final observation.
    fact: Callable[[Run], object]
    pydrake: object
    mutated: object


WITNESSES = [
    Witness(
        "allow_clears_invariants",
        [
            frame("f"),
            geometry("a", "f"),
            geometry("b", "f"),
            apply(allow_within(gset(frames=["f"]))),
        ],
        candidates(),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "allow_between_clears_within",
        [
            *on_own_frames("a", "b", "c"),
            apply(exclude_within(gset("a", "b", "c"))),
            apply(allow_between(gset("a", "b"), gset("c"))),
        ],
        candidates(),
        pydrake={"a-c", "b-c"},
        mutated={"a-b", "a-c", "b-c"},
    ),
    Witness(
        "reverse_statement_order",
        [
            *on_own_frames("a", "b"),
            apply(exclude_within(gset("a", "b")), allow_within(gset("a", "b"))),
        ],
        candidates(),
        pydrake={"a-b"},
        mutated=set(),
    ),
    Witness(
        "lazy_frame_resolution",
        [
            frame("f"),
            geometry("a", "f"),
            *on_own_frames("b"),
            apply(exclude_between(gset(frames=["f"]), gset("b"))),
            geometry("c", "f"),
        ],
        candidates(),
        pydrake={"b-c"},
        mutated=set(),
    ),
    Witness(
        "remove_declaration_no_replay",
        [
            *on_own_frames("a", "b", "c"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            apply_transient("t2", exclude_within(gset("a", "b", "c"))),
            remove_declaration("t2"),
        ],
        candidates(),
        pydrake={"a-c", "b-c"},
        mutated={"a-b", "a-c", "b-c"},
    ),
    Witness(
        "context_managers_write_model",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            apply(exclude_within(gset("a", "b")), context="c"),
        ],
        both_locations,
        pydrake=({"a-b"}, set()),
        mutated=(set(), {"a-b"}),
    ),
    Witness(
        "non_proximity_ids_raise",
        [
            *on_own_frames("a", "b"),
            geometry("n", "world", roles=["illustration"]),
            apply(exclude_within(gset("a", "b", "n"))),
        ],
        last_error_and_candidates,
        pydrake=(None, set()),
        mutated=(ErrorKind.OTHER, {"a-b"}),
    ),
    Witness(
        "apply_during_history_allowed",
        [
            *on_own_frames("a", "b", "c"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            apply(exclude_within(gset("b", "c"))),
        ],
        last_error_and_candidates,
        pydrake=(ErrorKind.TRANSIENT_HISTORY, {"a-c", "b-c"}),
        mutated=(None, {"a-c"}),
    ),
    Witness(
        "role_reassign_keeps_filters",
        [
            *on_own_frames("a", "b"),
            apply(exclude_within(gset("a", "b"))),
            Command("remove_role", {"geometry": "a", "role": "proximity"}),
            Command("assign_role", {"geometry": "a", "role": "proximity"}),
        ],
        candidates(),
        pydrake={"a-b"},
        mutated=set(),
    ),
    Witness(
        "stale_has_transient_history",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            remove_declaration("t1"),
        ],
        history,
        pydrake=False,
        mutated=True,
    ),
    Witness(
        "world_frame_resolves_nothing",
        [
            geometry("a", "world"),
            geometry("b", "world"),
            *on_own_frames("c"),
            apply(exclude_between(gset(frames=["world"]), gset("c"))),
        ],
        candidates(),
        pydrake=set(),
        mutated={"a-c", "b-c"},
    ),
    Witness(
        "no_same_frame_invariant",
        [frame("f"), geometry("a", "f"), geometry("b", "f")],
        candidates(),
        pydrake=set(),
        mutated={"a-b"},
    ),
    # -------------------------------------------- mutants_state: sizes
    Witness(
        "candidate_scan_one_word",
        on_own_frames(*CROWD),
        count(candidates()),
        pydrake=136,
        mutated=120,
    ),
    Witness(
        "invariant_word_overflow",
        [*on_own_frames(*CROWD), geometry("h", "f_g00")],
        lambda r: "g00-h" in candidates()(r),
        pydrake=False,
        mutated=True,
    ),
    # ----------------------------------------------------- sequences
    Witness(
        "history_ring_of_four",
        [
            *on_own_frames("a", "b"),
            *(apply_transient(f"t{i}", exclude_within(gset("a", "b"))) for i in range(5)),
        ],
        active("t0"),
        pydrake=True,
        mutated=False,
    ),
    Witness(
        "filter_ids_recycled",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            remove_declaration("t1"),
            apply_transient("t2", exclude_within(gset("a", "b"))),
        ],
        active("t1"),
        pydrake=False,
        mutated=True,
    ),
    Witness(
        "frame_index_stale_after_remove_role",
        [
            *on_own_frames("a", "x"),
            Command("remove_role", {"frame": "f_a", "role": "proximity"}),
            Command("assign_role", {"geometry": "a", "role": "proximity"}),
            apply(exclude_between(gset(frames=["f_a"]), gset("x"))),
        ],
        candidates(),
        pydrake=set(),
        mutated={"a-x"},
    ),
    # -------------------------------------------------------- replays
    Witness(
        "replay_newest_first",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            apply_transient("t2", allow_within(gset("a", "b"))),
            apply_transient("t3", exclude_within(gset("a"))),
            remove_declaration("t3"),
        ],
        candidates(),
        pydrake={"a-b"},
        mutated=set(),
    ),
    Witness(
        "replay_skips_oldest",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            apply_transient("t2", exclude_within(gset("a"))),
            remove_declaration("t2"),
        ],
        candidates(),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "erase_skips_successor",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a"))),
            apply_transient("t2", exclude_within(gset("a", "b"))),
            apply_transient("t3", exclude_within(gset("b"))),
            remove_declaration("t1"),
        ],
        candidates(),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "replay_allows_before_excludes",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b")), allow_within(gset("a", "b"))),
            apply_transient("t2", exclude_within(gset("a"))),
            remove_declaration("t2"),
        ],
        candidates(),
        pydrake={"a-b"},
        mutated=set(),
    ),
    # ------------------------------------------------------- contexts
    Witness(
        "copies_share_history",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            in_context("c", apply_transient("t1", exclude_within(gset("a", "b")))),
            Command("clone_context", {"name": "d", "from": "c"}),
            Command("is_active", {"label": "t1", "context": "d"}),
            in_context("c", remove_declaration("t1")),
        ],
        active("t1", "d"),
        pydrake=True,
        mutated=False,
    ),
    Witness(
        "clone_renumbers_history",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            in_context("c", apply_transient("t1", exclude_within(gset("a", "b")))),
            Command("clone_context", {"name": "d", "from": "c"}),
        ],
        active("t1", "d"),
        pydrake=True,
        mutated=False,
    ),
    Witness(
        "default_context_flattens_history",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            Command("create_context", {"name": "c"}),
        ],
        active("t1", "c"),
        pydrake=True,
        mutated=False,
    ),
    # Order across locations (mutants_order, issue 30): values measured on pydrake 1.51.1.
    Witness(
        "context_after_apply_stale",
        [
            *on_own_frames("a", "b"),
            apply(exclude_within(gset("a", "b"))),
            Command("create_context", {"name": "c"}),
        ],
        candidates("c"),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "context_after_removal_stale",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            remove_declaration("t1"),
            Command("create_context", {"name": "c"}),
        ],
        active("t1", "c"),
        pydrake=False,
        mutated=True,
    ),
    Witness(
        "copy_under_history_drops_own",
        [
            *on_own_frames("a", "b", "x", "y"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            Command("create_context", {"name": "c"}),
            in_context("c", apply_transient("t2", exclude_within(gset("x", "y")))),
            in_context("c", remove_declaration("t1")),
        ],
        active("t2", "c"),
        pydrake=True,
        mutated=False,
    ),
    Witness(
        "clone_drops_partial_apply",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            in_context(
                "c", apply(exclude_within(gset("a", "b")), exclude_within(gset("@unknown")))
            ),
            Command("clone_context", {"name": "d", "from": "c"}),
        ],
        candidates("d"),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "clone_keeps_removed_inherited",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            in_context("c", apply_transient("t1", exclude_within(gset("a", "b")))),
            Command("clone_context", {"name": "d", "from": "c"}),
            in_context("d", remove_declaration("t1")),
        ],
        active("t1", "d"),
        pydrake=False,
        mutated=True,
    ),
    Witness(
        "clone_frames_resolve_at_clone_time",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            Command("clone_context", {"name": "d", "from": "c"}),
            Command(
                "register_geometry",
                {"name": "x", "frame": "f_a", "roles": ["proximity"], "context": "d"},
            ),
            in_context("d", apply(exclude_between(gset(frames=["f_a"]), gset("b")))),
        ],
        candidates("d"),
        pydrake=set(),
        mutated={"b-x"},
    ),
    Witness(
        "context_reassign_takes_model_filters",
        [
            *on_own_frames("a", "b"),
            apply(exclude_within(gset("a", "b"))),
            Command("create_context", {"name": "c"}),
            Command("remove_role", {"frame": "f_a", "role": "proximity", "context": "c"}),
            Command("assign_role", {"geometry": "a", "role": "proximity", "context": "c"}),
        ],
        candidates("c"),
        pydrake={"a-b"},
        mutated=set(),
    ),
    Witness(
        "ring_replay_after_oldest_removed",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            apply_transient("t2", allow_within(gset("a", "b"))),
            apply_transient("t3", exclude_within(gset("a", "b"))),
            apply_transient("t4", allow_within(gset("a", "b"))),
            apply_transient("t5", exclude_within(gset("a", "b"))),
            remove_declaration("t1"),
        ],
        candidates(),
        pydrake=set(),
        mutated={"a-b"},
    ),
    # Boundaries (mutants_boundary, issue 30): values measured on pydrake 1.51.1.
    Witness(
        "pairwise_strict_at_max_distance",
        [*APART, Command("compute_signed_distance_pairwise_closest_points", {"max_distance": 0.5})],
        last_pairs,
        pydrake=[["a", "c"]],
        mutated=[],
    ),
    Witness(
        "pairwise_one_ulp_wide",
        [
            *APART,
            Command(
                "compute_signed_distance_pairwise_closest_points",
                {"max_distance": math.nextafter(0.5, 0.0)},
            ),
        ],
        last_pairs,
        pydrake=[],
        mutated=[["a", "c"]],
    ),
    Witness(
        "has_collisions_ignores_transient_filters",
        [*OVERLAP, Command("has_collisions", {})],
        last_value,
        pydrake=False,
        mutated=True,
    ),
    Witness(
        "pairwise_distances_ignore_transient_filters",
        [*OVERLAP, Command("compute_signed_distance_pairwise_closest_points", {})],
        last_pairs,
        pydrake=[],
        mutated=[["a", "b"]],
    ),
    # Reports only observe has (mutants_report, issue 30): measured on pydrake 1.51.1.
    Witness(
        "collision_filtered_blames_the_first",
        [*on_own_frames("a"), geometry("b", "f_a", roles=["illustration"])],
        filtered("a", "b"),
        pydrake=STATUS_ERROR + "b does not have a proximity role",
        mutated=STATUS_ERROR + "a does not have a proximity role",
    ),
    Witness(
        "frame_role_count_keeps_removed",
        [*on_own_frames("a"), Command("remove_role", {"geometry": "a", "role": "proximity"})],
        count_of("frame f_a proximity"),
        pydrake=0,
        mutated=1,
    ),
    # A blind audit (mutants_blind, issue 31): values measured on pydrake 1.51.1.
    Witness(
        "allow_within_clears_rows",
        [
            *on_own_frames("a", "b", "c"),
            apply(exclude_within(gset("a", "b", "c"))),
            apply(allow_within(gset("a", "b"))),
        ],
        candidates(),
        pydrake={"a-b"},
        mutated={"a-b", "a-c", "b-c"},
    ),
    Witness(
        "between_skips_overlap",
        [*on_own_frames("a", "b", "c"), apply(exclude_between(gset("a", "b"), gset("b", "c")))],
        candidates(),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "anchored_invariant_per_source",
        [
            Command("register_source", {"name": "s2"}),
            geometry("a", "world"),
            Command(
                "register_geometry",
                {"name": "b", "frame": "world", "source": "s2", "roles": ["proximity"]},
            ),
        ],
        candidates(),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "context_registration_misses_invariant",
        [
            frame("f"),
            geometry("a", "f"),
            Command("create_context", {"name": "c"}),
            in_context("c", geometry("b", "f")),
        ],
        candidates("c"),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "slot_reuse_inherits_filters",
        [
            *on_own_frames("a", "b"),
            apply(exclude_between(gset("a"), gset("b"))),
            Command("remove_role", {"geometry": "a", "role": "proximity"}),
            *on_own_frames("d"),
        ],
        candidates(),
        pydrake={"b-d"},
        mutated=set(),
    ),
    Witness(
        "world_role_removal_crosses_sources",
        [
            Command("register_source", {"name": "s2"}),
            geometry("a", "world"),
            Command(
                "register_geometry",
                {"name": "b", "frame": "world", "source": "s2", "roles": ["proximity"]},
            ),
            Command("remove_role", {"frame": "world", "role": "proximity"}),
        ],
        last_value,
        pydrake=1,
        mutated=2,
    ),
    Witness(
        "remove_role_counts_all",
        [
            frame("f"),
            geometry("a", "f"),
            geometry("b", "f", roles=["illustration"]),
            Command("remove_role", {"frame": "f", "role": "proximity"}),
        ],
        last_value,
        pydrake=1,
        mutated=2,
    ),
    Witness(
        "replace_proximity_resets_filters",
        [
            *on_own_frames("a", "b"),
            apply(exclude_within(gset("a", "b"))),
            Command("assign_role", {"geometry": "a", "role": "proximity", "assign": "replace"}),
        ],
        candidates(),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "set_default_context_keeps_filters",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            in_context("c", apply(exclude_within(gset("a", "b")))),
            Command("set_default_context", {"context": "c"}),
        ],
        candidates("c"),
        pydrake={"a-b"},
        mutated=set(),
    ),
    Witness(
        "context_managers_share_first",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            Command("create_context", {"name": "d"}),
            in_context("c", apply(allow_within(gset("a", "b")))),
            in_context("d", apply(exclude_within(gset("a", "b")))),
        ],
        lambda r: (candidates("c")(r), candidates("d")(r)),
        pydrake=({"a-b"}, set()),
        mutated=(set(), {"a-b"}),
    ),
    Witness(
        "clone_drops_history",
        [
            *on_own_frames("a", "b"),
            Command("create_context", {"name": "c"}),
            in_context("c", apply_transient("t1", exclude_within(gset("a", "b")))),
            Command("clone_context", {"name": "d", "from": "c"}),
        ],
        candidates("d"),
        pydrake=set(),
        mutated={"a-b"},
    ),
    Witness(
        "remove_declaration_twice_true",
        [
            *on_own_frames("a", "b"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            remove_declaration("t1"),
            remove_declaration("t1"),
        ],
        last_value,
        pydrake=False,
        mutated=True,
    ),
    Witness(
        "remove_declaration_off_by_one",
        [
            *on_own_frames("a", "b", "c"),
            apply_transient("t1", exclude_within(gset("a", "b"))),
            apply_transient("t2", exclude_within(gset("b", "c"))),
            remove_declaration("t1"),
        ],
        candidates(),
        pydrake={"a-b", "a-c"},
        mutated={"a-c", "b-c"},
    ),
]


def pydrake_backend() -> SceneGraphBackend:
    return SceneGraphBackend(pydrake_api())


def reimpl_backend() -> SceneGraphBackend:
    return SceneGraphBackend(reimpl_api())


def test_every_mutant_has_exactly_one_witness() -> None:
    assert sorted(w.mutant for w in WITNESSES) == sorted(MUTANTS)
    assert len(MUTANTS) >= 24


@pytest.mark.parametrize("witness", WITNESSES, ids=lambda w: w.mutant)
def test_plain_reimpl_matches_pydrake_on_the_witness(witness: Witness) -> None:
    oracle = run(pydrake_backend(), witness.commands)
    plain = run(reimpl_backend(), witness.commands)
    assert witness.fact(oracle) == witness.pydrake
    assert plain == oracle


@pytest.mark.parametrize("witness", WITNESSES, ids=lambda w: w.mutant)
def test_the_mutant_differs_from_pydrake_on_its_witness(witness: Witness) -> None:
    mutated = run(mutant_backend(witness.mutant), witness.commands)
    assert witness.fact(mutated) == witness.mutated
    assert witness.mutated != witness.pydrake


@pytest.mark.parametrize("witness", WITNESSES, ids=lambda w: w.mutant)
def test_interleaved_mutant_calls_leave_plain_reimpl_unaffected(witness: Witness) -> None:
    oracle = run(pydrake_backend(), witness.commands)
    alone = run(mutant_backend(witness.mutant), witness.commands)
    plain, mutant = reimpl_backend(), mutant_backend(witness.mutant)
    plain_results, mutant_results = [], []
    for command in witness.commands:
        mutant_results.append(mutant.execute(command))
        plain_results.append(plain.execute(command))
        mutant.observe()
    assert (plain_results, plain.observe()) == oracle
    assert (mutant_results, mutant.observe()) == alone


#: reimpl's public namespaces: the only reimpl modules a mutant may import.
PUBLIC_REIMPL = (reimpl.geometry, reimpl.math, reimpl.systems.framework)


@pytest.mark.parametrize("name", sorted(MUTANTS))
def test_a_mutant_leaves_reimpls_public_classes_untouched(name: str) -> None:
    targets = [
        value
        for module in PUBLIC_REIMPL
        for value in vars(module).values()
        if isinstance(value, type)
    ]
    before = [dict(vars(t)) for t in targets]
    backend = mutant_backend(name)
    run(
        backend,
        [
            frame("f"),
            geometry("a", "f"),
            geometry("b", "f"),
            Command("create_context", {"name": "c"}),
        ],
    )
    backend.reset()
    assert [dict(vars(t)) for t in targets] == before


@pytest.mark.parametrize("name", sorted(MUTANTS))
def test_a_mutant_replaces_public_classes_by_subclasses_only(name: str) -> None:
    geometry = MUTANTS[name].api().geometry
    for public in reimpl.geometry.__all__:
        mutated, original = getattr(geometry, public), getattr(reimpl.geometry, public)
        assert mutated is original or issubclass(mutated, original), public
    assert issubclass(geometry.SceneGraph, reimpl.geometry.SceneGraph)
    assert geometry.SceneGraph is not reimpl.geometry.SceneGraph


@pytest.mark.parametrize(
    "mutants_module",
    [
        conformance._testing.mutants,
        conformance._testing.mutants_basic,
        conformance._testing.mutants_blind,
        conformance._testing.mutants_boundary,
        conformance._testing.mutants_order,
        conformance._testing.mutants_report,
        conformance._testing.mutants_state,
    ],
    ids=lambda module: module.__name__.rsplit(".", 1)[-1],
)
def test_the_mutants_modules_use_only_reimpls_public_names(mutants_module: ModuleType) -> None:
    source = Path(str(mutants_module.__file__)).read_text(encoding="utf-8")
    exported = {m.__name__: set(m.__all__) for m in PUBLIC_REIMPL}
    tree = ast.parse(source)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "reimpl":
                    assert alias.name in exported, alias.name
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if module.split(".")[0] == "reimpl":
                assert module in exported, module
                for alias in node.names:
                    assert not alias.name.startswith("_"), f"{module}.{alias.name}"
                    assert alias.name in exported[module], f"{module}.{alias.name} is not exported"
        elif isinstance(node, ast.Attribute):
            # No private attribute of anything (reimpl's internals included) is read.
            private = node.attr.startswith("_") and not node.attr.startswith("__")
            assert not private, f"line {node.lineno}: .{node.attr}"


@pytest.mark.parametrize("name", ["apply_during_history_allowed", "remove_declaration_no_replay"])
def test_filter_ids_survive_a_mutant_re_applying_the_history(name: str) -> None:
    """These mutants re-apply transient declarations; the caller's FilterIds still work."""
    commands = [
        *on_own_frames("a", "b", "c"),
        apply_transient("t1", exclude_within(gset("a", "b"))),
        apply_transient("t2", exclude_within(gset("b", "c"))),
        apply(exclude_within(gset("a", "c"))),
        remove_declaration("t2"),
        Command("is_active", {"label": "t1"}),
        Command("is_active", {"label": "t2"}),
        remove_declaration("t1"),
        remove_declaration("t1"),
    ]
    oracle = run(pydrake_backend(), commands)
    mutated = run(mutant_backend(name), commands)
    assert [r.value for r in mutated[0][-4:]] == [r.value for r in oracle[0][-4:]]
    assert [r.value for r in oracle[0][-4:]] == [True, False, True, False]
    assert not history(mutated)
    assert mutated[1].locations[MODEL].active == oracle[1].locations[MODEL].active


def test_reset_gives_the_mutant_an_empty_scene_graph() -> None:
    backend = mutant_backend("no_same_frame_invariant")
    run(backend, [frame("f"), geometry("a", "f"), geometry("b", "f")])
    backend.reset()
    assert backend.observe().locations[MODEL].candidates == frozenset()


def test_a_mutant_backend_is_named_after_its_mutant() -> None:
    backend = mutant_backend("stale_has_transient_history")
    assert isinstance(backend, MutantBackend)
    assert backend.name == "mutant:stale_has_transient_history"
    assert backend.version() == reimpl_backend().version()
    # A mutant patches reimpl's SceneGraph only: it runs every SceneGraph case reimpl runs,
    # and skips model cases (its Api has no multibody modules).
    reimpl = reimpl_backend()
    assert backend.features() == reimpl.features() - model_features(reimpl.api)
    assert model_features(reimpl.api) == {
        "multibody",
        "parsing",
        "adjacency_opt_out",
        "filter_groups_report",
    }


def test_load_backend_resolves_a_mutant_spec() -> None:
    backend = load_backend("conformance._testing.mutants:reverse_statement_order")
    assert backend.name == "mutant:reverse_statement_order"


def test_the_module_offers_a_factory_per_mutant_and_nothing_else() -> None:
    factory = conformance._testing.mutants.allow_clears_invariants
    assert factory().name == "mutant:allow_clears_invariants"
    with pytest.raises(AttributeError, match="no_such_mutant"):
        _ = conformance._testing.mutants.no_such_mutant


@pytest.mark.parametrize("name", sorted(MUTANTS))
def test_every_mutant_bug_is_one_sentence(name: str) -> None:
    bug = MUTANTS[name].bug
    assert MUTANTS[name].name == name
    assert bug.endswith(".")
    assert bug.count(". ") == 0


#: Scenes one short of the size a size-dependent mutant needs (16 proximity
#: geometries), with the edits its witness makes.
ONE_SHORT = {
    "candidate_scan_one_word": on_own_frames(*CROWD[:16]),
    "invariant_word_overflow": [*on_own_frames(*CROWD[:15]), geometry("h", "f_g00")],
}


@pytest.mark.parametrize("name", sorted(ONE_SHORT))
def test_a_size_mutant_matches_reimpl_one_short_of_its_size(name: str) -> None:
    commands = ONE_SHORT[name]
    assert run(mutant_backend(name), commands) == run(reimpl_backend(), commands)
