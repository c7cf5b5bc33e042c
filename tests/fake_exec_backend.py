"""A backend in another process for ``tests/test_exec_backend.py``: reimpl behind the worker
protocol, with one fault on demand.

``python tests/fake_exec_backend.py [--fault FAULT] [--case N] [--once FILE] [--features F,..]``

========================  ==================================================================
fault                     what the process does
========================  ==================================================================
(none)                    answers like any backend (name ``fake-reimpl``)
``crash``                 exits (status 3) after answering the first step of batch ``N``
``hang``                  stops answering after the first step of batch ``N``
``malformed``             answers the first step of batch ``N`` with a Result that has
                          neither ``value`` nor ``error``
``arm-crash``             exits (status 3) when asked ``arm_guards`` (before the first batch)
``protocol-2``            answers ``hello`` with protocol 2
``garbage``               answers ``hello`` with a line that is not JSON
========================  ==================================================================

``--features`` declares those features only, and a command whose op needs another is an
unknown command (so a host that sends one fails).

With ``--once FILE`` the fault happens once: the process that meets it first creates FILE,
and processes that find it answer normally (a crash's replacement does not crash again).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's conformance

from conformance._backends.loader import load_backend
from conformance._backends.wire import hello_value, raised_answer
from conformance._grammar import features_of
from conformance.protocol import Command, Result, UnknownNameError


def _arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    parser.add_argument("--fault", default=None)
    parser.add_argument("--case", type=int, default=1)
    parser.add_argument("--once", type=Path, default=None)
    parser.add_argument("--features", default=None)
    return parser.parse_args()


def send(response: Any) -> None:
    sys.stdout.write((response if isinstance(response, str) else json.dumps(response)) + "\n")
    sys.stdout.flush()


class Fake:
    """reimpl, answering requests, with the fault of the module doc."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.args = args
        self.once_done = args.once is not None and args.once.exists()
        self.fault = None if self.once_done else args.fault
        self.backend = load_backend("reimpl")
        self.features = (
            self.backend.features() if args.features is None else args.features.split(",")
        )
        self.batches = 0

    def execute(self, data: dict[str, Any]) -> Result:
        command = Command.from_json(data)
        if not features_of([command.op]) <= frozenset(self.features):
            raise UnknownNameError("command", command.op)
        return self.backend.execute(command)

    def hello(self, request: dict[str, Any]) -> None:
        if self.fault == "garbage":
            send("hello, harness")
            return
        value = hello_value("fake-reimpl", self.backend.version(), self.features)
        if self.fault == "protocol-2":
            value["protocol"] = 2
        send({"value": value})

    def faulty_step(self) -> None:
        if self.args.once is not None:
            self.args.once.touch()
        if self.fault in ("crash", "arm-crash"):
            os._exit(3)
        if self.fault == "hang":
            time.sleep(3600)
        if self.fault == "malformed":
            send({"value": {"result": {"valu": None}, "observation": None}})

    def steps(self, request: dict[str, Any]) -> None:
        self.batches += 1
        for index, step in enumerate(request["steps"]):
            if self.fault is not None and self.batches == self.args.case and index == 1:
                self.faulty_step()
                return
            try:
                command = step["command"]
                result = Result() if command is None else self.execute(command)
                observation = self.backend.observe().to_json() if step["observe"] else None
                send({"value": {"result": result.to_json(), "observation": observation}})
            except Exception as exc:
                send(raised_answer(exc))
                return

    def answer(self, request: dict[str, Any]) -> None:
        if request.get("reset"):
            self.backend.reset()
        call = request["call"]
        if call in ("hello", "steps"):
            getattr(self, call)(request)
            return
        try:
            if call == "execute":
                send({"value": self.execute(request["command"]).to_json()})
            elif call == "observe":
                send({"value": self.backend.observe().to_json()})
            elif call == "arm_guards" and self.fault == "arm-crash":
                self.faulty_step()
            else:  # reset, arm_guards
                send({"value": None})
        except Exception as exc:
            send(raised_answer(exc))


def main() -> None:
    fake = Fake(_arguments())
    for line in sys.stdin:
        fake.answer(json.loads(line))


if __name__ == "__main__":
    main()
