"""Unit tests of reimpl's internals: CollisionFilter, declarations, overloads, math, shapes.

These run on reimpl only. Geometry ids are made with ``GeometryId.get_new_id()``
and sets resolve to their geometry ids directly (no SceneGraph), so each test
pins one piece of the pair state: C = (G × G) − I − V − U, U = replay(base,
history).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np
import pytest

from reimpl._overload import Overload, Param, dispatch, instance_of, list_of
from reimpl.geometry import (
    Box,
    Capsule,
    CollisionFilterDeclaration,
    Cylinder,
    Ellipsoid,
    FilterId,
    FrameId,
    GeometryId,
    GeometrySet,
    Sphere,
)
from reimpl.geometry.collision_filter import CollisionFilter, PairRelationship
from reimpl.geometry.collision_filter_declaration import Statement, StatementOp
from reimpl.geometry.errors import TransientHistoryActiveError, UnknownGeometryError
from reimpl.math import RigidTransform, RollPitchYaw, RotationMatrix


# ------------------------------------------------------------------ helpers
class Pairs:
    """A CollisionFilter over named geometries, with a resolver of known ids."""

    def __init__(self, *names: str) -> None:
        self.filter = CollisionFilter()
        self.ids: dict[str, GeometryId] = {}
        self.names: dict[GeometryId, str] = {}
        self.add(*names)

    def add(self, *names: str) -> None:
        for name in names:
            gid = GeometryId.get_new_id()
            self.ids[name] = gid
            self.names[gid] = name
            self.filter.add_geometry(gid)

    def remove(self, name: str) -> None:
        self.filter.remove_geometry(self.ids[name])

    def resolve(self, geometry_set: GeometrySet) -> list[GeometryId]:
        out = []
        for gid in geometry_set.geometry_ids():
            if not self.filter.has_geometry(gid):
                raise UnknownGeometryError(f"unknown {gid.get_value()}")
            out.append(gid)
        return out

    def s(self, *names: str) -> GeometrySet:
        return GeometrySet(geometry_ids=[self.ids[n] for n in names])

    def decl(self) -> CollisionFilterDeclaration:
        return CollisionFilterDeclaration()

    def excl(self, a: str, b: str) -> CollisionFilterDeclaration:
        return self.decl().ExcludeBetween(set_A=self.s(a), set_B=self.s(b))

    def allow(self, a: str, b: str) -> CollisionFilterDeclaration:
        return self.decl().AllowBetween(set_A=self.s(a), set_B=self.s(b))

    def apply(self, declaration: CollisionFilterDeclaration, *, invariant: bool = False) -> None:
        self.filter.apply(declaration.statements(), self.resolve, is_invariant=invariant)

    def transient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        return self.filter.apply_transient(declaration.statements(), self.resolve)

    def C(self) -> set[str]:
        out = set()
        for a, b in self.filter.candidates():
            assert a.get_value() < b.get_value()
            out.add("-".join(sorted((self.names[a], self.names[b]))))
        return out

    def rel(self, a: str, b: str) -> PairRelationship:
        forward = self.filter.relationship(self.ids[a], self.ids[b])
        assert forward is self.filter.relationship(self.ids[b], self.ids[a])
        return forward


def pairs_of(names: Iterable[str]) -> set[str]:
    ordered = sorted(names)
    return {f"{a}-{b}" for i, a in enumerate(ordered) for b in ordered[i + 1 :]}


# ----------------------------------------------------------- CollisionFilter
class TestCollisionFilterGeometries:
    def test_added_geometries_are_pairwise_candidates(self) -> None:
        p = Pairs("a", "b", "c")
        assert p.C() == {"a-b", "a-c", "b-c"}
        assert all(p.filter.has_geometry(p.ids[n]) for n in "abc")
        assert p.filter.has_geometry(GeometryId.get_new_id()) is False

    def test_adding_a_geometry_twice_raises_assertion_error(self) -> None:
        p = Pairs("a")
        with pytest.raises(AssertionError, match="already registered"):
            p.filter.add_geometry(p.ids["a"])

    def test_removed_geometry_leaves_c_and_the_filter(self) -> None:
        p = Pairs("a", "b", "c")
        p.apply(p.excl("a", "b"))
        p.remove("b")
        assert p.C() == {"a-c"}
        assert p.filter.has_geometry(p.ids["b"]) is False

    def test_removed_slot_is_reused_and_starts_unfiltered(self) -> None:
        p = Pairs("a", "b", "c")
        slot_b = p.filter._slot_of[p.ids["b"]]
        p.apply(p.decl().ExcludeWithin(geometry_set=p.s("a", "b", "c")))
        p.apply(p.excl("a", "b"), invariant=True)
        p.remove("b")
        p.add("d")
        assert p.filter._slot_of[p.ids["d"]] == slot_b
        assert p.rel("a", "d") is PairRelationship.UNFILTERED
        assert p.rel("c", "d") is PairRelationship.UNFILTERED
        assert p.rel("a", "c") is PairRelationship.FILTERED
        assert p.C() == {"a-d", "c-d"}

    def test_removed_geometry_leaves_the_transient_history(self) -> None:
        p = Pairs("a", "b", "c")
        tid = p.transient(p.decl().ExcludeWithin(geometry_set=p.s("a", "b", "c")))
        p.remove("b")
        p.add("d")  # reuses b's slot; the history must not cover it.
        assert p.C() == {"a-d", "c-d"}
        assert p.filter.remove_declaration(tid) is True
        assert p.C() == {"a-c", "a-d", "c-d"}

    def test_growth_past_sixteen_keeps_every_pair(self) -> None:
        names = [f"g{i:02d}" for i in range(40)]
        p = Pairs(*names[:10])
        p.apply(p.decl().ExcludeWithin(geometry_set=p.s(*names[:10])))
        p.add(*names[10:])
        assert len(p.filter._registered) >= 40
        assert p.C() == pairs_of(names) - pairs_of(names[:10])
        assert p.rel("g00", "g09") is PairRelationship.FILTERED
        assert p.rel("g00", "g39") is PairRelationship.UNFILTERED
        p.apply(p.excl("g05", "g39"))
        assert p.rel("g05", "g39") is PairRelationship.FILTERED
        assert len(p.C()) == 40 * 39 // 2 - 45 - 1


class TestCollisionFilterDeclarations:
    def test_apply_writes_the_base(self) -> None:
        p = Pairs("a", "b", "c")
        p.apply(p.excl("a", "b"))
        assert p.C() == {"a-c", "b-c"}
        tid = p.transient(p.decl())
        p.filter.remove_declaration(tid)
        assert p.C() == {"a-c", "b-c"}

    def test_apply_with_history_raises(self) -> None:
        p = Pairs("a", "b")
        p.transient(p.decl())
        with pytest.raises(TransientHistoryActiveError) as info:
            p.apply(p.decl())
        assert str(info.value).startswith("You cannot attempt to modify the persistent")
        assert isinstance(info.value, RuntimeError)

    def test_invariant_allow_is_rejected(self) -> None:
        p = Pairs("a", "b")
        with pytest.raises(AssertionError):
            p.apply(p.allow("a", "b"), invariant=True)

    def test_apply_transient_returns_a_new_active_filter_id(self) -> None:
        p = Pairs("a", "b")
        tid = p.transient(p.excl("a", "b"))
        assert isinstance(tid, FilterId)
        assert p.filter.is_active(tid) is True
        assert p.filter.has_transient_history() is True
        assert p.C() == set()
        assert p.filter.remove_declaration(tid) is True
        assert p.filter.remove_declaration(tid) is False
        assert p.filter.is_active(tid) is False
        assert p.filter.has_transient_history() is False
        assert p.C() == {"a-b"}

    def test_removing_a_middle_declaration_replays_the_rest(self) -> None:
        """Table 1 pattern: P1..P4 = W-g1..W-g4, the g's mutually invariant, so C ⊆ {P1..P4}."""
        p = Pairs("W", "g1", "g2", "g3", "g4")
        others = p.decl().ExcludeWithin(geometry_set=p.s("g1", "g2", "g3", "g4"))
        p.apply(others, invariant=True)
        p.apply(p.decl().ExcludeBetween(set_A=p.s("W"), set_B=p.s("g1", "g3", "g4")))
        assert p.C() == {"W-g2"}
        t1 = p.transient(p.decl().AllowBetween(set_A=p.s("W"), set_B=p.s("g3", "g4")))
        t2 = p.transient(p.decl().AllowBetween(set_A=p.s("W"), set_B=p.s("g1", "g3")))
        t3 = p.transient(p.excl("W", "g3"))
        assert p.C() == {"W-g1", "W-g2", "W-g4"}
        assert p.filter.remove_declaration(t2) is True
        # g3: t1 allows, t3 excludes -> filtered; g1: only t2 allowed it -> filtered.
        assert p.C() == {"W-g2", "W-g4"}
        assert [d.filter_id for d in p.filter._history] == [t1, t3]
        assert p.filter.remove_declaration(t3) is True
        assert p.C() == {"W-g2", "W-g3", "W-g4"}
        assert p.filter.remove_declaration(t1) is True
        assert p.C() == {"W-g2"}

    def test_later_transient_reasserting_a_pair_survives_removal_of_an_earlier_one(
        self,
    ) -> None:
        p = Pairs("a", "b")
        t1 = p.transient(p.excl("a", "b"))
        p.transient(p.excl("a", "b"))
        assert p.filter.remove_declaration(t1) is True
        assert p.rel("a", "b") is PairRelationship.FILTERED

    def test_replay_after_removal_leaves_later_geometry_unfiltered(self) -> None:
        p = Pairs("a", "b")
        p.apply(p.decl().ExcludeWithin(geometry_set=p.s("a", "b")))
        p.add("c")
        t = p.transient(p.decl().AllowWithin(geometry_set=p.s("a", "b")))
        p.add("d")
        p.filter.remove_declaration(t)
        assert p.C() == {"a-c", "a-d", "b-c", "b-d", "c-d"}

    def test_failed_resolution_leaves_leftover_rows_outside_the_base(self) -> None:
        p = Pairs("a", "b", "c")
        bad = GeometrySet(geometry_id=GeometryId.get_new_id())
        with pytest.raises(UnknownGeometryError):
            p.apply(p.excl("a", "b").ExcludeWithin(geometry_set=bad))
        assert p.C() == {"a-c", "b-c"}
        slots = {p.filter._slot_of[p.ids[n]] for n in "ab"}
        assert p.filter._leftover == slots
        assert not p.filter._base.any()
        assert p.filter.has_transient_history() is False
        assert p.filter.remove_declaration(FilterId.get_new_id()) is False
        assert p.C() == {"a-c", "b-c"}

    def test_failed_transient_leaves_no_history_entry(self) -> None:
        p = Pairs("a", "b", "c")
        bad = GeometrySet(geometry_id=GeometryId.get_new_id())
        with pytest.raises(UnknownGeometryError):
            p.transient(p.excl("a", "b").ExcludeWithin(geometry_set=bad))
        assert p.filter.has_transient_history() is False
        assert p.C() == {"a-c", "b-c"}

    def test_apply_transient_keeps_the_leftover_of_a_partial_apply(self) -> None:
        p = Pairs("a", "b", "c")
        bad = GeometrySet(geometry_id=GeometryId.get_new_id())
        with pytest.raises(UnknownGeometryError):
            p.apply(p.excl("a", "b").ExcludeWithin(geometry_set=bad))
        p.transient(p.decl())
        assert p.C() == {"a-c", "b-c"}

    def test_leftover_is_rederived_by_a_successful_removal(self) -> None:
        p = Pairs("a", "b", "c")
        bad = GeometrySet(geometry_id=GeometryId.get_new_id())
        with pytest.raises(UnknownGeometryError):
            p.apply(p.excl("a", "b").ExcludeWithin(geometry_set=bad))
        tid = p.transient(p.decl())
        assert p.filter.remove_declaration(tid) is True
        assert p.C() == {"a-b", "a-c", "b-c"}
        assert p.filter._leftover == set()

    def test_copy_is_independent_and_keeps_filter_ids(self) -> None:
        p = Pairs("a", "b", "c")
        tid = p.transient(p.excl("a", "b"))
        clone = p.filter.copy()
        assert clone.is_active(tid) is True
        assert clone.remove_declaration(tid) is True
        assert p.filter.is_active(tid) is True
        assert p.C() == {"a-c", "b-c"}
        assert len(clone.candidates()) == 3


