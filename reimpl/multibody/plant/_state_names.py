"""The names of q and v: ``GetPositionNames``, ``GetVelocityNames``, ``GetStateNames``.

Drake counterpart: MultibodyPlant's name methods (multibody_plant.cc).
Measured on pydrake 1.51.1: the name of coordinate i of joint J is

    [instance_]J[_suffix(i)]

at ``start(J) + i`` in q (or v), the suffixes being the joint's
(``position_suffix``, ``velocity_suffix``: ``q``, ``x``, ``qw``, ...). With
``always_add_suffix=False`` a one-coordinate joint's name has none; welds
have no coordinates. For one model instance the names go at ``start(J) + i
− min start``, the minimum over all the instance's joints, welds included,
and Drake demands that they fit: an instance whose coordinates are not
contiguous ends the program (SystemExit). ``GetStateNames`` is the position
names, then the velocity names, always with suffixes.
"""

from __future__ import annotations

from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.multibody.plant._demands import demand
from reimpl.multibody.plant._elements import Elements
from reimpl.multibody.tree import ModelInstanceIndex

__all__ = ["StateNames"]

_OWNER = "reimpl.multibody.plant.MultibodyPlant"
#: The accessors of a joint's positions and of its velocities: count, start, suffix.
_COORDINATES = {
    "position": ("num_positions", "position_start", "position_suffix"),
    "velocity": ("num_velocities", "velocity_start", "velocity_suffix"),
}


class StateNames(Elements):
    """The names of the plant's positions and velocities (after Finalize)."""

    def GetPositionNames(self, *args: Any, **kwargs: Any) -> list[str]:
        """``[instance_]joint[_suffix]`` for each position, in q's order (see ``_names``)."""
        return self._dispatch_names("position", args, kwargs)

    def GetVelocityNames(self, *args: Any, **kwargs: Any) -> list[str]:
        """``[instance_]joint[_suffix]`` for each velocity, in v's order (see ``_names``)."""
        return self._dispatch_names("velocity", args, kwargs)

    def GetStateNames(self, *args: Any, **kwargs: Any) -> list[str]:
        """The position names, then the velocity names, always with their suffixes."""

        def names(
            model_instance: ModelInstanceIndex | None = None,
            add_model_instance_prefix: bool = True,
        ) -> list[str]:
            return [
                *self._names("position", model_instance, add_model_instance_prefix, True),
                *self._names("velocity", model_instance, add_model_instance_prefix, True),
            ]

        flag = instance_of(bool)
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "GetStateNames",
            (
                Overload((Param("add_model_instance_prefix", flag, True),), names),
                Overload(
                    (
                        Param("model_instance", instance_of(ModelInstanceIndex)),
                        Param("add_model_instance_prefix", flag, False),
                    ),
                    names,
                ),
            ),
            args,
            kwargs,
        )

    def _dispatch_names(self, kind: str, args: Any, kwargs: Any) -> list[str]:
        """Binds GetPositionNames' or GetVelocityNames' two overloads."""

        def names(
            model_instance: ModelInstanceIndex | None = None,
            add_model_instance_prefix: bool = True,
            always_add_suffix: bool = True,
        ) -> list[str]:
            return self._names(kind, model_instance, add_model_instance_prefix, always_add_suffix)

        flag = instance_of(bool)
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            f"Get{kind.capitalize()}Names",
            (
                Overload(
                    (
                        Param("add_model_instance_prefix", flag, True),
                        Param("always_add_suffix", flag, True),
                    ),
                    names,
                ),
                Overload(
                    (
                        Param("model_instance", instance_of(ModelInstanceIndex)),
                        Param("add_model_instance_prefix", flag, False),
                        Param("always_add_suffix", flag, True),
                    ),
                    names,
                ),
            ),
            args,
            kwargs,
        )

    def _names(
        self,
        kind: str,
        model_instance: ModelInstanceIndex | None,
        add_model_instance_prefix: bool,
        always_add_suffix: bool,
    ) -> list[str]:
        """Drake's names of q (``kind`` "position") or v ("velocity").

        Joint J's names go at ``start(J) + i``; for one model instance at
        ``start(J) + i − min_J start(J)`` (the minimum over all the instance's
        joints, welds included), which Drake demands fit: an instance whose
        coordinates are not contiguous (a free tree's quaternion after another
        instance's joints) ends the program (SystemExit, measured on pydrake
        1.51.1). Without ``always_add_suffix``, a one-coordinate joint's name
        has no suffix. Welds are skipped.
        """
        method = f"Get{kind.capitalize()}Names"
        self._check_finalized(method)
        count_of, start_of, suffix_of = _COORDINATES[kind]
        joints = self._joints_of(model_instance)
        size = sum(getattr(j, count_of)() for j in joints)
        offset = 0
        if model_instance is not None:
            offset = min(
                (getattr(j, start_of)() for j in joints), default=getattr(self, count_of)()
            )
        result = [""] * size
        for joint in joints:
            if joint.num_positions() == 0:
                continue
            count, start = getattr(joint, count_of)(), getattr(joint, start_of)()
            if model_instance is not None:
                # N.B. Drake first demands start >= offset, which holds: offset is the least
                # start. The names fit (the demand <method>.fits) unless the instance's
                # coordinates are not contiguous.
                demand(start + count - offset <= size, f"{method}.fits")
            prefix = ""
            if add_model_instance_prefix:
                prefix = f"{self.GetModelInstanceName(joint.model_instance())}_"
            for i in range(count):
                name = f"{prefix}{joint.name()}"
                if always_add_suffix or count > 1:
                    name = f"{name}_{getattr(joint, suffix_of)(i)}"
                result[start + i - offset] = name
        return result
