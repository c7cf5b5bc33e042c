"""benchmarks/measure_hull_tolerances.py measures real hull scenes on both implementations.

Measured on pydrake 1.51.1 with seed 1: scenes 0-6 put a hull (a Mesh or Convex of a
vendored file) against each of the seven other shapes once; scene 13, Drake's octahedron
(a Convex, scale 0.1) against a half space at a gap of -3.77e-7 m, gives the same depth
and witness points to the bit on both (FCL's convex-halfspace closed form); scene 0, a
jaco finger against a sphere 2e-9 m inside, gives MPR depths 5.2e-9 (pydrake) and 1.0e-7
(reimpl), the two hulls' vertices numbered otherwise, within the ``HULL`` row.
"""

from __future__ import annotations

from types import ModuleType
from typing import Any

import pytest

from conformance._tolerances import HULL
from tests.dropin import benchmark_module

pytest.importorskip("pydrake")


def _script() -> ModuleType:
    return benchmark_module("measure_hull_tolerances")


def _scene(index: int) -> dict[str, Any]:
    script = _script()
    lines = list(script.base._scene_lines(1, index + 1, start=index, script=script.__file__))
    assert len(lines) == 1
    return lines[0]


def test_seven_seeded_scenes_measure_a_hull_against_each_other_shape() -> None:
    report = _script().measure(seed=1, scenes=7)
    assert list(report["pairs"]) == [
        "mesh/convex–sphere",
        "mesh/convex–box",
        "mesh/convex–cylinder",
        "mesh/convex–capsule",
        "mesh/convex–ellipsoid",
        "mesh/convex–mesh/convex",
        "mesh/convex–halfspace",
    ]
    rows = report["pairs"].values()
    assert [row["scenes"] for row in rows] == [1] * 7
    # Penetrating scenes give three records (penetration, both signed distances), separated
    # ones two; the half space's scene 6 (a gap of +1.8e-12 m) none: Drake has no signed
    # distance from a half space to a hull, and the two do not penetrate.
    assert [row["records"] for row in rows] == [3, 2, 2, 3, 2, 3, 0]
    assert all(row["outside"] == row["has_collisions_disagreements"] == 0 for row in rows)
    assert all(row["max_d_disagreeing"] == 0.0 for row in rows)
    assert sum(report["hulls"].values()) == 8


def test_a_hull_against_a_half_space_has_the_same_depth_to_the_bit() -> None:
    line = _scene(13)
    assert line["hulls"] == ["real_models/drake/geometry/test/octahedron.obj"]
    ref = line["pydrake"]["records"]["penetration"]
    other = line["reimpl"]["records"]["penetration"]
    assert ref[0] == other[0]
    assert ref[1] == other[1]
    assert abs(ref[0] + line["gap"]) <= 1e-8
    assert "pair" not in line["pydrake"]["records"]
    assert line["pydrake"]["has_collisions"] is line["reimpl"]["has_collisions"] is True


def test_mpr_depths_of_a_hull_differ_within_the_hull_row() -> None:
    line = _scene(0)
    depth_ref = line["pydrake"]["records"]["penetration"][0]
    depth = line["reimpl"]["records"]["penetration"][0]
    assert depth_ref == pytest.approx(5.18e-9, rel=1e-2)
    assert depth == pytest.approx(1.037e-7, rel=1e-2)
    assert abs(depth - depth_ref) <= HULL.distance
    # The signed distance (GJK/EPA) of the same scene agrees to the bit.
    assert line["pydrake"]["records"]["pair"][0] == line["reimpl"]["records"]["pair"][0]
