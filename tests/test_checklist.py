"""Checklist items 1-21 of shared/drake-semantics.md, on reimpl and on real pydrake.

Every test asserts the documented value; agreement between the two
implementations follows from both meeting it. Setup unless stated: one
source, each gᵢ a proximity geometry on its own dynamic frame.
"""

from __future__ import annotations

import pytest

from tests.conftest import Scene, all_pairs

UNKNOWN_GEOMETRY = "Geometry set includes a geometry id that doesn't belong to the SceneGraph: "
PERSISTENT_WITH_HISTORY = (
    "You cannot attempt to modify the persistent collision filter configuration when there "
    "are active, transient filter declarations"
)


class TestInvariantPairs:
    """C = (Gₚ × Gₚ) − (Aₚ × Aₚ) − Fₚ − Iₚ; no pair of Aₚ × Aₚ, Fₚ or Iₚ can be added to C."""

    def test_same_frame_pair_is_filtered_and_allow_within_keeps_it(self, scene: Scene) -> None:
        scene.frame("f0")
        scene.geometry("g0a", "f0")
        scene.geometry("g0b", "f0")
        assert scene.filtered("g0a", "g0b")
        scene.apply(scene.decl().AllowWithin(geometry_set=scene.set("g0a", "g0b")))
        assert scene.filtered("g0a", "g0b")
        assert scene.C() == set()

    def test_anchored_pair_is_filtered_and_allow_between_keeps_it(self, scene: Scene) -> None:
        scene.geometry("a1", "world")
        scene.geometry("a2", "world")
        scene.geometries("g")
        assert scene.filtered("a1", "a2")
        scene.apply(scene.decl().AllowBetween(set_A=scene.set("a1"), set_B=scene.set("a2")))
        assert scene.filtered("a1", "a2")
        assert not scene.filtered("g", "a1")
        assert scene.C() == {"a1-g", "a2-g"}

    def test_self_pair_is_filtered_and_never_a_candidate(self, scene: Scene) -> None:
        scene.geometries("g0", "g1")
        assert scene.filtered("g0", "g0")
        scene.apply(scene.decl().AllowWithin(geometry_set=scene.set("g0", "g1")))
        assert scene.filtered("g0", "g0")
        assert scene.C() == {"g0-g1"}

    def test_allow_within_world_frame_restores_anchored_dynamic_pairs_only(
        self, scene: Scene
    ) -> None:
        scene.geometry("a1", "world")
        scene.geometry("a2", "world")
        scene.geometries("g")
        scene.apply(scene.decl().ExcludeWithin(geometry_set=scene.set("a1", "a2", "g")))
        assert scene.C() == set()
        scene.apply(scene.decl().AllowWithin(geometry_set=scene.set("g", frames=["world"])))
        assert scene.C() == {"a1-g", "a2-g"}