class TestCollisionFilterRelationship:
    def test_relationship_names_each_row_of_the_table(self) -> None:
        p = Pairs("a", "b", "c", "d", "e")
        p.apply(p.excl("a", "b"), invariant=True)
        p.apply(p.excl("a", "c"))
        p.filter.set_active([p.ids["e"]], active=False)
        assert p.rel("a", "a") is PairRelationship.SELF
        assert p.rel("a", "e") is PairRelationship.INACTIVE
        assert p.rel("a", "b") is PairRelationship.INVARIANT
        assert p.rel("a", "c") is PairRelationship.FILTERED
        assert p.rel("a", "d") is PairRelationship.UNFILTERED
        assert p.filter.can_collide_with(p.ids["a"], p.ids["d"]) is True
        assert p.filter.can_collide_with(p.ids["a"], p.ids["c"]) is False

    def test_invariant_pairs_survive_allow(self) -> None:
        p = Pairs("a", "b")
        p.apply(p.excl("a", "b"), invariant=True)
        p.apply(p.allow("a", "b"))
        assert p.rel("a", "b") is PairRelationship.INVARIANT
        p.transient(p.decl().AllowWithin(geometry_set=p.s("a", "b")))
        assert p.C() == set()

    def test_inactive_wins_over_invariant(self) -> None:
        p = Pairs("a", "b")
        p.apply(p.excl("a", "b"), invariant=True)
        p.filter.set_active([p.ids["a"]], active=False)
        assert p.rel("a", "b") is PairRelationship.INACTIVE

    def test_set_active_removes_and_restores_pairs(self) -> None:
        p = Pairs("a", "b", "c")
        p.filter.set_active([p.ids["a"]], active=False)
        assert p.C() == {"b-c"}
        p.filter.set_active([p.ids["a"]], active=False)
        p.filter.set_active([p.ids["a"]], active=True)
        assert p.C() == {"a-b", "a-c", "b-c"}

    def test_set_active_is_allowed_with_history_and_survives_removal(self) -> None:
        p = Pairs("a", "b", "c")
        tid = p.transient(p.decl())
        p.filter.set_active([p.ids["a"]], active=False)
        p.filter.remove_declaration(tid)
        assert p.C() == {"b-c"}

    def test_candidates_are_ordered_by_value(self) -> None:
        p = Pairs("a", "b", "c")
        p.remove("a")
        p.add("z")  # reuses slot 0 but has the largest value
        for first, second in p.filter.candidates():
            assert first.get_value() < second.get_value()
        assert p.C() == {"b-c", "b-z", "c-z"}

    def test_fewer_than_two_live_geometries_have_no_candidates(self) -> None:
        assert Pairs().C() == set()
        assert Pairs("a").C() == set()


