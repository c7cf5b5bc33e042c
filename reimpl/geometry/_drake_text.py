"""How Drake 1.51.1 writes numbers into shape reprs and error messages (measured).

Two spellings build on the shortest round-trip digits that Python's
``repr(float)`` also produces (fixed notation for exponents in [-5, 16),
scientific otherwise); Eigen's stream layout uses 16 significant digits:

===============  =============================  ========  ===========  ==================
 spelling         used by                        1.0       1e-05        0.1 + 0.2
===============  =============================  ========  ===========  ==================
 ``shortest``     shape ``repr``                 ``1``     ``1e-05``    0.30000000000000004
 ``with_point``   DRAKE_THROW_UNLESS values      ``1.0``   ``1.e-05``   0.30000000000000004
 ``eigen_row``    vectors in Mesh/Convex errors  ``[1]``   ``[1e-05]``  ``[0.3]``
===============  =============================  ========  ===========  ==================

-0.0 is ``-0``, ``-0.0`` and ``-0`` respectively.
``eigen_row`` right-aligns its cells to the widest: ``[     1 -1e-09      1]``.
Since 1.52 the Mesh/Convex errors write a vector with fmt instead
(``eigen_vector``: ``[1, -1e-09, 1]ᵀ``, each value ``shortest``; release fact
eigen-vector-wording-since-1.52, measured on 1.51.1 and 1.52.0 to 1.58.0).
A negative NaN prints as ``-nan`` (C++ keeps the sign bit; Python drops it).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from reimpl._release import release

__all__ = ["eigen_row", "eigen_vector", "shortest", "with_point"]


def _repr(value: float) -> str:
    if math.isnan(value):
        return "-nan" if math.copysign(1.0, value) < 0 else "nan"
    return repr(float(value))


def shortest(value: float) -> str:
    """fmt's ``{}``: round-trip digits, no trailing ``.0`` (``1``, ``0.3``, ``1e+16``)."""
    text = _repr(value)
    return text[:-2] if text.endswith(".0") else text


def with_point(value: float) -> str:
    """Drake's fmt_floating_point: always a decimal point (``-1.0``, ``-1.e-05``)."""
    text = _repr(value)
    mantissa, e, exponent = text.partition("e")
    if e and "." not in mantissa:
        return f"{mantissa}.e{exponent}"
    return text


def _significant16(value: float) -> str:
    """A C++ stream at precision 16 (Eigen's FullPrecision for double): ``%.16g``."""
    if math.isnan(value):
        return _repr(value)
    return f"{value:.16g}"


def eigen_row(values: Iterable[float]) -> str:
    """Eigen's stream layout of a row vector, 1.51.1: ``[     1 -1e-09      1]``."""
    cells = [_significant16(v) for v in values]
    width = max(len(c) for c in cells)
    return "[" + " ".join(c.rjust(width) for c in cells) + "]"


def eigen_vector(values: Iterable[float]) -> str:
    """A vector in a Mesh/Convex error, as reimpl's release writes it: ``[1, 2, 3]ᵀ``
    since 1.52, Eigen's stream layout (``eigen_row``) before."""
    if not release.has("eigen-vector-wording-since-1.52"):
        return eigen_row(values)
    return "[" + ", ".join(shortest(v) for v in values) + "]ᵀ"
