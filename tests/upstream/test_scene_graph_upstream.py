# Ported from Drake: bindings/pydrake/geometry/test/scene_graph_test.py
# (https://github.com/RobotLocomotion/drake), the parts about the collision-filtering
# subset, re-expressed as pytest functions that run unchanged on pydrake and on reimpl.
# Expected values are upstream's, re-measured on pydrake 1.51.1 where a left-out part
# (deformable or hydroelastic geometry, renderers) changed a count.
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
"""Upstream SceneGraph binding tests, filter subset, on pydrake and on reimpl."""

from __future__ import annotations

from types import ModuleType
from typing import Any

import pytest


def _sphere(drake: ModuleType, name: str, radius: float = 1.0) -> Any:
    g = drake.geometry
    return g.GeometryInstance(
        X_PG=drake.math.RigidTransform_[float](), shape=g.Sphere(radius), name=name
    )


class TestSceneGraphApi:
    """Upstream ``test_scene_graph_api`` without renderers, hydroelastics and deformables.

    Scene: source "anchored"; frame anchored_frame1 (child anchored_frame2);
    sphere1 (no role) and sphere2 (proximity) on anchored_frame1; sphere3
    anchored (proximity).
    """

    @pytest.fixture
    def setup(self, drake: ModuleType) -> dict[str, Any]:
        g = drake.geometry
        scene_graph = g.SceneGraph_[float]()
        source = scene_graph.RegisterSource("anchored")
        frame = scene_graph.RegisterFrame(
            source_id=source, frame=g.GeometryFrame("anchored_frame1")
        )
        scene_graph.RenameFrame(frame_id=frame, name="something")
        scene_graph.RenameFrame(frame_id=frame, name="anchored_frame1")
        scene_graph.RegisterFrame(
            source_id=source, parent_id=frame, frame=g.GeometryFrame("anchored_frame2")
        )
        sphere1 = scene_graph.RegisterGeometry(
            source_id=source, frame_id=frame, geometry=_sphere(drake, "sphere1", 0.1)
        )
        sphere2 = scene_graph.RegisterGeometry(
            source_id=source, frame_id=frame, geometry=_sphere(drake, "sphere2")
        )
        scene_graph.RenameGeometry(geometry_id=sphere2, name="else")
        scene_graph.RenameGeometry(geometry_id=sphere2, name="sphere2")
        scene_graph.AssignRole(
            source_id=source, geometry_id=sphere2, properties=g.ProximityProperties()
        )
        sphere3 = scene_graph.RegisterAnchoredGeometry(
            source_id=source, geometry=_sphere(drake, "sphere3")
        )
        scene_graph.AssignRole(
            source_id=source, geometry_id=sphere3, properties=g.ProximityProperties()
        )
        return {
            "scene_graph": scene_graph,
            "source": source,
            "frame": frame,
            "sphere1": sphere1,
            "sphere2": sphere2,
            "sphere3": sphere3,
        }

    def test_ports_are_the_scalar_template_port_types(
        self, drake: ModuleType, setup: dict[str, Any]
    ) -> None:
        framework = drake.systems.framework
        scene_graph, source = setup["scene_graph"], setup["source"]
        assert isinstance(scene_graph.get_source_pose_port(source), framework.InputPort_[float])
        assert isinstance(
            scene_graph.get_source_configuration_port(source), framework.InputPort_[float]
        )
        assert isinstance(scene_graph.get_query_output_port(), framework.OutputPort_[float])

    def test_inspector_counts(self, drake: ModuleType, setup: dict[str, Any]) -> None:
        g = drake.geometry
        inspector = setup["scene_graph"].model_inspector()
        assert inspector.num_sources() == 2
        assert inspector.num_frames() == 3
        assert len(inspector.GetAllSourceIds()) == 2
        assert len(inspector.GetAllFrameIds()) == 3
        assert inspector.world_frame_id() in inspector.GetAllFrameIds()
        assert setup["frame"] in inspector.GetAllFrameIds()
        assert isinstance(inspector.world_frame_id(), g.FrameId)
        assert inspector.num_geometries() == 3
        assert len(inspector.GetAllGeometryIds()) == 3
        assert len(inspector.GetAllGeometryIds(role=g.Role.kProximity)) == 2
        assert inspector.NumGeometriesWithRole(role=g.Role.kUnassigned) == 1
        assert inspector.NumDynamicGeometries() == 2
        assert inspector.NumAnchoredGeometries() == 1
        # sphere2 (dynamic) and sphere3 (anchored) are the one candidate pair.
        assert len(inspector.GetCollisionCandidates()) == 1

    def test_geometry_set_spellings_resolve_the_same(
        self, drake: ModuleType, setup: dict[str, Any]
    ) -> None:
        g = drake.geometry
        inspector = setup["scene_graph"].model_inspector()
        frame, sphere1 = setup["frame"], setup["sphere1"]
        empty = g.GeometrySet()
        assert len(inspector.GetGeometryIds(empty)) == 0
        assert len(inspector.GetGeometryIds(empty, g.Role.kProximity)) == 0

        frame_sets = [
            g.GeometrySet(frame_id=frame),
            g.GeometrySet(frame_ids=[frame]),
            g.GeometrySet([frame]),
            g.GeometrySet(geometry_ids=[], frame_ids=[frame]),
            g.GeometrySet([], [frame]),
        ]
        for kwargs in (
            {"frame_id": frame},
            {"frame_ids": [frame]},
            {"geometry_ids": [], "frame_ids": [frame]},
        ):
            added = g.GeometrySet()
            added.Add(**kwargs)
            frame_sets.append(added)
        # sphere1 and sphere2 are affixed to the frame.
        assert [len(inspector.GetGeometryIds(s)) for s in frame_sets] == [2] * 8

        geometry_sets = [
            g.GeometrySet(geometry_id=sphere1),
            g.GeometrySet(geometry_ids=[sphere1]),
            g.GeometrySet([sphere1]),
            g.GeometrySet(geometry_ids=[sphere1], frame_ids=[]),
            g.GeometrySet([sphere1], []),
        ]
        for kwargs in (
            {"geometry_id": sphere1},
            {"geometry_ids": [sphere1]},
            {"geometry_ids": [sphere1], "frame_ids": []},
        ):
            added = g.GeometrySet()
            added.Add(**kwargs)
            geometry_sets.append(added)
        assert [len(inspector.GetGeometryIds(s)) for s in geometry_sets] == [1] * 8

    def test_inspector_source_frame_and_geometry_queries(
        self, drake: ModuleType, setup: dict[str, Any]
    ) -> None:
        g = drake.geometry
        inspector = setup["scene_graph"].model_inspector()
        source, frame, sphere1 = setup["source"], setup["frame"], setup["sphere1"]
        assert inspector.SourceIsRegistered(source_id=source)
        assert inspector.SourceIsRegistered(source)
        assert inspector.NumFramesForSource(source_id=source) == 2
        assert frame in inspector.FramesForSource(source_id=source)
        assert inspector.BelongsToSource(frame_id=frame, source_id=source)
        assert inspector.GetOwningSourceName(frame_id=frame) == "anchored"
        assert inspector.GetName(frame_id=frame) == "anchored_frame1"
        assert inspector.GetFrameGroup(frame_id=frame) == 0
        assert inspector.NumGeometriesForFrame(frame_id=frame) == 2
        assert inspector.NumGeometriesForFrameWithRole(frame_id=frame, role=g.Role.kProximity) == 1
        assert len(inspector.GetGeometries(frame_id=frame)) == 2
        assert sphere1 in inspector.GetGeometries(frame_id=frame)
        assert len(inspector.GetGeometries(frame_id=frame, role=g.Role.kProximity)) == 1
        assert (
            inspector.GetGeometryIdByName(frame_id=frame, role=g.Role.kUnassigned, name="sphere1")
            == sphere1
        )
        assert inspector.BelongsToSource(geometry_id=sphere1, source_id=source)
        assert inspector.GetOwningSourceName(geometry_id=sphere1) == "anchored"
        assert inspector.GetFrameId(sphere1) == frame
        assert inspector.GetName(geometry_id=sphere1) == "sphere1"
        assert isinstance(inspector.GetShape(geometry_id=sphere1), g.Sphere)
        assert isinstance(
            inspector.GetPoseInFrame(geometry_id=sphere1), drake.math.RigidTransform_[float]
        )

    def test_inspector_parent_frame(
        self, drake: ModuleType, api: Any, setup: dict[str, Any]
    ) -> None:
        """Upstream's ``GetParentFrame(frame_id=global_frame) == world_frame_id()``.

        Bound since pydrake 1.52 (upstream's test at v1.56+ asserts it); pydrake
        1.51.1 has no GetParentFrame. reimpl has it, as 1.58.0 does.
        """
        g = drake.geometry
        inspector = setup["scene_graph"].model_inspector()
        frame = setup["frame"]
        if api.name == "pydrake" and api.version == "1.51.1":
            assert not hasattr(inspector, "GetParentFrame")
            return
        assert inspector.GetParentFrame(frame_id=frame) == g.SceneGraph.world_frame_id()
        (child,) = [f for f in inspector.FramesForSource(source_id=setup["source"]) if f != frame]
        assert inspector.GetParentFrame(frame_id=child) == frame
        world = g.SceneGraph.world_frame_id()
        assert inspector.GetParentFrame(frame_id=world) == world
        unknown = g.FrameId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            inspector.GetParentFrame(frame_id=unknown)
        assert str(info.value) == (
            f"No frame name available for invalid frame id: {unknown.get_value()}"
        )
        with pytest.raises(TypeError):
            inspector.GetParentFrame(frame_id=setup["sphere1"])

    def test_roles_assign_and_remove_on_model_and_context(
        self, drake: ModuleType, setup: dict[str, Any]
    ) -> None:
        g = drake.geometry
        scene_graph, source = setup["scene_graph"], setup["source"]
        frame, sphere1 = setup["frame"], setup["sphere1"]
        inspector = scene_graph.model_inspector()
        context = scene_graph.CreateDefaultContext()
        # N.B. Upstream adds a RenderLabel to the perception properties; the
        # assignment does not need it.
        for properties in (
            g.ProximityProperties(),
            g.PerceptionProperties(),
            g.IllustrationProperties(),
        ):
            scene_graph.AssignRole(
                source_id=source,
                geometry_id=sphere1,
                properties=properties,
                assign=g.RoleAssign.kNew,
            )
            scene_graph.AssignRole(
                context=context,
                source_id=source,
                geometry_id=sphere1,
                properties=properties,
                assign=g.RoleAssign.kNew,
            )

        assert isinstance(
            inspector.GetProximityProperties(geometry_id=sphere1), g.ProximityProperties
        )
        assert isinstance(
            inspector.GetProperties(geometry_id=sphere1, role=g.Role.kProximity),
            g.ProximityProperties,
        )
        assert isinstance(
            inspector.GetIllustrationProperties(geometry_id=sphere1), g.IllustrationProperties
        )
        assert isinstance(
            inspector.GetProperties(geometry_id=sphere1, role=g.Role.kIllustration),
            g.IllustrationProperties,
        )
        assert isinstance(
            inspector.GetPerceptionProperties(geometry_id=sphere1), g.PerceptionProperties
        )
        assert isinstance(
            inspector.GetProperties(geometry_id=sphere1, role=g.Role.kPerception),
            g.PerceptionProperties,
        )
        assert isinstance(inspector.CloneGeometryInstance(geometry_id=sphere1), g.GeometryInstance)
        assert inspector.CollisionFiltered(geometry_id1=sphere1, geometry_id2=sphere1)

        for i, role in enumerate((g.Role.kProximity, g.Role.kPerception, g.Role.kIllustration)):
            assert scene_graph.RemoveRole(source_id=source, geometry_id=sphere1, role=role) == 1
            assert (
                scene_graph.RemoveRole(
                    context=context, source_id=source, geometry_id=sphere1, role=role
                )
                == 1
            )
            # Only sphere2 (proximity) is left with a role on the frame.
            expected = 1 if i == 0 else 0
            assert scene_graph.RemoveRole(source_id=source, frame_id=frame, role=role) == expected
            assert (
                scene_graph.RemoveRole(context=context, source_id=source, frame_id=frame, role=role)
                == expected
            )