# --------------------------------------------------------------- declarations
class TestCollisionFilterDeclarationStatements:
    def test_statements_record_op_and_sets_in_order(self) -> None:
        g1, g2 = GeometryId.get_new_id(), GeometryId.get_new_id()
        f1 = FrameId.get_new_id()
        a, b = GeometrySet(geometry_id=g1), GeometrySet(geometry_ids=[g2], frame_ids=[f1])
        declaration = (
            CollisionFilterDeclaration()
            .ExcludeWithin(geometry_set=a)
            .AllowBetween(set_A=a, set_B=b)
            .AllowWithin(geometry_set=b)
            .ExcludeBetween(set_A=b, set_B=a)
        )
        statements = declaration.statements()
        assert isinstance(statements, tuple)
        assert [s.op for s in statements] == [
            StatementOp.kExcludeWithin,
            StatementOp.kAllowBetween,
            StatementOp.kAllowWithin,
            StatementOp.kExcludeBetween,
        ]
        assert all(isinstance(s, Statement) for s in statements)
        assert statements[0].set_A.geometry_ids() == (g1,)
        assert statements[0].set_B.geometry_ids() == ()
        assert statements[1].set_B.geometry_ids() == (g2,)
        assert statements[1].set_B.frame_ids() == (f1,)
        assert statements[2].set_A.frame_ids() == (f1,)
        assert statements[3].set_A.geometry_ids() == (g2,)
        assert statements[3].set_B.geometry_ids() == (g1,)

    def test_statements_copy_the_sets(self) -> None:
        g1, g2 = GeometryId.get_new_id(), GeometryId.get_new_id()
        s = GeometrySet(geometry_id=g1)
        declaration = CollisionFilterDeclaration().ExcludeWithin(geometry_set=s)
        s.Add(geometry_id=g2)
        recorded = declaration.statements()[0].set_A
        assert recorded is not s
        assert recorded.geometry_ids() == (g1,)
        assert s.geometry_ids() == (g1, g2)

    def test_op_properties(self) -> None:
        assert StatementOp.kExcludeBetween.filters is True
        assert StatementOp.kAllowWithin.filters is False
        assert StatementOp.kAllowBetween.pairing.value == "between"
        assert StatementOp.kExcludeWithin.pairing.value == "within"

    def test_non_set_argument_raises_type_error(self) -> None:
        with pytest.raises(TypeError) as info:
            CollisionFilterDeclaration().ExcludeWithin(geometry_set=[GeometryId.get_new_id()])  # type: ignore[arg-type]
        assert str(info.value).startswith("ExcludeWithin(): incompatible function arguments")


