"""``python -m conformance.backends.worker``: a backend in its own process, over JSON lines.

Run by ``WorkerBackend`` in an environment holding one Drake release. It
drives that release's pydrake through ``SceneGraphBackend`` and answers one
request per line on stdin with one response per line on stdout:

========================================  ==================================
request                                   response
========================================  ==================================
``{"call": "hello"}``                     ``{"value": {"version", "features"}}``
``{"call": "reset"}``                     ``{"value": null}``
``{"call": "arm_guards", "ids": [...]}``  ``{"value": null}``
``{"call": "execute", "command": C}``     ``{"value": Result.to_json()}``
``{"call": "observe"}``                   ``{"value": Observation.to_json()}``
anything that raises                      ``{"raised": "Type: message"}``
========================================  ==================================

It imports only the harness's pure-Python modules and pydrake (through
``pydrake_api``, the one module that imports it). The host decides which
release guards are armed (``arm_guards``); with none armed, a call that
crashes the release ends this process, and the host records the crash.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from typing import Any, TextIO

from conformance.backends.pydrake_api import pydrake_api
from conformance.backends.scene_graph import SceneGraphBackend
from conformance.protocol import Command

__all__ = ["serve"]


def _handlers(backend: SceneGraphBackend) -> dict[str, Callable[[dict[str, Any]], Any]]:
    return {
        "hello": lambda r: {"version": backend.version(), "features": sorted(backend.features())},
        "reset": lambda r: backend.reset(),
        "arm_guards": lambda r: backend.arm_guards(frozenset(r["ids"])),
        "execute": lambda r: backend.execute(Command.from_json(r["command"])).to_json(),
        "observe": lambda r: backend.observe().to_json(),
    }


def serve(requests: TextIO, responses: TextIO) -> None:
    """Answers requests until stdin closes."""
    handlers = _handlers(SceneGraphBackend(pydrake_api()))
    for line in requests:
        request = json.loads(line)
        try:
            response = {"value": handlers[request["call"]](request)}
        except Exception as exc:
            response = {"raised": f"{type(exc).__name__}: {exc}"}
        responses.write(json.dumps(response) + "\n")
        responses.flush()


if __name__ == "__main__":
    serve(sys.stdin, sys.stdout)
