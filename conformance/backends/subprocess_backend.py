"""``drake==X``: a backend in a worker process that runs Drake release X.

``WorkerBackend`` builds (or reuses) the release's environment
(``backends.environments``), starts ``python -m conformance.backends.worker``
there, and forwards the protocol's calls as JSON lines, through the
protocol's own codec. It is *isolated*: when the worker dies (a signal such
as SIGABRT or SIGSEGV, or an exit) the call raises ``BackendCrashError``
with the signal and the tail of the worker's stderr, and when a call times
out the worker is killed; either way the next ``reset()`` starts a new
worker, so a run records the crash and goes on.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import tempfile
import weakref
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

from conformance.backends.calls import BackendCrashError
from conformance.backends.environments import DrakeEnvironment, ensure_environment, harness_path
from conformance.protocol import Command, Observation, Result

__all__ = ["SPEC_PREFIX", "WorkerBackend", "worker_spec_version"]

SPEC_PREFIX = "drake=="
#: Lines of the worker's stderr quoted when it dies.
_STDERR_TAIL = 8


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

    def __init__(
        self,
        version: str,
        *,
        python: str | None = None,
        cache: Path | None = None,
        log: Callable[[str], None] = lambda line: None,
    ) -> None:
        self.name = f"{SPEC_PREFIX}{version}"
        self.environment: DrakeEnvironment = ensure_environment(
            version, python=python, cache=cache, log=log
        )
        self._pythonpath = str(harness_path(cache))
        self._process: subprocess.Popen[str] | None = None
        self._stderr: IO[str] | None = None
        #: The guards the host armed (None: the worker's own default, its release's).
        self._armed: list[str] | None = None
        weakref.finalize(self, WorkerBackend.close, self)
        hello = self._request({"call": "hello"})
        self._version = str(hello["version"])
        self._features = frozenset(hello["features"])

    # ------------------------------------------------------------- process
    def _start(self) -> subprocess.Popen[str]:
        # Kept open for the worker's life (read when it dies), closed by the next _start.
        if self._stderr is not None:
            self._stderr.close()
        self._stderr = tempfile.TemporaryFile(mode="w+", encoding="utf-8")  # noqa: SIM115
        env = {**os.environ, "PYTHONPATH": self._pythonpath, "PYTHONUNBUFFERED": "1"}
        env.pop("PYTHONHOME", None)
        self._process = subprocess.Popen(
            [str(self.environment.interpreter), "-m", "conformance.backends.worker"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self._stderr,
            text=True,
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

    def _crash(self, process: subprocess.Popen[str], call: str) -> BackendCrashError:
        """The error for a worker that died; the worker is discarded."""
        code = process.wait()
        tail = self._stderr_tail()
        self._stop()
        message = f"the worker {_exit_description(code)}"
        return BackendCrashError(
            self.name, call, message + (f"; its stderr ends:\n{tail}" if tail else "")
        )

    def _request(self, request: dict[str, Any], *, fresh: bool = False) -> Any:
        """Sends ``request`` and returns its answer's value.

        A worker is started if there is none, or (``fresh``: a reset) if the
        last one died; a worker that died at any other time is a crash.
        """
        process = self._process
        if process is None or (fresh and process.poll() is not None):
            process = self._start()
            if self._armed is not None and request["call"] != "arm_guards":
                self._request({"call": "arm_guards", "ids": self._armed})
        elif process.poll() is not None:
            raise self._crash(process, request["call"])
        assert process.stdin is not None
        assert process.stdout is not None
        try:
            process.stdin.write(json.dumps(request) + "\n")
            process.stdin.flush()
            line = process.stdout.readline()
        except BrokenPipeError:
            line = ""
        except BaseException:  # a timeout (or Ctrl-C) mid-call: the worker cannot be trusted
            self._stop()
            raise
        if not line:
            raise self._crash(process, request["call"])
        response = json.loads(line)
        if "raised" in response:
            raise RuntimeError(f"in the worker: {response['raised']}")
        return response["value"]

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
        self._request({"call": "reset"}, fresh=True)

    def arm_guards(self, ids: frozenset[str]) -> None:
        """Arms release guards in the worker (and in every worker that replaces it)."""
        self._armed = sorted(ids)
        self._request({"call": "arm_guards", "ids": self._armed})

    def execute(self, command: Command) -> Result:
        return Result.from_json(self._request({"call": "execute", "command": command.to_json()}))

    def observe(self) -> Observation:
        return Observation.from_json(self._request({"call": "observe"}))
