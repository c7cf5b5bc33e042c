"""The broadphase boxes of Drake 1.58 and later: a rotated shape's box is |R|·h per axis.

Drake 1.58.0 updated its FCL (drake#25006), whose ``computeAABB`` bounds a
rotated shape's local box (centre 0, half-extents h) by ``|R|·h`` per world
axis (FCL issue #509); up to 1.57 a rotated shape's box was a cube of
half-width |h| (a sphere's r). An identity rotation (within 1e-12, Eigen's
``isIdentity``) keeps the local box; half spaces are unchanged (release fact
rotated-aabb-tight-since-1.58; measured on 24,300 swept scenes and 150
random 24-geometry scenes of 1.51.1, 1.52.0-1.57.0 and 1.58.0).

``overlapping_pairs`` keeps the pairs an older broadphase met whose new
boxes overlap, in that order, and adds the pairs only the new boxes meet.

============  =====================
FCL shape     local half-extents h
============  =====================
Sphere        (r, r, r)
Box           (w/2, d/2, h/2)
Cylinder      (r, r, l/2)
Capsule       (r, r, l/2 + r)
Ellipsoid     (a, b, c)
============  =====================
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt

__all__ = ["half_extents", "overlapping_pairs"]

Array = npt.NDArray[np.float64]

#: FCL shape name → its local half-extents from the engine's measures.
_HALF_EXTENTS: dict[str, Callable[[tuple[float, ...]], tuple[float, float, float]]] = {
    "Sphere": lambda m: (m[0], m[0], m[0]),
    "Box": lambda m: (m[0], m[1], m[2]),
    "Cylinder": lambda m: (m[0], m[0], m[1]),
    "Capsule": lambda m: (m[0], m[0], m[1] + m[0]),
    "Ellipsoid": lambda m: (m[0], m[1], m[2]),
}


def half_extents(kind: str, measures: tuple[float, ...]) -> tuple[float, float, float] | None:
    """A shape's local half-extents h (None for a shape whose box does not change)."""
    rule = _HALF_EXTENTS.get(kind)
    return None if rule is None else rule(measures)


def overlapping_pairs(
    met: Sequence[tuple[int, int]],
    kinds: Sequence[tuple[str, tuple[float, ...]]],
    dynamic: Sequence[bool],
    R_WG: Array,
    p_WG: Array,
) -> list[tuple[int, int]]:
    """The pairs whose 1.58 boxes overlap: ``met`` (the older broadphase's pairs, slot pairs)
    that still do, in order, then every other dynamic × dynamic or dynamic × anchored pair
    that does. A pair with a shape of unchanged box (a half space) stays as met."""
    h = [half_extents(kind, measures) for kind, measures in kinds]
    boxed = np.array([x is not None for x in h], dtype=bool)
    H = np.array([x if x is not None else (0.0, 0.0, 0.0) for x in h], dtype=float).reshape(-1, 3)
    identity = np.all(np.abs(R_WG - np.eye(3)) <= 1e-12, axis=(1, 2))
    half = np.where(identity[:, None], H, np.einsum("nij,nj->ni", np.abs(R_WG), H))
    lo, hi = p_WG - half, p_WG + half

    def overlap(a: int, b: int) -> bool:
        if not (boxed[a] and boxed[b]):
            return True  # kept as the older broadphase met it
        return bool(np.all(lo[a] <= hi[b]) and np.all(lo[b] <= hi[a]))

    kept = [(a, b) for a, b in met if overlap(a, b)]
    seen = {(min(a, b), max(a, b)) for a, b in met}
    n = len(kinds)
    for a in range(n):
        for b in range(a + 1, n):
            if (a, b) in seen or not (dynamic[a] or dynamic[b]):
                continue
            if boxed[a] and boxed[b] and overlap(a, b):
                kept.append((a, b) if dynamic[a] else (b, a))
    return kept
