"""The warning Drake 1.51.1 gives for a link's implausible ``<inertial>`` (measured).

Drake builds the rotational inertia I about the centre of mass from ``ixx``
.. ``izz`` (products as written) and checks it, then builds the spatial
inertia from the mass; a failure is a warning (an error under strict
parsing), and the body gets a stand-in inertia:

* principal moments λ (I's eigenvalues, ascending) with some λᵢ < -ε, or
  violating λ₀ + λ₁ + ε >= λ₂ (or its rotations), where ε = 16·2⁻⁵²·max(1,
  tr(I)/2)::

      While parsing inertia matrix: MakeFromMomentsAndProductsOfInertia(): The rotational inertia
      [-1   0   0]
      [ 0   1   0]
      [ 0   0   1]
      did not pass the test CouldBePhysicallyValid().
      The associated principal moments of inertia:
      -1  1  1
      are invalid since at least one is negative.

  (``do not satisfy the triangle inequality.`` when none is negative);
* otherwise, unless the mass and I are all zero (a massless body), a mass
  <= 0: ``While re-expressing as central inertia: Failure at ...unit_inertia.h:104
  in SetFromRotationalInertia(): condition 'mass > 0' failed.``

Numbers print as fmt's shortest round-trip text, the matrix's right-aligned
to the widest. With products of inertia (above 4ε·tr(I)/2) the moments come
from numpy's eigensolver here and Eigen's in Drake, and may print differently
in the last digits; without, they are the sorted diagonal in both.
"""

from __future__ import annotations

import numpy as np

from reimpl.geometry._drake_text import shortest

__all__ = ["inertia_warning"]

_PRECISION = 16 * float(np.finfo(float).eps)
_UNIT_INERTIA_DEMAND = (
    "Failure at bazel-out/k8-opt/bin/external/drake+/multibody/tree/_virtual_includes/"
    "unit_inertia/drake/multibody/tree/unit_inertia.h:104 in SetFromRotationalInertia(): "
    "condition 'mass > 0' failed."
)


def inertia_warning(mass: float, moments: dict[str, float]) -> str | None:
    """Drake's warning for ``mass`` and ``moments`` (``ixx`` .. ``izz``), or None."""
    m = moments
    inertia = np.array(
        [
            [m["ixx"], m["ixy"], m["ixz"]],
            [m["ixy"], m["iyy"], m["iyz"]],
            [m["ixz"], m["iyz"], m["izz"]],
        ]
    )
    report = _invalidity(inertia)
    if report is not None:
        return (
            "While parsing inertia matrix: MakeFromMomentsAndProductsOfInertia(): The "
            f"rotational inertia\n{_matrix_text(inertia)}did not pass the test "
            f"CouldBePhysicallyValid().{report}"
        )
    if mass == 0.0 and not inertia.any():
        return None  # N.B. A massless body.
    if not mass > 0:
        return f"While re-expressing as central inertia: {_UNIT_INERTIA_DEMAND}"
    return None


def _matrix_text(inertia: np.ndarray) -> str:
    """RotationalInertia's to_string: rows ``[a  b  c]``, entries right-aligned to the widest."""
    cells = [[shortest(float(v)) for v in row] for row in inertia]
    width = max(len(cell) for row in cells for cell in row)
    return "".join("[" + "  ".join(c.rjust(width) for c in row) + "]\n" for row in cells)


def _principal_moments(inertia: np.ndarray) -> list[float]:
    """CalcPrincipalMomentsOfInertia: the sorted diagonal when the products are ~0."""
    tolerance = 4 * float(np.finfo(float).eps) * 0.5 * abs(float(np.trace(inertia)))
    products = (inertia[1, 0], inertia[2, 0], inertia[2, 1])
    if all(abs(float(p)) <= tolerance for p in products):
        return sorted(float(v) for v in np.diag(inertia))
    return [float(v) for v in np.linalg.eigvalsh(inertia)]


def _invalidity(inertia: np.ndarray) -> str | None:
    """RotationalInertia's CreateInvalidityReport for a finite matrix."""
    epsilon = _PRECISION * max(1.0, 0.5 * abs(float(np.trace(inertia))))
    a, b, c = _principal_moments(inertia)
    near_positive = min(a, b, c) >= -epsilon
    triangle = a + b + epsilon >= c and a + b + epsilon >= b and b + c + epsilon >= a
    if near_positive and triangle:
        return None
    reason = (
        "are invalid since at least one is negative."
        if min(a, b, c) < 0
        else "do not satisfy the triangle inequality."
    )
    return (
        "\nThe associated principal moments of inertia:\n"
        f"{shortest(a)}  {shortest(b)}  {shortest(c)}\n{reason}"
    )
