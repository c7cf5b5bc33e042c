"""Mutants: reimpl with one deliberate bug each, to measure the harness itself.

Mutation testing of the harness: a differential fuzzer that cannot tell these
backends from real pydrake cannot be trusted to catch a real regression either.
Each mutant is the ``reimpl`` backend with exactly one bug injected; the
``bug`` field of its table entry says, in one sentence, what is wrong.

Injection swaps attributes on reimpl's classes only while the mutant backend's
own calls run (``reset``, ``execute``, ``observe``), then restores them, so a
plain reimpl backend in the same process is unaffected. Backends are called
one after another in one thread, which is what makes the swap safe.

Use a mutant as a backend spec, ``conformance.testing.mutants:<name>``, e.g.
``python -m conformance run --backend conformance.testing.mutants:reverse_statement_order
--backend pydrake``, or build one with ``mutant_backend(name)``.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass

import numpy as np

from conformance.backends.reimpl_api import reimpl_api
from conformance.backends.scene_graph import SceneGraphBackend
from conformance.protocol import Command, Observation, Result
from reimpl.geometry.collision_filter import (
    BoolMatrix,
    CollisionFilter,
    ResolvedStatement,
    Resolver,
    Slots,
)
from reimpl.geometry.collision_filter_declaration import (
    CollisionFilterDeclaration,
    Statement,
    StatementOp,
)
from reimpl.geometry.collision_filter_manager import CollisionFilterManager
from reimpl.geometry.errors import GeometryStateError
from reimpl.geometry.geometry_roles import Role
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.geometry_state import WORLD_FRAME_ID, GeometryState, _Geometry
from reimpl.geometry.identifier import FilterId, GeometryId
from reimpl.geometry.scene_graph import SceneGraph
from reimpl.systems.framework import Context

__all__ = ["MUTANTS", "Mutant", "MutantBackend", "Patch", "mutant_backend"]

#: One attribute swap: (target class or module, attribute name, replacement).
Patch = tuple[object, str, object]

_MISSING = object()


@contextmanager
def _swapped(patches: Sequence[Patch]) -> Iterator[None]:
    """Sets each attribute for the duration of the block, then restores the original."""

    def restore(target: object, name: str, original: object) -> None:
        if original is _MISSING:
            delattr(target, name)
        else:
            setattr(target, name, original)

    with ExitStack() as stack:
        for target, name, replacement in patches:
            stack.callback(restore, target, name, vars(target).get(name, _MISSING))
            setattr(target, name, replacement)
        yield


@dataclass(frozen=True)
class Mutant:
    """One injected bug: its name, what is wrong, and the swaps that inject it.

    ``patches`` is called once per backend, so state a bug needs (what it
    remembers between calls) lives in that backend's closures.
    """

    name: str
    bug: str
    patches: Callable[[], list[Patch]]


class MutantBackend(SceneGraphBackend):
    """The reimpl backend, with ``mutant``'s patches in force during its own calls."""

    def __init__(self, mutant: Mutant) -> None:
        self.mutant = mutant
        self._patches = mutant.patches()
        super().__init__(reimpl_api())  # Calls reset(), which needs the patches.
        self.name = f"mutant:{mutant.name}"

    def reset(self) -> None:
        with _swapped(self._patches):
            super().reset()

    def execute(self, command: Command) -> Result:
        with _swapped(self._patches):
            return super().execute(command)

    def observe(self) -> Observation:
        with _swapped(self._patches):
            return super().observe()


# ------------------------------------------------------------------ helpers
def _names_frames(statement: Statement) -> bool:
    return bool(statement.set_A.frame_ids() or statement.set_B.frame_ids())


def _filtered_set(
    geometry_set: GeometrySet, keep_geometry: Callable[[GeometryId], bool], keep_world: bool
) -> GeometrySet:
    out = GeometrySet()
    out.Add(
        geometry_ids=[g for g in geometry_set.geometry_ids() if keep_geometry(g)],
        frame_ids=[f for f in geometry_set.frame_ids() if keep_world or f != WORLD_FRAME_ID],
    )
    return out


def _partners(matrix: BoolMatrix, cf: CollisionFilter, slot: int) -> list[GeometryId]:
    """The registered geometries paired with ``slot`` in ``matrix``."""
    return [cf._id_at[s] for s in np.flatnonzero(matrix[slot]) if s != slot and cf._registered[s]]


# ------------------------------------------------------------------ mutants
def _allow_clears_invariants() -> list[Patch]:
    original = CollisionFilter._apply_to

    def _apply_to(
        self: CollisionFilter,
        target: BoolMatrix,
        statements: Sequence[Statement],
        resolve: Resolver,
    ) -> tuple[ResolvedStatement, ...]:
        resolved = original(self, target, statements, resolve)
        if target is not self._invariant:
            for item in resolved:
                if not item.op.filters:
                    a, b = item.slots_A, item.slots_B
                    self._invariant[np.ix_(a, b)] = False
                    self._invariant[np.ix_(b, a)] = False
        return resolved

    return [(CollisionFilter, "_apply_to", _apply_to)]


