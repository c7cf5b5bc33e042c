"""A call that fails each DRAKE_DEMAND reimpl reproduces, on pydrake or on reimpl.

Each trigger takes the root module (``pydrake`` or ``reimpl``; the two have the
same module paths) and makes one call that fails the demand, using pydrake's
keyword arguments. tools/measure_demand_lines.py runs them on a pydrake release
to measure where it reports each demand (reimpl/common/demand_lines.json);
tests/upstream/test_demand_lines.py runs them on both implementations and
compares the messages.

The ids are those of reimpl/common/demand_lines.json.
"""

from __future__ import annotations

import contextlib
import importlib
import tempfile
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

__all__ = ["TRIGGERS", "Trigger"]

Trigger = Callable[[ModuleType], Any]
#: pydrake's Parser keeps no plant alive, nor a plant its SceneGraph: they live here.
_KEEP: list[Any] = []


def _module(root: ModuleType, name: str) -> Any:
    return importlib.import_module(f"{root.__name__}.{name}")


def _plant(root: ModuleType) -> Any:
    plant = _module(root, "multibody.plant").MultibodyPlant(time_step=0.0)
    _KEEP.append(plant)
    return plant


def _inertia(root: ModuleType) -> Any:
    tree = _module(root, "multibody.tree")
    return tree.SpatialInertia(
        mass=1.0, p_PScm_E=[0.0, 0.0, 0.0], G_SP_E=tree.UnitInertia(1.0, 1.0, 1.0)
    )


def _body(root: ModuleType, plant: Any, name: str = "b", **kwargs: Any) -> Any:
    return plant.AddRigidBody(name=name, M_BBo_B=_inertia(root), **kwargs)


def _interleaved(root: ModuleType) -> tuple[Any, Any]:
    """A finalized plant whose instance ``a`` has positions 0 and 2 (``b`` has 1), and ``a``."""
    tree = _module(root, "multibody.tree")
    plant = _plant(root)
    a = plant.AddModelInstance(name="a")
    b = plant.AddModelInstance(name="b")
    for name, instance in (("a1", a), ("b1", b), ("a2", a)):
        body = _body(root, plant, name, model_instance=instance)
        plant.AddJoint(
            tree.RevoluteJoint(
                name=f"j{name}",
                frame_on_parent=plant.world_frame(),
                frame_on_child=body.body_frame(),
                axis=[0.0, 0.0, 1.0],
            )
        )
    plant.Finalize()
    return plant, a


def _negative_time_step(root: ModuleType) -> Any:
    return _module(root, "multibody.plant").MultibodyPlant(time_step=-1.0)


def _register_twice(root: ModuleType) -> Any:
    geometry = _module(root, "geometry")
    plant = _plant(root)
    _KEEP.extend(graphs := [geometry.SceneGraph(), geometry.SceneGraph()])
    plant.RegisterAsSourceForSceneGraph(scene_graph=graphs[0])
    return plant.RegisterAsSourceForSceneGraph(scene_graph=graphs[1])


def _register_visual(root: ModuleType) -> Any:
    plant = _plant(root)
    return plant.RegisterVisualGeometry(
        body=_body(root, plant),
        X_BG=_module(root, "math").RigidTransform(),
        shape=_module(root, "geometry").Sphere(radius=1.0),
        name="v",
        diffuse_color=[1.0, 1.0, 1.0, 1.0],
    )


def _register_collision(root: ModuleType) -> Any:
    plant = _plant(root)
    friction = _module(root, "multibody.plant").CoulombFriction
    return plant.RegisterCollisionGeometry(
        body=_body(root, plant),
        X_BG=_module(root, "math").RigidTransform(),
        shape=_module(root, "geometry").Sphere(radius=1.0),
        name="c",
        coulomb_friction=friction(static_friction=1.0, dynamic_friction=1.0),
    )


def _collect(root: ModuleType) -> Any:
    plant = _plant(root)
    return plant.CollectRegisteredGeometries(bodies=[_body(root, plant)])


def _rename_finalized(root: ModuleType) -> Any:
    plant = _plant(root)
    instance = plant.AddModelInstance(name="m")
    plant.Finalize()
    return plant.RenameModelInstance(model_instance=instance, name="n")


