"""The errors a MultibodyPlant raises; each is the RuntimeError pydrake raises.

Messages are Drake's, word for word; the classes only say which kind of
misuse it was, so that callers (and readers) need not match on text.
"""

from __future__ import annotations

__all__ = [
    "DemandFailedError",
    "DuplicateNameError",
    "FinalizedError",
    "MultibodyPlantError",
    "NotFinalizedError",
    "NotFoundError",
    "TopologyError",
]


class MultibodyPlantError(RuntimeError):
    """A misuse of a plant or of its elements."""


class FinalizedError(MultibodyPlantError):
    """A call that must come before Finalize() came after it (Finalize twice included)."""


class NotFinalizedError(MultibodyPlantError):
    """A call that must come after Finalize() came before it."""


class DuplicateNameError(MultibodyPlantError):
    """A model instance, body, frame or joint name already taken where it must be unique."""


class NotFoundError(MultibodyPlantError):
    """No element with that name, index or id (or, for a name, more than one)."""


class TopologyError(MultibodyPlantError):
    """Joints Drake cannot model: a body joined to itself, two joints between two
    bodies, a loop, or a joint that would have to be reversed and cannot be."""


class DemandFailedError(MultibodyPlantError):
    """A precondition Drake checks with DRAKE_DEMAND.

    N.B. Divergence by necessity: pydrake 1.51.1 prints the condition and
    aborts the process; reimpl raises instead.
    """
