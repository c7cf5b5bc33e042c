"""Measured pydrake 1.51.1 facts (probe report, sections A-C), on reimpl and on real pydrake.

Every test asserts the value pydrake was measured to give, never mere agreement
between the two implementations. Id values vary between runs, so expected
messages are built from ``get_value()``. Setup unless stated: one source named
``source``; ``scene.geometries(...)`` puts each proximity geometry on its own
frame ``f_<name>``.
"""

from __future__ import annotations

from typing import Any

import pytest

from conformance._backends.scene_graph import Api
from tests.conftest import Scene, all_pairs

UNKNOWN_GEOMETRY_IN_SET = (
    "Geometry set includes a geometry id that doesn't belong to the SceneGraph: "
)
CANNOT_REPORT = "Can't report collision filter status between geometries "
PERSISTENT_WITH_HISTORY = (
    "You cannot attempt to modify the persistent collision filter configuration when there "
    "are active, transient filter declarations"
)


def v(identifier: Any) -> int:
    """An id's integer value, as Drake prints it in messages."""
    return int(identifier.get_value())


def excl(scene: Scene, a: str, b: str) -> Any:
    return scene.decl().ExcludeBetween(set_A=scene.set(a), set_B=scene.set(b))


def instance(scene: Scene, name: str) -> Any:
    return scene.g.GeometryInstance(
        X_PG=scene.api.math.RigidTransform(), shape=scene.g.Sphere(radius=0.1), name=name
    )


def fix_poses(scene: Scene, context: Any) -> None:
    """Fixes the source's pose port with one identity pose per registered frame."""
    g = scene.g
    poses = g.FramePoseVector()
    for name, frame_id in scene.frames.items():
        if name != "world":
            poses.set_value(id=frame_id, value=scene.api.math.RigidTransform())
    scene.sg.get_source_pose_port(scene.source).FixValue(context=context, value=poses)


# --------------------------------------------------------------------------- A1
class TestGeometrySet:
    """Every constructor and Add overload; what pybind11 rejects."""

    def _setup(self, scene: Scene) -> None:
        scene.frame("f")
        scene.geometry("a", "f")
        scene.geometry("b", "f")
        scene.geometries("c")

    def _proximity(self, scene: Scene, geometry_set: Any) -> set[str]:
        ids = scene.inspector().GetGeometryIds(
            geometry_set=geometry_set, role=scene.g.Role.kProximity
        )
        return {scene.names[v(i)] for i in ids}

    def test_empty_constructor_resolves_to_nothing(self, scene: Scene) -> None:
        self._setup(scene)
        assert self._proximity(scene, scene.g.GeometrySet()) == set()

    def test_single_id_keyword_constructors(self, scene: Scene) -> None:
        self._setup(scene)
        g = scene.g
        assert self._proximity(scene, g.GeometrySet(geometry_id=scene.ids["c"])) == {"c"}
        assert self._proximity(scene, g.GeometrySet(frame_id=scene.frames["f"])) == {"a", "b"}

    def test_single_id_positional_constructors(self, scene: Scene) -> None:
        self._setup(scene)
        g = scene.g
        assert self._proximity(scene, g.GeometrySet(scene.ids["c"])) == {"c"}
        assert self._proximity(scene, g.GeometrySet(scene.frames["f"])) == {"a", "b"}

    def test_list_keyword_constructors(self, scene: Scene) -> None:
        self._setup(scene)
        g, ids, frames = scene.g, scene.ids, scene.frames
        assert self._proximity(scene, g.GeometrySet(geometry_ids=[ids["a"], ids["c"]])) == {
            "a",
            "c",
        }
        assert self._proximity(scene, g.GeometrySet(frame_ids=[frames["f_c"]])) == {"c"}
        both = g.GeometrySet(geometry_ids=[ids["c"]], frame_ids=[frames["f"]])
        assert self._proximity(scene, both) == {"a", "b", "c"}

    def test_add_overloads_return_none_and_accumulate(self, scene: Scene) -> None:
        self._setup(scene)
        g, ids, frames = scene.g, scene.ids, scene.frames
        s = g.GeometrySet()
        assert s.Add(geometry_id=ids["a"]) is None
        assert self._proximity(scene, s) == {"a"}
        s = g.GeometrySet()
        assert s.Add(frame_id=frames["f_c"]) is None
        assert self._proximity(scene, s) == {"c"}
        s = g.GeometrySet()
        assert s.Add(geometry_ids=[ids["b"]]) is None
        assert s.Add(frame_ids=[frames["f_c"]]) is None
        assert self._proximity(scene, s) == {"b", "c"}
        s = g.GeometrySet()
        assert s.Add(geometry_ids=[ids["c"]], frame_ids=[frames["f"]]) is None
        assert self._proximity(scene, s) == {"a", "b", "c"}

    def test_tuples_are_accepted_as_lists(self, scene: Scene) -> None:
        self._setup(scene)
        g, ids, frames = scene.g, scene.ids, scene.frames
        s = g.GeometrySet(geometry_ids=(ids["a"], ids["c"]))
        assert self._proximity(scene, s) == {"a", "c"}
        s = g.GeometrySet(geometry_ids=(ids["c"],), frame_ids=(frames["f"],))
        assert self._proximity(scene, s) == {"a", "b", "c"}
        s.Add(frame_ids=(frames["f_c"],))
        assert self._proximity(scene, s) == {"a", "b", "c"}

    def test_duplicates_collapse(self, scene: Scene) -> None:
        self._setup(scene)
        g, ids, frames = scene.g, scene.ids, scene.frames
        s = g.GeometrySet(geometry_ids=[ids["a"], ids["a"], ids["a"]], frame_ids=[frames["f"]])
        s.Add(geometry_id=ids["a"])
        s.Add(frame_ids=[frames["f"], frames["f"]])
        found = scene.inspector().GetGeometryIds(geometry_set=s, role=g.Role.kProximity)
        assert isinstance(found, set)
        assert found == {ids["a"], ids["b"]}
        # A set with a repeated id still excludes exactly the pair.
        scene.apply(
            scene.decl().ExcludeWithin(geometry_set=g.GeometrySet(geometry_ids=[ids["a"]] * 3))
        )
        assert scene.C() == {"a-c", "b-c"}

    @pytest.mark.release_fact("pybind-wording-until-1.57")
    def test_mixed_id_list_raises_type_error(self, scene: Scene) -> None:
        self._setup(scene)
        with pytest.raises(TypeError) as info:
            scene.g.GeometrySet([scene.ids["a"], scene.frames["f"]])
        assert str(info.value).startswith(
            "__init__(): incompatible constructor arguments. "
            "The following argument types are supported:"
        )

    @pytest.mark.release_fact("pybind-wording-until-1.57")
    def test_mixed_id_keyword_list_raises_type_error(self, scene: Scene) -> None:
        self._setup(scene)
        with pytest.raises(TypeError) as info:
            scene.g.GeometrySet(geometry_ids=[scene.ids["a"], scene.frames["f"]])
        assert str(info.value).startswith("__init__(): incompatible constructor arguments")

    @pytest.mark.release_fact("pybind-wording-until-1.57")
    def test_python_set_raises_type_error(self, scene: Scene) -> None:
        self._setup(scene)
        with pytest.raises(TypeError) as info:
            scene.g.GeometrySet({scene.ids["a"]})
        assert str(info.value).startswith("__init__(): incompatible constructor arguments")

    @pytest.mark.release_fact("pybind-wording-until-1.57")
    def test_int_raises_type_error(self, api: Api) -> None:
        with pytest.raises(TypeError) as info:
            api.geometry.GeometrySet(3)
        assert str(info.value).startswith("__init__(): incompatible constructor arguments")
        assert str(info.value).splitlines()[-1] == "Invoked with: 3"

    def test_add_of_a_geometry_set_raises_type_error(self, scene: Scene) -> None:
        self._setup(scene)
        g = scene.g
        with pytest.raises(TypeError) as info:
            g.GeometrySet().Add(g.GeometrySet(scene.ids["a"]))
        assert str(info.value).startswith(
            "Add(): incompatible function arguments. The following argument types are supported:"
        )


