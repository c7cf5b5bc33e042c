"""``exec:CMD``: a backend in any language, in its own process, over the worker protocol.

``ExecBackend`` runs a command (``shlex``-split; its working directory is the
caller's) and speaks the worker protocol with it (``docs/protocol.md``,
``backends.wire``): JSON requests, one per line, on its stdin; JSON
responses, one per line, on its stdout; its stderr is kept and quoted if it
dies. ``drake==X`` is one such backend whose command the harness knows
(``subprocess_backend.WorkerBackend``).

Every process it starts is first asked ``hello``: a backend that answers
another protocol version, or garbage, or an error, is refused
(``BackendProtocolError``). Its name, Drake release and features are those
of its first ``hello`` (unless the spec fixes the name, as ``drake==X``
does); a process that replaces it must answer the same.

It is *isolated*: when the process dies (a signal such as SIGABRT or
SIGSEGV, or an exit) the call raises ``BackendCrashError`` with the signal
and the tail of its stderr, and when a call times out the process is
killed; either way the next ``reset()`` starts a new process, so a run
records the crash and goes on. A process times itself: every answer must
come within ``step_timeout`` seconds (``select`` on its pipe), so a hang is a
``StepTimeoutError`` in any thread (a new process's ``hello`` may take
``STARTUP_SECONDS``: a Python worker imports pydrake first).

With ``validate`` (the default), every response is checked against its
message's JSON Schema (``conformance.protocol_schemas``); one that fails, or
a line that is not JSON, is a ``BackendProtocolError`` naming the call,
where the response is wrong and why. ``run_steps`` sends a whole case in one
request (a *batch*) and reads the answers as they come; ``reset`` travels
with the next request (and changed guards just before it), so a case costs
one round trip. ``transcript``, if a
list, receives every request and response as ``(direction, message)``.
"""

from __future__ import annotations

import contextlib
import json
import os
import select
import shlex
import signal
import subprocess
import tempfile
import time
import weakref
from collections.abc import Iterator, Mapping, Sequence
from typing import IO, Any

from conformance._backends.calls import (
    BackendCrashError,
    BackendError,
    BackendProtocolError,
    StepTimeoutError,
)
from conformance._backends.wire import PROTOCOL_VERSION, hello_request
from conformance._corpus_root import corpus_root
from conformance.protocol import Command, Observation, Result, UnknownNameError

__all__ = [
    "CORPUS_PLACEHOLDER",
    "EXEC_PREFIX",
    "STARTUP_SECONDS",
    "ExecBackend",
    "ExecSpecError",
    "exec_spec_command",
    "portable",
]

EXEC_PREFIX = "exec:"
#: Lines of the process's stderr quoted when it dies.
_STDERR_TAIL = 8

#: What stands for the corpus's folder in a quoted stderr (``portable``).
CORPUS_PLACEHOLDER = "<corpus>"


def portable(text: str) -> str:
    """``text`` with the corpus's folder (``corpus_root``) written as ``CORPUS_PLACEHOLDER``:
    a worker's stderr quotes the model files it read by absolute path, and a report
    that keeps it must read the same from any checkout or install."""
    try:
        root = str(corpus_root())
    except FileNotFoundError:
        return text
    return text.replace(root, CORPUS_PLACEHOLDER)


#: Seconds a new process may take for its ``hello`` (a Python worker imports pydrake first).
STARTUP_SECONDS = 120.0
#: Characters of a bad line quoted in an error.
_QUOTED = 120


class ExecSpecError(ValueError):
    """An ``exec:`` spec that names no command, or whose quoting is broken."""


def exec_spec_command(spec: str) -> list[str] | None:
    """The argv of an ``exec:CMD ARGS`` spec (``shlex`` rules), else None."""
    if not spec.startswith(EXEC_PREFIX):
        return None
    try:
        argv = shlex.split(spec[len(EXEC_PREFIX) :])
    except ValueError as exc:
        raise ExecSpecError(f"cannot split the command: {exc}") from None
    if not argv:
        raise ExecSpecError("no command after 'exec:' (e.g. exec:'node backend.js')")
    return argv


