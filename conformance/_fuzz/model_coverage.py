"""What ``fuzz --models`` reached: the grammar of the model files drawn, and the reference's errors.

Every feature is read from a case's commands (the texts and files of its
``add_models`` steps, the other steps) and from the reference's results,
never from how the generator chose them, so the table reads the same for
any generator. A feature counts once per case that reaches it.

=============================== ==============================================================
feature                         a case reached it when
=============================== ==============================================================
format:urdf, :sdf, :dmd         an add_models step parses a document of that format
parse:text, parse:file          ... from a string, from a file
parse:prefix, parse:auto_renam  ... with a model name prefix, with SetAutoRenaming
ing, parse:reuse_parser         ... with the last add_models' Parser
parse:again                     a case parses twice or more
packages>=2                     its files hold two or more ``package.xml``
package-across                  a file of one package names a file of another
                                (``package://``/``model://``; the case's folder is ``pkg``)
sdf:nested-model                a ``<model>`` in a ``<model>``
sdf:include-file, -dir          an ``<include>`` of a model file, of a model directory
sdf:include-model-uri           an ``<include>`` by ``model://``
sdf:merge-include               ``<include merge="true">``
sdf:include-name, -pose         an ``<include>`` with ``<name>``, with ``<pose>``
sdf:include-joint               a joint naming a link of an included model (``i0::l1``)
sdf:frame, -attached_to,        a ``<frame>``; with ``attached_to``; attached into a nested or
-attached_to-nested,            included model (``n0``, ``n0::l1``); with ``<pose
-relative_to                    relative_to>``
sdf:joint-via-frame             a joint whose parent or child is a ``<frame>``
sdf:<shape>, urdf:<shape>       a geometry of that shape (``sdf:drake:capsule``, ``urdf:mesh``)
{fmt}:mesh-declare_convex       a mesh with ``<drake:declare_convex/>``
urdf:mesh-scale-1, -3           a URDF mesh scaled by one value, by three
sdf:mesh-scale                  an SDFormat mesh with ``<scale>``
urdf:joint-<type>               a URDF joint of the type (``urdf:drake:joint-planar``: the
                                ``<drake:joint>`` spelling of planar)
sdf:joint-<type>                an SDFormat joint of the type
urdf:joint-world-child          a URDF joint whose child is the world
{fmt}:limit, {fmt}:dynamics     a joint with limits, with a damping
urdf:frame, urdf:frame-world    a URDF ``<frame>``; one on the world
{fmt}:collision_filter_group    a group; ``{fmt}:member_group``: one with a member group
dmd:<directive>                 a directives file with it (``dmd:add_weld``...)
dmd:member_groups, dmd:ignored  an ``add_collision_filter_group`` with ``member_groups``,
_collision_filter_groups        with ``ignored_collision_filter_groups``
dmd:model_namespace             an ``add_directives`` with a ``model_namespace``
dmd:group-model_namespace       an ``add_collision_filter_group`` with one
xml:<quirk>, xml:malformed      a root document bent by the quirk (``xml_quirks``); one that
                                tinyxml2 rejects
rename, rename-then-parse,      ``rename_model_instance``; then an add_models; with the same
rename-reuse-parser             Parser (Drake issue #21316)
report:groups                   a ``collision_filter_groups`` report that has a group
report:inventory-finalized      a ``model_inventory`` after Finalize
error:<kind>                    the reference answered an error of that ``ErrorKind``
parse-error:<category>          ... an add_models error of that category (``ERROR_CATEGORIES``)
=============================== ==============================================================
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from conformance._fuzz.coverage import Coverage
from conformance._fuzz.model_data import JOINT_KINDS, SHAPE_KINDS
from conformance._fuzz.model_scenes import PACKAGES
from conformance._fuzz.xml_quirks import XML_QUIRKS, detect_quirks
from conformance.protocol import Command, ErrorKind, Result

__all__ = [
    "ERROR_CATEGORIES",
    "MODEL_FEATURES",
    "ModelCoverage",
    "case_features",
    "error_category",
    "expected_model_features",
]

#: An add_models error's category, by the first pattern its message matches (pydrake
#: 1.51.1's messages).
ERROR_CATEGORIES: tuple[tuple[str, re.Pattern[str]], ...] = tuple(
    (name, re.compile(pattern))
    for name, pattern in (
        ("xml", r"XML_ERROR"),
        ("reserved-name", r"is reserved"),
        ("damping", r"damping"),
        ("limits", r"lower limit|pos_lower_limits"),
        ("mesh-hull", r"MakeConvexHull"),
        ("mesh-scale", r"values for attribute scale"),
        ("frame-cycle", r"cycle detected"),
        ("namespace", r"Namespace '.*' does not exist"),
        ("model-name-clash", r"already contains a model instance named"),
        ("element-name-clash", r"already contains a (?:frame|joint|body) named|Non-unique name"),
        ("unknown-model-instance", r"There is no model instance named"),
        (
            "group",
            r"collision filter group|has no members|already been defined|outside the|"
            r"cannot be a scoped name",
        ),
        (
            "unknown-name",
            r"Could not find link|body with name|frame with name|specified invalid|"
            r"does not match a nested model",
        ),
        ("missing-file", r"Unable to find uri|does not exist|Could not find model.config"),
    )
)

#: Error categories of faults the scenes do not draw (``model_scenes.UNOBSERVED_FAULTS``).
_UNDRAWN = frozenset({"mesh-hull"})
_URDF_JOINTS = ("fixed", "revolute", "continuous", "prismatic", "floating", "planar")
_DMD_DIRECTIVES = (
    "add_model",
    "add_model_instance",
    "add_frame",
    "add_weld",
    "add_directives",
    "add_collision_filter_group",
)

#: Every feature of the table (the module doc), in the order the table lists them.
MODEL_FEATURES: tuple[str, ...] = (
    "format:urdf",
    "format:sdf",
    "format:dmd",
    "parse:text",
    "parse:file",
    "parse:prefix",
    "parse:auto_renaming",
    "parse:reuse_parser",
    "parse:again",
    "packages>=2",
    "package-across",
    "sdf:nested-model",
    "sdf:include-file",
    "sdf:include-dir",
    "sdf:include-model-uri",
    "sdf:merge-include",
    "sdf:include-name",
    "sdf:include-pose",
    "sdf:include-joint",
    "sdf:frame",
    "sdf:frame-attached_to",
    "sdf:frame-attached_to-nested",
    "sdf:frame-relative_to",
    "sdf:joint-via-frame",
    *(f"sdf:{shape}" for shape, kind in SHAPE_KINDS.items() if kind.sdf and shape != "convex"),
    "sdf:mesh-declare_convex",
    "sdf:mesh-scale",
    *(f"sdf:joint-{kind.sdf}" for kind in JOINT_KINDS.values() if kind.sdf is not None),
    "sdf:limit",
    "sdf:dynamics",
    "sdf:collision_filter_group",
    "sdf:member_group",
    *(f"urdf:{shape}" for shape, kind in SHAPE_KINDS.items() if kind.urdf and shape != "convex"),
    "urdf:mesh-declare_convex",
    "urdf:mesh-scale-1",
    "urdf:mesh-scale-3",
    *(f"urdf:joint-{name}" for name in _URDF_JOINTS),
    *(f"urdf:joint-{name}" for name in ("ball", "universal", "screw", "curvilinear")),
    "urdf:drake:joint-planar",
    "urdf:joint-world-child",
    "urdf:limit",
    "urdf:dynamics",
    "urdf:frame",
    "urdf:frame-world",
    "urdf:collision_filter_group",
    "urdf:member_group",
    *(f"dmd:{name}" for name in _DMD_DIRECTIVES),
    "dmd:member_groups",
    "dmd:ignored_collision_filter_groups",
    "dmd:model_namespace",
    "dmd:group-model_namespace",
    *(f"xml:{name}" for name in XML_QUIRKS),
    "xml:malformed",
    "rename",
    "rename-then-parse",
    "rename-reuse-parser",
    "report:groups",
    "report:inventory-finalized",
    "error:other",
    "error:assertion",
    *(f"parse-error:{name}" for name, _ in ERROR_CATEGORIES if name not in _UNDRAWN),
)

#: A generator switch (``model_scenes.SWITCHES``) → the features it alone brings.
_BY_SWITCH: Mapping[str, tuple[str, ...]] = {
    "format:urdf": (*(f for f in MODEL_FEATURES if f.startswith("urdf:")), "format:urdf"),
    "format:sdf": (*(f for f in MODEL_FEATURES if f.startswith("sdf:")), "format:sdf"),
    "format:dmd": (*(f for f in MODEL_FEATURES if f.startswith("dmd:")), "format:dmd"),
    "packages": ("packages>=2", "package-across"),
    "sdf:frame": (
        "sdf:frame",
        "sdf:frame-attached_to",
        "sdf:frame-attached_to-nested",
        "sdf:frame-relative_to",
        "sdf:joint-via-frame",
    ),
    "urdf:frame": ("urdf:frame", "urdf:frame-world"),
    "sdf:limit": ("sdf:limit", "sdf:dynamics"),
    "urdf:limit": ("urdf:limit", "urdf:dynamics"),
    "sdf:convex": ("sdf:mesh-declare_convex",),
    "urdf:convex": ("urdf:mesh-declare_convex",),
    "sdf:mesh": ("sdf:mesh", "sdf:mesh-scale"),
    "urdf:mesh": ("urdf:mesh", "urdf:mesh-scale-1", "urdf:mesh-scale-3"),
    "urdf:joint-drake_planar": ("urdf:drake:joint-planar",),
    "rename-then-parse": ("rename", "rename-then-parse", "rename-reuse-parser"),
    "reversed-joints": ("urdf:joint-world-child",),
    "fault:two_value_scale": ("parse-error:mesh-scale",),
    "fault:frame_cycle": ("parse-error:frame-cycle",),
    "fault:negative_damping": ("parse-error:damping",),
    "fault:inverted_limits": ("parse-error:limits",),
    "fault:include-missing": ("parse-error:missing-file",),
    "fault:dmd-missing-namespace": ("parse-error:namespace",),
}


def expected_model_features(
    without: Iterable[str] = (), *, groups_report: bool = True
) -> list[str]:
    """The features a run should reach: ``MODEL_FEATURES`` less those that only the grammar
    elements of ``without`` bring, and the group report's without ``groups_report``."""
    gone: set[str] = set()
    for name in without:
        gone.update(_BY_SWITCH.get(name, (name,)))
    if not groups_report:
        gone.add("report:groups")
    return [f for f in MODEL_FEATURES if f not in gone]


