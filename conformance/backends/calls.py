"""Calling a backend: every way a call can go wrong becomes one narrow error.

The runner and the lockstep fuzzer call backends only through ``call``. A
backend is someone else's code, so a call may raise anything (including
``SystemExit``, which must never end a run as a success), return the wrong
type, or never return. ``call`` turns each into a ``BackendError`` that
names the backend, the step and what went wrong:

==========================================  ===================================
the backend ...                             ``call`` raises
==========================================  ===================================
raises ``UnknownNameError``                 it unchanged (the input's fault)
raises ``KeyboardInterrupt``                it unchanged (the user's Ctrl-C)
raises anything else, ``SystemExit`` too    ``BackendError``
returns a value not of type ``returns``     ``BackendError``
takes longer than ``timeout`` seconds       ``StepTimeoutError`` (a ``BackendError``)
dies in its own process                     ``BackendCrashError``, naming the step
==========================================  ===================================

The timeout is a ``SIGALRM`` timer, so it works in the main thread of a
POSIX process, and it interrupts Python code only: a call stuck inside a C++
extension (pydrake) is interrupted when it returns to Python. A backend that
``times_itself`` (a worker in its own process, which waits on its pipe with
a deadline, in any thread) gets no timer here.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, TypeVar

from conformance.protocol import Backend, UnknownNameError

__all__ = [
    "DEFAULT_STEP_TIMEOUT",
    "BackendCrashError",
    "BackendError",
    "StepTimeoutError",
    "call",
    "call_function",
    "deadline",
]

#: Seconds a single backend call may take before the step is reported as a timeout.
DEFAULT_STEP_TIMEOUT = 300.0

T = TypeVar("T")

#: Raised through a backend call unchanged: they are not the backend's fault.
_PASS_THROUGH = (UnknownNameError, KeyboardInterrupt)


class BackendError(RuntimeError):
    """A backend broke (raised, returned the wrong type, or hung) at ``where``: exit 2."""

    def __init__(self, backend: str, where: str, message: str) -> None:
        super().__init__(f"backend {backend!r} at {where}: {message}")
        self.backend = backend
        self.where = where
        self.message = message


class StepTimeoutError(BackendError):
    """A backend call took longer than the step timeout."""


class BackendCrashError(BackendError):
    """The backend's own process died (a signal, or an exit) during a call."""


@contextmanager
def deadline(seconds: float | None, backend: str, where: str) -> Iterator[None]:
    """Raises ``StepTimeoutError`` in the block after ``seconds`` (None or 0: no limit).

    Outside the main thread, or where there is no ``setitimer``, there is no limit.
    """
    if (
        not seconds
        or threading.current_thread() is not threading.main_thread()
        or not hasattr(signal, "setitimer")
    ):
        yield
        return

    def expire(signum: int, frame: object) -> None:
        raise StepTimeoutError(backend, where, f"no answer within {seconds:g} s (--step-timeout)")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def call(
    backend: Backend,
    method: str,
    *args: Any,
    where: str,
    returns: type[T],
    timeout: float | None = None,
) -> T:
    """``backend.<method>(*args)``, checked as the module doc's table says."""
    return call_function(
        backend,
        lambda: getattr(backend, method)(*args),
        method,
        where=where,
        returns=returns,
        timeout=timeout,
    )


def call_function(
    backend: Backend,
    function: Callable[[], Any],
    method: str,
    *,
    where: str,
    returns: type[T] | tuple[type, ...],
    timeout: float | None = None,
) -> T:
    """``function()``, a call into ``backend`` named ``method``, checked like ``call``."""
    name = str(getattr(backend, "name", type(backend).__name__))
    if getattr(backend, "times_itself", False):  # a worker keeps its own deadline
        timeout = None
    try:
        with deadline(timeout, name, where):
            value = function()
    except _PASS_THROUGH:
        raise
    except StepTimeoutError as exc:  # the deadline's, or a worker's own (naming its call)
        raise StepTimeoutError(name, where, exc.message) from exc
    except BackendCrashError as exc:
        raise BackendCrashError(name, where, exc.message) from exc
    except BaseException as exc:
        raise BackendError(name, where, f"{method}() raised {_describe(exc)}") from exc
    if not isinstance(value, returns):
        kinds = returns if isinstance(returns, tuple) else (returns,)
        raise BackendError(
            name,
            where,
            f"{method}() returned {type(value).__name__}, "
            f"not {' or '.join(k.__name__ for k in kinds)}",
        )
    return value  # type: ignore[return-value]


def _describe(exc: BaseException) -> str:
    text = str(exc)
    if len(text) > 300:
        text = text[:300] + "…"
    return f"{type(exc).__name__}({text!r})" if text else type(exc).__name__
