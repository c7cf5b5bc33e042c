# Ported from Drake: geometry/test/collision_filter_declaration_test.cc
# (https://github.com/RobotLocomotion/drake, at v1.51.1), re-expressed through the public API
# (statements observed by what they filter) as pytest functions that run unchanged on
# pydrake and on reimpl. Expected values are upstream's.
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
"""Upstream CollisionFilterDeclaration tests, on pydrake and on reimpl.

Drake's test reads a declaration's statements through a friend class; pydrake binds no
view of them. Here a declaration is observed by what it does: it is applied to a scene of
four proximity spheres g0..g3, each on its own dynamic frame f0..f3, with
``set_A = GeometrySet([g0, g1])`` (geometry ids) and ``set_B = GeometrySet([f2, f3])``
(frame ids), and the filtered pairs are read back with ``CollisionFiltered``. A statement
whose operation or sets were encoded wrongly filters other pairs.
"""

from __future__ import annotations

import copy
import pickle
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.geometry_support import Scene, all_pairs, filtered_pairs, pair


@dataclass
class Four:
    scene: Scene
    geometries: list[Any]
    set_A: Any
    set_B: Any

    def apply(self, *declarations: Any) -> set[frozenset[Any]]:
        """Applies the declarations in order to a fresh context; its filtered pairs."""
        context = self.scene.context()
        manager = self.scene.scene_graph.collision_filter_manager(context)
        for declaration in declarations:
            manager.Apply(declaration)
        return filtered_pairs(self.scene.context_inspector(context), self.geometries)

    def all_filtered(self) -> Any:
        """A declaration that filters every pair of g0..g3."""
        return self.scene.g.CollisionFilterDeclaration().ExcludeWithin(
            self.scene.g.GeometrySet(geometry_ids=self.geometries)
        )


@pytest.fixture
def four(drake: ModuleType) -> Four:
    scene = Scene(drake)
    g = scene.spheres_on_own_frames(4)
    GeometrySet = drake.geometry.GeometrySet
    return Four(
        scene,
        g,
        GeometrySet(geometry_ids=[g[0], g[1]]),
        GeometrySet(frame_ids=[scene.frames[2], scene.frames[3]]),
    )


def test_a_default_declaration_has_no_statements(drake: ModuleType, four: Four) -> None:
    """DefaultConstructor: no statements, so applying it filters nothing."""
    assert four.apply(drake.geometry.CollisionFilterDeclaration()) == set()


def test_allow_between_encodes_its_operation_and_both_sets(drake: ModuleType, four: Four) -> None:
    """AllowBetween(set_A, set_B): only the pairs across the two sets are allowed again."""
    g = four.geometries
    declaration = drake.geometry.CollisionFilterDeclaration()
    declaration.AllowBetween(set_A=four.set_A, set_B=four.set_B)
    assert four.apply(four.all_filtered(), declaration) == {pair(g[0], g[1]), pair(g[2], g[3])}


def test_allow_within_encodes_its_operation_and_one_set(drake: ModuleType, four: Four) -> None:
    """AllowWithin(set): only the pairs inside the set are allowed again (set_B is empty)."""
    g = four.geometries
    everything = all_pairs(g)
    for geometry_set, inside in ((four.set_A, pair(g[0], g[1])), (four.set_B, pair(g[2], g[3]))):
        declaration = drake.geometry.CollisionFilterDeclaration()
        declaration.AllowWithin(geometry_set=geometry_set)
        assert four.apply(four.all_filtered(), declaration) == everything - {inside}


def test_exclude_between_encodes_its_operation_and_both_sets(drake: ModuleType, four: Four) -> None:
    """ExcludeBetween(set_A, set_B): exactly the pairs across the two sets are filtered."""
    g = four.geometries
    declaration = drake.geometry.CollisionFilterDeclaration()
    declaration.ExcludeBetween(set_A=four.set_A, set_B=four.set_B)
    assert four.apply(declaration) == {pair(a, b) for a in g[:2] for b in g[2:]}


