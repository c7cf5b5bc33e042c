"""Where a parse error happened, and how Drake 1.51.1 prints it (measured).

Drake's parsers report through a diagnostic policy; ``Parser`` turns the first
error into an exception and logs warnings. The message names the source when
it knows one:

=======================================  ==============================================
 known                                    message
=======================================  ==============================================
 file and line                            ``<literal-string>.urdf:3: error: ...``
 file only                                ``<literal-string>.sdf: error: ...``
 neither (e.g. groups checked at the end) ``error: ...``
=======================================  ==============================================

A model given as text is named ``<literal-string>.<file_type>``; a file by its
path. SDFormat's own checks name the text ``<data-string>`` instead, and end
with a newline; ``SdformatSource`` formats those. Warnings go to the ``drake``
logger, as pydrake's do; inside ``recorded_warnings()`` they are also collected
(as Drake's sub-diagnostic policy collects a custom-parsed include's).
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

__all__ = ["Diagnostics", "ModelParseError", "literal_string_name", "recorded_warnings"]

_LOG = logging.getLogger("drake")
#: the innermost ``recorded_warnings()`` block's list, if any
_RECORDER: ContextVar[list[str] | None] = ContextVar("reimpl_recorded_warnings", default=None)


class ModelParseError(RuntimeError):
    """Raised for a model that Drake's parsers reject; the message is Drake's."""


def literal_string_name(file_type: str) -> str:
    """How Drake names model text that did not come from a file."""
    return f"<literal-string>.{file_type}"


@dataclass(frozen=True)
class Diagnostics:
    """Reports errors and warnings about one source (a file, or model text).

    ``filename`` is None where Drake prints no source at all. With ``strict``
    (``Parser.SetStrictParsing()``) a warning is an error.
    """

    filename: str | None
    strict: bool = False

    def _locate(self, line: int | None) -> str:
        if self.filename is None:
            return ""
        if line is None:
            return f"{self.filename}: "
        return f"{self.filename}:{line}: "

    def error(self, message: str, line: int | None = None) -> ModelParseError:
        """The exception to raise: ``raise diagnostics.error(...)``."""
        return ModelParseError(f"{self._locate(line)}error: {message}")

    def warning(self, message: str, line: int | None = None) -> None:
        if self.strict:
            raise self.error(message, line)
        _LOG.warning("%swarning: %s", self._locate(line), message)
        recorder = _RECORDER.get()
        if recorder is not None:
            recorder.append(f"{self._locate(line)}warning: {message}")


@contextmanager
def recorded_warnings() -> Iterator[list[str]]:
    """The warnings reported while the block runs (logged as well), in order; a block
    inside another records its own only."""
    found: list[str] = []
    token = _RECORDER.set(found)
    try:
        yield found
    finally:
        _RECORDER.reset(token)
