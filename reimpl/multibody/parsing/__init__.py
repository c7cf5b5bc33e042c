"""The model parsing subset of ``pydrake.multibody.parsing``, reimplemented.

``Parser`` reads URDF, SDFormat, MuJoCo XML, model directives (``.dmd.yaml``)
and ``.obj`` meshes (one-body models) into a MultibodyPlant, with the names,
collision filter groups and error messages of Drake 1.51.1 (measured on
pydrake). ``PackageMap`` resolves ``package://``
URIs; ``CollisionFilterGroups`` reports a parse's groups. The model-directive
structs (``ModelDirectives``, ``AddModel``, ...) and functions
(``LoadModelDirectives``, ``ProcessModelDirectives``, ...) are pydrake's.

What is read, and what is not:

* URDF, SDFormat (with libsdformat's own checks, includes of files and model
  directories, merge-includes and URDF through the interface API) and model
  directives, element by element in Drake's order of checks, so that the first
  error of a file with several is Drake's, with its line.
* Mesh files are named, not read, except where their contents decide a result
  Drake reports: a mesh in the proximity role has its convex hull made at
  registration, so reimpl reads a collision ``.obj``'s vertex lines (and which
  face, line and point elements it has), a ``.vtk``'s points, cell sizes and
  types, and whether a ``.gltf`` exists, to raise Drake's hull errors
  (``reimpl/geometry/_proximity_mesh.py``); a visual mesh is never read, and
  neither is a texture.
* MuJoCo XML (``_mjcf``): the subset Drake reads (compiler, option, defaults
  and classes, assets, bodies, geoms, joints, inertials, actuators, contact
  pairs and excludes, equality connects, ``<include>``), with Drake's warnings
  for what it ignores; the few parts reimpl leaves out raise a reimpl error
  that says so (see ``_mjcf``). ``.obj`` model files (``_mesh_model``): a body
  with the mesh as collision and visual geometry, its mass from the mesh at
  1000 kg/m³.
* Deformable bodies are not read: the only measured answer reimpl gives is
  Drake's refusal on a continuous plant.
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
