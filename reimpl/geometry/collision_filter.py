"""The pair state behind C: persistent base, transient history, invariants.

Drake counterpart: drake/geometry/proximity/collision_filter.h (internal).

The filter knows only proximity geometries. For those, with G their set, C is

    C = (Gₐ × Gₐ) − I − V − U

where Gₐ are the active geometries (all of them before Drake 1.55), I the self
pairs, V the invariant pairs (same frame, anchored × anchored: written by
GeometryState with ``is_invariant=True``) and U the user-filtered pairs.

U is the persistent base replayed with the transient history:

    U = replay(base, history),  history = [(FilterId, resolved statements), ...]

Representation. Each geometry owns a slot; ``_base``, ``_composite`` (U) and
``_invariant`` (V) are symmetric boolean matrices over slots, so a statement on
sets A and B is one slice assignment on A × B and B × A. Statements are stored
*resolved* (slot arrays), as Drake ≥ 1.52 stores them: a declaration is never
re-resolved on replay, so geometry added later is never covered by it.

Cost. ApplyTransient is O(Σ|A|·|B|). RemoveDeclaration re-derives only the rows
of the geometries the removed declaration mentions (R): O(|R|·n + replay of the
remaining statements restricted to R), never a full O(n²) rebuild.
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from reimpl.geometry.collision_filter_declaration import Pairing, Statement, StatementOp
from reimpl.geometry.errors import TransientHistoryActiveError
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.identifier import FilterId, GeometryId

__all__ = ["CollisionFilter", "PairRelationship", "ResolvedStatement"]

Slots = npt.NDArray[np.intp]
BoolMatrix = npt.NDArray[np.bool_]

_PERSISTENT_WITH_HISTORY = (
    "You cannot attempt to modify the persistent collision filter configuration when there "
    "are active, transient filter declarations"
)


class PairRelationship(enum.Enum):
    """What the filter says about a pair (a, b) of proximity geometries.

    One table decides it, read top to bottom; the first row that holds wins:

    ========================  ===================
    a == b                    SELF (never in C)
    a or b inactive           INACTIVE
    (a, b) ∈ V                INVARIANT
    (a, b) ∈ U                FILTERED
    otherwise                 UNFILTERED (in C)
    ========================  ===================
    """

    SELF = "self"
    INACTIVE = "inactive"
    INVARIANT = "invariant"
    FILTERED = "filtered"
    UNFILTERED = "unfiltered"


@dataclass(frozen=True)
class ResolvedStatement:
    """A statement whose sets have been resolved to slots at application time."""

    op: StatementOp
    slots_A: Slots
    slots_B: Slots

    def mentioned(self) -> Slots:
        return np.union1d(self.slots_A, self.slots_B)

    def without(self, slot: int) -> ResolvedStatement:
        return ResolvedStatement(
            self.op,
            self.slots_A[self.slots_A != slot],
            self.slots_B[self.slots_B != slot],
        )


def _write(matrix: BoolMatrix, statement: ResolvedStatement) -> None:
    """Writes the statement's value on its pairs: P = A × B ∪ B × A (or S × S).

    The diagonal may be written too; self pairs are never read from a matrix.
    """
    a, b, value = statement.slots_A, statement.slots_B, statement.op.filters
    matrix[np.ix_(a, b)] = value
    matrix[np.ix_(b, a)] = value


def _write_rows(rows: BoolMatrix, row_of: Slots, statement: ResolvedStatement) -> None:
    """``_write`` restricted to the slots that own a row (row_of[slot] ≥ 0)."""
    a, b, value = statement.slots_A, statement.slots_B, statement.op.filters
    for own, other in ((a, b), (b, a)):
        mine = row_of[own]
        mine = mine[mine >= 0]
        if mine.size and other.size:
            rows[np.ix_(mine, other)] = value


@dataclass(frozen=True)
class _Delta:
    filter_id: FilterId
    statements: tuple[ResolvedStatement, ...]


Resolver = Callable[[GeometrySet], Iterable[GeometryId]]


class CollisionFilter:
    """Pair state for one GeometryState (the model's or one context's)."""

    _INITIAL_CAPACITY = 16

    def __init__(self) -> None:
        cap = self._INITIAL_CAPACITY
        self._slot_of: dict[GeometryId, int] = {}
        self._id_at: npt.NDArray[np.object_] = np.full(cap, None, dtype=object)
        self._value_at: npt.NDArray[np.int64] = np.zeros(cap, dtype=np.int64)
        self._free: list[int] = list(range(cap - 1, -1, -1))
        self._registered: npt.NDArray[np.bool_] = np.zeros(cap, dtype=bool)
        self._inactive: npt.NDArray[np.bool_] = np.zeros(cap, dtype=bool)
        self._base: BoolMatrix = np.zeros((cap, cap), dtype=bool)
        self._composite: BoolMatrix = np.zeros((cap, cap), dtype=bool)
        self._invariant: BoolMatrix = np.zeros((cap, cap), dtype=bool)
        self._history: list[_Delta] = []
        # Slots whose rows in C may hold leftovers of a failed, partial apply.
        self._leftover: set[int] = set()

    # ----------------------------------------------------------------- copies
    def copy(self) -> CollisionFilter:
        """A deep copy: base, history (same FilterIds), invariants, inactive set."""
        other = object.__new__(CollisionFilter)
        other._slot_of = dict(self._slot_of)
        other._id_at = self._id_at.copy()
        other._value_at = self._value_at.copy()
        other._free = list(self._free)
        other._registered = self._registered.copy()
        other._inactive = self._inactive.copy()
        other._base = self._base.copy()
        other._composite = self._composite.copy()
        other._invariant = self._invariant.copy()
        other._history = list(self._history)  # deltas are immutable
        other._leftover = set(self._leftover)
        return other

    # ------------------------------------------------------------- geometries
    def has_geometry(self, geometry_id: GeometryId) -> bool:
        return geometry_id in self._slot_of

    def add_geometry(self, geometry_id: GeometryId) -> None:
        """Registers g, unfiltered against everything and active.

        Declarations made earlier, transient ones included, never cover g.
        """
        if geometry_id in self._slot_of:
            raise AssertionError(f"geometry {geometry_id.get_value()} is already registered")
        if not self._free:
            self._grow()
        slot = self._free.pop()
        self._slot_of[geometry_id] = slot
        self._id_at[slot] = geometry_id
        self._value_at[slot] = geometry_id.get_value()
        self._registered[slot] = True

    def remove_geometry(self, geometry_id: GeometryId) -> None:
        """Forgets g: every pair with g leaves the base, the history and V.

        Other pairs keep their state: a pair's state depends only on the
        statements that mention both of its geometries.
        """
        slot = self._slot_of.pop(geometry_id)
        for matrix in (self._base, self._composite, self._invariant):
            matrix[slot, :] = False
            matrix[:, slot] = False
        self._registered[slot] = False
        self._inactive[slot] = False
        self._id_at[slot] = None
        self._history = [
            _Delta(d.filter_id, tuple(s.without(slot) for s in d.statements)) for d in self._history
        ]
        self._free.append(slot)

    def _grow(self) -> None:
        old = len(self._registered)
        new = old * 2

        def grow_vector(v: npt.NDArray[np.generic], fill: object) -> npt.NDArray[np.generic]:
            out = np.full(new, fill, dtype=v.dtype)
            out[:old] = v
            return out

        def grow_matrix(m: BoolMatrix) -> BoolMatrix:
            out = np.zeros((new, new), dtype=bool)
            out[:old, :old] = m
            return out

        self._id_at = grow_vector(self._id_at, None)  # type: ignore[assignment]
        self._value_at = grow_vector(self._value_at, 0)  # type: ignore[assignment]
        self._registered = grow_vector(self._registered, False)  # type: ignore[assignment]
        self._inactive = grow_vector(self._inactive, False)  # type: ignore[assignment]
        self._base = grow_matrix(self._base)
        self._composite = grow_matrix(self._composite)
        self._invariant = grow_matrix(self._invariant)
        self._free.extend(range(new - 1, old - 1, -1))

    def _slots(self, ids: Iterable[GeometryId]) -> Slots:
        return np.fromiter((self._slot_of[g] for g in ids), dtype=np.intp)

    def _resolve(self, statement: Statement, resolve: Resolver) -> ResolvedStatement:
        slots_A = self._slots(resolve(statement.set_A))
        if statement.op.pairing is Pairing.WITHIN:
            return ResolvedStatement(statement.op, slots_A, slots_A)
        return ResolvedStatement(statement.op, slots_A, self._slots(resolve(statement.set_B)))

    # ------------------------------------------------------------ declarations
    def apply(
        self,
        statements: Sequence[Statement],
        resolve: Resolver,
        *,
        is_invariant: bool = False,
    ) -> None:
        """Applies statements, in order, to the persistent base (and so to C).

        Each statement is resolved, then written to C; the base is written only
        once every statement has resolved.

        Raises:
            TransientHistoryActiveError: if any transient declaration is active.
            UnknownGeometryError, UnknownFrameError: from ``resolve``. N.B. As in
                Drake ≤ 1.51, statements before the bad one stay in C (not in the
                base) until C is next re-derived from the base by RemoveDeclaration.
        """
        if self._history:
            raise TransientHistoryActiveError(_PERSISTENT_WITH_HISTORY)
        if is_invariant and any(not s.op.filters for s in statements):
            raise AssertionError("an Allow statement cannot be invariant")
        target = self._invariant if is_invariant else self._composite
        resolved = self._apply_to(target, statements, resolve)
        if not is_invariant:
            for item in resolved:
                _write(self._base, item)

    def apply_transient(self, statements: Sequence[Statement], resolve: Resolver) -> FilterId:
        """Appends a declaration to the history; C ← C then the declaration.

        Returns the new declaration's FilterId. If resolution fails part way,
        no history entry is made and the statements before the failure stay in
        C until it is next re-derived (Drake ≤ 1.51): a successful
        ApplyTransient writes onto C as it is, only RemoveDeclaration (or
        removing a geometry under history) re-derives C from the base.
        """
        resolved = self._apply_to(self._composite, statements, resolve)
        filter_id = FilterId.get_new_id()
        self._history.append(_Delta(filter_id, resolved))
        return filter_id

    def _apply_to(
        self, target: BoolMatrix, statements: Sequence[Statement], resolve: Resolver
    ) -> tuple[ResolvedStatement, ...]:
        """Resolves and writes each statement in turn; remembers partial work on failure."""
        resolved: list[ResolvedStatement] = []
        try:
            for statement in statements:
                item = self._resolve(statement, resolve)
                _write(target, item)
                resolved.append(item)
        except Exception:
            if target is self._composite:
                for item in resolved:
                    self._leftover.update(item.mentioned().tolist())
            raise
        return tuple(resolved)

    def remove_declaration(self, filter_id: FilterId) -> bool:
        """Removes a transient declaration; C ← replay(base, remaining history).

        Returns True iff ``filter_id`` was active.
        """
        index = next((i for i, d in enumerate(self._history) if d.filter_id == filter_id), None)
        if index is None:
            return False
        removed = self._history.pop(index)
        mentioned = [s.mentioned() for s in removed.statements]
        self._rederive(np.concatenate(mentioned) if mentioned else np.empty(0, np.intp))
        return True

    def _rederive(self, slots: Slots) -> None:
        """C ← replay(base, history) on the rows of ``slots`` and of any leftovers.

        Only a pair whose two geometries a statement mentions can change, so
        re-deriving the rows R of the mentioned slots suffices: rows_R ← base_R,
        then every live statement in order, restricted to R. Cost
        O(|R|·n + replay), never a full O(n²) rebuild.
        """
        R = np.unique(np.concatenate([slots, np.fromiter(self._leftover, np.intp)]))
        self._leftover.clear()
        if R.size == 0:
            return
        row_of = np.full(len(self._registered), -1, dtype=np.intp)
        row_of[R] = np.arange(R.size)
        rows = self._base[R, :].copy()
        for delta in self._history:
            for statement in delta.statements:
                _write_rows(rows, row_of, statement)
        self._composite[R, :] = rows
        self._composite[:, R] = rows.T

    def is_active(self, filter_id: FilterId) -> bool:
        return any(d.filter_id == filter_id for d in self._history)

    def has_transient_history(self) -> bool:
        return bool(self._history)

    def set_active(self, ids: Iterable[GeometryId], active: bool) -> None:
        """Edits the inactive set (Drake ≥ 1.55); allowed with transient history."""
        slots = self._slots(ids)
        self._inactive[slots] = not active

    # ---------------------------------------------------------------- queries
    def relationship(self, a: GeometryId, b: GeometryId) -> PairRelationship:
        """Classifies (a, b) by the table in ``PairRelationship``."""
        sa, sb = self._slot_of[a], self._slot_of[b]
        if sa == sb:
            return PairRelationship.SELF
        if self._inactive[sa] or self._inactive[sb]:
            return PairRelationship.INACTIVE
        if self._invariant[sa, sb]:
            return PairRelationship.INVARIANT
        if self._composite[sa, sb]:
            return PairRelationship.FILTERED
        return PairRelationship.UNFILTERED

    def can_collide_with(self, a: GeometryId, b: GeometryId) -> bool:
        return self.relationship(a, b) is PairRelationship.UNFILTERED

    def candidates(self) -> set[tuple[GeometryId, GeometryId]]:
        """C as pairs (a, b) with a.get_value() < b.get_value()."""
        live = np.flatnonzero(self._registered & ~self._inactive)
        live = live[np.argsort(self._value_at[live], kind="stable")]
        if live.size < 2:
            return set()
        blocked = (self._composite | self._invariant)[np.ix_(live, live)]
        i, j = np.triu_indices(live.size, 1)
        keep = ~blocked[i, j]
        ids = self._id_at[live]
        return set(zip(ids[i[keep]].tolist(), ids[j[keep]].tolist(), strict=True))
