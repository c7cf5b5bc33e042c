"""``drake==X``: a backend in a worker process that runs Drake release X.

``WorkerBackend`` builds (or reuses) the release's environment
(``backends.environments``), starts ``python -m conformance.backends.worker``
there, and forwards the protocol's calls as JSON lines, through the
protocol's own codec. It is *isolated*: when the worker dies (a signal such
as SIGABRT or SIGSEGV, or an exit) the call raises ``BackendCrashError``
with the signal and the tail of the worker's stderr, and when a call times
out the worker is killed; either way the next ``reset()`` starts a new
worker, so a run records the crash and goes on.

A worker times itself: every answer must come within ``step_timeout``
seconds (``select`` on its pipe), so a hang is a ``StepTimeoutError`` in any
thread, not only where a ``SIGALRM`` can interrupt (a new worker's first
answer, which waits for pydrake's import, may take ``STARTUP_SECONDS``). ``run_steps`` sends a
whole case in one request and reads the answers as they come, one per step
(a *batch*: one round trip per case instead of two per step); ``reset``
travels with the next request, so a case costs one round trip.
"""

from __future__ import annotations

import json
import os
import select
import signal
import subprocess
import tempfile
import time
import weakref
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import IO, Any

from conformance.backends.calls import BackendCrashError, StepTimeoutError
from conformance.backends.environments import DrakeEnvironment, ensure_environment, harness_path
from conformance.protocol import Command, Observation, Result, UnknownNameError

__all__ = ["SPEC_PREFIX", "STARTUP_SECONDS", "WorkerBackend", "worker_spec_version"]

SPEC_PREFIX = "drake=="
#: Lines of the worker's stderr quoted when it dies.
_STDERR_TAIL = 8
#: Seconds a new worker may take for its first answer (it imports pydrake first).
STARTUP_SECONDS = 120.0


def worker_spec_version(spec: str) -> str | None:
    """``X`` for a ``drake==X`` spec, else None."""
    return spec[len(SPEC_PREFIX) :] if spec.startswith(SPEC_PREFIX) else None


def _exit_description(code: int) -> str:
    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exited with status {code}"


