"""Parser: adds the models of URDF, SDFormat and model-directive text to a plant.

Each ``AddModels*`` call is one parse with its own collision filter group
resolver, resolved (filters applied) when the call's models are all added;
``GetCollisionFilterGroups()`` accumulates the reports of successful calls.
A failed call raises RuntimeError with Drake's message and leaves what it had
added in the plant, as Drake does (measured on pydrake 1.51.1).
"""

from __future__ import annotations

import os
from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.geometry import SceneGraph
from reimpl.multibody.parsing._collision_filter_group_resolver import (
    CollisionFilterGroupResolver,
)
from reimpl.multibody.parsing._collision_filter_groups import CollisionFilterGroups, NameGroups
from reimpl.multibody.parsing._diagnostics import ModelParseError, literal_string_name
from reimpl.multibody.parsing._directives import process_directives, read_directives
from reimpl.multibody.parsing._instanced_name import InstancedName, order, spelled
from reimpl.multibody.parsing._package_map import PackageMap, resolve_uri
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext, Reader
from reimpl.multibody.parsing._sdf import read_sdf
from reimpl.multibody.parsing._urdf import read_urdf
from reimpl.multibody.plant import MultibodyPlant
from reimpl.systems.framework import DiagramBuilder

__all__ = ["Parser"]

_OWNER = "reimpl.multibody.parsing.Parser"

#: file type (a file name's suffix, without the dot) -> reader
_READERS: dict[str, Reader] = {"urdf": read_urdf, "sdf": read_sdf, "dmd.yaml": read_directives}

#: file type -> Drake's message for a file that is not there
_MISSING_FILE = {
    "urdf": "{path}:0: error: Failed to parse XML file: XML_ERROR_FILE_NOT_FOUND",
    "sdf": "error: Error finding file [{path}].",
    "dmd.yaml": "No such file {path} during LoadModelDirectives",
}


def _file_type(name: str) -> str:
    lowered = name.lower()
    for file_type in _READERS:
        if lowered.endswith(f".{file_type}"):
            return file_type
    raise ModelParseError(
        f"error: The file '{name}' is not a recognized type. Known types are: .urdf, .sdf, "
        ".xml (Mujoco), .dmd.yaml, .obj"
    )


def _read_file(context: ParseContext, path: str, model_name: str | None, scope: str) -> list[Any]:
    """Adds the models of the file at ``path`` (its type from its name)."""
    file_type = _file_type(path)
    if not os.path.isfile(path):
        raise ModelParseError(_MISSING_FILE[file_type].format(path=path))
    with open(path, encoding="utf-8") as stream:
        text = stream.read()
    label = "/" + os.path.abspath(path) if file_type == "sdf" else None
    source = ModelSource(text, file_type, path, label)
    return _READERS[file_type](context, source, model_name, scope)