# --------------------------------------------------------------------------- A2
ID_TYPES = ("GeometryId", "FrameId", "SourceId", "FilterId")


class TestIds:
    @pytest.mark.parametrize("type_name", ID_TYPES)
    @pytest.mark.release_fact("pybind-wording-until-1.57")
    def test_id_constructor_raises_no_constructor_defined(self, api: Api, type_name: str) -> None:
        with pytest.raises(TypeError) as info:
            getattr(api.geometry, type_name)()
        assert "No constructor defined!" in str(info.value)
        assert str(info.value) == f"{api.geometry.__name__}.{type_name}: No constructor defined!"

    @pytest.mark.parametrize("type_name", ID_TYPES)
    def test_new_id_is_valid_and_prints_its_value(self, api: Api, type_name: str) -> None:
        new = getattr(api.geometry, type_name).get_new_id()
        assert new.is_valid()
        assert repr(new) == f"<{type_name} value={v(new)}>"
        assert str(new) == repr(new)

    def test_registered_ids_print_their_value(self, scene: Scene) -> None:
        scene.geometries("g")
        assert repr(scene.ids["g"]) == f"<GeometryId value={v(scene.ids['g'])}>"
        assert repr(scene.frames["f_g"]) == f"<FrameId value={v(scene.frames['f_g'])}>"
        assert repr(scene.source) == f"<SourceId value={v(scene.source)}>"

    def test_equal_ids_compare_and_hash_equal_across_objects(self, scene: Scene) -> None:
        scene.geometries("g")
        inspector = scene.inspector()
        gid = inspector.GetAllGeometryIds()[0]
        fid = inspector.GetFrameId(geometry_id=gid)
        assert gid == scene.ids["g"]
        assert (gid != scene.ids["g"]) is False
        assert hash(gid) == hash(scene.ids["g"])
        assert {scene.ids["g"]: "g"}[gid] == "g"
        assert fid == scene.frames["f_g"]
        assert {scene.frames["f_g"]: "f"}[fid] == "f"

    def test_geometry_id_hash_is_its_value(self, api: Api) -> None:
        gid = api.geometry.GeometryId.get_new_id()
        assert hash(gid) == v(gid)

    def test_ids_of_one_type_order_by_value(self, api: Api) -> None:
        g = api.geometry
        first, second = g.GeometryId.get_new_id(), g.GeometryId.get_new_id()
        assert first < second
        assert second > first
        assert not (second < first)
        assert first != second
        assert sorted([second, first]) == [first, second]

    def test_only_less_than_is_bound(self, api: Api) -> None:
        g = api.geometry
        first, second = g.GeometryId.get_new_id(), g.GeometryId.get_new_id()
        with pytest.raises(TypeError, match="'<=' not supported between instances of"):
            _ = first <= second
        with pytest.raises(TypeError, match="'>=' not supported between instances of"):
            _ = first >= second

    def test_geometry_id_equals_no_frame_id_and_no_int(self, api: Api) -> None:
        g = api.geometry
        gid, fid = g.GeometryId.get_new_id(), g.FrameId.get_new_id()
        assert (gid == fid) is False
        assert (gid != fid) is True
        assert (gid == v(gid)) is False

    def test_geometry_id_less_than_frame_id_raises_type_error(self, api: Api) -> None:
        g = api.geometry
        gid, fid = g.GeometryId.get_new_id(), g.FrameId.get_new_id()
        with pytest.raises(TypeError) as info:
            _ = gid < fid
        assert str(info.value).startswith("'<' not supported between instances of ")
        assert "GeometryId" in str(info.value)
        assert "FrameId" in str(info.value)

    def test_all_id_types_share_one_counter(self, api: Api) -> None:
        g = api.geometry
        values = [
            v(g.GeometryId.get_new_id()),
            v(g.FrameId.get_new_id()),
            v(g.SourceId.get_new_id()),
            v(g.FilterId.get_new_id()),
            v(g.GeometryId.get_new_id()),
        ]
        assert values == sorted(values)
        assert len(set(values)) == len(values)

    def test_registration_ids_share_the_counter_with_new_ids(self, scene: Scene) -> None:
        g = scene.g
        values = [
            v(scene.frame("f")),
            v(scene.geometry("a", "f")),
            v(g.FilterId.get_new_id()),
            v(scene.sg.RegisterSource(name="second")),
            v(scene.frame("f2")),
        ]
        assert values == sorted(values)
        assert len(set(values)) == len(values)

    def test_geometry_id_is_drawn_when_the_instance_is_constructed(self, scene: Scene) -> None:
        scene.frame("f")
        made = instance(scene, "x")
        later = scene.g.GeometryId.get_new_id()
        gid = scene.sg.RegisterGeometry(
            source_id=scene.source, frame_id=scene.frames["f"], geometry=made
        )
        assert gid == made.id()
        assert v(gid) < v(later)


class TestShapes:
    def test_shapes_print_measures_in_shortest_round_trip_form(self, api: Api) -> None:
        g = api.geometry
        assert repr(g.Sphere(radius=1)) == "Sphere(radius=1)"
        assert repr(g.Sphere(radius=1 / 3)) == "Sphere(radius=0.3333333333333333)"
        assert repr(g.Sphere(radius=1234567.0)) == "Sphere(radius=1234567)"
        assert repr(g.Sphere(radius=1e-7)) == "Sphere(radius=1e-07)"
        assert repr(g.Box(width=1, depth=2, height=3)) == "Box(width=1, depth=2, height=3)"
        assert repr(g.Cylinder(radius=0.5, length=2)) == "Cylinder(radius=0.5, length=2)"


# --------------------------------------------------------------------------- A3
class TestRegistrationErrors:
    def test_register_frame_with_unknown_source_raises(self, scene: Scene) -> None:
        g = scene.g
        bogus = g.SourceId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterFrame(source_id=bogus, frame=g.GeometryFrame(frame_name="x"))
        assert str(info.value) == f"Referenced geometry source {v(bogus)} is not registered."

    def test_register_frame_with_unknown_parent_raises(self, scene: Scene) -> None:
        g = scene.g
        bogus = g.FrameId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterFrame(
                source_id=scene.source, parent_id=bogus, frame=g.GeometryFrame(frame_name="x")
            )
        assert str(info.value) == (
            f"Indicated parent id {v(bogus)} does not belong to the indicated source id "
            f"{v(scene.source)}."
        )

    def test_register_frame_with_another_sources_parent_raises(self, scene: Scene) -> None:
        g = scene.g
        other = scene.sg.RegisterSource(name="other")
        foreign = scene.sg.RegisterFrame(source_id=other, frame=g.GeometryFrame(frame_name="fo"))
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterFrame(
                source_id=scene.source, parent_id=foreign, frame=g.GeometryFrame(frame_name="x")
            )
        assert str(info.value) == (
            f"Indicated parent id {v(foreign)} does not belong to the indicated source id "
            f"{v(scene.source)}."
        )

    def test_register_frame_with_duplicate_name_raises(self, scene: Scene) -> None:
        scene.frame("f")
        with pytest.raises(RuntimeError) as info:
            scene.frame("f")
        assert str(info.value) == "Registering frame for source 'source' with a duplicate name 'f'"

    def test_register_geometry_on_another_sources_frame_raises(self, scene: Scene) -> None:
        g = scene.g
        other = scene.sg.RegisterSource(name="other")
        foreign = scene.sg.RegisterFrame(source_id=other, frame=g.GeometryFrame(frame_name="fo"))
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterGeometry(
                source_id=scene.source, frame_id=foreign, geometry=instance(scene, "x")
            )
        assert str(info.value) == (
            f"Referenced frame {v(foreign)} for source {v(scene.source)}, but the frame "
            "doesn't belong to the source."
        )

    def test_register_geometry_on_unknown_frame_raises(self, scene: Scene) -> None:
        bogus = scene.g.FrameId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterGeometry(
                source_id=scene.source, frame_id=bogus, geometry=instance(scene, "x")
            )
        assert str(info.value) == (
            f"Referenced frame {v(bogus)} for source {v(scene.source)}, but the frame "
            "doesn't belong to the source."
        )

    def test_register_anchored_geometry_with_unknown_source_raises(self, scene: Scene) -> None:
        bogus = scene.g.SourceId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterAnchoredGeometry(source_id=bogus, geometry=instance(scene, "x"))
        assert str(info.value) == f"Referenced geometry source {v(bogus)} is not registered."

    def test_register_source_with_duplicate_name_raises(self, scene: Scene) -> None:
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterSource(name="source")
        assert str(info.value) == "Registering new source with duplicate name: source."

    def test_registering_one_instance_twice_raises(self, scene: Scene) -> None:
        scene.frame("f")
        made = instance(scene, "x")
        scene.sg.RegisterGeometry(source_id=scene.source, frame_id=scene.frames["f"], geometry=made)
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterGeometry(
                source_id=scene.source, frame_id=scene.frames["f"], geometry=made
            )
        assert str(info.value) == (
            f"Registering geometry with an id that has already been registered: {v(made.id())}"
        )


