"""PackageMap: ROS package names to local folders (drake/multibody/parsing/package_map.h).

A package is *local* (a folder: ``Add``, ``AddPackageXml``, ``PopulateFrom...``)
or *remote* (``AddRemote``: an archive fetched into a cache on first use; see
_remote_package). Either may be *deprecated*, by its ``package.xml``'s
``<export><deprecated>``; using it then logs a warning.

The default map holds Drake's own two packages, as pydrake 1.51.1's does:

* ``drake``: the model files pydrake's wheel ships in ``share/drake``
  (``examples/...``), vendored in ``_resources/drake`` with Drake's licence;
* ``drake_models``: remote, RobotLocomotion/models at the commit Drake pins
  (``_resources/drake/multibody/parsing/drake_models.json``).

Adding a name again is allowed when it names the same thing; the rules and
messages are Drake 1.51.1's (measured):

=================  ================  ============================================
 existing          new               result
=================  ================  ============================================
 local ``p``       local ``q``       kept if ``p`` and ``q`` (or their
                                     ``package.xml`` files) are the same file;
                                     else "the local paths are not equivalent"
 remote ``r``      remote ``s``      kept if ``r.ToJson() == s.ToJson()``; else
                                     "the remote package parameters differ"
 local             remote (or v.v.)  "the existing path is local ... but the the
                                     new path is remote"
=================  ================  ============================================

``Add``/``AddRemote`` raise ``PackageMap::Add[Remote]() cannot add '<name>'
because ...``; ``AddMap`` raises ``PackageMap::AddMap cannot merge the package
definition for '<name>' because ...`` and keeps a deprecation from either
side (the existing message first); ``PopulateFrom*`` log ``PackageMap is
ignoring newly-found path for package '<name>' because ...`` and go on.
A ``DRAKE_THROW_UNLESS`` failure (an unknown name in ``GetPath``, an empty
argument) is SystemExit, as in pydrake.
"""

from __future__ import annotations

import copy
import json
import logging
import os
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, ClassVar

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.common._drake_demand import failed_demand
from reimpl.multibody.parsing._binding import binds, is_path, is_str
from reimpl.multibody.parsing._package_manifest import read_manifest
from reimpl.multibody.parsing._remote_package import RemoteParams as _RemoteParams
from reimpl.multibody.parsing._remote_package import (
    allowed_urls,
    check_remote_params,
    fetch,
    find_in_cache,
)
from reimpl.multibody.parsing._resolve_uri import UriError, lexically_normal, resolve_uri

__all__ = ["DRAKE_PACKAGE_XML", "PackageMap", "UriError", "resolve_uri"]

_LOG = logging.getLogger("drake")
_OWNER = "reimpl.multibody.parsing.PackageMap"

#: The manifest of the vendored ``drake`` package (pydrake's ``share/drake``).
DRAKE_PACKAGE_XML = str(Path(__file__).resolve().parent / "_resources" / "drake" / "package.xml")
_DRAKE_MODELS_JSON = os.path.join(
    os.path.dirname(DRAKE_PACKAGE_XML), "multibody", "parsing", "drake_models.json"
)
#: ROS markers that stop PopulateFromRosPackagePath from crawling a folder.
_ROS_STOP_MARKERS = ("AMENT_IGNORE", "CATKIN_IGNORE", "COLCON_IGNORE")


@dataclass(frozen=True)
class _Package:
    """One package: a local ``path``, or ``remote`` params (path set once fetched)."""

    path: str | None = None
    remote: _RemoteParams | None = None
    #: None: not deprecated; else the message ("(no explanation given)" if none)
    deprecation: str | None = None

    @property
    def kind(self) -> str:
        return "remote" if self.remote is not None else "local"

    def display(self) -> str:
        """The local path, or a remote package's first URL."""
        return self.remote.urls[0] if self.remote is not None else str(self.path)

    def merge_error(self, other: _Package) -> str | None:
        """Why ``other`` cannot be folded into this package; None if it can."""
        if self.remote is None and other.remote is None:
            assert self.path is not None
            assert other.path is not None
            if _same_file(self.path, other.path) or _same_file(
                os.path.join(self.path, "package.xml"), os.path.join(other.path, "package.xml")
            ):
                return None
            return (
                "because the local paths are not equivalent "
                f"('{self.display()}' vs '{other.display()}')"
            )
        if self.remote is not None and other.remote is not None:
            if self.remote.ToJson() == other.remote.ToJson():
                return None
            return (
                "because the remote package parameters differ "
                f"({self.remote.ToJson()} vs {other.remote.ToJson()})"
            )
        return (
            f"because the existing path is {self.kind} ('{self.display()}') but the the new "
            f"path is {other.kind} ('{other.display()}')"
        )


def _same_file(a: str, b: str) -> bool:
    """Both exist and are the same file once symlinks are resolved."""
    try:
        return os.path.samefile(os.path.realpath(a), os.path.realpath(b))
    except OSError:
        return False


