"""The model commands of ``grammar.multibody``: a MultibodyPlant and its parsers, one method per op.

``MultibodyCommands`` is a mixin of ``SceneGraphBackend``: the plant is made
lazily, at the case's first model step, as ``MultibodyPlant(time_step=0.0)``
registered as a source of the backend's SceneGraph (its source joins those
whose poses ``clone_context`` fixes). Every call uses Drake's keyword names
(``file_contents=``, ``model_instance=``, ``frame_on_parent=``), except the
few that pydrake binds without one (``GetBodyFromFrameId(frame_id)``).

Names. A body the case adds (``add_rigid_body``) is its scenario name, and so
is its frame; ``world`` is the world body. Every body of the plant is also
``<model instance>::<body>`` (its frame, and its body in ``add_joint`` and
``weld_frames``), and every plant geometry the case did not name is
``<model instance>::<body>/<its name without the leading '<model instance>::'>``
(``m::l1/Sphere``, ``top::inner::x/c``, ``WorldModelInstance::world/Sphere``).
Only proximity (collision) geometries get such names: a visual one may share
its Drake name with a collision one on the same body (names are unique per
role), and never joins C.

Files. ``add_models`` writes ``files`` to the case's temporary folder, which
every Parser of the case knows as the package ``pkg``
(``package://pkg/rel/path.urdf``); ``path`` is a file in it. A folder of
them that holds a ``package.xml`` is a package of its own name as well
(``package://pa/...``, ``model://pa/...``): every Parser of the case then
calls ``PopulateFromFolder(path=)`` on the case's folder. The folder's path
is cut out of error messages, so they read ``rel/path.urdf:3: error: ...``
on every machine.

Renaming. ``rename_model_instance`` calls ``RenameModelInstance``; then the
renamed model's bodies are also ``<new name>::<body>`` and its geometries
are named again from their current names (``m2::l1/Sphere``, where Drake
renamed the geometry ``m2::Sphere``), so a later parse may reuse the old
names. A geometry whose name is taken gets ``#2``, ``#3``... (Drake issue
#21316 is about a Parser reused after a rename: ``add_models`` with
``reuse_parser``).
"""

from __future__ import annotations

import os
import shutil
import tempfile
import weakref
from collections.abc import Mapping, Sequence
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any
from xml.etree import ElementTree

from conformance._grammar import FEATURE_BINDINGS, release_features
from conformance._policy.release_facts import fact_holds, release_fact
from conformance.protocol import UnknownNameError

if TYPE_CHECKING:
    from conformance._backends.api import Api

__all__ = [
    "JOINT_CLASSES",
    "PACKAGE",
    "PLANT_SOURCE",
    "MultibodyCommands",
    "binding_error",
    "model_features",
    "package_names",
]

#: The package name of a case's files.
PACKAGE = "pkg"
#: The key of the plant's source among the backend's sources (no scenario name can be it).
PLANT_SOURCE = "@plant"
#: Separators of scoped names: model instance and body, body and geometry.
_SCOPE, _GEOMETRY = "::", "/"
WORLD = "world"

#: ``add_joint`` type (``grammar.multibody.JOINT_TYPES``) → (pydrake.multibody.tree class,
#: its frame keywords, other keywords; ``None`` stands for an identity RigidTransform).
JOINT_CLASSES: Mapping[str, tuple[str, tuple[str, str], Mapping[str, Any]]] = {
    "revolute": ("RevoluteJoint", ("frame_on_parent", "frame_on_child"), {"axis": [0.0, 0.0, 1.0]}),
    "prismatic": (
        "PrismaticJoint",
        ("frame_on_parent", "frame_on_child"),
        {"axis": [0.0, 0.0, 1.0]},
    ),
    "weld": ("WeldJoint", ("frame_on_parent_F", "frame_on_child_M"), {"X_FM": None}),
    "ball_rpy": ("BallRpyJoint", ("frame_on_parent", "frame_on_child"), {}),
    "universal": ("UniversalJoint", ("frame_on_parent", "frame_on_child"), {}),
    "planar": ("PlanarJoint", ("frame_on_parent", "frame_on_child"), {"damping": [0.0, 0.0, 0.0]}),
    "quaternion_floating": ("QuaternionFloatingJoint", ("frame_on_parent", "frame_on_child"), {}),
    "rpy_floating": ("RpyFloatingJoint", ("frame_on_parent", "frame_on_child"), {}),
}