class TestAssignRoleErrors:
    def test_unknown_geometry_raises(self, scene: Scene) -> None:
        bogus = scene.g.GeometryId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.sg.AssignRole(
                source_id=scene.source, geometry_id=bogus, properties=scene.g.ProximityProperties()
            )
        assert str(info.value) == f"Referenced geometry {v(bogus)} has not been registered."

    def test_unknown_source_raises(self, scene: Scene) -> None:
        scene.geometries("g")
        bogus = scene.g.SourceId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.sg.AssignRole(
                source_id=bogus,
                geometry_id=scene.ids["g"],
                properties=scene.g.IllustrationProperties(),
            )
        assert str(info.value) == f"Referenced geometry source {v(bogus)} is not registered."

    def test_source_that_does_not_own_the_geometry_raises_without_period(
        self, scene: Scene
    ) -> None:
        scene.geometries("g")
        other = scene.sg.RegisterSource(name="other")
        with pytest.raises(RuntimeError) as info:
            scene.sg.AssignRole(
                source_id=other,
                geometry_id=scene.ids["g"],
                properties=scene.g.PerceptionProperties(),
            )
        assert str(info.value) == (
            f"Given geometry id {v(scene.ids['g'])} does not belong to the given source id "
            f"{v(other)}"
        )

    @pytest.mark.parametrize("role", ["proximity", "illustration"])
    def test_replace_without_the_role_raises_and_leaves_it_absent(
        self, scene: Scene, role: str
    ) -> None:
        scene.frame("f")
        scene.geometry("n", "f", proximity=False)
        g = scene.g
        properties = {"proximity": g.ProximityProperties, "illustration": g.IllustrationProperties}
        with pytest.raises(RuntimeError) as info:
            scene.sg.AssignRole(
                source_id=scene.source,
                geometry_id=scene.ids["n"],
                properties=properties[role](),
                assign=g.RoleAssign.kReplace,
            )
        assert str(info.value) == (
            f"Trying to replace the properties on geometry id {v(scene.ids['n'])} for the "
            f"'{role}' role; it has not had the role initially assigned"
        )
        assert scene.inspector().GetProximityProperties(geometry_id=scene.ids["n"]) is None

    def test_replace_of_perception_raises(self, scene: Scene) -> None:
        scene.frame("f")
        scene.geometry("n", "f", proximity=False)
        with pytest.raises(RuntimeError) as info:
            scene.sg.AssignRole(
                source_id=scene.source,
                geometry_id=scene.ids["n"],
                properties=scene.g.PerceptionProperties(),
                assign=scene.g.RoleAssign.kReplace,
            )
        assert str(info.value) == (
            "AssignRole() with RoleAssign::kReplace does not work for perception properties"
        )

    @pytest.mark.parametrize("role", ["illustration", "perception"])
    def test_assigning_a_role_twice_raises(self, scene: Scene, role: str) -> None:
        scene.frame("f")
        scene.geometry("n", "f", proximity=False)
        g = scene.g
        properties = {
            "illustration": g.IllustrationProperties,
            "perception": g.PerceptionProperties,
        }
        kwargs = {"source_id": scene.source, "geometry_id": scene.ids["n"]}
        scene.sg.AssignRole(**kwargs, properties=properties[role]())
        with pytest.raises(RuntimeError) as info:
            scene.sg.AssignRole(**kwargs, properties=properties[role]())
        assert str(info.value) == (
            f"Trying to assign the '{role}' role to geometry id {v(scene.ids['n'])} for the "
            "first time; it already has the role assigned"
        )

    @pytest.mark.parametrize("role", ["proximity", "illustration"])
    def test_duplicate_name_on_one_frame_raises_when_the_role_is_assigned(
        self, scene: Scene, role: str
    ) -> None:
        g = scene.g
        properties = {"proximity": g.ProximityProperties, "illustration": g.IllustrationProperties}
        scene.frame("f")
        first = scene.geometry("g", "f", proximity=False)
        # Registration itself never checks names.
        second = scene.sg.RegisterGeometry(
            source_id=scene.source, frame_id=scene.frames["f"], geometry=instance(scene, "g")
        )
        scene.sg.AssignRole(
            source_id=scene.source, geometry_id=first, properties=properties[role]()
        )
        with pytest.raises(RuntimeError) as info:
            scene.sg.AssignRole(
                source_id=scene.source, geometry_id=second, properties=properties[role]()
            )
        assert str(info.value) == (
            f"The name 'g' has already been used by a geometry with the '{role}' role."
        )
        assert scene.inspector().GetProximityProperties(geometry_id=second) is None

    def test_duplicate_name_on_another_frame_is_fine(self, scene: Scene) -> None:
        scene.frame("f1")
        scene.frame("f2")
        first = scene.geometry("g", "f1")
        scene.geometry("g", "f2")
        assert scene.inspector().GetName(geometry_id=first) == "g"
        assert len(scene.C()) == 1

    def test_anchored_duplicate_names_clash_across_sources(self, scene: Scene) -> None:
        scene.geometry("A", "world")
        other = scene.sg.RegisterSource(name="other")
        gid = scene.sg.RegisterAnchoredGeometry(source_id=other, geometry=instance(scene, "A"))
        with pytest.raises(RuntimeError) as info:
            scene.sg.AssignRole(
                source_id=other, geometry_id=gid, properties=scene.g.ProximityProperties()
            )
        assert str(info.value) == (
            "The name 'A' has already been used by a geometry with the 'proximity' role."
        )

    def test_instance_with_proximity_and_duplicate_name_is_half_registered(
        self, scene: Scene
    ) -> None:
        scene.frame("f")
        scene.geometry("k", "f")
        scene.geometries("o")
        before = scene.inspector().num_geometries()
        made = instance(scene, "k")
        made.set_proximity_properties(scene.g.ProximityProperties())
        with pytest.raises(RuntimeError) as info:
            scene.sg.RegisterGeometry(
                source_id=scene.source, frame_id=scene.frames["f"], geometry=made
            )
        assert str(info.value) == (
            "The name 'k' has already been used by a geometry with the 'proximity' role."
        )
        inspector = scene.inspector()
        assert inspector.num_geometries() == before + 1
        assert inspector.GetName(geometry_id=made.id()) == "k"
        assert inspector.GetProximityProperties(geometry_id=made.id()) is None
        assert scene.C() == {"k-o"}


