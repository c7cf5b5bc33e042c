"""Parser: adds the models of URDF, SDFormat and model-directive text to a plant.

Each ``AddModels*`` call is one parse with its own collision filter group
resolver, resolved (filters applied) when the call's models are all added;
``GetCollisionFilterGroups()`` accumulates every parse's groups by model
instance index (see _instanced_name). A failed call raises with Drake's
message and leaves what it had added in the plant, as Drake does.

The order of the checks is Drake 1.51.1's (parser.cc, measured on pydrake):

1. the file type, from the name's suffix, case-insensitively (``.urdf``,
   ``.sdf``, ``.xml``, ``.dmd.yaml``, ``.obj``; model text is named
   ``<literal-string>.<file_type>``): ``error: The file '...' is not a
   recognized type. ...``;
2. a finalized plant registered with a SceneGraph: SystemExit (Drake's
   ``GetMutableSceneGraphPreFinalize`` DRAKE_DEMAND), even for an empty parse;
3. the reader: a finalized plant is the reader's DRAKE_THROW_UNLESS
   (SystemExit), then a missing file is the reader's own message, naming the
   file by its absolute path (``/cwd/a.urdf:0: error: ...``, ``error: Error
   finding file [/cwd/a.sdf].``); a ``.dmd.yaml`` keeps the name as given.

MuJoCo ``.xml`` files and text are read by ``_mjcf`` (a subset, as Drake's
parser reads one), ``.obj`` files as one-body models by ``_mesh_model``.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from typing import Any

from reimpl._overload import Overload, Param, dispatch
from reimpl._release import release
from reimpl.common._drake_demand import failed_demand
from reimpl.geometry import SceneGraph
from reimpl.multibody.parsing._binding import binds, is_path, is_str
from reimpl.multibody.parsing._collision_filter_group_resolver import (
    CollisionFilterGroupResolver,
)
from reimpl.multibody.parsing._collision_filter_groups import CollisionFilterGroups, NameGroups
from reimpl.multibody.parsing._diagnostics import (
    Diagnostics,
    ModelParseError,
    literal_string_name,
)
from reimpl.multibody.parsing._directives import process_directives, read_directives
from reimpl.multibody.parsing._instanced_name import InstancedName, order, spelled
from reimpl.multibody.parsing._mesh_model import read_obj_model
from reimpl.multibody.parsing._mjcf import read_mujoco
from reimpl.multibody.parsing._package_map import PackageMap, UriError, resolve_uri
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext, Reader
from reimpl.multibody.parsing._sdf import read_sdf
from reimpl.multibody.parsing._urdf import read_urdf
from reimpl.multibody.plant import MultibodyPlant
from reimpl.systems.framework import DiagramBuilder

__all__ = ["Parser"]

_OWNER = "reimpl.multibody.parsing.Parser"


@dataclass(frozen=True)
class _FileType:
    """How Drake reads one kind of model file."""

    reader: Reader
    #: the message for a file that is not there (or is a folder: ``{error}``)
    missing: str
    #: the reader's DRAKE_THROW_UNLESS(!plant->is_finalized()) (an id of demand_lines.json)
    finalized: str | None
    #: the message for model text of this type, where Drake refuses it
    text_error: str | None = None


_FINALIZED_URDF = "AddOrMergeModelFromUrdf.finalized"
_FINALIZED_SDF = "AddModelsFromSdf.finalized"
_FINALIZED_MJCF = "AddOrMergeModelFromMujocoXml.finalized"
_FINALIZED_MESH = "AddModelFromMesh.finalized"

#: file type (a name's suffix) -> how it is read, in Drake's SelectParser order
_FILE_TYPES: dict[str, _FileType] = {
    "urdf": _FileType(
        read_urdf, "{absolute}:0: error: Failed to parse XML file: {error}", _FINALIZED_URDF
    ),
    "sdf": _FileType(read_sdf, "error: Error finding file [{absolute}].", _FINALIZED_SDF),
    "xml": _FileType(
        read_mujoco,
        "{absolute}:0: error: Failed to parse XML file {path}:\n{error}",
        _FINALIZED_MJCF,
    ),
    "dmd.yaml": _FileType(read_directives, "No such file {path} during LoadModelDirectives", None),
    "obj": _FileType(
        read_obj_model,
        "error: Cannot open file '{absolute}'",
        _FINALIZED_MESH,
        text_error=(
            "Parser does not yet support adding models using in-memory OBJ data. The OBJ "
            "data must be referenced as a file."
        ),
    ),
}


#: The types the release's SelectParser knows: ``.obj`` since 1.14 (release fact
#: obj-model-files-since-1.14; up to 1.13 it is an unknown type, measured on 1.13.0).
_KNOWN_TYPES = tuple(
    t for t in _FILE_TYPES if t != "obj" or release.has("obj-model-files-since-1.14")
)


def _file_type(name: str) -> str:
    """Drake's SelectParser: the type whose suffix ``name`` ends with (any case)."""
    lowered = name.lower()
    for file_type in _KNOWN_TYPES:
        if lowered.endswith(f".{file_type}"):
            return file_type
    known = ".urdf, .sdf, .xml (Mujoco), .dmd.yaml" + (", .obj" if "obj" in _KNOWN_TYPES else "")
    raise ModelParseError(
        f"error: The file '{name}' is not a recognized type. Known types are: {known}"
    )


