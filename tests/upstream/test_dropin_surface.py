"""pydrake surface that Drake's own tests and scripts use, beyond the ported tests.

Not a port: every expected value here was measured on pydrake 1.51.1, and
each test runs unchanged on pydrake and on reimpl through the ``drake`` fixture.
"""

from __future__ import annotations

import re
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.parsing_support import fact_holds_for

MISMATCH_HELP = (
    "\nFor more information about Context-System mismatches, see "
    "https://drake.mit.edu/troubleshooting.html#framework-context-system-mismatch"
)
SCENE_GRAPH = "drake::geometry::SceneGraph<double>"
#: The name DiagramBuilder gives an unnamed SceneGraph: its type and its address.
AUTO_NAME = r"drake/geometry/SceneGraph@[0-9a-f]{16}"


def _sphere(drake: ModuleType, name: str) -> Any:
    g = drake.geometry
    return g.GeometryInstance(X_PG=drake.math.RigidTransform(), shape=g.Sphere(1.0), name=name)


class TestScalarTemplates:
    def test_float_instantiation_is_the_plain_class(self, drake: ModuleType) -> None:
        g, framework = drake.geometry, drake.systems.framework
        assert drake.math.RigidTransform_[float] is drake.math.RigidTransform
        assert g.SceneGraph_[float] is g.SceneGraph
        assert g.FramePoseVector_[float] is g.FramePoseVector
        assert g.QueryObject_[float] is g.QueryObject
        assert g.SceneGraphInspector_[float] is g.SceneGraphInspector
        assert framework.InputPort_[float] is framework.InputPort
        assert framework.OutputPort_[float] is framework.OutputPort
        assert framework.DiagramBuilder_[float] is framework.DiagramBuilder

    def test_an_unbound_parameter_is_an_invalid_instantiation(self, drake: ModuleType) -> None:
        with pytest.raises(RuntimeError, match=r"^Invalid instantiation: SceneGraph_\[int\]$"):
            drake.geometry.SceneGraph_[int]

    def test_template_str_names_the_module(self, drake: ModuleType) -> None:
        assert str(drake.math.RigidTransform_) == (
            f"<TemplateClass {drake.__name__}.math.RigidTransform_>"
        )


class TestValue:
    def test_make_picks_the_instantiation_from_the_type(self, drake: ModuleType) -> None:
        value = drake.common.value
        assert type(value.AbstractValue.Make(2.0)) is value.Value[float]
        assert type(value.Value("s")) is value.Value[str]
        assert type(value.Value(True)) is value.Value[bool]
        # An int is held as a Python object, not converted.
        assert type(value.Value(3)) is value.Value[object]
        assert value.Value(3).get_value() == 3
        if fact_holds_for(drake, "value-of-none-until-1.57"):
            assert type(value.Value(None)) is value.Value[object]
        else:  # 1.58 (measured): None picks no instantiation
            with pytest.raises(TypeError, match=r"^object\(\) takes no arguments$"):
                value.Value(None)

    def test_instantiation_class_names(self, drake: ModuleType) -> None:
        value = drake.common.value
        assert value.Value[float].__name__ == "Value\U0001d4e3float\U0001d4e4"
        assert issubclass(value.Value[object], value.AbstractValue)

    def test_conversion_types_have_no_mutable_value(self, drake: ModuleType) -> None:
        value = drake.common.value
        held = value.Value[float](2.0)
        with pytest.raises(
            RuntimeError,
            match=re.escape(
                "Cannot get mutable value (or reference) for a type-conversion type: "
                "<class 'float'>"
            ),
        ):
            held.get_mutable_value()
        held.set_value(4.0)
        assert held.Clone().get_value() == 4.0
        listed = value.Value[object]([1])
        assert listed.get_mutable_value() is listed.get_value()

    def test_set_from_another_type_names_both_cpp_types(self, drake: ModuleType) -> None:
        value = drake.common.value
        held = value.Value[float](1.0)
        held.SetFrom(value.Value[float](2.0))
        assert held.get_value() == 2.0
        with pytest.raises(RuntimeError) as info:
            held.SetFrom(value.Value("q"))
        assert str(info.value) == (
            "AbstractValue: a request to cast to 'double' failed because the value was created "
            "using the static type 'std::string'."
        )

    def test_abstract_value_has_no_constructor(self, drake: ModuleType) -> None:
        no = "No" if fact_holds_for(drake, "pybind-wording-until-1.57") else "no"  # 1.58: "no"
        with pytest.raises(TypeError, match=f"AbstractValue: {no} constructor defined!"):
            drake.common.value.AbstractValue()


