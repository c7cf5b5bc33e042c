"""Drake releases on the package index, and release specs: ``1.30.0`` or ``1.40..1.58``.

``drake_releases`` lists the Drake releases that the index serves (PyPI's
JSON API, ``$DRAKE_FILTER_CONFORMANCE_INDEX`` to use another), oldest first,
leaving out yanked ones and releases with no wheel for a Python this machine
could run (``PYTHONS_FOR``). The list is cached for a day in the cache folder
(``environments.cache_dir``), so a matrix or a bisection asks the index once;
without the index, a cached list of any age is used.

A *spec* is one release (``1.30.0``) or an inclusive range ``A..B`` of
dotted prefixes (``1.40..1.58`` is every release from 1.40.0 to the last
1.58.x); ``expand`` turns specs into releases, in order, without repeats.
"""

from __future__ import annotations

import json
import os
import re
import time
import urllib.request
from collections.abc import Iterable, Sequence
from pathlib import Path

from conformance._backends.environments import cache_dir, pythons_for
from conformance._policy.versions import parse_version, version_in_range

__all__ = [
    "INDEX_VARIABLE",
    "ReleaseSpecError",
    "check_release",
    "drake_releases",
    "expand",
    "releases_between",
]

INDEX_VARIABLE = "DRAKE_FILTER_CONFORMANCE_INDEX"
_INDEX = "https://pypi.org/pypi/drake/json"
#: Seconds a cached release list is trusted.
_FRESH = 24 * 3600
_RELEASE = re.compile(r"^\d+\.\d+\.\d+$")
_PREFIX = re.compile(r"^\d+\.\d+(\.\d+)?$")


class ReleaseSpecError(ValueError):
    """A spec that is not a release or a range, or names no release on the index."""


def check_release(text: str) -> str:
    """``text`` if it names one release as X.Y.Z, else ReleaseSpecError."""
    if not _RELEASE.match(text):
        raise ReleaseSpecError(f"{text!r} is not a Drake release (X.Y.Z, for example 1.30.0)")
    return text


def _fetch(url: str) -> list[str]:
    with urllib.request.urlopen(url, timeout=30) as answer:
        data = json.load(answer)
    return [
        version
        for version, files in data["releases"].items()
        if _RELEASE.match(version) and files and not all(f.get("yanked") for f in files)
    ]


def drake_releases(*, cache: Path | None = None) -> list[str]:
    """Every Drake release on the index that a supported Python can run, oldest first."""
    path = (cache or cache_dir()) / "drake-releases.json"
    url = os.environ.get(INDEX_VARIABLE, _INDEX)
    fresh = path.exists() and time.time() - path.stat().st_mtime < _FRESH
    if not fresh:
        try:
            releases = _fetch(url)
        except OSError as exc:
            if not path.exists():
                raise ReleaseSpecError(f"cannot list Drake releases from {url}: {exc}") from None
        else:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(json.dumps(sorted(releases, key=parse_version)) + "\n")
    listed = json.loads(path.read_text())
    return [v for v in sorted(listed, key=parse_version) if pythons_for(v)]


def releases_between(since: str, until: str, releases: Sequence[str]) -> list[str]:
    """The releases ``since``..``until`` (dotted prefixes, inclusive), oldest first."""
    return [v for v in releases if version_in_range(v, since, until)]


def expand(specs: Iterable[str], *, releases: Sequence[str] | None = None) -> list[str]:
    """The releases the specs name, in the order given, each once.

    A single release is taken as given (it need not be listed); a range
    needs the index (``releases``, default ``drake_releases()``).
    """
    out: list[str] = []
    for spec in specs:
        since, dots, until = spec.partition("..")
        if not dots and _RELEASE.match(spec):
            found = [spec]
        elif dots and _PREFIX.match(since) and _PREFIX.match(until):
            releases = drake_releases() if releases is None else releases
            found = releases_between(since, until, releases)
            if not found:
                raise ReleaseSpecError(f"{spec!r}: no Drake release on the index in this range")
        else:
            raise ReleaseSpecError(
                f"{spec!r} is not a Drake release (1.30.0) or a range of them (1.40..1.58)"
            )
        out.extend(v for v in found if v not in out)
    return out
