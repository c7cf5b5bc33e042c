"""reimpl defines each binding row's bindings exactly where the release table says.

For every ``binding`` row of conformance/_policy/release_facts.json, reimpl is
run in a subprocess as the release just before the row's ``since`` and as
``since`` itself (``REIMPL_DRAKE_RELEASE``), and a probe of the binding must
find it absent, then present. The probes do what a pydrake script does: look
the name up, or call the overload or keyword (pybind11's TypeError where it is
not bound). The boundaries were measured on pydrake of those releases (see
each row); no old pydrake is needed here.
"""

from __future__ import annotations

import functools
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from conformance._policy.release_facts import FactKind, release_facts

ROOT = Path(__file__).resolve().parent.parent

#: A script that prints, as JSON, whether each binding row's bindings are there.
_PROBE = """
import json
import reimpl.geometry as geometry
import reimpl.multibody.tree as tree
from reimpl.geometry import (
    CollisionFilterManager, FramePoseVector, GeometryFrame, GeometryInstance,
    ProximityProperties, Role, SceneGraph, Sphere,
)
from reimpl.math import RigidTransform
from reimpl.multibody.parsing import Parser
from reimpl.multibody.plant import MultibodyPlant
from reimpl.geometry import QueryObject


def binds(call):
    try:
        call()
    except TypeError:
        return False
    return True


scene_graph = SceneGraph()
source = scene_graph.RegisterSource(name="s")
frames = [
    scene_graph.RegisterFrame(source_id=source, frame=GeometryFrame(f"f{i}")) for i in range(2)
]
for frame in frames:
    geometry_id = scene_graph.RegisterGeometry(
        source_id=source, frame_id=frame,
        geometry=GeometryInstance(X_PG=RigidTransform(), shape=Sphere(1.0), name="g"),
    )
    scene_graph.AssignRole(
        source_id=source, geometry_id=geometry_id, properties=ProximityProperties()
    )
context = scene_graph.CreateDefaultContext()
poses = FramePoseVector()
for frame in frames:
    poses.set_value(id=frame, value=RigidTransform())
scene_graph.get_source_pose_port(source).FixValue(context, poses)
query = scene_graph.get_query_output_port().Eval(context)
plant = MultibodyPlant(time_step=0.0)
print(json.dumps({
    "remove-role-by-frame-since-1.13": binds(lambda: scene_graph.RemoveRole(
        source_id=source, frame_id=frames[0], role=Role.kIllustration)),
    "adjacent-filters-opt-out-since-1.13": hasattr(
        MultibodyPlant, "set_adjacent_bodies_collision_filters"
    ) and hasattr(MultibodyPlant, "get_adjacent_bodies_collision_filters"),
    "parser-model-name-prefix-since-1.13": binds(
        lambda: Parser(plant=plant, model_name_prefix="x")),
    "parser-auto-renaming-since-1.14": hasattr(Parser, "SetAutoRenaming")
    and hasattr(Parser, "GetAutoRenaming"),
    "set-default-context-keyword-since-1.15": binds(
        lambda: scene_graph.SetDefaultContext(context=context)),
    "rename-model-instance-since-1.20": hasattr(MultibodyPlant, "RenameModelInstance"),
    "rpy-floating-joint-since-1.27": hasattr(tree, "RpyFloatingJoint"),
    "filter-groups-report-since-1.31": hasattr(Parser, "GetCollisionFilterGroups"),
    "collision-filter-scope-since-1.42": hasattr(geometry, "CollisionFilterScope"),
    "find-collision-candidates-since-1.48": binds(query.FindCollisionCandidates),
    "activation-since-1.55": hasattr(CollisionFilterManager, "Activate")
    and hasattr(CollisionFilterManager, "Deactivate"),
}))
"""

BINDING_ROWS = sorted(f.id for f in release_facts().values() if f.kind is FactKind.BINDING)


@functools.cache
def _run_as(release: str, code: str) -> subprocess.CompletedProcess[str]:
    """``code`` in a fresh interpreter whose reimpl follows ``release``."""
    env = {**os.environ, "REIMPL_DRAKE_RELEASE": release, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=False
    )


def _bindings_at(release: str) -> dict[str, bool]:
    done = _run_as(release, _PROBE)
    assert done.returncode == 0, done.stderr
    found: dict[str, bool] = json.loads(done.stdout)
    return found


def _boundary(fact_id: str) -> tuple[str, str]:
    """The release before the row's ``since`` (X.Y-1.0) and ``since`` itself (X.Y.0)."""
    since = release_facts()[fact_id].releases.since
    assert since is not None, f"{fact_id}: a binding row without since"
    major, minor = (int(part) for part in since.split(".")[:2])
    return f"{major}.{minor - 1}.0", f"{major}.{minor}.0"


def test_every_binding_row_has_a_probe() -> None:
    assert set(_bindings_at("1.51.1")) == set(BINDING_ROWS)


@pytest.mark.parametrize("fact_id", BINDING_ROWS)
def test_a_binding_is_absent_before_its_release_and_present_from_it(fact_id: str) -> None:
    before, since = _boundary(fact_id)
    assert _bindings_at(before)[fact_id] is False, f"{fact_id} bound on {before}"
    assert _bindings_at(since)[fact_id] is True, f"{fact_id} missing on {since}"


def test_set_default_context_before_1_15_takes_its_context_by_position() -> None:
    """Measured on pydrake 1.14.0: ``SetDefaultContext(context)`` binds (``arg0``)."""
    code = _PROBE.split("plant = MultibodyPlant", maxsplit=1)[0] + (
        "scene_graph.SetDefaultContext(context)\nprint('reset')\n"
    )
    done = _run_as("1.14.0", code)
    assert (done.returncode, done.stdout) == (0, "reset\n"), done.stderr


def test_find_collision_candidates_before_1_48_raises_pybind11_s_conversion_error() -> None:
    """Measured on pydrake 1.45.0: the method is bound, and a pair cannot be converted."""
    code = _PROBE.split("plant = MultibodyPlant", maxsplit=1)[0] + (
        "try:\n    query.FindCollisionCandidates()\nexcept TypeError as e:\n    print(e)\n"
    )
    done = _run_as("1.45.0", code)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith(
        "Unable to convert function return value to a Python type! The signature was\n\t(self: "
    )
    assert done.stdout.rstrip().endswith("-> list[drake::SortedPair<drake::geometry::GeometryId>]")