def _set_positions(instance: bool, finite: bool) -> Trigger:
    """q of the wrong size (one too many), or of the right size but not finite."""

    def trigger(root: ModuleType) -> Any:
        plant, a = _interleaved(root)
        context = plant.CreateDefaultContext()
        size = 2 if instance else 3
        q = [float("nan")] * size if finite else [0.0] * (size + 1)
        if instance:
            return plant.SetPositions(context=context, model_instance=a, q=q)
        return plant.SetPositions(context=context, q=q)

    return trigger


def _set_default_positions(instance: bool) -> Trigger:
    def trigger(root: ModuleType) -> Any:
        plant, a = _interleaved(root)
        if instance:
            return plant.SetDefaultPositions(model_instance=a, q_instance=[0.0])
        return plant.SetDefaultPositions(q=[0.0])

    return trigger


def _names(kind: str) -> Trigger:
    """The names of an instance whose coordinates are not contiguous."""

    def trigger(root: ModuleType) -> Any:
        plant, a = _interleaved(root)
        return getattr(plant, f"Get{kind}Names")(model_instance=a)

    return trigger


def _listing(method: str) -> Trigger:
    def trigger(root: ModuleType) -> Any:
        plant = _plant(root)
        plant.Finalize()
        return getattr(plant, method)(_module(root, "multibody.tree").ModelInstanceIndex(99))

    return trigger


def _unique_base_body(root: ModuleType) -> Any:
    plant = _plant(root)
    plant.Finalize()
    index = _module(root, "multibody.tree").ModelInstanceIndex(99)
    return plant.HasUniqueFloatingBaseBody(model_instance=index)


def _empty_instance_name(root: ModuleType) -> Any:
    return _plant(root).AddModelInstance(name="")


def _invalid_directives(root: ModuleType) -> Any:
    load = _module(root, "multibody.parsing").LoadModelDirectivesFromString
    return load(model_directives="directives:\n- add_model_instance:\n")


def _unmatched_weld(root: ModuleType) -> Any:
    """add_weld of a child in a model these directives did not add."""
    parser = _module(root, "multibody.parsing").Parser
    plant = _plant(root)
    robot = "<robot name='r'><link name='l'/></robot>"
    parser(plant=plant).AddModelsFromString(file_contents=robot, file_type="urdf")
    weld = "directives:\n- add_weld: {parent: world, child: r::l}\n"
    return parser(plant=plant).AddModelsFromString(file_contents=weld, file_type="dmd.yaml")


def _parser_without_plant(root: ModuleType) -> Any:
    return _module(root, "multibody.parsing").Parser(None)


def _flatten_invalid_frame(root: ModuleType) -> Any:
    parsing = _module(root, "multibody.parsing")
    transform = _module(root, "common.schema").Transform
    frame = parsing.AddFrame(name="", X_PF=transform(base_frame="world"))
    directives = parsing.ModelDirectives(directives=[parsing.ModelDirective(add_frame=frame)])
    return parsing.FlattenModelDirectives(directives=directives, package_map=parsing.PackageMap())


def _group_twice(root: ModuleType) -> Any:
    groups = _module(root, "multibody.parsing").CollisionFilterGroups()
    groups.AddGroup(name="g", members={"a"})
    return groups.AddGroup(name="g", members={"a"})


def _read_finalized(file_name: str) -> Trigger:
    """A reader's check that the plant (no SceneGraph source) is not finalized; it comes
    before the file is opened, so the file need not exist."""

    def trigger(root: ModuleType) -> Any:
        plant = _plant(root)
        plant.Finalize()
        return _module(root, "multibody.parsing").Parser(plant=plant).AddModels(file_name=file_name)

    return trigger


def _parse_into_finalized_source(root: ModuleType) -> Any:
    """A parse into a finalized plant that is a SceneGraph source."""
    plant = _plant(root)
    _KEEP.append(scene_graph := _module(root, "geometry").SceneGraph())
    plant.RegisterAsSourceForSceneGraph(scene_graph=scene_graph)
    plant.Finalize()
    parser = _module(root, "multibody.parsing").Parser(plant=plant)
    return parser.AddModelsFromString(file_contents="<robot name='r'/>", file_type="urdf")


def _scene_graph_after_finalize(root: ModuleType) -> Any:
    plant = _plant(root)
    _KEEP.append(scene_graph := _module(root, "geometry").SceneGraph())
    plant.RegisterAsSourceForSceneGraph(scene_graph=scene_graph)
    parser = _module(root, "multibody.parsing").Parser(plant=plant)
    plant.Finalize()
    return parser.scene_graph()


