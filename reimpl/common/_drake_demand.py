"""How pydrake reports a failed DRAKE_DEMAND: SystemExit with Drake's own text.

``Failure at <prefix><path>:<line> in <function>(): condition '<condition>'
failed.`` (measured on pydrake 1.51.1). The prefix is ``external/drake+/``
since 1.37 and empty before (the release fact demand-path-external-since-1.37:
``DRAKE_PATH``). ``failed_demand`` takes the four parts from the table of
measured releases (see _demand_lines), for the release reimpl follows;
``demand_failure`` is given them (1.51.1's line, for the demands the table
does not hold yet). An uncaught C++ exception (``abort_uncaught``) ends the
process instead.
"""

from __future__ import annotations

import os
import sys
from typing import NoReturn

from reimpl._release import release
from reimpl.common._demand_lines import demand_site

__all__ = ["DRAKE_PATH", "abort_uncaught", "demand_failure", "failed_demand"]

#: Where Drake's sources are, as a failed DRAKE_DEMAND names its file.
DRAKE_PATH = "external/drake+/" if release.has("demand-path-external-since-1.37") else ""


def demand_failure(path: str, line: int, function: str, condition: str) -> SystemExit:
    """The SystemExit pydrake raises for a failed DRAKE_DEMAND at ``path:line``."""
    return SystemExit(
        f"Failure at {DRAKE_PATH}{path}:{line} in {function}(): condition '{condition}' failed."
    )


def failed_demand(demand: str) -> SystemExit:
    """The SystemExit pydrake raises for the failed demand ``demand`` (an id of
    demand_lines.json), as the release reimpl follows reports it."""
    path, line, function, condition = demand_site(demand)
    return SystemExit(f"Failure at {path}:{line} in {function}(): condition '{condition}' failed.")


def abort_uncaught(cpp_type: str, what: str) -> NoReturn:
    """Ends the process as an uncaught C++ exception ends pydrake's: libstdc++'s
    terminate handler writes the exception's type and ``what()``, then SIGABRT."""
    sys.stdout.flush()
    sys.stderr.write(f"terminate called after throwing an instance of '{cpp_type}'\n")
    sys.stderr.write(f"  what():  {what}\n")
    sys.stderr.flush()
    os.abort()
