"""Drake's failed preconditions, as pydrake 1.51.1 reports them.

Drake checks some preconditions with DRAKE_DEMAND or DRAKE_THROW_UNLESS. A
failure there is reported (measured on pydrake 1.51.1) as SystemExit with
the text ``Failure at <file>:<line> in <method>(): condition '<text>'
failed.``; the file is the one Drake was compiled from, and the line is
1.51.1's (1.58.0 reports other lines). Each function below raises that
text for one file; the callers name the line, the method and the condition.

Where the precondition guards a C++-only method (one pydrake does not bind),
reimpl raises ``DemandFailedError`` instead (``demand_failed``).
"""

from __future__ import annotations

from typing import NoReturn

from reimpl.multibody._errors import DemandFailedError

__all__ = ["demand_cc", "demand_failed", "demand_h", "demand_tree_cc"]

#: Where pydrake 1.51.1 reports its DRAKE_DEMAND failures (SystemExit, measured).
_PLANT_H = (
    "bazel-out/k8-opt/bin/external/drake+/tools/install/libdrake/_virtual_includes/"
    "drake_shared_library/drake/multibody/plant/multibody_plant.h"
)
_PLANT_CC = "external/drake+/multibody/plant/multibody_plant.cc"
_TREE_CC = "external/drake+/multibody/tree/multibody_tree.cc"


def demand_h(condition: bool, line: int, method: str, text: str) -> None:
    """pydrake 1.51.1's SystemExit for a failed DRAKE_DEMAND in multibody_plant.h."""
    if not condition:
        raise SystemExit(f"Failure at {_PLANT_H}:{line} in {method}(): condition '{text}' failed.")


def demand_cc(condition: bool, line: int, method: str, text: str) -> None:
    """pydrake 1.51.1's SystemExit for a failed DRAKE_DEMAND in multibody_plant.cc."""
    if not condition:
        raise SystemExit(f"Failure at {_PLANT_CC}:{line} in {method}(): condition '{text}' failed.")


def demand_tree_cc(line: int, method: str, text: str) -> NoReturn:
    """pydrake 1.51.1's SystemExit for a failed condition in multibody_tree.cc (measured)."""
    raise SystemExit(f"Failure at {_TREE_CC}:{line} in {method}(): condition '{text}' failed.")


def demand_failed(method: str, condition: str) -> DemandFailedError:
    """What reimpl raises where pydrake 1.51.1 prints this text and aborts."""
    return DemandFailedError(f"Failure in {method}(): condition '{condition}' failed.")
