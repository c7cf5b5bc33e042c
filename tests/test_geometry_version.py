"""GeometryVersion through the plant: which Finalize asks SceneGraph for a manager.

Handing out a CollisionFilterManager changes the model's proximity version (Drake's
GeometryState; reimpl/geometry/geometry_version.py), and MultibodyPlant asks for one per
default filter statement it makes at Finalize. So the proximity version after Finalize
says whether the plant had a statement to make. Measured on pydrake 1.51.1 and 1.58.0
(identical): the table below.
"""

from __future__ import annotations

import importlib
from types import ModuleType

import pytest

from tests.conftest import IMPLEMENTATIONS


def _inertial() -> str:
    return (
        '<inertial><mass value="1"/>'
        '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
    )


def _link(name: str, collision: bool) -> str:
    sphere = '<geometry><sphere radius="1"/></geometry>'
    geometry = f"<collision>{sphere}</collision><visual>{sphere}</visual>" if collision else ""
    return f'<link name="{name}">{_inertial()}{geometry}</link>'


_JOINT = (
    '<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>'
)
_GROUP = (
    '<drake:collision_filter_group name="g"><drake:member link="a"/><drake:member link="b"/>'
    '<drake:ignored_collision_filter_group name="g"/></drake:collision_filter_group>'
)

#: URDF (None: no model) -> (roles changed by parsing, roles changed by Finalize),
#: each as (proximity, perception, illustration) with X for changed.
FINALIZE_CHANGES = {
    "an empty plant": (None, "---", "---"),
    "two jointed bodies without geometry": (
        f'<robot name="r">{_link("a", False)}{_link("b", False)}{_JOINT}</robot>',
        "---",
        "X--",
    ),
    "two jointed bodies with geometry": (
        f'<robot name="r">{_link("a", True)}{_link("b", True)}{_JOINT}</robot>',
        "X-X",
        "X--",
    ),
    "one free body with geometry": (f'<robot name="r">{_link("a", True)}</robot>', "X-X", "---"),
    "two free bodies in one collision filter group": (
        f'<robot name="r">{_link("a", True)}{_link("b", True)}{_GROUP}</robot>',
        "X-X",
        "---",
    ),
}


def _modules(name: str) -> ModuleType:
    for sub in ("geometry", "systems.framework", "multibody.plant", "multibody.parsing"):
        importlib.import_module(f"{name}.{sub}")
    return importlib.import_module(name)


@pytest.mark.parametrize("implementation", IMPLEMENTATIONS)
@pytest.mark.parametrize("case", list(FINALIZE_CHANGES))
def test_finalize_changes_the_proximity_version_iff_it_declares_filters(
    implementation: str, case: str
) -> None:
    drake = _modules(implementation)
    g = drake.geometry
    roles = (g.Role.kProximity, g.Role.kPerception, g.Role.kIllustration)
    urdf, parse_changes, finalize_changes = FINALIZE_CHANGES[case]
    builder = drake.systems.framework.DiagramBuilder_[float]()
    plant, scene_graph = drake.multibody.plant.AddMultibodyPlantSceneGraph(builder, 0.0)
    inspector = scene_graph.model_inspector()

    def changed(before: object) -> str:
        after = inspector.geometry_version()
        return "".join("-" if before.IsSameAs(other=after, role=r) else "X" for r in roles)  # type: ignore[attr-defined]

    before = g.GeometryVersion(other=inspector.geometry_version())
    if urdf is not None:
        drake.multibody.parsing.Parser(plant).AddModelsFromString(urdf, "urdf")
    assert changed(before) == parse_changes
    before = g.GeometryVersion(other=inspector.geometry_version())
    plant.Finalize()
    assert changed(before) == finalize_changes
