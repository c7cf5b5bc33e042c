"""reimpl's modules in the ``Api`` shape, for the ``reimpl`` backend."""

from __future__ import annotations

import reimpl.geometry
import reimpl.math
from conformance.backends.scene_graph import Api

__all__ = ["REIMPL_DRAKE_VERSION", "reimpl_api"]

#: The Drake release whose observable semantics reimpl follows, for since/until.
REIMPL_DRAKE_VERSION = "1.51.1"


def reimpl_api() -> Api:
    return Api(
        name="reimpl",
        version=REIMPL_DRAKE_VERSION,
        geometry=reimpl.geometry,
        math=reimpl.math,
    )
