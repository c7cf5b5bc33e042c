"""The pair state behind C: persistent base, transient history, invariants.

Drake counterpart: drake/geometry/proximity/collision_filter.h (internal).

The filter knows only proximity geometries. For those, with G their set, C is

    C = (Gₐ × Gₐ) − I − V − U

where Gₐ are the active geometries (all of them before Drake 1.55), I the self
pairs, V the invariant pairs (same frame, anchored × anchored: written by
GeometryState with ``is_invariant=True``) and U the user-filtered pairs.

U is the persistent base replayed with the transient history:

    U = replay(base, history),  history = [(FilterId, resolved statements), ...]

Representation: bit rows. Each geometry owns a slot (an index, reused after
the geometry leaves). V, the base and U are each a ``PairBits``: one Python
int per slot, bit b of row a set iff (a, b) is in the relation. A statement
on sets A and B sets (Exclude) or clears (Allow) the bits A × B and B × A:
row a ← row a | mask(B) for each a ∈ A, and row b ← row b | mask(A) for each
b ∈ B. Statements are stored *resolved* (slots and masks), as Drake ≥ 1.52
stores them: a declaration is never re-resolved on replay, so geometry added
later is never covered by it.

Why bit rows. Drake 1.51's dense table (a map entry per pair) blew up between
28k and 43k geometries (drake#24246); a store of filtered pairs (Drake ≥ 1.52)
is as large as the filtered set, which is n²/2 pairs when a scene welds
everything to the world (MultibodyPlant's ExcludeWithin of a welded subgraph).
A bit row holds any mix of filtered and unfiltered pairs in n/8 bytes, so the
worst case is n²/8 bytes per relation (312 MB at n = 50,000), and rows are
immutable ints: copying a relation copies n references, and the copies share
every row until one of them writes it. So

- without transient history, U's row of a slot *is* the base's row (the same
  object) unless a failed Apply left that row different (``_failed_apply``);
- a context shares every row with the model until it writes one.

Cost model (n slots; a row write costs O(w), w = ⌈n/64⌉ machine words, at
memcpy speed: about 1 µs at n = 50,000):

============================  ==============================================
statement on A, B             O(|A| + |B|) row writes + O(|A| + |B|) for the
                              masks: the pairs it touches, |A|·|B|, are set
                              a row at a time, never O(n²)
ApplyTransient                its statements
RemoveDeclaration             re-derives the rows R its statements mention:
                              O(|R|) + the live statements' writes to R
CanCollideWith                O(w)
GetCollisionCandidates        O(n·w + |C|)
copy (a context)              O(n) references; rows shared (copy-on-write)
memory                        ≤ 3 · n · n/8 bytes; V's rows are only as wide
                              as a geometry's highest same-frame slot, and U
                              shares its rows with the base
============================  ==============================================
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import NamedTuple, cast

import numpy as np
import numpy.typing as npt

from reimpl._release import release
from reimpl.common._drake_demand import demand_failure
from reimpl.geometry._pair_bits import PairBits, mask_of
from reimpl.geometry.collision_filter_declaration import Pairing, Statement, StatementOp
from reimpl.geometry.errors import TransientHistoryActiveError, UnregisteredFilterGeometryError
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.identifier import FilterId, GeometryId

__all__ = ["CollisionFilter", "PairRelationship", "ResolvedStatement"]

#: Up to this many slots, GetCollisionCandidates reads the rows bit by bit in
#: Python; above, a block of rows at a time with numpy (fewer calls either way).
_ROWS_READ_BY_BIT = 256

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


class ResolvedStatement(NamedTuple):
    """A statement whose sets have been resolved to slots at application time.

    For a *Within statement ``slots_B is slots_A``: P = S × S.
    """

    op: StatementOp
    slots_A: tuple[int, ...]
    slots_B: tuple[int, ...]
    mask_A: int
    mask_B: int

    @staticmethod
    def of(
        op: StatementOp, slots_A: tuple[int, ...], slots_B: tuple[int, ...] | None
    ) -> ResolvedStatement:
        """``slots_B`` None means a *Within statement (B = A)."""
        mask_A = mask_of(slots_A)
        if slots_B is None:
            return ResolvedStatement(op, slots_A, slots_A, mask_A, mask_A)
        return ResolvedStatement(op, slots_A, slots_B, mask_A, mask_of(slots_B))

    def mentioned(self) -> set[int]:
        return {*self.slots_A, *self.slots_B}

    def write(self, relation: PairBits, only: frozenset[int] | None = None) -> None:
        """Writes the statement's value on P = A × B ∪ B × A (or S × S)."""
        filters = self.op.filters
        relation.write(self.slots_A, self.mask_B, filters, only)
        if self.slots_B is not self.slots_A:
            relation.write(self.slots_B, self.mask_A, filters, only)

    def without(self, slot: int) -> ResolvedStatement:
        within = self.slots_B is self.slots_A
        slots_A = tuple(s for s in self.slots_A if s != slot)
        return ResolvedStatement.of(
            self.op, slots_A, None if within else tuple(s for s in self.slots_B if s != slot)
        )


