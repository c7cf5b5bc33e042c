"""The worker protocol's wire format: its version, its calls and the answers both sides build.

A backend in its own process (``exec:CMD``, and ``drake==X``, whose worker is
``python -m conformance._backends.worker``) reads one JSON request per line on
stdin and writes one JSON response per line on stdout. ``docs/protocol.md``
describes the protocol; ``conformance.protocol_schemas`` holds one JSON Schema
per message. This module is what the host (``exec_backend``) and the Python
worker share, and imports nothing but the standard library and
``conformance.protocol``, so the worker runs in an environment holding only a
Drake release.

Versioning: ``PROTOCOL_VERSION`` is one integer. The host sends it in
``hello`` and accepts only a backend that answers the same number. Within a
version, changes are additive: a request may gain members (a backend ignores
members it does not know) and the grammar may gain ops (sent only in cases
whose features the backend declared). Anything else (a new call every
backend must answer, a new required member, a changed meaning) is a new
version.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from conformance.protocol import UnknownNameError

__all__ = [
    "CALLS",
    "PROTOCOL_VERSION",
    "hello_request",
    "hello_value",
    "raised_answer",
]

#: The protocol version this harness speaks (see the module doc).
PROTOCOL_VERSION = 1

#: Every call a backend answers, in the order docs/protocol.md lists them.
CALLS: tuple[str, ...] = ("hello", "reset", "arm_guards", "execute", "observe", "steps")


def hello_request() -> dict[str, Any]:
    """The first request to every process: the host's protocol version."""
    return {"call": "hello", "protocol": PROTOCOL_VERSION}


def hello_value(name: str, version: str, features: Iterable[str]) -> dict[str, Any]:
    """A backend's answer to ``hello``: its protocol, name, Drake release and features."""
    return {
        "protocol": PROTOCOL_VERSION,
        "name": name,
        "version": version,
        "features": sorted(features),
    }


def raised_answer(exc: BaseException) -> dict[str, Any]:
    """The error answer for a call that raised ``exc``; an ``UnknownNameError`` (the
    input's fault, raised again by the host) carries its kind and name."""
    kind = type(exc).__name__
    answer: dict[str, Any] = {"raised": f"{kind}: {exc}", "type": kind}
    if isinstance(exc, UnknownNameError):
        answer["unknown"] = [exc.kind, exc.name]
    return answer
