"""The one module that imports pydrake in-process.

Everything else reaches pydrake through ``pydrake_api()``, which returns the
same ``Api`` shape that reimpl provides, so one backend class drives both.
"""

from __future__ import annotations

import importlib
import importlib.metadata
from types import ModuleType

from conformance._backends.api import Api

__all__ = ["PydrakeUnavailableError", "pydrake_api"]


class PydrakeUnavailableError(ImportError):
    """Raised when pydrake cannot be imported in this environment."""


def pydrake_api() -> Api:
    """The pydrake modules of this environment, with the installed Drake version."""
    try:
        import pydrake.geometry  # noqa: PLC0415 (deferred: a missing pydrake is a usage error)
        import pydrake.math  # noqa: PLC0415
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise PydrakeUnavailableError(
            f"pydrake is not importable here ({exc}); install it with `pip install drake`"
        ) from exc
    return Api(
        name="pydrake",
        version=importlib.metadata.version("drake"),
        geometry=pydrake.geometry,
        math=pydrake.math,
        plant=_optional("pydrake.multibody.plant"),
        tree=_optional("pydrake.multibody.tree"),
        parsing=_optional("pydrake.multibody.parsing"),
    )


def _optional(name: str) -> ModuleType | None:
    """The module ``name``, or None where it cannot be imported (its feature tags are then
    missing: Drake 1.12-1.23 under numpy 2 cannot import ``pydrake.multibody``)."""
    try:
        return importlib.import_module(name)
    except ImportError:
        return None
