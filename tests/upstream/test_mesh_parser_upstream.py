# Ported from Drake: multibody/parsing/test/detail_mesh_parser_test.cc at v1.51.1
# (https://github.com/RobotLocomotion/drake), the cases about naming, the errors and the
# registered geometries of an .obj file added as a one-body model, re-expressed as pytest
# functions that run unchanged on pydrake and on reimpl through the public Parser API.
# Upstream passes a model name and a parent model name to the internal parser; here a
# model directive names the model (add_model's name) and the Parser's model-name prefix is
# the parent. The mass is checked as reimpl keeps it (mass and centre of mass; upstream
# also compares the rotational inertia). Expected values are upstream's, measured on
# pydrake 1.51.1 and 1.58.0 (both give the same answers here).
#
# Drake's license (BSD 3-Clause), which covers the upstream test this file is ported from:
#
#   Copyright 2012-2022, Robot Locomotion Group @ CSAIL, Massachusetts Institute of Technology
#   All rights reserved.
#
#   Redistribution and use in source and binary forms, with or without modification, are
#   permitted provided that the following conditions are met:
#
#   1. Redistributions of source code must retain the above copyright notice, this list of
#      conditions and the following disclaimer.
#   2. Redistributions in binary form must reproduce the above copyright notice, this list of
#      conditions and the following disclaimer in the documentation and/or other materials
#      provided with the distribution.
#   3. Neither the name of the copyright holder nor the names of its contributors may be used
#      to endorse or promote products derived from this software without specific prior
#      written permission.
#
#   THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS" AND ANY
#   EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE IMPLIED WARRANTIES OF
#   MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE DISCLAIMED. IN NO EVENT SHALL THE
#   COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE FOR ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL,
#   EXEMPLARY, OR CONSEQUENTIAL DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF
#   SUBSTITUTE GOODS OR SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION)
#   HOWEVER CAUSED AND ON ANY THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY, OR
#   TORT (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE OF THIS
#   SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
"""Upstream mesh (.obj model) parser tests, on pydrake and reimpl."""

from __future__ import annotations

from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

BOX_OBJ = "multibody/parsing/test/box_package/meshes/box.obj"
#: A 2 x 2 x 2 box too, whose OBJ data names its object "test_box" (and a material library).
NAMED_BOX_OBJ = "geometry/render/test/meshes/box.obj"


class Meshes:
    """A continuous plant (as upstream's), with a SceneGraph only when asked."""

    def __init__(self, drake: ModuleType, scene_graph: bool = False) -> None:
        self.drake = drake
        self.plant = drake.multibody.plant.MultibodyPlant(time_step=0.0)
        self.scene_graph = drake.geometry.SceneGraph() if scene_graph else None
        if self.scene_graph is not None:
            self.plant.RegisterAsSourceForSceneGraph(scene_graph=self.scene_graph)

    def parser(self, prefix: str = "") -> Any:
        parsing = self.drake.multibody.parsing
        if prefix:
            return parsing.Parser(plant=self.plant, model_name_prefix=prefix)
        return parsing.Parser(plant=self.plant)

    def add(self, path: Path, name: str = "", prefix: str = "") -> str:
        """The model instance's name; ``name``, when given, names the model as upstream's
        model_name does (through a model directive)."""
        parser = self.parser(prefix)
        if name:
            directives = f"directives:\n- add_model:\n    name: {name}\n    file: file://{path}\n"
            (instance,) = parser.AddModels(file_contents=directives, file_type="dmd.yaml")
        else:
            (instance,) = parser.AddModels(file_name=str(path))
        return str(self.plant.GetModelInstanceName(model_instance=instance))

    def bodies(self, model: str) -> list[str]:
        plant = self.plant
        instance = plant.GetModelInstanceByName(name=model)
        return [plant.get_body(body_index=b).name() for b in plant.GetBodyIndices(instance)]


