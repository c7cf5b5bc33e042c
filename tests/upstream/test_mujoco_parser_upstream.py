# Ported from Drake: multibody/parsing/test/detail_mujoco_parser_test.cc at v1.51.1
# (https://github.com/RobotLocomotion/drake), the cases about model structure (model
# instances, bodies, frames, joints and their types, geometries with their shapes, poses,
# roles and colours, collision filters), masses where reimpl keeps them, and the parse
# errors and warnings, re-expressed as pytest functions that run unchanged on pydrake and on
# reimpl through the public Parser API.
#
# Upstream drives the internal parser with a diagnostic policy that records every error and
# goes on; through the public Parser the first error is raised (with Drake's whole message,
# measured on pydrake 1.51.1 and 1.58.0), so a case with several errors is split into one
# case per error, and warnings are read from the "drake" logger. Upstream passes a model
# name beside the text; here the text names its model (<mujoco model>). Left out: gravity
# (Option; reimpl's plant has no gravity field), actuators' effort limits, gear ratios, rotor
# inertias and gains, ball constraints, rotational inertias (reimpl keeps mass and centre of
# mass), cameras with a DiagramBuilder (Drake adds RgbdSensors; reimpl refuses), the
# dm_control models (CartPole, Acrobot, Visualize: not vendored), and the convex-hull
# fallback of a planar mesh (BadMeshSpatialInertiaTotalFail: reimpl refuses it; the fallback
# case is kept with a vendored mesh of zero volume instead of MuJoCo Menagerie's).
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
"""Upstream MuJoCo (MJCF) parser tests, on pydrake and reimpl."""

from __future__ import annotations

import logging
import math
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

BOX_OBJ = "multibody/parsing/test/box_package/meshes/box.obj"
NON_CONVEX_OBJ = "geometry/test/non_convex_mesh.obj"
MUJOCO_TEST = "multibody/parsing/test/mujoco_parser_test"
#: How Drake's MuJoCo parser names model text in its messages (sic: ``urdf``).
TEXT = "<literal-string>.urdf"


class Mjcf:
    """A discrete plant (0.1 s, as upstream's fixture) with a SceneGraph, and a Parser."""

    def __init__(self, drake: ModuleType, scene_graph: bool = True) -> None:
        self.drake = drake
        self.plant = drake.multibody.plant.MultibodyPlant(time_step=0.1)
        self.scene_graph = drake.geometry.SceneGraph() if scene_graph else None
        if self.scene_graph is not None:
            self.plant.RegisterAsSourceForSceneGraph(scene_graph=self.scene_graph)
        self.parser = drake.multibody.parsing.Parser(plant=self.plant)

    def add(self, text: str) -> list[str]:
        added = self.parser.AddModels(file_contents=text, file_type="xml")
        return [self.plant.GetModelInstanceName(model_instance=i) for i in added]

    def file(self, path: Path) -> list[str]:
        added = self.parser.AddModels(file_name=str(path))
        return [self.plant.GetModelInstanceName(model_instance=i) for i in added]

    def error(self, text: str, kind: type[BaseException] = RuntimeError) -> str:
        with pytest.raises(kind) as info:
            self.add(text)
        return str(info.value)

    # ------------------------------------------------------------ geometries
    @property
    def inspector(self) -> Any:
        assert self.scene_graph is not None
        return self.scene_graph.model_inspector()

    def world_geometry(self, name: str, role: Any) -> Any:
        inspector = self.inspector
        return inspector.GetGeometryIdByName(
            frame_id=inspector.world_frame_id(), role=role, name=name
        )

    def roles(self, name: str) -> list[Any]:
        """The roles under which the world holds a geometry named ``name``."""
        role = self.drake.geometry.Role
        found = []
        for each in (role.kProximity, role.kIllustration, role.kPerception):
            try:
                self.world_geometry(name, each)
            except RuntimeError:
                continue
            found.append(each)
        return found

    def body(self, name: str) -> Any:
        return self.plant.GetBodyByName(name=name)


def _rotation(drake: ModuleType, axis: list[float], angle: float) -> Any:
    """R about ``axis`` by ``angle`` (Rodrigues), as a RotationMatrix."""
    a = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    R = np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K
    return drake.math.RotationMatrix(R=R)


def _pose(drake: ModuleType, R: Any, p: list[float]) -> Any:
    return drake.math.RigidTransform(R=R, p=np.asarray(p, dtype=float))


@pytest.fixture
def drake_log(caplog: pytest.LogCaptureFixture) -> Iterator[pytest.LogCaptureFixture]:
    with caplog.at_level(logging.WARNING, logger="drake"):
        yield caplog


def warnings(caplog: pytest.LogCaptureFixture) -> list[str]:
    """The messages logged to the "drake" logger (pydrake's and reimpl's warnings)."""
    return [r.getMessage() for r in caplog.records if r.name == "drake"]


# ---------------------------------------------------------------- the document


def test_empty_text_is_tinyxml2s_empty_document(drake: ModuleType) -> None:
    """Upstream EmptyString."""
    assert Mjcf(drake).error("") == (
        f"{TEXT}:0: error: Failed to parse XML string: XML_ERROR_EMPTY_DOCUMENT"
    )


def test_an_empty_file_is_tinyxml2s_empty_document(drake: ModuleType, tmp_path: Path) -> None:
    """Upstream EmptyFile (an empty .xml file: the Parser picks the reader by suffix)."""
    path = tmp_path / "empty.xml"
    path.write_text("")
    with pytest.raises(RuntimeError) as info:
        Mjcf(drake).file(path)
    assert str(info.value) == (
        f"{path}:0: error: Failed to parse XML file {path}:\nXML_ERROR_EMPTY_DOCUMENT"
    )


def test_a_document_without_mujoco_is_an_error(drake: ModuleType) -> None:
    """Upstream NoMujocoRoot."""
    assert Mjcf(drake).error("<stuff/>") == (
        f"{TEXT}:1: error: ERROR: XML does not contain a mujoco tag."
    )


def test_a_model_needs_a_name(drake: ModuleType) -> None:
    """Upstream NoName."""
    assert Mjcf(drake).error("<mujoco/>") == (
        f"{TEXT}:1: error: ERROR: Your robot must have a name attribute or a model name must "
        "be specified."
    )


# ------------------------------------------------------------------ geometries

GEOMETRY_TYPES = """
<mujoco model="test">
  <default class="default_box">
    <geom type="box" size="0.1 0.2 0.3"/>
    <default class="sub">
      <geom size="0.4 0.5 0.6"/>
    </default>
  </default>
  <worldbody>
    <geom name="default" size="0.1"/>
    <geom name="plane" type="plane"/>
    <geom name="sphere" type="sphere" size="0.1"/>
    <geom name="capsule" type="capsule" size="0.1 2.0"/>
    <geom name="ellipsoid" type="ellipsoid" size="0.1 0.2 0.3"/>
    <geom name="cylinder" type="cylinder" size="0.1 2.0"/>
    <geom name="box" type="box" size="0.1 2.0 3.0"/>
    <geom name="box_from_default" class="default_box"/>
    <geom name="ellipsoid_from_default" type="ellipsoid" class="default_box"/>
    <geom name="box_from_sub" class="sub"/>
  </worldbody>
</mujoco>
"""


def test_geoms_become_shapes_of_every_role_by_type_and_class(drake: ModuleType) -> None:
    """Upstream GeometryTypes, with the sizes (MuJoCo's half sizes double)."""
    mjcf = Mjcf(drake)
    assert mjcf.add(GEOMETRY_TYPES) == ["test"]
    role = drake.geometry.Role
    expected = {
        "default": "Sphere(radius=0.1)",
        "plane": "HalfSpace()",
        "sphere": "Sphere(radius=0.1)",
        "capsule": "Capsule(radius=0.1, length=4)",
        "ellipsoid": "Ellipsoid(a=0.1, b=0.2, c=0.3)",
        "cylinder": "Cylinder(radius=0.1, length=4)",
        "box": "Box(width=0.2, depth=4, height=6)",
        "box_from_default": "Box(width=0.2, depth=0.4, height=0.6)",
        "ellipsoid_from_default": "Ellipsoid(a=0.1, b=0.2, c=0.3)",
        "box_from_sub": "Box(width=0.8, depth=1, height=1.2)",
    }
    for name, shape in expected.items():
        for each in (role.kProximity, role.kPerception, role.kIllustration):
            geometry_id = mjcf.world_geometry(name, each)
            assert repr(mjcf.inspector.GetShape(geometry_id=geometry_id)) == shape