def _fix_older_context(root: ModuleType) -> Any:
    """Fixing a source's pose port in a SceneGraph context made before the source."""
    geometry = _module(root, "geometry")
    _KEEP.append(scene_graph := geometry.SceneGraph())
    context = scene_graph.CreateDefaultContext()
    source = scene_graph.RegisterSource(name="s")
    port = scene_graph.get_source_pose_port(source)
    return port.FixValue(context, geometry.FramePoseVector())


def _wire_twice(root: ModuleType) -> Any:
    builder = _module(root, "systems.framework").DiagramBuilder()
    _KEEP.append(builder)
    plant, scene_graph = _module(root, "multibody.plant").AddMultibodyPlantSceneGraph(
        builder, time_step=0.0
    )
    return builder.Connect(
        scene_graph.get_query_output_port(), plant.get_geometry_query_input_port()
    )


def _random_rotation(root: ModuleType) -> Any:
    schema = _module(root, "common.schema")
    rotation = schema.Rotation()
    rotation.value = schema.Rotation.Uniform()
    return rotation


def _rotation_value(root: ModuleType) -> Any:
    return _random_rotation(root).GetDeterministicValue()


def _transform_value(root: ModuleType) -> Any:
    transform = _module(root, "common.schema").Transform()
    transform.rotation = _random_rotation(root)
    return transform.GetDeterministicValue()


def _change_anchored_activity(activate: bool) -> Trigger:
    """Deactivating anchored proximity geometry (and then activating it again)."""

    def trigger(root: ModuleType) -> Any:
        geometry = _module(root, "geometry")
        _KEEP.append(scene_graph := geometry.SceneGraph())
        source = scene_graph.RegisterSource(name="s")
        instance = geometry.GeometryInstance(
            X_PG=_module(root, "math").RigidTransform(),
            shape=geometry.Sphere(radius=1.0),
            name="g",
        )
        anchored = scene_graph.RegisterAnchoredGeometry(source_id=source, geometry=instance)
        scene_graph.AssignRole(
            source_id=source, geometry_id=anchored, properties=geometry.ProximityProperties()
        )
        manager = scene_graph.collision_filter_manager()
        anchored_set = geometry.GeometrySet(geometry_ids=[anchored])
        if not activate:
            return manager.Deactivate(geometry_set=anchored_set)
        # N.B. Where Deactivate fails its own demand, the geometry is inactive all the same.
        with contextlib.suppress(SystemExit):
            manager.Deactivate(geometry_set=anchored_set)
        return manager.Activate(geometry_set=anchored_set)

    return trigger


def _package_map_call(method: str, **kwargs: Any) -> Trigger:
    def trigger(root: ModuleType) -> Any:
        return getattr(_module(root, "multibody.parsing").PackageMap(), method)(**kwargs)

    return trigger


def _manifest(name_element: str) -> Trigger:
    """A package.xml whose <name> is ``name_element``."""

    def trigger(root: ModuleType) -> Any:
        folder = Path(tempfile.mkdtemp())
        manifest = folder / "package.xml"
        manifest.write_text(f"<package>{name_element}</package>\n", "utf-8")
        package_map = _module(root, "multibody.parsing").PackageMap()
        return package_map.AddPackageXml(filename=str(manifest))

    return trigger


def _group_in_older_instance(root: ModuleType) -> Any:
    """A directives group whose model_namespace is an instance an earlier parse made."""
    parser = _module(root, "multibody.parsing").Parser
    plant = _plant(root)
    _KEEP.append(scene_graph := _module(root, "geometry").SceneGraph())
    plant.RegisterAsSourceForSceneGraph(scene_graph=scene_graph)
    robot = "<robot name='r'><link name='l'/></robot>"
    parser(plant=plant).AddModelsFromString(file_contents=robot, file_type="urdf")
    group = (
        "directives:\n- add_collision_filter_group: {name: g, model_namespace: r, members: [l]}\n"
    )
    return parser(plant=plant).AddModelsFromString(file_contents=group, file_type="dmd.yaml")


def _world_body_call(method: str, *args: Any) -> Trigger:
    """A floating-body accessor of the world body (not floating) of a finalized plant."""

    def trigger(root: ModuleType) -> Any:
        plant = _plant(root)
        plant.Finalize()
        return getattr(plant.world_body(), method)(*args)

    return trigger


