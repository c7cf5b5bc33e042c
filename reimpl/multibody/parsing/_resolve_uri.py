"""From a URI in model text to an existing local path (Drake's ``ResolveUri``).

A URI is ``scheme://package/path`` when it matches
``^([a-z0-9+.-]+)://([^/]*)/+(.*)`` (lowercase schemes only; any run of
slashes after the package). Otherwise it is a bare file name:

==========================  =====================================================
 URI                         local path
==========================  =====================================================
 ``package://pkg/rel``       the package's path ``/`` ``rel`` (``model://`` alike);
                             a package the map lacks is an error
 ``file://host/abs``         ``/abs`` (the host is ignored)
 ``other://...``             an error: unsupported scheme
 ``name`` (not a URI)        ``name`` if absolute, else relative to the folder of
                             the file being parsed; model text has no folder, so
                             there it is an error
==========================  =====================================================

The path is then normalized lexically (``a/./b/../c`` is ``a/c``, a trailing
slash stays), and must exist. The error messages are Drake 1.51.1's (measured);
a deprecated package adds a warning ``In URI '...': Package '...' is deprecated:
...``.
"""

from __future__ import annotations

import logging
import os
import re
from collections.abc import Callable
from typing import Protocol


class PackageMap(Protocol):
    """What resolution asks of a package map (``_package_map.PackageMap`` has it)."""

    def Contains(self, package_name: str) -> bool: ...

    def _path_and_deprecation(self, package_name: str) -> tuple[str, str | None]: ...


__all__ = ["UriError", "join_path", "lexically_normal", "resolve_uri"]

_URI = re.compile(r"([a-z0-9+.-]+)://([^/\n\r]*)/+([^\n\r]*)")


class UriError(RuntimeError):
    """A URI that names no existing file; the text is Drake's (without ``error:``)."""


def join_path(base: str, relative: str) -> str:
    """``std::filesystem::path(base) / relative``: an absolute ``relative`` replaces
    ``base``; otherwise one separator goes between them (none after a trailing one)."""
    if relative.startswith("/"):
        return relative
    separator = "/" if base and not base.endswith("/") else ""
    return base + separator + relative


def lexically_normal(path: str) -> str:
    """``std::filesystem::path::lexically_normal()`` of a POSIX path."""
    if not path:
        return ""
    rooted = path.startswith("/")
    names = path.split("/")
    # N.B. "a/b/.." is "a/": a last name that goes away leaves its separator.
    trailing = names[-1] in ("", ".", "..")
    parts: list[str] = []
    for name in names:
        if name in ("", "."):
            continue
        if name == ".." and parts and parts[-1] != "..":
            parts.pop()
        elif not (name == ".." and rooted):
            parts.append(name)
    if not parts:
        return "/" if rooted else "."
    text = ("/" if rooted else "") + "/".join(parts)
    return text + "/" if trailing and parts[-1] != ".." else text


def resolve_uri(
    package_map: PackageMap,
    uri: str,
    root_dir: str | None,
    warn: Callable[[str], None] | None = None,
) -> str:
    """The existing local path ``uri`` names; ``root_dir`` is the parsed file's folder.

    Raises UriError with Drake's message; ``warn`` receives the deprecation
    warning of a deprecated package (by default it is logged).
    """
    match = _URI.fullmatch(uri)
    if match:
        scheme, package, relative = match.groups()
        if scheme == "file":
            result = "/" + relative
        elif scheme in ("model", "package"):
            if not package_map.Contains(package_name=package):
                raise UriError(f"URI '{uri}' refers to unknown package '{package}'")
            path, deprecation = package_map._path_and_deprecation(package)
            if deprecation is not None:
                (warn or _log_warning)(f"In URI '{uri}': {deprecation}")
            result = join_path(path, relative)
        else:
            raise UriError(
                f"URI '{uri}' specifies an unsupported scheme; supported schemes are "
                "'file://', 'model://', and 'package://'."
            )
    elif not root_dir:
        raise UriError(f"URI '{uri}' is invalid when parsing a string instead of a filename.")
    elif uri.startswith("/"):
        result = uri
    elif root_dir.startswith("/"):
        result = join_path(root_dir, uri)
    else:
        result = join_path(join_path(os.getcwd(), root_dir), uri)
    normal = lexically_normal(result)
    if not os.path.exists(normal):
        raise UriError(f"URI '{uri}' resolved to '{result}' which does not exist.")
    return normal


def _log_warning(message: str) -> None:
    logging.getLogger("drake").warning("warning: %s", message)