def _absolute(path: str) -> str:
    """``std::filesystem::absolute``: the working folder prefixed, nothing normalized."""
    return path if os.path.isabs(path) else os.path.join(os.getcwd(), path)


def _check_reader(context: ParseContext, file_type: str) -> None:
    """The reader's own DRAKE_THROW_UNLESS(!plant->is_finalized())."""
    finalized = _FILE_TYPES[file_type].finalized
    if finalized is not None and context.plant.is_finalized():
        raise failed_demand(finalized)


def _read_file(context: ParseContext, path: str, model_name: str | None, scope: str) -> list[Any]:
    """Adds the models of the file at ``path`` (its type from its name)."""
    file_type = _file_type(path)
    kind = _FILE_TYPES[file_type]
    _check_reader(context, file_type)
    if os.path.isdir(path) and file_type == "dmd.yaml":
        raise RuntimeError("basic_filebuf::underflow error reading the file: Is a directory")
    if os.path.isdir(path) and file_type == "sdf":
        raise ModelParseError(
            f"error: Could not find model.config or manifest.xml in [/{_absolute(path)}]"
        )
    if not os.path.isfile(path):
        error = "XML_ERROR_FILE_READ_ERROR" if os.path.isdir(path) else "XML_ERROR_FILE_NOT_FOUND"
        raise ModelParseError(kind.missing.format(path=path, absolute=_absolute(path), error=error))
    with open(path, encoding="utf-8") as stream:
        text = stream.read()
    label = _sdf_label(path) if file_type == "sdf" else None
    source = ModelSource(text, file_type, path, label)
    return kind.reader(context, source, model_name, scope)


def _sdf_label(path: str) -> str:
    """How an SDFormat file's diagnostics name it: '/' + its absolute path since 1.34
    (sdformat 15), its absolute path before (sdf-file-path-double-slash-since-1.34)."""
    slash = "/" if release.has("sdf-file-path-double-slash-since-1.34") else ""
    return slash + os.path.abspath(path)


#: Whether the plant-first constructors refuse a plant of None (pybind11's TypeError)
#: rather than failing Drake's check (SystemExit): release fact
#: parser-plant-none-refused-since-1.58. The builder constructor takes None for its
#: builder and its plant on every release measured (1.51.1, 1.52.0 to 1.58.0).
_PLANT_NONE_REFUSED = release.has("parser-plant-none-refused-since-1.58")


def _is_plant(value: object) -> bool:
    return isinstance(value, MultibodyPlant) or (value is None and not _PLANT_NONE_REFUSED)


def _is_plant_or_none(value: object) -> bool:
    return value is None or isinstance(value, MultibodyPlant)


def _is_builder(value: object) -> bool:
    return value is None or isinstance(value, DiagramBuilder)


def _is_scene_graph(value: object) -> bool:
    return value is None or isinstance(value, SceneGraph)


_is_plant.__name__ = "reimpl.multibody.plant.MultibodyPlant"
_is_plant_or_none.__name__ = _is_plant.__name__
_is_builder.__name__ = "reimpl.systems.framework.DiagramBuilder"
_is_scene_graph.__name__ = "reimpl.geometry.SceneGraph"

