"""``python -m conformance._backends.worker``: a backend in its own process, over JSON lines.

Run by ``WorkerBackend`` in an environment holding one Drake release (it is
``drake==X``: an exec backend whose command the harness knows). It drives
that release's pydrake through ``SceneGraphBackend`` and speaks the worker
protocol (``docs/protocol.md``, ``backends.wire``): one request per line on
stdin, one response per line on stdout:

==================================================  ==================================
request                                             response
==================================================  ==================================
``{"call": "hello", "protocol": 1}``                ``{"value": {"protocol", "name",
                                                    "version", "features"}}``
``{"call": "reset"}``                               ``{"value": null}``
``{"call": "arm_guards", "ids": [...]}``            ``{"value": null}``
``{"call": "execute", "command": C}``               ``{"value": Result.to_json()}``
``{"call": "observe"}``                             ``{"value": Observation.to_json()}``
``{"call": "steps", "steps": [S, ...]}``            one line per step (a *batch*), each
                                                    ``{"value": {"result", "observation"}}``
anything that raises                                ``{"raised": "Type: message",
                                                    "type": "Type"}``
==================================================  ==================================

Its name is ``drake==<the release>``. Any request may carry ``"reset": true``:
the backend is reset before it is answered (the host's ``reset()`` costs no
round trip of its own).

A batch step ``S`` is ``{"command": C or null, "observe": bool}``: a null
command runs nothing (a ``check`` step) and answers an empty Result; the
observation is null unless ``observe``. A batch answers step by step, so a
worker that dies mid-case has already sent every earlier answer; a step that
raises answers ``raised`` and ends the batch.

It imports only the harness's pure-Python modules and pydrake (through
``pydrake_api``, the one module that imports it). Run as ``python -m
conformance._backends.worker reimpl`` it drives reimpl instead, following the
release its ``REIMPL_DRAKE_RELEASE`` names, and is named ``reimpl==<that
release>`` (``backends.reimpl_worker``). The host decides which
release guards are armed (``arm_guards``); with none armed, a call that
crashes the release ends this process, and the host records the crash.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from typing import Any, TextIO

from conformance._backends.api import Api
from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.scene_graph import SceneGraphBackend
from conformance._backends.wire import hello_value, raised_answer
from conformance.protocol import Command, Result

__all__ = ["serve"]


def _handlers(
    backend: SceneGraphBackend, prefix: str
) -> dict[str, Callable[[dict[str, Any]], Any]]:
    return {
        "hello": lambda r: hello_value(
            f"{prefix}{backend.version()}", backend.version(), backend.features()
        ),
        "reset": lambda r: backend.reset(),
        "arm_guards": lambda r: backend.arm_guards(frozenset(r["ids"])),
        "execute": lambda r: backend.execute(Command.from_json(r["command"])).to_json(),
        "observe": lambda r: backend.observe().to_json(),
    }


def _step(backend: SceneGraphBackend, step: dict[str, Any]) -> dict[str, Any]:
    command = step["command"]
    result = Result() if command is None else backend.execute(Command.from_json(command))
    observation = backend.observe().to_json() if step["observe"] else None
    return {"result": result.to_json(), "observation": observation}


def _reimpl_api() -> Api:
    from conformance._backends.reimpl_api import reimpl_api  # noqa: PLC0415 (reimpl workers only)

    return reimpl_api()


#: The implementations a worker drives, by its command-line argument (none: pydrake), each
#: with the prefix of its name (``drake==X``, ``reimpl==X``).
IMPLEMENTATIONS: dict[str, tuple[Callable[[], Api], str]] = {
    "pydrake": (pydrake_api, "drake=="),
    "reimpl": (_reimpl_api, "reimpl=="),
}


def serve(requests: TextIO, responses: TextIO, implementation: str = "pydrake") -> None:
    """Answers requests until stdin closes."""
    api, prefix = IMPLEMENTATIONS[implementation]
    backend = SceneGraphBackend(api())
    handlers = _handlers(backend, prefix)

    def send(response: dict[str, Any]) -> None:
        responses.write(json.dumps(response) + "\n")
        responses.flush()

    for line in requests:
        request = json.loads(line)
        if request.get("reset"):
            backend.reset()
        if request["call"] == "steps":
            for step in request["steps"]:
                try:
                    send({"value": _step(backend, step)})
                except Exception as exc:
                    send(raised_answer(exc))
                    break
            continue
        try:
            send({"value": handlers[request["call"]](request)})
        except Exception as exc:
            send(raised_answer(exc))


if __name__ == "__main__":
    serve(sys.stdin, sys.stdout, sys.argv[1] if len(sys.argv) > 1 else "pydrake")
