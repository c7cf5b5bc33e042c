"""CollisionFilterManager: the public handle that edits one state's C.

Drake counterpart: drake/geometry/collision_filter_manager.h. A manager is a
view: copies of it edit the same data, which is either the model's
GeometryState or one context's copy of it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, NoReturn

from reimpl._release import release
from reimpl.common._pybind_text import cannot_pickle, no_constructor
from reimpl.geometry.collision_filter_declaration import CollisionFilterDeclaration
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.identifier import FilterId

if TYPE_CHECKING:
    from reimpl.geometry.geometry_state import GeometryState

__all__ = ["CollisionFilterManager"]


class CollisionFilterManager:
    """Applies declarations to C, persistently or transiently.

    C is the persistent base with the transient history replayed in order.
    N.B. reimpl registers no deformable geometry, so a declaration's
    CollisionFilterScope (kAll or kOmitDeformable) resolves every set alike.
    """

    def __init__(self, *args: object, **kwargs: object) -> None:
        raise no_constructor("reimpl.geometry.CollisionFilterManager")

    _state_of: Callable[[], GeometryState]

    @classmethod
    def _view(cls, state_of: Callable[[], GeometryState]) -> CollisionFilterManager:
        """A view of whatever state ``state_of()`` returns at each call."""
        manager = object.__new__(cls)
        manager._state_of = state_of
        return manager

    @property
    def _state(self) -> GeometryState:
        return self._state_of()

    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        """Applies ``declaration`` to the persistent base, statement by statement.

        Raises:
            RuntimeError: an id in the declaration is not registered (what the
                statements before it leave depends on the release:
                ``CollisionFilter._failed_apply``), or transient history is active.
        """
        state = self._state
        state.collision_filter.apply(declaration.statements(), state.collect_ids)

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        """Appends ``declaration`` to the transient history and returns its id."""
        state = self._state
        return state.collision_filter.apply_transient(declaration.statements(), state.collect_ids)

    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        """Removes a transient declaration; True iff ``IsActive(filter_id)`` was True."""
        return self._state.collision_filter.remove_declaration(filter_id)

    def __reduce__(self) -> NoReturn:
        raise cannot_pickle("reimpl.geometry.CollisionFilterManager")

    def IsActive(self, filter_id: FilterId) -> bool:
        return self._state.collision_filter.is_active(filter_id)

    def has_transient_history(self) -> bool:
        return self._state.collision_filter.has_transient_history()

    if release.has("activation-since-1.55"):

        def Deactivate(self, geometry_set: GeometrySet) -> None:
            """C ← C − {(a, b) : a ∈ S or b ∈ S}, until reactivated (Drake ≥ 1.55)."""
            self._state.set_active(geometry_set, active=False)

        def Activate(self, geometry_set: GeometrySet) -> None:
            """Undoes Deactivate for the geometries in S (Drake ≥ 1.55)."""
            self._state.set_active(geometry_set, active=True)