class TestPropertiesListing:
    """Groups and properties list in libstdc++ unordered_map order (measured)."""

    def test_str_lists_groups_and_cpp_types(self, drake: ModuleType) -> None:
        props = drake.geometry.ProximityProperties()
        props.AddProperty("g", "p", 10)
        props.AddProperty("a", "s", "x")
        props.AddProperty("__default__", "z", 1.5)
        assert str(props) == (
            "[a]\n  s: std::string\n[g]\n  p: drake::pydrake::Object\n[__default__]\n  z: double"
        )
        assert props.num_groups() == 3

    def test_fifteen_properties_list_in_hash_order(self, drake: ModuleType) -> None:
        props = drake.geometry.ProximityProperties()
        names = "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi omicron"
        for name in names.split():
            props.AddProperty("material", name, 1.0)
        props.AddProperty("hydroelastic", "resolution_hint", 0.5)
        props.AddProperty("hydroelastic", "compliance_type", "rigid")
        order = "omicron xi alpha delta zeta lambda gamma iota epsilon eta kappa beta theta mu nu"
        assert list(props.GetPropertiesInGroup("material")) == order.split()
        material = "".join(f"\n  {name}: double" for name in order.split())
        assert str(props) == (
            "[hydroelastic]\n  compliance_type: std::string\n  resolution_hint: double\n"
            f"[material]{material}\n[__default__]"
        )
        # A copy lists in the same order.
        assert str(drake.geometry.ProximityProperties(props)) == str(props)

    def test_property_values_are_abstract_values_of_their_type(self, drake: ModuleType) -> None:
        value = drake.common.value
        props = drake.geometry.ProximityProperties()
        props.AddProperty("g", "f", 1.5)
        props.AddProperty("g", "s", "x")
        props.AddProperty("g", "i", 3)
        held = props.GetPropertiesInGroup("g")
        assert type(held["f"]) is value.Value[float]
        assert type(held["s"]) is value.Value[str]
        assert type(held["i"]) is value.Value[object]
        assert {k: v.get_value() for k, v in held.items()} == {"f": 1.5, "s": "x", "i": 3}

    def test_group_and_type_errors(self, drake: ModuleType) -> None:
        props = drake.geometry.ProximityProperties()
        props.AddProperty("g", "n", 2.0)
        with pytest.raises(RuntimeError) as info:
            props.GetPropertiesInGroup("nope")
        assert str(info.value) == (
            "GetPropertiesInGroup(): Can't retrieve properties for a group that doesn't exist: "
            "'nope'"
        )
        with pytest.raises(RuntimeError) as info:
            props.GetProperty("zz", "v")
        assert str(info.value) == (
            "GetProperty(): Trying to read property ('zz', 'v'), but the group does not exist."
        )
        with pytest.raises(RuntimeError) as info:
            props.UpdateProperty("g", "n", True)
        assert str(info.value) == (
            "UpdateProperty(): Trying to update property ('g', 'n'); The property already "
            "exists and is of different type. New type bool, existing type double"
        )
        assert not props.RemoveProperty("zz", "v")
        assert props.RemoveProperty("g", "n")
        assert str(props) == "[g]\n[__default__]"


