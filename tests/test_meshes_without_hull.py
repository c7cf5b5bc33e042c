"""A collision mesh Drake cannot make a convex hull of keeps its proximity role, outside the
collision filter (known divergence ``failed-hull-half-registers``).

GeometryState stores the properties before the proximity engine computes the hull, so the
error (here: a ``.stl`` mesh) leaves a geometry that the inspector lists with the role but
that the engine and the filter never got. Every later question about a pair holding it then
fails: the filter's ``unordered_map::at`` (IndexError ``_Map_base::at``), a DRAKE_DEMAND
(SystemExit) when a declaration would write such a pair, and the proximity defaults that
context creation re-applies (RuntimeError). Found on Gepetto/example-robot-data's URDFs,
whose collision meshes are ``.stl``.

That is pydrake up to 1.51.1. Since 1.52 (the filter keeps filtered pairs by id) the pair
questions answer as if the mesh were unfiltered (release fact
unengined-geometry-unfiltered-since-1.52), and since 1.57 a declaration that names it raises
a RuntimeError (unengined-declaration-error-since-1.57); removing the role still raises
IndexError, in its newer library's words (clone-error-wording-since-1.52). Measured on
1.51.1 and 1.52.0-1.58.0; reimpl follows the release it is set to.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from conformance._backends.api import Api
from conformance._policy.release_facts import fact_holds

#: Link ``a`` holds a box and then the ``.stl`` mesh; link ``b`` is never reached.
URDF = (
    '<robot name="r"><link name="a"><collision name="c"><geometry><box size="1 1 1"/>'
    '</geometry></collision><collision name="m"><geometry><mesh filename="a.stl"/></geometry>'
    '</collision></link><link name="b"><collision name="d"><geometry><box size="1 1 1"/>'
    "</geometry></collision></link></robot>\n"
)
HULL_ERROR = (
    "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes; unsupported extension "
    "'.stl' for geometry data: {path}."
)


class Parsed:
    """The URDF parsed until its error: the box ``c`` and the unengined mesh ``m``."""

    def __init__(self, api: Api, folder: Path) -> None:
        assert api.plant is not None
        assert api.parsing is not None
        (folder / "a.stl").write_text("solid a\nendsolid a\n", encoding="utf-8")
        (folder / "r.urdf").write_text(URDF, encoding="utf-8")
        g = api.geometry
        self.g = g
        self.scene_graph = g.SceneGraph()
        self.plant = api.plant.MultibodyPlant(time_step=0.0)
        self.source = self.plant.RegisterAsSourceForSceneGraph(scene_graph=self.scene_graph)
        with pytest.raises(RuntimeError) as info:
            api.parsing.Parser(plant=self.plant).AddModels(file_name=str(folder / "r.urdf"))
        self.error = str(info.value)
        self.inspector = self.scene_graph.model_inspector()
        self.box, self.mesh = self.inspector.GetAllGeometryIds()

    def declaration(self) -> Any:
        return self.g.CollisionFilterDeclaration()


@pytest.fixture
def parsed(api: Api, tmp_path: Path) -> Parsed:
    return Parsed(api, tmp_path)


def _unfiltered(api: Api) -> bool:
    """Whether the release answers pair questions about the mesh (since 1.52)."""
    return fact_holds("unengined-geometry-unfiltered-since-1.52", api.version)


def _refuses_declarations(api: Api) -> bool:
    """Whether a declaration naming the mesh raises RuntimeError (since 1.57)."""
    return fact_holds("unengined-declaration-error-since-1.57", api.version)


def _map_at(api: Api) -> str:
    """libstdc++'s message for a missing key, as the release's wheel was built with."""
    return (
        "unordered_map::at"
        if fact_holds("clone-error-wording-since-1.52", api.version)
        else "_Map_base::at"
    )


def test_the_mesh_keeps_its_proximity_role_after_the_hull_error(
    parsed: Parsed, tmp_path: Path
) -> None:
    assert parsed.error == HULL_ERROR.format(path=tmp_path / "a.stl")
    inspector = parsed.inspector
    assert [inspector.GetName(geometry_id=g) for g in (parsed.box, parsed.mesh)] == ["r::c", "r::m"]
    assert inspector.GetProximityProperties(geometry_id=parsed.mesh) is not None
    assert inspector.NumGeometriesWithRole(role=parsed.g.Role.kProximity) == 2


def test_filter_questions_about_a_pair_with_it_raise_index_error(api: Api, parsed: Parsed) -> None:
    inspector = parsed.inspector
    assert inspector.CollisionFiltered(geometry_id1=parsed.mesh, geometry_id2=parsed.mesh)
    if _unfiltered(api):
        assert inspector.GetCollisionCandidates() == {(parsed.box, parsed.mesh)}
        assert not inspector.CollisionFiltered(geometry_id1=parsed.box, geometry_id2=parsed.mesh)
        return
    with pytest.raises(IndexError, match=r"^_Map_base::at$"):
        inspector.GetCollisionCandidates()
    with pytest.raises(IndexError, match=r"^_Map_base::at$"):
        inspector.CollisionFiltered(geometry_id1=parsed.box, geometry_id2=parsed.mesh)


def test_no_context_can_be_made(parsed: Parsed) -> None:
    with pytest.raises(RuntimeError) as info:
        parsed.scene_graph.CreateDefaultContext()
    assert str(info.value) == (
        f"The proximity engine does not contain a geometry with the id "
        f"{parsed.mesh.get_value()}; its properties cannot be updated"
    )


def test_a_declaration_writing_a_pair_with_it_fails_drakes_demand(api: Api, parsed: Parsed) -> None:
    manager = parsed.scene_graph.collision_filter_manager()
    both = parsed.g.GeometrySet(geometry_ids=[parsed.box, parsed.mesh])
    empty = parsed.g.GeometrySet()
    if _unfiltered(api) and not _refuses_declarations(api):
        # 1.52-1.56: a declaration filters the mesh like any other geometry.
        manager.Apply(declaration=parsed.declaration().ExcludeBetween(set_A=both, set_B=both))
        assert parsed.inspector.GetCollisionCandidates() == set()
        manager.Apply(declaration=parsed.declaration().AllowWithin(geometry_set=both))
        assert parsed.inspector.GetCollisionCandidates() == {(parsed.box, parsed.mesh)}
        return
    if _refuses_declarations(api):
        for declaration in (
            parsed.declaration().AllowWithin(geometry_set=both),
            parsed.declaration().ExcludeBetween(set_A=both, set_B=empty),
        ):
            with pytest.raises(RuntimeError) as refused:
                manager.Apply(declaration=declaration)
            assert str(refused.value) == (
                f"Collision filter declaration references geometry id {parsed.mesh.get_value()} "
                "which has not been registered with this filter system."
            )
        return
    with pytest.raises(SystemExit) as info:
        manager.Apply(declaration=parsed.declaration().AllowWithin(geometry_set=both))
    assert str(info.value) == (
        "Failure at external/drake+/geometry/proximity/collision_filter.cc:197 in "
        "RemoveFilteredPair(): condition 'filter_state.contains(id_A) && "
        "filter_state.contains(id_B)' failed."
    )
    manager.Apply(
        declaration=parsed.declaration().ExcludeBetween(set_A=both, set_B=empty)
    )  # no pair to write: no demand


def test_removing_its_proximity_role_raises_index_error(api: Api, parsed: Parsed) -> None:
    with pytest.raises(IndexError, match=f"^{_map_at(api)}$"):
        parsed.scene_graph.RemoveRole(
            source_id=parsed.source, geometry_id=parsed.mesh, role=parsed.g.Role.kProximity
        )
