"""A plant context's positions q, and the joints' default positions.

Drake counterpart: MultibodyPlant's context and position methods
(multibody_plant.h/.cc). reimpl tracks q only (no velocities). After
Finalize every joint J owns ``q[position_start(J) : position_start(J) +
num_positions(J)]`` (laid out by the forest, see plant._topology):

- A new context (``CreateDefaultContext``, needs Finalize) and
  ``SetDefaultContext`` hold the joints' default positions laid out so.
- ``GetPositions``/``SetPositions`` read and write q, or one model
  instance's part of it: its joints' slices in position order, concatenated.
- ``GetDefaultPositions``/``SetDefaultPositions`` do the same for the joints'
  defaults (need Finalize).
- ``SetPositions`` demands (SystemExit on pydrake 1.51.1, measured) the
  size and, since Drake 1.38, that every value is finite (release fact
  set-positions-finite-demand-since-1.38; up to 1.37 it stores NaN, measured on
  1.12.0 to 1.58.0); ``SetDefaultPositions`` the size.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._release import release
from reimpl.multibody._errors import NotFinalizedError
from reimpl.multibody.plant._demands import demand
from reimpl.multibody.plant._elements import Elements
from reimpl.multibody.tree import Joint, ModelInstanceIndex
from reimpl.systems._context_keyword import context_argument
from reimpl.systems.framework import Context, LeafContext

__all__ = ["Positions"]

_OWNER = "reimpl.multibody.plant.MultibodyPlant"
#: Where a plant context keeps its positions q (Context._values).
_POSITIONS = "q"


def _is_vector(value: object) -> bool:
    try:
        return np.asarray(value, dtype=float).ndim in {1, 2}
    except (TypeError, ValueError):
        return False


_is_vector.__name__ = "numpy.ndarray[numpy.float64[m, 1]]"


def _positions_vector(q: Any) -> Any:
    return np.asarray(q, dtype=float).reshape(-1)


#: Whether SetPositions demands finite values (Drake 1.38 on).
_FINITE_DEMANDED = release.has("set-positions-finite-demand-since-1.38")


def _finite(values: Any) -> bool:
    """Whether ``values`` pass SetPositions' finiteness demand on reimpl's release."""
    return not _FINITE_DEMANDED or bool(np.isfinite(values).all())


class Positions(Elements):
    """Contexts and their q; the joints' defaults as a q."""

    def _new_context(self) -> Context:
        if not self._finalized:
            raise NotFinalizedError(
                "MultibodyPlant cannot SetDefaultParameters or CreateDefaultContext until "
                "after MultibodyPlant::Finalize() has been called."
            )
        context = LeafContext._for(self)
        context._values[_POSITIONS] = self.GetDefaultPositions()
        return context

    @context_argument
    def SetDefaultContext(self, context: Context) -> None:
        """Resets the context's q to the joints' default positions."""
        self._context_positions(context)[:] = self.GetDefaultPositions()

    def _context_positions(self, context: Context) -> Any:
        """The q held by ``context`` (mutable), after Drake's context check."""
        self.ValidateContext(context)
        return context._values[_POSITIONS]

    def _joints_in_position_order(self, model_instance: ModelInstanceIndex | None) -> list[Joint]:
        joints = self._joints_of(model_instance)
        return sorted(joints, key=lambda j: j.position_start())

    def _instance_slices(self, model_instance: ModelInstanceIndex) -> list[slice]:
        return [
            slice(j.position_start(), j.position_start() + j.num_positions())
            for j in self._joints_in_position_order(model_instance)
        ]

    def GetPositions(self, *args: Any, **kwargs: Any) -> Any:
        """q, or the positions of one model instance's joints in position order."""

        def all_positions(context: Context) -> Any:
            return self._context_positions(context).copy()

        def of_instance(context: Context, model_instance: ModelInstanceIndex) -> Any:
            q = self._context_positions(context)
            slices = self._instance_slices(model_instance)
            return np.concatenate([q[s] for s in slices]) if slices else np.zeros(0)

        context = Param("context", instance_of(Context))
        return dispatch(
            _OWNER,
            "GetPositions",
            (
                Overload((context,), all_positions),
                Overload(
                    (context, Param("model_instance", instance_of(ModelInstanceIndex))),
                    of_instance,
                ),
            ),
            args,
            kwargs,
        )

    def SetPositions(self, *args: Any, **kwargs: Any) -> None:
        """Sets q, or one model instance's positions; sizes and finiteness as Drake demands."""

        def all_positions(context: Context, q: Any) -> None:
            positions = self._context_positions(context)
            values = _positions_vector(q)
            demand(values.size == positions.size, "SetPositions.q.size")
            demand(_finite(values), "SetPositions.q.finite")
            positions[:] = values

        def of_instance(context: Context, model_instance: ModelInstanceIndex, q: Any) -> None:
            positions = self._context_positions(context)
            values = _positions_vector(q)
            slices = self._instance_slices(model_instance)
            size = sum(s.stop - s.start for s in slices)
            demand(values.size == size, "SetPositions.q_instance.size")
            demand(_finite(values), "SetPositions.q_instance.finite")
            first = 0
            for s in slices:
                positions[s] = values[first : first + s.stop - s.start]
                first += s.stop - s.start

        context = Param("context", instance_of(Context))
        q = Param("q", _is_vector)
        dispatch(
            _OWNER,
            "SetPositions",
            (
                Overload((context, q), all_positions),
                Overload(
                    (context, Param("model_instance", instance_of(ModelInstanceIndex)), q),
                    of_instance,
                ),
            ),
            args,
            kwargs,
        )

    def GetDefaultPositions(self, *args: Any, **kwargs: Any) -> Any:
        """The joints' default positions, laid out as q (after Finalize)."""

        def of(model_instance: ModelInstanceIndex | None = None) -> Any:
            self._check_finalized("GetDefaultPositions")
            joints = self._joints_in_position_order(model_instance)
            if model_instance is None:
                q = np.zeros(self.num_positions())
                for joint in joints:
                    start = joint.position_start()
                    q[start : start + joint.num_positions()] = joint.default_positions()
                return q
            parts = [j.default_positions() for j in joints]
            return np.concatenate(parts) if parts else np.zeros(0)

        return dispatch(
            _OWNER,
            "GetDefaultPositions",
            (
                Overload((), of),
                Overload((Param("model_instance", instance_of(ModelInstanceIndex)),), of),
            ),
            args,
            kwargs,
        )

    def SetDefaultPositions(self, *args: Any, **kwargs: Any) -> None:
        """Sets every joint's default positions from q (or one instance's, in position order)."""

        def all_positions(q: Any) -> None:
            self._check_finalized("SetDefaultPositions")
            values = _positions_vector(q)
            demand(values.size == self.num_positions(), "SetDefaultPositions.q.size")
            for joint in self._joints:
                start = joint.position_start()
                joint._set_default(0, values[start : start + joint.num_positions()])

        def of_instance(model_instance: ModelInstanceIndex, q_instance: Any) -> None:
            self._check_finalized("SetDefaultPositions")
            values = _positions_vector(q_instance)
            joints = self._joints_in_position_order(model_instance)
            demand(
                values.size == sum(j.num_positions() for j in joints),
                "SetDefaultPositions.q_instance.size",
            )
            first = 0
            for joint in joints:
                joint._set_default(0, values[first : first + joint.num_positions()])
                first += joint.num_positions()

        dispatch(
            _OWNER,
            "SetDefaultPositions",
            (
                Overload((Param("q", _is_vector),), all_positions),
                Overload(
                    (
                        Param("model_instance", instance_of(ModelInstanceIndex)),
                        Param("q_instance", _is_vector),
                    ),
                    of_instance,
                ),
            ),
            args,
            kwargs,
        )
