"""Backend lookup: the built-ins by name, third-party ones as ``module:attribute``."""

from __future__ import annotations

import importlib
import os
import sys
from collections.abc import Callable, Sequence
from typing import Any, cast

from conformance._backends.calls import BackendError
from conformance._backends.environments import DrakeEnvironmentError
from conformance._backends.exec_backend import (
    EXEC_PREFIX,
    ExecBackend,
    ExecSpecError,
    exec_spec_command,
)
from conformance._backends.reimpl_worker import reimpl_spec_version
from conformance._backends.releases import ReleaseSpecError, check_release
from conformance._backends.subprocess_backend import worker_spec_version
from conformance.protocol import Backend

__all__ = ["BUILTIN_BACKENDS", "BackendLoadError", "load_backend"]


class BackendLoadError(ValueError):
    """Raised when a backend name or ``module:attribute`` cannot be turned into a backend."""


def _reimpl() -> Backend:
    from conformance._backends.reimpl_api import reimpl_api  # noqa: PLC0415 (loaded on demand)
    from conformance._backends.scene_graph import SceneGraphBackend  # noqa: PLC0415

    return SceneGraphBackend(reimpl_api())


def _pydrake() -> Backend:
    from conformance._backends.pydrake_api import pydrake_api  # noqa: PLC0415 (pydrake may be absent)
    from conformance._backends.scene_graph import SceneGraphBackend  # noqa: PLC0415

    return SceneGraphBackend(pydrake_api())


#: Built-in backends: ``reimpl`` and ``pydrake`` (in-process, the installed release).
BUILTIN_BACKENDS: dict[str, Callable[[], Backend]] = {"reimpl": _reimpl, "pydrake": _pydrake}

_REQUIRED = ("name", "version", "features", "reset", "execute", "observe")
#: What the identity methods (or attributes) must answer.
_ANSWERS: dict[str, tuple[type, ...]] = {
    "name": (str,),
    "version": (str,),
    "features": (frozenset, set),
}


def _describe(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__


def _import(spec: str, module_name: str) -> Any:
    """Imports ``module_name``; the current folder is importable, as under ``python -m``."""
    here = os.getcwd()
    if here not in sys.path and "" not in sys.path:
        sys.path.append(here)
    try:
        return importlib.import_module(module_name)
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # a plugin's import may raise anything
        raise BackendLoadError(
            f"backend {spec!r}: cannot import {module_name!r}: {_describe(exc)}"
        ) from None


def _make(spec: str, factory: Callable[[], Any]) -> Any:
    try:
        return factory()
    except KeyboardInterrupt:
        raise
    except BackendLoadError:
        raise
    except BaseException as exc:  # SystemExit too: a plugin must not end the run
        raise BackendLoadError(f"backend {spec!r}: its factory raised {_describe(exc)}") from None


def _checked(spec: str, backend: Any) -> Backend:
    """``backend`` if it has the protocol's methods and its name, version and features answer."""
    missing = [m for m in _REQUIRED if not hasattr(backend, m)]
    if missing:
        raise BackendLoadError(
            f"backend {spec!r} does not implement the Backend protocol: missing {missing}"
        )
    for method, kinds in _ANSWERS.items():
        try:
            value = getattr(backend, method)
            value = value() if callable(value) else value
        except KeyboardInterrupt:
            raise
        except BaseException as exc:
            raise BackendLoadError(f"backend {spec!r}: {method} raised {_describe(exc)}") from None
        if not isinstance(value, kinds):
            raise BackendLoadError(
                f"backend {spec!r}: {method} is a {type(value).__name__}, "
                f"not {' or '.join(k.__name__ for k in kinds)}"
            )
    return cast(Backend, backend)


def _worker(
    spec: str, release: str, python: Sequence[str] | None, step_timeout: float | None
) -> Backend:
    """A ``drake==X`` worker; building its environment is reported on stderr."""
    from conformance._backends.subprocess_backend import WorkerBackend  # noqa: PLC0415

    def log(line: str) -> None:
        sys.stderr.write(line + "\n")
        sys.stderr.flush()

    try:
        return WorkerBackend(release, python=python, step_timeout=step_timeout, log=log)
    except (DrakeEnvironmentError, BackendError) as exc:
        raise BackendLoadError(f"backend {spec!r}: {exc}") from None


def _exec(spec: str, step_timeout: float | None) -> Backend:
    """An ``exec:CMD`` backend: CMD speaks the worker protocol (docs/protocol.md); a
    command that cannot run, or that breaks the protocol at its ``hello``, is refused."""
    try:
        return ExecBackend(exec_spec_command(spec) or [], spec=spec, step_timeout=step_timeout)
    except ExecSpecError as exc:
        raise BackendLoadError(f"backend {spec!r}: {exc}") from None
    except BackendError as exc:
        raise BackendLoadError(f"backend {spec!r} at {exc.where}: {exc.message}") from None


def _reimpl_worker(spec: str, release: str, step_timeout: float | None) -> Backend:
    """A ``reimpl==X`` worker: reimpl following release X in its own process."""
    from conformance._backends.reimpl_worker import ReimplWorkerBackend  # noqa: PLC0415

    try:
        return ReimplWorkerBackend(release, step_timeout=step_timeout)
    except BackendError as exc:
        raise BackendLoadError(f"backend {spec!r}: {exc}") from None


def load_backend(
    spec: str, *, python: Sequence[str] | None = None, step_timeout: float | None = None
) -> Backend:
    """``reimpl``, ``pydrake``, ``drake==X`` (release X in a worker process),
    ``reimpl==X`` (reimpl following release X, in a worker process),
    ``exec:CMD ARGS`` (any program that speaks the worker protocol), or
    ``package.module:attribute`` (a class or factory).

    For ``drake==X``: ``python`` are the interpreters to choose from (``--python``;
    default: discovered), and ``step_timeout`` the seconds the worker may take
    for one answer (it times itself, in any thread).

    Anything that goes wrong (an import or a factory raising, a missing
    method, a ``version()`` that is not a string) is a ``BackendLoadError``
    naming the spec.
    """
    if spec in BUILTIN_BACKENDS:
        try:
            return BUILTIN_BACKENDS[spec]()
        except ImportError as exc:
            raise BackendLoadError(f"backend {spec!r} is unavailable: {exc}") from None
    release = worker_spec_version(spec)
    if release is not None:
        try:
            check_release(release)
        except ReleaseSpecError as exc:
            raise BackendLoadError(f"backend {spec!r}: {exc}") from None
        return _worker(spec, release, python, step_timeout)
    followed = reimpl_spec_version(spec)
    if followed is not None:
        try:
            check_release(followed)
        except ReleaseSpecError as exc:
            raise BackendLoadError(f"backend {spec!r}: {exc}") from None
        return _reimpl_worker(spec, followed, step_timeout)
    if spec.startswith(EXEC_PREFIX):
        return _exec(spec, step_timeout)
    if ":" not in spec:
        known = ", ".join(sorted(BUILTIN_BACKENDS))
        raise BackendLoadError(
            f"unknown backend {spec!r}: use one of {known}, drake==X.Y.Z, reimpl==X.Y.Z, "
            "exec:'CMD ARGS', or package.module:attribute"
        )
    module_name, _, attribute = spec.partition(":")
    module = _import(spec, module_name)
    factory = getattr(module, attribute, None)
    if factory is None or not callable(factory):
        raise BackendLoadError(f"backend {spec!r}: {module_name} has no callable {attribute!r}")
    return _checked(spec, _make(spec, factory))