class TestRenaming:
    @pytest.fixture
    def scene(self, drake: ModuleType) -> dict[str, Any]:
        g = drake.geometry
        sg = g.SceneGraph()
        source = sg.RegisterSource("src")
        f1 = sg.RegisterFrame(source_id=source, frame=g.GeometryFrame("f1"))
        sg.RegisterFrame(source_id=source, frame=g.GeometryFrame("f2"))
        a = sg.RegisterGeometry(source_id=source, frame_id=f1, geometry=_sphere(drake, "a"))
        b = sg.RegisterGeometry(source_id=source, frame_id=f1, geometry=_sphere(drake, "b"))
        return {"sg": sg, "source": source, "f1": f1, "a": a, "b": b}

    def test_rename_frame_to_a_sibling_name_raises(
        self, drake: ModuleType, scene: dict[str, Any]
    ) -> None:
        sg = scene["sg"]
        with pytest.raises(RuntimeError) as info:
            sg.RenameFrame(frame_id=scene["f1"], name="f2")
        assert str(info.value) == "Renaming frame from 'f1' to an already existing name 'f2'"
        sg.RenameFrame(frame_id=scene["f1"], name="f1")
        sg.RenameFrame(frame_id=scene["f1"], name="renamed")
        assert sg.model_inspector().GetName(frame_id=scene["f1"]) == "renamed"

    def test_unknown_ids_raise(self, drake: ModuleType, scene: dict[str, Any]) -> None:
        g, sg = drake.geometry, scene["sg"]
        frame_id, geometry_id = g.FrameId.get_new_id(), g.GeometryId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            sg.RenameFrame(frame_id=frame_id, name="q")
        assert str(info.value) == (
            f"Cannot rename frame with invalid frame id: {frame_id.get_value()}"
        )
        with pytest.raises(RuntimeError) as info:
            sg.RenameGeometry(geometry_id=geometry_id, name="q")
        assert str(info.value) == (
            f"Cannot rename geometry with invalid geometry id: {geometry_id.get_value()}"
        )
        with pytest.raises(RuntimeError) as info:
            sg.model_inspector().GetGeometries(frame_id=frame_id)
        assert str(info.value) == (
            f"Cannot report geometries associated with invalid frame id: {frame_id.get_value()}"
        )
        with pytest.raises(RuntimeError) as info:
            sg.model_inspector().CloneGeometryInstance(geometry_id=geometry_id)
        assert str(info.value) == (
            f"No geometry available for invalid geometry id: {geometry_id.get_value()}"
        )

    def test_geometry_names_are_unique_per_role_only(
        self, drake: ModuleType, scene: dict[str, Any]
    ) -> None:
        g, sg, source = drake.geometry, scene["sg"], scene["source"]
        a, b = scene["a"], scene["b"]
        # Neither has a role yet: the same name is allowed.
        sg.RenameGeometry(geometry_id=b, name="a")
        sg.RenameGeometry(geometry_id=b, name="b")
        for gid in (a, b):
            sg.AssignRole(source_id=source, geometry_id=gid, properties=g.IllustrationProperties())
        with pytest.raises(RuntimeError) as info:
            sg.RenameGeometry(geometry_id=b, name="a")
        assert str(info.value) == (
            "The name 'a' has already been used by a geometry with the 'illustration' role."
        )
        sg.RenameGeometry(geometry_id=b, name="b")
        assert sg.model_inspector().GetName(geometry_id=b) == "b"

    def test_renaming_refreshes_contexts_made_afterwards(
        self, drake: ModuleType, scene: dict[str, Any]
    ) -> None:
        """A manager held from earlier edits the model without marking the context cache
        dirty; RenameFrame, as SceneGraph's own model edits do, marks it."""
        g, sg, source = drake.geometry, scene["sg"], scene["source"]
        anchored = sg.RegisterAnchoredGeometry(source_id=source, geometry=_sphere(drake, "w"))
        for gid in (scene["a"], anchored):
            sg.AssignRole(source_id=source, geometry_id=gid, properties=g.ProximityProperties())
        manager = sg.collision_filter_manager()
        sg.CreateDefaultContext()

        def candidates() -> int:
            context = sg.CreateDefaultContext()
            return len(
                sg.get_query_output_port().Eval(context).inspector().GetCollisionCandidates()
            )

        manager.Apply(
            g.CollisionFilterDeclaration().ExcludeWithin(g.GeometrySet([scene["a"], anchored]))
        )
        assert candidates() == 1
        sg.RenameFrame(frame_id=scene["f1"], name="f1b")
        assert candidates() == 0

    def test_get_geometries_lists_in_registration_order_by_role(
        self, drake: ModuleType, scene: dict[str, Any]
    ) -> None:
        g, sg, source = drake.geometry, scene["sg"], scene["source"]
        a, b = scene["a"], scene["b"]
        sg.AssignRole(source_id=source, geometry_id=a, properties=g.ProximityProperties())
        inspector = sg.model_inspector()
        assert inspector.GetGeometries(frame_id=scene["f1"]) == [a, b]
        assert inspector.GetGeometries(scene["f1"], g.Role.kProximity) == [a]
        assert inspector.GetGeometries(scene["f1"], g.Role.kUnassigned) == [b]
        assert inspector.GetGeometries(frame_id=sg.world_frame_id()) == []

    def test_clone_geometry_instance_copies_all_but_the_id(
        self, drake: ModuleType, scene: dict[str, Any]
    ) -> None:
        g, sg, source = drake.geometry, scene["sg"], scene["source"]
        instance = g.GeometryInstance(
            X_PG=drake.math.RigidTransform([1, 2, 3]), shape=g.Box(1, 2, 3), name="box"
        )
        props = g.ProximityProperties()
        props.AddProperty("a", "b", 1.0)
        instance.set_proximity_properties(props)
        gid = sg.RegisterGeometry(source_id=source, frame_id=scene["f1"], geometry=instance)
        clone = sg.model_inspector().CloneGeometryInstance(geometry_id=gid)
        assert clone.id() != gid
        assert clone.name() == "box"
        assert list(clone.pose().translation()) == [1.0, 2.0, 3.0]
        assert repr(clone.shape()) == "Box(width=1, depth=2, height=3)"
        assert str(clone.proximity_properties()) == "[a]\n  b: double\n[__default__]"
        assert clone.illustration_properties() is None
        assert clone.perception_properties() is None


