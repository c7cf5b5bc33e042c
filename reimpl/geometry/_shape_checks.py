"""The DRAKE_THROW_UNLESS checks of drake/geometry/shape_specification.cc, as one table.

pydrake reports a failed check as ``SystemExit`` (not RuntimeError) whose text
names the file, the line, the function, the condition and the offending value::

    Failure at external/drake+/geometry/shape_specification.cc:309 in Sphere():
    condition 'std::isfinite(radius) && radius >= 0' failed. radius = -1.0.

(one line; measured on pydrake 1.51.1). The file, line, function and condition
are the release's, from reimpl/common/demand_lines.json by the id
``<function>.<measure>`` (1.58.0 reports Sphere at line 285); this module keeps
what each check accepts. Measures are checked in declaration order, so the
first bad one is reported. Up to 1.45 (measured on 1.12.0 to 1.45.0) Drake
checked shapes with its own RuntimeError wording instead; reimpl does not
follow that.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from reimpl.common._demand_lines import demand_site
from reimpl.geometry._drake_text import with_point

__all__ = ["measure_names", "require"]


def _finite_positive(value: float) -> bool:
    return math.isfinite(value) and value > 0


def _finite_non_negative(value: float) -> bool:
    return math.isfinite(value) and value >= 0


def _not_tiny(value: float) -> bool:
    return value >= 1e-10


#: (function, measure) -> what the check accepts, in Drake's order of checks.
_CHECKS: dict[tuple[str, str], Callable[[float], bool]] = {
    ("Box", "width"): _finite_positive,
    ("Box", "depth"): _finite_positive,
    ("Box", "height"): _finite_positive,
    ("Capsule", "radius"): _finite_positive,
    ("Capsule", "length"): _finite_positive,
    ("Cylinder", "radius"): _finite_positive,
    ("Cylinder", "length"): _finite_positive,
    ("Ellipsoid", "a"): _finite_positive,
    ("Ellipsoid", "b"): _finite_positive,
    ("Ellipsoid", "c"): _finite_positive,
    ("MakePose", "norm"): _not_tiny,
    ("MeshcatCone", "height"): _finite_positive,
    ("MeshcatCone", "a"): _finite_positive,
    ("MeshcatCone", "b"): _finite_positive,
    ("Sphere", "radius"): _finite_non_negative,
}


def measure_names(function: str) -> tuple[str, ...]:
    """The measures ``function`` checks, in the order it checks them."""
    return tuple(name for owner, name in _CHECKS if owner == function)


def require(function: str, name: str, value: float) -> None:
    """Raises pydrake's SystemExit unless ``value`` passes ``function``'s check of ``name``."""
    if not _CHECKS[(function, name)](value):
        path, line, reported, condition = demand_site(f"{function}.{name}")
        raise SystemExit(
            f"Failure at {path}:{line} in {reported}(): "
            f"condition '{condition}' failed. {name} = {with_point(value)}."
        )
