"""A plant's two phases: it is built, then ``Finalize()`` seals it.

Drake counterpart: MultibodyPlant's ``is_finalized()`` and the phase checks
its methods make (multibody_plant.cc). Every method that changes the model
(adding bodies, joints, geometry, filter settings) belongs to the building
phase; every method that reads what Finalize made (the floating joints, the
positions q, the forest of mobilizers) to the finalized one. A call in the
wrong phase raises Drake's message, which names the method:

==============  ===================================================================
phase needed    message
==============  ===================================================================
building        ``Post-finalize calls to 'M()' are not allowed; calls to this method
                must happen before Finalize().``
finalized       ``Pre-finalize calls to 'M()' are not allowed; you must call
                Finalize() first.``
==============  ===================================================================

Some methods raise other texts of their own (AddModelInstance, AddFrame,
RegisterAsSourceForSceneGraph); they test ``_finalized`` themselves.
"""

from __future__ import annotations

from reimpl.multibody._errors import FinalizedError, NotFinalizedError
from reimpl.systems.framework import LeafSystem

__all__ = ["PlantPhase"]


class PlantPhase(LeafSystem):
    """The base of the plant's parts: the phase flag and its two checks."""

    def __init__(self) -> None:
        super().__init__()
        self._finalized = False

    def is_finalized(self) -> bool:
        return self._finalized

    def _check_not_finalized(self, method: str) -> None:
        if self._finalized:
            raise FinalizedError(
                f"Post-finalize calls to '{method}()' are not allowed; calls to this method "
                "must happen before Finalize()."
            )

    def _check_finalized(self, method: str) -> None:
        if not self._finalized:
            raise NotFinalizedError(
                f"Pre-finalize calls to '{method}()' are not allowed; you must call Finalize() "
                "first."
            )
