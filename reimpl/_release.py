"""The Drake release reimpl follows, and the release facts that hold for it.

reimpl behaves as one Drake release, chosen once per process: the
environment variable ``REIMPL_DRAKE_RELEASE`` (``X.Y.Z``, any release the
release table describes: 1.12.0 to 1.58.0), else 1.51.1, the release pip
serves to Python 3.11. ``release.has(fact_id)`` says whether a row of the
release table (``conformance/_policy/release_facts.json``, read here as data,
not through the harness's code) holds for that release.

Each place where releases differ asks one named fact, next to the rule it
changes: a binding row decides whether a class defines the binding at all
(``if release.has("activation-since-1.55"):`` in the class body, so an
absent binding is absent as in that release's pydrake), a behaviour row picks
the rule, a wording row the message. An unknown fact id is a KeyError, so a
misspelt switch fails at import. ``@release.binding("<id>")`` on a method is the
same gate as the ``if`` in the class body, written on the method's own line.
"""

from __future__ import annotations

import json
import os
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from importlib import resources
from typing import Any, TypeVar

__all__ = ["DEFAULT_RELEASE", "RELEASE_VARIABLE", "Release", "release"]

#: The environment variable that chooses the release.
RELEASE_VARIABLE = "REIMPL_DRAKE_RELEASE"
#: The release reimpl follows when the variable is unset.
DEFAULT_RELEASE = "1.51.1"
_RELEASE = re.compile(r"^\d+\.\d+\.\d+$")

Version = tuple[int, ...]
_Method = TypeVar("_Method", bound=Callable[..., Any])


def _version(text: str) -> Version:
    return tuple(int(part) for part in text.split("."))


@dataclass(frozen=True)
class _Range:
    """since ≤ version ≤ until; ``until`` may be a prefix (1.51 covers 1.51.x)."""

    since: Version | None
    until: Version | None

    def __contains__(self, version: Version) -> bool:
        if self.since is not None and version < self.since:
            return False
        return self.until is None or version[: len(self.until)] <= self.until


class Release:
    """A Drake release and the table's facts: ``has(fact_id)`` for that release."""

    def __init__(self, version: str, facts: Mapping[str, _Range]) -> None:
        self.version = version
        self._version = _version(version)
        self._facts = facts

    def has(self, fact_id: str) -> bool:
        """Whether the release fact ``fact_id`` holds for this release (KeyError if unknown)."""
        try:
            fact = self._facts[fact_id]
        except KeyError:
            raise KeyError(f"no release fact {fact_id!r} in release_facts.json") from None
        return self._version in fact

    def binding(self, fact_id: str) -> Callable[[_Method], _Method]:
        """A method decorator: the class defines the method only where the binding row
        ``fact_id`` holds (else the name is left out of the class, as pydrake leaves it)."""
        if self.has(fact_id):
            return lambda method: method
        return lambda method: _Unbound()  # type: ignore[return-value]

    def __repr__(self) -> str:
        return f"Release({self.version!r})"


class _Unbound:
    """A class attribute that removes itself when the class is made (``type.__new__``
    calls ``__set_name__`` on a copy of the class namespace, so the removal is safe)."""

    def __set_name__(self, owner: type, name: str) -> None:
        delattr(owner, name)


def _load(version: str) -> Release:
    path = resources.files("conformance._policy").joinpath("release_facts.json")
    table = json.loads(path.read_text("utf-8"))
    first, last = _version(table["first_release"]), _version(table["last_release"])
    if not _RELEASE.match(version) or not first <= _version(version) <= last:
        raise ValueError(
            f"{RELEASE_VARIABLE}={version!r}: reimpl follows a Drake release from "
            f"{table['first_release']} to {table['last_release']} (X.Y.Z)"
        )
    facts = {
        row["id"]: _Range(
            *(
                _version(row["releases"][key]) if key in row["releases"] else None
                for key in ("since", "until")
            )
        )
        for row in table["facts"]
    }
    return Release(version, facts)


#: The release this process's reimpl follows.
release: Release = _load(os.environ.get(RELEASE_VARIABLE) or DEFAULT_RELEASE)
