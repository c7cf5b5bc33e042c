"""SDFormat ``<include>``: where an included file is, and what stands in its place.

libsdformat (as Drake 1.51.1 configures it, measured) looks for an
``<include><uri>`` U (whitespace collapsed) with the scheme stripped, f:

1. ``<cwd>/f``, then ``/f``, then ``f`` (so a relative URI is relative to the
   *working directory*, not to the including file);
2. then Drake's package map: ``package://pkg/rel`` and ``model://pkg/rel``
   name ``rel`` in the package ``pkg``.

A directory (``model://simple_robot1/``) holds a ``model.config`` whose
``<sdf>`` entry of the highest version up to 1.12 names the model file. The
included text is named by the path libsdformat finds when it looks for the
path found (``/`` + it, by step 1), so ``package://p/x.sdf`` in ``/abs`` is
named ``//abs/x.sdf``, and ``<uri>/abs/x.sdf</uri>`` is named ``///abs/x.sdf``.

What replaces the ``<include>``, by the file's suffix:

=========================  ==================================================
 suffix                     stands in place of the ``<include>``
=========================  ==================================================
 ``.sdf``, ``.world``       the file's first ``<model>``, read as a document
                            of its own (its errors name that file), with the
                            include's ``<name>``, ``<pose>``, ``<static>`` and
                            ``<placement_frame>`` put in; ``merge="true"``
                            marks it to be merged into the parent (_sdf_dom)
 anything else              the ``<include>`` itself, for Drake's custom
                            parsers (URDF and MuJoCo, see _sdf_interface)
=========================  ==================================================
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._package_map import PackageMap, UriError, resolve_uri
from reimpl.multibody.parsing._sdf_document import (
    check_document,
    sdformat_bool,
    version_tuple,
)
from reimpl.multibody.parsing._xml import XmlElement, XmlSyntaxError, children, parse_xml

__all__ = ["Loaded", "find_file", "load_include_hook", "text_of"]

#: the newest SDFormat version libsdformat 16 reads
_NEWEST = (1, 12)
_SDF_SUFFIXES = (".sdf", ".world")


def text_of(element: XmlElement) -> str:
    """An element's text as libsdformat's tinyxml2 reads it (whitespace collapsed)."""
    return " ".join((element.text or "").split())


@dataclass
class Loaded:
    """What reading a document learned beyond its element tree."""

    #: element -> the name of the text it came from (elements of included files)
    origins: dict[XmlElement, str] = field(default_factory=dict)
    #: models included with ``merge="true"``
    merged: set[XmlElement] = field(default_factory=set)
    #: model -> the ``<include>`` it came from
    includes: dict[XmlElement, XmlElement] = field(default_factory=dict)
    #: included model -> the SDFormat version of its file
    versions: dict[XmlElement, tuple[int, ...]] = field(default_factory=dict)


def _lexically_normal(path: str) -> str:
    normal = os.path.normpath(path)
    return normal + "/" if path.endswith("/") and not normal.endswith("/") else normal


def find_file(uri: str, package_map: PackageMap) -> str | None:
    """sdf::findFile with Drake's callback: the path ``uri`` names, or None."""
    _, separator, rest = uri.partition("://")
    name = rest if separator else uri
    for candidate in (f"{os.getcwd()}/{name}", f"/{name}", name):
        if os.path.exists(candidate):
            return candidate
    try:
        return _lexically_normal(resolve_uri(package_map, uri, root_dir=os.getcwd()))
    except UriError:
        return None