@dataclass(frozen=True)
class _Delta:
    filter_id: FilterId
    statements: tuple[ResolvedStatement, ...]


Resolver = Callable[[GeometrySet], Sequence[GeometryId]]


class CollisionFilter:
    """Pair state for one GeometryState (the model's or one context's)."""

    def __init__(self) -> None:
        self._slot_of: dict[GeometryId, int] = {}
        self._id_at: list[GeometryId | None] = []
        self._registered: list[bool] = []
        self._inactive: list[bool] = []
        self._free: list[int] = []
        self._invariant = PairBits()  # V
        self._base = PairBits()  # the persistent part of U
        self._filtered = PairBits()  # U = replay(base, history), what C reads
        self._history: list[_Delta] = []
        self._active: set[FilterId] = set()  # the history's FilterIds
        # Slots whose rows in U may differ from the base's after a failed apply.
        self._leftover: set[int] = set()
        # Geometries given a slot though their proximity engine entry failed.
        self._unengined: set[GeometryId] = set()

    # ----------------------------------------------------------------- copies
    def copy(self) -> CollisionFilter:
        """A copy: base, history (same FilterIds), invariants, inactive set.

        O(n) references: the rows are shared until one of the copies writes them.
        """
        other = object.__new__(CollisionFilter)
        other._slot_of = dict(self._slot_of)
        other._id_at = list(self._id_at)
        other._registered = list(self._registered)
        other._inactive = list(self._inactive)
        other._free = list(self._free)
        other._invariant = self._invariant.copy()
        other._base = self._base.copy()
        other._filtered = self._filtered.copy()
        other._history = list(self._history)  # deltas are immutable
        other._active = set(self._active)
        other._leftover = set(self._leftover)
        other._unengined = set(self._unengined)
        return other

    # ------------------------------------------------------------- geometries
    def has_geometry(self, geometry_id: GeometryId) -> bool:
        return geometry_id in self._slot_of

    def add_geometry(self, geometry_id: GeometryId, *, engined: bool = True) -> None:
        """Registers g, unfiltered against everything and active.

        Declarations made earlier, transient ones included, never cover g.
        ``engined=False``: g's proximity engine entry failed. Drake ≥ 1.52 keeps
        filtered pairs by id, so g is unfiltered against everything all the same
        (unengined-geometry-unfiltered-since-1.52); since 1.57 a declaration that
        names g raises (unengined-declaration-error-since-1.57).
        """
        if geometry_id in self._slot_of:
            raise AssertionError(f"geometry {geometry_id.get_value()} is already registered")
        if self._free:
            slot = self._free.pop()
        else:
            slot = len(self._id_at)
            self._id_at.append(None)
            self._registered.append(False)
            self._inactive.append(False)
            for relation in (self._invariant, self._base, self._filtered):
                relation.add_slot()
        self._slot_of[geometry_id] = slot
        self._id_at[slot] = geometry_id
        self._registered[slot] = True
        if not engined:
            self._unengined.add(geometry_id)

    def remove_geometry(self, geometry_id: GeometryId) -> None:
        """Forgets g: every pair with g leaves the base, the history and V.

        Other pairs keep their state: a pair's state depends only on the
        statements that mention both of its geometries.
        """
        slot = self._slot_of.pop(geometry_id)
        self._unengined.discard(geometry_id)
        for relation in (self._base, self._filtered, self._invariant):
            relation.clear_slot(slot)
        self._registered[slot] = False
        self._inactive[slot] = False
        self._id_at[slot] = None
        self._history = [
            _Delta(d.filter_id, tuple(s.without(slot) for s in d.statements)) for d in self._history
        ]
        self._free.append(slot)

    def _slots(self, ids: Iterable[GeometryId]) -> tuple[int, ...]:
        return tuple(map(self._slot_of.__getitem__, ids))

    def _resolve(self, statement: Statement, resolve: Resolver) -> ResolvedStatement:
        ids_A = resolve(statement.set_A)
        ids_B = None if statement.op.pairing is Pairing.WITHIN else resolve(statement.set_B)
        self._refuse_unengined(ids_A, ids_B or ())
        try:
            slots_B = None if ids_B is None else self._slots(ids_B)
            return ResolvedStatement.of(statement.op, self._slots(ids_A), slots_B)
        except KeyError:  # a proximity geometry this filter never got (GeometryState)
            return self._unregistered(statement, ids_A, ids_A if ids_B is None else ids_B)

    def _refuse_unengined(self, ids_A: Sequence[GeometryId], ids_B: Sequence[GeometryId]) -> None:
        """Since 1.57 a declaration naming an unengined geometry raises (before any write)."""
        if not self._unengined or not release.has("unengined-declaration-error-since-1.57"):
            return
        for geometry_id in (*ids_A, *ids_B):
            if geometry_id in self._unengined:
                raise UnregisteredFilterGeometryError(
                    f"Collision filter declaration references geometry id "
                    f"{geometry_id.get_value()} which has not been registered with this "
                    "filter system."
                )

    def _unregistered(
        self, statement: Statement, ids_A: Sequence[GeometryId], ids_B: Sequence[GeometryId]
    ) -> ResolvedStatement:
        """Drake demands that every pair it writes has both ids registered; with no pair to
        write (one side empty), the statement does nothing. The demand's line and words by
        release: AddFilteredPair at line 184 up to 1.19, 185 since 1.20
        (filter-demand-line-since-1.20); RemoveFilteredPair at 197, but 198 in 1.20.0
        (filter-demand-remove-line-1.20); the condition with ``count(...) == 1`` up to 1.26
        (filter-demand-contains-since-1.27)."""
        if ids_A and ids_B:
            if statement.op.filters:
                line = 185 if release.has("filter-demand-line-since-1.20") else 184
                function = "AddFilteredPair"
            else:
                line = 198 if release.has("filter-demand-remove-line-1.20") else 197
                function = "RemoveFilteredPair"
            condition = (
                "filter_state.contains(id_A) && filter_state.contains(id_B)"
                if release.has("filter-demand-contains-since-1.27")
                else "filter_state.count(id_A) == 1 && filter_state.count(id_B) == 1"
            )
            raise demand_failure(
                "geometry/proximity/collision_filter.cc", line, function, condition
            )
        empty = None if statement.op.pairing is Pairing.WITHIN else ()
        return ResolvedStatement.of(statement.op, (), empty)

    def _resolve_all(
        self, statements: Sequence[Statement], resolve: Resolver
    ) -> tuple[list[ResolvedStatement], Exception | None]:
        """Resolves statements in order up to the first that fails, and that failure.

        Resolution reads the scene only, so resolving every statement before
        writing any is the same as Drake's resolve-then-write per statement.
        """
        resolved: list[ResolvedStatement] = []
        try:
            for statement in statements:
                resolved.append(self._resolve(statement, resolve))
        except Exception as error:
            return resolved, error
        return resolved, None

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
            UnknownGeometryError, UnknownFrameError: from ``resolve``; what the
                statements before the bad one leave is ``_failed_apply``'s.
        """
        if self._history:
            raise TransientHistoryActiveError(_PERSISTENT_WITH_HISTORY)
        if is_invariant and any(not s.op.filters for s in statements):
            raise AssertionError("an Allow statement cannot be invariant")
        resolved, error = self._resolve_all(statements, resolve)
        if is_invariant:
            for item in resolved:
                item.write(self._invariant)
        elif error is not None:
            self._failed_apply(resolved)
        else:
            self._write_base(resolved)
        if error is not None:
            raise error

    def _failed_apply(self, resolved: Sequence[ResolvedStatement]) -> None:
        """What a failing Apply leaves of the statements before the bad one, by release:

        - up to 1.51 (partial-apply-until-1.51): they are in C, not in the base,
          until C is next re-derived from the base (a successful RemoveDeclaration);
        - 1.52-1.56 (failed-apply-writes-base-1.52-1.56): they are in the base, not
          in C, until that re-derivation shows them;
        - since 1.57: nowhere.

        Either way U's rows of the slots they mention differ from the base's
        (``_leftover``) until the next re-derivation.
        """
        if release.has("partial-apply-until-1.51"):
            self._write_leftover(resolved)
        elif release.has("failed-apply-writes-base-1.52-1.56"):
            for item in resolved:
                item.write(self._base)
                self._leftover |= item.mentioned()

    def _write_base(self, resolved: Sequence[ResolvedStatement]) -> None:
        """Writes the base; U's rows follow it (no history: U = base off the leftovers).

        U's row of a mentioned slot becomes the base's row itself, unless a
        failed Apply left that row different: there the statements are
        written onto U's row as well.
        """
        mentioned: set[int] = set()
        for item in resolved:
            item.write(self._base)
            mentioned |= item.mentioned()
        leftover = frozenset(mentioned & self._leftover)
        base, filtered = self._base.rows, self._filtered.rows
        for slot in mentioned - leftover:
            filtered[slot] = base[slot]
        if leftover:
            for item in resolved:
                item.write(self._filtered, only=leftover)

    def _write_leftover(self, resolved: Sequence[ResolvedStatement]) -> None:
        """A failed apply: the statements before the failure are written to U only."""
        for item in resolved:
            item.write(self._filtered)
            self._leftover |= item.mentioned()

    def apply_transient(self, statements: Sequence[Statement], resolve: Resolver) -> FilterId:
        """Appends a declaration to the history; C ← C then the declaration.

        Returns the new declaration's FilterId. If resolution fails part way,
        no history entry is made. Up to 1.51 (partial-apply-until-1.51) the
        statements before the failure stay in C until it is next re-derived (a
        successful ApplyTransient writes onto C as it is, only
        RemoveDeclaration re-derives C from the base); since 1.52 C is unchanged.
        """
        resolved, error = self._resolve_all(statements, resolve)
        if error is not None:
            if release.has("partial-apply-until-1.51"):
                self._write_leftover(resolved)
            raise error
        for item in resolved:
            item.write(self._filtered)
        filter_id = FilterId.get_new_id()
        self._history.append(_Delta(filter_id, tuple(resolved)))
        self._active.add(filter_id)
        return filter_id

    def remove_declaration(self, filter_id: FilterId) -> bool:
        """Removes a transient declaration; C ← replay(base, remaining history).

        Returns True iff ``filter_id`` was active.
        """
        if filter_id not in self._active:
            return False
        self._active.remove(filter_id)
        index = next(i for i, d in enumerate(self._history) if d.filter_id == filter_id)
        removed = self._history.pop(index)
        mentioned: set[int] = set()
        for statement in removed.statements:
            mentioned |= statement.mentioned()
        self._rederive(mentioned)
        return True

    def _rederive(self, slots: set[int]) -> None:
        """U ← replay(base, history) on the rows of ``slots`` and of any leftovers.

        Only a pair whose two geometries a statement mentions can change, so
        re-deriving the rows R of the mentioned slots suffices: row r ← base
        row r, then every live statement in order, written to the rows of R
        only. The pairs (r, x) with x ∉ R keep their value, so the other rows
        stay as they are and U stays symmetric. Cost O(|R|) + the statements'
        writes to R, never a full O(n²) rebuild.
        """
        R = frozenset(slots | self._leftover)
        self._leftover.clear()
        base, filtered = self._base.rows, self._filtered.rows
        for slot in R:
            filtered[slot] = base[slot]
        for delta in self._history:
            for statement in delta.statements:
                statement.write(self._filtered, only=R)

    def is_active(self, filter_id: FilterId) -> bool:
        return filter_id in self._active

    def has_transient_history(self) -> bool:
        return bool(self._history)

    def set_active(self, ids: Iterable[GeometryId], active: bool) -> list[GeometryId]:
        """Edits the inactive set (Drake ≥ 1.55); allowed with transient history.

        Returns the ids whose status changed (Drake's ActiveStatusChange).
        """
        changed = []
        for geometry_id in ids:
            slot = self._slot_of[geometry_id]
            if self._inactive[slot] == active:
                self._inactive[slot] = not active
                changed.append(geometry_id)
        return changed

    # ---------------------------------------------------------------- queries
    def relationship(self, a: GeometryId, b: GeometryId) -> PairRelationship:
        """Classifies (a, b) by the table in ``PairRelationship``."""
        sa, sb = self._slot_of[a], self._slot_of[b]
        if sa == sb:
            return PairRelationship.SELF
        if self._inactive[sa] or self._inactive[sb]:
            return PairRelationship.INACTIVE
        if self._invariant.contains(sa, sb):
            return PairRelationship.INVARIANT
        if self._filtered.contains(sa, sb):
            return PairRelationship.FILTERED
        return PairRelationship.UNFILTERED

    def can_collide_with(self, a: GeometryId, b: GeometryId) -> bool:
        return self.relationship(a, b) is PairRelationship.UNFILTERED

    def candidates(self) -> set[tuple[GeometryId, GeometryId]]:
        """C as pairs (a, b) with a.get_value() < b.get_value().

        Row by row: the partners b > a of a live slot a are the live slots
        whose bits are clear in a's rows of V and U. O(n·w) plus O(|C|).
        """
        live = [r and not i for r, i in zip(self._registered, self._inactive, strict=True)]
        live_slots = [slot for slot, is_live in enumerate(live) if is_live]
        if len(live) > _ROWS_READ_BY_BIT:
            return self._candidates_by_block(np.array(live, dtype=bool))
        live_mask = mask_of(live_slots)
        ids = cast(list[GeometryId], self._id_at)  # a live slot holds an id
        value = [-1 if g is None else g.get_value() for g in self._id_at]  # ints compare faster
        invariant, filtered = self._invariant.rows, self._filtered.rows
        pairs: set[tuple[GeometryId, GeometryId]] = set()
        for a in live_slots:
            ga, va = ids[a], value[a]
            free = live_mask >> (a + 1) << (a + 1) & ~(invariant[a] | filtered[a])
            while free:
                lowest = free & -free
                free ^= lowest
                b = lowest.bit_length() - 1
                pairs.add((ga, ids[b]) if va < value[b] else (ids[b], ga))
        return pairs

    def _candidates_by_block(
        self, live: npt.NDArray[np.bool_]
    ) -> set[tuple[GeometryId, GeometryId]]:
        """``candidates`` for many slots: a block of rows at a time, unpacked by numpy.

        The rows V | U of a block are unpacked to booleans (about 4 MB a block);
        the pairs are read with array operations, not bit by bit.
        """
        n = len(self._id_at)
        ids = np.empty(n, dtype=object)
        ids[:] = self._id_at
        values = np.array([-1 if g is None else g.get_value() for g in self._id_at], np.int64)
        invariant, filtered = self._invariant.rows, self._filtered.rows
        width = (n + 7) >> 3
        rows_per_block = max(1, (4 << 20) // n)
        live_slots = np.flatnonzero(live)
        pairs: set[tuple[GeometryId, GeometryId]] = set()
        for start in range(0, live_slots.size, rows_per_block):
            block = live_slots[start : start + rows_per_block]
            packed = b"".join(
                (invariant[a] | filtered[a]).to_bytes(width, "little") for a in block.tolist()
            )
            blocked = np.unpackbits(
                np.frombuffer(packed, np.uint8).reshape(block.size, width),
                axis=1,
                count=n,
                bitorder="little",
            ).view(bool)
            free = live & ~blocked & (np.arange(n) > block[:, None])
            rows, b = np.nonzero(free)
            a = block[rows]
            a_first = values[a] < values[b]
            first, second = np.where(a_first, a, b), np.where(a_first, b, a)
            pairs.update(zip(ids[first].tolist(), ids[second].tolist(), strict=True))
        return pairs