#: Drake's type names, for "Cannot cast ..." (the "plant" subsystem is not a plant)
_CPP_TYPES = {SceneGraph: "drake::geometry::SceneGraph<double>"}


class Parser:
    """Adds models to a MultibodyPlant (drake/multibody/parsing/parser.h)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._builder: DiagramBuilder | None = None
        self._package_map = PackageMap()
        self._auto_renaming = False
        self._strict = False
        self._groups: NameGroups[InstancedName] = NameGroups(order)
        plant = Param("plant", _is_plant)
        scene_graph = Param("scene_graph", _is_scene_graph, None)
        prefix = Param("model_name_prefix", is_str)
        # model_name_prefix is bound since 1.13 (parser-model-name-prefix-since-1.13: measured
        # on pydrake 1.12.0, (plant, scene_graph=None) only, and 1.13.0, these two).
        by_plant = (
            (
                Overload((plant, scene_graph, Param(prefix.name, prefix.check, "")), self._init),
                Overload((Param("plant", _is_plant), prefix), self._init),
            )
            if release.has("parser-model-name-prefix-since-1.13")
            else (Overload((plant, scene_graph), partial(self._init, model_name_prefix="")),)
        )
        dispatch(
            _OWNER,
            "__init__",
            (
                *by_plant,
                Overload(
                    (
                        Param("builder", _is_builder),
                        Param("plant", _is_plant_or_none, None),
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
        self,
        plant: MultibodyPlant | None,
        model_name_prefix: str,
        scene_graph: SceneGraph | None = None,
    ) -> None:
        if plant is None:
            raise failed_demand("Parser.plant")
        if scene_graph is not None and not plant.geometry_source_is_registered():
            plant.RegisterAsSourceForSceneGraph(scene_graph)
        self._plant = plant
        self._prefix = model_name_prefix

    def _init_from_builder(
        self,
        builder: DiagramBuilder | None,
        plant: MultibodyPlant | None,
        scene_graph: SceneGraph | None,
        model_name_prefix: str,
    ) -> None:
        if builder is None:  # N.B. As Drake's: no builder, only the plant's own checks.
            self._init(plant, model_name_prefix, scene_graph)
            return
        systems = builder.GetSystems()
        if plant is None:
            plant = self._plant_named_plant(systems)
        if not any(s is plant for s in systems):
            raise RuntimeError("The provided plant must be one of the systems in the builder")
        if scene_graph is not None and not any(s is scene_graph for s in systems):
            raise RuntimeError("The provided scene_graph must be one of the systems in the builder")
        self._builder = builder
        self._init(plant, model_name_prefix, scene_graph)

    @staticmethod
    def _plant_named_plant(systems: list[Any]) -> MultibodyPlant:
        """Drake's ``GetMutableDowncastSubsystemByName<MultibodyPlant>("plant")``."""
        named = [s for s in systems if s.get_name() == "plant"]
        if not named:
            names = ", ".join(s.get_name() for s in systems)
            raise RuntimeError(
                f"DiagramBuilder does not contain a subsystem named plant. Valid subsystems "
                f"are {names}."
            )
        if not isinstance(named[0], MultibodyPlant):
            cpp = _CPP_TYPES.get(type(named[0]), f"drake::systems::{type(named[0]).__name__}")
            raise RuntimeError(
                f"Cannot cast a drake::systems::System<double>* pointing to an object of type "
                f"{cpp} to drake::multibody::MultibodyPlant<double>*."
            )
        return named[0]

    # ---------------------------------------------------------- accessors
    def plant(self) -> MultibodyPlant:
        return self._plant

    def scene_graph(self) -> SceneGraph | None:
        """The SceneGraph the plant is registered with (None if it is not)."""
        if not self._plant.geometry_source_is_registered():
            return None
        if self._plant.is_finalized():
            raise failed_demand("Parser.scene_graph.finalized")
        scene_graph: SceneGraph = self._plant._registered_scene_graph("scene_graph")[0]
        return scene_graph

    def builder(self) -> DiagramBuilder | None:
        return self._builder

    def package_map(self) -> PackageMap:
        return self._package_map

    @release.binding("parser-auto-renaming-since-1.14")
    @binds(_OWNER, Param("value", lambda value: True))
    def SetAutoRenaming(self, value: bool) -> None:
        """With auto-renaming, a taken model name gets the first free ``_1``, ``_2``, ...
        (``value`` is read as a bool, as pybind11 reads it)."""
        self._auto_renaming = bool(value)

    @release.binding("parser-auto-renaming-since-1.14")
    def GetAutoRenaming(self) -> bool:
        return self._auto_renaming

    @binds(_OWNER)
    def SetStrictParsing(self) -> None:
        """Makes every warning an error."""
        self._strict = True

    if release.has("filter-groups-report-since-1.31"):  # bound since 1.31

        def GetCollisionFilterGroups(self) -> CollisionFilterGroups:
            """The groups and pairs of every parse so far, named with the model
            instances' current names (see _instanced_name)."""
            plant = self._plant
            return CollisionFilterGroups._from(
                self._groups.convert(lambda name: spelled(plant, name), str)
            )

    # ------------------------------------------------------------ parsing
    def AddModels(self, *args: Any, **kwargs: Any) -> list[Any]:
        """``AddModels(file_name)``, or keywords only: ``(url=)``,
        ``(file_contents=, file_type=)``."""
        by_name = Overload((Param("file_name", is_path),), self._add_file)
        overloads: tuple[Overload, ...] = (by_name,)
        if not args:
            overloads += (
                Overload((Param("url", is_str),), self.AddModelsFromUrl),
                Overload(
                    (Param("file_contents", is_str), Param("file_type", is_str)),
                    self.AddModelsFromString,
                ),
            )
        return dispatch(_OWNER, "AddModels", overloads, args, kwargs)  # type: ignore[no-any-return]

    @binds(_OWNER, Param("url", is_str))
    def AddModelsFromUrl(self, url: str) -> list[Any]:
        """The models of the file ``url`` names (``package://``, ``model://``, ``file://``)."""
        try:
            path = resolve_uri(self._package_map, url, None, warn=self._warn)
        except UriError as exc:
            raise ModelParseError(f"error: {exc}") from None
        return self._add_file(path)

    @binds(_OWNER, Param("file_contents", is_str), Param("file_type", is_str))
    def AddModelsFromString(self, file_contents: str, file_type: str) -> list[Any]:
        """The models of ``file_contents``, a model of type ``file_type`` (``urdf``, ...)."""
        kind = _file_type(literal_string_name(file_type))
        source = ModelSource(file_contents, kind)

        def read(context: ParseContext) -> list[Any]:
            text_error = _FILE_TYPES[kind].text_error
            if text_error is not None:
                raise RuntimeError(text_error)
            _check_reader(context, kind)
            return _FILE_TYPES[kind].reader(context, source, None, self._prefix)

        return self._parse(read)

    def _warn(self, message: str) -> None:
        Diagnostics(None, self._strict).warning(message)

    def _add_file(self, file_name: str | os.PathLike[str]) -> list[Any]:
        path = os.fspath(file_name)
        _file_type(path)
        return self._parse(lambda context: _read_file(context, path, None, self._prefix))

    def _process_directives(self, directives: Any) -> list[Any]:
        """ProcessModelDirectives: one parse of ``directives`` at global scope."""
        return self._parse(lambda context: process_directives(context, directives, ""))

    def _parse(self, read: Callable[[ParseContext], list[Any]]) -> list[Any]:
        """One composite parse: ``read``'s models, then the groups resolved and kept."""
        plant = self._plant
        if plant.geometry_source_is_registered() and plant.is_finalized():
            raise failed_demand("GetMutableSceneGraphPreFinalize.finalized")
        context = ParseContext(
            plant=plant,
            package_map=self._package_map,
            resolver=CollisionFilterGroupResolver(plant),
            auto_renaming=self._auto_renaming,
            strict=self._strict,
            read_file=_read_file,
            builder=self._builder,
        )
        try:
            instances = read(context)
        except Exception:
            context.resolver.resolve_unwinding()  # up to 1.30 only
            raise
        self._groups.merge(context.resolver.resolve())
        return instances
