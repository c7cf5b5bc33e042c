"""Remote packages: ``PackageMap.RemoteParams``, their checks, and fetching them.

A remote package names an archive by ``urls`` (tried in order), its
``sha256``, an optional ``archive_type`` (else taken from the URL's suffix)
and an optional ``strip_prefix`` (the folder inside the archive that is the
package). Drake fetches it on first use into a per-user cache,

    <cache>/drake/package_map/<sha256>-<sha256 of strip_prefix>/

where <cache> is ``$TEST_TMPDIR/.cache``, else ``$XDG_CACHE_HOME``, else
``~/.cache``; a package already in the cache is used as it is. reimpl uses the
same cache, so a package pydrake fetched is found by reimpl too.

N.B. Known divergence: reimpl fetches ``file://`` URLs only (unpacking the
archive as Drake's downloader does); it never opens a network connection, so a
package that only ``https://`` URLs provide, and that is not in the cache,
fails with a message that says so, where pydrake would download it.

The messages are Drake 1.51.1's (measured), the JSON is Drake's
``yaml::SaveJsonString``: keys sorted, no spaces, absent optionals left out,
and every byte of a string that is ``"``, ``\\``, below ``0x20`` or above
``0x7f`` written as ``\\u00XX``.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import shutil
import tempfile
import urllib.parse
from pathlib import Path
from typing import Any

from reimpl.common._struct import Field, Struct, optional_of, str_list, string

__all__ = ["RemoteParams", "check_remote_params", "fetch", "find_in_cache", "networking_allowed"]

#: archive types Drake's downloader can unpack (shutil.get_unpack_formats())
_ARCHIVE_TYPES = ("zip", "tar", "gztar", "bztar", "xztar")
_URL_SCHEMES = ("https://", "http://", "file://")


def _str_list(value: Any) -> list[str]:
    return [v.decode() if isinstance(v, bytes) else v for v in value]


class RemoteParams(Struct):
    """Where a remote package's archive is and how to check and unpack it."""

    MODULE = "reimpl.multibody.parsing"
    QUALNAME = "PackageMap.RemoteParams"
    FIELDS = (
        Field("urls", "list[str]", str_list, list, _str_list),
        Field("sha256", "str", string, str),
        Field("archive_type", "Optional[str]", optional_of(string), lambda: None),
        Field("strip_prefix", "Optional[str]", optional_of(string), lambda: None),
    )

    def ToJson(self) -> str:
        """These params as Drake's JSON (see the module docstring)."""
        values = dict(self._values())
        return _json({key: value for key, value in values.items() if value is not None})


def _json(value: Any) -> str:
    if isinstance(value, dict):
        items = (f"{_json_string(k)}:{_json(v)}" for k, v in sorted(value.items()))
        return "{" + ",".join(items) + "}"
    if isinstance(value, list):
        return "[" + ",".join(_json(v) for v in value) + "]"
    return _json_string(value)


def _json_string(text: str) -> str:
    escaped = "".join(
        f"\\u00{byte:02x}" if byte in b'"\\' or byte < 0x20 or byte > 0x7F else chr(byte)
        for byte in text.encode()
    )
    return f'"{escaped}"'


def check_remote_params(package_name: str, params: RemoteParams) -> None:
    """Drake's ``AddRemote`` checks, in its order; RuntimeError with its messages."""
    where = f"PackageMap::AddRemote on '{package_name}'"
    if not params.urls:
        raise RuntimeError(f"{where} requires at least one URL")
    for url in params.urls:
        if not url.startswith(_URL_SCHEMES):
            raise RuntimeError(f"{where} has unsupported URL '{url}'")
    sha256 = params.sha256
    if len(sha256) != 64 or any(c not in "0123456789abcdefABCDEF" for c in sha256):
        raise RuntimeError(f"{where} has invalid sha256 '{sha256}'")
    if params.archive_type is not None and params.archive_type not in _ARCHIVE_TYPES:
        raise RuntimeError(f"{where} has unsupported archive type '{params.archive_type}'")


def networking_allowed() -> bool:
    """Drake's ``IsNetworkingAllowed("package_map")`` from ``$DRAKE_ALLOW_NETWORK``.

    Unset or empty allows everything; otherwise the colon-separated tokens must
    name ``package_map`` and must not include ``none``.
    """
    value = os.environ.get("DRAKE_ALLOW_NETWORK", "")
    if not value:
        return True
    tokens = value.split(":")
    return "none" not in tokens and "package_map" in tokens