def _free_body_call(method: str, *args: Any) -> Trigger:
    """A floating-body accessor of a free body, with an index out of range."""

    def trigger(root: ModuleType) -> Any:
        plant = _plant(root)
        body = _body(root, plant)
        plant.Finalize()
        return getattr(body, method)(*args)

    return trigger


def _unfinalized_joint_call(method: str, *args: Any) -> Trigger:
    """A joint accessor that needs the mobilizer Finalize makes, before Finalize."""

    def trigger(root: ModuleType) -> Any:
        plant, _ = _revolute(root)
        return getattr(plant.GetJointByName("j"), method)(*args)

    return trigger


def _revolute(root: ModuleType) -> tuple[Any, Any]:
    plant = _plant(root)
    body = _body(root, plant)
    joint = _module(root, "multibody.tree").RevoluteJoint(
        name="j",
        frame_on_parent=plant.world_frame(),
        frame_on_child=body.body_frame(),
        axis=[0.0, 0.0, 1.0],
    )
    return plant, plant.AddJoint(joint)


def _joint_with(kind: str, **parameters: Any) -> Trigger:
    """A ``kind`` joint between the world and a body, built with ``parameters``."""

    def trigger(root: ModuleType) -> Any:
        plant = _plant(root)
        body = _body(root, plant)
        joint = getattr(_module(root, "multibody.tree"), kind)
        return joint(
            name="j",
            frame_on_parent=plant.world_frame(),
            frame_on_child=body.body_frame(),
            **parameters,
        )

    return trigger


#: Each shape's measures in its constructor's order (geometry/shape_specification.cc).
_SHAPE_MEASURES = {
    "Box": ("width", "depth", "height"),
    "Capsule": ("radius", "length"),
    "Cylinder": ("radius", "length"),
    "Ellipsoid": ("a", "b", "c"),
    "MeshcatCone": ("height", "a", "b"),
    "Sphere": ("radius",),
}


def _bad_shape(shape: str, measure: str) -> Trigger:
    """A ``shape`` whose ``measure`` is -1 (the others 1)."""

    def trigger(root: ModuleType) -> Any:
        values = {m: -1.0 if m == measure else 1.0 for m in _SHAPE_MEASURES[shape]}
        return getattr(_module(root, "geometry"), shape)(**values)

    return trigger


def _zero_normal_pose(root: ModuleType) -> Any:
    half_space = _module(root, "geometry").HalfSpace
    return half_space.MakePose(Hz_dir_F=[0.0, 0.0, 0.0], p_FB=[0.0, 0.0, 0.0])