class TestContextSystemMismatch:
    def test_another_scene_graphs_context(self, drake: ModuleType) -> None:
        g = drake.geometry
        sg, other = g.SceneGraph(), g.SceneGraph()
        context = other.CreateDefaultContext()
        expected = (
            f"A function call on a {SCENE_GRAPH} system named '::_' was passed the Context of a "
            f"system named '::_' instead of the appropriate subsystem Context.{MISMATCH_HELP}"
        )
        source = sg.RegisterSource("s")
        frame = sg.RegisterFrame(source_id=source, frame=g.GeometryFrame("f"))
        calls = [
            lambda: sg.collision_filter_manager(context),
            lambda: sg.collision_filter_manager(context=context),
            lambda: sg.SetDefaultContext(context),
            lambda: sg.RemoveRole(
                context=context, source_id=source, frame_id=frame, role=g.Role.kProximity
            ),
            lambda: sg.RegisterGeometry(
                context=context, source_id=source, frame_id=frame, geometry=_sphere(drake, "x")
            ),
        ]
        for call in calls:
            with pytest.raises(RuntimeError) as info:
                call()
            assert str(info.value) == expected

    def test_named_systems_appear_in_the_message(self, drake: ModuleType) -> None:
        g = drake.geometry
        sg, other = g.SceneGraph(), g.SceneGraph()
        sg.set_name("mine")
        other.set_name("other")
        with pytest.raises(RuntimeError) as info:
            sg.collision_filter_manager(other.CreateDefaultContext())
        assert str(info.value) == (
            f"A function call on a {SCENE_GRAPH} system named '::mine' was passed the Context "
            f"of a system named '::other' instead of the appropriate subsystem Context."
            f"{MISMATCH_HELP}"
        )

    def test_ports_name_their_system(self, drake: ModuleType) -> None:
        g = drake.geometry
        sg, other = g.SceneGraph(), g.SceneGraph()
        source = sg.RegisterSource("src")
        context = other.CreateDefaultContext()
        with pytest.raises(RuntimeError) as info:
            sg.get_query_output_port().Eval(context)
        assert str(info.value) == (
            "OutputPort: The Context given as an argument was not created for this "
            "OutputPort[0] (query) of System ::_ (SceneGraph<double>)"
        )
        with pytest.raises(RuntimeError) as info:
            sg.get_source_pose_port(source).FixValue(context, g.FramePoseVector())
        assert str(info.value) == (
            "InputPort: The Context given as an argument was not created for this "
            "InputPort[0] (src_pose) of System ::_ (SceneGraph<double>)"
        )


