"""PackageMap: package names to local directories, and ``package://`` URIs.

``package://pkg/rel/path`` (or ``model://pkg/rel/path``) names ``rel/path``
inside the directory registered for ``pkg``; ``file:///abs/path`` names an
absolute path. A URI without a scheme is relative to the file being parsed,
and is an error in model text. Every resolved path must exist. The messages
are Drake 1.51.1's (measured).

pydrake's default map holds the packages ``drake`` and ``drake_models``;
reimpl's holds the same names but ships no Drake resources, so resolving a
path inside them raises ``UnavailablePackageError``.
"""

from __future__ import annotations

import os
from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of

__all__ = ["PackageMap", "UnavailablePackageError", "UriError", "resolve_uri"]

_OWNER = "reimpl.multibody.parsing.PackageMap"
_DEFAULT_PACKAGES = ("drake", "drake_models")
_SCHEMES = ("package://", "model://")


class UriError(RuntimeError):
    """Raised for a URI that does not name an existing file; the text is Drake's."""


class UnavailablePackageError(RuntimeError):
    """Raised for a path inside Drake's own packages, which reimpl does not ship."""


def _is_path(value: object) -> bool:
    return isinstance(value, str | os.PathLike)


class PackageMap:
    """Maps package names to directories (drake/multibody/parsing/package_map.h)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._paths: dict[str, str | None] = {}

        def default() -> None:
            self._paths = dict.fromkeys(_DEFAULT_PACKAGES)

        def copy(other: PackageMap) -> None:
            self._paths = dict(other._paths)

        dispatch(
            _OWNER,
            "__init__",
            (Overload((), default), Overload((Param("other", instance_of(PackageMap)),), copy)),
            args,
            kwargs,
        )

    @staticmethod
    def MakeEmpty() -> PackageMap:
        package_map = PackageMap()
        package_map._paths.clear()
        return package_map

    def Add(self, package_name: str, package_path: str | os.PathLike[str]) -> None:
        """Adds a package; the directory must exist, and a name keeps its first path."""
        path = os.fspath(package_path)
        if not os.path.isdir(path):
            raise RuntimeError(
                f"PackageMap::Add cannot add '{package_name}' because directory "
                f"'{path}' does not exist"
            )
        self._add(package_name, path)

    def _add(self, package_name: str, path: str | None) -> None:
        if package_name in self._paths:
            old = self._paths[package_name]
            if old is not None and path is not None and not os.path.samefile(old, path):
                raise RuntimeError(
                    f"PackageMap::Add() cannot add '{package_name}' because the local paths "
                    f"are not equivalent ('{old}' vs '{path}')"
                )
            return
        self._paths[package_name] = path

    def AddMap(self, other_map: PackageMap) -> None:
        for name, path in other_map._paths.items():
            self._add(name, path)

    def Contains(self, package_name: str) -> bool:
        return package_name in self._paths

    def GetPackageNames(self) -> list[str]:
        return sorted(self._paths)

    def size(self) -> int:
        return len(self._paths)

    def Remove(self, package_name: str) -> None:
        if package_name not in self._paths:
            raise RuntimeError(
                f"Could not find and remove package://{package_name} from the search path."
            )
        del self._paths[package_name]

    def GetPath(self, package_name: str) -> str:
        """The package's directory. Like pydrake, an unknown name ends the program."""
        if package_name not in self._paths:
            raise SystemExit(
                "Failure at external/drake+/multibody/parsing/package_map.cc:755 in GetPath(): "
                "condition 'Contains(package_name)' failed."
            )
        path = self._paths[package_name]
        if path is None:
            raise UnavailablePackageError(
                f"PackageMap: reimpl ships no Drake resources, so package '{package_name}' "
                "has no local path"
            )
        return path

    def ResolveUrl(self, url: str) -> str:
        try:
            return resolve_uri(self, url, root_dir=None)
        except UriError as exc:
            raise UriError(f"error: {exc}") from None


def resolve_uri(package_map: PackageMap, uri: str, root_dir: str | None) -> str:
    """The existing local path ``uri`` names; ``root_dir`` is the parsed file's directory.

    Raises UriError with Drake's message (without the ``error:`` prefix).
    """
    scheme, separator, rest = uri.partition("://")
    if not separator:
        if root_dir is None:
            raise UriError(f"URI '{uri}' is invalid when parsing a string instead of a filename.")
        path = os.path.join(root_dir, uri)
    elif f"{scheme}://" in _SCHEMES:
        package, slash, relative = rest.partition("/")
        if not slash:
            raise UriError(f"URI '{uri}' is invalid when parsing a string instead of a filename.")
        if not package_map.Contains(package):
            raise UriError(f"URI '{uri}' refers to unknown package '{package}'")
        path = os.path.join(package_map.GetPath(package), relative)
    elif scheme == "file":
        path = rest
    else:
        raise UriError(
            f"URI '{uri}' specifies an unsupported scheme; supported schemes are 'file://', "
            "'model://', and 'package://'."
        )
    if not os.path.exists(path):
        raise UriError(f"URI '{uri}' resolved to '{path}' which does not exist.")
    return path