class TestFrameResolution:
    """A FrameId stands for the proximity geometries *directly* on it, at application time."""

    def test_parent_and_child_frames_are_not_filtered(self, scene: Scene) -> None:
        scene.frame("f1")
        scene.frame("f2", parent="f1")
        scene.geometry("g1", "f1")
        scene.geometry("g2", "f2")
        assert not scene.filtered("g1", "g2")

    def test_frame_set_covers_only_direct_children(self, scene: Scene) -> None:
        scene.frame("f1")
        scene.frame("f2", parent="f1")
        scene.geometry("g1", "f1")
        scene.geometry("g2", "f2")
        scene.geometries("x")
        scene.apply(
            scene.decl().ExcludeBetween(set_A=scene.set(frames=["f1"]), set_B=scene.set("x"))
        )
        assert scene.C() == {"g1-g2", "g2-x"}

    def test_world_frame_set_covers_all_anchored_geometry(self, scene: Scene) -> None:
        scene.geometry("a1", "world")
        scene.geometry("a2", "world")
        scene.geometries("g")
        scene.apply(
            scene.decl().ExcludeBetween(set_A=scene.set(frames=["world"]), set_B=scene.set("g"))
        )
        assert scene.C() == set()

    def test_geometry_added_to_a_frame_later_is_not_covered(self, scene: Scene) -> None:
        scene.geometries("g0", "g1")
        f0 = "f_g0"
        scene.apply(
            scene.decl().ExcludeBetween(
                set_A=scene.set(frames=[f0]), set_B=scene.set(frames=["f_g1"])
            )
        )
        scene.geometry("gnew", f0)
        assert not scene.filtered("gnew", "g1")
        assert scene.filtered("gnew", "g0")
        assert scene.C() == {"g1-gnew"}

    def test_non_proximity_geometry_is_dropped_and_not_covered_later(self, scene: Scene) -> None:
        scene.geometries("g1")
        scene.frame("f2")
        scene.geometry("n", "f2", proximity=False)
        scene.apply(scene.decl().ExcludeBetween(set_A=scene.set("n"), set_B=scene.set("g1")))
        scene.assign_proximity("n")
        assert not scene.filtered("n", "g1")
        scene.apply(scene.decl().ExcludeBetween(set_A=scene.set("n"), set_B=scene.set("g1")))
        assert scene.filtered("n", "g1")

    def test_non_proximity_geometry_on_a_shared_frame_is_filtered_on_assignment(
        self, scene: Scene
    ) -> None:
        scene.geometries("g1")
        scene.geometry("n", "f_g1", proximity=False)
        scene.apply(scene.decl().ExcludeBetween(set_A=scene.set("n"), set_B=scene.set("g1")))
        scene.assign_proximity("n")
        assert scene.filtered("n", "g1")


class TestStatements:
    """Each statement's P, from collision_filter_declaration.h."""

    def test_exclude_between_removes_exactly_the_cross_pairs(self, scene: Scene) -> None:
        scene.geometries("g0", "g1", "g2")
        scene.apply(scene.decl().ExcludeBetween(set_A=scene.set("g0"), set_B=scene.set("g1", "g2")))
        assert scene.C() == {"g1-g2"}

    def test_exclude_within_removes_every_pair_inside_each_set(self, scene: Scene) -> None:
        scene.geometries("g0", "g1", "g2", "g3")
        scene.apply(
            scene.decl()
            .ExcludeWithin(geometry_set=scene.set("g0", "g1", "g3"))
            .ExcludeWithin(geometry_set=scene.set("g0", "g2"))
        )
        assert scene.C() == {"g1-g2", "g2-g3"}

    def test_exclude_between_overlapping_sets_filters_the_shared_member_too(
        self, scene: Scene
    ) -> None:
        scene.geometries("g0", "g1", "g2")
        scene.apply(
            scene.decl().ExcludeBetween(set_A=scene.set("g0", "g1"), set_B=scene.set("g1", "g2"))
        )
        assert scene.C() == set()

    def test_allow_between_leaves_within_set_pairs_filtered(self, scene: Scene) -> None:
        scene.geometries("g0", "g1", "g2")
        scene.apply(scene.decl().ExcludeWithin(geometry_set=scene.set("g0", "g1", "g2")))
        scene.apply(scene.decl().AllowBetween(set_A=scene.set("g0"), set_B=scene.set("g1", "g2")))
        assert scene.C() == {"g0-g1", "g0-g2"}

    def test_statements_apply_in_invocation_order(self, scene: Scene) -> None:
        scene.geometries("g1", "g2")
        scene.apply(
            scene.decl()
            .ExcludeWithin(geometry_set=scene.set("g1", "g2"))
            .AllowBetween(set_A=scene.set("g1"), set_B=scene.set("g2"))
        )
        assert not scene.filtered("g1", "g2")
        scene.apply(
            scene.decl()
            .AllowBetween(set_A=scene.set("g1"), set_B=scene.set("g2"))
            .ExcludeWithin(geometry_set=scene.set("g1", "g2"))
        )
        assert scene.filtered("g1", "g2")

    def test_every_statement_returns_the_declaration_itself(self, scene: Scene) -> None:
        scene.geometries("g0")
        decl = scene.decl()
        s = scene.set("g0")
        assert decl.ExcludeWithin(geometry_set=s) is decl
        assert decl.AllowWithin(geometry_set=s) is decl
        assert decl.ExcludeBetween(set_A=s, set_B=s) is decl
        assert decl.AllowBetween(set_A=s, set_B=s) is decl