def error_category(message: str) -> str:
    """The ``ERROR_CATEGORIES`` name of an add_models error message (``other`` if none)."""
    for name, pattern in ERROR_CATEGORIES:
        if pattern.search(message):
            return name
    return "other"


# ------------------------------------------------------------------ XML
@dataclass
class _Element:
    """An element of a tolerant parse (malformed text too): tag, attributes, first text."""

    tag: str
    attrs: dict[str, str]
    parent: _Element | None = None
    text: str = ""
    children: list[_Element] = field(default_factory=list)

    def child(self, tag: str) -> _Element | None:
        return next((c for c in self.children if c.tag == tag), None)

    def walk(self) -> Iterator[_Element]:
        yield self
        for child in self.children:
            yield from child.walk()


_TOKEN = re.compile(
    r"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<[?!][^>]*>|<(/?)([A-Za-z_][\w:.-]*)([^>]*?)(/?)>", re.S
)
_ATTRIBUTE = re.compile(r'([\w:.-]+)\s*=\s*"([^"]*)"')


def _elements(text: str) -> _Element:
    """The element tree of ``text``, read leniently: unclosed and mismatched tags too."""
    root = _Element("", {})
    current = root
    for match in _TOKEN.finditer(text):
        closing, tag, attributes, empty = match.groups()
        if tag is None:
            continue
        if closing:
            node: _Element | None = current
            while node is not None and node.tag != tag:
                node = node.parent
            if node is not None and node.parent is not None:
                current = node.parent
            continue
        element = _Element(tag, dict(_ATTRIBUTE.findall(attributes)), current)
        end = text.find("<", match.end())
        element.text = text[match.end() : end if end >= 0 else len(text)].strip()
        current.children.append(element)
        if not empty:
            current = element
    return root


