"""The ``drake`` fixture: the implementation under test as one module namespace.

It builds on ``tests/conftest.py``'s ``api`` fixture (same parameters, same
ids), so each ported upstream test runs once on reimpl and once on pydrake,
unchanged: ``drake.geometry``, ``drake.math``, ``drake.systems.framework``
and ``drake.common.value`` are the implementation's modules.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any

import pytest

_SUBMODULES = ("geometry", "math", "systems.framework", "common.value")


@pytest.fixture
def drake(api: Any) -> ModuleType:
    """``pydrake`` or ``reimpl``, with the submodules the ported tests use imported."""
    for submodule in _SUBMODULES:
        importlib.import_module(f"{api.name}.{submodule}")
    return importlib.import_module(api.name)