def _deprecation(message: str | None) -> str | None:
    return "(no explanation given)" if message == "" else message


def _is_path(value: object) -> bool:
    return isinstance(value, str | os.PathLike)


def _drake_models_params() -> _RemoteParams:
    with open(_DRAKE_MODELS_JSON, encoding="utf-8") as stream:
        metadata = json.load(stream)
    return _RemoteParams(
        urls=metadata["urls"], sha256=metadata["sha256"], strip_prefix=metadata["strip_prefix"]
    )


class PackageMap:
    """Maps package names to folders (drake/multibody/parsing/package_map.h)."""

    RemoteParams: ClassVar[type[_RemoteParams]] = _RemoteParams

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._packages: dict[str, _Package] = {}
        dispatch(
            _OWNER,
            "__init__",
            (
                Overload((), self._add_default_packages),
                Overload((Param("other", instance_of(PackageMap)),), self._copy_from),
            ),
            args,
            kwargs,
        )

    def _add_default_packages(self) -> None:
        self.AddPackageXml(filename=DRAKE_PACKAGE_XML)
        self.AddRemote(package_name="drake_models", params=_drake_models_params())

    def _copy_from(self, other: PackageMap) -> None:
        self._packages = dict(other._packages)

    def __copy__(self) -> PackageMap:
        return PackageMap(other=self)

    def __deepcopy__(self, memo: dict[int, Any]) -> PackageMap:
        return PackageMap(other=self)

    def __reduce__(self) -> Any:
        raise TypeError("cannot pickle 'reimpl.multibody.parsing.PackageMap' object")

    @staticmethod
    def MakeEmpty() -> PackageMap:
        package_map = PackageMap.__new__(PackageMap)
        package_map._packages = {}
        return package_map

    # ------------------------------------------------------------- adding
    def _emplace(self, name: str, package: _Package) -> None:
        existing = self._packages.get(name)
        if existing is None:
            self._packages[name] = package
            return
        error = existing.merge_error(package)
        if error is not None:
            kind = "Remote" if package.remote is not None else ""
            raise RuntimeError(f"PackageMap::Add{kind}() cannot add '{name}' {error}")

    @binds(_OWNER, Param("package_name", is_str), Param("package_path", is_path))
    def Add(self, package_name: str, package_path: str | os.PathLike[str]) -> None:
        """Adds a local package; the folder must exist."""
        path = os.fspath(package_path)
        if not os.path.isdir(path):
            raise RuntimeError(
                f"PackageMap::Add cannot add '{package_name}' because directory '{path}' "
                "does not exist"
            )
        self._emplace(package_name, _Package(path=path))

    @binds(_OWNER, Param("package_name", is_str), Param("params", instance_of(_RemoteParams)))
    def AddRemote(self, package_name: str, params: _RemoteParams) -> None:
        """Declares a remote package; nothing is fetched until its path is asked for."""
        check_remote_params(package_name, params)
        package = _Package(remote=copy.deepcopy(params))
        if not allowed_urls(params.urls) and find_in_cache(params) is None:
            raise RuntimeError(
                f"PackageMap::AddRemote on '{package_name}' only provides network URLs (i.e., "
                "no file:// fallbacks) but PackageMap networking has been disabled via the "
                "DRAKE_ALLOW_NETWORK environment variable and the download cache does not "
                "contain any matching file"
            )
        self._emplace(package_name, package)

    @binds(_OWNER, Param("filename", is_path))
    def AddPackageXml(self, filename: str | os.PathLike[str]) -> None:
        """Adds the package ``filename`` (a ``package.xml``) describes, at its folder."""
        path = os.fspath(filename)
        if not path:
            raise failed_demand("PackageMap.AddPackageXml.filename")
        manifest = read_manifest(path)
        self.Add(package_name=manifest.name, package_path=os.path.dirname(path))
        self._set_deprecated(manifest.name, manifest.deprecation)

    def _set_deprecated(self, name: str, message: str | None) -> None:
        self._packages[name] = replace(self._packages[name], deprecation=_deprecation(message))

    @binds(_OWNER, Param("other_map", lambda value: isinstance(value, PackageMap)))
    def AddMap(self, other_map: PackageMap) -> None:
        """Adds every package of ``other_map`` (see the module docstring for clashes)."""
        for name, package in sorted(other_map._packages.items()):
            existing = self._packages.get(name)
            if existing is None:
                self._packages[name] = package
                continue
            error = existing.merge_error(package)
            if error is not None:
                raise RuntimeError(
                    f"PackageMap::AddMap cannot merge the package definition for '{name}' {error}"
                )
            if existing.deprecation is None and package.deprecation is not None:
                self._set_deprecated(name, package.deprecation)

    # ----------------------------------------------------------- crawling
    @binds(_OWNER, Param("path", is_path))
    def PopulateFromFolder(self, path: str | os.PathLike[str]) -> None:
        """Adds every package found in ``path`` and below (hidden folders skipped)."""
        folder = os.fspath(path)
        if not folder:
            raise failed_demand("PackageMap.PopulateFromFolder.path")
        self._crawl(folder, stop_at_package=False, stop_markers=())

    @binds(_OWNER, Param("environment_variable", is_str))
    def PopulateFromEnvironment(self, environment_variable: str) -> None:
        """Crawls each folder of the colon-separated list in ``environment_variable``."""
        if not environment_variable:
            raise failed_demand("PackageMap.PopulateFromEnvironment.variable")
        if environment_variable == "ROS_PACKAGE_PATH":
            raise RuntimeError(
                "PackageMap::PopulateFromEnvironment() must not be used to load a "
                '"ROS_PACKAGE_PATH"; use PopulateFromRosPackagePath() instead.'
            )
        for folder in os.environ.get(environment_variable, "").split(":"):
            if folder:
                self._crawl(folder, stop_at_package=False, stop_markers=())

    def PopulateFromRosPackagePath(self) -> None:
        """Crawls ``$ROS_PACKAGE_PATH`` as ROS does: a package's folder is not
        searched further, nor is a folder holding a ``*_IGNORE`` marker."""
        for folder in os.environ.get("ROS_PACKAGE_PATH", "").split(":"):
            if folder:
                self._crawl(folder, stop_at_package=True, stop_markers=_ROS_STOP_MARKERS)

    def _crawl(self, path: str, stop_at_package: bool, stop_markers: tuple[str, ...]) -> None:
        folder = lexically_normal(path)
        if any(os.path.exists(os.path.join(folder, marker)) for marker in stop_markers):
            return
        manifest_path = os.path.join(folder, "package.xml")
        if os.path.exists(manifest_path):
            self._add_found(manifest_path, folder + "/")
            if stop_at_package:
                return
        try:
            entries = sorted(os.scandir(folder), key=lambda entry: entry.name)
        except OSError:
            _LOG.warning("Unable to open directory: %s", path)
            return
        for entry in entries:
            if entry.is_dir() and not entry.name.startswith("."):
                self._crawl(entry.path, stop_at_package, stop_markers)

    def _add_found(self, manifest_path: str, folder: str) -> None:
        manifest = read_manifest(manifest_path)
        existing = self._packages.get(manifest.name)
        if existing is None:
            self.Add(package_name=manifest.name, package_path=folder)
            self._set_deprecated(manifest.name, manifest.deprecation)
            return
        error = existing.merge_error(_Package(path=folder))
        if error is not None:
            _LOG.warning(
                "PackageMap is ignoring newly-found path for package '%s' %s",
                manifest.name,
                error,
            )

    # ------------------------------------------------------------ queries
    @binds(_OWNER, Param("package_name", is_str))
    def Contains(self, package_name: str) -> bool:
        return package_name in self._packages

    def size(self) -> int:
        return len(self._packages)

    def GetPackageNames(self) -> list[str]:
        """The names, sorted (byte order, as Drake's std::map)."""
        return sorted(self._packages)

    @binds(_OWNER, Param("package_name", is_str))
    def Remove(self, package_name: str) -> None:
        if self._packages.pop(package_name, None) is None:
            raise RuntimeError(
                f"Could not find and remove package://{package_name} from the search path."
            )

    @binds(_OWNER, Param("package_name", is_str))
    def GetPath(self, package_name: str) -> str:
        """The package's folder (fetching a remote package first); a deprecated
        package logs ``PackageMap: Package '<name>' is deprecated: <message>``."""
        path, deprecation = self._path_and_deprecation(package_name)
        if deprecation is not None:
            _LOG.warning("PackageMap: %s", deprecation)
        return path

    def _path_and_deprecation(self, package_name: str) -> tuple[str, str | None]:
        """GetPath, with the deprecation warning returned instead of logged."""
        package = self._packages.get(package_name)
        if package is None:
            raise failed_demand("PackageMap.GetPath.contains")
        deprecation = None
        if package.deprecation is not None:
            deprecation = f"Package '{package_name}' is deprecated: {package.deprecation}"
        if package.path is None:
            assert package.remote is not None
            if find_in_cache(package.remote) is None:
                _LOG.info("PackageMap: Downloading %s", package.remote.urls[0])
            path = fetch(package_name, package.remote)
            self._packages[package_name] = replace(package, path=path)
            return path, deprecation
        return package.path, deprecation

    @binds(_OWNER, Param("url", is_str))
    def ResolveUrl(self, url: str) -> str:
        """The existing local path ``url`` names (a ``package://``, ``model://`` or
        ``file://`` URL); RuntimeError ``error: ...`` otherwise."""
        try:
            return resolve_uri(self, url, root_dir=None)
        except UriError as exc:
            raise UriError(f"error: {exc}") from None
