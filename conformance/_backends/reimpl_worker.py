"""``reimpl==X``: reimpl following Drake release X, in a worker process of this interpreter.

reimpl chooses the release it follows once per process
(``REIMPL_DRAKE_RELEASE``: ``reimpl/_release.py``), so a run that holds
``reimpl==1.58.0`` beside plain ``reimpl`` (1.51.1) gives the other release
its own process: ``python -m conformance._backends.worker reimpl`` with the
variable set, started by this interpreter with this checkout's ``reimpl``
and ``conformance`` first on its path. Everything else is an exec backend's
(``ExecBackend``): the worker protocol and its handshake, crash and timeout
isolation (a release fact of kind ``crash`` ends the worker as it ends
pydrake's), batching. No environment is built: the release is a table row
away.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import conformance
from conformance._backends.exec_backend import ExecBackend

__all__ = ["REIMPL_SPEC_PREFIX", "ReimplWorkerBackend", "reimpl_spec_version"]

REIMPL_SPEC_PREFIX = "reimpl=="
#: The variable reimpl reads (``reimpl._release.RELEASE_VARIABLE``; not imported, so that
#: loading the harness does not import reimpl).
_RELEASE_VARIABLE = "REIMPL_DRAKE_RELEASE"
#: The worker's module, run with ``python -m``.
_WORKER_MODULE = "conformance._backends.worker"


def reimpl_spec_version(spec: str) -> str | None:
    """``X`` for a ``reimpl==X`` spec, else None."""
    return spec[len(REIMPL_SPEC_PREFIX) :] if spec.startswith(REIMPL_SPEC_PREFIX) else None


class ReimplWorkerBackend(ExecBackend):
    """reimpl following Drake ``version``, served by a worker process (see the module doc)."""

    def __init__(self, version: str, *, step_timeout: float | None = None) -> None:
        root = str(Path(conformance.__file__).resolve().parent.parent)
        path = os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")]))
        env = {
            **os.environ,
            "PYTHONPATH": path,
            "PYTHONUNBUFFERED": "1",
            _RELEASE_VARIABLE: version,
        }
        name = f"{REIMPL_SPEC_PREFIX}{version}"
        super().__init__(
            [sys.executable, "-m", _WORKER_MODULE, "reimpl"],
            spec=name,
            name=name,
            env=env,
            step_timeout=step_timeout,
            validate=False,  # the worker is this harness's own code (as drake==X's)
        )