def _shape_features(fmt: str, geometry: _Element) -> Iterator[str]:
    for shape in geometry.children:
        if shape.tag in SHAPE_KINDS:
            yield f"{fmt}:{shape.tag}"
        if shape.tag != "mesh":
            continue
        if shape.child("drake:declare_convex") is not None:
            yield f"{fmt}:mesh-declare_convex"
        scale = shape.attrs.get("scale") if fmt == "urdf" else None
        if scale is not None:
            yield f"urdf:mesh-scale-{len(scale.split())}"
        if fmt == "sdf" and shape.child("scale") is not None:
            yield "sdf:mesh-scale"


def _group_features(fmt: str, element: _Element) -> Iterator[str]:
    if element.tag == "drake:collision_filter_group":
        yield f"{fmt}:collision_filter_group"
        if element.child("drake:member_group") is not None:
            yield f"{fmt}:member_group"


def _urdf_features(text: str) -> Iterator[str]:
    for element in _elements(text).walk():
        yield from _group_features("urdf", element)
        if element.tag == "geometry":
            yield from _shape_features("urdf", element)
        elif element.tag in ("joint", "drake:joint") and element.parent is not None:
            if element.parent.tag != "robot":
                continue
            spelling = "drake:joint" if element.tag == "drake:joint" else "joint"
            joint_type = element.attrs.get("type", "")
            yield (
                f"urdf:drake:joint-{joint_type}"
                if spelling == "drake:joint" and joint_type == "planar"
                else f"urdf:joint-{joint_type}"
            )
            child = element.child("child")
            if child is not None and child.attrs.get("link") == "world":
                yield "urdf:joint-world-child"
            if element.child("limit") is not None:
                yield "urdf:limit"
            if element.child("dynamics") is not None:
                yield "urdf:dynamics"
        elif element.tag == "frame" and element.parent is not None:
            yield "urdf:frame"
            if element.attrs.get("link") == "world":
                yield "urdf:frame-world"