def test_scene_graph_register_geometry(drake: ModuleType) -> None:
    """Upstream ``test_scene_graph_register_geometry`` without the deformable part."""
    g = drake.geometry
    scene_graph = g.SceneGraph_[float]()
    source = scene_graph.RegisterSource("anchored")
    world = scene_graph.world_frame_id()
    context = scene_graph.CreateDefaultContext()
    model_inspector = scene_graph.model_inspector()
    context_inspector = scene_graph.get_query_output_port().Eval(context).inspector()
    assert model_inspector.num_geometries() == 0
    assert context_inspector.num_geometries() == 0

    scene_graph.RegisterGeometry(
        context=context, source_id=source, frame_id=world, geometry=_sphere(drake, "sphere1")
    )
    assert model_inspector.num_geometries() == 0
    assert context_inspector.num_geometries() == 1

    scene_graph.RegisterGeometry(
        source_id=source, frame_id=world, geometry=_sphere(drake, "sphere1")
    )
    assert model_inspector.num_geometries() == 1
    assert context_inspector.num_geometries() == 1


def test_scene_graph_remove_geometry(drake: ModuleType) -> None:
    g = drake.geometry
    scene_graph = g.SceneGraph_[float]()
    source = scene_graph.RegisterSource("anchored")
    geometry = scene_graph.RegisterGeometry(
        source_id=source, frame_id=scene_graph.world_frame_id(), geometry=_sphere(drake, "sphere1")
    )
    context = scene_graph.CreateDefaultContext()
    model_inspector = scene_graph.model_inspector()
    context_inspector = scene_graph.get_query_output_port().Eval(context).inspector()
    scene_graph.RemoveGeometry(context=context, source_id=source, geometry_id=geometry)
    assert model_inspector.num_geometries() == 1
    assert context_inspector.num_geometries() == 0
    scene_graph.RemoveGeometry(source_id=source, geometry_id=geometry)
    assert model_inspector.num_geometries() == 0


