"""How pydrake reports a failed DRAKE_DEMAND: SystemExit with Drake's own text.

``Failure at external/drake+/<path>:<line> in <function>(): condition '<condition>'
failed.`` (measured on pydrake 1.51.1; the line numbers are that release's).
"""

from __future__ import annotations

__all__ = ["demand_failure"]


def demand_failure(path: str, line: int, function: str, condition: str) -> SystemExit:
    """The SystemExit pydrake raises for a failed DRAKE_DEMAND at ``path:line``."""
    return SystemExit(
        f"Failure at external/drake+/{path}:{line} in {function}(): condition '{condition}' failed."
    )
