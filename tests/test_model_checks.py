"""The checks that decide whether a model parses: joint constructors and proximity meshes.

A parser hands a model's joint limits and dampings to the joints' constructors,
and registers its collision meshes with the proximity role, where Drake makes
their convex hulls; these checks raise, and so decide parse-or-error. Each test
runs on reimpl and on real pydrake and asserts the values measured on pydrake
1.51.1; where 1.58.0 differs, the expectation depends on ``api.version`` and the
comment gives both.
"""

from __future__ import annotations

import importlib
import re
from pathlib import Path
from typing import Any

import pytest

from conformance._backends.api import Api

#: Where pydrake's messages print the joint headers (pydrake 1.51.1 and 1.58.0).
TREE_H = (
    "bazel-out/k8-opt/bin/external/drake+/multibody/tree/_virtual_includes/"
    "multibody_tree_core/drake/multibody/tree/"
)
INSTALLED_TREE_H = (
    "bazel-out/k8-opt/bin/external/drake+/tools/install/libdrake/_virtual_includes/"
    "drake_shared_library/drake/multibody/tree/"
)
TETRAHEDRON = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"


def limits_message(api: Api) -> str:
    # The Joint constructor's DRAKE_DEMAND moved from joint.h:159 (1.51.1) to :160 (1.58.0).
    line = 159 if api.version == "1.51.1" else 160
    return (
        f"Failure at {TREE_H}joint.h:{line} in Joint(): condition "
        "'(pos_lower_limits.array() <= pos_upper_limits.array()).all()' failed."
    )


class Bodies:
    """A plant (not finalized) with bodies ``a`` and ``b``; ``F``, ``C`` their frames."""

    def __init__(self, api: Api) -> None:
        assert api.plant is not None
        assert api.tree is not None
        self.tree = api.tree
        self.plant = api.plant.MultibodyPlant(time_step=0.0)
        self.F = self.plant.AddRigidBody(name="a").body_frame()
        self.C = self.plant.AddRigidBody(name="b").body_frame()


def parse(api: Api, text: str, file_type: str) -> Any:
    """A plant and SceneGraph with ``text`` parsed; returns the SceneGraph's inspector."""
    assert api.plant is not None
    assert api.parsing is not None
    framework = importlib.import_module(f"{api.name}.systems.framework")
    plant, scene_graph = api.plant.AddMultibodyPlantSceneGraph(
        builder=framework.DiagramBuilder(), time_step=0.0
    )
    api.parsing.Parser(plant=plant).AddModelsFromString(file_contents=text, file_type=file_type)
    return scene_graph.model_inspector()


def urdf_joint(kind: str, extra: str) -> str:
    return (
        '<robot name="r"><link name="a"/><link name="b"/>'
        f'<joint name="j" type="{kind}"><parent link="a"/><child link="b"/>'
        f'<axis xyz="0 0 1"/>{extra}</joint></robot>'
    )