# ------------------------------------------------------------------ overloads
class TestDispatch:
    OVERLOADS = (
        Overload((Param("x", instance_of(int)),), lambda x: ("int", x)),
        Overload(
            (Param("names", list_of(str)), Param("flag", instance_of(bool), False)),
            lambda names, flag: ("names", names, flag),
        ),
    )

    def call(self, *args: object, **kwargs: object) -> object:
        return dispatch("pkg.Owner", "Do", self.OVERLOADS, args, kwargs)

    def test_first_matching_overload_is_called(self) -> None:
        assert self.call(3) == ("int", 3)
        assert self.call(x=4) == ("int", 4)
        assert self.call(["a"]) == ("names", ["a"], False)
        assert self.call(names=("a", "b"), flag=True) == ("names", ("a", "b"), True)

    def test_mismatch_raises_pybind11_function_text(self) -> None:
        with pytest.raises(TypeError) as info:
            self.call("nope", k=1)
        assert str(info.value) == (
            "Do(): incompatible function arguments. The following argument types are supported:\n"
            "    1. (self: pkg.Owner, x: int)\n"
            "    2. (self: pkg.Owner, names: list[str], flag: bool = False)\n"
            "\n"
            "Invoked with: 'nope', kwargs: k=1"
        )

    def test_constructor_mismatch_says_constructor(self) -> None:
        with pytest.raises(TypeError) as info:
            dispatch("pkg.Owner", "__init__", self.OVERLOADS, (1.5,), {})
        lines = str(info.value).splitlines()
        assert lines[0] == (
            "__init__(): incompatible constructor arguments. "
            "The following argument types are supported:"
        )
        assert lines[-1] == "Invoked with: 1.5"

    def test_bool_is_not_an_int_and_sets_are_not_lists(self) -> None:
        with pytest.raises(TypeError):
            self.call(True)
        with pytest.raises(TypeError):
            self.call({"a"})
        with pytest.raises(TypeError):
            self.call("ab")

    def test_argument_given_twice_does_not_bind(self) -> None:
        with pytest.raises(TypeError):
            self.call(3, x=3)