class TestDiagram:
    @pytest.fixture
    def built(self, drake: ModuleType) -> tuple[Any, Any]:
        builder = drake.systems.framework.DiagramBuilder()
        sg = builder.AddSystem(drake.geometry.SceneGraph())
        return builder, sg

    def test_scene_graph_in_a_diagram_has_its_own_subcontext(
        self, drake: ModuleType, built: tuple[Any, Any]
    ) -> None:
        g, framework = drake.geometry, drake.systems.framework
        builder, sg = built
        assert re.fullmatch(AUTO_NAME, sg.get_name())
        source = sg.RegisterSource("src")
        frame = sg.RegisterFrame(source_id=source, frame=g.GeometryFrame("f"))
        a = sg.RegisterGeometry(source_id=source, frame_id=frame, geometry=_sphere(drake, "a"))
        b = sg.RegisterAnchoredGeometry(source_id=source, geometry=_sphere(drake, "b"))
        for gid in (a, b):
            sg.AssignRole(source_id=source, geometry_id=gid, properties=g.ProximityProperties())
        diagram = builder.Build()
        assert isinstance(diagram, framework.Diagram)
        assert diagram.GetSystems() == [sg]
        root = diagram.CreateDefaultContext()
        assert isinstance(root, framework.Context)
        sg_context = diagram.GetMutableSubsystemContext(sg, root)
        assert isinstance(sg_context, framework.LeafContext)
        assert diagram.GetSubsystemContext(sg, root) is sg_context
        assert sg.GetMyContextFromRoot(root) is sg_context

        sg.collision_filter_manager(sg_context).Apply(
            g.CollisionFilterDeclaration().ExcludeBetween(g.GeometrySet(a), g.GeometrySet(b))
        )
        query = sg.get_query_output_port().Eval(sg_context)
        assert query.inspector().CollisionFiltered(geometry_id1=a, geometry_id2=b)
        assert not sg.model_inspector().CollisionFiltered(geometry_id1=a, geometry_id2=b)

    def test_root_context_passed_to_the_scene_graph(
        self, drake: ModuleType, built: tuple[Any, Any]
    ) -> None:
        builder, sg = built
        sg.set_name("mysg")
        diagram = builder.Build()
        diagram.set_name("dia")
        with pytest.raises(RuntimeError) as info:
            sg.collision_filter_manager(diagram.CreateDefaultContext())
        assert str(info.value) == (
            f"A function call on a {SCENE_GRAPH} system named '::dia::mysg' was passed the "
            "root Diagram's Context instead of the appropriate subsystem Context. Use "
            "GetMyContextFromRoot() or similar to acquire the appropriate subsystem Context."
            f"{MISMATCH_HELP}"
        )

    def test_subcontext_passed_to_the_diagram(
        self, drake: ModuleType, built: tuple[Any, Any]
    ) -> None:
        builder, sg = built
        sg.set_name("mysg")
        diagram = builder.Build()
        root = diagram.CreateDefaultContext()
        with pytest.raises(RuntimeError) as info:
            diagram.GetMutableSubsystemContext(sg, diagram.GetMutableSubsystemContext(sg, root))
        assert str(info.value) == (
            "A function call on the root Diagram was passed a subcontext associated with its "
            "subsystem named '::_::mysg' instead of the root context. When calling a function "
            "on a the root Digram, you must pass a reference to the root Context, not a "
            f"subcontext.{MISMATCH_HELP}"
        )
        with pytest.raises(RuntimeError) as info:
            diagram.GetSubsystemContext(drake.geometry.SceneGraph(), root)
        assert str(info.value) == (
            f"GetSubsystemContext(): {SCENE_GRAPH} subsystem '::_' is not contained in "
            "drake::systems::Diagram<double> System '::_'."
        )

    def test_builder_is_single_use_and_not_empty(self, drake: ModuleType) -> None:
        framework = drake.systems.framework
        with pytest.raises(RuntimeError, match=r"^Cannot Compile an empty DiagramBuilder\.$"):
            framework.DiagramBuilder().Build()
        builder = framework.DiagramBuilder()
        builder.AddSystem(drake.geometry.SceneGraph())
        builder.Build()
        with pytest.raises(RuntimeError) as info:
            builder.AddSystem(drake.geometry.SceneGraph())
        assert str(info.value) == (
            "DiagramBuilder: Build() or BuildInto() has already been called to create a "
            "Diagram; this DiagramBuilder may no longer be used."
        )