class _Includes:
    """The include hook of one parse (shared by every included document)."""

    def __init__(self, package_map: PackageMap, loaded: Loaded, strict: bool) -> None:
        self.package_map = package_map
        self.loaded = loaded
        self.strict = strict

    def __call__(
        self, include: XmlElement, parent: XmlElement, path: str, label: str
    ) -> list[XmlElement]:
        uris = children(include, "uri")
        if not uris:
            raise ModelParseError(
                f"{label}:{include.line}: error: At XML path {path}: <include> element missing "
                "'uri' attribute"
            )
        uri = text_of(uris[0])
        found = find_file(uri, self.package_map)
        if found is None:
            raise self._error(label, uris[0], f"{path}/uri", f"Unable to find uri[{uri}]")
        if os.path.isdir(found):
            found = self._model_file(found)
        if not _is_sdf_file(found):
            return [include]
        model = self._read(found, label, uris[0], f"{path}/uri")
        self._override(model, include, label, path)
        if sdformat_bool(include.get("merge", "false")):
            self.loaded.merged.add(model)
        self.loaded.includes[model] = include
        return [model]

    @staticmethod
    def _error(label: str, element: XmlElement, path: str, message: str) -> ModelParseError:
        return ModelParseError(f"{label}:{element.line}: error: At XML path {path}: {message}")

    @staticmethod
    def _model_file(directory: str) -> str:
        """The model file a model directory's ``model.config`` names."""
        config = os.path.join(directory, "model.config")
        if not os.path.exists(config):
            if not os.path.exists(os.path.join(directory, "manifest.xml")):
                raise Diagnostics(None).error(
                    f"Could not find model.config or manifest.xml in [{directory}]"
                )
            raise Diagnostics(None).error(
                "The manifest.xml for a model is deprecated. Please rename manifest.xml to "
                "model.config."
            )
        try:
            root = ET.parse(config).getroot()
        except ET.ParseError as exc:
            raise Diagnostics(None).error(f"Error parsing XML in file [{config}]: {exc}") from None
        if root.tag != "model":
            raise Diagnostics(None).error(f"No <model> element in configFile[{config}]")
        return f"{directory}/{_best_model_file(root)}"

    def _read(self, path: str, label: str, uri_element: XmlElement, uri_path: str) -> XmlElement:
        """The included file's first ``<model>``, read and checked as its own document."""
        found = find_file(path, self.package_map) or path
        file_label = found
        with open(path, encoding="utf-8") as stream:
            text = stream.read()
        try:
            root = parse_xml(text)
        except XmlSyntaxError as exc:
            raise Diagnostics(None).error(
                f"Error parsing XML in file [{found}]: Error={exc.name} ErrorID={exc.error_id} "
                f"(0x{exc.error_id:x}) Line number={exc.line}"
            ) from None
        if root.tag != "sdf":
            raise Diagnostics(None).error(
                "XML does not seem to be an SDFormat or an URDF file."
                if root.tag != "robot"
                else f"reimpl does not convert a URDF file named like SDFormat ({found})"
            )
        for element in root.iter():
            self.loaded.origins[element] = file_label  # type: ignore[index]
        check_document(root, file_label, self, self.strict)
        models = children(root, "model")
        kinds = [kind for kind in ("model", "actor", "light") if children(root, kind)]
        for other in kinds[1:]:
            raise Diagnostics(path).error(
                f"At XML path /sdf/{other}: Found other top level element <{other}> in addition "
                f"to <{kinds[0]}> in include file."
            )
        if not kinds:
            raise self._error(
                label,
                uri_element,
                uri_path,
                "Failed to find top level <model> / <actor> / <light> for <include>\n",
            )
        if len(children(root, kinds[0])) > 1:
            raise Diagnostics(path).error(
                f"At XML path /sdf/{kinds[0]}: Found more than one {kinds[0]} for <include>."
            )
        if not models:
            return children(root, kinds[0])[0]
        self.loaded.versions[models[0]] = version_tuple(root.get("version", ""))
        return models[0]

    @staticmethod
    def _override(model: XmlElement, include: XmlElement, label: str, path: str) -> None:
        """The include's ``<name>``, ``<pose>``, ``<static>``, ``<placement_frame>``."""
        for name in children(include, "name"):
            model.set("name", text_of(name))
            break
        for pose in children(include, "pose"):
            for old in children(model, "pose"):
                model.remove(old)
            model.insert(0, pose)
            break
        for static in children(include, "static"):
            for old in children(model, "static"):
                model.remove(old)
            model.insert(0, static)
            break
        for placement in children(include, "placement_frame"):
            if not children(include, "pose"):
                raise ModelParseError(
                    f"{label}:{include.line}: error: At XML path {path}/placement_frame: <pose> "
                    "is required when specifying the placement_frame element"
                )
            model.set("placement_frame", text_of(placement))
            break


def _best_model_file(config: ET.Element) -> str:
    """getBestSupportedModelVersion: the ``<sdf>`` entry of the highest version up to 1.12
    (else the first); a newer one, or one without a version, is libsdformat's warning (an
    error for Drake)."""
    entries = config.findall("sdf")
    name = (config.findtext("name") or "").strip()
    chosen = entries[0] if entries else None
    best: tuple[int, ...] = (0, 0)
    for entry in entries:
        version = entry.get("version")
        if version is None or version_tuple(version) <= best:
            continue
        if version_tuple(version) > _NEWEST:
            raise Diagnostics(None).error(
                f"Ignoring version {version} for model {name} because is newer than this sdf "
                "parser (version 1.12)"
            )
        chosen, best = entry, version_tuple(version)
    if chosen is None or not (chosen.text or "").strip():
        raise Diagnostics(None).error(
            f"Failure to detect an sdf tag in the model config file for model: {name}"
        )
    if chosen.get("version") is None:
        raise Diagnostics(None).error(
            "Can not find the XML attribute 'version' in sdf XML tag for model: "
            f"{name}. Please specify the SDF protocol supported in the model configuration file. "
            "The first sdf tag in the config file will be used "
        )
    return " ".join((chosen.text or "").split())


def _is_sdf_file(path: str) -> bool:
    """libsdformat's isSdfFile: the text from the last ``.`` is ``.sdf`` or ``.world``."""
    dot = path.rfind(".")
    return dot >= 0 and path[dot:] in _SDF_SUFFIXES


def load_include_hook(package_map: PackageMap, loaded: Loaded, strict: bool) -> _Includes:
    """The hook that expands the includes of one parse (check_document's ``include``)."""
    return _Includes(package_map, loaded, strict)
