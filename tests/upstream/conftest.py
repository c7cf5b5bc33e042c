"""The ``drake`` fixture: the implementation under test as one module namespace.

It builds on ``tests/conftest.py``'s ``api`` fixture (same parameters, same
ids), so each ported upstream test runs once on reimpl and once on pydrake,
unchanged: ``drake.geometry``, ``drake.math``, ``drake.systems.framework``
``drake.common.value`` and ``drake.multibody.{plant,parsing,tree}`` are the
implementation's modules. ``drake_models`` is the vendored copy of Drake's model
files (``scenarios/real_models/drake``), for tests that parse Drake's own test models.
"""

from __future__ import annotations

import importlib
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

#: Drake's model files, vendored at Drake's own paths (scenarios/real_models/README.md).
DRAKE_MODELS = Path(__file__).resolve().parents[2] / "scenarios" / "real_models" / "drake"

_SUBMODULES = (
    "geometry",
    "math",
    "systems.framework",
    "common.value",
    "multibody.plant",
    "multibody.parsing",
    "multibody.tree",
)


@pytest.fixture
def drake(api: Any) -> ModuleType:
    """``pydrake`` or ``reimpl``, with the submodules the ported tests use imported."""
    for submodule in _SUBMODULES:
        importlib.import_module(f"{api.name}.{submodule}")
    return importlib.import_module(api.name)


@pytest.fixture
def drake_models() -> Path:
    """The root of the vendored Drake checkout: ``drake_models / "multibody/parsing/test/..."``."""
    return DRAKE_MODELS
