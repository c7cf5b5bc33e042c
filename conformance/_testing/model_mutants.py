"""Model mutants: reimpl's multibody modules with one deliberate bug each, for ``fuzz --models``.

As for the SceneGraph mutants (``conformance._testing.mutants``), a model
mutant touches nothing inside reimpl and monkeypatches nothing: it is the
reimpl ``Api`` in which one multibody module (``tree``, ``plant`` or
``parsing``) is a copy whose class under test is a subclass of reimpl's
public class. The bug is written with pydrake's public names only (a joint's
``type_name()``, ``Parser.AddModelsFromString``, ``MultibodyPlant.WeldFrames``),
so a plain reimpl backend in the same process is unaffected.

Most parsing mutants are *readers with a bug*: a ``Parser`` whose
``AddModelsFromString`` and ``AddModels(file_name=)`` see the document
rewritten (the ``<name>`` of an ``<include>`` gone, say) before reimpl's
parser reads it; a file is rewritten in place for the parse and restored
after. The rewrites keep every line where it was, so that Drake's messages
keep their line numbers. Files a document names (an included model, a
second directives file) are read as they are.

Each mutant's ``witness`` is the shortest input found at seed 1 (``fuzz
--models --seed 1 --max-examples 300 --backend
conformance._testing.model_mutants:<name>``) and pydrake 1.51.1's exact
answer on it.

Use one as a backend spec, ``conformance._testing.model_mutants:<name>``, e.g.
``python -m conformance fuzz --models --backend
conformance._testing.model_mutants:rpy_floating_unfiltered``.
"""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import Any
from xml.etree import ElementTree

from conformance._backends.reimpl_api import reimpl_api
from conformance._backends.scene_graph import Api, SceneGraphBackend

__all__ = ["MODEL_MUTANTS", "ModelMutant", "model_mutant_backend"]

#: A rewrite of a document: (text, file type: ``urdf``, ``sdf`` or ``dmd.yaml``) → text.
Rewrite = Callable[[str, str], str]


def _rpy_floating_as_quaternion(tree: ModuleType) -> Mapping[str, type]:
    """An RpyFloatingJoint that reports QuaternionFloatingJoint's type name."""

    class RpyFloatingJoint(tree.RpyFloatingJoint):  # type: ignore[name-defined,misc]
        kTypeName = tree.QuaternionFloatingJoint.kTypeName

    return {"RpyFloatingJoint": RpyFloatingJoint}


def _file_type(path: Path) -> str:
    name = path.name.lower()
    return next((t for t in ("dmd.yaml", "urdf", "sdf") if name.endswith(f".{t}")), "")


@contextmanager
def _rewritten(path: Path, rewrite: Rewrite) -> Iterator[None]:
    """The file at ``path`` rewritten while the block runs, restored after (byte for byte)."""
    try:
        original = path.read_bytes()
        text = original.decode("utf-8")
    except (OSError, UnicodeDecodeError):
        yield
        return
    changed = rewrite(text, _file_type(path))
    if changed == text:
        yield
        return
    path.write_bytes(changed.encode("utf-8"))
    try:
        yield
    finally:
        path.write_bytes(original)


def _reading(rewrite: Rewrite) -> Callable[[ModuleType], Mapping[str, type]]:
    """A Parser that reads each document through ``rewrite`` (the module doc)."""

    def classes(parsing: ModuleType) -> Mapping[str, type]:
        class Parser(parsing.Parser):  # type: ignore[name-defined,misc]
            def AddModelsFromString(self, file_contents: str, file_type: str) -> list[Any]:
                text = rewrite(file_contents, file_type.lower().removeprefix("."))
                return super().AddModelsFromString(file_contents=text, file_type=file_type)  # type: ignore[no-any-return]

            def AddModels(self, *args: Any, **kwargs: Any) -> list[Any]:
                file_name = kwargs.get("file_name", args[0] if len(args) == 1 else None)
                if not isinstance(file_name, str | os.PathLike) or "file_contents" in kwargs:
                    return super().AddModels(*args, **kwargs)  # type: ignore[no-any-return]
                with _rewritten(Path(file_name), rewrite):
                    return super().AddModels(*args, **kwargs)  # type: ignore[no-any-return]

        return {"Parser": Parser}

    return classes


def _keep_lines(match: re.Match[str]) -> str:
    """The newlines of ``match``: what a removed element leaves, so lines do not move."""
    return "\n" * match.group(0).count("\n")


