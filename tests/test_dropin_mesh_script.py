"""A pydrake script on a real robot whose links collide through meshes runs on reimpl.

``examples/mesh_robot_queries.py`` parses Drake's Jaco arm (``drake_models``,
seven ``.obj`` collision meshes, each its convex hull in Drake) beside a static
table and post, poses it in five configurations and prints, per configuration,
HasCollisions, the penetrating pairs with depths, the pairs within 2 cm with
signed distances, and the signed distances to the wrist. It runs in a subprocess
as written and with ``pydrake.`` switched to ``reimpl.`` in its imports: the
two outputs must name the same pairs in the same lines, with every number within
the tolerance of its shape pair (``conformance._tolerances``); the lines checked
below are what pydrake 1.51.1 prints.

Measured against pydrake 1.51.1 with the script's numbers printed to 17
significant digits (``MEASURED``): 56 lines, the same text but for the numbers;
the largest differences are 1.19e-6 (a Mesh-Mesh penetration depth, MPR on the
two hulls, HULL row 1e-2), 4.4e-14 (Mesh-Cylinder depth) and <= 5.6e-17
elsewhere (Mesh-Box, Sphere-Mesh, the signed distances, the point distances).
"""

from __future__ import annotations

import re

import pytest

from conformance._tolerances import tolerance
from tests.dropin import ROOT, as_reimpl, run_script

SCRIPT = (ROOT / "examples" / "mesh_robot_queries.py").read_text()
#: A pair line: names (shapes): depth|distance d; a point line: name (shape) ...: d.
_PAIR = re.compile(r"^  (.+) \((\w+)-(\w+)\): (depth|distance) (-?\d+\.\d+)$")
_POINT = re.compile(r"^  (.+) \((\w+)\) to the wrist: point distance (-?\d+\.\d+)$")


@pytest.fixture(scope="module")
def outputs() -> tuple[str, str]:
    return run_script(SCRIPT), run_script(as_reimpl(SCRIPT))


def _shape(name: str) -> str:
    return name.lower()


def test_the_mesh_script_imports_only_reimpl_once_switched() -> None:
    switched = as_reimpl(SCRIPT)
    assert "pydrake" not in switched
    assert "from reimpl.multibody.parsing import Parser" in switched


def test_the_mesh_script_reports_the_same_pairs_within_the_tolerances(
    outputs: tuple[str, str],
) -> None:
    theirs, mine = (text.splitlines() for text in outputs)
    assert len(mine) == len(theirs) == 56
    numbers = 0
    for want, got in zip(theirs, mine, strict=True):
        pair_want, pair_got = _PAIR.match(want), _PAIR.match(got)
        point_want, point_got = _POINT.match(want), _POINT.match(got)
        if pair_want and pair_got:
            assert pair_want.groups()[:4] == pair_got.groups()[:4]
            row = tolerance(_shape(pair_want[2]), _shape(pair_want[3]))
            assert abs(float(pair_want[5]) - float(pair_got[5])) <= row.distance + 1e-6
            numbers += 1
        elif point_want and point_got:
            assert point_want.groups()[:2] == point_got.groups()[:2]
            row = tolerance(_shape(point_want[2]), "point")
            assert abs(float(point_want[3]) - float(point_got[3])) <= row.distance + 1e-6
            numbers += 1
        else:
            assert got == want
    assert numbers > 40


#: The largest |pydrake 1.51.1 - reimpl| per kind of line and shape pair, as measured (see the
#: module doc), with a margin of 10 (rounded up): a regression check far inside the tolerances.
MEASURED = {
    ("depth", "Mesh-Mesh"): 1.2e-5,
    ("depth", "Mesh-Cylinder"): 5e-13,
    ("depth", "Mesh-Box"): 1e-15,
    ("depth", "Sphere-Mesh"): 1e-15,
    ("distance", "Mesh-Mesh"): 1e-15,
    ("distance", "Mesh-Cylinder"): 1e-15,
    ("distance", "Mesh-Box"): 1e-15,
    ("distance", "Sphere-Mesh"): 1e-15,
    ("point distance", "Mesh"): 1e-15,
    ("point distance", "Box"): 1e-15,
    ("point distance", "Cylinder"): 1e-15,
}
_NUMBER = re.compile(r"\((\S+)\)(?: to the wrist)?: (depth|distance|point distance) (\S+)$")


def test_the_mesh_script_at_full_precision_differs_by_no_more_than_measured() -> None:
    precise = SCRIPT.replace(":.6f}", ":.17g}")
    assert precise != SCRIPT
    theirs = run_script(precise).splitlines()
    mine = run_script(as_reimpl(precise)).splitlines()
    assert len(mine) == len(theirs) == 56
    seen = set()
    for want, got in zip(theirs, mine, strict=True):
        number_want, number_got = _NUMBER.search(want), _NUMBER.search(got)
        if number_want is None or number_got is None:
            assert got == want
            continue
        assert want[: number_want.start(3)] == got[: number_got.start(3)]
        key = (number_want[2], number_want[1])
        assert abs(float(number_want[3]) - float(number_got[3])) <= MEASURED[key], want
        seen.add(key)
    assert seen == set(MEASURED)


@pytest.mark.parametrize("implementation", ["pydrake", "reimpl"])
def test_the_mesh_script_finds_the_measured_contacts(
    outputs: tuple[str, str], implementation: str
) -> None:
    lines = (outputs[0] if implementation == "pydrake" else outputs[1]).splitlines()
    expected = [
        "-- reach: collisions False",
        "-- tangled: collisions True",
        "  j2s7s300_link_2 x j2s7s300_link_base (Mesh-Mesh): depth 0.090189",
        "  j2s7s300_link_3 x top (Mesh-Box): depth 0.144438",
        "  j2s7s300_link_5 x post (Mesh-Cylinder): depth 0.039973",
        "  base x j2s7s300_link_3 (Sphere-Mesh): depth 0.055732",
        "  j2s7s300_link_5 (Mesh) to the wrist: point distance -0.003759",
        "  j2s7s300_link_4 x j2s7s300_link_6 (Mesh-Mesh): distance -0.004452",
    ]
    for line in expected:
        assert line in lines
