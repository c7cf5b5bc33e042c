"""A pydrake script that poses a MultibodyPlant and queries its SceneGraph runs on reimpl.

``examples/posed_plant_queries.py`` builds the plant in a diagram with
``AddMultibodyPlantSceneGraph`` from a URDF arm and an SDFormat ball, moves it
(``set_angle``, ``SetPositions``, ``SetFreeBodyPose``) and queries through the
SceneGraph's query port and the plant's geometry query input. It runs in a
subprocess as written and with ``pydrake.`` switched to ``reimpl.`` in its
imports; the outputs must be identical, and the lines below are what pydrake
1.51.1 prints.
"""

from __future__ import annotations

import pytest

from tests.dropin import ROOT, as_reimpl, run_script

SCRIPT = (ROOT / "examples" / "posed_plant_queries.py").read_text()


@pytest.fixture(scope="module")
def outputs() -> tuple[str, str]:
    return run_script(SCRIPT), run_script(as_reimpl(SCRIPT))


def test_reimpl_variant_imports_only_reimpl() -> None:
    switched = as_reimpl(SCRIPT)
    assert "pydrake" not in switched
    assert "from reimpl.multibody.plant import AddMultibodyPlantSceneGraph" in switched


def test_posed_script_outputs_are_identical(outputs: tuple[str, str]) -> None:
    pydrake_out, reimpl_out = outputs
    assert len(pydrake_out.splitlines()) == 23
    assert reimpl_out == pydrake_out


@pytest.mark.parametrize("implementation", ["pydrake", "reimpl"])
def test_posed_script_prints_the_measured_lines(
    outputs: tuple[str, str], implementation: str
) -> None:
    lines = (outputs[0] if implementation == "pydrake" else outputs[1]).splitlines()
    expected = [
        "default q: [0.000000, 0.000000, 1.000000, 0.000000, 0.000000, 0.000000, 0.400000, "
        "0.000000, 0.800000]",
        # X_WH = X_W,shoulder * R_y(0) * X_upper,elbow (rpy 0 0.3 0) * (0, 0, 0.4).
        "hand at q=0: [0.118208, 0.000000, 0.982135]",
        "-- arm up: collisions False",
        "palm X_WG: [0.372816, 0.000000, 0.744943]",
        "-- elbow 0.9: collisions True",
        "  arm::palm x ball::ball: depth 0.098598",
        "  arm::fore ~ ball::ball: distance -0.036082",
        # SetFreeBodyPose wrote the quaternion of R_z(0.5): [cos 0.25, 0, 0, sin 0.25].
        "q: [1.270796, 0.000000, 0.968912, 0.000000, 0.000000, 0.247404, 0.500000, 0.120000, "
        "0.090000]",
        "  arm::floor x ball::ball: depth 0.010000",
        "  arm::upper ~ ball::ball: distance 0.049395",
        "palm to ball: 0.266523",
    ]
    for line in expected:
        assert line in lines