# ----------------------------------------------------------------------- math
def z_rotation(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


class TestMath:
    def test_make_z_rotation_is_the_standard_matrix(self) -> None:
        for theta in (0.0, 0.3, math.pi / 2, -2.0):
            assert np.allclose(RotationMatrix.MakeZRotation(theta).matrix(), z_rotation(theta))
        assert np.allclose(
            RotationMatrix.MakeZRotation(math.pi / 2).matrix(),
            [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
        )

    def test_make_x_and_y_rotations_are_the_standard_matrices(self) -> None:
        c, s = math.cos(0.7), math.sin(0.7)
        assert np.allclose(
            RotationMatrix.MakeXRotation(0.7).matrix(),
            np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]),
        )
        assert np.allclose(
            RotationMatrix.MakeYRotation(0.7).matrix(),
            np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]),
        )

    def test_roll_pitch_yaw_composes_z_y_x(self) -> None:
        R = RollPitchYaw(0.1, 0.2, 0.3).ToRotationMatrix().matrix()
        expected = (
            RotationMatrix.MakeZRotation(0.3).matrix()
            @ RotationMatrix.MakeYRotation(0.2).matrix()
            @ RotationMatrix.MakeXRotation(0.1).matrix()
        )
        assert np.allclose(R, expected)

    def test_rigid_transform_holds_translation_and_rotation(self) -> None:
        X = RigidTransform(R=RotationMatrix.MakeZRotation(0.5), p=[1.0, 2.0, 3.0])
        assert np.allclose(X.translation(), [1.0, 2.0, 3.0])
        assert np.allclose(X.rotation().matrix(), z_rotation(0.5))
        M = X.GetAsMatrix4()
        assert np.allclose(M[:3, :3], z_rotation(0.5))
        assert np.allclose(M[:3, 3], [1.0, 2.0, 3.0])
        assert np.allclose(M[3], [0.0, 0.0, 0.0, 1.0])

    def test_multiply_is_the_matrix_product(self) -> None:
        X = RigidTransform(R=RotationMatrix.MakeZRotation(0.5), p=[1.0, 2.0, 3.0])
        Y = RigidTransform(R=RotationMatrix.MakeXRotation(-1.1), p=[-4.0, 0.5, 2.0])
        assert np.allclose(X.multiply(Y).GetAsMatrix4(), X.GetAsMatrix4() @ Y.GetAsMatrix4())
        assert np.allclose((X @ Y).GetAsMatrix4(), X.GetAsMatrix4() @ Y.GetAsMatrix4())

    def test_inverse_round_trips_to_identity(self) -> None:
        X = RigidTransform(R=RollPitchYaw(0.4, -0.2, 1.3).ToRotationMatrix(), p=[1.0, -2.0, 0.5])
        assert np.allclose(X.inverse().multiply(X).GetAsMatrix4(), np.eye(4))
        assert np.allclose(X.multiply(X.inverse()).GetAsMatrix4(), np.eye(4))
        assert np.allclose(X.inverse().inverse().GetAsMatrix4(), X.GetAsMatrix4())
        assert np.allclose(X.inverse().translation(), -(X.rotation().matrix().T @ [1.0, -2.0, 0.5]))

    def test_identity_and_copies(self) -> None:
        assert np.allclose(RigidTransform().GetAsMatrix4(), np.eye(4))
        X = RigidTransform(p=[1.0, 2.0, 3.0])
        copy = RigidTransform(X)
        copy.set_translation(np.zeros(3))
        assert np.allclose(X.translation(), [1.0, 2.0, 3.0])

    def test_rigid_transform_prints_as_pydrake(self) -> None:
        assert repr(RigidTransform(p=[1, 2, 3])) == (
            "RigidTransform(\n"
            "  R=RotationMatrix([\n"
            "    [1.0, 0.0, 0.0],\n"
            "    [0.0, 1.0, 0.0],\n"
            "    [0.0, 0.0, 1.0],\n"
            "  ]),\n"
            "  p=[1.0, 2.0, 3.0],\n"
            ")"
        )


