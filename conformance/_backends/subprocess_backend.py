"""``drake==X``: a backend in a worker process that runs Drake release X.

``WorkerBackend`` builds (or reuses) the release's environment
(``backends.environments``) and is then an exec backend
(``backends.exec_backend``) whose command the harness knows:
``<environment>/bin/python -m conformance._backends.worker``, with this
harness's ``conformance`` package (and nothing else of this environment) on
its ``PYTHONPATH``. So a cached environment needs nothing but its Drake
release: the worker's code is always this checkout's. Crash and timeout
isolation, batching and the handshake are ``ExecBackend``'s. Its name is
``drake==X``; its responses are not checked against the protocol's schemas
(the worker is this harness's own code, and tests check its traffic).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from conformance._backends.environments import DrakeEnvironment, ensure_environment, harness_path
from conformance._backends.exec_backend import STARTUP_SECONDS, ExecBackend

__all__ = ["SPEC_PREFIX", "STARTUP_SECONDS", "WorkerBackend", "worker_spec_version"]

SPEC_PREFIX = "drake=="
#: The worker's module, run with ``python -m``.
WORKER_MODULE = "conformance._backends.worker"


def worker_spec_version(spec: str) -> str | None:
    """``X`` for a ``drake==X`` spec, else None."""
    return spec[len(SPEC_PREFIX) :] if spec.startswith(SPEC_PREFIX) else None


class WorkerBackend(ExecBackend):
    """Drake release ``version``'s pydrake, in a worker process (see the module doc)."""

    def __init__(
        self,
        version: str,
        *,
        python: str | Sequence[str] | None = None,
        cache: Path | None = None,
        step_timeout: float | None = None,
        log: Callable[[str], None] = lambda line: None,
        validate: bool = False,
        transcript: list[tuple[str, Any]] | None = None,
    ) -> None:
        self.environment: DrakeEnvironment = ensure_environment(
            version, python=python, cache=cache, log=log
        )
        env = {**os.environ, "PYTHONPATH": str(harness_path(cache)), "PYTHONUNBUFFERED": "1"}
        env.pop("PYTHONHOME", None)
        name = f"{SPEC_PREFIX}{version}"
        super().__init__(
            [str(self.environment.interpreter), "-m", WORKER_MODULE],
            spec=name,
            name=name,
            env=env,
            step_timeout=step_timeout,
            validate=validate,
            transcript=transcript,
        )
