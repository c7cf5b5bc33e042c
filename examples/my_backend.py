"""A skeleton backend: copy this file and put your implementation behind it.

``python -m conformance new-backend DIR`` writes a copy to ``DIR/my_backend.py``
(from an installed package too) and prints the command that runs it. Run it
against real Drake from the folder that holds its folder, here ``examples/``::

    python -m conformance run --backend examples.my_backend:MyBackend --backend pydrake
    python -m conformance fuzz --backend examples.my_backend:MyBackend --against pydrake

The current folder is importable for ``--backend`` specs, under ``python -m``
and under the ``drake-filter-conformance`` script alike.

Two ways in:

* **Your implementation has pydrake's Python API** (``SceneGraph``,
  ``CollisionFilterDeclaration``, ...): ``pydrake_like`` below is all you need.
  ``SceneGraphBackend`` turns scenario commands into those calls.
* **Anything else** (another language, a service, a different API): fill in
  ``MyBackend``. Each method says what the harness expects. As shipped it
  forwards to reimpl, so it passes the corpus as it is; replace the
  forwarding with your own calls one method at a time.

Everything crossing the boundary is names, booleans and strings
(``conformance.protocol``); ``Command``, ``Result`` and ``Observation``
round-trip through JSON, so ``execute`` may forward to another process.
"""

from __future__ import annotations

import reimpl.geometry
import reimpl.math
from conformance.adapters import Api, SceneGraphBackend, load_backend
from conformance.protocol import Backend, Command, Observation, Result

__all__ = ["MyBackend", "pydrake_like"]


def pydrake_like() -> Backend:
    """A backend for an implementation with pydrake's Python API (here: reimpl's modules).

    Put your modules in place of ``reimpl.geometry`` and ``reimpl.math``, and
    name the Drake release whose behaviour you follow: it selects the cases'
    ``since``/``until`` expectations and the known divergences that apply.
    """
    return SceneGraphBackend(
        Api(name="mine", version="1.51.1", geometry=reimpl.geometry, math=reimpl.math)
    )


class MyBackend:
    """The backend protocol, method by method (``conformance.protocol.Backend``)."""

    #: A short name, unique among the backends of a run (reports use it).
    name = "mine"

    def __init__(self) -> None:
        # Replace with your implementation. The harness makes one backend per run.
        self._engine = load_backend("reimpl")

    def version(self) -> str:
        """The Drake release whose behaviour this implements, e.g. ``"1.51.1"``."""
        return self._engine.version()

    def features(self) -> frozenset[str]:
        """The scenario feature tags supported; a case needing others is skipped.

        Tags: ``core``, ``transient``, ``contexts``, ``roles``, ``errors``,
        ``quirk``, ``scope``, ``activation`` (Drake >= 1.55).
        """
        return self._engine.features()

    def reset(self) -> None:
        """Start from a fresh, empty SceneGraph (called before every case and example)."""
        self._engine.reset()

    def execute(self, command: Command) -> Result:
        """Run one command; ``command.op`` and ``command.args`` follow the grammar.

        The ops and their arguments are the rows of
        ``conformance/_grammar/scene_graph.py`` (``python -m conformance schema``
        prints them as a JSON schema). Return ``Result(value=...)``, or
        ``Result(error=ErrorInfo(kind, message))`` when your implementation
        refuses the call. Do not raise for a refusal: an exception means the
        backend itself broke (the run stops with exit 2). Raise
        ``conformance.protocol.UnknownNameError`` if the command names
        something no earlier command made.
        """
        return self._engine.execute(command)

    def observe(self) -> Observation:
        """The observable state: per location (``model`` and every context) the
        candidate pairs (by name), IsActive of every declaration label, and
        ``has_transient_history()``."""
        return self._engine.observe()
