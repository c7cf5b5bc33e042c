"""reimpl's modules in the ``Api`` shape, for the ``reimpl`` backend."""

from __future__ import annotations

import importlib
from types import ModuleType

import reimpl.geometry
import reimpl.math
from conformance._backends.api import Api
from reimpl._release import release

__all__ = ["REIMPL_DRAKE_VERSION", "reimpl_api"]

#: The Drake release whose observable semantics reimpl follows in this process
#: (``REIMPL_DRAKE_RELEASE``, default 1.51.1: ``reimpl/_release.py``).
REIMPL_DRAKE_VERSION = release.version


def reimpl_api() -> Api:
    return Api(
        name="reimpl",
        version=REIMPL_DRAKE_VERSION,
        geometry=reimpl.geometry,
        math=reimpl.math,
        plant=_optional("reimpl.multibody.plant"),
        tree=_optional("reimpl.multibody.tree"),
        parsing=_optional("reimpl.multibody.parsing"),
    )


def _optional(name: str) -> ModuleType | None:
    """reimpl's module ``name``, or None while it does not exist (its features are missing)."""
    try:
        return importlib.import_module(name)
    except ModuleNotFoundError as exc:
        if exc.name is not None and name.startswith(exc.name):
            return None
        raise
