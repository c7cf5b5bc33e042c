"""The model parsing subset of ``pydrake.multibody.parsing``, reimplemented.

``Parser`` reads URDF, SDFormat and model directives (``.dmd.yaml``) into a
MultibodyPlant, with the names, collision filter groups and error messages of
Drake 1.51.1 (measured on pydrake). ``PackageMap`` resolves ``package://``
URIs; ``CollisionFilterGroups`` reports a parse's groups. The model-directive
structs (``ModelDirectives``, ``AddModel``, ...) and functions
(``LoadModelDirectives``, ``ProcessModelDirectives``, ...) are pydrake's.
"""

from __future__ import annotations

from reimpl.multibody.parsing._collision_filter_groups import CollisionFilterGroups
from reimpl.multibody.parsing._directive_structs import (
    AddCollisionFilterGroup,
    AddDirectives,
    AddFrame,
    AddModel,
    AddModelInstance,
    AddWeld,
    ModelDirective,
    ModelDirectives,
)
from reimpl.multibody.parsing._model_directives import (
    FlattenModelDirectives,
    GetScopedFrameByName,
    GetScopedFrameByNameMaybe,
    LoadModelDirectives,
    LoadModelDirectivesFromString,
    ModelInstanceInfo,
    ProcessModelDirectives,
)
from reimpl.multibody.parsing._package_map import PackageMap
from reimpl.multibody.parsing._parser import Parser

__all__ = [
    "AddCollisionFilterGroup",
    "AddDirectives",
    "AddFrame",
    "AddModel",
    "AddModelInstance",
    "AddWeld",
    "CollisionFilterGroups",
    "FlattenModelDirectives",
    "GetScopedFrameByName",
    "GetScopedFrameByNameMaybe",
    "LoadModelDirectives",
    "LoadModelDirectivesFromString",
    "ModelDirective",
    "ModelDirectives",
    "ModelInstanceInfo",
    "PackageMap",
    "Parser",
    "ProcessModelDirectives",
]