def allowed_urls(urls: list[str]) -> list[str]:
    """The URLs the network policy lets Drake try (``file://`` ones always)."""
    return list(urls) if networking_allowed() else [u for u in urls if u.startswith("file://")]


def _cache_dir() -> Path:
    """Drake's ``FindOrCreateCache("package_map")``, created if need be."""
    if os.environ.get("TEST_TMPDIR"):
        base = Path(os.environ["TEST_TMPDIR"]) / ".cache"
    elif os.environ.get("XDG_CACHE_HOME"):
        base = Path(os.environ["XDG_CACHE_HOME"])
    else:
        base = Path(os.path.expanduser("~")) / ".cache"
    cache = base / "drake" / "package_map"
    cache.mkdir(parents=True, exist_ok=True)
    return cache


def _cache_name(params: RemoteParams) -> str:
    prefix = hashlib.sha256((params.strip_prefix or "").encode()).hexdigest()
    return f"{params.sha256}-{prefix}"


def find_in_cache(params: RemoteParams) -> str | None:
    """The cached copy of the package, if there is one."""
    try:
        path = _cache_dir() / _cache_name(params)
    except OSError:
        return None
    return str(path) if path.is_dir() else None


def fetch(package_name: str, params: RemoteParams) -> str:
    """The local folder of the remote package, unpacked into the cache if need be."""
    cached = find_in_cache(params)
    if cached is not None:
        return cached
    output_dir = _cache_dir() / _cache_name(params)
    errors: list[str] = []
    with tempfile.TemporaryDirectory(prefix="drake_downloader_") as temp:
        for url in allowed_urls(params.urls):
            archive = _copy_local(url, params.sha256, Path(temp), errors)
            if archive is not None:
                _unpack(package_name, archive, params, Path(temp) / "unpack", output_dir)
                return str(output_dir)
    messages = "\n\n".join(errors)
    raise RuntimeError(
        f"PackageMap: when downloading '{package_name}', the downloader experienced an "
        f"error: All downloads failed:\n\n{messages}"
    )


def _copy_local(url: str, sha256: str, temp: Path, errors: list[str]) -> Path | None:
    """The archive a ``file://`` URL names, copied and checked; None (noted) if not."""
    if not url.startswith("file://"):
        errors.append(
            f"Candidate {url} failed:\nreimpl does not download over the network; only "
            "file:// URLs are fetched (add a local copy with PackageMap.Add instead)"
        )
        return None
    source = urllib.parse.unquote(urllib.parse.urlparse(url).path)
    target = temp / (source.rsplit("/", 1)[-1] or "empty")
    try:
        shutil.copyfile(source, target)
    except OSError as exc:
        errors.append(f"Candidate {url} failed:\n<urlopen error {exc}>")
        return None
    digest = hashlib.sha256(target.read_bytes()).hexdigest()
    if digest != sha256:
        errors.append(
            f"Candidate {url} failed:\nChecksum mismatch; was {digest} but wanted {sha256}."
        )
        return None
    return target


def _unpack(
    package_name: str, archive: Path, params: RemoteParams, unpack_dir: Path, output_dir: Path
) -> None:
    shutil.unpack_archive(archive, unpack_dir, format=params.archive_type)
    package_dir = unpack_dir / (params.strip_prefix or "")
    if not package_dir.is_dir():
        raise RuntimeError(
            f"PackageMap: when downloading '{package_name}', the downloader experienced an "
            f"error: The strip_prefix='{params.strip_prefix}' does not exist within "
            f"{archive.name}"
        )
    with tempfile.TemporaryDirectory(
        dir=output_dir.parent, prefix=f"temp.{output_dir.name}."
    ) as staging:
        incoming = Path(staging) / "incoming"
        shutil.move(package_dir, incoming)
        # N.B. The rename fails if another process unpacked the same package first.
        with contextlib.suppress(OSError):
            incoming.rename(output_dir)
    readme = output_dir.with_name(output_dir.name + ".README")
    urls = "".join(f" {url}\n" for url in params.urls)
    readme.write_text(
        f"Our sibling directory ./{output_dir.name} contains package://{package_name}.\n\n"
        f"It was downloaded by Drake from one of these URLs:\n{urls}"
    )