#: ``add_joint`` types whose class some releases lack → its binding row.
_JOINT_BINDINGS: Mapping[str, str] = {"rpy_floating": "rpy-floating-joint-since-1.27"}

#: Model feature tag → the modules of the implementation it needs (``Api`` attributes).
#: Which releases have a tag is the release table's (``grammar.FEATURE_BINDINGS``).
_FEATURE_MODULES: Mapping[str, tuple[str, ...]] = {
    "multibody": ("plant", "tree"),
    "parsing": ("parsing", "tree"),
    "adjacency_opt_out": ("plant", "tree"),
    "filter_groups_report": ("parsing", "tree"),
}


#: Role name → the SceneGraphInspector method that reads its properties (None: no role).
_ROLE_READERS: Mapping[str, str] = {
    "proximity": "GetProximityProperties",
    "illustration": "GetIllustrationProperties",
    "perception": "GetPerceptionProperties",
}


def _spellings(path: str) -> list[str]:
    """A folder as messages may spell it: as given, normalized, resolved (no final slash)."""
    path = path.rstrip("/")
    return list(dict.fromkeys([path, os.path.normpath(path), os.path.realpath(path)]))


def package_names(folder: Path) -> list[str]:
    """The names of the packages below ``folder`` (each ``package.xml``'s ``<name>``), in the
    sorted order of their folders, each once."""
    names: dict[str, None] = {}
    for manifest in sorted(folder.rglob("package.xml")):
        try:
            name = ElementTree.parse(manifest).getroot().findtext("name")
        except (ElementTree.ParseError, OSError):
            continue
        if name and name.strip():
            names.setdefault(name.strip())
    return list(names)


def model_features(api: Api) -> frozenset[str]:
    """The model feature tags ``api`` supports: its modules exist (Drake 1.12-1.23 under
    numpy 2 cannot import ``pydrake.multibody``) and its release has them
    (``grammar.release_features``)."""
    released = release_features(api.version)
    return frozenset(
        tag
        for tag, modules in _FEATURE_MODULES.items()
        if all(getattr(api, m) is not None for m in modules)
        and (tag not in FEATURE_BINDINGS or tag in released)
    )


def _missing(api: Api, what: str) -> TypeError:
    """A binding error (ErrorKind.BINDING): the implementation lacks ``what``."""
    return TypeError(f"{api.name} {api.version} has no {what}")


def binding_error(api: Api, fact: str) -> TypeError:
    """The binding error of a call whose binding row ``fact`` does not hold for ``api``."""
    return _missing(api, " / ".join(release_fact(fact).bindings))


def _require(api: Api, fact: str) -> None:
    """Raises the binding error of a call whose binding row (``fact``) does not hold for
    ``api``'s release: the release table decides, not the implementation's attributes."""
    if not fact_holds(fact, api.version):
        raise binding_error(api, fact)