def _allow_between_clears_within() -> list[Patch]:
    original = CollisionFilter._resolve

    def _resolve(
        self: CollisionFilter, statement: Statement, resolve: Resolver
    ) -> ResolvedStatement:
        item = original(self, statement, resolve)
        if item.op is not StatementOp.kAllowBetween:
            return item
        both = np.union1d(item.slots_A, item.slots_B)
        return ResolvedStatement(item.op, both, both)

    return [(CollisionFilter, "_resolve", _resolve)]


def _reverse_statement_order() -> list[Patch]:
    original = CollisionFilterDeclaration.statements

    def statements(self: CollisionFilterDeclaration) -> tuple[Statement, ...]:
        return original(self)[::-1]

    return [(CollisionFilterDeclaration, "statements", statements)]


def _lazy_frame_resolution() -> list[Patch]:
    original_apply = CollisionFilterManager.Apply
    original_assign = GeometryState._assign_proximity
    recorded: weakref.WeakKeyDictionary[GeometryState, list[Statement]] = (
        weakref.WeakKeyDictionary()
    )

    def Apply(self: CollisionFilterManager, declaration: CollisionFilterDeclaration) -> None:
        original_apply(self, declaration)
        named = [s for s in declaration.statements() if _names_frames(s)]
        recorded.setdefault(self._state, []).extend(named)

    def _assign_proximity(self: GeometryState, geometry: _Geometry) -> None:
        original_assign(self, geometry)
        statements = recorded.get(self)
        if statements and not self.collision_filter.has_transient_history():
            live = set(self.geometry_ids())

            def resolve(geometry_set: GeometrySet) -> list[GeometryId]:
                return self.collect_ids(_filtered_set(geometry_set, live.__contains__, True))

            self.collision_filter.apply(statements, resolve)

    return [
        (CollisionFilterManager, "Apply", Apply),
        (GeometryState, "_assign_proximity", _assign_proximity),
    ]


def _remove_declaration_no_replay() -> list[Patch]:
    original = CollisionFilter._rederive

    def _rederive(self: CollisionFilter, slots: Slots) -> None:
        history, self._history = self._history, []
        try:
            original(self, slots)
        finally:
            self._history = history

    return [(CollisionFilter, "_rederive", _rederive)]


def _context_managers_write_model() -> list[Patch]:
    def _context_manager(self: SceneGraph, context: Context) -> CollisionFilterManager:
        self._state_of(context)
        return self._model_manager()

    return [(SceneGraph, "_context_manager", _context_manager)]


def _non_proximity_ids_raise() -> list[Patch]:
    original = GeometryState.collect_ids

    def collect_ids(self: GeometryState, geometry_set: GeometrySet) -> list[GeometryId]:
        ids = original(self, geometry_set)
        for geometry_id in geometry_set.geometry_ids():
            if not self.has_role(geometry_id, Role.kProximity):
                raise GeometryStateError(
                    f"Geometry set includes geometry {geometry_id.get_value()}, "
                    "which has no proximity role"
                )
        return ids

    return [(GeometryState, "collect_ids", collect_ids)]


def _apply_during_history_allowed() -> list[Patch]:
    original = CollisionFilter.apply

    def apply(
        self: CollisionFilter,
        statements: Sequence[Statement],
        resolve: Resolver,
        *,
        is_invariant: bool = False,
    ) -> None:
        if is_invariant:
            original(self, statements, resolve, is_invariant=True)
            return
        history, self._history = self._history, []
        try:
            original(self, statements, resolve)
        finally:
            self._history = history

    return [(CollisionFilter, "apply", apply)]


def _role_reassign_keeps_filters() -> list[Patch]:
    original_add = CollisionFilter.add_geometry
    original_remove = CollisionFilter.remove_geometry
    # Per filter: a removed geometry's partners in (base, composite).
    memory: weakref.WeakKeyDictionary[
        CollisionFilter, dict[GeometryId, tuple[list[GeometryId], list[GeometryId]]]
    ] = weakref.WeakKeyDictionary()

    def remove_geometry(self: CollisionFilter, geometry_id: GeometryId) -> None:
        slot = self._slot_of[geometry_id]
        partners = (_partners(self._base, self, slot), _partners(self._composite, self, slot))
        memory.setdefault(self, {})[geometry_id] = partners
        original_remove(self, geometry_id)

    def add_geometry(self: CollisionFilter, geometry_id: GeometryId) -> None:
        original_add(self, geometry_id)
        remembered = memory.get(self, {}).pop(geometry_id, None)
        if remembered is None:
            return
        slot = self._slot_of[geometry_id]
        for matrix, partners in zip((self._base, self._composite), remembered, strict=True):
            for other in (self._slot_of[p] for p in partners if p in self._slot_of):
                matrix[slot, other] = matrix[other, slot] = True

    return [
        (CollisionFilter, "add_geometry", add_geometry),
        (CollisionFilter, "remove_geometry", remove_geometry),
    ]