def test_unnamed_geoms_are_numbered(drake: ModuleType) -> None:
    """Upstream UniqueGeometryNames."""
    mjcf = Mjcf(drake)
    mjcf.add("""
<mujoco model="test">
  <default class="default_box">
    <geom type="box" size="0.1 0.2 0.3"/>
  </default>
  <worldbody>
    <geom class="default_box"/>
    <geom class="default_box"/>
  </worldbody>
</mujoco>
""")
    role = drake.geometry.Role
    assert mjcf.roles("geom0") == [role.kProximity, role.kIllustration, role.kPerception]
    assert mjcf.roles("geom1") == [role.kProximity, role.kIllustration, role.kPerception]


def test_an_unknown_geom_type_is_an_error(drake: ModuleType) -> None:
    """Upstream UnrecognizedGeometryTypes."""
    text = '<mujoco model="test">\n<worldbody>\n<geom name="garbage" type="garbage"/>\n'
    assert Mjcf(drake).error(text + "</worldbody>\n</mujoco>") == (
        f"{TEXT}:3: error: Unrecognized geom type garbage"
    )


def test_a_nested_default_needs_a_class(drake: ModuleType) -> None:
    """Upstream DefaultError."""
    assert Mjcf(drake).error("""<mujoco model="test">
  <default class="default_box">
    <geom type="box" size="0.1 0.2 0.3"/>
    <default/>
  </default>
</mujoco>""") == (
        f"{TEXT}:4: error: The `class` attribute is required for all `default` elements "
        "except at the top-level"
    )


GEOMETRY_POSES = """
<mujoco model="test">
  <compiler eulerseq="XYZ"/>
  <default class="default_pose">
    <geom pos="1 2 3" quat="0 1 0 0"/>
  </default>
  <worldbody>
    <geom name="identity" type="sphere" size="0.1" />
    <geom name="quat" quat="0 1 0 0" pos="1 2 3" type="sphere" size="0.1" />
    <geom name="axisangle" axisangle="4 5 6 30" pos="1 2 3" type="sphere"
          size="0.1" />
    <geom name="euler" euler="30 45 60" pos="1 2 3" type="sphere" size="0.1" />
    <geom name="xyaxes" xyaxes="0 1 0 -1 0 0" pos="1 2 3" type="sphere"
          size="0.1" />
    <geom name="zaxis" zaxis="0 1 0" pos="1 2 3" type="sphere" size="0.1" />
    <geom name="fromto_capsule" fromto="-1 -3 -3 -1 -1 -3"
          quat="0.2 0.4 0.3 .1" pos="1 2 3" type="capsule" size="0.1" />
    <geom name="fromto_cylinder" fromto="-1 -3 -3 -1 -1 -3"
          quat="0.2 0.4 0.3 .1" pos="1 2 3" type="cylinder" size="0.1" />
    <geom name="from_default" type="sphere" size="0.1" class="default_pose" />
    <geom name="from_default2" type="sphere" size="0.1" class="default_pose"
          euler="30 45 60"/> <!-- euler should overwrite quat -->
  </worldbody>
</mujoco>
"""

RADIANS = """
<mujoco model="radians_test">
  <compiler angle="radian"/>
  <worldbody>
    <geom name="axisangle_rad" axisangle="4 5 6 0.5" pos="1 2 3" type="sphere"
          size="0.1" />
    <geom name="euler_rad" euler="0.5 0.7 1.05" pos="1 2 3" type="sphere"
          size="0.1" />
  </worldbody>
</mujoco>
"""

DEGREES = """
<mujoco model="degrees_test">
  <compiler angle="degree" eulerseq="ZYZ"/>
  <worldbody>
    <geom name="axisangle_deg" axisangle="4 5 6 30" pos="1 2 3" type="sphere"
          size="0.1" />
    <geom name="euler_deg" euler="30 45 60" pos="1 2 3" type="sphere"
          size="0.1" />
  </worldbody>
</mujoco>
"""


def test_geom_poses_take_every_orientation_in_the_compilers_units(drake: ModuleType) -> None:
    """Upstream GeometryPose: degrees by default, euler sequences, a class's pose."""
    mjcf = Mjcf(drake)
    for text in (GEOMETRY_POSES, RADIANS, DEGREES):
        mjcf.add(text)
    m = drake.math
    RotationMatrix, rpy = (
        m.RotationMatrix,
        m.RollPitchYaw(roll=math.pi / 6, pitch=math.pi / 4, yaw=math.pi / 3),
    )
    p = [1.0, 2.0, 3.0]
    expected = {
        "identity": m.RigidTransform(),
        "quat": _pose(drake, _rotation(drake, [1, 0, 0], math.pi), p),
        "axisangle": _pose(drake, _rotation(drake, [4, 5, 6], math.pi / 6), p),
        "euler": _pose(drake, RotationMatrix(rpy=rpy), p),
        "xyaxes": _pose(drake, RotationMatrix.MakeZRotation(theta=math.pi / 2), p),
        "zaxis": _pose(drake, RotationMatrix.MakeXRotation(theta=-math.pi / 2), p),
        "fromto_capsule": _pose(
            drake, RotationMatrix.MakeXRotation(theta=-math.pi / 2), [-1.0, -2.0, -3.0]
        ),
        "fromto_cylinder": _pose(
            drake, RotationMatrix.MakeXRotation(theta=-math.pi / 2), [-1.0, -2.0, -3.0]
        ),
        "from_default": _pose(drake, _rotation(drake, [1, 0, 0], math.pi), p),
        "from_default2": _pose(drake, RotationMatrix(rpy=rpy), p),
        "axisangle_rad": _pose(drake, _rotation(drake, [4, 5, 6], 0.5), p),
        "euler_rad": _pose(
            drake,
            RotationMatrix.MakeXRotation(theta=0.5)
            .multiply(other=RotationMatrix.MakeYRotation(theta=0.7))
            .multiply(other=RotationMatrix.MakeZRotation(theta=1.05)),
            p,
        ),
        "axisangle_deg": _pose(drake, _rotation(drake, [4, 5, 6], math.pi / 6), p),
        "euler_deg": _pose(
            drake,
            RotationMatrix.MakeZRotation(theta=math.pi / 3)
            .multiply(other=RotationMatrix.MakeYRotation(theta=math.pi / 4))
            .multiply(other=RotationMatrix.MakeZRotation(theta=math.pi / 6)),
            p,
        ),
    }
    role = drake.geometry.Role
    for name, X_FG in expected.items():
        for each in (role.kProximity, role.kPerception, role.kIllustration):
            geometry_id = mjcf.world_geometry(name, each)
            X = mjcf.inspector.GetPoseInFrame(geometry_id=geometry_id)
            assert X.IsNearlyEqualTo(other=X_FG, tolerance=1e-14), name


def test_two_orientations_are_an_error_listing_the_attributes(drake: ModuleType) -> None:
    """Upstream GeometryPoseErrors (upstream sees the error twice; the first one raises)."""
    assert Mjcf(drake).error("""
<mujoco model="test">
  <worldbody>
    <geom name="two_angles" type="sphere" size="0.1" pos="1 2 3"
          quat="0 1 0 0" euler="30 45 60" />
  </worldbody>
</mujoco>
""") == (
        f"{TEXT}:4: error: Element geom has more than one orientation attribute specified. "
        "There must be no more than one instance of `quat`, `axisangle`, `euler`, `xyaxes`, "
        'or `zaxis`. Attributes: [name="two_angles" type="sphere" size="0.1" pos="1 2 3" '
        'quat="0 1 0 0" euler="30 45 60" ]'
    )


GEOMETRY_PROPERTIES = """
<mujoco model="test">
  <asset>
    <material name="Orange" rgba="1 0.5 0 1"/>
  </asset>
  <default class="default_rgba">
    <geom rgba="0 1 0 1"/>
  </default>
  <worldbody>
    <geom name="default" type="sphere" size="0.1"/>
    <geom name="default_rgba" type="sphere" size="0.1" class="default_rgba"/>
    <geom name="sphere" type="sphere" size="0.1" friction="0.9 0.0 0.0"
          rgba="1 0 0 1"/>
    <geom name="orange" type="sphere" size="0.1" material="Orange"/>
    <geom name="red" type="sphere" size="0.1" material="Orange" rgba="1 0 0 1"/>
    <geom name="green" type="sphere" size="0.1" material="Orange"
          class="default_rgba"/>
    <geom name="no_collision" contype="0" conaffinity="0" />
    <geom name="no_visual" size="0.1" group="3" />
  </worldbody>
</mujoco>
"""


