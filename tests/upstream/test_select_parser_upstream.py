# Ported from Drake: multibody/parsing/test/detail_select_parser_test.cc at v1.51.1
# (https://github.com/RobotLocomotion/drake), re-expressed as pytest functions that run
# unchanged on pydrake and on reimpl through the public Parser API (the internal
# SelectParser is not bound: a file's extension selects its parser inside
# Parser.AddModels / AddModelsFromUrl).
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
"""Upstream SelectParserTest cases, through ``Parser.AddModels``.

Upstream calls ``SelectParser(policy, "foo.URDF")`` and checks that no error is
emitted; here a file of each spelling is parsed, from a file and (with the spelling
as ``file_type``) from a string, and the model it adds is the one in the text. The
unknown type's error, upstream matched as ``.*not a recognized type.*``, is pydrake's
full message (measured on 1.51.1 and 1.58.0).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.parsing_support import names_of

_TEXT = {
    "urdf": '<robot name="urdf_model"><link name="link"/></robot>',
    "sdf": '<sdf version="1.7"><model name="sdf_model"><link name="link"/></model></sdf>',
    "xml": (
        '<mujoco model="mujoco_model"><worldbody><body name="body">'
        '<geom type="sphere" size="1"/></body></worldbody></mujoco>'
    ),
}
_KNOWN_TYPES = "Known types are: .urdf, .sdf, .xml (Mujoco), .dmd.yaml, .obj"


@pytest.mark.parametrize(
    "extension", ["URDF", "Urdf", "urdf", "SDF", "Sdf", "sdf", "XML", "Xml", "xml"]
)
def test_an_extension_selects_its_parser_in_any_case(
    drake: ModuleType, tmp_path: Path, extension: str
) -> None:
    """CaseInsensitiveMatch."""
    text = _TEXT[extension.lower()]
    expected = [f"{extension.lower().replace('xml', 'mujoco')}_model"]
    path = tmp_path / f"foo.{extension}"
    path.write_text(text)
    plant = drake.multibody.plant.MultibodyPlant(time_step=0.0)
    added = drake.multibody.parsing.Parser(plant=plant).AddModels(file_name=str(path))
    assert names_of(plant, added) == expected
    plant = drake.multibody.plant.MultibodyPlant(time_step=0.0)
    added = drake.multibody.parsing.Parser(plant=plant).AddModels(
        file_contents=text, file_type=extension
    )
    assert names_of(plant, added) == expected


@pytest.mark.parametrize("source", ["file", "url", "contents"])
def test_an_unknown_file_type_is_an_error_and_adds_nothing(
    drake: ModuleType, tmp_path: Path, source: str
) -> None:
    """UnknownFileType: the error, and (upstream: the parser it selects ignores its
    input) no model instance is added."""
    path = tmp_path / "nope"
    path.write_text("")
    plant = drake.multibody.plant.MultibodyPlant(time_step=0.0)
    parser = drake.multibody.parsing.Parser(plant=plant)
    before = plant.num_model_instances()
    parse: Callable[[], Any] = {
        "file": lambda: parser.AddModels(file_name=str(path)),
        "url": lambda: parser.AddModelsFromUrl(url=f"file://{path}"),
        "contents": lambda: parser.AddModels(file_contents="", file_type="nope"),
    }[source]
    with pytest.raises(RuntimeError) as error:
        parse()
    # A string's "file name" is <literal-string> with the type as its extension.
    named = "<literal-string>.nope" if source == "contents" else str(path)
    assert str(error.value) == f"error: The file '{named}' is not a recognized type. {_KNOWN_TYPES}"
    assert plant.num_model_instances() == before