def test_a_mesh_model_is_named_by_the_caller_then_its_object_then_its_file(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream ModelInstanceNameTest: a prefix scopes the model's name, not its body's."""
    meshes = Meshes(drake)
    box, named_box = drake_models / BOX_OBJ, drake_models / NAMED_BOX_OBJ
    assert meshes.add(box) == "box"
    with pytest.raises(RuntimeError) as info:
        meshes.add(box)
    assert str(info.value) == (
        "This model already contains a model instance named 'box'. Model instance names must "
        "be unique within a given model."
    )
    added = [
        meshes.add(box, name="box1"),
        meshes.add(box, name="box2", prefix="prefix"),
        meshes.add(box, prefix="prefix"),
        meshes.add(named_box),
        meshes.add(named_box, name="geom_box"),
        meshes.add(named_box, prefix="prefix"),
    ]
    assert added == [
        "box1",
        "prefix::box2",
        "prefix::box",
        "test_box",
        "geom_box",
        "prefix::test_box",
    ]
    assert not meshes.plant.geometry_source_is_registered()
    meshes.plant.Finalize()
    assert meshes.plant.num_model_instances() == 9
    bodies = {model: meshes.bodies(model) for model in ["box", *added]}
    assert bodies == {
        "box": ["box"],
        "box1": ["box1"],
        "prefix::box2": ["box2"],
        "prefix::box": ["box"],
        "test_box": ["test_box"],
        "geom_box": ["geom_box"],
        "prefix::test_box": ["test_box"],
    }


def test_a_mesh_of_several_objects_is_named_by_the_last(drake: ModuleType, tmp_path: Path) -> None:
    """Upstream MultiObjects: two triangles facing away from the origin make a valid body."""
    path = tmp_path / "two_objects.obj"
    path.write_text("v 0 0 1\nv 1 0 1\nv 0 1 1\no one\nf 1 2 3\no two\nf 1 2 3\n")
    assert Meshes(drake).add(path) == "two"


@pytest.mark.parametrize("text", ["v 0 0 0\n", "Non-OBJ gibberish"])
def test_obj_data_without_a_face_is_no_model(drake: ModuleType, tmp_path: Path, text: str) -> None:
    """Upstream ErrorModes 1 and 2: a lone vertex, and text that is no OBJ at all."""
    path = tmp_path / "empty.obj"
    path.write_text(text)
    with pytest.raises(RuntimeError) as info:
        Meshes(drake).add(path)
    assert str(info.value) == (
        "error: The OBJ data parsed contains no objects; the data could be corrupt, empty, "
        f"or not an OBJ file. Name: '{path}'"
    )


def test_obj_data_in_a_string_is_refused(drake: ModuleType) -> None:
    """Upstream ErrorModes 3."""
    meshes = Meshes(drake)  # N.B. pydrake's Parser does not keep its plant alive.
    with pytest.raises(RuntimeError) as info:
        meshes.parser().AddModels(file_contents="Just some text", file_type="obj")
    assert str(info.value) == (
        "Parser does not yet support adding models using in-memory OBJ data. The OBJ data "
        "must be referenced as a file."
    )


def test_a_finalized_plant_takes_no_mesh_model(drake: ModuleType, drake_models: Path) -> None:
    """Upstream ErrorModes 5: the parser's DRAKE_THROW_UNLESS, reported as SystemExit."""
    meshes = Meshes(drake)
    meshes.plant.Finalize()
    with pytest.raises(SystemExit) as info:
        meshes.add(drake_models / BOX_OBJ)
    assert str(info.value) == (
        "Failure at external/drake+/multibody/parsing/detail_mesh_parser.cc:133 in "
        "AddModelFromMesh(): condition '!workspace.plant->is_finalized()' failed."
    )


def test_a_mesh_body_has_the_mass_of_water(drake: ModuleType, drake_models: Path) -> None:
    """Upstream CorrectMass: a 2 x 2 x 2 box at 1000 kg/m³, centred on its frame."""
    meshes = Meshes(drake)
    model = meshes.add(drake_models / BOX_OBJ, name="body")
    meshes.plant.Finalize()
    instance = meshes.plant.GetModelInstanceByName(name=model)
    body = meshes.plant.GetBodyByName(name="body", model_instance=instance)
    assert body.default_mass() == 2 * 2 * 2 * 1000
    assert list(body.default_spatial_inertia().get_com()) == [0.0, 0.0, 0.0]


def test_a_mesh_of_zero_volume_is_an_error(drake: ModuleType, drake_models: Path) -> None:
    """Upstream ZeroVolume."""
    with pytest.raises(RuntimeError) as info:
        Meshes(drake).add(drake_models / "geometry/test/bad_geometry_volume_zero.obj")
    assert str(info.value) == (
        "error: CalcSpatialInertia(): The calculated volume of a triangle surface mesh is 0 "
        "whereas a reasonable positive value of at least 1e-14 was expected. The mesh may have "
        "bad geometry, e.g., it is an open mesh or the winding (order of vertices) of at least "
        "one face does not produce an outward normal."
    )


def test_a_mesh_body_has_one_geometry_per_role(drake: ModuleType, drake_models: Path) -> None:
    """Upstream RegisteredGeometry: illustration, perception and proximity, the proximity
    geometry with nothing but the default property group."""
    meshes = Meshes(drake, scene_graph=True)
    model = meshes.add(drake_models / BOX_OBJ, name="body")
    meshes.plant.Finalize()
    plant, role = meshes.plant, drake.geometry.Role
    body = plant.GetBodyByName(name="body", model_instance=plant.GetModelInstanceByName(model))
    frame_id = plant.GetBodyFrameIdIfExists(body_index=body.index())
    assert frame_id is not None
    assert meshes.scene_graph is not None
    inspector = meshes.scene_graph.model_inspector()
    counts = [
        inspector.NumGeometriesForFrameWithRole(frame_id=frame_id, role=r)
        for r in (role.kIllustration, role.kPerception, role.kProximity)
    ]
    assert counts == [1, 1, 1]
    (geometry_id,) = inspector.GetGeometries(frame_id=frame_id, role=role.kProximity)
    properties = inspector.GetProximityProperties(geometry_id=geometry_id)
    assert properties.GetGroupNames() == {properties.default_group_name()}
    assert inspector.GetName(geometry_id=geometry_id) == "body::collision"