def test_frame_pose_vector_api(drake: ModuleType) -> None:
    g = drake.geometry
    RigidTransform = drake.math.RigidTransform_[float]
    poses = g.FramePoseVector_[float]()
    frame_id = g.FrameId.get_new_id()
    poses.set_value(id=frame_id, value=RigidTransform.Identity())
    assert poses.size() == 1
    assert isinstance(poses.value(id=frame_id), RigidTransform)
    assert poses.has_id(id=frame_id)
    assert isinstance(poses.ids(), list)
    assert isinstance(poses.ids()[0], g.FrameId)
    poses.clear()
    assert poses.size() == 0


def test_query_object_serves_the_inspector(drake: ModuleType) -> None:
    """Upstream ``test_query_object``, reduced to what the filter subset has: the inspector."""
    g = drake.geometry
    QueryObject = g.QueryObject_[float]
    assert isinstance(QueryObject(), QueryObject)

    scene_graph = g.SceneGraph_[float]()
    source = scene_graph.RegisterSource("source")
    frame = scene_graph.RegisterFrame(source_id=source, frame=g.GeometryFrame("frame"))
    scene_graph.RegisterGeometry(
        source_id=source, frame_id=frame, geometry=_sphere(drake, "sphere")
    )
    context = scene_graph.CreateDefaultContext()
    poses = g.FramePoseVector_[float]()
    poses.set_value(frame, drake.math.RigidTransform_[float]())
    scene_graph.get_source_pose_port(source).FixValue(context, poses)
    query_object = scene_graph.get_query_output_port().Eval(context)
    assert isinstance(query_object, QueryObject)
    assert isinstance(query_object.inspector(), g.SceneGraphInspector_[float])
    assert query_object.inspector().num_geometries() == 1


def test_value_instantiations(drake: ModuleType) -> None:
    Value = drake.common.value.Value
    g = drake.geometry
    assert issubclass(Value[g.FramePoseVector_[float]], drake.common.value.AbstractValue)
    assert issubclass(Value[g.QueryObject_[float]], drake.common.value.AbstractValue)