class Parser:
    """Adds models to a MultibodyPlant (drake/multibody/parsing/parser.h)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._builder: DiagramBuilder | None = None
        self._package_map = PackageMap()
        self._auto_renaming = False
        self._strict = False
        self._groups: NameGroups[InstancedName] = NameGroups(order)
        plant = Param("plant", instance_of(MultibodyPlant))
        scene_graph = Param("scene_graph", instance_of(SceneGraph), None)
        prefix = Param("model_name_prefix", instance_of(str))
        dispatch(
            _OWNER,
            "__init__",
            (
                Overload((plant, scene_graph, Param(prefix.name, prefix.check, "")), self._init),
                Overload((plant, prefix), self._init),
                Overload(
                    (
                        Param("builder", instance_of(DiagramBuilder)),
                        Param("plant", instance_of(MultibodyPlant), None),
                        scene_graph,
                        Param(prefix.name, prefix.check, ""),
                    ),
                    self._init_from_builder,
                ),
            ),
            args,
            kwargs,
        )

    def _init(
        self, plant: MultibodyPlant, model_name_prefix: str, scene_graph: SceneGraph | None = None
    ) -> None:
        if scene_graph is not None and not plant.geometry_source_is_registered():
            plant.RegisterAsSourceForSceneGraph(scene_graph)
        self._plant = plant
        self._prefix = model_name_prefix

    def _init_from_builder(
        self,
        builder: DiagramBuilder,
        plant: MultibodyPlant | None,
        scene_graph: SceneGraph | None,
        model_name_prefix: str,
    ) -> None:
        systems = builder.GetSystems()
        if plant is None:
            named = [s for s in systems if s.get_name() == "plant"]
            if not named or not isinstance(named[0], MultibodyPlant):
                names = ", ".join(s.get_name() for s in systems)
                raise RuntimeError(
                    "DiagramBuilder does not contain a subsystem named plant. Valid subsystems "
                    f"are {names}."
                )
            plant = named[0]
        elif not any(s is plant for s in systems):
            raise RuntimeError("The provided plant must be one of the systems in the builder")
        self._builder = builder
        self._init(plant, model_name_prefix, scene_graph)

    # ---------------------------------------------------------- accessors
    def plant(self) -> MultibodyPlant:
        return self._plant

    def scene_graph(self) -> SceneGraph | None:
        # N.B. pydrake returns the SceneGraph the plant is registered with.
        scene_graph: SceneGraph | None = getattr(self._plant, "_scene_graph", None)
        return scene_graph

    def builder(self) -> DiagramBuilder | None:
        return self._builder

    def package_map(self) -> PackageMap:
        return self._package_map

    def SetAutoRenaming(self, value: bool) -> None:
        """With auto-renaming, a taken model name gets the first free ``_1``, ``_2``, ..."""
        self._auto_renaming = bool(value)

    def GetAutoRenaming(self) -> bool:
        return self._auto_renaming

    def SetStrictParsing(self) -> None:
        """Makes every warning an error."""
        self._strict = True

    def GetCollisionFilterGroups(self) -> CollisionFilterGroups:
        """The groups and pairs of every parse so far, named with the model
        instances' current names (see _instanced_name)."""
        plant = self._plant
        return CollisionFilterGroups._from(
            self._groups.convert(lambda name: spelled(plant, name), str)
        )

    # ------------------------------------------------------------ parsing
    def AddModels(self, *args: Any, **kwargs: Any) -> list[Any]:
        """``AddModels(file_name)``, ``(url=)`` or ``(file_contents=, file_type=)``."""
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "AddModels",
            (
                Overload((Param("file_name", _is_path),), self._add_file),
                Overload((Param("url", instance_of(str)),), self.AddModelsFromUrl),
                Overload(
                    (
                        Param("file_contents", instance_of(str)),
                        Param("file_type", instance_of(str)),
                    ),
                    self.AddModelsFromString,
                ),
            ),
            args,
            kwargs,
        )

    def AddModelsFromUrl(self, url: str) -> list[Any]:
        try:
            path = resolve_uri(self._package_map, url, root_dir=None)
        except RuntimeError as exc:
            raise ModelParseError(f"error: {exc}") from None
        return self._add_file(path)

    def AddModelsFromString(self, file_contents: str, file_type: str) -> list[Any]:
        normalized = file_type.lower().removeprefix(".")
        if normalized not in _READERS:
            _file_type(literal_string_name(file_type))
        source = ModelSource(file_contents, normalized)
        return self._parse(lambda c: _READERS[normalized](c, source, None, self._prefix))

    def _add_file(self, file_name: str | os.PathLike[str]) -> list[Any]:
        path = os.fspath(file_name)
        return self._parse(lambda c: _read_file(c, path, None, self._prefix))

    def _process_directives(self, directives: Any) -> list[Any]:
        """ProcessModelDirectives: one parse of ``directives`` at global scope."""
        return self._parse(lambda context: process_directives(context, directives, ""))

    def _parse(self, read: Any) -> list[Any]:
        context = ParseContext(
            plant=self._plant,
            package_map=self._package_map,
            resolver=CollisionFilterGroupResolver(self._plant),
            auto_renaming=self._auto_renaming,
            strict=self._strict,
            read_file=_read_file,
        )
        instances: list[Any] = read(context)
        self._groups.merge(context.resolver.resolve())
        return instances


def _is_path(value: object) -> bool:
    return isinstance(value, str | os.PathLike)
