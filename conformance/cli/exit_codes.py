"""The command line's exit codes (shared by ``run`` and ``fuzz``)."""

from __future__ import annotations

__all__ = ["EXIT_FAILURE", "EXIT_OK", "EXIT_USAGE"]

#: Every case passed; no divergence was found.
EXIT_OK = 0
#: A conformance failure, or a divergence (written to a scenario file).
EXIT_FAILURE = 1
#: A usage or input error, a broken backend, or an interrupted run that found nothing.
EXIT_USAGE = 2
