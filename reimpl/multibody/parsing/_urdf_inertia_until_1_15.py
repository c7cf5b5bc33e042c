"""Drake 1.12-1.15: a URDF link's implausible ``<inertial>`` is a parse error (measured).

Since 1.16 Drake warns and gives the body a stand-in (``_urdf_inertia``); up to
1.15 (release fact urdf-implausible-inertia-error-until-1.15) the link's
``SpatialInertia::MakeFromCentralInertia(m, p, I)`` throws, before the body is
added, where ``p`` is the ``<origin>``'s xyz and ``I`` the moments and products
re-expressed in the link frame (I_B = R·I·Rᵀ):

* unless m = 0 and I = 0 (a massless body), ``m > 0`` must hold, or
  UnitInertia::SetFromRotationalInertia fails its demand (SystemExit ``Failure at
  ...unit_inertia.h:95 in SetFromRotationalInertia(): condition 'mass > 0'
  failed.``);
* the spatial inertia (m, p, G_P = I/m + [p]×ᵀ[p]×) must pass IsPhysicallyValid():
  I_cm = (G_P − [p]×ᵀ[p]×)·m could be physical (principal moments near
  positive, triangle inequality), or RuntimeError::

      Spatial inertia fails SpatialInertia::IsPhysicallyValid().
       mass = 2.0
       Center of mass = [0.1  0.2  0.0]
       Inertia about point P, I_BP =
      [1.08  0.06     0]
      ...
       Inertia about center of mass, I_BBcm =      (only when p ≠ 0)
      ...
       Principal moments of inertia about Bcm (center of mass) =
      [0.8999999999999999  1.0999999999999996  3.0]

Scalars print as that release's fmt printed a double (Python's ``repr``: ``0.0``,
``1e-05``), matrices as RotationalInertia's stream text at a C++ stream's default 6
significant digits (``7.95654e-05``), right-aligned to the widest (measured with
example-robot-data's allegro hand on 1.15.0).
The principal moments are Eigen's eigenvalues as reimpl computes them for 1.51.1
(Eigen 5.0.1); Drake 1.15's older Eigen can differ in the last digit when the
products of inertia are not zero (measured: robotiq_simple.urdf's link prints
0.0009999888913713216 on 1.15.0, reimpl 0.0009999888913713219). The harness
compares an error's first line, which is exact.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from reimpl.common._drake_demand import demand_failure
from reimpl.multibody.parsing._diagnostics import ModelParseError
from reimpl.multibody.parsing._mesh_inertia import _point_mass
from reimpl.multibody.parsing._urdf_inertia import _eigen_eigenvalues, _invalidity

__all__ = ["inertia_error"]

_Matrix = npt.NDArray[np.float64]
_HEADER = "Spatial inertia fails SpatialInertia::IsPhysicallyValid()."
_UNIT_INERTIA_H = (
    "bazel-out/k8-opt/bin/multibody/tree/_virtual_includes/unit_inertia/drake/multibody/tree/"
    "unit_inertia.h"
)


def inertia_error(
    mass: float, com: tuple[float, float, float], inertia: _Matrix
) -> BaseException | None:
    """What MakeFromCentralInertia(mass, com, inertia) raises on Drake <= 1.15, or None.

    ``inertia``: the moments and products about the centre of mass, in the link frame.
    """
    if mass == 0.0 and not inertia.any():
        return None  # N.B. A massless body.
    if not mass > 0:
        return demand_failure(_UNIT_INERTIA_H, 95, "SetFromRotationalInertia", "mass > 0")
    p = np.asarray(com, dtype=float)
    about_p = (inertia / mass + _point_mass(p)) * mass
    central = (about_p / mass - _point_mass(p)) * mass
    if _invalidity(central) is None:
        return None
    x, y, z = (repr(float(c)) for c in com)
    report = (
        f"{_HEADER}\n mass = {mass!r}\n Center of mass = [{x}  {y}  {z}]\n"
        f" Inertia about point P, I_BP =\n{_matrix_text(about_p)}"
    )
    if p.any():
        report += f" Inertia about center of mass, I_BBcm =\n{_matrix_text(central)}"
    a, b, c = _moments(central)
    report += f" Principal moments of inertia about Bcm (center of mass) =\n[{a!r}  {b!r}  {c!r}]\n"
    return ModelParseError(report)


def _matrix_text(inertia: _Matrix) -> str:
    """Rows ``[a  b  c]``, each entry ``%.6g``, right-aligned to the widest."""
    cells = [[f"{float(v):.6g}" for v in row] for row in inertia]
    width = max(len(cell) for row in cells for cell in row)
    return "".join("[" + "  ".join(c.rjust(width) for c in row) + "]\n" for row in cells)


def _moments(inertia: _Matrix) -> list[float]:
    """1.15's CalcPrincipalMomentsOfInertia: the sorted diagonal when every product is
    exactly zero, else the eigenvalues."""
    if inertia[1, 0] == 0 and inertia[2, 0] == 0 and inertia[2, 1] == 0:
        return sorted(float(v) for v in np.diag(inertia))
    return _eigen_eigenvalues(inertia.tolist())
