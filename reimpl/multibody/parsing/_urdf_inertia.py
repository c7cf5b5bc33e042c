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
to the widest. The moments are the sorted diagonal when the products of
inertia are all within 4ε·tr(I)/2 of zero, else the eigenvalues as Eigen
5.0.1's SelfAdjointEigenSolver computes them (the solver pydrake's wheels are
built with), step for step, so that they print to the same last digit.
"""

from __future__ import annotations

import math

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
    return _eigen_eigenvalues(inertia.tolist())


# ------------------------------------------------- Eigen's symmetric eigensolver
# Eigen 5.0.1, SelfAdjointEigenSolver::compute(EigenvaluesOnly) for a 3x3 matrix:
# scale by the largest |entry| of the lower triangle, tridiagonalize (the 3x3
# closed form), Francis QR steps with a Wilkinson shift, unscale, sort. Written
# as Eigen writes each operation, so each double rounds as it does there.

_MIN_NORMAL = float(np.finfo(float).tiny)
_EPSILON = float(np.finfo(float).eps)


def _eigen_eigenvalues(matrix: list[list[float]]) -> list[float]:
    lower = [[matrix[i][j] if j <= i else 0.0 for j in range(3)] for i in range(3)]
    scale = max(abs(v) for row in lower for v in row)
    if scale == 0:
        scale = 1.0
    m = [[v / scale for v in row] for row in lower]
    diag, sub = _tridiagonalize(m)
    _qr_iterations(diag, sub)
    values = [d * scale for d in diag]
    for i in range(2):  # N.B. Eigen's selection sort by the first minimum.
        rest = values[i:]
        k = rest.index(min(rest))
        if k > 0:
            values[i], values[i + k] = values[i + k], values[i]
    return values


def _tridiagonalize(m: list[list[float]]) -> tuple[list[float], list[float]]:
    """tridiagonalization_inplace_selector<MatrixType, 3, false>::run."""
    diag = [m[0][0], 0.0, 0.0]
    v1norm2 = m[2][0] * m[2][0]
    if v1norm2 <= _MIN_NORMAL:
        diag[1], diag[2] = m[1][1], m[2][2]
        return diag, [m[1][0], m[2][1]]
    beta = math.sqrt(m[1][0] * m[1][0] + v1norm2)
    inv_beta = 1.0 / beta
    m01 = m[1][0] * inv_beta
    m02 = m[2][0] * inv_beta
    q = 2.0 * m01 * m[2][1] + m02 * (m[2][2] - m[1][1])
    diag[1] = m[1][1] + m02 * q
    diag[2] = m[2][2] - m02 * q
    return diag, [beta, m[2][1] - m01 * q]


def _qr_iterations(diag: list[float], sub: list[float]) -> None:
    """computeFromTridiagonal_impl, without the sort (30 iterations per row at most)."""
    n, end, start, iterations = 3, 2, 0, 0
    precision_inv = 1.0 / _EPSILON
    while end > 0:
        for i in range(start, end):
            if abs(sub[i]) < _MIN_NORMAL:
                sub[i] = 0.0
            else:
                scaled = precision_inv * sub[i]
                if scaled * scaled <= abs(diag[i]) + abs(diag[i + 1]):
                    sub[i] = 0.0
        while end > 0 and sub[end - 1] == 0:
            end -= 1
        if end <= 0:
            break
        iterations += 1
        if iterations > 30 * n:
            break
        start = end - 1
        while start > 0 and sub[start - 1] != 0:
            start -= 1
        _qr_step(diag, sub, start, end)


def _qr_step(diag: list[float], sub: list[float], start: int, end: int) -> None:
    """tridiagonal_qr_step: one Francis step with a Wilkinson shift."""
    td = (diag[end - 1] - diag[end]) * 0.5
    e = sub[end - 1]
    mu = diag[end]
    if td == 0:
        mu -= abs(e)
    elif e != 0:
        e2 = e * e
        h = _hypot(td, e)
        if e2 == 0:
            mu -= e / ((td + (h if td > 0 else -h)) / e)
        else:
            mu -= e2 / (td + (h if td > 0 else -h))
    x = diag[start] - mu
    z = sub[start]
    k = start
    while k < end and z != 0:
        c, s = _givens(x, z)
        sdk = s * diag[k] + c * sub[k]
        dkp1 = s * sub[k] + c * diag[k + 1]
        diag[k] = c * (c * diag[k] - s * sub[k]) - s * (c * sub[k] - s * diag[k + 1])
        diag[k + 1] = s * sdk + c * dkp1
        sub[k] = c * sdk - s * dkp1
        if k > start:
            sub[k - 1] = c * sub[k - 1] - s * z
        x = sub[k]
        if k < end - 1:
            z = -s * sub[k + 1]
            sub[k + 1] = c * sub[k + 1]
        k += 1


def _hypot(x: float, y: float) -> float:
    """Eigen's positive_real_hypot of |x|, |y|."""
    x, y = abs(x), abs(y)
    p = max(x, y)
    if p == 0:
        return 0.0
    qp = min(y, x) / p
    return p * math.sqrt(1.0 + qp * qp)


def _givens(p: float, q: float) -> tuple[float, float]:
    """JacobiRotation::makeGivens for reals: (c, s)."""
    if q == 0:
        return (-1.0 if p < 0 else 1.0), 0.0
    if p == 0:
        return 0.0, (1.0 if q < 0 else -1.0)
    if abs(p) > abs(q):
        t = q / p
        u = math.sqrt(1.0 + t * t)
        if p < 0:
            u = -u
        c = 1.0 / u
        return c, -t * c
    t = p / q
    u = math.sqrt(1.0 + t * t)
    if q < 0:
        u = -u
    s = -1.0 / u
    return -t * s, s


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