def _include_name(include: _Element) -> str:
    """An include's name in its parent: ``<name>``, else its URI's last segment's stem."""
    name = include.child("name")
    if name is not None and name.text:
        return name.text
    uri = include.child("uri")
    last = (uri.text if uri is not None else "").rstrip("/").rsplit("/", 1)[-1]
    return last.split(".", 1)[0]


def _include_features(include: _Element) -> Iterator[str]:
    uri = include.child("uri")
    path = uri.text if uri is not None else ""
    yield "sdf:include-file" if path.endswith((".sdf", ".urdf")) else "sdf:include-dir"
    if path.startswith("model://"):
        yield "sdf:include-model-uri"
    if include.attrs.get("merge") == "true":
        yield "sdf:merge-include"
    if include.child("name") is not None:
        yield "sdf:include-name"
    if include.child("pose") is not None:
        yield "sdf:include-pose"


def _frame_features(frame: _Element, children: set[str]) -> Iterator[str]:
    """An SDFormat frame's features; ``children``: the names of the model's nested and
    (not merged) included models."""
    yield "sdf:frame"
    target = frame.attrs.get("attached_to")
    if target is not None:
        yield "sdf:frame-attached_to"
        if "::" in target or target in children:
            yield "sdf:frame-attached_to-nested"
    pose = frame.child("pose")
    if pose is not None and "relative_to" in pose.attrs:
        yield "sdf:frame-relative_to"


def _joint_features(joint: _Element, frames: set[str], included: set[str]) -> Iterator[str]:
    yield f"sdf:joint-{joint.attrs.get('type', '')}"
    ends = [joint.child(end) for end in ("parent", "child")]
    names = [end.text for end in ends if end is not None]
    if any(name in frames for name in names):
        yield "sdf:joint-via-frame"
    if any(name.split("::")[0] in included for name in names if "::" in name):
        yield "sdf:include-joint"
    axis = joint.child("axis")
    if axis is not None and axis.child("limit") is not None:
        yield "sdf:limit"
    if axis is not None and axis.child("dynamics") is not None:
        yield "sdf:dynamics"


def _sdf_model_features(model: _Element) -> Iterator[str]:
    """The features of one ``<model>`` element's own children."""
    frames = {f.attrs.get("name", "") for f in model.children if f.tag == "frame"}
    inner = {m.attrs.get("name", "") for m in model.children if m.tag == "model"}
    includes = [c for c in model.children if c.tag == "include"]
    included = {_include_name(i) for i in includes if i.attrs.get("merge") != "true"}
    for include in includes:
        yield from _include_features(include)
    for element in model.children:
        if element.tag == "model":
            yield "sdf:nested-model"
        elif element.tag == "frame":
            yield from _frame_features(element, inner | included)
        elif element.tag == "joint":
            yield from _joint_features(element, frames, included)


def _sdf_features(text: str) -> Iterator[str]:
    for element in _elements(text).walk():
        yield from _group_features("sdf", element)
        if element.tag == "geometry":
            yield from _shape_features("sdf", element)
        elif element.tag == "model":
            yield from _sdf_model_features(element)


# ------------------------------------------------------------------ directives
_DIRECTIVE = re.compile(r"^- (\w+):", re.M)