class WorkerBackend:
    """The backend protocol, served by a worker process (see the module doc)."""

    #: A crash or a timeout does not spoil later cases: the worker is replaced.
    isolated = True
    #: It keeps its own deadline (``step_timeout``), so ``calls.call`` sets no timer.
    times_itself = True

    def __init__(
        self,
        version: str,
        *,
        python: str | Sequence[str] | None = None,
        cache: Path | None = None,
        step_timeout: float | None = None,
        log: Callable[[str], None] = lambda line: None,
    ) -> None:
        self.name = f"{SPEC_PREFIX}{version}"
        self.environment: DrakeEnvironment = ensure_environment(
            version, python=python, cache=cache, log=log
        )
        #: Seconds an answer may take (None or 0: no limit).
        self.step_timeout = step_timeout
        self._pythonpath = str(harness_path(cache))
        self._process: subprocess.Popen[bytes] | None = None
        self._stderr: IO[str] | None = None
        self._pending = bytearray()  # read from the worker, not yet a whole line
        self._starting = False  # no answer yet from the running worker
        self._reset_pending = False  # reset() was called: the next request resets first
        #: The guards the host armed (None: the worker's own default, its release's).
        self._armed: list[str] | None = None
        weakref.finalize(self, WorkerBackend.close, self)
        hello = self._request({"call": "hello"})
        self._version = str(hello["version"])
        self._features = frozenset(hello["features"])

    # ------------------------------------------------------------- process
    @property
    def pid(self) -> int | None:
        """The running worker's process id (None if there is none)."""
        return None if self._process is None else self._process.pid

    def _start(self) -> subprocess.Popen[bytes]:
        """A new worker, in place of the last one (reaped, its pipes closed, if it died)."""
        self._stop()
        # Kept open for the worker's life (read when it dies), closed by the next _start.
        if self._stderr is not None:
            self._stderr.close()
        self._stderr = tempfile.TemporaryFile(mode="w+", encoding="utf-8")  # noqa: SIM115
        self._pending.clear()
        self._starting = True
        env = {**os.environ, "PYTHONPATH": self._pythonpath, "PYTHONUNBUFFERED": "1"}
        env.pop("PYTHONHOME", None)
        self._process = subprocess.Popen(
            [str(self.environment.interpreter), "-m", "conformance.backends.worker"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self._stderr,
            bufsize=0,
            env=env,
        )
        return self._process

    def _stop(self) -> None:
        """Kills the worker (if any) and closes its pipes; the next request starts a new one."""
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
        return "\n".join(lines)

    def _crash(self, process: subprocess.Popen[bytes], call: str) -> BackendCrashError:
        """The error for a worker that died; the worker is discarded."""
        code = process.wait()
        tail = self._stderr_tail()
        self._stop()
        message = f"the worker {_exit_description(code)}"
        return BackendCrashError(
            self.name, call, message + (f"; its stderr ends:\n{tail}" if tail else "")
        )

    def _readline(self, process: subprocess.Popen[bytes], call: str) -> bytes:
        """The worker's next line (b"" if it closed its output), within ``step_timeout``."""
        assert process.stdout is not None
        fd = process.stdout.fileno()
        seconds = self.step_timeout
        if seconds and self._starting:
            seconds = max(seconds, STARTUP_SECONDS)
        limit = None if not seconds else time.monotonic() + seconds
        while (end := self._pending.find(b"\n")) < 0:
            wait = None if limit is None else limit - time.monotonic()
            if wait is not None and (wait <= 0 or not select.select([fd], [], [], wait)[0]):
                raise StepTimeoutError(
                    self.name, call, f"no answer within {self.step_timeout:g} s (--step-timeout)"
                )
            chunk = os.read(fd, 1 << 16)
            if not chunk:
                return b""
            self._pending += chunk
        line = bytes(self._pending[:end])
        del self._pending[: end + 1]
        self._starting = False
        return line

    def _send(self, request: dict[str, Any], *, fresh: bool = False) -> subprocess.Popen[bytes]:
        """Writes ``request`` to the worker; see ``_request`` for ``fresh``.

        A pending reset travels with it (``"reset": true``), and allows a new worker.
        """
        if self._reset_pending and request["call"] != "arm_guards":
            request, fresh, self._reset_pending = {**request, "reset": True}, True, False
        process = self._process
        if process is None or (fresh and process.poll() is not None):
            process = self._start()
            if self._armed is not None and request["call"] != "arm_guards":
                self._request({"call": "arm_guards", "ids": self._armed})
        elif process.poll() is not None:
            raise self._crash(process, request["call"])
        assert process.stdin is not None
        try:
            process.stdin.write(json.dumps(request).encode() + b"\n")
        except BrokenPipeError:
            raise self._crash(process, request["call"]) from None
        return process

    def _answer(self, process: subprocess.Popen[bytes], call: str) -> Any:
        """The value of the worker's next answer."""
        try:
            line = self._readline(process, call)
        except BaseException:  # a timeout (or Ctrl-C) mid-call: the worker cannot be trusted
            self._stop()
            raise
        if not line:
            raise self._crash(process, call)
        response = json.loads(line)
        if "raised" in response:
            if "unknown" in response:
                raise UnknownNameError(*response["unknown"])
            raise RuntimeError(f"in the worker: {response['raised']}")
        return response["value"]

    def _request(self, request: dict[str, Any], *, fresh: bool = False) -> Any:
        """Sends ``request`` and returns its answer's value.

        A worker is started if there is none, or (``fresh``: a reset) if the
        last one died; a worker that died at any other time is a crash.
        """
        process = self._send(request, fresh=fresh)
        return self._answer(process, request["call"])

    def close(self) -> None:
        """Ends the worker and frees its pipes and files (also done at exit)."""
        self._stop()
        if self._stderr is not None:
            self._stderr.close()
            self._stderr = None

    # ------------------------------------------------------------ protocol
    def version(self) -> str:
        return self._version

    def features(self) -> frozenset[str]:
        return self._features

    def reset(self) -> None:
        """Resets with the next request (no round trip of its own); a dead worker is
        replaced then."""
        self._reset_pending = True

    def arm_guards(self, ids: frozenset[str]) -> None:
        """Arms release guards in the worker (and in every worker that replaces it)."""
        if sorted(ids) == self._armed and self._process is not None:
            return  # already armed in the running worker
        self._armed = sorted(ids)
        self._request({"call": "arm_guards", "ids": self._armed})

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
