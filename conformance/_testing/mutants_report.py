"""Mutants whose only wrong answer is a report that no command asks for (issue 30).

Each one is reimpl with one deliberate bug in its inspector (as
``conformance._testing.mutants``, whose ``MUTANTS`` registry lists them),
written with public calls only. Their filters and candidate sets are right:
only ``observe``'s sampled ``CollisionFiltered`` answers and the inspector's
counts (``protocol.LocationState``) show them. The group report's mutants
are model mutants (``model_mutants``).

``tests/test_mutants.py`` holds each one's witness (pydrake's exact value).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from conformance._testing.mutants_basic import Inspector, Mutant, MutantSceneGraph, _context_of
from reimpl.geometry import FrameId, GeometryId, Role

__all__ = ["REPORT_MUTANTS"]


# ------------------------------------------- CollisionFiltered's error
class _BlamingInspector(Inspector):
    def CollisionFiltered(self, geometry_id1: GeometryId, geometry_id2: GeometryId) -> bool:
        try:
            return super().CollisionFiltered(geometry_id1=geometry_id1, geometry_id2=geometry_id2)
        except RuntimeError as exc:
            second = f"; {geometry_id2.get_value()} "
            message = str(exc)
            if second not in message:
                raise
            blamed = message.replace(second, f"; {geometry_id1.get_value()} ", 1)
            raise RuntimeError(blamed) from None


class CollisionFilteredBlamesTheFirst(MutantSceneGraph):
    """CollisionFiltered's error names its first geometry as the one at fault, whichever is.

    Reached by CollisionFiltered of a pair whose second geometry has no
    proximity role or is removed (the sampled pairs of every observation).
    """

    inspector_class = _BlamingInspector


# ------------------------------------------------ the inspector's counts
@dataclass
class _Unroled:
    """Per location: geometries whose proximity role RemoveRole took."""

    ids: set[GeometryId] = field(default_factory=set)


class _StaleCountInspector(Inspector):
    def NumGeometriesForFrameWithRole(self, frame_id: FrameId, role: Role) -> int:
        count: int = self.inner.NumGeometriesForFrameWithRole(frame_id=frame_id, role=role)
        if role is not Role.kProximity:
            return count
        unroled: _Unroled = self.graph.memory_of(self.context)
        on_frame = set(self.inner.GetGeometries(frame_id=frame_id))
        return count + len(unroled.ids & on_frame)


class FrameRoleCountKeepsRemoved(MutantSceneGraph):
    """NumGeometriesForFrameWithRole(kProximity) still counts geometry whose proximity role
    RemoveRole took (until it is assigned again).

    Reached by ``remove_role`` of proximity (the counts of every observation).
    """

    inspector_class = _StaleCountInspector

    def new_memory(self) -> _Unroled:
        return _Unroled()

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        context = _context_of(args, kwargs)
        return self.remove_role_noting_unroled(context, *args, **kwargs)

    def AssignRole(self, *args: Any, **kwargs: Any) -> None:
        context = _context_of(args, kwargs)
        super().AssignRole(*args, **kwargs)
        live = set(self.real_inspector(context).GetAllGeometryIds(role=Role.kProximity))
        self.memory_of(context).ids -= live

    def RemoveGeometry(self, *args: Any, **kwargs: Any) -> None:
        context = _context_of(args, kwargs)
        super().RemoveGeometry(*args, **kwargs)
        self.memory_of(context).ids.discard(kwargs.get("geometry_id"))


# ------------------------------------------------------------------- table
REPORT_MUTANTS: tuple[Mutant, ...] = (
    Mutant(
        "collision_filtered_blames_the_first",
        "CollisionFiltered's error names its first geometry as the one at fault, whichever is.",
        CollisionFilteredBlamesTheFirst,
    ),
    Mutant(
        "frame_role_count_keeps_removed",
        "NumGeometriesForFrameWithRole(kProximity) still counts geometry whose proximity role "
        "was removed.",
        FrameRoleCountKeepsRemoved,
    ),
)
