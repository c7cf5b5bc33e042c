"""Random model files as real projects hold them: packages, includes, meshes and model directives.

A ``Scene`` is one parse: the root document (URDF, SDFormat or model
directives), parsed from a string or from a file, and every file it needs,
as the ``files`` of an ``add_models`` step (``conformance._backends.multibody``:
the case's folder is the package ``pkg``, and each folder of it with a
``package.xml`` a package of its own). ``model_scenes`` draws one:

- **layout**: every file in ``pkg``, or (``packages``) the files spread over
  the packages ``pa`` and ``pb``, each with its ``package.xml``, so that a
  file of one package names files of another (``package://pb/...``);
- **SDFormat includes** (up to two): of a model file (``package://pa/i0.sdf``,
  ``model://pa/i0.sdf``) or of a model directory (``package://pb/i1``: a
  folder with ``model.config`` and ``model.sdf``), merged (``merge="true"``)
  or not, with a ``<name>`` and a ``<pose>`` or without; the including
  model's joints, frames and groups name the included model's links and
  groups (``i0::i0l1``, or ``i0l1`` merged);
- **meshes**: small valid ``.obj`` files (a tetrahedron), and a ``.stl``
  beside it, in ``pkg/meshes``;
- **model directives**: ``add_model`` of URDF and SDFormat files,
  ``add_model_instance`` and ``add_directives`` of a second directives file
  with a ``model_namespace``, ``add_frame`` (scoped or not), ``add_weld`` of
  a free root body to the world, to a body of an earlier model or to an added
  frame, ``add_collision_filter_group`` with ``members``,
  ``member_groups``, ``ignored_collision_filter_groups`` and a group
  ``model_namespace``;
- **XML quirks** (``conformance._fuzz.xml_quirks``): one time in three the
  root XML document bent in ways tinyxml2 accepts (each quirk in about three
  of four of them).

With ``invalid``, one fault is drawn: a model fault
(``conformance._fuzz.models.FAULTS``), an XML error, an include of a file
that does not exist, or a directives fault (a namespace that no model
instance has, a weld of an unknown frame, a model name twice, a group
member no model has). Every choice has a name (``SWITCHES``): ``without``
leaves out the choices named, for an implementation that lacks them, and
``conformance._fuzz.model_coverage`` counts the same names in the files.
All of it was measured on pydrake 1.51.1, which parses every valid scene
and refuses every invalid one (``tests/test_model_fuzz.py``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import TypeVar

from hypothesis import strategies as st

from conformance._fuzz.model_data import (
    JOINT_KINDS,
    SHAPE_KINDS,
    WORLD,
    Include,
    Model,
    drops,
    geometry_names,
)
from conformance._fuzz.model_render import MESH_BASE, render
from conformance._fuzz.models import (
    FAULTS,
    GROUP_FAULTS,
    faults_for,
    free_roots,
    kinematic_trees,
    spread,
)
from conformance._fuzz.xml_quirks import XML_QUIRKS

__all__ = [
    "DIRECTIVES",
    "MESH_OBJ",
    "PACKAGES",
    "SCENE_FORMATS",
    "SWITCHES",
    "UNOBSERVED_FAULTS",
    "Scene",
    "model_scenes",
    "package_xml",
    "scene_faults",
]

DIRECTIVES = "dmd.yaml"
SCENE_FORMATS = ("urdf", "sdf", DIRECTIVES)
#: The packages a scene spreads its files over (besides ``pkg``, the case's folder).
PACKAGES = ("pa", "pb")
#: A tetrahedron: the smallest closed mesh (Drake computes its convex hull for proximity).
MESH_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
_MESH_STL = "solid t\nendsolid t\n"
_MESHES = "meshes/"
_NAMESPACE = "ns"
T = TypeVar("T")


#: Faults a scene does not draw: after a ``.stl`` collision mesh fails (MakeConvexHull),
#: pydrake 1.51.1's SceneGraph holds the geometry with proximity properties that its
#: proximity engine lacks, and GetCollisionCandidates raises IndexError('_Map_base::at'),
#: so the runner cannot observe the state after the step (1.58.0 lists the geometry's
#: pairs; measured). ``kinematic_trees(invalid=True, faults=("stl_collision",))`` draws it.
UNOBSERVED_FAULTS = frozenset({"stl_collision"})


#: The model faults that draw a frame.
_FRAME_FAULTS = frozenset({"frame_on_unknown_link", "frame_cycle", "world_frame"})


def package_xml(name: str) -> str:
    """A minimal ROS ``package.xml`` (format 2) naming the package."""
    return (
        '<?xml version="1.0"?>\n<package format="2">\n'
        f"  <name>{name}</name>\n  <version>0.0.0</version>\n"
        "  <description>fuzz</description>\n"
        '  <maintainer email="fuzz@example.com">fuzz</maintainer>\n'
        "  <license>BSD</license>\n</package>\n"
    )


def _model_config(name: str) -> str:
    return (
        '<?xml version="1.0"?>\n<model>\n'
        f"  <name>{name}</name>\n  <version>1.0</version>\n"
        '  <sdf version="1.9">model.sdf</sdf>\n</model>\n'
    )


#: The names of the choices ``model_scenes`` makes, for ``without``.
SWITCHES: tuple[str, ...] = (
    "format:urdf",
    "format:sdf",
    "format:dmd",
    "parse:file",
    "packages",
    "sdf:include-file",
    "sdf:include-dir",
    "sdf:include-model-uri",
    "sdf:merge-include",
    "sdf:include-name",
    "sdf:include-pose",
    "sdf:include-joint",
    "sdf:nested-model",
    "urdf:frame",
    "sdf:frame",
    "sdf:frame-attached_to-nested",
    "urdf:limit",
    "sdf:limit",
    "urdf:mesh-scale-1",
    "reversed-joints",
    "dmd:nested-model",
    "dmd:add_model_instance",
    "dmd:add_directives",
    "dmd:model_namespace",
    "dmd:add_frame",
    "dmd:add_weld",
    "dmd:add_collision_filter_group",
    "dmd:member_groups",
    "dmd:group-model_namespace",
    *(f"{fmt}:{shape}" for fmt in ("urdf", "sdf") for shape in SHAPE_KINDS),
    *(f"urdf:joint-{name}" for name in JOINT_KINDS),
    *(f"xml:{name}" for name in XML_QUIRKS),
    *(f"fault:{name}" for name in FAULTS),
    "fault:include-missing",
    *(
        f"fault:dmd-{name}"
        for name in ("missing-namespace", "unknown-weld-frame", "model-twice", "unknown-member")
    ),
)


@dataclass(frozen=True)
class Scene:
    """One parse: the root document and every file it needs (see the module doc).

    ``path`` is where the root is written (None: parsed from ``text``), and
    ``files`` hold it then. ``instances`` are the model instances the parse
    makes that a case may name, ``(name, model, format)`` (the name before
    any prefix); ``top`` is the first.
    """

    format: str
    text: str
    path: str | None
    files: dict[str, str] = field(default_factory=dict)
    instances: tuple[tuple[str, Model, str], ...] = ()
    #: The fault drawn (``scene_faults``), or None for a valid scene.
    fault: str | None = None

    @property
    def valid(self) -> bool:
        return self.fault is None

    @property
    def top(self) -> str:
        return self.instances[0][0]

    def bodies(self, scope: str = "") -> list[str]:
        """Every body of the instances, as ``<scope><instance>::<body>``."""
        return [
            f"{scope}{name}::{body}"
            for name, model, _ in self.instances
            for body, _ in model.scoped_bodies()
        ]

    def geometries(self, scope: str = "") -> list[str]:
        """The collision geometries whose names are certain (``models.geometry_names``)."""
        return [
            f"{scope}{g}"
            for name, model, fmt in self.instances
            for g in geometry_names(replace(model, name=name), fmt)
        ]


class _Switches:
    """The choices a scene may make: ``on(name)`` unless ``without`` names it."""

    def __init__(self, without: frozenset[str]) -> None:
        unknown = sorted(without - set(SWITCHES))
        if unknown:
            raise ValueError(f"unknown model grammar element(s): {', '.join(unknown)}")
        self.without = without

    def on(self, name: str) -> bool:
        return name not in self.without

    def shapes(self, fmt: str) -> list[str]:
        return [s for s, k in SHAPE_KINDS.items() if getattr(k, fmt) and self.on(f"{fmt}:{s}")]

    def kinds(self, fmt: str) -> list[str] | None:
        if fmt != "urdf":
            return None
        return [k for k in JOINT_KINDS if self.on(f"urdf:joint-{k}")]

    def faults(self, fmt: str) -> list[str]:
        """The model faults drawn for ``fmt``: not those of elements left out (a frame
        fault without ``<fmt>:frame``)."""
        frames = self.on(f"{fmt}:frame")
        return [
            f
            for f in FAULTS
            if self.on(f"fault:{f}")
            and f not in UNOBSERVED_FAULTS
            and (frames or f not in _FRAME_FAULTS)
        ]


def _spread(draw: st.DrawFn, items: Sequence[T]) -> T:
    """One of ``items``, about evenly (``models.spread``)."""
    return draw(spread(items))


def _choice(draw: st.DrawFn, on: bool, share: int = 2) -> bool:
    """True one time in ``share`` if the choice is on (False shrinks first)."""
    return on and draw(st.integers(0, share - 1)) == share - 1


def _package(draw: st.DrawFn, packages: bool) -> str:
    """Where a file goes: ``""`` (pkg's root) or ``pa/``, ``pb/``."""
    if not packages:
        return ""
    return draw(st.sampled_from(PACKAGES)) + "/"


def _uri(folder: str, path: str, scheme: str = "package") -> str:
    """The URI of ``path`` in ``folder`` (``""``: the package ``pkg``)."""
    package = folder.rstrip("/") or "pkg"
    return f"{scheme}://{package}/{path}"


def _uri_of(path: str) -> str:
    """The ``package://`` URI of a file of the scene (``pa/x`` in ``pa``, else in ``pkg``)."""
    folder, _, name = path.rpartition("/")
    return _uri(f"{folder}/" if folder in PACKAGES else "", path if not folder else name)


def _mesh_files(texts: Sequence[str]) -> dict[str, str]:
    """The mesh files the texts name."""
    files = {}
    for name, content in (("mesh.obj", MESH_OBJ), ("mesh.stl", _MESH_STL)):
        if any(f"{_MESHES}{name}" in text for text in texts):
            files[f"{_MESHES}{name}"] = content
    return files


def _with_packages(files: dict[str, str]) -> dict[str, str]:
    """``files`` with a ``package.xml`` in each package folder they use."""
    used = sorted({path.split("/", 1)[0] for path in files if path.split("/", 1)[0] in PACKAGES})
    return {**{f"{p}/package.xml": package_xml(p) for p in used}, **files}


# ------------------------------------------------------------------ XML scenes
@st.composite
def _includes(
    draw: st.DrawFn, switches: _Switches, packages: bool, shapes: Sequence[str], least: int
) -> tuple[list[Include], list[dict[str, str]]]:
    """Up to two includes (at least ``least``) and the files each names."""
    ways = [w for w in ("file", "dir") if switches.on(f"sdf:include-{w}")]
    if not ways:
        return [], []
    includes, files = [], []
    for k in range(draw(st.integers(least, 2))):
        name = f"i{k}"
        model = draw(
            kinematic_trees(
                formats=("sdf",),
                model_names=(name,),
                max_bodies=3,
                max_groups=2,
                attach_to_world=False,
                shapes=shapes,
                prefix=name,
            )
        )
        way = draw(st.sampled_from(ways))
        folder = _package(draw, packages)
        scheme = "package"
        if folder and _choice(draw, switches.on("sdf:include-model-uri")):
            scheme = "model"
        if way == "file":
            files.append({f"{folder}{name}.sdf": render(model, "sdf")})
            uri = _uri(folder, f"{name}.sdf", scheme)
        else:
            files.append(
                {
                    f"{folder}{name}/model.sdf": render(model, "sdf"),
                    f"{folder}{name}/model.config": _model_config(name),
                }
            )
            uri = _uri(folder, name, scheme)
        includes.append(
            Include(
                model,
                uri,
                name=f"r{k}" if _choice(draw, switches.on("sdf:include-name")) else None,
                pose=_choice(draw, switches.on("sdf:include-pose")),
                merge=_choice(draw, switches.on("sdf:merge-include")),
            )
        )
    return includes, files


@st.composite
def _xml_scene(
    draw: st.DrawFn, fmt: str, switches: _Switches, packages: bool, fault: str | None
) -> Scene:
    sdf = fmt == "sdf"
    shapes = switches.shapes(fmt)
    includes: list[Include] = []
    included: list[dict[str, str]] = []
    if sdf:
        least = 1 if fault == "include-missing" else 0
        includes, included = draw(_includes(switches, packages, shapes, least))
    if fault == "include-missing":  # a name no scene writes: a case's files stay for later steps
        includes[0] = replace(includes[0], uri=f"{includes[0].uri}_gone")
        included = included[1:]
    broken, faults = _model_faults(fault, switches, fmt)
    model = draw(
        kinematic_trees(
            formats=(fmt,),
            joint_kinds=switches.kinds(fmt),
            invalid=broken,
            max_nested=2 if sdf and switches.on("sdf:nested-model") else 0,
            shapes=shapes,
            max_frames=3 if switches.on(f"{fmt}:frame") else 0,
            frames_into_children=switches.on("sdf:frame-attached_to-nested"),
            joint_attributes=switches.on(f"{fmt}:limit"),
            includes=includes,
            joints_into_includes=switches.on("sdf:include-joint"),
            faults=faults,
            one_value_scale=switches.on("urdf:mesh-scale-1"),
            reversed_joints=switches.on("reversed-joints"),
        )
    )
    text = render(model, fmt, mesh_base=MESH_BASE)
    if fault is not None and fault.startswith("xml:"):
        text = XML_QUIRKS[fault.removeprefix("xml:")].apply(text)
    quirks = [q for q in XML_QUIRKS.values() if q.accepted and switches.on(f"xml:{q.name}")]
    if fault is None and quirks and _choice(draw, True, 3):
        # Each quirk in about three of four bent documents (they combine: xml_quirks); a
        # shrunk one keeps the quirks a finding needs.
        for quirk in quirks:
            if draw(st.integers(0, 3)):
                text = quirk.apply(text)
    files = {path: content for named in included for path, content in named.items()}
    files |= _mesh_files([text, *files.values()])
    path = None
    if _choice(draw, switches.on("parse:file")):
        path = f"{_package(draw, packages)}{model.name}.{fmt}"
        files[path] = text
    return Scene(fmt, text, path, _with_packages(files), ((model.name, model, fmt),), fault)


# ------------------------------------------------------------------ directives
def _yaml_list(items: Sequence[str]) -> str:
    return "[" + ", ".join(items) + "]"


#: A model instance of a directives scene: (name, model, the format of its file).
_Instance = tuple[str, Model, str]


@dataclass
class _Directives:
    """A directives document being written, with the model instances it adds."""

    lines: list[str] = field(default_factory=lambda: ["directives:"])
    instances: list[_Instance] = field(default_factory=list)

    def add(self, directive: str, **keys: str) -> None:
        self.lines.append(f"- {directive}:")
        self.lines.extend(f"    {key}: {value}" for key, value in keys.items())

    def text(self) -> str:
        return "\n".join(self.lines) + "\n"


@dataclass(frozen=True)
class _Options:
    """What a directives scene may draw."""

    switches: _Switches
    packages: bool


@st.composite
def _directive_models(
    draw: st.DrawFn, options: _Options, prefix: str, count: int, *, fault: bool = False
) -> tuple[list[tuple[_Instance, str]], dict[str, str]]:
    """``count`` models in files, each with its URI, and the files (the first with a model
    fault (``FAULTS``) if ``fault``)."""
    switches = options.switches
    formats = [f for f in ("urdf", "sdf") if switches.on(f"format:{f}")] or ["urdf"]
    out, files = [], {}
    for k in range(count):
        fmt = draw(st.sampled_from(formats))
        model = draw(
            kinematic_trees(
                formats=(fmt,),
                max_bodies=3,
                max_groups=2,
                joint_kinds=switches.kinds(fmt),
                shapes=switches.shapes(fmt),
                max_nested=1 if fmt == "sdf" and switches.on("dmd:nested-model") else 0,
                invalid=fault and k == 0,
                faults=switches.faults(fmt),
                one_value_scale=switches.on("urdf:mesh-scale-1"),
                reversed_joints=switches.on("reversed-joints"),
                # A URDF joint from the world adds a frame '<joint>_parent' to the world's
                # model instance: two models' joints must differ in name (measured).
                prefix=f"{prefix}{k}",
            )
        )
        folder = _package(draw, options.packages)
        path = f"{folder}{prefix}{k}.{fmt}"
        files[path] = render(model, fmt)
        out.append(((f"{prefix}{k}", model, fmt), _uri_of(path)))
    return out, files


def _kept_groups(name: str, model: Model, fmt: str) -> list[str]:
    """The instance's groups that its format keeps, scoped (``d0::g1``, ``d0::n0::g0``)."""
    return [f"{name}::{g}" for g, group in model.all_groups() if not drops(group, fmt)]


@st.composite
def _collision_filter_groups(
    draw: st.DrawFn,
    doc: _Directives,
    switches: _Switches,
    instances: Sequence[_Instance],
    extra_groups: Sequence[str],
) -> None:
    """Up to three ``add_collision_filter_group``: G0, G1... over the bodies and groups of
    ``instances`` and ``extra_groups`` (see the module doc)."""
    bodies = [f"{n}::{b}" for n, m, _ in instances for b, _ in m.scoped_bodies()]
    kept = [g for n, m, f in instances for g in _kept_groups(n, m, f)] + list(extra_groups)
    names = [f"G{k}" for k in range(draw(st.integers(0, 3)))]
    spaced = [
        _choice(draw, switches.on("dmd:group-model_namespace"), 4) and bool(doc.instances)
        for _ in names
    ]
    own = [n for n, namespaced in zip(names, spaced, strict=True) if not namespaced]
    for name, namespaced in zip(names, spaced, strict=True):
        keys: dict[str, str] = {"name": name}
        if namespaced:  # names relative to one model, which owns the group
            instance, model, fmt = draw(st.sampled_from(doc.instances))
            keys["model_namespace"] = instance
            members = [b for b, _ in model.scoped_bodies()]
            groups = [g.removeprefix(f"{instance}::") for g in _kept_groups(instance, model, fmt)]
            ignorable = [name, *groups]
        else:
            members, groups, ignorable = bodies, [*kept, *own], [*kept, *own]
        picked = draw(st.lists(st.sampled_from(members), max_size=2, unique=True))
        member_groups: list[str] = []
        if groups and switches.on("dmd:member_groups"):
            member_groups = draw(st.lists(st.sampled_from(groups), max_size=2, unique=True))
        if not picked and not member_groups:
            picked = members[:1]
        keys["members"] = _yaml_list(picked)
        if member_groups:
            keys["member_groups"] = _yaml_list(member_groups)
        ignored = draw(st.lists(st.sampled_from(ignorable), max_size=2, unique=True))
        if ignored:
            keys["ignored_collision_filter_groups"] = _yaml_list(ignored)
        doc.add("add_collision_filter_group", **keys)


@st.composite
def _sub_directives(
    draw: st.DrawFn, options: _Options
) -> tuple[str, list[_Instance], dict[str, str], list[str]]:
    """A second directives file: its path, instances (unscoped), files and groups."""
    switches = options.switches
    models, files = draw(_directive_models(options, "s", 1))
    doc = _Directives()
    (instance, uri) = models[0]
    name, model, _ = instance
    doc.add("add_model", name=name, file=uri)
    doc.instances.append(instance)
    roots = free_roots(model)
    if roots and _choice(draw, switches.on("dmd:add_weld")):
        doc.add("add_weld", parent=WORLD, child=f"{name}::{roots[0]}")
    groups: list[str] = []
    if _choice(draw, switches.on("dmd:add_collision_filter_group")):
        member = f"{name}::{model.bodies[0].name}"
        doc.add("add_collision_filter_group", name="H0", members=_yaml_list([member]))
        groups.append("H0")
    path = f"{_package(draw, options.packages)}sub.dmd.yaml"
    files[path] = doc.text()
    return path, doc.instances, files, groups


@st.composite
def _added_frame(draw: st.DrawFn, doc: _Directives) -> tuple[str, str] | None:
    """An ``add_frame`` on the world or a body, scoped or not: (frame, its instance), or
    None on the world."""
    name, model, _ = draw(st.sampled_from(doc.instances))
    base = draw(st.sampled_from([WORLD, *(f"{name}::{b.name}" for b in model.bodies)]))
    scoped = base != WORLD and draw(st.booleans())
    frame = f"{name}::f0" if scoped else "f0"
    doc.lines += ["- add_frame:", f"    name: {frame}", "    X_PF:", f"      base_frame: {base}"]
    doc.lines.append("      translation: [0, 0, 0.1]")
    return None if base == WORLD else (f"{name}::f0", name)


def _welds(draw: st.DrawFn, doc: _Directives, frame: tuple[str, str] | None) -> None:
    """``add_weld`` of free root bodies, each model's once, to the world, a body of an
    earlier model, or the added frame once its model is earlier."""
    parents: list[str] = [WORLD]
    for name, model, _ in doc.instances:
        roots = free_roots(model)
        if roots and draw(st.integers(0, 2)) == 2:
            parent = draw(st.sampled_from(parents))
            doc.add("add_weld", parent=parent, child=f"{name}::{draw(st.sampled_from(roots))}")
        parents += [f"{name}::{b.name}" for b in model.bodies]
        if frame is not None and frame[1] == name:
            parents.append(frame[0])


_DMD_FAULTS = ("missing-namespace", "unknown-weld-frame", "model-twice", "unknown-member")


def _directives_fault(doc: _Directives, fault: str, uri: str) -> None:
    """The directives fault (``_DMD_FAULTS``) at the end of ``doc``; ``uri`` is d0's file."""
    name = doc.instances[0][0]
    if fault == "missing-namespace":
        doc.add("add_directives", file="package://pkg/none.dmd.yaml", model_namespace="nope")
    elif fault == "unknown-weld-frame":
        doc.add("add_weld", parent=WORLD, child="zz::l0")
    elif fault == "model-twice":
        doc.add("add_model", name=name, file=uri)
    else:
        doc.add("add_collision_filter_group", name="GX", members=_yaml_list([f"{name}::zz"]))


@st.composite
def _directives_scene(draw: st.DrawFn, options: _Options, fault: str | None) -> Scene:
    switches = options.switches
    models, files = draw(
        _directive_models(options, "d", draw(st.integers(1, 3)), fault=fault == "model:any")
    )
    doc = _Directives()
    for instance, uri in models:
        doc.add("add_model", name=instance[0], file=uri)
        doc.instances.append(instance)
    instances = list(doc.instances)
    extra_groups: list[str] = []
    if _choice(draw, switches.on("dmd:add_directives")):
        path, sub_instances, sub_files, sub_groups = draw(_sub_directives(options))
        files |= sub_files
        scope = ""
        if _choice(draw, switches.on("dmd:model_namespace")):
            scope = f"{_NAMESPACE}::"
            doc.add("add_model_instance", name=_NAMESPACE)
        keys = {"file": _uri_of(path)}
        if scope:
            keys["model_namespace"] = _NAMESPACE
        doc.add("add_directives", **keys)
        instances += [(f"{scope}{n}", m, f) for n, m, f in sub_instances]
        extra_groups = [f"{scope}{g}" for g in sub_groups]
    elif _choice(draw, switches.on("dmd:add_model_instance"), 4):
        doc.add("add_model_instance", name=_NAMESPACE)
    frame = draw(_added_frame(doc)) if _choice(draw, switches.on("dmd:add_frame")) else None
    if switches.on("dmd:add_weld"):
        _welds(draw, doc, frame)
    if switches.on("dmd:add_collision_filter_group"):
        draw(_collision_filter_groups(doc, switches, instances, extra_groups))
    if fault is not None and fault.startswith("dmd:"):
        _directives_fault(doc, fault.removeprefix("dmd:"), models[0][1])
    text = doc.text()
    files |= _mesh_files(list(files.values()))
    root = None
    if _choice(draw, switches.on("parse:file")):
        root = f"{_package(draw, options.packages)}main.dmd.yaml"
        files[root] = text
    return Scene(DIRECTIVES, text, root, _with_packages(files), tuple(instances), fault)


# ------------------------------------------------------------------ scenes
def scene_faults(fmt: str, without: frozenset[str] = frozenset()) -> list[str]:
    """The faults an invalid scene of ``fmt`` may have, in their order (``_faults_of``)."""
    return _faults_of(fmt, _Switches(without))


def _faults_of(fmt: str, switches: _Switches) -> list[str]:
    """The faults a scene of ``fmt`` may have: ``dmd:<fault>``, ``xml:<quirk>`` (a quirk
    tinyxml2 rejects), ``include-missing``, or ``model:<fault>`` (``model:group``: one of
    the group faults; ``model:any``: any model fault)."""
    if fmt == DIRECTIVES:
        return ["model:any", *(f"dmd:{f}" for f in _DMD_FAULTS if switches.on(f"fault:dmd-{f}"))]
    xml = [
        f"xml:{q.name}"
        for q in XML_QUIRKS.values()
        if not q.accepted and switches.on(f"xml:{q.name}")
    ]
    drawn = switches.faults(fmt)
    faults = [f for f in faults_for(fmt) if f in drawn and f not in GROUP_FAULTS]
    if any(switches.on(f"fault:{f}") for f in GROUP_FAULTS):
        faults.insert(0, "group")
    kinds = [*xml, *(f"model:{f}" for f in faults)]
    if fmt == "sdf" and switches.on("fault:include-missing"):
        kinds.append("include-missing")
    return kinds or ["model:any"]


def _model_faults(fault: str | None, switches: _Switches, fmt: str) -> tuple[bool, list[str]]:
    """Whether a model is drawn broken, and with which faults (``_faults_of``)."""
    if fault is None or not fault.startswith("model:"):
        return False, switches.faults(fmt)
    name = fault.removeprefix("model:")
    if name == "group":
        return True, [f for f in GROUP_FAULTS if switches.on(f"fault:{f}")]
    if name == "any":
        return True, switches.faults(fmt)
    return True, [name]


@st.composite
def model_scenes(
    draw: st.DrawFn,
    *,
    formats: Sequence[str] = SCENE_FORMATS,
    invalid: bool = False,
    without: frozenset[str] = frozenset(),
    fault_index: int | None = None,
) -> Scene:
    """One scene (see the module doc): valid, or with ``invalid`` one fault, the
    ``fault_index``-th (modulo their number) of the format's faults if given, else any."""
    switches = _Switches(without)
    usable = [f for f in formats if switches.on(f"format:{f.split('.')[0]}")]
    fmt = _spread(draw, usable or list(formats))
    packages = _choice(draw, switches.on("packages"))
    fault = None
    if invalid:
        faults = _faults_of(fmt, switches)
        fault = _spread(draw, faults) if fault_index is None else faults[fault_index % len(faults)]
    if fmt == DIRECTIVES:
        return draw(_directives_scene(_Options(switches, packages), fault))
    return draw(_xml_scene(fmt, switches, packages, fault))
