"""Drake's failed preconditions, as pydrake reports them.

Drake checks some preconditions with DRAKE_DEMAND or DRAKE_THROW_UNLESS. A
failure there is reported (measured on pydrake 1.12.0 to 1.58.0) as SystemExit
with the text ``Failure at <file>:<line> in <method>(): condition '<text>'
failed.``; the file is the one Drake was compiled from and the line that
release's. The callers name the demand by its id in the table of measured
releases (reimpl/common/demand_lines.json, see reimpl.common._demand_lines),
which gives the text for the release reimpl follows.

Where the precondition guards a C++-only method (one pydrake does not bind),
reimpl raises ``DemandFailedError`` instead (``demand_failed``).
"""

from __future__ import annotations

from typing import NoReturn

from reimpl.common._drake_demand import failed_demand
from reimpl.multibody._errors import DemandFailedError

__all__ = ["demand", "demand_failed", "fail_demand"]


def demand(holds: bool, demand_id: str) -> None:
    """pydrake's SystemExit for the demand ``demand_id`` unless it holds."""
    if not holds:
        raise failed_demand(demand_id)


def fail_demand(demand_id: str) -> NoReturn:
    """pydrake's SystemExit for the failed demand ``demand_id``."""
    raise failed_demand(demand_id)


def demand_failed(method: str, condition: str) -> DemandFailedError:
    """What reimpl raises where pydrake 1.51.1 prints this text and aborts."""
    return DemandFailedError(f"Failure in {method}(): condition '{condition}' failed.")