class TestJointConstructors:
    def test_a_lower_limit_above_the_upper_limit_ends_in_system_exit(self, api: Api) -> None:
        m = Bodies(api)
        for make in (m.tree.RevoluteJoint, m.tree.PrismaticJoint):
            with pytest.raises(SystemExit) as info:
                make(
                    name="j",
                    frame_on_parent=m.F,
                    frame_on_child=m.C,
                    axis=[0, 0, 1],
                    pos_lower_limit=1.0,
                    pos_upper_limit=-1.0,
                    damping=0.0,
                )
            assert str(info.value) == limits_message(api)

    def test_equal_limits_are_accepted_and_read_back(self, api: Api) -> None:
        m = Bodies(api)
        joint = m.tree.RevoluteJoint(
            name="j",
            frame_on_parent=m.F,
            frame_on_child=m.C,
            axis=[0, 0, 2],
            pos_lower_limit=0.5,
            pos_upper_limit=0.5,
            damping=0.25,
        )
        assert joint.position_lower_limit() == 0.5
        assert joint.position_upper_limits().tolist() == [0.5]
        assert joint.velocity_lower_limits().tolist() == [float("-inf")]
        assert joint.default_damping() == 0.25
        assert joint.revolute_axis().tolist() == [0.0, 0.0, 1.0]

    def test_a_nan_limit_fails_the_ordering_demand(self, api: Api) -> None:
        m = Bodies(api)
        with pytest.raises(SystemExit) as info:
            m.tree.RevoluteJoint("j", m.F, m.C, [0, 0, 1], float("nan"), 1.0, 0.0)
        assert str(info.value) == limits_message(api)

    def test_the_limits_are_checked_before_the_damping(self, api: Api) -> None:
        m = Bodies(api)
        with pytest.raises(SystemExit) as info:
            m.tree.RevoluteJoint("j", m.F, m.C, [0, 0, 1], 1.0, -1.0, -0.5)
        assert str(info.value) == limits_message(api)

    @pytest.mark.parametrize(
        ("joint", "kind"),
        [("RevoluteJoint", "Revolute"), ("PrismaticJoint", "Prismatic")],
    )
    def test_negative_damping_raises_runtime_error(self, api: Api, joint: str, kind: str) -> None:
        m = Bodies(api)
        with pytest.raises(RuntimeError, match=rf"^{kind} joint damping must be nonnegative.$"):
            getattr(m.tree, joint)("j", m.F, m.C, [0, 0, 1], -1.0, 1.0, -0.5)

    def test_a_screw_joint_checks_its_axis_then_its_damping(self, api: Api) -> None:
        m = Bodies(api)
        with pytest.raises(
            RuntimeError, match=r"^Screw joint axis vector must have nonzero length.$"
        ):
            m.tree.ScrewJoint("j", m.F, m.C, [0, 0, 0], 0.1, -1.0)
        with pytest.raises(RuntimeError, match=r"^Screw joint damping must be nonnegative.$"):
            m.tree.ScrewJoint("j", m.F, m.C, 0.1, -1.0)

    def test_a_zero_axis_raises_before_the_damping(self, api: Api) -> None:
        m = Bodies(api)
        with pytest.raises(
            RuntimeError, match=r"^Revolute joint axis vector must have nonzero length.$"
        ):
            m.tree.RevoluteJoint("j", m.F, m.C, [0, 0, 0], -1.0)

    @pytest.mark.parametrize(
        ("make", "where"),
        [
            (
                lambda t, F, C: t.BallRpyJoint("j", F, C, -1.0),
                "ball_rpy_joint.h:71 in BallRpyJoint(): condition 'damping >= 0'",
            ),
            (
                lambda t, F, C: t.UniversalJoint("j", F, C, -1.0),
                "universal_joint.h:87 in UniversalJoint(): condition 'damping >= 0'",
            ),
            (
                lambda t, F, C: t.PlanarJoint("j", F, C, [0.0, -1.0, 0.0]),
                "planar_joint.h:74 in PlanarJoint(): condition '(damping.array() >= 0).all()'",
            ),
            (
                lambda t, F, C: t.QuaternionFloatingJoint("j", F, C, 0.0, -1.0),
                "quaternion_floating_joint.h:94 in QuaternionFloatingJoint(): condition "
                "'translational_damping >= 0'",
            ),
            (
                lambda t, F, C: t.RpyFloatingJoint("j", F, C, -1.0, -1.0),
                "rpy_floating_joint.h:89 in RpyFloatingJoint(): condition 'angular_damping >= 0'",
            ),
        ],
    )
    def test_other_joints_demand_nonnegative_damping(self, api: Api, make: Any, where: str) -> None:
        m = Bodies(api)
        with pytest.raises(SystemExit) as info:
            make(m.tree, m.F, m.C)
        assert str(info.value) == f"Failure at {TREE_H}{where} failed."

    def test_a_joint_reads_back_its_damping_vector_and_suffixes_after_finalize(
        self, api: Api
    ) -> None:
        m = Bodies(api)
        m.plant.WeldFrames(frame_on_parent_F=m.plant.world_frame(), frame_on_child_M=m.F)
        joint = m.plant.AddJoint(m.tree.QuaternionFloatingJoint("j", m.F, m.C, 0.5, 0.25))
        with pytest.raises(SystemExit) as info:
            joint.velocity_suffix(0)
        # velocity_suffix's DRAKE_DEMAND: joint.h:275 on 1.51.1, :291 on 1.58.0.
        line = 275 if api.version == "1.51.1" else 291
        assert str(info.value) == (
            f"Failure at {INSTALLED_TREE_H}joint.h:{line} in velocity_suffix(): "
            "condition 'has_mobilizer()' failed."
        )
        m.plant.Finalize()
        assert joint.default_damping_vector().tolist() == [0.5, 0.5, 0.5, 0.25, 0.25, 0.25]
        assert joint.default_angular_damping() == 0.5
        assert [joint.velocity_suffix(i) for i in range(6)] == ["wx", "wy", "wz", "vx", "vy", "vz"]
        assert (joint.can_rotate(), joint.can_translate()) == (True, True)