class TestRemoveRole:
    def _frame_of_three(self, scene: Scene) -> None:
        scene.frame("f")
        scene.geometry("p1", "f")
        scene.geometry("p2", "f")
        scene.geometry("q", "f", proximity=False)

    def test_remove_role_by_frame_counts_the_geometries_that_had_it(self, scene: Scene) -> None:
        self._frame_of_three(scene)
        kwargs = {
            "source_id": scene.source,
            "frame_id": scene.frames["f"],
            "role": scene.g.Role.kProximity,
        }
        assert scene.sg.RemoveRole(**kwargs) == 2
        assert scene.sg.RemoveRole(**kwargs) == 0
        assert scene.inspector().GetAllGeometryIds(role=scene.g.Role.kProximity) == []

    def test_remove_role_by_world_frame_removes_the_sources_anchored_geometry(
        self, scene: Scene
    ) -> None:
        scene.geometry("A", "world")
        scene.geometries("g")
        removed = scene.sg.RemoveRole(
            source_id=scene.source,
            frame_id=scene.sg.world_frame_id(),
            role=scene.g.Role.kProximity,
        )
        assert removed == 1
        assert scene.C() == set()

    def test_remove_unassigned_role_returns_zero(self, scene: Scene) -> None:
        self._frame_of_three(scene)
        role = scene.g.Role.kUnassigned
        assert (
            scene.sg.RemoveRole(source_id=scene.source, geometry_id=scene.ids["q"], role=role) == 0
        )
        assert (
            scene.sg.RemoveRole(source_id=scene.source, geometry_id=scene.ids["p1"], role=role) == 0
        )
        assert (
            scene.sg.RemoveRole(source_id=scene.source, frame_id=scene.frames["f"], role=role) == 0
        )

    def test_remove_role_from_another_sources_geometry_raises(self, scene: Scene) -> None:
        scene.geometries("g")
        other = scene.sg.RegisterSource(name="other")
        with pytest.raises(RuntimeError) as info:
            scene.sg.RemoveRole(
                source_id=other, geometry_id=scene.ids["g"], role=scene.g.Role.kProximity
            )
        assert str(info.value) == (
            f"Trying to remove the role proximity from the geometry {v(scene.ids['g'])} from "
            f"source {v(other)}, but the geometry doesn't belong to that source."
        )

    def test_remove_role_from_another_sources_frame_raises(self, scene: Scene) -> None:
        scene.geometries("g")
        other = scene.sg.RegisterSource(name="other")
        with pytest.raises(RuntimeError) as info:
            scene.sg.RemoveRole(
                source_id=other, frame_id=scene.frames["f_g"], role=scene.g.Role.kProximity
            )
        assert str(info.value) == (
            f"Referenced frame {v(scene.frames['f_g'])} for source {v(other)}, but the frame "
            "doesn't belong to the source."
        )

    def test_remove_role_of_unknown_geometry_raises(self, scene: Scene) -> None:
        bogus = scene.g.GeometryId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.sg.RemoveRole(
                source_id=scene.source, geometry_id=bogus, role=scene.g.Role.kProximity
            )
        assert str(info.value) == f"Referenced geometry {v(bogus)} has not been registered."


class TestRemoveGeometry:
    def test_unknown_geometry_raises(self, scene: Scene) -> None:
        bogus = scene.g.GeometryId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.sg.RemoveGeometry(source_id=scene.source, geometry_id=bogus)
        assert str(info.value) == f"Referenced geometry {v(bogus)} has not been registered."

    def test_removing_twice_raises_the_second_time(self, scene: Scene) -> None:
        scene.geometries("g", "h")
        gid = scene.ids["g"]
        assert scene.sg.RemoveGeometry(source_id=scene.source, geometry_id=gid) is None
        with pytest.raises(RuntimeError) as info:
            scene.sg.RemoveGeometry(source_id=scene.source, geometry_id=gid)
        assert str(info.value) == f"Referenced geometry {v(gid)} has not been registered."
        assert scene.C() == set()

    def test_another_source_cannot_remove_it(self, scene: Scene) -> None:
        scene.geometries("g")
        other = scene.sg.RegisterSource(name="other")
        with pytest.raises(RuntimeError) as info:
            scene.sg.RemoveGeometry(source_id=other, geometry_id=scene.ids["g"])
        assert str(info.value) == (
            f"Trying to remove geometry {v(scene.ids['g'])} from source {v(other)}, but the "
            "geometry doesn't belong to that source."
        )

    def test_name_is_free_again_after_removal(self, scene: Scene) -> None:
        scene.geometries("g", "h")
        scene.sg.RemoveGeometry(source_id=scene.source, geometry_id=scene.ids["g"])
        scene.geometry("g", "f_g")
        assert scene.C() == {"g-h"}


# --------------------------------------------------------------------------- A4
class TestInspector:
    def test_fresh_scene_graph_has_the_world_frame_and_the_internal_source(self, api: Api) -> None:
        sg = api.geometry.SceneGraph()
        inspector = sg.model_inspector()
        assert inspector.num_frames() == 1
        assert inspector.num_sources() == 1
        assert inspector.num_geometries() == 0
        assert inspector.GetName(frame_id=sg.world_frame_id()) == "world"
        assert inspector.GetCollisionCandidates() == set()

    def test_source_without_frames_adds_no_frame(self, scene: Scene) -> None:
        inspector = scene.inspector()
        assert inspector.num_frames() == 1
        assert inspector.num_sources() == 2
        assert inspector.GetName(source_id=scene.source) == "source"

    def test_get_name_of_unknown_ids_raises(self, scene: Scene) -> None:
        g = scene.g
        inspector = scene.inspector()
        gid, fid, sid = g.GeometryId.get_new_id(), g.FrameId.get_new_id(), g.SourceId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            inspector.GetName(geometry_id=gid)
        assert str(info.value) == f"No geometry available for invalid geometry id: {v(gid)}"
        with pytest.raises(RuntimeError) as info:
            inspector.GetName(frame_id=fid)
        assert str(info.value) == f"No frame name available for invalid frame id: {v(fid)}"
        with pytest.raises(RuntimeError) as info:
            inspector.GetName(source_id=sid)
        assert str(info.value) == f"Querying source name for an invalid source id: {v(sid)}."

    def test_get_proximity_properties_of_unknown_geometry_raises_without_period(
        self, scene: Scene
    ) -> None:
        bogus = scene.g.GeometryId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.inspector().GetProximityProperties(geometry_id=bogus)
        assert str(info.value) == f"Referenced geometry {v(bogus)} has not been registered"

    def test_get_proximity_properties_is_none_without_the_role(self, scene: Scene) -> None:
        scene.frame("f")
        scene.geometry("n", "f", proximity=False)
        scene.geometry("i", "f", proximity=False)
        scene.geometry("p", "f")
        scene.sg.AssignRole(
            source_id=scene.source,
            geometry_id=scene.ids["i"],
            properties=scene.g.IllustrationProperties(),
        )
        inspector = scene.inspector()
        assert inspector.GetProximityProperties(geometry_id=scene.ids["n"]) is None
        assert inspector.GetProximityProperties(geometry_id=scene.ids["i"]) is None
        assert inspector.GetIllustrationProperties(geometry_id=scene.ids["n"]) is None
        assert inspector.GetProximityProperties(geometry_id=scene.ids["p"]) is not None
        assert inspector.GetIllustrationProperties(geometry_id=scene.ids["i"]) is not None

    def test_get_frame_id_of_unknown_geometry_raises(self, scene: Scene) -> None:
        bogus = scene.g.GeometryId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            scene.inspector().GetFrameId(geometry_id=bogus)
        assert str(info.value) == f"Referenced geometry {v(bogus)} has not been registered."

    def test_get_all_geometry_ids_is_sorted_by_value(self, scene: Scene) -> None:
        scene.frame("f")
        made = [instance(scene, f"g{i}") for i in range(4)]
        for index in (3, 1, 0, 2):
            scene.sg.RegisterGeometry(
                source_id=scene.source, frame_id=scene.frames["f"], geometry=made[index]
            )
        ids = scene.inspector().GetAllGeometryIds()
        assert isinstance(ids, list)
        assert ids == [m.id() for m in made]
        assert [v(i) for i in ids] == sorted(v(i) for i in ids)

    def test_get_all_geometry_ids_filters_by_role(self, scene: Scene) -> None:
        scene.frame("f")
        scene.geometry("p", "f")
        scene.geometry("n", "f", proximity=False)
        inspector = scene.inspector()
        role = scene.g.Role
        assert inspector.GetAllGeometryIds(role=role.kProximity) == [scene.ids["p"]]
        assert inspector.GetAllGeometryIds(role=role.kUnassigned) == [scene.ids["n"]]
        assert inspector.GetAllGeometryIds(role=role.kIllustration) == []

    def test_get_geometry_ids_rejects_unknown_ids(self, scene: Scene) -> None:
        g = scene.g
        inspector = scene.inspector()
        gid, fid = g.GeometryId.get_new_id(), g.FrameId.get_new_id()
        with pytest.raises(RuntimeError) as info:
            inspector.GetGeometryIds(geometry_set=g.GeometrySet(geometry_id=gid))
        assert str(info.value) == UNKNOWN_GEOMETRY_IN_SET + str(v(gid))
        with pytest.raises(RuntimeError) as info:
            inspector.GetGeometryIds(geometry_set=g.GeometrySet(frame_id=fid))
        assert str(info.value) == f"Referenced frame {v(fid)} has not been registered."

    def test_get_geometry_ids_of_world_frame_gives_anchored_geometry(self, scene: Scene) -> None:
        scene.geometry("A", "world")
        scene.geometries("g")
        found = scene.inspector().GetGeometryIds(
            geometry_set=scene.g.GeometrySet(frame_id=scene.sg.world_frame_id()),
            role=scene.g.Role.kProximity,
        )
        assert found == {scene.ids["A"]}

    def test_model_inspector_is_one_live_object(self, scene: Scene) -> None:
        early = scene.sg.model_inspector()
        assert early is scene.sg.model_inspector()
        scene.geometries("a", "b")
        assert early.num_geometries() == 2
        scene.geometries("c")
        assert early.num_geometries() == 3
        assert len(early.GetCollisionCandidates()) == 3
        scene.apply(excl(scene, "a", "c"))
        assert early.CollisionFiltered(geometry_id1=scene.ids["a"], geometry_id2=scene.ids["c"])
        assert early is scene.sg.model_inspector()

    def test_context_inspector_is_the_model_inspectors_class(self, scene: Scene) -> None:
        scene.geometries("a")
        context = scene.sg.CreateDefaultContext()
        query = scene.sg.get_query_output_port().Eval(context)
        assert type(query).__name__ == "QueryObject"
        assert type(query.inspector()) is type(scene.sg.model_inspector())
        assert type(query.inspector()).__name__ == "SceneGraphInspector"

    def test_candidates_are_ordered_by_value_not_registration(self, scene: Scene) -> None:
        scene.frame("f1")
        scene.frame("f2")
        late = instance(scene, "late")
        scene.geometry("A", "world")
        scene.geometry("d", "f1")
        scene.sg.RegisterGeometry(
            source_id=scene.source, frame_id=scene.frames["f2"], geometry=late
        )
        scene.ids["late"] = late.id()
        scene.names[v(late.id())] = "late"
        scene.assign_proximity("late")
        candidates = scene.inspector().GetCollisionCandidates()
        assert scene.C() == {"A-d", "A-late", "d-late"}
        for first, second in candidates:
            assert v(first) < v(second)