# ------------------------------------------------------------------ rewrites
def _without_include_names(text: str, file_type: str) -> str:
    """SDFormat: an ``<include>``'s ``<name>`` is not read."""
    if file_type != "sdf":
        return text
    return re.sub(
        r"<include\b.*?</include>",
        lambda m: re.sub(r"<name>[^<]*</name>", "", m.group(0)),
        text,
        flags=re.S,
    )


def _without_merge(text: str, file_type: str) -> str:
    """SDFormat: ``<include merge="true">`` is read as a plain include."""
    return text.replace(' merge="true"', "") if file_type == "sdf" else text


def _without_attached_to(text: str, file_type: str) -> str:
    """SDFormat: a ``<frame>``'s ``attached_to`` is not read (the model frame instead)."""
    if file_type != "sdf":
        return text
    return re.sub(r'(<frame\b[^>]*?)\s+attached_to="[^"]*"', r"\1", text)


def _without_drake_capsules(text: str, file_type: str) -> str:
    """A ``<drake:capsule>`` geometry is dropped: no geometry, no error."""
    if file_type == "urdf":
        pattern = r"<(collision|visual)\b[^>]*>(?:(?!</\1>).)*?<drake:capsule\b.*?</\1>"
        return re.sub(pattern, _keep_lines, text, flags=re.S)
    if file_type == "sdf":
        return re.sub(
            r"<drake:capsule>.*?</drake:capsule>",
            lambda m: "<empty />" + _keep_lines(m),
            text,
            flags=re.S,
        )
    return text


def _without_declare_convex(text: str, file_type: str) -> str:
    """``<drake:declare_convex/>`` is not read: the mesh stays a Mesh."""
    return re.sub(r"<drake:declare_convex\s*/>", "", text)


def _without_model_namespaces(text: str, file_type: str) -> str:
    """Directives: ``model_namespace`` is not read (add_directives, groups)."""
    if file_type != "dmd.yaml":
        return text
    return re.sub(r"(?m)^[ \t]*model_namespace:.*$", "", text)


def _without_member_groups(text: str, file_type: str) -> str:
    """Directives: an add_collision_filter_group's ``member_groups`` is not read."""
    if file_type != "dmd.yaml":
        return text
    return re.sub(r"(?m)^[ \t]*member_groups:.*$", "", text)


def _closing_root(text: str, file_type: str) -> str:
    """A document whose root element is not closed is read as if it were."""
    root = {"urdf": "robot", "sdf": "sdf"}.get(file_type)
    if root is None or f"<{root}" not in text or f"</{root}" in text:
        return text
    return text.rstrip("\0 \n") + f"</{root}>\n"


def _one_value_scale_rejected(text: str, file_type: str) -> str:
    """URDF: a mesh ``scale`` of one value is refused as pydrake refuses two."""
    if file_type == "urdf":
        for value in re.findall(r'<mesh\b[^>]*\bscale="([^" ]*)"', text):
            raise ValueError(f"Expected 3 values for attribute scale got {value}")
    return text


# ------------------------------------------------------------------ classes
def _renaming_ignored(parsing: ModuleType) -> Mapping[str, type]:
    """A Parser whose SetAutoRenaming does nothing."""

    class Parser(parsing.Parser):  # type: ignore[name-defined,misc]
        def SetAutoRenaming(self, value: bool) -> None:
            pass

    return {"Parser": Parser}


def _stale_report(parsing: ModuleType) -> Mapping[str, type]:
    """A Parser whose group report names each model as it was named when parsed."""

    class Parser(parsing.Parser):  # type: ignore[name-defined,misc]
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            self.mutant_names: dict[Any, str] = {}

        def _remember(self, models: list[Any]) -> list[Any]:
            plant = self.plant()
            for model in models:
                self.mutant_names[model] = plant.GetModelInstanceName(model_instance=model)
            return models

        def AddModelsFromString(self, file_contents: str, file_type: str) -> list[Any]:
            models = super().AddModelsFromString(file_contents=file_contents, file_type=file_type)
            return self._remember(models)

        def AddModels(self, *args: Any, **kwargs: Any) -> list[Any]:
            return self._remember(super().AddModels(*args, **kwargs))

        def GetCollisionFilterGroups(self) -> Any:
            report = super().GetCollisionFilterGroups()
            plant = self.plant()
            renamed = {
                plant.GetModelInstanceName(model_instance=model): old
                for model, old in self.mutant_names.items()
                if plant.GetModelInstanceName(model_instance=model) != old
            }

            def old_name(name: str) -> str:
                for new, old in sorted(renamed.items(), key=lambda item: -len(item[0])):
                    if name.startswith(f"{new}::"):
                        return f"{old}::{name.removeprefix(f'{new}::')}"
                return name

            stale = parsing.CollisionFilterGroups()
            for name, members in report.groups().items():
                stale.AddGroup(name=old_name(name), members={old_name(m) for m in members})
            for a, b in report.exclusion_pairs():
                stale.AddExclusionPair(pair=(old_name(a), old_name(b)))
            return stale

    return {"Parser": Parser}


