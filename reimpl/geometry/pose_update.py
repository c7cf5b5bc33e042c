"""The pose update: a context's cached poses, and what makes them stale.

Drake counterpart: SceneGraph's pose-update cache entry (FullPoseUpdate).
Measured on pydrake 1.51.1 and 1.58 (tests/test_query_object.py, "pose
update"): a query that needs poses (every QueryObject query but
``inspector()``) runs the pose update when it is out of date. The update
checks that every source with frames has its pose port fixed with one pose per
frame (the first failing source, in Drake's walk of the sources, is named),
then poses ``X_WF = X_WP · X_PF`` and ``X_WG = X_WF · X_FG``. It then stays up
to date until an input port of the SceneGraph gets a value (``FixValue``, even
of the same value). Nothing else makes it stale, not even a new state:

=================== ==================== ==================== ====================
event               OUT_OF_DATE          FROM_PORTS           MODEL_DEFAULTS
=================== ==================== ==================== ====================
a query             check, pose:         poses from the       X_PF = X_WF = I,
                    FROM_PORTS           ports                X_WG = X_FG
FixValue            OUT_OF_DATE          OUT_OF_DATE          OUT_OF_DATE
SetDefaultContext   OUT_OF_DATE          MODEL_DEFAULTS       MODEL_DEFAULTS
Clone, the query    check, pose:         FROM_PORTS           MODEL_DEFAULTS
port evaluated      FROM_PORTS
=================== ==================== ==================== ====================

``SetDefaultContext`` copies the model's state together with the model's
poses, which were never posed (``X_PF = X_WF = I``, ``X_WG = X_FG``), and
leaves the update up to date. Until the next ``FixValue`` the queries see
those poses and check no pose port, not even for frames it added. A clone
copies the update as it is (Drake copies cache values), after the original
ran it.

N.B. reimpl cannot see when the value of a *connected* pose port changes
upstream, so a context with a connected pose port (fixed when the diagram is
built) records no update and is out of date at every query (Drake: until the
upstream value changes).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from reimpl.systems.framework import Context

__all__ = ["PoseMode", "PoseUpdate", "on_set_default_context", "pose_mode", "posed_from_ports"]

_KEY = "pose update"


class PoseMode(Enum):
    """Where a context's poses come from at its next query."""

    OUT_OF_DATE = "out of date: check the ports and pose from them"
    FROM_PORTS = "up to date, posed from the pose ports"
    MODEL_DEFAULTS = "up to date, with the model's default poses"


@dataclass(frozen=True)
class PoseUpdate:
    """A context's pose update, and the context's input revision when it was made."""

    mode: PoseMode
    input_revision: int


#: SetDefaultContext: the model's poses replace the context's, and an up-to-date update stays so.
_ON_SET_DEFAULT_CONTEXT = {
    PoseMode.OUT_OF_DATE: PoseMode.OUT_OF_DATE,
    PoseMode.FROM_PORTS: PoseMode.MODEL_DEFAULTS,
    PoseMode.MODEL_DEFAULTS: PoseMode.MODEL_DEFAULTS,
}


def pose_mode(context: Context) -> PoseMode:
    """The context's mode: out of date if no update was recorded, or after any FixValue."""
    update: PoseUpdate | None = context._cache.get(_KEY)
    if update is None or update.input_revision != context._input_revision:
        return PoseMode.OUT_OF_DATE
    return update.mode


def posed_from_ports(context: Context) -> None:
    """Records a successful pose update from the ports (only where no pose port is connected)."""
    context._cache[_KEY] = PoseUpdate(PoseMode.FROM_PORTS, context._input_revision)


def on_set_default_context(context: Context) -> None:
    """Applies the SetDefaultContext row of the table."""
    mode = _ON_SET_DEFAULT_CONTEXT[pose_mode(context)]
    if mode is PoseMode.OUT_OF_DATE:
        context._cache.pop(_KEY, None)
    else:
        context._cache[_KEY] = PoseUpdate(mode, context._input_revision)
