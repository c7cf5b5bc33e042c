"""Backend lookup: the built-ins by name, third-party ones as ``module:attribute``."""

from __future__ import annotations

import importlib
from collections.abc import Callable

from conformance.protocol import Backend

__all__ = ["BUILTIN_BACKENDS", "BackendLoadError", "load_backend"]


class BackendLoadError(ValueError):
    """Raised when a backend name or ``module:attribute`` cannot be turned into a backend."""


def _reimpl() -> Backend:
    from conformance.backends.reimpl_api import reimpl_api  # noqa: PLC0415 (loaded on demand)
    from conformance.backends.scene_graph import SceneGraphBackend  # noqa: PLC0415

    return SceneGraphBackend(reimpl_api())


def _pydrake() -> Backend:
    from conformance.backends.pydrake_api import pydrake_api  # noqa: PLC0415 (pydrake may be absent)
    from conformance.backends.scene_graph import SceneGraphBackend  # noqa: PLC0415

    return SceneGraphBackend(pydrake_api())


#: Built-in backends: ``reimpl`` and ``pydrake`` (in-process, the installed release).
BUILTIN_BACKENDS: dict[str, Callable[[], Backend]] = {"reimpl": _reimpl, "pydrake": _pydrake}

_REQUIRED = ("name", "version", "features", "reset", "execute", "observe")


def load_backend(spec: str) -> Backend:
    """``reimpl``, ``pydrake``, or ``package.module:attribute`` (a class or factory)."""
    if spec in BUILTIN_BACKENDS:
        try:
            return BUILTIN_BACKENDS[spec]()
        except ImportError as exc:
            raise BackendLoadError(f"backend {spec!r} is unavailable: {exc}") from None
    if ":" not in spec:
        known = ", ".join(sorted(BUILTIN_BACKENDS))
        raise BackendLoadError(
            f"unknown backend {spec!r}: use one of {known}, or package.module:attribute"
        )
    module_name, _, attribute = spec.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as exc:
        raise BackendLoadError(f"backend {spec!r}: cannot import {module_name!r}: {exc}") from None
    factory = getattr(module, attribute, None)
    if factory is None or not callable(factory):
        raise BackendLoadError(f"backend {spec!r}: {module_name} has no callable {attribute!r}")
    backend = factory()
    missing = [m for m in _REQUIRED if not hasattr(backend, m)]
    if missing:
        raise BackendLoadError(
            f"backend {spec!r} does not implement the Backend protocol: missing {missing}"
        )
    return backend  # type: ignore[no-any-return]
