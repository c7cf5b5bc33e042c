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
breaks the worker protocol (``exec:``)       ``BackendProtocolError``, naming the step
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
from collections.abc import Callable
from typing import Any, TypeVar

from conformance.protocol import Backend, UnknownNameError

__all__ = [
    "DEFAULT_STEP_TIMEOUT",
    "BackendCrashError",
    "BackendError",
    "BackendProtocolError",
    "StepTimeoutError",
    "Where",
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


class BackendProtocolError(BackendError):
    """A backend in its own process answered what the worker protocol does not allow: not
    JSON, another protocol version, a response that fails its schema (docs/protocol.md)."""


class _Alarm:
    """The one SIGALRM handler: raises ``StepTimeoutError`` for the call it is armed for.

    Installed once and then left in place (installing a handler per call cost
    most of a fuzz step's harness time); with nothing armed it hands the
    signal to the handler it replaced.
    """

    armed: tuple[str, Where, float] | None = None
    previous: Any = signal.SIG_DFL

    @classmethod
    def install(cls) -> None:
        if signal.getsignal(signal.SIGALRM) != cls.fire:  # (a new bound method each time)
            cls.previous = signal.signal(signal.SIGALRM, cls.fire)

    @classmethod
    def fire(cls, signum: int, frame: Any) -> None:
        if cls.armed is not None:
            backend, where, seconds = cls.armed
            raise StepTimeoutError(
                backend, _text(where), f"no answer within {seconds:g} s (--step-timeout)"
            )
        previous = cls.previous
        if callable(previous):
            previous(signum, frame)
        elif previous != signal.SIG_IGN:  # the default action: end the process
            signal.signal(signal.SIGALRM, signal.SIG_DFL)
            signal.raise_signal(signal.SIGALRM)


class deadline:  # noqa: N801 (a context manager, used as ``with deadline(...)``)
    """Raises ``StepTimeoutError`` in the block after ``seconds`` (None or 0: no limit).

    Outside the main thread, or where there is no ``setitimer``, there is no limit.
    """

    def __init__(self, seconds: float | None, backend: str, where: Where) -> None:
        self.armed = (
            (backend, where, seconds)
            if seconds
            and hasattr(signal, "setitimer")
            and threading.current_thread() is threading.main_thread()
            else None
        )
        self.outer: tuple[str, Where, float] | None = None

    def __enter__(self) -> None:
        if self.armed is not None:
            _Alarm.install()
            self.outer, _Alarm.armed = _Alarm.armed, self.armed
            signal.setitimer(signal.ITIMER_REAL, self.armed[2])

    def __exit__(self, *exc_info: object) -> None:
        if self.armed is not None:
            signal.setitimer(signal.ITIMER_REAL, 0)
            _Alarm.armed = self.outer


#: Where a call is, for its error message: the text, or a function that makes it
#: (called only when the call goes wrong, so a step need not format it up front).
Where = str | Callable[[], str]


def call(
    backend: Backend,
    method: str,
    *args: Any,
    where: Where,
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
    where: Where,
    returns: type[T] | tuple[type, ...],
    timeout: float | None = None,
) -> T:
    """``function()``, a call into ``backend`` named ``method``, checked like ``call``."""
    name = str(getattr(backend, "name", type(backend).__name__))
    if getattr(backend, "times_itself", False):  # a worker keeps its own deadline
        timeout = None
    try:
        with deadline(timeout, name, where):  # a Where function is called only if it fires
            value = function()
    except _PASS_THROUGH:
        raise
    except BackendError as exc:  # the deadline's, or a worker's own (naming its call)
        raise type(exc)(name, _text(where), exc.message) from exc
    except BaseException as exc:
        raise BackendError(name, _text(where), f"{method}() raised {_describe(exc)}") from exc
    if not isinstance(value, returns):
        kinds = returns if isinstance(returns, tuple) else (returns,)
        raise BackendError(
            name,
            _text(where),
            f"{method}() returned {type(value).__name__}, "
            f"not {' or '.join(k.__name__ for k in kinds)}",
        )
    return value  # type: ignore[return-value]


def _text(where: Where) -> str:
    return where if isinstance(where, str) else where()


def _describe(exc: BaseException) -> str:
    try:
        text = str(exc)
    except Exception:  # a plugin's exception may fail to print
        return f"{type(exc).__name__} (whose str() raised)"
    if len(text) > 300:
        text = text[:300] + "…"
    return f"{type(exc).__name__}({text!r})" if text else type(exc).__name__