class TestEnums:
    """Role, RoleAssign and CollisionFilterScope are pybind11 enums, not ints."""

    @pytest.mark.parametrize(
        ("enum", "member", "value"),
        [
            ("Role", "kUnassigned", 0),
            ("Role", "kProximity", 1),
            ("Role", "kPerception", 4),
            ("RoleAssign", "kNew", 0),
            ("CollisionFilterScope", "kOmitDeformable", 1),
        ],
    )
    def test_a_member_converts_to_its_value_but_is_no_int(
        self, api: Api, enum: str, member: str, value: int
    ) -> None:
        item = getattr(getattr(api.geometry, enum), member)
        assert int(item) == value
        assert [10, 11, 12, 13, 14][item] == 10 + value
        assert item.value == value
        assert item.name == member
        assert not isinstance(item, int)
        assert item != value
        assert {value: "x"}.get(item) is None
        assert bool(item) is True
        assert repr(item) == f"<{enum}.{member}: {value}>"
        assert str(item) == f"{enum}.{member}"
        with pytest.raises(TypeError):
            item + 1

    def test_calling_the_enum_with_a_value_gives_its_member_or_an_unnamed_one(
        self, api: Api
    ) -> None:
        role = api.geometry.Role
        assert role(1) == role.kProximity
        assert repr(role(3)) == "<Role.???: 3>"
        assert list(role.__members__) == [
            "kUnassigned",
            "kProximity",
            "kIllustration",
            "kPerception",
        ]
        with pytest.raises(TypeError):
            iter(role)  # type: ignore[call-overload]

    def test_members_order_by_value_only_against_their_own_enum(self, api: Api) -> None:
        role = api.geometry.Role
        assert role.kUnassigned < role.kProximity < role.kIllustration < role.kPerception
        assert sorted([role.kPerception, role.kProximity]) == [role.kProximity, role.kPerception]
        with pytest.raises(TypeError, match="Expected an enumeration of matching type!"):
            role.kProximity < 2  # noqa: B015
        assert api.geometry.RoleAssign.kNew != role.kUnassigned


class TestNames:
    """Names: canonical geometry names, GetGeometryIdByName, unnamed sources, the world frame."""

    @pytest.mark.parametrize("raw", [" a", "a\t", " \t a \t "])
    def test_a_geometry_name_is_kept_without_its_outer_spaces_and_tabs(
        self, api: Api, raw: str
    ) -> None:
        instance = api.geometry.GeometryInstance(
            X_PG=api.math.RigidTransform(), shape=api.geometry.Sphere(radius=1.0), name=raw
        )
        assert instance.name() == "a"
        instance.set_name(" b ")  # pydrake names the parameter arg0
        assert instance.name() == "b"

    @pytest.mark.parametrize("raw", ["\na", "a\r", "a\v"])
    def test_other_whitespace_stays_in_a_geometry_name(self, api: Api, raw: str) -> None:
        instance = api.geometry.GeometryInstance(
            X_PG=api.math.RigidTransform(), shape=api.geometry.Sphere(radius=1.0), name=raw
        )
        assert instance.name() == raw

    @pytest.mark.parametrize("raw", ["", " \t "])
    def test_an_empty_canonical_geometry_name_raises(self, api: Api, raw: str) -> None:
        with pytest.raises(RuntimeError) as raised:
            api.geometry.GeometryInstance(
                X_PG=api.math.RigidTransform(), shape=api.geometry.Sphere(radius=1.0), name=raw
            )
        assert str(raised.value) == (
            f"GeometryInstance given the name '{raw}' which is an empty canonical string"
        )

    def test_get_geometry_id_by_name_finds_the_canonical_name_with_the_role(
        self, scene: Scene
    ) -> None:
        scene.frame("F")
        scene.geometry("a", "F")
        scene.geometry("u", "F", proximity=False)
        inspector = scene.inspector()
        find = inspector.GetGeometryIdByName
        proximity, unassigned = scene.g.Role.kProximity, scene.g.Role.kUnassigned
        assert find(frame_id=scene.frames["F"], role=proximity, name=" a\t") == scene.ids["a"]
        assert find(frame_id=scene.frames["F"], role=unassigned, name="u") == scene.ids["u"]

    def test_get_geometry_id_by_name_lists_the_frames_names_with_the_role(
        self, scene: Scene
    ) -> None:
        scene.frame("F")
        for name in ("zeta", "alpha", "mid"):
            scene.geometry(name, "F")
        scene.geometry("u", "F", proximity=False)
        frame = scene.frames["F"]
        with pytest.raises(RuntimeError) as raised:
            scene.inspector().GetGeometryIdByName(
                frame_id=frame, role=scene.g.Role.kProximity, name=" nope "
            )
        message = str(raised.value)
        head = (
            f"The frame 'F' ({v(frame)}) has no geometry with the role 'proximity' and the "
            "canonical name 'nope'. The names associated with this frame/role are {"
        )
        assert message.startswith(head)
        assert message.endswith("}.")
        assert set(message[len(head) : -2].split(", ")) == {"zeta", "alpha", "mid"}

    @pytest.mark.parametrize(
        ("role", "text"),
        [("kIllustration", "illustration"), ("kPerception", "perception")],
    )
    def test_get_geometry_id_by_name_without_geometries_of_the_role_lists_none(
        self, scene: Scene, role: str, text: str
    ) -> None:
        scene.geometry("a", "world")
        world = scene.sg.world_frame_id()
        with pytest.raises(RuntimeError) as raised:
            scene.inspector().GetGeometryIdByName(
                frame_id=world, role=getattr(scene.g.Role, role), name="a"
            )
        assert str(raised.value) == (
            f"The frame 'world' ({v(world)}) has no geometry with the role '{text}' and the "
            "canonical name 'a'. The names associated with this frame/role are {}."
        )

    def test_get_geometry_id_by_name_of_an_unknown_frame_raises(self, scene: Scene) -> None:
        frame = scene.g.FrameId.get_new_id()
        with pytest.raises(RuntimeError) as raised:
            scene.inspector().GetGeometryIdByName(
                frame_id=frame, role=scene.g.Role.kProximity, name="a"
            )
        assert str(raised.value) == f"Referenced frame {v(frame)} has not been registered."

    @pytest.mark.parametrize("name", [None, ""])
    def test_an_unnamed_source_is_named_after_its_own_id(self, api: Api, name: str | None) -> None:
        sg = api.geometry.SceneGraph()
        source = sg.RegisterSource() if name is None else sg.RegisterSource(name=name)
        assert sg.model_inspector().GetName(source_id=source) == f"Source_{v(source)}"
        assert sg.get_source_pose_port(source).get_name() == f"Source_{v(source)}_pose"

    def test_a_duplicate_source_name_uses_up_an_id(self, api: Api) -> None:
        sg = api.geometry.SceneGraph()
        sg.RegisterSource(name="s")
        before = api.geometry.SourceId.get_new_id()
        with pytest.raises(RuntimeError, match="duplicate name: s"):
            sg.RegisterSource(name="s")
        assert v(api.geometry.SourceId.get_new_id()) == v(before) + 2

    def test_the_world_frame_is_in_frame_group_minus_1234567(self, api: Api) -> None:
        sg = api.geometry.SceneGraph()
        assert sg.model_inspector().GetFrameGroup(frame_id=sg.world_frame_id()) == -1234567