class _WrongPackages:
    """A package map whose PopulateFromFolder gives every package found the folder of the
    first (sorted by folder); everything else is the real map's."""

    def __init__(self, real: Any) -> None:
        self.real = real

    def __getattr__(self, name: str) -> Any:
        return getattr(self.real, name)

    def PopulateFromFolder(self, path: str) -> None:
        manifests = sorted(Path(path).rglob("package.xml"))
        for manifest in manifests:
            name = (ElementTree.parse(manifest).getroot().findtext("name") or "").strip()
            if name and not self.real.Contains(package_name=name):
                self.real.Add(package_name=name, package_path=str(manifests[0].parent))


def _wrong_packages(parsing: ModuleType) -> Mapping[str, type]:
    """A Parser whose package map looks packages up in the wrong folder."""

    class Parser(parsing.Parser):  # type: ignore[name-defined,misc]
        def package_map(self) -> Any:
            return _WrongPackages(super().package_map())

    return {"Parser": Parser}


def _welds_unfiltered(plant_module: ModuleType) -> Mapping[str, type]:
    """A MultibodyPlant whose Finalize allows back the pairs of the bodies WeldFrames
    joined (as model directives' add_weld does), through the SceneGraph's public filters."""

    class MultibodyPlant(plant_module.MultibodyPlant):  # type: ignore[name-defined,misc]
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            self.mutant_welds: list[tuple[Any, Any]] = []
            self.mutant_scene_graph: Any = None

        def RegisterAsSourceForSceneGraph(self, scene_graph: Any) -> Any:
            self.mutant_scene_graph = scene_graph
            return super().RegisterAsSourceForSceneGraph(scene_graph=scene_graph)

        def WeldFrames(self, *args: Any, **kwargs: Any) -> Any:
            joint = super().WeldFrames(*args, **kwargs)
            self.mutant_welds.append((joint.parent_body(), joint.child_body()))
            return joint

        def Finalize(self) -> None:
            super().Finalize()
            if self.mutant_scene_graph is None or not self.mutant_welds:
                return
            from reimpl import geometry  # noqa: PLC0415 (the mutant's own SceneGraph API)

            declaration = geometry.CollisionFilterDeclaration()
            for parent, child in self.mutant_welds:
                frames = [self.GetBodyFrameIdOrThrow(body_index=b.index()) for b in (parent, child)]
                declaration.AllowBetween(
                    set_A=geometry.GeometrySet(frame_ids=[frames[0]]),
                    set_B=geometry.GeometrySet(frame_ids=[frames[1]]),
                )
            self.mutant_scene_graph.collision_filter_manager().Apply(declaration=declaration)

    return {"MultibodyPlant": MultibodyPlant}


def _welded_direct_only(plant_module: ModuleType) -> Mapping[str, type]:
    """A MultibodyPlant whose Finalize filters only bodies a weld joins directly (an
    implementer who walks the weld joints instead of the weld subgraphs): after reimpl's
    Finalize, the pairs of bodies of one weld subgraph that no joint joins are allowed
    back, through the SceneGraph's public filters.

    N.B. Allowed back whatever else filtered them (a collision filter group pair too).
    """

    class MultibodyPlant(plant_module.MultibodyPlant):  # type: ignore[name-defined,misc]
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            self.mutant_scene_graph: Any = None

        def RegisterAsSourceForSceneGraph(self, scene_graph: Any) -> Any:
            self.mutant_scene_graph = scene_graph
            return super().RegisterAsSourceForSceneGraph(scene_graph=scene_graph)

        def Finalize(self) -> None:
            super().Finalize()
            if self.mutant_scene_graph is None:
                return
            from reimpl import geometry  # noqa: PLC0415 (the mutant's own SceneGraph API)
            from reimpl.multibody.tree import BodyIndex, JointIndex  # noqa: PLC0415

            joints = [self.get_joint(JointIndex(i)) for i in range(self.num_joints())]
            ends = [(int(j.parent_body().index()), int(j.child_body().index())) for j in joints]
            joined = {frozenset(e) for e in ends}
            root = list(range(self.num_bodies()))

            def find(b: int) -> int:
                while root[b] != b:
                    b = root[b]
                return b

            for joint, (a, b) in zip(joints, ends, strict=True):
                if joint.type_name() == "weld":
                    root[find(a)] = find(b)
            declaration = geometry.CollisionFilterDeclaration()
            for a in range(self.num_bodies()):
                for b in range(a + 1, self.num_bodies()):
                    if find(a) != find(b) or frozenset((a, b)) in joined:
                        continue
                    try:
                        frames = [
                            self.GetBodyFrameIdOrThrow(
                                body_index=self.get_body(BodyIndex(i)).index()
                            )
                            for i in (a, b)
                        ]
                    except RuntimeError:
                        continue
                    declaration.AllowBetween(
                        set_A=geometry.GeometrySet(frame_ids=[frames[0]]),
                        set_B=geometry.GeometrySet(frame_ids=[frames[1]]),
                    )
            self.mutant_scene_graph.collision_filter_manager().Apply(declaration=declaration)

    return {"MultibodyPlant": MultibodyPlant}


