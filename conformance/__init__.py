"""Conformance harness: drive implementations with identical scenarios, compare pair by pair.

The public API is five modules; every other module is private (a leading underscore)
and may change in any release:

=========================  ===============================================================
``conformance.protocol``   what crosses the boundary: Backend, Command, Result, Observation
``conformance.compare``    how two answers are compared (Difference, diff_results, ...)
``conformance.strategies`` Hypothesis strategies for scenes and declarations; the lockstep
                           machine that fuzzes two backends
``conformance.adapters``   SceneGraphBackend(Api(...)) for a pydrake-like Python API, and
                           load_backend(spec)
``conformance.cli``        ``python -m conformance`` (run, fuzz, matrix, bisect, models, ...)
=========================  ===============================================================

The package itself hands on the protocol's names.
"""

from conformance.protocol import (
    MODEL,
    Backend,
    Command,
    ErrorInfo,
    ErrorKind,
    LocationState,
    Observation,
    Result,
)

__all__ = [
    "MODEL",
    "Backend",
    "Command",
    "ErrorInfo",
    "ErrorKind",
    "LocationState",
    "Observation",
    "Result",
]
