"""The checks a joint's constructor makes on its parameters, in Drake's order.

Drake counterpart: the constructors in drake/multibody/tree/*_joint.{h,cc}.
A parser hands a model's limits and dampings to these constructors, so these
checks decide whether a URDF parses (SDFormat's parser checks first, with its
own messages). Measured on pydrake 1.51.1, by joint type (``p`` the bound
parameters; a constructor without limits passes −∞ and +∞):

================== ============================================================
revolute           lower ≤ upper (SystemExit, joint.h:159); ‖axis‖∞ > ε
                   (RuntimeError); not damping < 0 (RuntimeError)
prismatic          as revolute, with √ε for the axis
screw              ‖axis‖∞ > ε; not damping < 0 (both RuntimeError)
ball_rpy           damping ≥ 0 (SystemExit, ball_rpy_joint.h:71)
universal          damping ≥ 0 (SystemExit, universal_joint.h:87)
planar             every damping ≥ 0 (SystemExit, planar_joint.h:74)
quaternion_floating angular, then translational damping ≥ 0 (SystemExit, :93, :94)
rpy_floating       angular, then translational damping ≥ 0 (SystemExit, :89, :90)
================== ============================================================

A comparison with NaN fails, so a NaN limit fails ``lower ≤ upper`` and a NaN
damping fails ``damping ≥ 0`` but passes ``not damping < 0``, as in C++.
pydrake reports a failed DRAKE_DEMAND or header DRAKE_THROW_UNLESS as
SystemExit (measured: catchable, the process goes on), at the file and line of
the release reimpl follows (1.58.0 reports the limits at joint.h:160): each
demand is named by its id in reimpl/common/demand_lines.json.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from reimpl.common._drake_demand import failed_demand

__all__ = ["check_joint_parameters"]


_Parameters = Mapping[str, Any]


@dataclass(frozen=True)
class _Demand:
    """A condition Drake demands in a header (``demand``: its id in demand_lines.json);
    pydrake raises SystemExit when it fails."""

    demand: str
    holds: Callable[[_Parameters], bool]

    def check(self, parameters: _Parameters) -> None:
        if not self.holds(parameters):
            raise failed_demand(self.demand)


@dataclass(frozen=True)
class _Throw:
    """A condition a constructor checks with ``throw std::logic_error`` (RuntimeError)."""

    message: str
    holds: Callable[[_Parameters], bool]

    def check(self, parameters: _Parameters) -> None:
        if not self.holds(parameters):
            raise RuntimeError(self.message)


_Check = _Demand | _Throw


def _limits_ordered(p: _Parameters) -> bool:
    return bool(p.get("pos_lower_limit", -math.inf) <= p.get("pos_upper_limit", math.inf))


_LIMITS_ORDERED = _Demand("Joint.limits", _limits_ordered)


def _axis_nonzero(kind: str, epsilon: float) -> _Throw:
    """Eigen's ``axis.isZero(epsilon)`` fails: some |component| > epsilon."""

    def holds(p: _Parameters) -> bool:
        axis = np.asarray(p.get("axis", (0.0, 0.0, 1.0)), dtype=float).reshape(-1)
        return not bool((np.abs(axis) <= epsilon).all())

    return _Throw(f"{kind} joint axis vector must have nonzero length.", holds)


def _damping_not_negative(kind: str) -> _Throw:
    return _Throw(f"{kind} joint damping must be nonnegative.", lambda p: not p["damping"] < 0)


def _nonnegative(joint: str, name: str) -> _Demand:
    return _Demand(f"{joint}.{name}", lambda p: bool(p[name] >= 0))


_EPSILON = sys.float_info.epsilon

#: The checks, in order, of each joint type's constructors.
_CHECKS: dict[str, tuple[_Check, ...]] = {
    "revolute": (
        _LIMITS_ORDERED,
        _axis_nonzero("Revolute", _EPSILON),
        _damping_not_negative("Revolute"),
    ),
    "prismatic": (
        _LIMITS_ORDERED,
        _axis_nonzero("Prismatic", math.sqrt(_EPSILON)),
        _damping_not_negative("Prismatic"),
    ),
    "screw": (_axis_nonzero("Screw", _EPSILON), _damping_not_negative("Screw")),
    "ball_rpy": (_nonnegative("BallRpyJoint", "damping"),),
    "universal": (_nonnegative("UniversalJoint", "damping"),),
    "planar": (
        _Demand(
            "PlanarJoint.damping",
            lambda p: bool((np.asarray(p["damping"], dtype=float) >= 0).all()),
        ),
    ),
    "quaternion_floating": (
        _nonnegative("QuaternionFloatingJoint", "angular_damping"),
        _nonnegative("QuaternionFloatingJoint", "translational_damping"),
    ),
    "rpy_floating": (
        _nonnegative("RpyFloatingJoint", "angular_damping"),
        _nonnegative("RpyFloatingJoint", "translational_damping"),
    ),
}


def check_joint_parameters(type_name: str, parameters: _Parameters) -> None:
    """Raises what pydrake's constructor of a ``type_name`` joint raises for ``parameters``."""
    for check in _CHECKS.get(type_name, ()):
        check.check(parameters)