def _report_without_self_pairs(parsing: ModuleType) -> Mapping[str, type]:
    """A Parser whose group report leaves out a group's exclusion of itself."""

    class Parser(parsing.Parser):  # type: ignore[name-defined,misc]
        def GetCollisionFilterGroups(self) -> Any:
            report = super().GetCollisionFilterGroups()
            out = parsing.CollisionFilterGroups()
            for name, members in report.groups().items():
                out.AddGroup(name=name, members=set(members))
            for a, b in report.exclusion_pairs():
                if a != b:
                    out.AddExclusionPair(pair=(a, b))
            return out

    return {"Parser": Parser}


def _report_of_last_parse(parsing: ModuleType) -> Mapping[str, type]:
    """A Parser whose group report holds the groups of its last parse only."""

    class Parser(parsing.Parser):  # type: ignore[name-defined,misc]
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            self.mutant_before: tuple[set[str], set[tuple[str, str]]] = (set(), set())

        def _forget_earlier(self) -> None:
            report = super().GetCollisionFilterGroups()
            self.mutant_before = (set(report.groups()), set(report.exclusion_pairs()))

        def AddModelsFromString(self, file_contents: str, file_type: str) -> list[Any]:
            self._forget_earlier()
            return super().AddModelsFromString(  # type: ignore[no-any-return]
                file_contents=file_contents, file_type=file_type
            )

        def AddModels(self, *args: Any, **kwargs: Any) -> list[Any]:
            self._forget_earlier()
            return super().AddModels(*args, **kwargs)  # type: ignore[no-any-return]

        def GetCollisionFilterGroups(self) -> Any:
            report = super().GetCollisionFilterGroups()
            groups, pairs = self.mutant_before
            out = parsing.CollisionFilterGroups()
            for name, members in report.groups().items():
                if name not in groups:
                    out.AddGroup(name=name, members=set(members))
            for pair in report.exclusion_pairs():
                if pair not in pairs:
                    out.AddExclusionPair(pair=pair)
            return out

    return {"Parser": Parser}


@dataclass(frozen=True)
class ModelMutant:
    """One injected bug: its name, what is wrong, and the classes that carry it.

    ``module`` names the Api's multibody module (``tree``, ``plant`` or
    ``parsing``) and ``classes`` makes its replaced classes from reimpl's.
    ``witness`` is the shortest input found and pydrake's answer on it.
    """

    name: str
    bug: str
    module: str
    classes: Callable[[ModuleType], Mapping[str, type]] = field(repr=False)
    witness: str = ""

    def api(self) -> Api:
        """reimpl's Api with the mutated copy of ``module``."""
        api = reimpl_api()
        original: ModuleType | None = getattr(api, self.module)
        if original is None:
            raise RuntimeError(f"reimpl has no multibody.{self.module} module to mutate")
        copy = ModuleType(f"{__name__}.{self.name}.{self.module}", f"{original.__name__}, mutated")
        for name in getattr(original, "__all__", ()):
            setattr(copy, name, getattr(original, name))
        for name, cls in self.classes(original).items():
            setattr(copy, name, cls)
        changes: dict[str, Any] = {"name": f"mutant:{self.name}", self.module: copy}
        return dataclasses.replace(api, **changes)