@pytest.mark.parametrize(
    "case",
    [
        ("default", 1.0, [0.5, 0.5, 0.5, 1], True, True),
        ("default_rgba", 1.0, [0, 1, 0, 1], True, True),
        ("sphere", 0.9, [1, 0, 0, 1], True, True),
        ("orange", 1.0, [1, 0.5, 0, 1], True, True),
        ("red", 1.0, [1, 0, 0, 1], True, True),  # N.B. rgba wins over the material.
        ("green", 1.0, [0, 1, 0, 1], True, True),
        ("no_collision", 1.0, [0.5, 0.5, 0.5, 1], False, True),
        ("no_visual", 1.0, [0.5, 0.5, 0.5, 1], True, False),
    ],
)
def test_a_geom_has_its_friction_colour_and_roles(
    drake: ModuleType, case: tuple[str, float, list[float], bool, bool]
) -> None:
    """Upstream GeometryProperties: (name, friction, colour, has collision, has visual)."""
    name, mu, rgba, collision, visual = case
    mjcf = Mjcf(drake)
    mjcf.add(GEOMETRY_PROPERTIES)
    role, inspector = drake.geometry.Role, mjcf.inspector
    assert mjcf.roles(name) == [
        r
        for r, has in (
            (role.kProximity, collision),
            (role.kIllustration, visual),
            (role.kPerception, visual),
        )
        if has
    ]
    if collision:
        properties = inspector.GetProximityProperties(
            geometry_id=mjcf.world_geometry(name, role.kProximity)
        )
        friction = properties.GetProperty(group_name="material", name="coulomb_friction")
        assert (friction.static_friction(), friction.dynamic_friction()) == (mu, mu)
    if visual:
        for each, read in (
            (role.kPerception, inspector.GetPerceptionProperties),
            (role.kIllustration, inspector.GetIllustrationProperties),
        ):
            properties = read(geometry_id=mjcf.world_geometry(name, each))
            diffuse = properties.GetProperty(group_name="phong", name="diffuse")
            assert list(diffuse.rgba) == rgba


def test_an_unnamed_geom_is_a_zero_radius_sphere(drake: ModuleType) -> None:
    """Upstream GeometryProperties' last check: MuJoCo's default size is 0."""
    mjcf = Mjcf(drake)
    mjcf.add(GEOMETRY_PROPERTIES)
    geometry_id = mjcf.world_geometry("no_collision", drake.geometry.Role.kIllustration)
    assert mjcf.inspector.GetShape(geometry_id=geometry_id).radius() == 0.0


def test_a_material_needs_a_name(drake: ModuleType) -> None:
    """Upstream GeometryPropertiesErrors."""
    text = '<mujoco model="test">\n  <asset>\n    <material/>\n  </asset>\n</mujoco>'
    assert Mjcf(drake).error(text) == (
        f"{TEXT}:2: error: ERROR: Material elements must have a name attribute."
    )


