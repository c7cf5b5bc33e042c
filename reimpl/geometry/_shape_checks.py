"""The DRAKE_THROW_UNLESS checks of drake/geometry/shape_specification.cc, as one table.

pydrake reports a failed check as ``SystemExit`` (not RuntimeError) whose text
names the file, the line, the function, the condition and the offending value::

    Failure at external/drake+/geometry/shape_specification.cc:309 in Sphere():
    condition 'std::isfinite(radius) && radius >= 0' failed. radius = -1.0.

(one line). Lines are Drake 1.51.1's, which reimpl follows; later releases move
them (1.58.0: Sphere is at 285) and keep the rest. Measures are checked in
declaration order, so the first bad one is reported.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from reimpl.common._drake_demand import DRAKE_PATH
from reimpl.geometry._drake_text import with_point

__all__ = ["measure_names", "require"]

_FILE = f"{DRAKE_PATH}geometry/shape_specification.cc"


def _finite_positive(value: float) -> bool:
    return math.isfinite(value) and value > 0


def _finite_non_negative(value: float) -> bool:
    return math.isfinite(value) and value >= 0


def _not_tiny(value: float) -> bool:
    return value >= 1e-10


_POSITIVE = ("std::isfinite({0}) && {0} > 0", _finite_positive)
_NON_NEGATIVE = ("std::isfinite({0}) && {0} >= 0", _finite_non_negative)

#: (function, measure) -> (line in Drake 1.51.1, condition template, predicate).
_CHECKS: dict[tuple[str, str], tuple[int, tuple[str, Callable[[float], bool]]]] = {
    ("Box", "width"): (110, _POSITIVE),
    ("Box", "depth"): (111, _POSITIVE),
    ("Box", "height"): (112, _POSITIVE),
    ("Capsule", "radius"): (129, _POSITIVE),
    ("Capsule", "length"): (130, _POSITIVE),
    ("Cylinder", "radius"): (194, _POSITIVE),
    ("Cylinder", "length"): (195, _POSITIVE),
    ("Ellipsoid", "a"): (206, _POSITIVE),
    ("Ellipsoid", "b"): (207, _POSITIVE),
    ("Ellipsoid", "c"): (208, _POSITIVE),
    ("MakePose", "norm"): (225, ("norm >= 1e-10", _not_tiny)),
    ("MeshcatCone", "height"): (296, _POSITIVE),
    ("MeshcatCone", "a"): (297, _POSITIVE),
    ("MeshcatCone", "b"): (298, _POSITIVE),
    ("Sphere", "radius"): (309, _NON_NEGATIVE),
}


def measure_names(function: str) -> tuple[str, ...]:
    """The measures ``function`` checks, in the order it checks them."""
    return tuple(name for owner, name in _CHECKS if owner == function)


def require(function: str, name: str, value: float) -> None:
    """Raises pydrake's SystemExit unless ``value`` passes ``function``'s check of ``name``."""
    line, (condition, holds) = _CHECKS[(function, name)]
    if not holds(value):
        raise SystemExit(
            f"Failure at {_FILE}:{line} in {function}(): "
            f"condition '{condition.format(name)}' failed. {name} = {with_point(value)}."
        )