class TestJointsInParsedModels:
    @pytest.mark.parametrize("kind", ["revolute", "prismatic", "continuous"])
    def test_urdf_limits_out_of_order_end_in_system_exit(self, api: Api, kind: str) -> None:
        limit = '<limit lower="1" upper="-1" effort="1" velocity="1"/>'
        with pytest.raises(SystemExit) as info:
            parse(api, urdf_joint(kind, limit), "urdf")
        assert str(info.value) == limits_message(api)

    @pytest.mark.parametrize(
        ("kind", "label"),
        [("revolute", "Revolute"), ("prismatic", "Prismatic"), ("continuous", "Revolute")],
    )
    def test_urdf_negative_damping_is_the_constructors_error(
        self, api: Api, kind: str, label: str
    ) -> None:
        with pytest.raises(RuntimeError, match=rf"^{label} joint damping must be nonnegative.$"):
            parse(api, urdf_joint(kind, '<dynamics damping="-1"/>'), "urdf")


def mesh_urdf(element: str, path: Path, tag: str = "mesh") -> str:
    return (
        f'<robot name="r"><link name="a"><{element}><geometry>'
        f'<{tag} filename="file://{path}"/></geometry></{element}></link></robot>'
    )


def mesh_sdf(element: str, path: Path) -> str:
    return (
        '<sdf version="1.9"><model name="m"><link name="a">'
        f'<{element} name="g"><geometry><mesh><uri>file://{path}</uri></mesh></geometry>'
        f"</{element}></link></model></sdf>"
    )


def register(api: Api, shape: Any) -> tuple[Any, Any]:
    """Registers ``shape`` as a collision geometry of a body; returns (plant, inspector)."""
    assert api.plant is not None
    framework = importlib.import_module(f"{api.name}.systems.framework")
    plant, scene_graph = api.plant.AddMultibodyPlantSceneGraph(
        builder=framework.DiagramBuilder(), time_step=0.0
    )
    body = plant.AddRigidBody(name="b")
    plant.RegisterCollisionGeometry(
        body=body,
        X_BG=api.math.RigidTransform(),
        shape=shape,
        name="g",
        properties=api.geometry.ProximityProperties(),
    )
    return plant, scene_graph.model_inspector()