#: Each demand (its id in reimpl/common/demand_lines.json) and a call that fails it.
TRIGGERS: dict[str, Trigger] = {
    "MultibodyPlant.time_step": _negative_time_step,
    "RegisterAsSourceForSceneGraph.registered": _register_twice,
    "RegisterVisualGeometry.no_source": _register_visual,
    "RegisterCollisionGeometry.no_source": _register_collision,
    "CollectRegisteredGeometries.no_source": _collect,
    "RenameModelInstance.finalized": _rename_finalized,
    "SetPositions.q.size": _set_positions(instance=False, finite=False),
    "SetPositions.q.finite": _set_positions(instance=False, finite=True),
    "SetPositions.q_instance.size": _set_positions(instance=True, finite=False),
    "SetPositions.q_instance.finite": _set_positions(instance=True, finite=True),
    "SetDefaultPositions.q.size": _set_default_positions(instance=False),
    "SetDefaultPositions.q_instance.size": _set_default_positions(instance=True),
    "GetPositionNames.fits": _names("Position"),
    "GetVelocityNames.fits": _names("Velocity"),
    "GetBodyIndices.instance": _listing("GetBodyIndices"),
    "GetJointIndices.instance": _listing("GetJointIndices"),
    "GetFrameIndices.instance": _listing("GetFrameIndices"),
    "MaybeGetUniqueBaseBodyIndex.instance": _unique_base_body,
    "ModelInstance.set_name": _empty_instance_name,
    "LoadModelDirectives.valid": _invalid_directives,
    "AddWeld.found": _unmatched_weld,
    "Parser.plant": _parser_without_plant,
    "ApplyDirectiveNamespace.valid": _flatten_invalid_frame,
    "CollisionFilterGroups.AddGroup.new": _group_twice,
    "AddOrMergeModelFromUrdf.finalized": _read_finalized("missing.urdf"),
    "AddModelsFromSdf.finalized": _read_finalized("missing.sdf"),
    "AddOrMergeModelFromMujocoXml.finalized": _read_finalized("missing.xml"),
    "AddModelFromMesh.finalized": _read_finalized("missing.obj"),
    "GetMutableSceneGraphPreFinalize.finalized": _parse_into_finalized_source,
    "Parser.scene_graph.finalized": _scene_graph_after_finalize,
    "SetFixedInputPortValue.index": _fix_older_context,
    "ThrowIfInputAlreadyWired.wired": _wire_twice,
    "Rotation.GetDeterministicValue": _rotation_value,
    "Transform.GetDeterministicValue": _transform_value,
    "ApplyActiveStatusChange.deactivate": _change_anchored_activity(activate=False),
    "ApplyActiveStatusChange.activate": _change_anchored_activity(activate=True),
    "PackageMap.GetPath.contains": _package_map_call("GetPath", package_name="nowhere"),
    "PackageMap.AddPackageXml.filename": _package_map_call("AddPackageXml", filename=""),
    "PackageMap.PopulateFromFolder.path": _package_map_call("PopulateFromFolder", path=""),
    "PackageMap.PopulateFromEnvironment.variable": _package_map_call(
        "PopulateFromEnvironment", environment_variable=""
    ),
    "ParsePackageManifest.name_children": _manifest("<name/>"),
    "ParsePackageManifest.name": _manifest("<name><!----></name>"),
    "CollisionFilterGroupResolver.AddGroup.instance": _group_in_older_instance,
    "RigidBody.floating_positions_start.floating": _world_body_call("floating_positions_start"),
    "RigidBody.floating_velocities_start_in_v.floating": _world_body_call(
        "floating_velocities_start_in_v"
    ),
    "RigidBody.floating_position_suffix.floating": _world_body_call("floating_position_suffix", 0),
    "RigidBody.floating_velocity_suffix.floating": _world_body_call("floating_velocity_suffix", 0),
    "RigidBody.floating_position_suffix.index": _free_body_call("floating_position_suffix", 7),
    "RigidBody.floating_velocity_suffix.index": _free_body_call("floating_velocity_suffix", 6),
    "Joint.position_start.mobilizer": _unfinalized_joint_call("position_start"),
    "Joint.velocity_start.mobilizer": _unfinalized_joint_call("velocity_start"),
    "Joint.position_suffix.mobilizer": _unfinalized_joint_call("position_suffix", 0),
    "Joint.velocity_suffix.mobilizer": _unfinalized_joint_call("velocity_suffix", 0),
    "Joint.can_rotate.mobilizer": _unfinalized_joint_call("can_rotate"),
    "Joint.can_translate.mobilizer": _unfinalized_joint_call("can_translate"),
    "Joint.limits": _joint_with(
        "RevoluteJoint", axis=[0.0, 0.0, 1.0], pos_lower_limit=1.0, pos_upper_limit=0.0
    ),
    "BallRpyJoint.damping": _joint_with("BallRpyJoint", damping=-1.0),
    "UniversalJoint.damping": _joint_with("UniversalJoint", damping=-1.0),
    "PlanarJoint.damping": _joint_with("PlanarJoint", damping=[-1.0, 0.0, 0.0]),
    "QuaternionFloatingJoint.angular_damping": _joint_with(
        "QuaternionFloatingJoint", angular_damping=-1.0, translational_damping=0.0
    ),
    "QuaternionFloatingJoint.translational_damping": _joint_with(
        "QuaternionFloatingJoint", angular_damping=0.0, translational_damping=-1.0
    ),
    "RpyFloatingJoint.angular_damping": _joint_with(
        "RpyFloatingJoint", angular_damping=-1.0, translational_damping=0.0
    ),
    "RpyFloatingJoint.translational_damping": _joint_with(
        "RpyFloatingJoint", angular_damping=0.0, translational_damping=-1.0
    ),
    **{
        f"{shape}.{measure}": _bad_shape(shape, measure)
        for shape, measures in _SHAPE_MEASURES.items()
        for measure in measures
    },
    "MakePose.norm": _zero_normal_pose,
}
