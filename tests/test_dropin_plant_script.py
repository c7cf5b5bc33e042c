"""A pydrake script that builds a plant from model files runs unchanged on reimpl.

``examples/cell_from_models.py`` is an ordinary pydrake script: a DiagramBuilder
with ``AddMultibodyPlantSceneGraph``, two prefixed copies of a URDF arm with a
collision filter group, an SDFormat bin with a nested model and a group, a
world-welded floor, an ``RpyFloatingJoint`` tool, ``Finalize``, a filter
declared on a diagram context on top of the parsed model, and three caught
errors. It runs in a subprocess as written and with ``pydrake.`` switched to
``reimpl.`` in its imports; the outputs (candidate sets by scoped name
included) must be identical, and the lines below are what pydrake 1.51.1
prints.
"""

from __future__ import annotations

import pytest

from tests.dropin import ROOT, as_reimpl, run_script

SCRIPT = (ROOT / "examples" / "cell_from_models.py").read_text()


@pytest.fixture(scope="module")
def outputs() -> tuple[str, str]:
    return run_script(SCRIPT), run_script(as_reimpl(SCRIPT))


def test_reimpl_variant_imports_only_reimpl() -> None:
    switched = as_reimpl(SCRIPT)
    assert "pydrake" not in switched
    assert "from reimpl.multibody.parsing import Parser" in switched
    assert "from reimpl.multibody.plant import AddMultibodyPlantSceneGraph" in switched


def test_plant_script_outputs_are_identical(outputs: tuple[str, str]) -> None:
    pydrake_out, reimpl_out = outputs
    assert len(pydrake_out.splitlines()) > 130
    assert reimpl_out == pydrake_out


@pytest.mark.parametrize("implementation", ["pydrake", "reimpl"])
def test_plant_script_prints_the_measured_lines(
    outputs: tuple[str, str], implementation: str
) -> None:
    lines = (outputs[0] if implementation == "pydrake" else outputs[1]).splitlines()
    expected = [
        "models: ['left::arm', 'right::arm', 'bin', 'bin::lid']",
        "bin groups: {'bin::all': ['bin::lid::panel', 'bin::tray']}",
        "bin exclusions: [('bin::all', 'bin::all')]",
        "bodies: 12 models: 6",
        "joints: ['elbow', 'elbow', 'hinge', 'shoulder', 'shoulder', 'tool_float', "
        "'world_welds_to_base', 'world_welds_to_base', 'world_welds_to_tray', 'wrist', 'wrist']",
        "welded to left hand: ['fore', 'hand']",
        "left hand geometries: ['left::arm::finger', 'left::arm::palm']",
        "world frame: True",
        # 12 bodies, 16 proximity geometries; adjacency, welds to the world, the
        # arm's group and the bin's group leave 68 of the 120 pairs.
        "after Finalize: 68 pairs",
        # Excluding left hand × right hand (2 × 2 geometries) in the context.
        "context: 64 pairs",
        "late adjacency flag: Post-finalize calls to 'set_adjacent_bodies_collision_filters()' "
        "are not allowed; calls to this method must happen before Finalize().",
        "unknown link: <literal-string>.urdf:2: error: body with name 'arm::claw' not found",
    ]
    for line in expected:
        assert line in lines
    # The RpyFloatingJoint's two bodies are filtered (only QuaternionFloatingJoint is skipped),
    # and the world-welded bases never meet the floor.
    assert not any("right::arm::hand/" in line and "right::arm::tool/" in line for line in lines)
    assert not any("world/floor" in line and "::base/" in line for line in lines)
    assert "  bin::tray/bin::bottom - left::arm::fore/left::arm::Cylinder" in lines
