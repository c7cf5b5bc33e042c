"""CoulombFriction: a static and a dynamic friction coefficient, stored only.

Drake counterpart: drake/multibody/plant/coulomb_friction.h. A collision
geometry may carry one (``RegisterCollisionGeometry(..., coulomb_friction)``
puts it in the ``("material", "coulomb_friction")`` property); reimpl does no
contact, so it is never read. The one rule is the constructor's:
dynamic ≤ static, else Drake's error.
"""

from __future__ import annotations

from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.common.value import register_value_type
from reimpl.multibody._errors import MultibodyPlantError

__all__ = ["CoulombFriction"]


class CoulombFriction:
    """Static and dynamic friction coefficients (stored only)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._static, self._dynamic = 0.0, 0.0

        def set_coefficients(static_friction: float, dynamic_friction: float) -> None:
            if dynamic_friction > static_friction:
                raise MultibodyPlantError(
                    f"The given dynamic friction ({dynamic_friction:g}) is greater than the "
                    f"given static friction ({static_friction:g}); dynamic friction must be "
                    "less than or equal to static friction."
                )
            self._static, self._dynamic = float(static_friction), float(dynamic_friction)

        number = instance_of(int, float)
        dispatch(
            "reimpl.multibody.plant.CoulombFriction",
            "__init__",
            (
                Overload((), lambda: None),
                Overload(
                    (Param("static_friction", number), Param("dynamic_friction", number)),
                    set_coefficients,
                ),
            ),
            args,
            kwargs,
        )

    def static_friction(self) -> float:
        return self._static

    def dynamic_friction(self) -> float:
        return self._dynamic


register_value_type(CoulombFriction, "drake::multibody::CoulombFriction<double>")