MODEL_MUTANTS: dict[str, ModelMutant] = {
    mutant.name: mutant
    for mutant in (
        ModelMutant(
            "rpy_floating_unfiltered",
            "An RpyFloatingJoint is taken for a QuaternionFloatingJoint, so Finalize does not "
            "filter its two bodies (Drake filters every joint type but the quaternion one).",
            "tree",
            _rpy_floating_as_quaternion,
            witness="A body B0 with a sphere, an RpyFloatingJoint J0 from the world, Finalize: "
            "pydrake 1.51.1's inventory lists 'DefaultModelInstance::J0 (rpy_floating)' (the "
            "mutant: quaternion_floating), and filters B0 against the world.",
        ),
        ModelMutant(
            "include_name_ignored",
            "An SDFormat include's <name> is not read, so the included model keeps its own name.",
            "parsing",
            _reading(_without_include_names),
            witness='SDFormat <model name="m"><link '
            'name="l0"/><include><uri>package://pkg/i0.sdf</uri><name>r0</name></include></model>, '
            "i0.sdf a model i0 of one link: pydrake 1.51.1 returns ['m', 'm::r0'] (the mutant "
            "['m', 'm::i0']).",
        ),
        ModelMutant(
            "merge_include_not_merged",
            'An SDFormat <include merge="true"> is read as a plain include (a nested model).',
            "parsing",
            _reading(_without_merge),
            witness='SDFormat <model name="m"><link name="l0"/><include '
            'merge="true"><uri>package://pkg/i0.sdf</uri></include></model>: pydrake 1.51.1 '
            "returns ['m'] (the mutant ['m', 'm::i0']).",
        ),
        ModelMutant(
            "frame_attached_to_ignored",
            "An SDFormat frame's attached_to is not read, so the frame is on the model frame.",
            "parsing",
            _reading(_without_attached_to),
            witness="SDFormat model m with links l0-l3, frames f0 and f1 on l0, "
            "f2 on l3, a revolute "
            "j0 from the world to f2, Finalize: pydrake 1.51.1's inventory has j0 holding l3 "
            "and floats l0, l1, l2 ('m::l0 (quaternion_floating)'; the mutant floats l3).",
        ),
        ModelMutant(
            "drake_capsule_dropped",
            "A <drake:capsule> geometry is dropped without an error, in URDF and SDFormat.",
            "parsing",
            _reading(_without_drake_capsules),
            witness='URDF <link name="l0"><collision><geometry><drake:capsule radius="0.1" '
            'length="0.2"/></geometry></collision></link>: pydrake 1.51.1\'s inventory lists '
            "'m::l0/m::Capsule: Capsule [proximity]' (the mutant no geometry).",
        ),
        ModelMutant(
            "declare_convex_ignored",
            "A mesh's <drake:declare_convex/> is not read, so the geometry is a Mesh.",
            "parsing",
            _reading(_without_declare_convex),
            witness="URDF <mesh "
            'filename="package://pkg/meshes/mesh.obj"><drake:declare_convex/></mesh> '
            "collision: pydrake 1.51.1's inventory lists 'm::l0/m::Convex: Convex "
            "[proximity]' (the mutant a Mesh).",
        ),
        ModelMutant(
            "one_value_scale_rejected",
            'A URDF mesh scale of one value (scale="2") is refused as pydrake refuses two.',
            "parsing",
            _reading(_one_value_scale_rejected),
            witness='URDF <mesh filename="package://pkg/meshes/mesh.obj" scale="2"/> collision: '
            "pydrake 1.51.1 returns ['m'] (the mutant: ValueError 'Expected 3 values for "
            "attribute scale got 2').",
        ),
        ModelMutant(
            "directives_model_namespace_ignored",
            "A directives model_namespace is not read, in add_directives and in groups.",
            "parsing",
            _reading(_without_model_namespaces),
            witness="Directives adding d0, d1, d2 and add_collision_filter_group G0 with "
            "model_namespace: d0 and members: [d0l0]: pydrake 1.51.1 returns ['d0', 'd1', "
            "'d2'] (the mutant: \"error: body with name 'd0l0' not found\").",
        ),
        ModelMutant(
            "member_groups_ignored",
            "An add_collision_filter_group's member_groups are not read.",
            "parsing",
            _reading(_without_member_groups),
            witness="Directives adding d0, d1, d2 and add_collision_filter_group "
            "G0 with members: [] "
            "and member_groups: [G0]: pydrake 1.51.1 returns ['d0', 'd1', 'd2'] (a group "
            "whose one member group is itself is valid); the mutant fails "
            "LoadModelDirectives' 'directives.IsValid()' DRAKE_DEMAND.",
        ),
        ModelMutant(
            "malformed_xml_accepted",
            "A URDF or SDFormat document whose root element is not closed is read as closed.",
            "parsing",
            _reading(_closing_root),
            witness='URDF text \'<robot name="m" ...>\\n  <link name="l0" />\\n\\n\' '
            "without </robot>: "
            "pydrake 1.51.1 raises '<literal-string>.urdf:1: error: Failed to parse XML "
            "string: XML_ERROR_PARSING' (the mutant returns ['m']).",
        ),
        ModelMutant(
            "auto_renaming_ignored",
            "Parser.SetAutoRenaming does nothing, so a second parse of a model clashes.",
            "parsing",
            _renaming_ignored,
            witness='URDF <robot name="m"><link name="l0"/></robot> parsed twice, the second time '
            "with SetAutoRenaming(True): pydrake 1.51.1 returns ['m_1'] (the mutant: \"This "
            "model already contains a model instance named 'm'...\").",
        ),
        ModelMutant(
            "renamed_model_report_stale",
            "The group report keeps a renamed model's old name (Drake issue #21316 fixed it).",
            "parsing",
            _stale_report,
            witness="URDF r with group g = {a, b}, RenameModelInstance(r, "
            "'r_first'), then the same "
            "Parser's report: pydrake 1.51.1 reports {'r_first::g': ['r_first::a', "
            "'r_first::b']} (tests/test_model_scenes.py). The campaign's witness waits for "
            "reimpl's #21316 fix: today it meets reimpl's own divergence first.",
        ),
        ModelMutant(
            "package_lookup_wrong_package",
            "PopulateFromFolder gives every package found the folder of the first one.",
            "parsing",
            _wrong_packages,
            witness="Directives adding d0 from package://pa/d0.urdf and d1 from "
            "package://pb/d1.urdf, "
            "pa/ and pb/ each with a package.xml: pydrake 1.51.1 returns ['d0', 'd1'] (the "
            "mutant: \"error: URI 'package://pb/d1.urdf' resolved to 'pa/d1.urdf' which does "
            'not exist.").',
        ),
        ModelMutant(
            "add_weld_unfiltered",
            "The bodies WeldFrames joins (model directives' add_weld) are not filtered.",
            "plant",
            _welds_unfiltered,
            witness="An anchored sphere w0, directives adding d0 (link d0l0 with a sphere) and "
            "add_weld world to d0::d0l0, Finalize: pydrake 1.51.1 has no candidate pairs (the "
            "mutant: d0::d0l0/Sphere with w0).",
        ),
        ModelMutant(
            "welded_subgraph_direct_only",
            "Finalize filters the bodies one weld joins, not every pair of a weld subgraph "
            "(A welded to B welded to C leaves A and C unfiltered).",
            "plant",
            _welded_direct_only,
            witness="URDF m with links l0 and l1 (a sphere each) both welded to the world, "
            "Finalize: pydrake 1.51.1 has no candidate pairs (the mutant: m::l0/Sphere with "
            "m::l1/Sphere).",
        ),
        ModelMutant(
            "group_report_drops_self_exclusion",
            "The group report leaves out the exclusion pair of a group that ignores itself "
            "(the filters are right).",
            "parsing",
            _report_without_self_pairs,
            witness="URDF r with group g = {a, b} ignoring g: pydrake 1.51.1 reports "
            "pairs [['r::g', 'r::g']] (the mutant: []).",
        ),
        ModelMutant(
            "group_report_of_last_parse",
            "A Parser's group report holds the groups of its last parse only (the filters are "
            "right).",
            "parsing",
            _report_of_last_parse,
            witness="URDF r1 with group g, then URDF r2 with group g by the same Parser: pydrake "
            "1.51.1 reports groups 'r1::g' and 'r2::g' (the mutant: 'r2::g' only).",
        ),
    )
}


def model_mutant_backend(name: str) -> SceneGraphBackend:
    """A fresh backend for the model mutant ``name`` (a key of MODEL_MUTANTS)."""
    return SceneGraphBackend(MODEL_MUTANTS[name].api())


def __getattr__(name: str) -> Callable[[], SceneGraphBackend]:
    """``conformance._testing.model_mutants:<name>`` as a backend spec: a zero-argument factory."""
    if name in MODEL_MUTANTS:
        return lambda: model_mutant_backend(name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
