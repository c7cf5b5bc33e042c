"""Drake's sphere–sphere closed forms for many pairs at once, vectorised with numpy.

One concept: the Sphere–Sphere rows of ``narrowphase`` (through
``distance_to_point``'s sphere), for a stack of pairs (A, B), A the lower id,
with the same operations in the same order as the one-pair path, so the same
bits. With Q = Ao and G = B:

* ``p_GQ = R_WBᵀ·p_WQ + R_WBᵀ·(−p_WB)``, ``∇φ_G = p_GQ/|p_GQ|`` (+x within
  1e-14·max(1, r_B) of the centre), ``N = r_B·∇φ_G``,
  ``φ_B(Q) = (p_GQ − N)·∇φ_G``, ``∇φ_W = R_WB·∇φ_G``;
* penetration: ``depth = r_A − φ_B(Q)`` (None below zero),
  ``p_WCa = p_WA − r_A·∇φ_W``, ``p_WCb = R_WB·N + p_WB``, ``nhat_BA_W = ∇φ_W``;
* signed distance: ``φ = φ_B(Q) − r_A``, ``p_ACa = −r_A·R_WAᵀ·∇φ_W``,
  ``p_BCb = N``, ``nhat_BA_W = ∇φ_W``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from reimpl.geometry.proximity.narrowphase import PairResult, PosedGeometry
from reimpl.geometry.proximity.transforms import Array

__all__ = ["sphere_sphere"]


def sphere_sphere(
    pairs: Sequence[tuple[int, int]],
    bodies: Sequence[PosedGeometry],
    R_WG: Array,
    p_WG: Array,
    *,
    penetration: bool,
) -> list[PairResult | None]:
    """Each pair's penetration (None if separated) or signed distance, in order; ``pairs``
    index ``bodies`` and the stacked X_WG (``R_WG``, ``p_WG``), A the lower id."""
    a = np.array([p[0] for p in pairs])
    b = np.array([p[1] for p in pairs])
    r_A = np.array([bodies[i].m[0] for i in a])
    r_B = np.array([bodies[i].m[0] for i in b])
    R, pB, pA = R_WG[b], p_WG[b], p_WG[a]

    def rot_t(v: Array) -> list[Array]:
        return [
            R[:, 0, j] * v[:, 0] + R[:, 1, j] * v[:, 1] + R[:, 2, j] * v[:, 2] for j in range(3)
        ]

    q1, q2 = rot_t(pA), rot_t(pB * -1.0)
    q = np.stack([q1[j] + q2[j] for j in range(3)], axis=1)
    dist = np.sqrt(q[:, 0] * q[:, 0] + q[:, 1] * q[:, 1] + q[:, 2] * q[:, 2])
    inside = ~(dist > np.maximum(1.0, r_B) * 1e-14)
    with np.errstate(invalid="ignore", divide="ignore"):
        grad = q / dist[:, None]
    grad[inside] = (1.0, 0.0, 0.0)
    N = grad * r_B[:, None]
    d = q - N
    phi = d[:, 0] * grad[:, 0] + d[:, 1] * grad[:, 1] + d[:, 2] * grad[:, 2]
    grad_W = np.stack(
        [
            R[:, i, 0] * grad[:, 0] + R[:, i, 1] * grad[:, 1] + R[:, i, 2] * grad[:, 2]
            for i in range(3)
        ],
        axis=1,
    )
    ids = [(bodies[i].id, bodies[j].id) for i, j in pairs]
    if penetration:
        depth = r_A - phi
        p_WCa = pA - grad_W * r_A[:, None]
        RN = np.stack(
            [R[:, i, 0] * N[:, 0] + R[:, i, 1] * N[:, 1] + R[:, i, 2] * N[:, 2] for i in range(3)],
            axis=1,
        )
        vectors = np.stack([p_WCa, RN + pB, grad_W], axis=1)
        values = depth.tolist()
        return [
            None if value < 0 else PairResult(id_A, id_B, value, vectors[k])
            for k, ((id_A, id_B), value) in enumerate(zip(ids, values, strict=True))
        ]
    RA = R_WG[a]
    p_ACa = np.stack(
        [
            (RA[:, 0, j] * grad_W[:, 0] + RA[:, 1, j] * grad_W[:, 1] + RA[:, 2, j] * grad_W[:, 2])
            * -r_A
            for j in range(3)
        ],
        axis=1,
    )
    vectors = np.stack([p_ACa, N, grad_W], axis=1)
    values = (phi - r_A).tolist()
    return [
        PairResult(id_A, id_B, value, vectors[k])
        for k, ((id_A, id_B), value) in enumerate(zip(ids, values, strict=True))
    ]