class TestErrors:
    """Unknown ids raise RuntimeError with Drake's message; nothing else is validated."""

    def test_unknown_geometry_id_raises_with_its_value(self, scene: Scene) -> None:
        scene.geometries("g0")
        unknown = scene.g.GeometryId.get_new_id()
        decl = scene.decl().ExcludeBetween(
            set_A=scene.set("g0"), set_B=scene.g.GeometrySet(geometry_ids=[unknown])
        )
        with pytest.raises(RuntimeError) as info:
            scene.apply(decl)
        assert str(info.value) == UNKNOWN_GEOMETRY + str(unknown.get_value())

    def test_unknown_frame_id_raises_with_its_value(self, scene: Scene) -> None:
        scene.geometries("g0")
        unknown = scene.g.FrameId.get_new_id()
        decl = scene.decl().ExcludeWithin(geometry_set=scene.g.GeometrySet(frame_ids=[unknown]))
        with pytest.raises(RuntimeError) as info:
            scene.apply_transient(decl)
        assert str(info.value) == f"Referenced frame {unknown.get_value()} has not been registered."
        assert not scene.manager().has_transient_history()

    def test_removed_geometry_id_is_unknown(self, scene: Scene) -> None:
        scene.geometries("g0", "g1")
        scene.sg.RemoveGeometry(source_id=scene.source, geometry_id=scene.ids["g1"])
        with pytest.raises(RuntimeError, match="doesn't belong to the SceneGraph"):
            scene.apply(scene.decl().ExcludeWithin(geometry_set=scene.set("g0", "g1")))

    @pytest.mark.release_fact("partial-apply-until-1.51")
    def test_apply_is_not_atomic(self, scene: Scene) -> None:
        """Drake ≤ 1.51: statements before the bad id stay applied (pydrake-observed §2)."""
        scene.geometries("a", "b")
        bad = scene.g.GeometrySet(geometry_ids=[scene.g.GeometryId.get_new_id()])
        with pytest.raises(RuntimeError):
            scene.apply(
                scene.decl()
                .ExcludeWithin(geometry_set=scene.set("a", "b"))
                .ExcludeWithin(geometry_set=bad)
            )
        assert scene.C() == set()

    def test_collision_filtered_names_the_invalid_geometry(self, scene: Scene) -> None:
        scene.geometries("g0")
        bad = scene.g.GeometryId.get_new_id()
        inspector = scene.inspector()
        with pytest.raises(RuntimeError) as info:
            inspector.CollisionFiltered(geometry_id1=scene.ids["g0"], geometry_id2=bad)
        g0, b = scene.ids["g0"].get_value(), bad.get_value()
        assert str(info.value) == (
            f"Can't report collision filter status between geometries {g0} and {b}; "
            f"{b} is not a valid geometry"
        )

    def test_collision_filtered_names_the_geometry_without_proximity(self, scene: Scene) -> None:
        scene.geometries("g0")
        scene.geometry("n", "f_g0", proximity=False)
        g0, n = scene.ids["g0"].get_value(), scene.ids["n"].get_value()
        with pytest.raises(RuntimeError) as info:
            scene.filtered("g0", "n")
        assert str(info.value) == (
            f"Can't report collision filter status between geometries {g0} and {n}; "
            f"{n} does not have a proximity role"
        )

    def test_assigning_proximity_twice_raises(self, scene: Scene) -> None:
        scene.geometries("g0")
        with pytest.raises(RuntimeError) as info:
            scene.assign_proximity("g0")
        assert str(info.value) == (
            f"Trying to assign the 'proximity' role to geometry id "
            f"{scene.ids['g0'].get_value()} for the first time; it already has the role assigned"
        )


