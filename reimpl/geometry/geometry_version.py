"""GeometryVersion: one revision id per role of a GeometryState's data.

Drake counterpart: drake/geometry/geometry_version.h. A consumer keeps a copy and asks
``IsSameAs(other, role)`` to learn whether that role's data may have changed. Each
role's id is replaced (never incremented in place) when the state changes that role, so
two versions agree on a role iff neither has seen a change of it since one was copied
from the other.

Which calls change which role (measured on pydrake 1.51.1 and 1.58.0; X = changed):

==========================================================  =========  ==========  ============
call                                                        proximity  perception  illustration
==========================================================  =========  ==========  ============
``collision_filter_manager()`` (model or context), each     X
AssignRole(proximity), kNew or kReplace, once validated     X
AssignRole(illustration), kNew or kReplace, once validated                         X
RemoveRole / RemoveGeometry of a geometry with the role     X (prox.)              X (illus.)
anything with perception (no renderer here)
RegisterFrame, RenameGeometry, Apply, ApplyTransient
==========================================================  =========  ==========  ============

A call that fails validation (a duplicate role, say) changes nothing; a proximity
assignment that fails later (transient history, a mesh without a hull) has already
changed the proximity version, as in Drake. Perception changes only when a renderer
takes or drops a geometry, and reimpl has no renderers. A context's state starts
with a copy of the model's version, so the two agree until either changes.
"""

from __future__ import annotations

import itertools
from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.common._pybind_text import cannot_pickle
from reimpl.geometry.geometry_roles import Role

__all__ = ["GeometryVersion"]

_OWNER = "reimpl.geometry.GeometryVersion"

#: Role version ids, unique across every GeometryVersion of the process.
_NEW_ID = itertools.count(1).__next__

#: The roles a version tracks (kUnassigned has no data of its own).
_TRACKED = (Role.kProximity, Role.kPerception, Role.kIllustration)


class GeometryVersion:
    """Per-role revision ids; ``IsSameAs(other, role)`` compares one role's ids.

    >>> a = GeometryVersion()
    >>> b = GeometryVersion(other=a)
    >>> b.IsSameAs(other=a, role=Role.kProximity)
    True
    >>> b._modify(Role.kProximity)
    >>> b.IsSameAs(other=a, role=Role.kProximity), b.IsSameAs(other=a, role=Role.kIllustration)
    (False, True)
    """

    __slots__ = ("_ids",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        other: GeometryVersion | None = dispatch(_OWNER, "__init__", _OVERLOADS, args, kwargs)
        self._ids: dict[Role, int] = (
            {role: _NEW_ID() for role in _TRACKED} if other is None else dict(other._ids)
        )

    def IsSameAs(self, other: GeometryVersion, role: Role) -> bool:
        """True iff ``self`` and ``other`` have the same version of ``role``'s data.

        Raises:
            RuntimeError: ``role`` is kUnassigned (Drake's std::logic_error).
        """
        if role not in _TRACKED:
            raise RuntimeError("Trying to compare the version of unassigned roles.")
        return self._ids[role] == other._ids[role]

    def _modify(self, role: Role) -> None:
        """Marks ``role``'s data as changed (GeometryState's ``modify_<role>()``)."""
        self._ids[role] = _NEW_ID()

    def __copy__(self) -> GeometryVersion:
        return GeometryVersion(self)

    def __deepcopy__(self, memo: dict[int, Any]) -> GeometryVersion:
        return GeometryVersion(self)

    def __reduce__(self) -> Any:
        raise cannot_pickle(_OWNER)  # copies, yes; pickles, no (pydrake 1.51.1, 1.58.0)


#: The constructor's overloads, in pydrake's order: a new version, or a copy of ``other``.
_OVERLOADS = (
    Overload((), lambda: None),
    Overload((Param("other", instance_of(GeometryVersion)),), lambda other: other),
)