class TestProximityMeshes:
    @pytest.mark.parametrize("name", ["a.stl", "a.STL", "a.dae", "noext"])
    @pytest.mark.parametrize("shape", ["Mesh", "Convex"])
    def test_a_file_that_is_not_obj_vtk_or_gltf_has_no_hull(
        self, api: Api, tmp_path: Path, name: str, shape: str
    ) -> None:
        path = tmp_path / name
        path.write_text("solid x\nendsolid x\n")
        extension = Path(name).suffix.lower()
        with pytest.raises(RuntimeError) as info:
            register(api, getattr(api.geometry, shape)(str(path)))
        assert str(info.value) == (
            "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes; unsupported extension "
            f"'{extension}' for geometry data: {path}."
        )

    @pytest.mark.parametrize(
        ("text", "count"), [("", 0), ("garbage\n", 0), ("v 0 0 0\nv 1 0 0\n", 2)]
    )
    def test_fewer_than_three_vertices_have_no_hull(
        self, api: Api, tmp_path: Path, text: str, count: int
    ) -> None:
        path = tmp_path / "few.obj"
        path.write_text(text)
        with pytest.raises(RuntimeError) as info:
            register(api, api.geometry.Convex(str(path)))
        assert str(info.value) == (
            "MakeConvexHull() cannot be used on a mesh with fewer than three vertices; found "
            f"{count} vertices in geometry data: {path}."
        )

    @pytest.mark.parametrize("name", ["missing.obj", "missing.vtk", "missing.gltf", "missing.stl"])
    def test_a_missing_file_raises_its_readers_error(
        self, api: Api, tmp_path: Path, name: str
    ) -> None:
        path = tmp_path / name
        with pytest.raises(RuntimeError) as info:
            register(api, api.geometry.Convex(str(path)))
        if api.version != "1.51.1":
            # 1.58.0 checks that the file exists before anything else.
            assert str(info.value) == (
                f"Unable to access mesh file '{path}': No such file or directory"
            )
            return
        assert (
            str(info.value)
            == {
                "missing.obj": f"MemoryFile::Make() cannot read the file '{path}'.",
                "missing.vtk": "A mesh must contain at least one tetrahedron",
                "missing.gltf": (
                    f"glTF '{path}', named an inaccessible file: '<the .gltf file itself>'."
                ),
                "missing.stl": (
                    "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes; unsupported "
                    f"extension '.stl' for geometry data: {path}."
                ),
            }[name]
        )

    def test_a_vtk_cell_that_is_not_a_tetrahedron_is_named(self, api: Api, tmp_path: Path) -> None:
        path = tmp_path / "triangle.vtk"
        path.write_text(
            "# vtk DataFile Version 2.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n"
            "POINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n"
        )
        with pytest.raises(RuntimeError) as info:
            register(api, api.geometry.Convex(str(path)))
        assert str(info.value) == (
            "ReadVtkToVolumeMesh(): mesh data should only contain tetrahedra (type id=10). Read "
            f"cell with type id=5, dimension 2, and number of points 3 in '{path}'."
        )

    def test_vertices_within_1e_12_of_one_point_have_no_hull(
        self, api: Api, tmp_path: Path
    ) -> None:
        path = tmp_path / "point.obj"
        path.write_text("v 0 0 0\nv 1e-13 0 0\nv 0 1e-13 0\nv 0 0 1e-13\nf 1 2 3\n")
        with pytest.raises(RuntimeError) as info:
            register(api, api.geometry.Convex(str(path)))
        assert str(info.value) == (
            "MakeConvexHull failed because all vertices in the mesh were within a sphere with "
            f"radius 1e-12 for geometry: {path}."
        )

    def test_colinear_vertices_have_no_hull_at_the_scale_given(
        self, api: Api, tmp_path: Path
    ) -> None:
        path = tmp_path / "line.obj"
        path.write_text("v 0 0 0\nv 1 1 1\nv 2 2 2.0000000001\nf 1 2 3\n")
        register(api, api.geometry.Convex(str(path), 1.0))  # not co-linear at scale 1
        with pytest.raises(RuntimeError) as info:
            register(api, api.geometry.Convex(str(path), 1e-7))
        assert str(info.value) == (
            "MakeConvexHull failed because all vertices in the mesh appear to be co-linear for "
            f"file: {path}."
        )

    def test_coplanar_vertices_make_a_convex_hull(self, api: Api, tmp_path: Path) -> None:
        path = tmp_path / "square.obj"
        path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n")
        plant, inspector = register(api, api.geometry.Convex(str(path)))
        assert inspector.NumGeometriesWithRole(role=api.geometry.Role.kProximity) == 1
        assert len(plant.GetCollisionGeometriesForBody(body=plant.GetBodyByName("b"))) == 1

    def test_a_mesh_obj_without_faces_has_no_triangle_mesh_on_1_51(
        self, api: Api, tmp_path: Path
    ) -> None:
        no_elements, lines_only = tmp_path / "points.obj", tmp_path / "lines.obj"
        no_elements.write_text(TETRAHEDRON)
        lines_only.write_text(TETRAHEDRON + "l 1 2\n")
        if api.version != "1.51.1":
            # 1.58.0 no longer reads a Mesh's OBJ as a triangle mesh when it registers it.
            register(api, api.geometry.Mesh(str(no_elements)))
            register(api, api.geometry.Mesh(str(lines_only)))
            return
        with pytest.raises(RuntimeError) as info:
            register(api, api.geometry.Mesh(str(no_elements)))
        assert str(info.value) == (
            "error: The OBJ data parsed contains no objects; the data could be corrupt, empty, "
            f"or not an OBJ file. Name: '{no_elements}'"
        )
        with pytest.raises(RuntimeError, match=r"^A mesh must contain at least one triangle$"):
            register(api, api.geometry.Mesh(str(lines_only)))
        register(api, api.geometry.Convex(str(no_elements)))  # a Convex needs no faces

    def test_a_failed_hull_leaves_the_geometry_registered(self, api: Api, tmp_path: Path) -> None:
        assert api.plant is not None
        framework = importlib.import_module(f"{api.name}.systems.framework")
        plant, scene_graph = api.plant.AddMultibodyPlantSceneGraph(
            builder=framework.DiagramBuilder(), time_step=0.0
        )
        body = plant.AddRigidBody(name="b")
        stl = tmp_path / "a.stl"
        stl.write_text("solid x\nendsolid x\n")
        with pytest.raises(RuntimeError, match=r"^MakeConvexHull only applies"):
            plant.RegisterCollisionGeometry(
                body=body,
                X_BG=api.math.RigidTransform(),
                shape=api.geometry.Mesh(str(stl)),
                name="g",
                properties=api.geometry.ProximityProperties(),
            )
        inspector = scene_graph.model_inspector()
        assert inspector.num_geometries() == 1
        assert plant.GetCollisionGeometriesForBody(body=body) == []

    def test_a_visual_mesh_is_not_read(self, api: Api, tmp_path: Path) -> None:
        empty = tmp_path / "empty.obj"
        empty.write_text("")
        inspector = parse(api, mesh_urdf("visual", empty), "urdf")
        assert inspector.NumGeometriesWithRole(role=api.geometry.Role.kIllustration) == 1
        stl = tmp_path / "a.stl"
        stl.write_text("solid x\nendsolid x\n")
        inspector = parse(api, mesh_sdf("visual", stl), "sdf")
        assert inspector.NumGeometriesWithRole(role=api.geometry.Role.kIllustration) == 1


class TestProximityMeshesInParsedModels:
    def test_a_urdf_collision_stl_fails_the_parse(self, api: Api, tmp_path: Path) -> None:
        stl = tmp_path / "a.stl"
        stl.write_text("solid x\nendsolid x\n")
        with pytest.raises(RuntimeError) as info:
            parse(api, mesh_urdf("collision", stl), "urdf")
        assert str(info.value) == (
            "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes; unsupported extension "
            f"'.stl' for geometry data: {stl}."
        )

    def test_an_sdformat_collision_obj_without_vertices_fails_the_parse(
        self, api: Api, tmp_path: Path
    ) -> None:
        empty = tmp_path / "empty.obj"
        empty.write_text("")
        with pytest.raises(
            RuntimeError,
            match=re.escape(
                "MakeConvexHull() cannot be used on a mesh with fewer than three vertices; found 0 "
                f"vertices in geometry data: {empty}."
            ),
        ):
            parse(api, mesh_sdf("collision", empty), "sdf")