class MultibodyCommands:
    """The model ops (see the module doc); mixed into ``SceneGraphBackend``."""

    # Provided by SceneGraphBackend.
    api: Api
    scene_graph: Any
    sources: dict[str, Any]
    frames: dict[str, Any]
    geometries: dict[str, Any]
    names_by_value: dict[int, str]

    def _reset_models(self) -> None:
        """Forgets the plant, its bodies and parser, and removes the case's files."""
        self.plant: Any = None
        self.bodies: dict[str, Any] = {}
        self.parser: Any = None
        #: The geometry names ``_name_plant_geometries`` gave (not the case's own).
        self._plant_named: set[str] = set()
        cleanup = getattr(self, "_cleanup", None)
        if cleanup is not None:
            cleanup()
        self._folder: Path | None = None
        self._cleanup: weakref.finalize[..., Any] | None = None

    # ------------------------------------------------------------- helpers
    def _module(self, name: str) -> ModuleType:
        """The implementation's ``multibody.<name>`` module (a binding error if it lacks it)."""
        module: ModuleType | None = getattr(self.api, name)
        if module is None:
            raise _missing(self.api, f"multibody.{name}")
        return module

    def _plant(self) -> Any:
        """The case's plant, made and registered with the SceneGraph at the first call."""
        if self.plant is None:
            self._module("tree")
            plant = self._module("plant").MultibodyPlant(time_step=0.0)
            self.sources[PLANT_SOURCE] = plant.RegisterAsSourceForSceneGraph(
                scene_graph=self.scene_graph
            )
            self.plant = plant
        return self.plant

    def _package(self) -> Path:
        """The case's temporary folder (made at the first call, removed at reset)."""
        if self._folder is None:
            self._folder = Path(tempfile.mkdtemp(prefix="conformance-models-")).resolve()
            self._cleanup = weakref.finalize(self, shutil.rmtree, self._folder, ignore_errors=True)
        return self._folder

    def _model_instance(self, name: str) -> Any:
        plant = self._plant()
        if plant.HasModelInstanceNamed(name=name):
            return plant.GetModelInstanceByName(name=name)
        return plant.AddModelInstance(name=name)

    def _body(self, name: str) -> Any:
        """The body ``name`` stands for: ``world``, a body the case added, or ``model::body``."""
        plant = self._plant()
        if name == WORLD:
            return plant.world_body()
        if name in self.bodies:
            return self.bodies[name]
        model, scope, body = name.rpartition(_SCOPE)
        if (
            scope
            and plant.HasModelInstanceNamed(name=model)
            and plant.HasBodyNamed(
                name=body, model_instance=plant.GetModelInstanceByName(name=model)
            )
        ):
            return plant.GetBodyByName(
                name=body, model_instance=plant.GetModelInstanceByName(name=model)
            )
        raise UnknownNameError("body", name)

    def _scoped(self, body: Any) -> str:
        """``<model instance>::<body>``."""
        model = self.plant.GetModelInstanceName(model_instance=body.model_instance())
        return f"{model}{_SCOPE}{body.name()}"

    def _name_plant_geometries(self) -> None:
        """Names every plant body's frame and every unnamed plant proximity geometry (module doc).

        N.B. It asks the SceneGraph, not the plant: a parse that fails while
        registering (during transient history) leaves a proximity geometry
        that the plant does not list for its body.
        """
        plant = self.plant
        inspector = self.scene_graph.model_inspector()
        source = self.sources[PLANT_SOURCE]
        world = self.scene_graph.world_frame_id()
        for frame_id in inspector.FramesForSource(source_id=source):
            self.frames.setdefault(self._scoped(plant.GetBodyFromFrameId(frame_id)), frame_id)
        for geometry_id in inspector.GetAllGeometryIds():
            if (
                geometry_id.get_value() in self.names_by_value
                or not inspector.BelongsToSource(geometry_id=geometry_id, source_id=source)
                or inspector.GetProximityProperties(geometry_id=geometry_id) is None
            ):
                continue
            frame_id = inspector.GetFrameId(geometry_id=geometry_id)
            body = plant.world_body() if frame_id == world else plant.GetBodyFromFrameId(frame_id)
            scoped = self._scoped(body)
            model = scoped[: -len(body.name())]
            drake_name = inspector.GetName(geometry_id=geometry_id)
            name = base = f"{scoped}{_GEOMETRY}{drake_name.removeprefix(model)}"
            clash = 1
            while name in self.geometries:  # e.g. a parse reusing a renamed model's old name
                clash += 1
                name = f"{base}#{clash}"
            self.geometries[name] = geometry_id
            self.names_by_value[geometry_id.get_value()] = name
            self._plant_named.add(name)

    def _rename_plant_geometries(self) -> None:
        """Names every plant body's frame and plant proximity geometry again, by the model
        instances' current names (after ``rename_model_instance``); the frames keep their
        old names too."""
        for name in self._plant_named:
            self.names_by_value.pop(self.geometries.pop(name).get_value(), None)
        self._plant_named.clear()
        self._name_plant_geometries()

    def _local(
        self, exc: Exception, *folders: Path, named: Mapping[str, Sequence[str]] | None = None
    ) -> Exception:
        """``exc`` with the case's folder (and ``folders``) cut out of its message, and each
        ``named`` package folder (name: its spellings) written ``<name>``: the
        implementation's own ``drake`` package, which each release installs elsewhere, and
        the packages a step names."""
        cut = [f for f in (self._folder, *folders) if f is not None]
        renamed = named or {}
        if (cut or renamed) and exc.args and isinstance(exc.args[0], str):
            message = exc.args[0]
            for folder in cut:
                message = message.replace(f"{folder}/", "")
            for name, spellings in renamed.items():
                for path in spellings:
                    message = message.replace(f"{path}/", f"<{name}>/")
            exc.args = (message, *exc.args[1:])
        return exc

    @staticmethod
    def _drake_package(parser: Any) -> list[str]:
        """The spellings of the implementation's default ``drake`` package folder (as its
        map gives it, normalized, resolved), if the map has one."""
        package_map = parser.package_map()
        if not package_map.Contains(package_name="drake"):
            return []
        return _spellings(str(package_map.GetPath(package_name="drake")))

    @staticmethod
    def _add_named_packages(parser: Any, packages: Mapping[str, str]) -> None:
        """Each ``name: path`` as a package (Add(package_name=, package_path=)), replacing
        one the map already has by that name (Drake's defaults too)."""
        package_map = parser.package_map()
        for name, path in packages.items():
            if package_map.Contains(package_name=name):
                package_map.Remove(package_name=name)
            package_map.Add(package_name=name, package_path=path)

    def _add_packages(self, parser: Any, folder: Path) -> None:
        """The packages below ``folder``: PopulateFromFolder(path=), after removing the
        packages of the map (Drake's defaults ``drake``, ``drake_models``) that the folder
        also provides, so that its own copy is the one found."""
        package_map = parser.package_map()
        for name in package_names(folder):
            if package_map.Contains(package_name=name):
                package_map.Remove(package_name=name)
        try:
            populate = package_map.PopulateFromFolder
        except AttributeError:  # an implementation without the binding answers, not breaks
            raise _missing(self.api, "PackageMap.PopulateFromFolder") from None
        populate(path=str(folder))

    # ------------------------------------------------------------ commands
    def _parser(self, args: Mapping[str, Any]) -> Any:
        """A new Parser of the plant (with the prefix), or with ``reuse_parser`` the last one."""
        parsing = self._module("parsing")
        plant = self._plant()
        if args.get("reuse_parser"):
            if "prefix" in args:
                raise ValueError("add_models: reuse_parser takes no prefix (the Parser exists)")
            if self.parser is None:
                raise UnknownNameError("parser", "(reuse_parser needs an earlier add_models)")
            return self.parser
        if "prefix" in args:
            _require(self.api, "parser-model-name-prefix-since-1.13")
            return parsing.Parser(plant=plant, model_name_prefix=args["prefix"])
        return parsing.Parser(plant=plant)

    def add_models(self, args: Mapping[str, Any]) -> list[str]:
        plant = self._plant()
        parser = self.parser = self._parser(args)
        if "auto_renaming" in args:
            _require(self.api, "parser-auto-renaming-since-1.14")
            parser.SetAutoRenaming(value=args["auto_renaming"])
        files = args.get("files", {})
        if files or ("path" in args and "folder" not in args):
            folder = self._package()
            for relative, text in files.items():
                target = folder / relative
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(text, encoding="utf-8")
        if self._folder is not None and not parser.package_map().Contains(package_name=PACKAGE):
            parser.package_map().Add(package_name=PACKAGE, package_path=str(self._folder))
        models_folder = Path(args["folder"]) if "folder" in args else None
        named = {"drake": self._drake_package(parser)} | {
            name: _spellings(path) for name, path in args.get("packages", {}).items()
        }
        try:
            self._add_named_packages(parser, args.get("packages", {}))
            if self._folder is not None and package_names(self._folder):
                self._add_packages(parser, self._folder)
            if models_folder is not None:
                self._add_packages(parser, models_folder)
                models = parser.AddModels(file_name=str(models_folder / args["path"]))
            elif "path" in args:
                models = parser.AddModels(file_name=str(self._package() / args["path"]))
            else:
                models = parser.AddModelsFromString(
                    file_contents=args["text"], file_type=args["format"]
                )
        except Exception as exc:
            raise self._local(exc, *filter(None, [models_folder]), named=named) from None
        finally:
            self._name_plant_geometries()
        return [plant.GetModelInstanceName(model_instance=m) for m in models]

    def collision_filter_groups(self, args: Mapping[str, Any]) -> dict[str, Any]:
        if self.parser is None:
            raise UnknownNameError(
                "parser", "(collision_filter_groups needs an earlier add_models)"
            )
        return self._group_report(self.parser)

    def _filter_groups(self) -> dict[str, Any] | None:
        """The last Parser's group report for ``observe`` (None: no parse yet, or a
        release without GetCollisionFilterGroups, before 1.31)."""
        if self.parser is None or not fact_holds(
            "filter-groups-report-since-1.31", self.api.version
        ):
            return None
        return self._group_report(self.parser)

    @staticmethod
    def _group_report(parser: Any) -> dict[str, Any]:
        groups = parser.GetCollisionFilterGroups()
        return {
            "groups": {name: sorted(members) for name, members in sorted(groups.groups().items())},
            "pairs": sorted(sorted(pair) for pair in groups.exclusion_pairs()),
        }

    def model_inventory(self, args: Mapping[str, Any]) -> dict[str, list[str]]:
        """The plant's model instances, bodies, frames and joints (``model::name``), and its
        geometries (``frame/name: Shape [roles]``), each list sorted."""
        plant, tree = self._plant(), self._module("tree")
        inspector = self.scene_graph.model_inspector()

        def scoped(element: Any) -> str:
            model = plant.GetModelInstanceName(model_instance=element.model_instance())
            return f"{model}{_SCOPE}{element.name()}"

        count = {
            "bodies": plant.num_bodies(),
            "frames": plant.num_frames(),
            "joints": plant.num_joints(),
        }
        source = self.sources[PLANT_SOURCE]
        geometries = []
        for geometry_id in inspector.GetAllGeometryIds():
            if not inspector.BelongsToSource(geometry_id=geometry_id, source_id=source):
                continue
            frame = inspector.GetName(frame_id=inspector.GetFrameId(geometry_id=geometry_id))
            name = inspector.GetName(geometry_id=geometry_id)
            shape = type(inspector.GetShape(geometry_id=geometry_id)).__name__
            roles = [
                role
                for role, read in _ROLE_READERS.items()
                if getattr(inspector, read)(geometry_id=geometry_id) is not None
            ]
            geometries.append(f"{frame}/{name}: {shape} [{', '.join(roles)}]")
        return {
            "models": sorted(
                plant.GetModelInstanceName(model_instance=tree.ModelInstanceIndex(i))
                for i in range(plant.num_model_instances())
            ),
            "bodies": sorted(
                scoped(plant.get_body(body_index=tree.BodyIndex(i))) for i in range(count["bodies"])
            ),
            "frames": sorted(
                scoped(plant.get_frame(frame_index=tree.FrameIndex(i)))
                for i in range(count["frames"])
            ),
            "joints": sorted(
                f"{scoped(joint)} ({joint.type_name()})"
                for joint in (
                    plant.get_joint(joint_index=tree.JointIndex(i)) for i in range(count["joints"])
                )
            ),
            "geometries": sorted(geometries),
        }

    def rename_model_instance(self, args: Mapping[str, Any]) -> None:
        plant = self._plant()
        plant.RenameModelInstance(
            model_instance=plant.GetModelInstanceByName(name=args["model"]), name=args["name"]
        )
        self._rename_plant_geometries()

    def add_rigid_body(self, args: Mapping[str, Any]) -> None:
        tree = self._module("tree")
        plant = self._plant()
        model = args.get("model")
        instance = tree.default_model_instance() if model is None else self._model_instance(model)
        body = plant.AddRigidBody(
            name=args["name"],
            model_instance=instance,
            M_BBo_B=tree.SpatialInertia(
                mass=1.0,
                p_PScm_E=[0.0, 0.0, 0.0],
                G_SP_E=tree.UnitInertia(Ixx=1.0, Iyy=1.0, Izz=1.0),
            ),
        )
        self.bodies[args["name"]] = body
        self.frames[args["name"]] = plant.GetBodyFrameIdOrThrow(body_index=body.index())
        self._name_plant_geometries()

    def add_joint(self, args: Mapping[str, Any]) -> None:
        class_name, (on_parent, on_child), extra = JOINT_CLASSES[args["type"]]
        if args["type"] in _JOINT_BINDINGS:
            _require(self.api, _JOINT_BINDINGS[args["type"]])
        cls = getattr(self._module("tree"), class_name)
        keywords = {
            key: self.api.math.RigidTransform() if value is None else value
            for key, value in extra.items()
        }
        joint = cls(
            name=args["name"],
            **{
                on_parent: self._body(args["parent"]).body_frame(),
                on_child: self._body(args["child"]).body_frame(),
            },
            **keywords,
        )
        self._plant().AddJoint(joint=joint)

    def weld_frames(self, args: Mapping[str, Any]) -> None:
        self._plant().WeldFrames(
            frame_on_parent_F=self._body(args["parent"]).body_frame(),
            frame_on_child_M=self._body(args["child"]).body_frame(),
            X_FM=self.api.math.RigidTransform(),
        )

    def _register(self, args: Mapping[str, Any], geometry_id: Any) -> None:
        self.geometries[args["name"]] = geometry_id
        self.names_by_value[geometry_id.get_value()] = args["name"]

    def register_collision_geometry(self, args: Mapping[str, Any]) -> None:
        plant = self._plant()
        geometry_id = plant.RegisterCollisionGeometry(
            body=self._body(args["body"]),
            X_BG=self.api.math.RigidTransform(),
            shape=self.api.geometry.Sphere(radius=0.1),
            name=args.get("drake_name", args["name"]),
            coulomb_friction=self._module("plant").CoulombFriction(
                static_friction=1.0, dynamic_friction=1.0
            ),
        )
        self._register(args, geometry_id)

    def register_visual_geometry(self, args: Mapping[str, Any]) -> None:
        plant = self._plant()
        geometry_id = plant.RegisterVisualGeometry(
            body=self._body(args["body"]),
            X_BG=self.api.math.RigidTransform(),
            shape=self.api.geometry.Sphere(radius=0.1),
            name=args.get("drake_name", args["name"]),
            diffuse_color=[0.5, 0.5, 0.5, 1.0],
        )
        self._register(args, geometry_id)

    def set_adjacent_filters(self, args: Mapping[str, Any]) -> None:
        plant = self._plant()
        plant.set_adjacent_bodies_collision_filters(value=args["value"])

    def finalize(self, args: Mapping[str, Any]) -> None:
        self._plant().Finalize()
