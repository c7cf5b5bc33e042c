"""Drake's own log lines during a case: kept with the case, not written to stderr.

pydrake routes Drake's C++ log (spdlog) to Python's ``logging``, logger
``drake``; reimpl logs the same warnings there (a URDF floating joint, a
package path ignored, ...). Left alone they reach stderr through the root
logger's handlers (``WARNING:drake:...``), case after case of a run that
passes. While ``drake_log_of_case`` is open, the records of WARNING and above
that the calling thread makes on ``drake`` go to its list of lines instead,
formatted as stderr showed them (``WARNING:drake:message``); the run shows
them with ``-v``, and in the report of a case that fails.

One handler serves every thread (matrix columns run in threads): it is
installed, and the logger's propagation turned off, while any thread
captures, and records of a thread that does not capture are passed to the
root logger's handlers (or ``logging.lastResort``), as propagation would.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["DRAKE_LOGGER", "drake_log_of_case"]

#: The logger pydrake's C++ log and reimpl's mirrored warnings are written to.
DRAKE_LOGGER = "drake"

_FORMAT = logging.Formatter("%(levelname)s:%(name)s:%(message)s")


class _CaseHandler(logging.Handler):
    def __init__(self) -> None:
        super().__init__(level=logging.WARNING)
        self.local = threading.local()

    def emit(self, record: logging.LogRecord) -> None:
        lines: list[str] | None = getattr(self.local, "lines", None)
        if lines is not None:
            lines.append(_FORMAT.format(record))
            return
        handlers: list[logging.Handler | None] = [*logging.getLogger().handlers]
        for handler in handlers or [logging.lastResort]:
            if handler is not None and record.levelno >= handler.level:
                handler.handle(record)


_HANDLER = _CaseHandler()
_LOCK = threading.Lock()
_users = 0
_propagate = True


def _install() -> None:
    global _users, _propagate  # noqa: PLW0603 (one handler for the process)
    logger = logging.getLogger(DRAKE_LOGGER)
    with _LOCK:
        if _users == 0:
            _propagate = logger.propagate
            logger.addHandler(_HANDLER)
            logger.propagate = False
        _users += 1


def _uninstall() -> None:
    global _users  # noqa: PLW0603
    logger = logging.getLogger(DRAKE_LOGGER)
    with _LOCK:
        _users -= 1
        if _users == 0:
            logger.removeHandler(_HANDLER)
            logger.propagate = _propagate


@contextmanager
def drake_log_of_case() -> Iterator[list[str]]:
    """The lines Drake (or reimpl) logs in this thread while open; none reach stderr."""
    lines: list[str] = []
    outer = getattr(_HANDLER.local, "lines", None)
    _install()
    _HANDLER.local.lines = lines
    try:
        yield lines
    finally:
        _HANDLER.local.lines = outer
        _uninstall()