class TestCollisionFiltered:
    def _setup(self, scene: Scene) -> tuple[int, int, int, int]:
        scene.geometries("c")
        scene.frame("fd")
        scene.geometry("d", "fd", proximity=False)
        scene.geometry("e", "fd", proximity=False)
        bogus = scene.g.GeometryId.get_new_id()
        scene.ids["bogus"] = bogus
        return v(scene.ids["c"]), v(scene.ids["d"]), v(scene.ids["e"]), v(bogus)

    def _message(self, scene: Scene, a: str, b: str) -> str:
        with pytest.raises(RuntimeError) as info:
            scene.inspector().CollisionFiltered(
                geometry_id1=scene.ids[a], geometry_id2=scene.ids[b]
            )
        return str(info.value)

    def test_one_invalid_geometry_is_named_in_either_position(self, scene: Scene) -> None:
        c, _, _, bogus = self._setup(scene)
        assert self._message(scene, "c", "bogus") == (
            f"{CANNOT_REPORT}{c} and {bogus}; {bogus} is not a valid geometry"
        )
        assert self._message(scene, "bogus", "c") == (
            f"{CANNOT_REPORT}{bogus} and {c}; {bogus} is not a valid geometry"
        )

    def test_two_invalid_geometries_say_neither_with_one_space(self, scene: Scene) -> None:
        _, _, _, bogus = self._setup(scene)
        other = scene.g.GeometryId.get_new_id()
        scene.ids["other"] = other
        assert self._message(scene, "bogus", "other") == (
            f"{CANNOT_REPORT}{bogus} and {v(other)}; neither id is a valid geometry"
        )
        assert self._message(scene, "bogus", "bogus") == (
            f"{CANNOT_REPORT}{bogus} and {bogus}; neither id is a valid geometry"
        )

    def test_one_geometry_without_proximity_is_named_in_either_position(self, scene: Scene) -> None:
        c, d, _, _ = self._setup(scene)
        assert self._message(scene, "c", "d") == (
            f"{CANNOT_REPORT}{c} and {d}; {d} does not have a proximity role"
        )
        assert self._message(scene, "d", "c") == (
            f"{CANNOT_REPORT}{d} and {c}; {d} does not have a proximity role"
        )

    def test_two_geometries_without_proximity_say_neither_with_two_spaces(
        self, scene: Scene
    ) -> None:
        _, d, e, _ = self._setup(scene)
        assert self._message(scene, "d", "e") == (
            f"{CANNOT_REPORT}{d} and {e};  neither id has a proximity role"
        )
        assert self._message(scene, "d", "d") == (
            f"{CANNOT_REPORT}{d} and {d};  neither id has a proximity role"
        )

    def test_validity_is_checked_before_the_role(self, scene: Scene) -> None:
        _, d, _, bogus = self._setup(scene)
        assert self._message(scene, "d", "bogus") == (
            f"{CANNOT_REPORT}{d} and {bogus}; {bogus} is not a valid geometry"
        )

    def test_self_pair_of_a_proximity_geometry_is_filtered(self, scene: Scene) -> None:
        self._setup(scene)
        assert scene.filtered("c", "c") is True


