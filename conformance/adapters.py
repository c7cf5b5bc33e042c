"""Make a Python implementation a backend.

``SceneGraphBackend(Api(name, version, geometry, math, ...))`` drives any module set
with pydrake's Python API (``SceneGraph``, ``CollisionFilterDeclaration``, ...):
it turns scenario commands into those calls, by Drake's keyword names. The harness
runs reimpl and pydrake through it. ``load_backend(spec)`` makes a backend from a
spec as the command line takes it (``reimpl``, ``pydrake``, ``drake==X.Y.Z``,
``exec:'CMD'``, ``module:attr``). An implementation in another language speaks the
worker protocol instead (docs/protocol.md); one with another Python API implements
``conformance.protocol.Backend`` itself (examples/my_backend.py).
"""

from conformance._backends.api import Api
from conformance._backends.loader import load_backend
from conformance._backends.scene_graph import SceneGraphBackend

__all__ = ["Api", "SceneGraphBackend", "load_backend"]