class TestRoles:
    """Removing the proximity role forgets a geometry's filters; kReplace keeps them."""

    def test_remove_and_reassign_proximity_forgets_user_filters(self, scene: Scene) -> None:
        scene.geometries("g0", "g1")
        scene.apply(scene.decl().ExcludeBetween(set_A=scene.set("g0"), set_B=scene.set("g1")))
        assert scene.remove_proximity("g0") == 1
        scene.assign_proximity("g0")
        assert not scene.filtered("g0", "g1")

    def test_remove_and_reassign_proximity_restores_same_frame_invariants(
        self, scene: Scene
    ) -> None:
        scene.frame("f0")
        scene.geometry("a", "f0")
        scene.geometry("b", "f0")
        scene.remove_proximity("a")
        scene.assign_proximity("a")
        assert scene.filtered("a", "b")

    def test_replace_proximity_keeps_user_filters(self, scene: Scene) -> None:
        scene.geometries("g0", "g1")
        scene.apply(scene.decl().ExcludeBetween(set_A=scene.set("g0"), set_B=scene.set("g1")))
        scene.assign_proximity("g0", replace=True)
        assert scene.filtered("g0", "g1")

    def test_remove_role_without_the_role_returns_zero(self, scene: Scene) -> None:
        scene.frame("f0")
        scene.geometry("n", "f0", proximity=False)
        assert scene.remove_proximity("n") == 0

    def test_candidates_hold_only_proximity_geometries_smaller_id_first(self, scene: Scene) -> None:
        scene.geometries("g0", "g1", "g2")
        scene.geometry("n", "f_g0", proximity=False)
        candidates = scene.inspector().GetCollisionCandidates()
        assert isinstance(candidates, set)
        assert len(candidates) == 3
        for a, b in candidates:
            assert a.get_value() < b.get_value()
        assert scene.C() == all_pairs("g0", "g1", "g2")


