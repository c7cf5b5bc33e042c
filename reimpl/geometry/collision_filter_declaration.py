"""CollisionFilterDeclaration: an ordered list of statements that edit C.

Each statement names the pairs P it speaks about and what it does to them
(drake/geometry/collision_filter_declaration.h):

- ExcludeBetween(A, B): C ← C − P,  P = {(a, b)} ∀ a ∈ A, b ∈ B, a ≠ b
- ExcludeWithin(S):     C ← C − P,  P = {(gᵢ, gⱼ)} ∀ gᵢ, gⱼ ∈ S, i ≠ j
- AllowBetween(A, B):   C ← C ∪ P*, P* = P − (Aₚ × Aₚ) − Fₚ − Iₚ
- AllowWithin(S):       C ← C ∪ P*

N.B. AllowBetween does not clear pairs inside A or inside B: only the cross
pairs are in P. Statements are evaluated in invocation order, so a later
statement can undo an earlier one. Nothing is validated here; ids are checked
when the declaration is applied.
"""

from __future__ import annotations

import enum
from typing import Any, ClassVar, NamedTuple, Self

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._release import release
from reimpl.common._pybind_enum import PybindEnum
from reimpl.common._pybind_text import cannot_pickle
from reimpl.geometry.geometry_set import GeometrySet

__all__ = [
    "CollisionFilterDeclaration",
    "CollisionFilterScope",
    "Pairing",
    "Statement",
    "StatementOp",
]


class CollisionFilterScope(PybindEnum):
    """Which geometries a declaration's sets resolve to (pydrake ≥ 1.42 binds it)."""

    __slots__ = ()
    kAll: ClassVar[CollisionFilterScope]
    kOmitDeformable: ClassVar[CollisionFilterScope]


CollisionFilterScope.define(kAll=0, kOmitDeformable=1)


class Pairing(enum.Enum):
    """How a statement's sets become pairs."""

    BETWEEN = "between"  # P = A × B
    WITHIN = "within"  # P = S × S


class StatementOp(enum.Enum):
    """The four statements; ``filters`` says whether P leaves C (True) or joins it."""

    kAllowBetween = (Pairing.BETWEEN, False)
    kAllowWithin = (Pairing.WITHIN, False)
    kExcludeBetween = (Pairing.BETWEEN, True)
    kExcludeWithin = (Pairing.WITHIN, True)

    pairing: Pairing
    filters: bool

    def __init__(self, pairing: Pairing, filters: bool) -> None:
        self.pairing = pairing
        self.filters = filters


class Statement(NamedTuple):
    """One recorded statement; ``set_B`` is empty for the *Within ops."""

    op: StatementOp
    set_A: GeometrySet
    set_B: GeometrySet


_OWNER = "reimpl.geometry.CollisionFilterDeclaration"

#: The constructor's overloads; each gives the declaration's scope. ``scope=`` is bound
#: since 1.42 (collision-filter-scope-since-1.42: measured on pydrake 1.41.0 and 1.42.0);
#: before, a declaration has no scope (it is kAll).
_OVERLOADS = (
    Overload((), lambda: CollisionFilterScope.kAll),
    *(
        [Overload((Param("scope", instance_of(CollisionFilterScope)),), lambda scope: scope)]
        if release.has("collision-filter-scope-since-1.42")
        else []
    ),
)


class CollisionFilterDeclaration:
    """Statements to apply to C, in order; every method returns ``self``.

    >>> from reimpl.geometry import GeometrySet
    >>> d = CollisionFilterDeclaration().ExcludeWithin(geometry_set=GeometrySet())
    >>> len(d.statements())
    1
    """

    __slots__ = ("_scope", "_statements")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._statements: list[Statement] = []
        self._scope: CollisionFilterScope = dispatch(_OWNER, "__init__", _OVERLOADS, args, kwargs)

    @classmethod
    def _scoped(cls, scope: CollisionFilterScope) -> Self:
        """A declaration of ``scope`` on every release (reimpl's own declarations: the
        plant's default filters omit deformable geometry, whether or not ``scope=`` is bound)."""
        declaration = cls()
        declaration._scope = scope
        return declaration

    def _append(self, op: StatementOp, set_A: object, set_B: object) -> Self:
        for value in (set_A, set_B):
            if not isinstance(value, GeometrySet):
                raise TypeError(
                    f"{op.name[1:]}(): incompatible function arguments; "
                    f"expected reimpl.geometry.GeometrySet, got {type(value).__name__}"
                )
        # Sets are copied: editing a GeometrySet later does not edit the statement.
        self._statements.append(Statement(op, set_A._copy(), set_B._copy()))  # type: ignore[attr-defined]
        return self

    def AllowBetween(self, set_A: GeometrySet, set_B: GeometrySet) -> Self:
        return self._append(StatementOp.kAllowBetween, set_A, set_B)

    def AllowWithin(self, geometry_set: GeometrySet) -> Self:
        return self._append(StatementOp.kAllowWithin, geometry_set, GeometrySet())

    def ExcludeBetween(self, set_A: GeometrySet, set_B: GeometrySet) -> Self:
        return self._append(StatementOp.kExcludeBetween, set_A, set_B)

    def ExcludeWithin(self, geometry_set: GeometrySet) -> Self:
        return self._append(StatementOp.kExcludeWithin, geometry_set, GeometrySet())

    # reimpl-only introspection (pydrake binds none).
    def statements(self) -> tuple[Statement, ...]:
        return tuple(self._statements)

    def scope(self) -> CollisionFilterScope:
        return self._scope

    def __reduce__(self) -> Any:
        raise cannot_pickle(_OWNER)
