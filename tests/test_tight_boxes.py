"""A Mesh's or Convex's broadphase box from Drake 1.58 on (``proximity.tight_aabb``).

Drake 1.58's FCL bounds a turned shape by ``p + R·c ± |R|·h`` per world axis, where c and h
are the centre and half-extents of its local box; a hull's local box is its vertices' box,
whose centre need not be the frame's origin. The arithmetic is checked by hand below, and
the fuzz finding that showed reimpl keeping the old box (``tests/data/mesh_tight_box.json``:
a capsule met a turned ``two_tets.vtk`` mesh in reimpl only) runs on both implementations:
on pydrake 1.51.1 the pair is a candidate, on 1.58.0 it is not (CI's newest-Drake step).
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from conformance.cli.main import EXIT_OK, main
from reimpl.geometry.proximity.tight_aabb import local_box, overlapping_pairs

FINDING = Path(__file__).parent / "data" / "mesh_tight_box.json"
#: A hull whose vertices' box is centred at c = (1, 2, 3) with half-extents h = (1, 2, 3).
HULL = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 0.0, 6.0]])
#: A quarter turn about z: R·c = (-2, 1, 3) and |R|·h = (2, 1, 3), so the hull's box is
#: x ∈ [-4, 0], y ∈ [0, 2], z ∈ [0, 6].
QUARTER_TURN = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


def test_a_hulls_local_box_is_its_vertices_box() -> None:
    assert local_box("Convex", (), HULL) == ((1.0, 2.0, 3.0), (1.0, 2.0, 3.0))
    assert local_box("Sphere", (0.5,)) == ((0.0, 0.0, 0.0), (0.5, 0.5, 0.5))
    assert local_box("HalfSpace", ()) is None


def _pairs(sphere_at: tuple[float, float, float]) -> list[tuple[int, int]]:
    boxes = [local_box("Convex", (), HULL), local_box("Sphere", (0.5,))]
    R_WG = np.stack([QUARTER_TURN, np.eye(3)])
    p_WG = np.array([[0.0, 0.0, 0.0], sphere_at])
    return overlapping_pairs([(0, 1)], boxes, [True, True], R_WG, p_WG)


def test_a_turned_hulls_box_is_about_its_turned_centre() -> None:
    # x ∈ [0.5, 1.5]: outside the hull's box, though inside the box centred at the origin.
    assert _pairs((1.0, 1.0, 1.0)) == []
    # x ∈ [-1.5, -0.5], y ∈ [0.5, 1.5], z ∈ [0.5, 1.5]: inside.
    assert _pairs((-1.0, 1.0, 1.0)) == [(0, 1)]


def test_the_fuzz_finding_of_a_turned_mesh_passes_on_both_implementations() -> None:
    out, err = io.StringIO(), io.StringIO()
    code = main(["run", str(FINDING), "-q"], out=out, err=err)
    assert code == EXIT_OK, out.getvalue() + err.getvalue()
    assert "1 pass, 0 fail, 0 xfail, 0 skip" in out.getvalue()