class TestTransientHistory:
    """C is the persistent base with the live transient declarations replayed in order."""

    def _table_one(self, scene: Scene) -> None:
        """4 geometries, P₁..P₆ = 01, 02, 03, 12, 13, 23; lines 1-4 persistent."""
        scene.geometries("g0", "g1", "g2", "g3")
        assert scene.C() == all_pairs("g0", "g1", "g2", "g3")  # line 1
        scene.apply(scene.decl().ExcludeBetween(set_A=scene.set("g0"), set_B=scene.set("g1")))
        assert scene.C() == {"g0-g2", "g0-g3", "g1-g2", "g1-g3", "g2-g3"}  # line 2
        scene.apply(scene.decl().ExcludeBetween(set_A=scene.set("g2"), set_B=scene.set("g3")))
        assert scene.C() == {"g0-g2", "g0-g3", "g1-g2", "g1-g3"}  # line 3
        scene.apply(
            scene.decl()
            .ExcludeWithin(geometry_set=scene.set("g0", "g1", "g2", "g3"))
            .AllowBetween(set_A=scene.set("g0"), set_B=scene.set("g2"))
        )
        assert scene.C() == {"g0-g2"}  # line 4

    def test_table_one_lines_one_to_seven(self, scene: Scene) -> None:
        self._table_one(scene)
        t1 = scene.apply_transient(
            scene.decl().AllowBetween(set_A=scene.set("g1"), set_B=scene.set("g2", "g3"))
        )
        assert scene.C() == {"g0-g2", "g1-g2", "g1-g3"}  # line 5: P₂, P₄, P₅
        t2 = scene.apply_transient(
            scene.decl()
            .AllowBetween(set_A=scene.set("g0"), set_B=scene.set("g3"))
            .AllowBetween(set_A=scene.set("g1"), set_B=scene.set("g2"))
        )
        assert scene.C() == {"g0-g2", "g0-g3", "g1-g2", "g1-g3"}  # line 6: P₂..P₅
        assert scene.remove(t1) is True
        assert scene.C() == {"g0-g2", "g0-g3", "g1-g2"}  # line 7: P₂, P₃, P₄
        assert scene.manager().IsActive(filter_id=t2)
        assert not scene.manager().IsActive(filter_id=t1)

    def test_table_one_line_eight_has_no_public_flatten_so_removing_the_rest_restores_the_base(
        self, scene: Scene
    ) -> None:
        self._table_one(scene)
        t1 = scene.apply_transient(
            scene.decl().AllowBetween(set_A=scene.set("g1"), set_B=scene.set("g2", "g3"))
        )
        t2 = scene.apply_transient(
            scene.decl()
            .AllowBetween(set_A=scene.set("g0"), set_B=scene.set("g3"))
            .AllowBetween(set_A=scene.set("g1"), set_B=scene.set("g2"))
        )
        assert scene.remove(t1)
        assert not hasattr(scene.manager(), "Flatten")
        assert scene.remove(t1) is False
        assert scene.remove(t2) is True
        assert scene.C() == {"g0-g2"}
        assert not scene.manager().has_transient_history()

    def test_unknown_filter_id_is_inactive_and_not_removable(self, scene: Scene) -> None:
        scene.geometries("g0", "g1")
        unknown = scene.g.FilterId.get_new_id()
        assert scene.manager().IsActive(filter_id=unknown) is False
        assert scene.remove(unknown) is False
        assert scene.C() == {"g0-g1"}

    def test_apply_during_history_raises(self, scene: Scene) -> None:
        scene.geometries("g0", "g1")
        scene.apply_transient(scene.decl())
        with pytest.raises(RuntimeError) as info:
            scene.apply(scene.decl())
        assert str(info.value) == PERSISTENT_WITH_HISTORY

    def test_assigning_proximity_during_history_raises_and_skips_same_frame_invariants(
        self, scene: Scene
    ) -> None:
        scene.frame("f0")
        scene.geometry("a", "f0")
        scene.apply_transient(scene.decl())
        with pytest.raises(RuntimeError) as info:
            scene.geometry("late", "f0")
        assert str(info.value) == PERSISTENT_WITH_HISTORY
        assert scene.inspector().GetProximityProperties(geometry_id=scene.ids["late"]) is not None
        assert not scene.filtered("a", "late")
        assert scene.C() == {"a-late"}

    def test_empty_transient_declaration_is_active_history_and_changes_nothing(
        self, scene: Scene
    ) -> None:
        scene.geometries("g0", "g1")
        t = scene.apply_transient(scene.decl())
        assert t.is_valid()
        assert scene.manager().IsActive(filter_id=t)
        assert scene.manager().has_transient_history()
        assert scene.C() == {"g0-g1"}

    def test_collision_filter_test_transient_sequence(self, scene: Scene) -> None:
        """collision_filter_test.cc TransientDeclarations, with D and E on one frame."""
        scene.geometries("A", "B", "C")
        scene.frame("fDE")
        scene.geometry("D", "fDE")
        scene.geometry("E", "fDE")
        s = scene.set
        scene.apply(scene.decl().ExcludeBetween(set_A=s("B"), set_B=s("C", "D", "E")))
        base = {"A-B", "A-C", "A-D", "A-E", "C-D", "C-E"}
        assert scene.C() == base
        id0 = scene.apply_transient(scene.decl().ExcludeBetween(set_A=s("B"), set_B=s("C")))
        assert scene.C() == base
        id1 = scene.apply_transient(
            scene.decl()
            .ExcludeWithin(geometry_set=s("C", "D"))
            .AllowWithin(geometry_set=s("B", "D"))
        )
        after_id1 = {"A-B", "A-C", "A-D", "A-E", "B-D", "C-E"}
        assert scene.C() == after_id1

        def second():
            return (
                scene.decl()
                .ExcludeBetween(set_A=s("A"), set_B=s("B", "C"))
                .AllowBetween(set_A=s("B"), set_B=s("C", "E"))
            )

        id2 = scene.apply_transient(second())
        assert scene.C() == {"A-D", "A-E", "B-C", "B-D", "B-E", "C-E"}
        assert scene.remove(scene.g.FilterId.get_new_id()) is False
        assert scene.remove(id2)
        assert scene.C() == after_id1
        id3 = scene.apply_transient(second())
        scene.apply_transient(
            scene.decl()
            .ExcludeWithin(geometry_set=s("A", "B"))
            .AllowWithin(geometry_set=s("B", "E"))
        )
        assert scene.remove(id3)
        assert scene.C() == {"A-C", "A-D", "A-E", "B-D", "B-E", "C-E"}
        scene.apply_transient(scene.decl().AllowWithin(geometry_set=s("D", "E")))
        assert scene.filtered("D", "E")
        assert all(scene.manager().IsActive(filter_id=i) for i in (id0, id1))

    def test_removing_a_geometry_under_history_drops_its_pairs_and_replay_omits_it(
        self, scene: Scene
    ) -> None:
        scene.geometries("g0", "g1", "g2")
        t = scene.apply_transient(
            scene.decl().ExcludeWithin(geometry_set=scene.set("g0", "g1", "g2"))
        )
        scene.sg.RemoveGeometry(source_id=scene.source, geometry_id=scene.ids["g2"])
        assert scene.C() == set()
        assert scene.remove(t)
        assert scene.C() == {"g0-g1"}


