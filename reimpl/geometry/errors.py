"""Narrow error classes, each a ``RuntimeError`` as pydrake raises.

C++ ``std::logic_error`` and ``std::runtime_error`` both reach Python as
``RuntimeError``; our classes subclass it, so ``except RuntimeError`` code
written for pydrake catches them unchanged, while our own code can be precise.
Every message is Drake's text, with ids printed as their integer values.
"""

from __future__ import annotations

__all__ = [
    "CollisionFilterError",
    "DuplicateRoleError",
    "GeometryStateError",
    "TransientHistoryActiveError",
    "UnenginedGeometryError",
    "UnknownFrameError",
    "UnknownGeometryError",
    "UnknownSourceError",
    "UnqueryableGeometryError",
    "UnregisteredFilterGeometryError",
]


class GeometryStateError(RuntimeError):
    """Raised when a SceneGraph operation refers to the scene inconsistently."""


class CollisionFilterError(GeometryStateError):
    """Raised when a collision filter operation cannot be carried out."""


class UnknownGeometryError(CollisionFilterError):
    """Raised when a GeometryId is not registered with this SceneGraph (or context)."""


class UnknownFrameError(CollisionFilterError):
    """Raised when a FrameId is not registered with this SceneGraph (or context)."""


class UnknownSourceError(GeometryStateError):
    """Raised when a SourceId is not registered with this SceneGraph."""


class TransientHistoryActiveError(CollisionFilterError):
    """Raised when the persistent configuration is edited while transient history exists."""


class UnqueryableGeometryError(CollisionFilterError):
    """Raised when CollisionFiltered() is asked about an invalid or non-proximity geometry."""


class UnregisteredFilterGeometryError(CollisionFilterError):
    """Raised (since Drake 1.57) when a declaration names a proximity geometry whose
    proximity engine entry failed, so the filter never registered it."""


class DuplicateRoleError(GeometryStateError):
    """Raised when a role is assigned with RoleAssign.kNew to a geometry that has it."""


class UnenginedGeometryError(IndexError):
    """Raised, as Drake's ``std::out_of_range`` from ``unordered_map::at``, when the collision
    filter is asked about a geometry that has the proximity role but whose proximity engine
    entry failed (its convex hull could not be made): ``GeometryState.unengined``."""