def _dmd_features(text: str) -> Iterator[str]:
    directive = ""
    for line in text.splitlines():
        match = _DIRECTIVE.match(line)
        if match is not None:
            directive = match.group(1)
            yield f"dmd:{directive}"
            continue
        key = line.strip().split(":", 1)[0]
        if directive == "add_collision_filter_group" and key in (
            "member_groups",
            "ignored_collision_filter_groups",
        ):
            yield f"dmd:{key}"
        elif key == "model_namespace":
            yield (
                "dmd:model_namespace"
                if directive == "add_directives"
                else "dmd:group-model_namespace"
            )


# ------------------------------------------------------------------ files
def _format(path: str) -> str:
    for fmt in ("urdf", "sdf", "dmd.yaml"):
        if path.endswith(f".{fmt}"):
            return fmt
    return ""


_DOCUMENT_FEATURES = {"urdf": _urdf_features, "sdf": _sdf_features, "dmd.yaml": _dmd_features}
_URI = re.compile(r"(?:package|model)://([\w.-]+)/")


def _package_features(files: Mapping[str, str], root: str) -> Iterator[str]:
    """``packages>=2`` and ``package-across`` (``root``: a document parsed from a string, in
    the package ``pkg`` as far as this goes)."""
    packages = {p.split("/", 1)[0] for p in files if p.endswith("/package.xml")} & set(PACKAGES)
    if len(packages) >= 2:
        yield "packages>=2"
    for path, text in [*files.items(), ("", root)]:
        folder = path.split("/", 1)[0] if "/" in path else ""
        home = folder if folder in packages else "pkg"
        if any(name != home for name in _URI.findall(text)):
            yield "package-across"
            return


def _parse_features(args: Mapping[str, Any]) -> Iterator[str]:
    """The features of one add_models step's arguments and documents."""
    files: dict[str, str] = dict(args.get("files", {}))
    if "path" in args:
        yield "parse:file"
        root, fmt = files.get(args["path"], ""), _format(args["path"])
    else:
        yield "parse:text"
        root, fmt = args.get("text", ""), args.get("format", "")
    yield f"format:{fmt.split('.')[0]}"
    for key in ("prefix", "auto_renaming", "reuse_parser"):
        if args.get(key):
            yield f"parse:{key}"
    if fmt in ("urdf", "sdf"):
        quirks = detect_quirks(root)
        yield from (f"xml:{q}" for q in quirks)
        if any(not XML_QUIRKS[q].accepted for q in quirks):
            yield "xml:malformed"
    documents = [(fmt, root)] + [
        (_format(path), text) for path, text in files.items() if path != args.get("path")
    ]
    for document_format, text in documents:
        read = _DOCUMENT_FEATURES.get(document_format)
        if read is not None:
            yield from read(text)
    yield from _package_features(files, "" if "path" in args else root)


def case_features(commands: Sequence[Command], results: Sequence[Result]) -> set[str]:
    """The features one case reached (see the module doc), given the reference's results."""
    reached: set[str] = set()
    parses = 0
    renamed = finalized = False
    for command, result in zip(commands, results, strict=False):
        if result.error is not None:
            reached.add(f"error:{result.error.kind.value}")
            if command.op == "add_models" and result.error.kind is not ErrorKind.BINDING:
                reached.add(f"parse-error:{error_category(result.error.message)}")
        if command.op == "add_models":
            parses += 1
            reached.update(_parse_features(command.args))
            if renamed:
                reached.add("rename-then-parse")
                if command.args.get("reuse_parser"):
                    reached.add("rename-reuse-parser")
        elif command.op == "rename_model_instance":
            reached.add("rename")
            renamed = True
        elif command.op == "finalize":
            finalized = True
        elif command.op == "model_inventory" and finalized and result.error is None:
            reached.add("report:inventory-finalized")
        elif (
            command.op == "collision_filter_groups"
            and isinstance(result.value, dict)
            and result.value.get("groups")
        ):
            reached.add("report:groups")
    if parses >= 2:
        reached.add("parse:again")
    return reached


class ModelCoverage(Coverage):
    """``Coverage`` of ``fuzz --models``: features per case (``case_features``)."""

    def follow_case(self, commands: Sequence[Command], results: Sequence[Result]) -> None:
        """Counts the features of one case run (``run_model_case``'s ``on_results``)."""
        self.add(case_features(commands, results))

    def headline(self, expected: list[str]) -> str:
        reached = len(expected) - len(self.gaps(expected))
        return (
            f"coverage: {reached} of {len(expected)} model grammar features reached "
            "(each counted once per case)"
        )
