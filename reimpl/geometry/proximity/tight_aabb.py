"""The broadphase boxes of Drake 1.58 and later: a rotated shape's box is |R|·h per axis.

Drake 1.58.0 updated its FCL (drake#25006), whose ``computeAABB`` bounds a
rotated shape's local box (centre c, half-extents h) by ``p + R·c ± |R|·h``
per world axis (FCL issue #509); up to 1.57 a rotated shape's box was a cube
of half-width |h| around ``p + R·c`` (a sphere's r). A primitive's local box
is centred (c = 0); a Convex's (a Mesh's or Convex's hull) is the box of its
vertices, whose centre is where the vertices put it. An identity rotation (within 1e-12, Eigen's
``isIdentity``) keeps the local box (release fact rotated-aabb-tight-since-1.58; measured on
24,300 swept scenes and 150 random 24-geometry scenes of 1.51.1, 1.52.0-1.57.0 and 1.58.0).

A half space's box is FCL's, unchanged by the update but now met by tighter boxes
(``half_space_box``): unbounded, except that when its world normal n = R·ẑ lies exactly
along an axis i the box stops at d = n·p on that axis (hi_i = d for n_i > 0, lo_i = −d
for n_i < 0). So a capsule lying 0.06 above a floor ({z ≤ 0}, identity pose), turned
90° about y, is no candidate of it on 1.58 while its 1.57 cube reached below the floor
(measured on pydrake 1.51.1 and 1.58.0: dm_control's hopper foot, swimmer and walker;
a tilted or flipped half space, whose n has a component of 1e-16, meets everything).

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
Convex        the vertices' box
============  =====================
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt

__all__ = ["HALF_SPACE", "half_extents", "half_space_box", "local_box", "overlapping_pairs"]

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


#: A shape's local box: (centre c, half-extents h) in its own frame.
LocalBox = tuple[tuple[float, float, float], tuple[float, float, float]]


def local_box(
    kind: str, measures: tuple[float, ...], vertices: Array | None = None
) -> LocalBox | None:
    """A shape's local box (None for a shape whose box does not change, a half space): a
    primitive's is centred, a Convex's is the box of its ``vertices``."""
    if kind == "Convex" and vertices is not None and len(vertices):
        low, high = vertices.min(axis=0), vertices.max(axis=0)
        c, h = (low + high) / 2.0, (high - low) / 2.0
        return (float(c[0]), float(c[1]), float(c[2])), (float(h[0]), float(h[1]), float(h[2]))
    h3 = half_extents(kind, measures)
    return None if h3 is None else ((0.0, 0.0, 0.0), h3)


#: The kind name of FCL's half space (its box is ``half_space_box``'s, not a local box's).
HALF_SPACE = "Halfspace"


def half_space_box(R_WG: Array, p_WG: Array) -> tuple[Array, Array]:
    """FCL's world box (lo, hi) of the half space {z ≤ 0 in G} posed at (R_WG, p_WG): the
    normal n = R_WG·ẑ, d = n·p_WG; unbounded unless n lies exactly along one axis i, where
    the box stops at hi_i = d (n_i > 0) or lo_i = −d (n_i < 0)."""
    lo, hi = np.full(3, -np.inf), np.full(3, np.inf)
    n = R_WG[:, 2]
    d = float(n @ p_WG)
    for i in range(3):
        if n[(i + 1) % 3] == 0.0 and n[(i + 2) % 3] == 0.0:
            if n[i] > 0:
                hi[i] = d
            elif n[i] < 0:
                lo[i] = -d
            break
    return lo, hi


def overlapping_pairs(
    met: Sequence[tuple[int, int]],
    boxes: Sequence[LocalBox | None],
    dynamic: Sequence[bool],
    R_WG: Array,
    p_WG: Array,
    *,
    half_spaces: Sequence[bool] | None = None,
) -> list[tuple[int, int]]:
    """The pairs whose 1.58 boxes overlap: ``met`` (the older broadphase's pairs, slot pairs)
    that still do, in order, then every other dynamic × dynamic or dynamic × anchored pair
    that does. ``boxes`` holds each shape's ``local_box``; ``half_spaces`` marks the half
    spaces, whose box is ``half_space_box``'s. A pair with a shape of neither (None, not a
    half space) stays as met. A half space's box is the same as before, so it only drops
    met pairs (a 1.58 box lies inside the older cube)."""
    spaces = np.zeros(len(boxes), dtype=bool) if half_spaces is None else np.array(half_spaces)
    boxed = np.array([x is not None for x in boxes], dtype=bool)
    C = np.array([x[0] if x is not None else (0.0, 0.0, 0.0) for x in boxes], dtype=float)
    H = np.array([x[1] if x is not None else (0.0, 0.0, 0.0) for x in boxes], dtype=float)
    C, H = C.reshape(-1, 3), H.reshape(-1, 3)
    identity = np.all(np.abs(R_WG - np.eye(3)) <= 1e-12, axis=(1, 2))
    half = np.where(identity[:, None], H, np.einsum("nij,nj->ni", np.abs(R_WG), H))
    centre = p_WG + np.einsum("nij,nj->ni", R_WG, C)
    lo, hi = centre - half, centre + half
    for i in np.flatnonzero(spaces):
        lo[i], hi[i] = half_space_box(R_WG[i], p_WG[i])
    bounded = boxed | spaces

    def overlap(a: int, b: int) -> bool:
        if not (bounded[a] and bounded[b]):
            return True  # kept as the older broadphase met it
        return bool(np.all(lo[a] <= hi[b]) and np.all(lo[b] <= hi[a]))

    kept = [(a, b) for a, b in met if overlap(a, b)]
    seen = {(min(a, b), max(a, b)) for a, b in met}
    n = len(boxes)
    for a in range(n):
        for b in range(a + 1, n):
            if (a, b) in seen or not (dynamic[a] or dynamic[b]):
                continue
            if boxed[a] and boxed[b] and overlap(a, b):
                kept.append((a, b) if dynamic[a] else (b, a))
    return kept