# ---------------------------------------------------------------------------- B
class TestStaleModelManager:
    """A model manager held across CreateDefaultContext() edits the model but not the cache.

    Contexts copy a cached model; the cache is refreshed only if a flag-setting
    SceneGraph call (collision_filter_manager(), Register*, AssignRole,
    RemoveRole, RemoveGeometry; even when it throws) happened since the last
    CreateDefaultContext()/SetDefaultContext().
    """

    def _held_apply(self, scene: Scene) -> tuple[Any, Any]:
        scene.geometries("a", "b", "c")
        held = scene.sg.collision_filter_manager()
        ctx1 = scene.sg.CreateDefaultContext()
        held.Apply(declaration=excl(scene, "a", "b"))
        return held, ctx1

    def test_held_manager_apply_misses_contexts_created_afterwards(self, scene: Scene) -> None:
        _, ctx1 = self._held_apply(scene)
        assert scene.filtered("a", "b") is True
        assert scene.filtered("a", "b", ctx1) is False
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is False
        assert scene.C(ctx2) == all_pairs("a", "b", "c")

    def test_fresh_managers_reach_contexts_created_afterwards(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        ctx1 = scene.sg.CreateDefaultContext()
        scene.apply(excl(scene, "a", "b"))
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx1) is False
        assert scene.filtered("a", "b", ctx2) is True

    def test_discarded_collision_filter_manager_call_makes_it_visible(self, scene: Scene) -> None:
        self._held_apply(scene)
        scene.sg.collision_filter_manager()
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is True

    def test_register_source_makes_it_visible(self, scene: Scene) -> None:
        self._held_apply(scene)
        scene.sg.RegisterSource(name="other")
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is True

    def test_register_frame_makes_it_visible(self, scene: Scene) -> None:
        self._held_apply(scene)
        scene.frame("fx")
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is True

    def test_failing_register_source_makes_it_visible(self, scene: Scene) -> None:
        self._held_apply(scene)
        with pytest.raises(RuntimeError):
            scene.sg.RegisterSource(name="source")
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is True

    def test_failing_remove_geometry_makes_it_visible(self, scene: Scene) -> None:
        self._held_apply(scene)
        with pytest.raises(RuntimeError):
            scene.sg.RemoveGeometry(
                source_id=scene.source, geometry_id=scene.g.GeometryId.get_new_id()
            )
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is True

    def test_no_op_remove_role_makes_it_visible(self, scene: Scene) -> None:
        self._held_apply(scene)
        removed = scene.sg.RemoveRole(
            source_id=scene.source, geometry_id=scene.ids["c"], role=scene.g.Role.kIllustration
        )
        assert removed == 0
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is True

    def test_model_inspector_does_not_make_it_visible(self, scene: Scene) -> None:
        self._held_apply(scene)
        scene.sg.model_inspector().GetCollisionCandidates()
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is False

    def test_context_manager_call_does_not_make_it_visible(self, scene: Scene) -> None:
        _, ctx1 = self._held_apply(scene)
        scene.sg.collision_filter_manager(context=ctx1)
        scene.sg.CreateDefaultContext()
        ctx3 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx3) is False

    def test_refresh_before_the_held_apply_makes_it_visible(self, scene: Scene) -> None:
        """The snapshot is lazy: only the order of flag-setting and context creation matters."""
        scene.geometries("a", "b", "c")
        held = scene.sg.collision_filter_manager()
        scene.sg.CreateDefaultContext()
        scene.sg.collision_filter_manager()
        held.Apply(declaration=excl(scene, "a", "b"))
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx2) is True

    def test_held_manager_reaches_the_first_context_only(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        held = scene.sg.collision_filter_manager()
        held.Apply(declaration=excl(scene, "a", "b"))
        ctx1 = scene.sg.CreateDefaultContext()
        held.Apply(declaration=excl(scene, "a", "c"))
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx1) is True
        assert scene.filtered("a", "c", ctx2) is False
        assert scene.filtered("a", "c") is True

    def test_held_manager_apply_transient_misses_later_contexts(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        held = scene.sg.collision_filter_manager()
        scene.sg.CreateDefaultContext()
        tid = held.ApplyTransient(declaration=excl(scene, "a", "b"))
        assert held.has_transient_history() is True
        assert scene.filtered("a", "b") is True
        ctx2 = scene.sg.CreateDefaultContext()
        ctx2_manager = scene.manager(ctx2)
        assert scene.filtered("a", "b", ctx2) is False
        assert ctx2_manager.has_transient_history() is False
        assert ctx2_manager.IsActive(filter_id=tid) is False
        scene.sg.collision_filter_manager()
        ctx3 = scene.sg.CreateDefaultContext()
        assert scene.manager(ctx3).has_transient_history() is True
        assert scene.manager(ctx3).IsActive(filter_id=tid) is True
        assert scene.filtered("a", "b", ctx3) is True

    def test_held_manager_remove_declaration_misses_later_contexts(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        tid = scene.apply_transient(excl(scene, "a", "b"))
        held = scene.sg.collision_filter_manager()
        scene.sg.CreateDefaultContext()
        assert held.RemoveDeclaration(filter_id=tid) is True
        assert held.has_transient_history() is False
        ctx2 = scene.sg.CreateDefaultContext()
        assert scene.manager(ctx2).has_transient_history() is True
        assert scene.filtered("a", "b", ctx2) is True
        scene.sg.collision_filter_manager()
        ctx3 = scene.sg.CreateDefaultContext()
        assert scene.manager(ctx3).has_transient_history() is False
        assert scene.filtered("a", "b", ctx3) is False

    def test_set_default_context_reads_the_stale_cache(self, scene: Scene) -> None:
        held, ctx1 = self._held_apply(scene)
        del held
        scene.sg.SetDefaultContext(context=ctx1)
        assert scene.filtered("a", "b", ctx1) is False
        scene.sg.collision_filter_manager()
        scene.sg.SetDefaultContext(context=ctx1)
        assert scene.filtered("a", "b", ctx1) is True

    def test_set_default_context_consumes_the_flag(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        ctx0 = scene.sg.CreateDefaultContext()
        held = scene.sg.collision_filter_manager()
        scene.sg.SetDefaultContext(context=ctx0)
        held.Apply(declaration=excl(scene, "a", "b"))
        ctx1 = scene.sg.CreateDefaultContext()
        assert scene.filtered("a", "b", ctx1) is False
        assert scene.filtered("a", "b") is True


# --------------------------------------------------------------------------- C9
class TestPartialApply:
    """Drake 1.51.1 applies statements before a bad id to C (not to the base)."""

    def _bad_declaration(self, scene: Scene) -> Any:
        bad = scene.g.GeometrySet(geometry_ids=[scene.g.GeometryId.get_new_id()])
        return excl(scene, "a", "b").ExcludeWithin(geometry_set=bad)

    def _fail(self, scene: Scene, transient: bool) -> None:
        scene.geometries("a", "b", "c")
        apply = scene.apply_transient if transient else scene.apply
        declaration = self._bad_declaration(scene)
        with pytest.raises(RuntimeError, match=r"^Geometry set includes a geometry id"):
            apply(declaration)

    @pytest.mark.parametrize("transient", [False, True], ids=["apply", "apply_transient"])
    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_failed_apply_leaves_the_first_statement_in_c(
        self, scene: Scene, transient: bool
    ) -> None:
        self._fail(scene, transient)
        assert scene.C() == {"a-c", "b-c"}
        assert scene.manager().has_transient_history() is False

    @pytest.mark.parametrize("transient", [False, True], ids=["apply", "apply_transient"])
    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_unknown_frame_also_leaves_the_first_statement_in_c(
        self, scene: Scene, transient: bool
    ) -> None:
        scene.geometries("a", "b", "c")
        fid = scene.g.FrameId.get_new_id()
        declaration = excl(scene, "a", "b").ExcludeWithin(
            geometry_set=scene.g.GeometrySet(frame_id=fid)
        )
        with pytest.raises(RuntimeError) as info:
            (scene.apply_transient if transient else scene.apply)(declaration)
        assert str(info.value) == f"Referenced frame {v(fid)} has not been registered."
        assert scene.C() == {"a-c", "b-c"}
        assert scene.manager().has_transient_history() is False

    def test_bad_statement_first_applies_nothing(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        bad = scene.g.GeometrySet(geometry_ids=[scene.g.GeometryId.get_new_id()])
        with pytest.raises(RuntimeError):
            scene.apply(
                scene.decl()
                .ExcludeWithin(geometry_set=bad)
                .ExcludeWithin(geometry_set=scene.set("a", "b"))
            )
        assert scene.C() == all_pairs("a", "b", "c")

    def test_bad_id_inside_a_statements_set_applies_nothing_of_it(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        bad = scene.g.GeometryId.get_new_id()
        with pytest.raises(RuntimeError):
            scene.apply(
                scene.decl().ExcludeBetween(
                    set_A=scene.set("a"),
                    set_B=scene.g.GeometrySet(geometry_ids=[scene.ids["b"], bad]),
                )
            )
        assert scene.C() == all_pairs("a", "b", "c")

    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_only_statements_before_the_bad_one_are_applied(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        bad = scene.g.GeometrySet(geometry_ids=[scene.g.GeometryId.get_new_id()])
        with pytest.raises(RuntimeError):
            scene.apply_transient(
                excl(scene, "a", "b")
                .ExcludeWithin(geometry_set=bad)
                .ExcludeBetween(set_A=scene.set("b"), set_B=scene.set("c"))
            )
        assert scene.C() == {"a-c", "b-c"}

    @pytest.mark.parametrize("transient", [False, True], ids=["apply", "apply_transient"])
    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_leftover_survives_a_following_transient_add(
        self, scene: Scene, transient: bool
    ) -> None:
        self._fail(scene, transient)
        scene.apply_transient(scene.decl())
        assert scene.C() == {"a-c", "b-c"}

    @pytest.mark.parametrize("transient", [False, True], ids=["apply", "apply_transient"])
    def test_leftover_is_gone_after_a_transient_add_and_remove(
        self, scene: Scene, transient: bool
    ) -> None:
        self._fail(scene, transient)
        filter_id = scene.apply_transient(scene.decl())
        assert scene.remove(filter_id) is True
        assert scene.C() == all_pairs("a", "b", "c")
        assert scene.manager().has_transient_history() is False

    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_leftover_survives_removing_an_unknown_filter_id(self, scene: Scene) -> None:
        self._fail(scene, transient=False)
        assert scene.remove(scene.g.FilterId.get_new_id()) is False
        assert scene.C() == {"a-c", "b-c"}

    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_leftover_is_not_in_the_persistent_base(self, scene: Scene) -> None:
        self._fail(scene, transient=False)
        scene.apply(excl(scene, "b", "c"))
        assert scene.C() == {"a-c"}
        scene.remove(scene.apply_transient(scene.decl()))
        assert scene.C() == {"a-b", "a-c"}

    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_partial_transient_while_another_is_active_leaves_its_first_statement(
        self, scene: Scene
    ) -> None:
        scene.geometries("a", "b", "c")
        t1 = scene.apply_transient(excl(scene, "b", "c"))
        with pytest.raises(RuntimeError):
            scene.apply_transient(self._bad_declaration(scene))
        assert scene.C() == {"a-c"}
        assert scene.remove(t1) is True
        assert scene.C() == all_pairs("a", "b", "c")

    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_context_created_while_the_leftover_exists_has_it(self, scene: Scene) -> None:
        self._fail(scene, transient=False)
        context = scene.sg.CreateDefaultContext()
        assert scene.C(context) == {"a-c", "b-c"}
        assert scene.manager(context).has_transient_history() is False


# --------------------------------------------------------------------------- A7
class TestContextClone:
    def _two_frames(self, scene: Scene) -> None:
        scene.geometries("a", "b")

    def test_clone_after_unfixed_query_eval_raises(self, scene: Scene) -> None:
        self._two_frames(scene)
        context = scene.sg.CreateDefaultContext()
        scene.sg.get_query_output_port().Eval(context)
        with pytest.raises(RuntimeError) as info:
            context.Clone()
        assert str(info.value) == (
            f"Source 'source' (id: {v(scene.source)}) has registered dynamic frames but is not "
            "connected to the appropriate input port."
        )

    def test_clone_without_eval_is_fine(self, scene: Scene) -> None:
        self._two_frames(scene)
        context = scene.sg.CreateDefaultContext()
        clone = context.Clone()
        assert clone is not context
        assert scene.C(clone) == {"a-b"}

    def test_clone_of_anchored_only_source_after_eval_is_fine(self, scene: Scene) -> None:
        scene.geometry("A", "world")
        scene.geometry("B", "world")
        context = scene.sg.CreateDefaultContext()
        scene.sg.get_query_output_port().Eval(context)
        assert scene.C(context.Clone()) == set()

    def test_clone_with_fixed_poses_after_eval_is_fine(self, scene: Scene) -> None:
        self._two_frames(scene)
        context = scene.sg.CreateDefaultContext()
        fix_poses(scene, context)
        assert scene.C(context) == {"a-b"}
        assert scene.C(context.Clone()) == {"a-b"}

    def test_clone_copies_filters_and_history_then_is_independent(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        context = scene.sg.CreateDefaultContext()
        fix_poses(scene, context)
        scene.apply(excl(scene, "a", "b"), context)
        tid = scene.apply_transient(excl(scene, "b", "c"), context)
        assert scene.C(context) == {"a-c"}
        clone = context.Clone()
        clone_manager = scene.manager(clone)
        assert scene.C(clone) == {"a-c"}
        assert clone_manager.has_transient_history() is True
        assert clone_manager.IsActive(filter_id=tid) is True
        assert clone_manager.RemoveDeclaration(filter_id=tid) is True
        assert scene.C(clone) == {"a-c", "b-c"}
        assert scene.C(context) == {"a-c"}
        assert scene.manager(context).IsActive(filter_id=tid) is True
        assert scene.C() == all_pairs("a", "b", "c")

    def test_clone_of_a_clone_of_an_evaluated_context_does_not_check_poses(
        self, scene: Scene
    ) -> None:
        """Cloning ran the pose update, and the clone copies it up to date (pose_update's table)."""
        scene.geometry("A", "world")
        context = scene.sg.CreateDefaultContext()
        scene.sg.get_query_output_port().Eval(context)
        clone = context.Clone()  # No dynamic frames yet: fine on both.
        scene.geometries("g")
        scene.sg.SetDefaultContext(context=clone)
        assert scene.C(clone) == {"A-g"}
        # pydrake: Clone() succeeds here; the original context still raises.
        assert scene.C(clone.Clone()) == {"A-g"}

    def test_evaluated_context_given_frames_by_set_default_context_raises_on_clone(
        self, scene: Scene
    ) -> None:
        scene.geometry("A", "world")
        context = scene.sg.CreateDefaultContext()
        scene.sg.get_query_output_port().Eval(context)
        scene.geometries("g")
        scene.sg.SetDefaultContext(context=context)
        assert scene.C(context) == {"A-g"}
        with pytest.raises(RuntimeError, match="has registered dynamic frames but is not"):
            context.Clone()

    def test_context_copies_the_model_history_with_the_same_filter_id(self, scene: Scene) -> None:
        scene.geometries("a", "b")
        tid = scene.apply_transient(excl(scene, "a", "b"))
        context = scene.sg.CreateDefaultContext()
        manager = scene.manager(context)
        assert manager.IsActive(filter_id=tid) is True
        with pytest.raises(RuntimeError) as info:
            manager.Apply(declaration=scene.decl())
        assert str(info.value) == PERSISTENT_WITH_HISTORY
        assert manager.RemoveDeclaration(filter_id=tid) is True
        assert scene.C(context) == {"a-b"}
        assert scene.C() == set()
        assert scene.manager().IsActive(filter_id=tid) is True


# ---------------------------------------------------------------------- C2/C3/C5
class TestRolesDuringFiltering:
    def test_remove_illustration_role_leaves_c_unchanged(self, scene: Scene) -> None:
        scene.frame("F")
        scene.geometry("a", "F")
        scene.geometry("a2", "F")
        scene.geometries("o", "p")
        for name in ("a", "o"):
            scene.sg.AssignRole(
                source_id=scene.source,
                geometry_id=scene.ids[name],
                properties=scene.g.IllustrationProperties(),
            )
        scene.apply(excl(scene, "a", "o"))
        before = {"a-p", "a2-o", "a2-p", "o-p"}
        assert scene.C() == before
        role = scene.g.Role.kIllustration
        assert (
            scene.sg.RemoveRole(source_id=scene.source, geometry_id=scene.ids["a"], role=role) == 1
        )
        assert (
            scene.sg.RemoveRole(source_id=scene.source, frame_id=scene.frames["f_o"], role=role)
            == 1
        )
        assert scene.C() == before
        assert scene.filtered("a", "o")

    def test_remove_proximity_during_history_succeeds(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c")
        scene.apply(excl(scene, "a", "c"))
        tid = scene.apply_transient(
            excl(scene, "a", "b").ExcludeBetween(set_A=scene.set("b"), set_B=scene.set("c"))
        )
        assert scene.C() == set()
        assert scene.remove_proximity("b") == 1
        assert scene.C() == set()
        assert scene.manager().has_transient_history() is True
        assert scene.manager().IsActive(filter_id=tid) is True
        assert scene.remove(tid) is True
        assert scene.C() == set()
        assert scene.manager().has_transient_history() is False
        scene.assign_proximity("b")
        assert scene.C() == {"a-b", "b-c"}

    def test_remove_geometry_during_history_then_remove_declaration(self, scene: Scene) -> None:
        scene.geometries("a", "b", "c", "d")
        scene.apply(excl(scene, "c", "d"))
        tid = scene.apply_transient(
            scene.decl()
            .ExcludeWithin(geometry_set=scene.set("a", "b", "c"))
            .AllowBetween(set_A=scene.set("c"), set_B=scene.set("d"))
        )
        assert scene.C() == {"a-d", "b-d", "c-d"}
        scene.sg.RemoveGeometry(source_id=scene.source, geometry_id=scene.ids["b"])
        assert scene.C() == {"a-d", "c-d"}
        assert scene.manager().IsActive(filter_id=tid) is True
        assert scene.remove(tid) is True
        assert scene.C() == {"a-c", "a-d"}
        scene.frame("fb2")
        scene.geometry("b", "fb2")
        assert scene.C() == {"a-b", "a-c", "a-d", "b-c", "b-d"}

    def test_proximity_assigned_during_history_raises_but_keeps_the_role(
        self, scene: Scene
    ) -> None:
        scene.frame("F")
        scene.geometry("a", "F")
        scene.geometries("o")
        tid = scene.apply_transient(excl(scene, "a", "o"))
        with pytest.raises(RuntimeError) as info:
            scene.geometry("n", "F")
        assert str(info.value) == PERSISTENT_WITH_HISTORY
        assert scene.inspector().GetProximityProperties(geometry_id=scene.ids["n"]) is not None
        assert scene.C() == {"a-n", "n-o"}
        assert scene.remove(tid) is True
        assert scene.C() == {"a-n", "a-o", "n-o"}

    def test_replace_proximity_during_history_is_allowed(self, scene: Scene) -> None:
        scene.geometries("a", "b")
        scene.apply_transient(excl(scene, "a", "b"))
        scene.assign_proximity("a", replace=True)
        assert scene.C() == set()
