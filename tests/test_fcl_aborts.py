"""Where FCL's EPA fails near contact, pydrake raises or answers and reimpl's process aborts.

``tests/data/fcl_epa_abort.py`` is a pydrake script: two anchored shapes a touch apart,
posed bit for bit as scenes of ``benchmarks/measure_tolerances.py --seed 1`` left them,
and ComputeSignedDistancePairClosestPoints, a RuntimeError caught and printed. It runs
in a subprocess as written and with ``pydrake.`` switched to ``reimpl.`` in its imports.
reimpl asks python-fcl (0.7.0.11) for these signed distances; its FCL throws the failure
as a std::logic_error that python-fcl does not translate (its ``distance`` is declared
without ``except +``), so std::terminate ends the process with SIGABRT. Known divergence
``reimpl-fcl-epa-aborts``. Every expectation was measured on pydrake 1.51.1 and 1.58.0
(the same on both) and on reimpl following each. Older releases differ on the pydrake side
only (measured, every release 1.12.0-1.58.0; the suite runs on 1.51.1 and 1.58.0): the
box-ellipsoid scene raises the same RuntimeError on 1.15.0-1.49.0 and is answered since
1.50.0; the message has "by ..., exceeding the threshold ..." since 1.40.0; 1.12.0-1.14.0
do not support either pair.
"""

from __future__ import annotations

import signal
import subprocess
from pathlib import Path

import pytest

from tests.dropin import ROOT, as_reimpl, run_python

SCRIPT = (ROOT / "tests" / "data" / "fcl_epa_abort.py").read_text()
#: FCL's text in the message of both builds (Drake's vendored FCL and python-fcl's).
FCL_TEXT = "validateNearestFeatureOfPolytopeBeingEdge(): The origin is outside of the polytope"
#: The whole of the sentence in Drake's FCL (box-capsule; 1.51.1 and 1.58.0 alike).
DRAKE_FCL_MESSAGE = (
    "validateNearestFeatureOfPolytopeBeingEdge(): The origin is outside of the polytope by "
    "3.01829e-12, exceeding the threshold 4.44089e-16. This should already have been "
    "identified as separating."
)
#: python-fcl's FCL has no threshold in the check or the message.
PYTHON_FCL_MESSAGE = (
    "validateNearestFeatureOfPolytopeBeingEdge(): The origin is outside of the polytope. "
    "This should already have been identified as separating."
)


def _run(script: str, scene: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return run_python(script, scene, cwd=cwd)


def test_the_reimpl_variant_imports_only_reimpl() -> None:
    switched = as_reimpl(SCRIPT)
    assert "from pydrake" not in switched
    assert "from reimpl.geometry import (\n" in switched
    assert "from reimpl.math import RigidTransform, RotationMatrix" in switched


def test_pydrake_raises_runtime_error_with_fcls_message_for_box_capsule(tmp_path: Path) -> None:
    completed = _run(SCRIPT, "box-capsule", tmp_path)
    assert completed.returncode == 0, completed.stderr
    assert completed.stdout.startswith("RuntimeError: Error with configuration\n")
    assert DRAKE_FCL_MESSAGE in completed.stdout
    assert "Box<double>(0.19000000000000000222, 0.050000000000000002776" in completed.stdout


def test_pydrake_answers_box_ellipsoid(tmp_path: Path) -> None:
    completed = _run(SCRIPT, "box-ellipsoid", tmp_path)
    assert completed.returncode == 0, completed.stderr
    assert completed.stdout == "distance: 1.334765759278556e-09\n"


@pytest.mark.parametrize("scene", ["box-capsule", "box-ellipsoid"])
def test_reimpl_is_killed_by_sigabrt_with_fcls_message(scene: str, tmp_path: Path) -> None:
    completed = _run(as_reimpl(SCRIPT), scene, tmp_path)
    assert completed.returncode == -signal.SIGABRT, completed.stderr
    assert completed.stdout == ""
    assert "terminate called after throwing an instance of 'std::logic_error'" in (completed.stderr)
    assert FCL_TEXT in completed.stderr
    assert PYTHON_FCL_MESSAGE in completed.stderr