# --------------------------------------------------------------------- shapes
class TestShapes:
    """Strings measured on pydrake 1.51.1."""

    def test_shapes_print_as_pydrake(self) -> None:
        assert repr(Sphere(radius=1)) == "Sphere(radius=1)"
        assert repr(Sphere(radius=0.1)) == "Sphere(radius=0.1)"
        assert repr(Box(width=1, depth=2, height=3)) == "Box(width=1, depth=2, height=3)"
        assert repr(Box(0.5, 0.25, 1e-3)) == "Box(width=0.5, depth=0.25, height=0.001)"
        assert repr(Cylinder(radius=0.5, length=2)) == "Cylinder(radius=0.5, length=2)"
        assert repr(Capsule(radius=0.5, length=2)) == "Capsule(radius=0.5, length=2)"
        assert repr(Ellipsoid(a=1, b=2, c=3)) == "Ellipsoid(a=1, b=2, c=3)"

    def test_shapes_print_full_precision_as_pydrake(self) -> None:
        assert repr(Sphere(radius=1 / 3)) == "Sphere(radius=0.3333333333333333)"
        assert repr(Sphere(radius=1234567.0)) == "Sphere(radius=1234567)"

    def test_shape_accessors_return_the_measures(self) -> None:
        box = Box(width=1, depth=2, height=3)
        assert (box.width(), box.depth(), box.height()) == (1.0, 2.0, 3.0)
        assert np.allclose(box.size(), [1.0, 2.0, 3.0])
        assert Sphere(radius=0.25).radius() == 0.25