def _exit_description(code: int) -> str:
    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exited with status {code}"


def _quote(line: bytes) -> str:
    text = line.decode("utf-8", errors="replace")
    return repr(text if len(text) <= _QUOTED else text[:_QUOTED] + "…")


class ExecBackend:
    """The backend protocol, served by a process that speaks the worker protocol."""

    #: A crash or a timeout does not spoil later cases: the process is replaced.
    isolated = True
    #: It keeps its own deadline (``step_timeout``), so ``calls.call`` sets no timer.
    times_itself = True

    def __init__(
        self,
        command: Sequence[str],
        *,
        spec: str | None = None,
        name: str | None = None,
        env: Mapping[str, str] | None = None,
        step_timeout: float | None = None,
        validate: bool = True,
        transcript: list[tuple[str, Any]] | None = None,
    ) -> None:
        self.command = list(command)
        self.spec = spec or EXEC_PREFIX + shlex.join(self.command)
        #: The spec until ``hello`` answers; then its name (unless ``name`` fixes it).
        self.name = name or self.spec
        self._fixed_name = name is not None
        self._env = dict(env) if env is not None else None
        #: Seconds an answer may take (None or 0: no limit).
        self.step_timeout = step_timeout
        self.validate = validate
        self.transcript = transcript
        self._process: subprocess.Popen[bytes] | None = None
        self._stderr: IO[str] | None = None
        self._pending = bytearray()  # read from the process, not yet a whole line
        self._starting = False  # no answer yet from the running process
        self._reset_pending = False  # reset() was called: the next request resets first
        #: The guards the host armed (None: the backend's own default).
        self._armed: list[str] | None = None
        self._arm_pending = False  # arm_guards() changed them: sent before the next request
        self._hello: dict[str, Any] | None = None
        weakref.finalize(self, ExecBackend.close, self)
        self._start()

    # ------------------------------------------------------------- process
    @property
    def pid(self) -> int | None:
        """The running process's id (None if there is none)."""
        return None if self._process is None else self._process.pid

    def _start(self) -> subprocess.Popen[bytes]:
        """A new process in place of the last one (reaped, its pipes closed, if it died),
        after its ``hello``."""
        self._stop()
        # Kept open for the process's life (read when it dies), closed by the next _start.
        if self._stderr is not None:
            self._stderr.close()
        self._stderr = tempfile.TemporaryFile(mode="w+", encoding="utf-8")  # noqa: SIM115
        self._pending.clear()
        self._starting = True
        try:
            self._process = subprocess.Popen(
                self.command,
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=self._stderr,
                bufsize=0,
                env=self._env,
            )
        except OSError as exc:
            raise BackendError(
                self.name, "start", f"cannot run {self.command[0]!r}: {exc.strerror or exc}"
            ) from None
        self._handshake(self._process)
        return self._process

    def _handshake(self, process: subprocess.Popen[bytes]) -> None:
        """Sends ``hello`` and takes the answer: the protocol version first, then the rest.

        A process that exits at once may have said why on stdout: that is read first.
        """
        with contextlib.suppress(BackendCrashError):  # its answer, or its end, says what happened
            self._write(process, hello_request())
        response = self._response(process, "hello", check=False)
        value = response.get("value")
        protocol = value.get("protocol") if isinstance(value, dict) else None
        if protocol is not None and protocol != PROTOCOL_VERSION:
            raise self._refuse(
                "hello",
                f"it speaks protocol {protocol!r}; this harness speaks protocol "
                f"{PROTOCOL_VERSION} (docs/protocol.md)",
            )
        if "raised" in response:
            raise self._refuse("hello", f"it answered hello with an error: {response['raised']}")
        self._check(response, "hello")
        if not isinstance(value, dict):
            raise self._refuse("hello", f"its hello response has no value: {json.dumps(response)}")
        if self._hello is None:
            self._hello = value
            if not self._fixed_name:
                self.name = str(value["name"])
        elif value != self._hello:
            raise self._refuse(
                "hello",
                f"a new process answered hello {json.dumps(value)}, "
                f"the first {json.dumps(self._hello)}",
            )

    def _refuse(self, call: str, message: str) -> BackendProtocolError:
        """The error for a process that broke the protocol; the process is discarded."""
        self._stop()
        return BackendProtocolError(self.name, call, message)

    def _stop(self) -> None:
        """Kills the process (if any) and closes its pipes; the next request starts a new one."""
        process, self._process = self._process, None
        if process is None:
            return
        if process.poll() is None:
            process.kill()
        process.wait()
        for pipe in (process.stdin, process.stdout):
            if pipe is not None:
                pipe.close()

    def _stderr_tail(self) -> str:
        if self._stderr is None:
            return ""
        self._stderr.seek(0)
        lines = self._stderr.read().strip().splitlines()[-_STDERR_TAIL:]
        return portable("\n".join(lines))

    def _crash(self, process: subprocess.Popen[bytes], call: str) -> BackendCrashError:
        """The error for a process that died; the process is discarded."""
        code = process.wait()
        tail = self._stderr_tail()
        self._stop()
        message = f"the worker {_exit_description(code)}"
        return BackendCrashError(
            self.name, call, message + (f"; its stderr ends:\n{tail}" if tail else "")
        )

    def _readline(self, process: subprocess.Popen[bytes], call: str) -> bytes:
        """The process's next line (b"" if it closed its output), within ``step_timeout``."""
        assert process.stdout is not None
        fd = process.stdout.fileno()
        seconds = self.step_timeout
        if seconds and self._starting:
            seconds = max(seconds, STARTUP_SECONDS)
        limit = None if not seconds else time.monotonic() + seconds
        while (end := self._pending.find(b"\n")) < 0:
            wait = None if limit is None else limit - time.monotonic()
            if wait is not None and (wait <= 0 or not select.select([fd], [], [], wait)[0]):
                why = "--step-timeout" if seconds == self.step_timeout else "a new process's hello"
                raise StepTimeoutError(self.name, call, f"no answer within {seconds:g} s ({why})")
            chunk = os.read(fd, 1 << 16)
            if not chunk:
                return b""
            self._pending += chunk
        line = bytes(self._pending[:end])
        del self._pending[: end + 1]
        self._starting = False
        return line

    def _write(self, process: subprocess.Popen[bytes], request: dict[str, Any]) -> None:
        assert process.stdin is not None
        if self.transcript is not None:
            self.transcript.append(("request", request))
        try:
            process.stdin.write(json.dumps(request).encode() + b"\n")
        except BrokenPipeError:
            raise BackendCrashError(self.name, request["call"], "its stdin is closed") from None

    def _send(self, request: dict[str, Any], *, fresh: bool = False) -> subprocess.Popen[bytes]:
        """Writes ``request`` to the process; see ``_request`` for ``fresh``.

        A pending reset travels with it (``"reset": true``), and allows a new process;
        guards armed since the last request (or for a new process) go first.
        """
        if self._reset_pending and request["call"] != "arm_guards":
            request, fresh, self._reset_pending = {**request, "reset": True}, True, False
        process = self._process
        started = process is None or (fresh and process.poll() is not None)
        if started:
            process = self._start()
        elif process is not None and process.poll() is not None:
            raise self._crash(process, request["call"])
        assert process is not None
        if (started or self._arm_pending) and request["call"] != "arm_guards":
            self._arm_pending = False
            if self._armed is not None:
                self._request({"call": "arm_guards", "ids": self._armed})
        try:
            self._write(process, request)
        except BackendCrashError:
            raise self._crash(process, request["call"]) from None
        return process

    def _check(self, response: Any, call: str) -> None:
        """Raises BackendProtocolError if ``response`` fails its schema (with ``validate``)."""
        if not self.validate:
            return
        from conformance.protocol_schemas import problem  # noqa: PLC0415 (jsonschema: host only)

        raised = isinstance(response, dict) and "raised" in response
        name = "raised.json" if raised else f"{call}.response.json"
        wrong = problem(name, response)
        if wrong is not None:
            raise self._refuse(call, f"its {call} response fails {name} at {wrong}")

    def _response(
        self, process: subprocess.Popen[bytes], call: str, *, check: bool = True
    ) -> dict[str, Any]:
        """The process's next response, parsed (and, with ``check``, validated)."""
        try:
            line = self._readline(process, call)
        except BaseException:  # a timeout (or Ctrl-C) mid-call: the process cannot be trusted
            self._stop()
            raise
        if not line:
            raise self._crash(process, call)
        try:
            response = json.loads(line)
        except ValueError:
            raise self._refuse(
                call,
                f"it answered a line that is not JSON: {_quote(line)} "
                "(stdout carries protocol lines only; write anything else to stderr)",
            ) from None
        if self.transcript is not None:
            self.transcript.append(("response", response))
        if not isinstance(response, dict):
            raise self._refuse(call, f"it answered {_quote(line)}, not a JSON object")
        if check:
            self._check(response, call)
        return response

    def _answer(self, process: subprocess.Popen[bytes], call: str) -> Any:
        """The value of the process's next answer."""
        response = self._response(process, call)
        if "raised" in response:
            if "unknown" in response:
                raise UnknownNameError(*response["unknown"])
            raise RuntimeError(f"in the worker: {response['raised']}")
        if "value" not in response:
            raise self._refuse(call, f"its {call} response has no value: {json.dumps(response)}")
        return response["value"]

    def _request(self, request: dict[str, Any], *, fresh: bool = False) -> Any:
        """Sends ``request`` and returns its answer's value.

        A process is started if there is none, or (``fresh``: a reset) if the
        last one died; a process that died at any other time is a crash.
        """
        process = self._send(request, fresh=fresh)
        return self._answer(process, request["call"])

    def close(self) -> None:
        """Ends the process and frees its pipes and files (also done at exit)."""
        self._stop()
        if self._stderr is not None:
            self._stderr.close()
            self._stderr = None

    # ------------------------------------------------------------ protocol
    def version(self) -> str:
        assert self._hello is not None
        return str(self._hello["version"])

    def features(self) -> frozenset[str]:
        assert self._hello is not None
        return frozenset(self._hello["features"])

    def reset(self) -> None:
        """Resets with the next request (no round trip of its own); a dead process is
        replaced then."""
        self._reset_pending = True

    def arm_guards(self, ids: frozenset[str]) -> None:
        """Arms release guards in the process (and in every process that replaces it).

        Like ``reset``, the ``arm_guards`` request travels just before the next
        request, so a process that dies answering it is a crash of that step
        (recorded, and replaced), not of the engine's setup."""
        if sorted(ids) != self._armed:
            self._armed = sorted(ids)
            self._arm_pending = True

    def execute(self, command: Command) -> Result:
        return Result.from_json(self._request({"call": "execute", "command": command.to_json()}))

    def observe(self) -> Observation:
        return Observation.from_json(self._request({"call": "observe"}))

    def run_steps(
        self, steps: Sequence[tuple[Command | None, bool]]
    ) -> Iterator[tuple[Result, Observation | None]]:
        """Each step's Result (an empty one for ``None``) and, if asked, the Observation after
        it: one request for the whole batch, answers read as they come."""
        batch = [
            {"command": None if c is None else c.to_json(), "observe": observe}
            for c, observe in steps
        ]
        process = self._send({"call": "steps", "steps": batch})
        for _ in steps:
            value = self._answer(process, "steps")
            observation = value["observation"]
            yield (
                Result.from_json(value["result"]),
                None if observation is None else Observation.from_json(observation),
            )