class TestContexts:
    """A context copies the model when created; afterwards each is independent."""

    def test_context_filters_are_invisible_to_the_model_and_back(self, scene: Scene) -> None:
        scene.geometries("g0", "g1", "g2")
        ctx = scene.sg.CreateDefaultContext()
        scene.apply(scene.decl().ExcludeWithin(geometry_set=scene.set("g0", "g1")), context=ctx)
        scene.apply(scene.decl().ExcludeWithin(geometry_set=scene.set("g1", "g2")))
        assert scene.C(ctx) == {"g0-g2", "g1-g2"}
        assert scene.C() == {"g0-g1", "g0-g2"}

    def test_model_transient_is_copied_into_new_contexts_with_its_filter_id(
        self, scene: Scene
    ) -> None:
        scene.geometries("g0", "g1")
        t = scene.apply_transient(scene.decl().ExcludeWithin(geometry_set=scene.set("g0", "g1")))
        ctx = scene.sg.CreateDefaultContext()
        assert scene.manager(ctx).IsActive(filter_id=t)
        assert scene.remove(t)
        assert scene.C() == {"g0-g1"}
        assert scene.C(ctx) == set()
        assert scene.manager(ctx).IsActive(filter_id=t)
        with pytest.raises(RuntimeError, match="active, transient filter declarations"):
            scene.apply(scene.decl(), context=ctx)
        assert scene.remove(t, context=ctx)
        assert scene.C(ctx) == {"g0-g1"}

    def test_set_default_context_resets_filters_to_the_model(self, scene: Scene) -> None:
        scene.geometries("g0", "g1")
        ctx = scene.sg.CreateDefaultContext()
        t = scene.apply_transient(
            scene.decl().ExcludeWithin(geometry_set=scene.set("g0", "g1")), context=ctx
        )
        assert scene.C(ctx) == set()
        scene.sg.SetDefaultContext(context=ctx)
        assert scene.C(ctx) == {"g0-g1"}
        assert not scene.manager(ctx).IsActive(filter_id=t)
