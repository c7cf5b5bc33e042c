# Ported from Drake: multibody/parsing/test/detail_make_model_name_test.cc at v1.51.1
# (https://github.com/RobotLocomotion/drake), re-expressed as pytest functions that run
# unchanged on pydrake and on reimpl through the public Parser API (the internal
# MakeModelName is not bound: it names the model instance a Parser adds).
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
"""Upstream MakeModelNameTest cases, through the names of the instances a Parser adds.

Upstream's ``MakeModelName(name, prefix, workspace)`` is observed here as the name of
the model instance that parsing a URDF robot called ``name`` adds, with the Parser's
``model_name_prefix`` as the prefix and ``SetAutoRenaming`` as
``options.enable_auto_renaming``.
"""

from __future__ import annotations

from types import ModuleType
from typing import Any

import pytest


def _urdf(name: str) -> str:
    return f'<robot name="{name}"><link name="link"/></robot>'


class Naming:
    """A plant and a way to ask which name a parsed model would get."""

    def __init__(self, drake: ModuleType) -> None:
        self.drake = drake
        self.plant = drake.multibody.plant.MultibodyPlant(time_step=0.0)

    def parser(self, prefix: str | None, auto_renaming: bool) -> Any:
        parsing = self.drake.multibody.parsing
        if prefix is None:
            parser = parsing.Parser(plant=self.plant)
        else:
            parser = parsing.Parser(plant=self.plant, model_name_prefix=prefix)
        parser.SetAutoRenaming(value=auto_renaming)
        return parser

    def model_name(self, name: str, prefix: str | None = None, *, auto_renaming: bool) -> str:
        """The name the model instance of robot ``name`` gets. Upstream's MakeModelName
        only computes it; parsing adds the instance, so callers below add, as upstream's
        AddModelInstance does, each name they depend on explicitly."""
        parser = self.parser(prefix, auto_renaming)
        (added,) = parser.AddModels(file_contents=_urdf(name), file_type="urdf")
        return str(self.plant.GetModelInstanceName(model_instance=added))


def test_a_name_without_prefix_is_kept(drake: ModuleType) -> None:
    """Identity."""
    assert Naming(drake).model_name("robot", auto_renaming=False) == "robot"


def test_a_prefix_scopes_the_name(drake: ModuleType) -> None:
    """Prefix."""
    assert Naming(drake).model_name("robot", "prefix", auto_renaming=False) == "prefix::robot"


def test_auto_renaming_subscripts_are_compact_and_start_at_one(drake: ModuleType) -> None:
    """AutoRename: each parse below adds the instance upstream adds with AddModelInstance
    before its next MakeModelName call."""
    naming = Naming(drake)
    naming.plant.AddModelInstance(name="robot")
    assert naming.model_name("robot", auto_renaming=True) == "robot_1"
    assert naming.model_name("robot", auto_renaming=True) == "robot_2"
    # Subscripts of different base names are independent.
    naming.plant.AddModelInstance(name="thing")
    assert naming.model_name("thing", auto_renaming=True) == "thing_1"
    assert naming.model_name("thing", auto_renaming=True) == "thing_2"


def test_auto_renaming_subscripts_the_prefixed_name(drake: ModuleType) -> None:
    """PrefixAndAutoRename."""
    naming = Naming(drake)
    naming.plant.AddModelInstance(name="prefix::robot")
    assert naming.model_name("robot", "prefix", auto_renaming=True) == "prefix::robot_1"


def test_without_auto_renaming_a_taken_name_is_an_error(drake: ModuleType) -> None:
    """The counterpart of AutoRename with ``enable_auto_renaming`` off (Drake's default):
    MakeModelName returns the taken name and adding it fails (pydrake 1.51.1 and 1.58.0)."""
    naming = Naming(drake)
    naming.plant.AddModelInstance(name="robot")
    with pytest.raises(RuntimeError) as error:
        naming.model_name("robot", auto_renaming=False)
    assert str(error.value) == (
        "This model already contains a model instance named 'robot'. "
        "Model instance names must be unique within a given model."
    )