def test_includes_are_expanded_from_the_main_files_folder(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream Include: scene.xml includes two pendula (one through nested.xml), whose geom
    comes from a nested include."""
    mjcf = Mjcf(drake)
    assert mjcf.plant.num_model_instances() == 2
    assert mjcf.file(drake_models / MUJOCO_TEST / "scene.xml") == ["scene"]
    mjcf.plant.Finalize()
    assert mjcf.plant.num_model_instances() == 3
    assert mjcf.plant.num_positions() == 2
    assert mjcf.plant.num_velocities() == 2
    masses = [mjcf.body(name).default_mass() for name in ("body1", "body2")]
    assert masses == [1.0, 1.0]


def test_an_included_elements_errors_are_at_line_0(drake: ModuleType, tmp_path: Path) -> None:
    """The included copies keep no line numbers (tinyxml2's DeepClone; measured)."""
    (tmp_path / "part.xml").write_text('<mujoco>\n\n<geom type="capsule" size="1"/>\n</mujoco>')
    main = tmp_path / "main.xml"
    main.write_text(
        '<mujoco model="m">\n<worldbody>\n<body>\n<include file="part.xml"/>\n</body>\n'
        "</worldbody>\n</mujoco>"
    )
    with pytest.raises(RuntimeError) as info:
        Mjcf(drake).file(main)
    assert str(info.value) == (
        f"{main}:0: error: The size attribute for capsule geom must have at least two elements."
    )


# ---------------------------------------------------------------------- meshes


def _box_mesh(drake: ModuleType, asset: str, compiler: str = "") -> Any:
    """Upstream BoxMeshTest::TestBoxMesh: the world's mesh geom ``box_geom``."""
    mjcf = Mjcf(drake)
    mjcf.add(f"""
<mujoco model="test">
  {compiler}
  <asset>
    {asset}
  </asset>
  <worldbody>
    <geom name="box_geom" type="mesh" mesh="box"/>
  </worldbody>
</mujoco>
""")
    geometry_id = mjcf.world_geometry("box_geom", drake.geometry.Role.kProximity)
    return mjcf.inspector.GetShape(geometry_id=geometry_id)


@pytest.mark.parametrize(
    "case",
    [
        ('<mesh file="{box}"/>', "", [1, 1, 1]),  # MeshFileDirectNoName: named by its stem
        ('<mesh name="box" file="{box}"/>', "", [1, 1, 1]),  # MeshFileDirect
        (  # MeshFileRelativePath: from the working folder, for model text
            '<mesh name="box" file="multibody/parsing/test/box_package/meshes/box.obj"/>',
            "",
            [1, 1, 1],
        ),
        (  # MeshFileAbsolutePathCompiler: meshdir wins over assetdir
            '<mesh name="box" file="box.obj"/>',
            '<compiler assetdir="invalid_name" meshdir="{folder}"/>',
            [1, 1, 1],
        ),
        (  # MeshFileAbsolutePathCompilerUsingAssetDir
            '<mesh name="box" file="box.obj"/>',
            '<compiler assetdir="{folder}"/>',
            [1, 1, 1],
        ),
        (  # MeshFileRelativePathCompiler
            '<mesh name="box" file="box.obj"/>',
            '<compiler meshdir="multibody/parsing/test/box_package/meshes"/>',
            [1, 1, 1],
        ),
        ('<mesh name="box" file="{box}" scale="2 3 1.5"/>', "", [2, 3, 1.5]),  # MeshFileScale
        (  # MeshFileScaleViaDefault
            '<mesh name="box" file="{box}"/>',
            '<default><mesh scale="2 3 4"/></default>',
            [2, 3, 4],
        ),
    ],
)
def test_a_mesh_asset_names_its_file_and_scale(
    drake: ModuleType,
    drake_models: Path,
    monkeypatch: pytest.MonkeyPatch,
    case: tuple[str, str, list[float]],
) -> None:
    """Upstream BoxMeshTest: the Mesh's file is the canonical path, however it is given
    (the case: the <mesh> asset, the <compiler>, the scale)."""
    asset, compiler, scale = case
    monkeypatch.chdir(drake_models)
    box = (drake_models / BOX_OBJ).resolve()
    names = {"box": str(box), "folder": str(box.parent)}
    mesh = _box_mesh(drake, asset.format(**names), compiler.format(**names))
    assert type(mesh).__name__ == "Mesh"
    assert mesh.source().path() == box
    assert list(mesh.scale3()) == scale


def test_a_mesh_file_is_found_from_the_model_files_folder(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream MeshFileRelativePathFromFile: box.xml's meshdir is "../meshes"."""
    mjcf = Mjcf(drake)
    mjcf.file(drake_models / "multibody/parsing/test/box_package/mjcfs/box.xml")
    geometry_id = mjcf.world_geometry("box_geom", drake.geometry.Role.kProximity)
    mesh = mjcf.inspector.GetShape(geometry_id=geometry_id)
    assert mesh.source().path() == (drake_models / BOX_OBJ).resolve()
    assert list(mesh.scale3()) == [1, 1, 1]


def test_a_mesh_without_volume_falls_back_to_its_convex_hull(
    drake: ModuleType, drake_models: Path, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream BadMeshSpatialInertiaFallback, with a vendored mesh of zero volume (a box of
    inverted faces): two warnings, and the hull's mass (half a 1 m cube at 1000 kg/m³)."""
    path = drake_models / "geometry/test/bad_geometry_volume_zero.obj"
    mjcf = Mjcf(drake)
    mjcf.add(f"""<mujoco model="test">
  <asset>
    <mesh name="box" file="{path}"/>  </asset>
  <worldbody>
    <body name="body1">
      <geom name="box_geom" type="mesh" mesh="box"/>
    </body>
  </worldbody>
</mujoco>""")
    assert warnings(drake_log) == [
        f"{TEXT}:6: warning: CalcSpatialInertia(): The calculated volume of a triangle surface "
        "mesh is 0 whereas a reasonable positive value of at least 1e-14 was expected. The "
        "mesh may have bad geometry, e.g., it is an open mesh or the winding (order of "
        "vertices) of at least one face does not produce an outward normal.",
        f"{TEXT}:6: warning: CalcSpatialInertia() failed to compute a physically valid inertia "
        "for mesh box (probably the mesh is not watertight). The spatial inertia was computed "
        "using its convex hull as a fallback.",
    ]
    assert mjcf.body("body1").default_mass() == pytest.approx(500.0, rel=1e-14)


# --------------------------------------------------------------------- inertia

INERTIAL_FROM_GEOMETRY = """
<mujoco model="test">
  <default class="main">
    <geom mass="2.53"/>
    <default class="default_box">
      <geom type="box" size="0.1 0.2 0.3"/>
      <default class="sub">
        <geom size="0.4 0.5 0.6"/>
      </default>
    </default>
  </default>
  <asset>
    <mesh name="box_mesh" file="{box}"/>
    <mesh name="non_convex_mesh" file="{non_convex}"/>
  </asset>
  <worldbody>
    <geom name="plane" type="plane" />
    <body name="default">
      <geom name="default" size="0.1"/>
    </body>
    <body name="sphere">
      <inertial mass="524" diaginertia="1 2 3"/>
      <geom name="sphere" type="sphere" size="0.1"/>
    </body>
    <body name="capsule">
      <geom name="capsule" type="capsule" size="0.1 2.0"/>
    </body>
    <body name="ellipsoid">
      <geom name="ellipsoid" type="ellipsoid" size="0.1 0.2 0.3"/>
    </body>
    <body name="cylinder">
      <geom name="cylinder" type="cylinder" size="0.1 2.0"/>
    </body>
    <body name="box">
      <geom name="box" type="box" size="0.1 2.0 3.0"/>
    </body>
    <body name="box_from_default">
      <geom name="box_from_default" class="default_box"/>
    </body>
    <body name="ellipsoid_from_default">
      <geom name="ellipsoid_from_default" type="ellipsoid" class="default_box"/>
    </body>
    <body name="box_from_sub" childclass="sub">
      <geom name="box_from_sub"/>
    </body>
    <body name="two_spheres">
      <geom name="thing1" type="sphere" size="0.1"/>
      <geom name="thing2" type="sphere" size="0.2"/>
    </body>
    <body name="offset_cylinder">
      <geom name="offset_cylinder" type="cylinder" size="0.4 2.0" pos="2 0 0"
            zaxis="1 0 0"/>
    </body>
    <body name="box_from_mesh">
      <geom name="box_from_mesh" type="mesh" mesh="box_mesh" mass="1.0"/>
    </body>
    <body name="non_convex_body">
      <geom name="non_convex" type="mesh" mesh="non_convex_mesh" mass="1.0"/>
    </body>
  </worldbody>
</mujoco>
"""

INERTIAL_AUTO = """
<mujoco model="test_auto">
  <compiler inertiafromgeom="auto"/>
  <asset>
    <mesh name="box_mesh" file="{box}"/>
    <mesh name="non_convex_mesh" file="{non_convex}"/>
  </asset>
  <worldbody>
    <body name="sphere_auto">
      <inertial mass="524" diaginertia="1 2 3"/>
      <geom name="sphere" mass="2.53" type="sphere" size="0.1"/>
    </body>
    <body name="box_w_density">
      <geom name="box_w_density" density="123" type="box" size=".4 .5 .6"/>
    </body>
    <body name="box_default_density">
      <geom name="box_w_density" type="box" size=".4 .5 .6"/>
    </body>
    <body name="box_from_mesh_w_density">
      <geom name="box_from_mesh_w_density" type="mesh" mesh="box_mesh"
            density="1.0"/>
    </body>
    <body name="non_convex_body_w_density">
      <geom name="non_convex_w_density" type="mesh" mesh="non_convex_mesh"
            density="1.0"/>
    </body>
  </worldbody>
</mujoco>
"""

INERTIAL_TRUE = """
<mujoco model="test_true">
  <compiler inertiafromgeom="true"/>
  <default class="main">
    <geom mass="2.53"/>
  </default>
  <worldbody>
    <body name="sphere_true">
      <inertial mass="524" diaginertia="1 2 3"/>
      <geom name="sphere" type="sphere" size="0.1"/>
    </body>
  </worldbody>
</mujoco>
"""

INERTIAL_FALSE = """
<mujoco model="test_false">
  <compiler inertiafromgeom="false"/>
  <default class="main">
    <geom mass="2.53"/>
  </default>
  <worldbody>
    <body name="sphere_false">
      <inertial mass="524" diaginertia="1 2 3"/>
      <geom name="sphere" type="sphere" size="0.1"/>
    </body>
    <body name="full_inertia">
      <inertial mass="1.23" fullinertia="2 2 2 -.75 -.75 -.75"/>
    </body>
    <body name="full_inertia_w_pose">
      <inertial mass="1.23" fullinertia="2 2 2 -.75 -.75 -.75"
               quat="0.2 0.4 0.3 .1" pos="1 2 3"/>
    </body>
  </worldbody>
</mujoco>
"""

#: body -> (mass, centre of mass), as upstream's expected spatial inertias have them.
BODY_MASSES = {
    "default": (2.53, [0, 0, 0]),
    "sphere": (524, [0, 0, 0]),
    "capsule": (2.53, [0, 0, 0]),
    "ellipsoid": (2.53, [0, 0, 0]),
    "cylinder": (2.53, [0, 0, 0]),
    "box": (2.53, [0, 0, 0]),
    "box_from_default": (2.53, [0, 0, 0]),
    "ellipsoid_from_default": (2.53, [0, 0, 0]),
    "box_from_sub": (2.53, [0, 0, 0]),
    "two_spheres": (2 * 2.53, [0, 0, 0]),
    "offset_cylinder": (2.53, [2, 0, 0]),
    "box_from_mesh": (1.0, [0, 0, 0]),
    "non_convex_body": (1.0, [0.2166666666666666] * 3),
    "sphere_auto": (524, [0, 0, 0]),
    "sphere_true": (2.53, [0, 0, 0]),
    "sphere_false": (524, [0, 0, 0]),
    "box_w_density": (123 * 0.8 * 1.0 * 1.2, [0, 0, 0]),
    "box_default_density": (1000 * 0.8 * 1.0 * 1.2, [0, 0, 0]),
    "box_from_mesh_w_density": (8.0, [0, 0, 0]),
    "non_convex_body_w_density": (0.1, [0.2166666666666666] * 3),
    "full_inertia": (1.23, [0, 0, 0]),
    "full_inertia_w_pose": (1.23, [1, 2, 3]),
}


def test_a_body_takes_its_mass_from_its_inertial_or_its_geoms(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream InertialFromGeometry, for the masses and centres of mass."""
    mjcf = Mjcf(drake)
    files = {"box": drake_models / BOX_OBJ, "non_convex": drake_models / NON_CONVEX_OBJ}
    for text in (INERTIAL_FROM_GEOMETRY, INERTIAL_AUTO):
        mjcf.add(text.format(**files))
    mjcf.add(INERTIAL_TRUE)
    mjcf.add(INERTIAL_FALSE)
    mjcf.plant.Finalize()
    for name, (mass, com) in BODY_MASSES.items():
        inertia = mjcf.body(name).default_spatial_inertia()
        assert inertia.get_mass() == pytest.approx(mass, rel=1e-14), name
        assert np.allclose(inertia.get_com(), com, rtol=0, atol=1e-13), name


def test_compiler_errors_stop_at_the_first(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream CompilerErrors: the coordinate error comes before the compiler's warnings;
    without it, the angle warning comes before the eulerseq error, which is read before
    inertiafromgeom (whose warning upstream's recording policy sees after the error)."""
    compiler = 'angle="grad" inertiafromgeom="QQQ" eulerseq="abc"'
    text = """
<mujoco model="test">
  <compiler {}/>
  <worldbody>
    <body name="trigger_bad_euler_seq" euler="30 45 60"/>
  </worldbody>
</mujoco>
"""
    assert Mjcf(drake).error(text.format(f'coordinate="global" {compiler}')) == (
        f"{TEXT}:3: error: Compiler attribute coordinate=global is not supported yet."
    )
    assert warnings(drake_log) == []
    assert Mjcf(drake).error(text.format(compiler)) == (
        f"{TEXT}:3: error: Illegal value 'abc' for the eulerseq in compiler. Valid eulerseq are "
        "exactly three characters from the set [x,y,z,X,Y,Z]"
    )
    assert warnings(drake_log) == [
        f"{TEXT}:3: warning: Unknown value grad for the compiler `angle` attribute will be "
        "ignored.  The existing value of `angle=degree` will remain unchanged."
    ]


def test_a_short_eulerseq_is_an_error(drake: ModuleType) -> None:
    """Upstream CompilerErrorsShortEulerSeq."""
    assert Mjcf(drake).error('<mujoco model="test">\n<compiler eulerseq="a"/>\n</mujoco>') == (
        f"{TEXT}:2: error: Illegal value 'a' for the eulerseq in compiler. Valid eulerseq are "
        "exactly three characters from the set [x,y,z,X,Y,Z]"
    )


@pytest.mark.parametrize(
    "case",
    [
        (
            '<mesh name="wrong_format" file="{stl}"/>',
            "Drake's MuJoCo parser currently only supports mesh files in .obj format, but the "
            'meshfile "{stl}" was requested. See https://drake.mit.edu/troubleshooting.html '
            "for additional resources.",
        ),
        (
            '<mesh name="missing_file" file="bad_file_name"/>',
            'The mesh asset "{cwd}/bad_file_name" could not be found.',
        ),
    ],
)
def test_a_mesh_asset_must_be_an_existing_obj(
    drake: ModuleType,
    drake_models: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    case: tuple[str, str],
) -> None:
    """Upstream AssetErrors (an .stl of our own: Drake's quad_cube.stl is not vendored); the
    errors are at the <asset>'s line."""
    mesh, message = case
    monkeypatch.chdir(tmp_path)
    stl = tmp_path / "quad_cube.stl"
    stl.write_text("solid a\nendsolid a\n")
    names = {"stl": str(stl), "cwd": str(tmp_path)}
    text = f"""<mujoco model="test">
  <asset>
    <mesh name="box_mesh" file="{drake_models / BOX_OBJ}" scale="1 3 5"/>
    {mesh.format(**names)}
  </asset>
</mujoco>"""
    assert Mjcf(drake).error(text) == f"{TEXT}:2: error: {message.format(**names)}"


def test_a_mesh_without_a_file_and_a_texture_are_ignored_with_warnings(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream AssetErrors' warnings."""
    Mjcf(drake).add("""<mujoco model="test">
  <asset>
    <mesh name="no_file_name"/>
    <texture name="bad_texture" file="bad_file_name"/>
  </asset>
</mujoco>""")
    assert warnings(drake_log) == [
        f"{TEXT}:2: warning: The mesh asset named no_file_name did not specify a 'file' "
        "attribute and so will be ignored.",
        f"{TEXT}:2: warning: The texture element is not supported, see "
        "https://drake.mit.edu/troubleshooting.html for additional resources.",
    ]


def test_an_assetdir_that_holds_no_mesh_is_an_error(
    drake: ModuleType, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Upstream AssetDirErrors (its warning about the unknown mesh comes after the error)."""
    monkeypatch.chdir(tmp_path)
    assert Mjcf(drake).error("""<mujoco model="test">
  <compiler assetdir="invalid_dir"/>
  <asset>
    <mesh name="box_mesh" file="box.obj" />
  </asset>
  <worldbody>
    <geom name="box_geom" type="mesh" mesh="box_mesh"/>
  </worldbody>
</mujoco>""") == (
        f'{TEXT}:3: error: The mesh asset "{tmp_path}/invalid_dir/box.obj" could not be found.'
    )


def test_an_unknown_mesh_is_ignored_with_a_warning(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream AssetDirErrors' warning."""
    mjcf = Mjcf(drake)
    mjcf.add("""<mujoco model="test">
  <worldbody>
    <geom name="box_geom" type="mesh" mesh="box_mesh"/>
  </worldbody>
</mujoco>""")
    assert warnings(drake_log) == [
        f"{TEXT}:3: warning: geom box_geom specified unknown mesh box_mesh and will be ignored"
    ]
    assert mjcf.roles("box_geom") == []


def test_a_body_needs_an_inertial_when_inertiafromgeom_is_false(drake: ModuleType) -> None:
    """Upstream BodyError."""
    assert Mjcf(drake).error("""<mujoco model="test">
  <compiler inertiafromgeom="false"/>
  <worldbody>
    <body name="sphere"/>
  </worldbody>
</mujoco>""") == (
        f"{TEXT}:4: error: sphere has no inertial tag and inertiafromgeom=false. You must "
        "specify an inertia."
    )


# ---------------------------------------------------------------------- joints

JOINTS = """
<mujoco model="test">
  <compiler eulerseq="XYZ"/>
  <default>
    <geom type="sphere" size="1"/>
    <default class="default_joint">
      <joint type="hinge" damping="0.24" pos="-.1 -.2 -.3"
             axis="1 0 0" limited="true" range="-30 60" />
    </default>
  </default>
  <worldbody>
    <body name="freejoint" pos="1 2 3" euler="30 45 60">
      <freejoint name="xfreejoint"/>  <!-- ignored -->
    </body>
    <body name="free" pos="1 2 3" euler="30 45 60">
      <joint type="free" name="xfree"/>  <!-- ignored -->
    </body>
    <body name="ball" pos="1 2 3" euler="30 45 60">
      <joint type="ball" name="ball" damping="0.1" pos=".1 .2 .3"/>
    </body>
    <body name="slide" pos="1 2 3" euler="30 45 60">
      <joint type="slide" name="slide" damping="0.2" pos=".1 .2 .3"
             axis="1 0 0" limited="true" range="-2 1.5"/>
    </body>
    <body name="hinge" pos="1 2 3" euler="30 45 60">
      <joint type="hinge" name="hinge" damping="0.3" pos=".1 .2 .3"
             axis="0 1 0" limited="true" range="-30 60"/>
    </body>
    <body name="hinge_w_joint_defaults" pos="1 2 3" euler="30 45 60">
      <joint type="hinge" name="hinge_w_joint_defaults" class="default_joint" />
    </body>
    <body name="slide_w_ref">
      <joint type="slide" name="slide_w_ref" ref="1.1"/>
    </body>
    <body name="hinge_w_ref">
      <joint type="hinge" name="hinge_w_ref" ref="15"/>
    </body>
    <body name="default" pos="1 2 3" euler="30 45 60">
      <!-- without the limited=true tag -->
      <joint name="default" damping="0.4" range="-20 15"/>
    </body>
    <body name="weld" pos="1 2 3" euler="30 45 60"/>
    <body name="two_hinges" pos="1 2 3" euler="30 45 60">
      <joint type="hinge" name="hinge1" damping="0.5" pos=".1 .2 .3"
             axis="1 0 0"/>
      <joint type="hinge" name="hinge2" damping="0.6" pos=".1 .2 .3"
             axis="0 1 0"/>
    </body>
    <body name="default_joint">
      <!-- provides code coverage for defaults logic. -->
      <joint/>
    </body>
  </worldbody>
</mujoco>
"""


class Joints:
    """JOINTS parsed and finalized, with a default context."""

    def __init__(self, drake: ModuleType) -> None:
        self.drake = drake
        self.mjcf = Mjcf(drake)
        self.mjcf.add(JOINTS)
        self.plant = self.mjcf.plant
        self.plant.Finalize()
        self.context = self.plant.CreateDefaultContext()
        rpy = drake.math.RollPitchYaw(roll=math.pi / 6, pitch=math.pi / 4, yaw=math.pi / 3)
        self.X_WB = drake.math.RigidTransform(rpy=rpy, p=np.array([1.0, 2.0, 3.0]))
        self.X_pos = drake.math.RigidTransform(p=np.array([0.1, 0.2, 0.3]))

    def joint(self, name: str) -> Any:
        return self.plant.GetJointByName(name=name)

    def X_WB_of(self, body: str) -> Any:
        return self.mjcf.body(body).EvalPoseInWorld(context=self.context)

    def X_CJ(self, joint: str) -> Any:
        return self.joint(joint).frame_on_child().CalcPoseInBodyFrame(context=self.context)


def test_free_joints_float_their_body_under_the_bodys_own_name(drake: ModuleType) -> None:
    """Upstream Joint: <freejoint> and type="free" (their names are not joints' names)."""
    j = Joints(drake)
    for body, ignored in (("freejoint", "xfreejoint"), ("free", "xfree")):
        assert not j.plant.HasJointNamed(name=ignored)
        assert j.plant.HasJointNamed(name=body)
        assert j.mjcf.body(body).is_floating_base_body()
        X = j.plant.GetFreeBodyPose(context=j.context, body=j.mjcf.body(body))
        assert X.IsNearlyEqualTo(other=j.X_WB, tolerance=1e-14)


def test_ball_slide_and_hinge_joints_are_drake_joints_at_their_pos(drake: ModuleType) -> None:
    """Upstream Joint: types, damping, the joint frame on the child, axes, limits (hinge
    limits in degrees), and the bodies' default poses."""
    j = Joints(drake)
    expected = {
        "ball": ("ball_rpy", 0.1, None, None),
        "slide": ("prismatic", 0.2, [1, 0, 0], (-2.0, 1.5)),
        "hinge": ("revolute", 0.3, [0, 1, 0], (-math.pi / 6, math.pi / 3)),
    }
    for name, (type_name, damping, axis, limits) in expected.items():
        joint = j.joint(name)
        assert joint.type_name() == type_name
        assert joint.default_damping() == damping
        assert j.X_CJ(name).IsNearlyEqualTo(other=j.X_pos, tolerance=1e-14)
        assert j.X_WB_of(name).IsNearlyEqualTo(other=j.X_WB, tolerance=1e-14)
        if axis is not None:
            read = joint.translation_axis if type_name == "prismatic" else joint.revolute_axis
            assert list(read()) == axis
            assert np.allclose(
                [joint.position_lower_limits()[0], joint.position_upper_limits()[0]],
                limits,
                rtol=0,
                atol=1e-14,
            )


def test_a_joint_takes_its_class_defaults(drake: ModuleType) -> None:
    """Upstream Joint: hinge_w_joint_defaults."""
    j = Joints(drake)
    joint = j.joint("hinge_w_joint_defaults")
    assert joint.type_name() == "revolute"
    assert joint.default_damping() == 0.24
    X_CJ = drake.math.RigidTransform(p=np.array([-0.1, -0.2, -0.3]))
    assert j.X_CJ("hinge_w_joint_defaults").IsNearlyEqualTo(other=X_CJ, tolerance=1e-14)
    assert list(joint.revolute_axis()) == [1, 0, 0]
    assert j.X_WB_of("hinge_w_joint_defaults").IsNearlyEqualTo(other=j.X_WB, tolerance=1e-14)
    assert joint.position_lower_limits()[0] == pytest.approx(-math.pi / 6, abs=1e-14)
    assert joint.position_upper_limits()[0] == pytest.approx(math.pi / 3, abs=1e-14)


def test_a_joints_ref_is_its_default_position(drake: ModuleType) -> None:
    """Upstream Joint: hinge_w_ref (degrees) and slide_w_ref; at q = 0 the body is where the
    ref says it is not."""
    j = Joints(drake)
    hinge, slide = j.joint("hinge_w_ref"), j.joint("slide_w_ref")
    ref = 15.0 * math.pi / 180.0
    assert hinge.get_default_angle() == pytest.approx(ref, abs=1e-14)
    assert j.X_WB_of("hinge_w_ref").IsNearlyIdentity(translation_tolerance=1e-14)
    hinge.set_angle(context=j.context, angle=0.0)
    turned = drake.math.RigidTransform(R=_rotation(drake, [0, 0, 1], -ref), p=np.zeros(3))
    assert np.allclose(
        j.X_WB_of("hinge_w_ref").GetAsMatrix34(), turned.GetAsMatrix34(), rtol=0, atol=1e-14
    )
    assert slide.get_default_translation() == 1.1
    assert j.X_WB_of("slide_w_ref").IsNearlyIdentity(translation_tolerance=1e-14)
    slide.set_translation(context=j.context, translation=0.0)
    assert np.allclose(j.X_WB_of("slide_w_ref").translation(), [0, 0, -1.1], rtol=0, atol=1e-14)


def test_a_joint_without_type_is_a_hinge_about_z_limited_by_its_range(
    drake: ModuleType,
) -> None:
    """Upstream Joint: default (autolimits make range limit it)."""
    j = Joints(drake)
    joint = j.joint("default")
    assert joint.type_name() == "revolute"
    assert joint.default_damping() == 0.4
    assert j.X_CJ("default").IsNearlyIdentity(translation_tolerance=1e-14)
    assert list(joint.revolute_axis()) == [0, 0, 1]
    assert j.X_WB_of("default").IsNearlyEqualTo(other=j.X_WB, tolerance=1e-14)
    assert joint.position_lower_limits()[0] == -math.pi / 9
    assert joint.position_upper_limits()[0] == math.pi / 12


def test_several_joints_are_chained_through_massless_bodies(drake: ModuleType) -> None:
    """Upstream Joint: two_hinges (hinge1 to the dummy body two_hinges0, whose pose is the
    parent's; hinge2 to the body), and a body without joints is welded."""
    j = Joints(drake)
    hinge1, hinge2 = j.joint("hinge1"), j.joint("hinge2")
    assert (hinge1.default_damping(), list(hinge1.revolute_axis())) == (0.5, [1, 0, 0])
    X_PJ = hinge1.frame_on_parent().CalcPoseInBodyFrame(context=j.context)
    assert X_PJ.IsNearlyEqualTo(other=j.X_pos, tolerance=1e-14)
    assert hinge1.child_body().name() == "two_hinges0"
    assert hinge1.child_body().default_mass() == 0.0
    assert (hinge2.default_damping(), list(hinge2.revolute_axis())) == (0.6, [0, 1, 0])
    assert j.X_CJ("hinge2").IsNearlyEqualTo(other=j.X_pos, tolerance=1e-14)
    assert j.X_WB_of("two_hinges").IsNearlyEqualTo(other=j.X_WB, tolerance=1e-14)
    assert j.X_WB_of("weld").IsNearlyEqualTo(other=j.X_WB, tolerance=1e-14)
    weld = j.joint("world_welds_to_weld")
    assert weld.type_name() == "weld"
    assert weld.X_FM().IsNearlyEqualTo(other=j.X_WB, tolerance=1e-14)


def test_a_free_joint_among_others_is_an_error_after_its_damping_warning(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream JointErrors, the free body."""
    assert Mjcf(drake).error("""<mujoco model="test">
  <worldbody>
    <body name="free" pos="1 2 3" euler="30 45 60">
      <joint type="free" name="free" damping="10"/>
      <joint type="hinge"/>
    </body>
  </worldbody>
</mujoco>""") == (
        f"{TEXT}:3: error: No other joints can be defined in the body free if a free joint is "
        "defined."
    )
    assert warnings(drake_log) == [
        f"{TEXT}:4: warning: Damping was specified for the 'free' joint free, but is not "
        "supported for free bodies."
    ]


def test_a_ball_joints_range_is_ignored_and_an_unknown_type_is_an_error(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream JointErrors, the ball and the impossible joint."""
    assert (
        Mjcf(drake).error("""<mujoco model="test">
  <worldbody>
    <body>
      <joint type="ball" limited="true" range="-1 1"/>
    </body>
    <body>
      <joint type="impossible"/>
    </body>
  </worldbody>
</mujoco>""")
        == f"{TEXT}:7: error: Unknown joint type impossible"
    )
    assert warnings(drake_log) == [
        f"{TEXT}:4: warning: The attribute 'range' found in a 'joint' tag is currently "
        "unsupported and will be ignored."
    ]


def _autolimits(autolimits: bool, limited: str = "") -> str:
    """Upstream MakeAutoLimitsXML's joints (its motors' limits are dynamics: left out)."""
    bad = f'<joint type="hinge" name="hinge6" range="-5 5" limited="{limited}"/>'
    return f"""
  <mujoco model="test">
    <compiler autolimits="{str(autolimits).lower()}" angle="radian"/>
    <worldbody>
      <body>
        <joint type="hinge" name="hinge0" limited="true"/>
        {"" if autolimits else "<!--"}
        <joint type="hinge" name="hinge1" range="-1 1"/>
        <joint type="hinge" name="hinge2" range="-2 2" limited="auto"/>
        {"" if autolimits else "-->"}
        <joint type="hinge" name="hinge3" range="-3 3" limited="true"/>
        <joint type="hinge" name="hinge4" range="-4 4" limited="false"/>
        {bad if limited else ""}
      </body>
    </worldbody>
  </mujoco>
  """


@pytest.mark.parametrize(
    ("autolimits", "limits"),
    [(True, [0.0, 1.0, 2.0, 3.0, math.inf]), (False, [0.0, 3.0, math.inf])],
)
def test_autolimits_decide_whether_a_range_limits_a_joint(
    drake: ModuleType, autolimits: bool, limits: list[float]
) -> None:
    """Upstream AutoLimitsTrue and AutoLimitsFalse: the joints' position limits (with
    autolimits off, hinge1 and hinge2 are commented out: each is an error, below)."""
    mjcf = Mjcf(drake)
    mjcf.add(_autolimits(autolimits))
    joints = [mjcf.plant.get_joint(joint_index=j) for j in mjcf.plant.GetJointIndices()]
    lower = [j.position_lower_limits()[0] for j in joints if j.num_positions() == 1]
    upper = [j.position_upper_limits()[0] for j in joints if j.num_positions() == 1]
    assert (lower, upper) == ([-v for v in limits], limits)


@pytest.mark.parametrize(
    ("autolimits", "line", "message"),
    [
        (True, 13, "The 'limited' attribute must be one of 'true', 'false', or 'auto'."),
        (False, 13, "The 'limited' attribute must be one of 'true', 'false', or 'auto'."),
    ],
)
def test_limited_must_be_true_false_or_auto(
    drake: ModuleType, autolimits: bool, line: int, message: str
) -> None:
    """Upstream AutoLimitsTrue and AutoLimitsFalse: hinge6's limited="bad"."""
    assert Mjcf(drake).error(_autolimits(autolimits, limited="bad")) == (
        f"{TEXT}:{line}: error: {message}"
    )


def test_a_range_without_limited_is_an_error_without_autolimits(drake: ModuleType) -> None:
    """Upstream AutoLimitsFalse: hinge1's range."""
    text = _autolimits(False).replace("<!--", "").replace("-->", "")
    assert Mjcf(drake).error(text) == (
        f"{TEXT}:8: error: The 'range' attribute was specified but 'autolimits' is disabled."
    )


@pytest.mark.parametrize(
    ("inertial", "line", "message"),
    [
        ("<inertial/>", 4, "The inertial tag must include the mass attribute."),
        (
            '<inertial mass="10"/>',
            4,
            "The inertial tag must include either the diaginertia or fullinertia attribute.",
        ),
        (
            '<geom name="negative_mass" type="sphere" size="1" mass="-1"/>',
            4,
            "geom negative_mass Spatial inertia fails SpatialInertia::IsPhysicallyValid().\n"
            "mass = -1 is negative or not finite.\n",
        ),
    ],
)
def test_inertial_errors(drake: ModuleType, inertial: str, line: int, message: str) -> None:
    """Upstream InertialErrors, one body each."""
    text = f'<mujoco model="test">\n<worldbody>\n<body>\n{inertial}\n</body>\n</worldbody>\n'
    assert Mjcf(drake).error(text + "</mujoco>") == f"{TEXT}:{line}: error: {message}"


def test_an_unnamed_geom_is_named_geom0_in_its_model(drake: ModuleType) -> None:
    """Upstream GeomAutoName."""
    mjcf = Mjcf(drake)
    mjcf.add("""<mujoco model="test">
  <worldbody>
    <body>
      <geom type="sphere" size="1"/>
    </body>
  </worldbody>
</mujoco>""")
    inspector = mjcf.inspector
    names = [inspector.GetName(geometry_id=g) for g in inspector.GetAllGeometryIds()]
    assert names == ["test::geom0", "test::geom0"]


@pytest.mark.parametrize(
    ("geom", "message"),
    [
        ('type="capsule"', "The size attribute for capsule geom must have at least two elements."),
        (
            'type="capsule" fromto="1 2 3 4 5 6"',
            "The size attribute for capsule geom using fromto must have at least one element.",
        ),
        (
            'type="ellipsoid"',
            "The size attribute for ellipsoid geom must have at least three elements.",
        ),
        (
            'type="cylinder"',
            "The size attribute for cylinder geom must have at least two elements.",
        ),
        (
            'type="cylinder" fromto="1 2 3 4 5 6"',
            "The size attribute for cylinder geom using fromto must have at least one element.",
        ),
        ('type="box"', "The size attribute for box geom must have at least three elements."),
        ('type="mesh"', "geom geom0 specified type 'mesh', but did not set the mesh attribute"),
        (
            'type="capsule" mesh="nonsense"',
            "geom geom0 specified type 'capsule' but also has a mesh attribute. The intended "
            "behavior is to compute the size of the shape from the mesh, but this is not "
            "supported yet (#22372).",
        ),
        (
            'type="plane" mesh="nonsense"',
            "geom geom0 specified a 'mesh', but this is not allowed for type 'plane'.",
        ),
    ],
)
def test_geom_errors(drake: ModuleType, geom: str, message: str) -> None:
    """Upstream GeomErrors, one geom each."""
    text = f'<mujoco model="test">\n<worldbody>\n<body>\n<geom {geom}/>\n</body>\n</worldbody>\n'
    assert Mjcf(drake).error(text + "</mujoco>") == f"{TEXT}:4: error: {message}"


def test_geoms_drake_cannot_make_are_ignored_with_warnings(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream GeomErrors' warnings: the zero-radius default sphere is kept."""
    mjcf = Mjcf(drake)
    mjcf.add("""<mujoco model="test">
  <worldbody>
    <body>
      <geom/>
      <geom type="ellipsoid" fromto="1 2 3 4 5 6"/>
      <geom type="box" fromto="1 2 3 4 5 6"/>
      <geom type="mesh" mesh="nonsense"/>
      <geom type="hfield"/>
    </body>
  </worldbody>
</mujoco>""")
    assert warnings(drake_log) == [
        f"{TEXT}:4: warning: Using zero-radius spheres (MuJoCo's default geometry) for "
        "collision geometry may not be supported by all features in Drake. Consider specifying "
        "a non-zero size for geom geom0.",
        f"{TEXT}:5: warning: The fromto tag for ellipsoid is currently unsupported; geom geom1 "
        "will be ignored.",
        f"{TEXT}:6: warning: The fromto tag for box is currently unsupported; geom geom1 will "
        "be ignored.",
        f"{TEXT}:7: warning: geom geom1 specified unknown mesh nonsense and will be ignored",
        f"{TEXT}:8: warning: The geom type 'hfield' is currently unsupported and will be ignored.",
    ]
    inspector = mjcf.inspector
    names = [inspector.GetName(geometry_id=g) for g in inspector.GetAllGeometryIds()]
    assert names == ["test::geom0", "test::geom0"]


MOTORS = """
<mujoco model="test">
  <default>
    <geom type="sphere" size="1"/>
  </default>
  <worldbody>
    <body>
      <joint type="hinge" name="hinge1" axis="0 1 0"/>
    </body>
    <body>
      <joint type="hinge" name="hinge2" axis="0 1 0"/>
    </body>
    <body>
      <joint type="hinge" name="hinge3" axis="0 1 0"/>
    </body>
    <body>
      <joint type="hinge" name="hinge5" axis="0 1 0"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="m1" joint="hinge1" ctrllimited="true" ctrlrange="-1 2"/>
    <motor name="m2" joint="hinge2" ctrllimited="true" ctrlrange="-3 2"
           forcelimited="true" forcerange="-.5 .4"/>
    <motor name="m3" joint="hinge3" ctrllimited="true" ctrlrange="2 1"
           forcelimited="true" forcerange="2 1"/>
    <motor joint="hinge5" gear="3 0 0"/>
  </actuator>
</mujoco>
"""


def test_motor_limits_and_gears_drake_cannot_take_are_warned_about(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream Motor's warnings (the actuators' values are dynamics: left out; the motors
    are renamed, as an unnamed one is motor<n>, n the plant's actuators so far)."""
    Mjcf(drake).add(MOTORS)
    asymmetric = (
        "where lower limit != -upper limit. Asymmetrical effort limits are not supported yet, "
        "so the larger of the values {} will be used."
    )
    reversed_ = "where lower limit > upper limit; these limits will be ignored."
    assert warnings(drake_log) == [
        f"{TEXT}:21: warning: The motor 'm1' specified a ctrlrange attribute "
        + asymmetric.format(2),
        f"{TEXT}:22: warning: The motor 'm2' specified a ctrlrange attribute "
        + asymmetric.format(3),
        f"{TEXT}:22: warning: The motor 'm2' specified a forcerange attribute "
        + asymmetric.format(0.5),
        f"{TEXT}:24: warning: The motor 'm3' specified a ctrlrange attribute " + reversed_,
        f"{TEXT}:24: warning: The motor 'm3' specified a forcerange attribute " + reversed_,
        f"{TEXT}:26: warning: Expected either 1 value or 6 values for 'gear' attribute, but "
        "got 3 0 0.",
    ]


def test_a_camera_without_a_builder_is_ignored_with_a_warning(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream CameraWithoutSceneGraph (here: a Parser given no DiagramBuilder)."""
    Mjcf(drake, scene_graph=False).add("""<mujoco model="test">
  <default>
    <geom type="sphere" size="1"/>
  </default>
  <worldbody>
    <camera name="world_camera" fovy="30" resolution="100 100"/>
  </worldbody>
</mujoco>""")
    assert warnings(drake_log) == [
        f"{TEXT}:6: warning: camera element ignored; to register cameras, you must pass a "
        "DiagramBuilder to the Parser and the plant must be registered with a scene graph."
    ]


# --------------------------------------------------------------------- contact

CONTACT = """
  <mujoco model="test">
    <default>
      <geom type="sphere" size="1"/>
    </default>
    <worldbody>
      <body name="base">
        <geom name="base_geom"/>
        <body name="body1">
          <geom name="body1_geom"/>
          <joint type="hinge"/>
        </body>
        <body name="body2">
          <geom name="body2_geom"/>
          <joint type="hinge"/>
        </body>
      </body>
    </worldbody>
    {}
  </mujoco>
"""

CONTACT_NODE = """
    <contact>
      <pair name="pair1" geom1="base_geom" geom2="body1_geom"/>
      <exclude name="exclude1" body1="body1" body2="body2" />
    </contact>
"""


@pytest.mark.parametrize("include_contact", [False, True])
@pytest.mark.parametrize("adjacent_filters", [False, True])
def test_contact_pairs_and_excludes_change_the_collision_filters(
    drake: ModuleType,
    drake_log: pytest.LogCaptureFixture,
    include_contact: bool,
    adjacent_filters: bool,
) -> None:
    """Upstream ContactTest: a pair unfilters two geometries (until Finalize filters adjacent
    bodies again, warned about); an exclude filters two bodies."""
    mjcf = Mjcf(drake)
    mjcf.plant.set_adjacent_bodies_collision_filters(value=adjacent_filters)
    mjcf.add(CONTACT.format(CONTACT_NODE if include_contact else ""))
    mjcf.plant.Finalize()
    inspector, role = mjcf.inspector, drake.geometry.Role

    def geometry(body: str) -> Any:
        frame_id = mjcf.plant.GetBodyFrameIdOrThrow(body_index=mjcf.body(body).index())
        return inspector.GetGeometries(frame_id=frame_id, role=role.kProximity)[0]

    base, body1, body2 = geometry("base"), geometry("body1"), geometry("body2")
    filtered = [
        inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b)
        for a, b in ((base, body1), (body1, body2))
    ]
    assert filtered == [adjacent_filters, include_contact]
    expected = []
    if include_contact and adjacent_filters:
        expected = [
            f"{TEXT}:20: warning: This mjcf specified a contact pair with geom1 base_geom and "
            "are on adjacent bodies (connected by a joint). A collision filter excluding these "
            "bodies will be added during MultibodyPlant::Finalize(), which will overwrite the "
            "collision filter specified in this file. To avoid this you must call "
            "MultibodyPlant::set_adjacent_bodies_collision_filters(), and understand the "
            "implications."
        ]
    assert warnings(drake_log) == expected


def test_contact_elements_drake_cannot_take_are_warned_about(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream ContactWarnings: the top-level default's pair (class main) gives every pair
    its friction, warned about for the one pair that is read that far; the others are
    warned about at the <contact>'s line."""
    Mjcf(drake).add("""<mujoco model="test">
  <default>
    <geom type="sphere" size="1"/>
    <pair name="with_friction" friction="0.5"/>
  </default>
  <worldbody>
    <body name="base">
      <geom name="base_geom"/>
      <body name="body1">
        <geom name="body1_geom"/>
        <joint type="hinge"/>
      </body>
      <body name="body2">
        <geom name="body2_geom"/>
        <joint type="hinge"/>
      </body>
    </body>
  </worldbody>
  <contact>
    <pair name="with_default" geom1="body1_geom" geom2="body2_geom" class="with_friction"/>
    <pair name="no-geom1" geom2="body1_geom"/>
    <pair name="no-geom2" geom1="body1_geom"/>
    <pair name="unknown-geom1" geom1="QQQ" geom2="body1_geom"/>
    <pair name="unknown-geom2" geom1="body1_geom" geom2="QQQ"/>
    <exclude name="no-body1" body2="body2" />
    <exclude name="no-body2" body1="body1" />
  </contact>
</mujoco>""")
    pair = "contact pair node does not have required geom1 and/or geom2 attributes, so will be"
    exclude = (
        "contact exclude node does not have required body1 and/or body2 attributes, so will "
        "be ignored."
    )
    assert warnings(drake_log) == [
        f"{TEXT}:20: warning: The attribute 'friction' found in a 'pair' tag is currently "
        "unsupported and will be ignored.",
        f"{TEXT}:19: warning: {pair} ignored.",
        f"{TEXT}:19: warning: {pair} ignored.",
        f"{TEXT}:19: warning: contact pair specified unknown geom1 QQQ and will be ignored.",
        f"{TEXT}:19: warning: contact pair specified unknown geom2 QQQ and will be ignored.",
        f"{TEXT}:19: warning: {exclude}",
        f"{TEXT}:19: warning: {exclude}",
    ]


@pytest.mark.parametrize(("body1", "body2"), [("QQQ", "body2"), ("body1", "QQQ")])
def test_an_exclude_of_an_unknown_body_is_get_body_by_names_error(
    drake: ModuleType, body1: str, body2: str
) -> None:
    """Upstream ContactThrows."""
    text = f"""<mujoco model="bad_body">
  <worldbody>
    <body name="base">
      <body name="body1">
        <joint type="hinge"/>
      </body>
      <body name="body2">
        <joint type="hinge"/>
      </body>
    </body>
  </worldbody>
  <contact>
    <exclude name="unknown-body" body1="{body1}" body2="{body2}" />
  </contact>
</mujoco>"""
    assert Mjcf(drake).error(text) == (
        "GetRigidBodyByName(): There is no RigidBody named 'QQQ' anywhere in the model (valid "
        "names in model instance 'WorldModelInstance' are: world; valid names in model instance "
        "'bad_body' are: base, body1, body2)"
    )


# -------------------------------------------------------------------- equality

EQUALITY = """<mujoco model="test">
  <worldbody>
    <body name="body1">
      <geom type="box" size="0.1 0.2 0.3"/>
      <joint type="hinge" pos="-1 0 0"/>
    </body>
    <body name="body2">
      <geom type="box" size="0.1 0.2 0.3"/>
      <joint type="hinge" pos="1 0 0"/>
    </body>
  </worldbody>
  <equality>
    {}
  </equality>
</mujoco>"""


@pytest.mark.parametrize(
    ("connect", "line", "message"),
    [
        (
            '<connect body1="body1" body2="body2"/>',
            12,
            "connect specified body1 but does not have the required anchor attribute.",
        ),
        ("<connect/>", 13, "connect must specify body1 and anchor OR site1 and site2."),
        (
            '<connect body1="body1" site1="site1"/>',
            13,
            "connect node must specify either body1 and anchor OR site1 and site2, but not both.",
        ),
        (
            '<connect body1="nonsense" anchor="1 2 3"/>',
            12,
            "connect specified body1: nonsense but no body with that name exists in model "
            "instance: test",
        ),
        (
            '<connect body1="body1" anchor="1 2 3" body2="nonsense"/>',
            12,
            "connect specified body2: nonsense but no body with that name exists in model "
            "instance: test",
        ),
    ],
)
def test_equality_connect_errors(drake: ModuleType, connect: str, line: int, message: str) -> None:
    """Upstream BadEqualityTest, one connect each (some at the <equality>'s line, some at
    the <connect>'s)."""
    assert Mjcf(drake).error(EQUALITY.format(connect)) == f"{TEXT}:{line}: error: {message}"


def test_a_connect_of_sites_is_ignored_with_a_warning(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream BadEqualityTest's warning."""
    Mjcf(drake).add(EQUALITY.format('<connect site1="site1" site2="site2"/>'))
    assert warnings(drake_log) == [
        f"{TEXT}:13: warning: connect node uses the site1 and site2 specification, which is "
        "not supported yet. This constraint will be ignored."
    ]


def test_connects_of_bodies_parse(drake: ModuleType) -> None:
    """Upstream EqualityTest (its ball constraints are dynamics: left out)."""
    connects = '<connect body1="body1" anchor="1 2 3" body2="body2"/>\n'
    connects += '<connect body1="body1" anchor="4 5 6"/>'
    assert Mjcf(drake).add(EQUALITY.format(connects)) == ["test"]