def _stale_has_transient_history() -> list[Patch]:
    original = CollisionFilter.apply_transient
    ever: weakref.WeakSet[CollisionFilter] = weakref.WeakSet()

    def apply_transient(
        self: CollisionFilter, statements: Sequence[Statement], resolve: Resolver
    ) -> FilterId:
        filter_id = original(self, statements, resolve)
        ever.add(self)
        return filter_id

    def has_transient_history(self: CollisionFilter) -> bool:
        return bool(self._history) or self in ever

    return [
        (CollisionFilter, "apply_transient", apply_transient),
        (CollisionFilter, "has_transient_history", has_transient_history),
    ]


def _world_frame_resolves_nothing() -> list[Patch]:
    # Only declarations applied through a manager are affected: the invariant
    # statements GeometryState writes for anchored geometry still see the world.
    def world_blind(state: GeometryState) -> Callable[[GeometrySet], Iterable[GeometryId]]:
        def resolve(geometry_set: GeometrySet) -> list[GeometryId]:
            return state.collect_ids(_filtered_set(geometry_set, lambda _: True, False))

        return resolve

    def Apply(self: CollisionFilterManager, declaration: CollisionFilterDeclaration) -> None:
        state = self._state
        state.collision_filter.apply(declaration.statements(), world_blind(state))

    def ApplyTransient(
        self: CollisionFilterManager, declaration: CollisionFilterDeclaration
    ) -> FilterId:
        state = self._state
        return state.collision_filter.apply_transient(declaration.statements(), world_blind(state))

    return [
        (CollisionFilterManager, "Apply", Apply),
        (CollisionFilterManager, "ApplyTransient", ApplyTransient),
    ]


def _no_same_frame_invariant() -> list[Patch]:
    def _assign_proximity(self: GeometryState, geometry: _Geometry) -> None:
        self.collision_filter.add_geometry(geometry.id)
        # An empty invariant Apply keeps the transient-history error, and writes nothing.
        self.collision_filter.apply([], self.collect_ids, is_invariant=True)

    return [(GeometryState, "_assign_proximity", _assign_proximity)]


MUTANTS: dict[str, Mutant] = {
    mutant.name: mutant
    for mutant in (
        Mutant(
            "allow_clears_invariants",
            "AllowWithin/AllowBetween also clear invariant pairs (same frame, anchored-anchored).",
            _allow_clears_invariants,
        ),
        Mutant(
            "allow_between_clears_within",
            "AllowBetween(A, B) also allows the pairs within A and within B.",
            _allow_between_clears_within,
        ),
        Mutant(
            "reverse_statement_order",
            "A declaration's statements are applied in reverse order.",
            _reverse_statement_order,
        ),
        Mutant(
            "lazy_frame_resolution",
            "Persistent declarations naming a frame also cover geometry that gets the "
            "proximity role on that frame later.",
            _lazy_frame_resolution,
        ),
        Mutant(
            "remove_declaration_no_replay",
            "RemoveDeclaration re-derives C from the persistent base without replaying the "
            "remaining transient declarations.",
            _remove_declaration_no_replay,
        ),
        Mutant(
            "context_managers_write_model",
            "collision_filter_manager(context=...) edits the model instead of the context.",
            _context_managers_write_model,
        ),
        Mutant(
            "non_proximity_ids_raise",
            "A GeometrySet naming a registered geometry without the proximity role raises "
            "instead of ignoring it.",
            _non_proximity_ids_raise,
        ),
        Mutant(
            "apply_during_history_allowed",
            "Persistent Apply succeeds while transient history is active.",
            _apply_during_history_allowed,
        ),
        Mutant(
            "role_reassign_keeps_filters",
            "Removing a geometry's proximity role and assigning it again restores its old "
            "filtered pairs.",
            _role_reassign_keeps_filters,
        ),
        Mutant(
            "stale_has_transient_history",
            "has_transient_history() stays True after the last transient declaration is removed.",
            _stale_has_transient_history,
        ),
        Mutant(
            "world_frame_resolves_nothing",
            "The world frame in a GeometrySet resolves to no geometry instead of every "
            "anchored proximity geometry.",
            _world_frame_resolves_nothing,
        ),
        Mutant(
            "no_same_frame_invariant",
            "A geometry getting the proximity role is not invariantly excluded from the other "
            "proximity geometries on its frame.",
            _no_same_frame_invariant,
        ),
    )
}


def mutant_backend(name: str) -> MutantBackend:
    """A fresh backend for the mutant ``name`` (a key of MUTANTS)."""
    return MutantBackend(MUTANTS[name])


def __getattr__(name: str) -> Callable[[], MutantBackend]:
    """``conformance.testing.mutants:<name>`` as a backend spec: a zero-argument factory."""
    if name in MUTANTS:
        return lambda: mutant_backend(name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