def test_exclude_within_encodes_its_operation_and_one_set(drake: ModuleType, four: Four) -> None:
    """ExcludeWithin(set): exactly the pairs inside the set are filtered."""
    g = four.geometries
    for geometry_set, inside in ((four.set_A, pair(g[0], g[1])), (four.set_B, pair(g[2], g[3]))):
        declaration = drake.geometry.CollisionFilterDeclaration()
        declaration.ExcludeWithin(geometry_set=geometry_set)
        assert four.apply(declaration) == {inside}


def test_every_statement_method_returns_its_declaration(drake: ModuleType) -> None:
    """ChainingStatements: each statement method returns the declaration itself.

    C++ compares addresses; pydrake returns the same Python object (``is``).
    """
    g = drake.geometry
    set_A = g.GeometrySet(geometry_ids=[g.GeometryId.get_new_id(), g.GeometryId.get_new_id()])
    declaration = g.CollisionFilterDeclaration()
    assert declaration.AllowBetween(set_A=set_A, set_B=set_A) is declaration
    assert declaration.AllowWithin(geometry_set=set_A) is declaration
    assert declaration.ExcludeBetween(set_A=set_A, set_B=set_A) is declaration
    assert declaration.ExcludeWithin(geometry_set=set_A) is declaration


def test_statements_are_kept_in_the_order_given(drake: ModuleType, four: Four) -> None:
    """StatementOrder: each statement method appends, leaving earlier statements alone.

    C++ copies a one-statement declaration and checks that the second statement is
    appended after the first; pydrake cannot copy a declaration (``copy.copy`` raises
    TypeError), so each case builds its declaration afresh. The observable consequence
    of order: the two-statement declaration filters what its statements applied one
    after the other filter, and an Exclude then an Allow of the same set differs from
    the Allow then the Exclude.
    """
    g = drake.geometry
    gs = four.geometries
    set_1 = g.GeometrySet(geometry_ids=[gs[0], gs[1]])
    set_2 = g.GeometrySet(geometry_ids=[gs[2], gs[3]])
    base_pair = pair(gs[0], gs[1])

    def base() -> Any:
        return g.CollisionFilterDeclaration().ExcludeWithin(geometry_set=set_1)

    assert four.apply(base()) == {base_pair}
    cases = {
        "AllowBetween": (lambda d: d.AllowBetween(set_A=set_2, set_B=set_1), set()),
        "AllowWithin": (lambda d: d.AllowWithin(geometry_set=set_2), set()),
        "ExcludeBetween": (
            lambda d: d.ExcludeBetween(set_A=set_2, set_B=set_1),
            {pair(a, b) for a in gs[:2] for b in gs[2:]},
        ),
        "ExcludeWithin": (lambda d: d.ExcludeWithin(geometry_set=set_2), {pair(gs[2], gs[3])}),
    }
    for name, (append, added) in cases.items():
        declaration = append(base())
        alone = append(g.CollisionFilterDeclaration())
        assert four.apply(declaration) == {base_pair} | added, name
        assert four.apply(base(), alone) == {base_pair} | added, name

    exclude_then_allow = g.CollisionFilterDeclaration().ExcludeWithin(geometry_set=set_1)
    exclude_then_allow.AllowWithin(geometry_set=set_1)
    allow_then_exclude = g.CollisionFilterDeclaration().AllowWithin(geometry_set=set_1)
    allow_then_exclude.ExcludeWithin(geometry_set=set_1)
    assert four.apply(exclude_then_allow) == set()
    assert four.apply(allow_then_exclude) == {base_pair}


def test_a_declaration_cannot_be_copied(drake: ModuleType) -> None:
    """pydrake binds no copy of a CollisionFilterDeclaration (not upstream: the reason
    StatementOrder is rebuilt above). Measured on pydrake 1.51.1 and 1.58.0."""
    message = f"cannot pickle '{drake.__name__}.geometry.CollisionFilterDeclaration' object"
    for duplicate in (copy.copy, copy.deepcopy, pickle.dumps):
        with pytest.raises(TypeError, match=f"^{message}$"):
            duplicate(drake.geometry.CollisionFilterDeclaration())
