"""Real pydrake under another name, so that a campaign can run pydrake against itself.

``--backend`` and ``--against`` must differ in name; ``pydrake`` here is the
installed pydrake named ``pydrake-twin``. A campaign of it against
``pydrake`` finds nothing unless pydrake answers the same case two ways (a
harness bug), and shows the coverage a generator reaches whatever an
implementation lacks:

    python -m conformance fuzz --models --backend conformance._testing.twins:pydrake --coverage
"""

from __future__ import annotations

import dataclasses

from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.scene_graph import SceneGraphBackend

__all__ = ["pydrake"]


def pydrake() -> SceneGraphBackend:
    """The installed pydrake as a backend named ``pydrake-twin``."""
    return SceneGraphBackend(dataclasses.replace(pydrake_api(), name="pydrake-twin"))
