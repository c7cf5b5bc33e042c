"""What QueryObject's proximity queries return: PenetrationAsPointPair, SignedDistancePair and
SignedDistanceToPoint.

Drake counterparts: drake/geometry/query_results/penetration_as_point_pair.h,
signed_distance_pair.h and signed_distance_to_point.h, as pydrake 1.51.1 binds
them (measured):

* The constructor takes keyword arguments only, one per attribute
  (``PenetrationAsPointPair(depth=0.5)``); an unknown keyword raises
  AttributeError, a positional argument TypeError.
* Defaults: ids of value 0 (invalid), ``depth = -1`` for a penetration and
  ``distance = 0`` for a signed distance (to a shape or a point), zero vectors.
* The vector attributes read as numpy copies (changing the array read does
  not change the object) and are written from anything of shape (3,).
* Neither pickles nor copies (pydrake: "cannot pickle").

``_swap()`` is Drake's SwapAAndB (unbound in pydrake), used by the engine: A and B trade
ids and witness points, and the normal turns around (``nhat_AB_W = −nhat_BA_W``).
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from reimpl._template import scalar_template
from reimpl.common._pybind_text import incompatible_arguments
from reimpl.geometry.identifier import GeometryId

__all__ = [
    "PenetrationAsPointPair",
    "PenetrationAsPointPair_",
    "SignedDistancePair",
    "SignedDistancePair_",
    "SignedDistanceToPoint",
    "SignedDistanceToPoint_",
]

Vector3 = npt.NDArray[np.float64]


def _vector3(owner: str, name: str, value: object) -> Vector3:
    """``value`` as a float vector of shape (3,), or pydrake's TypeError."""
    try:
        array = np.array(value, dtype=float)
    except (TypeError, ValueError):
        array = np.empty(0)
    if array.shape not in {(3,), (3, 1)}:
        raise TypeError(
            "(): incompatible function arguments. The following argument types are supported:\n"
            f"    1. (self: reimpl.geometry.{owner}, arg0: numpy.ndarray[numpy.float64[3, 1]])"
            f" -> None\n\nInvoked with: <reimpl.geometry.{owner} object>, {value!r}"
        )
    return array.reshape(3)


def _float(owner: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating | np.integer):
        raise TypeError(
            "(): incompatible function arguments. The following argument types are supported:\n"
            f"    1. (self: reimpl.geometry.{owner}, arg0: float) -> None\n\n"
            f"Invoked with: <reimpl.geometry.{owner} object>, {value!r}"
        )
    return float(value)


class _QueryResult:
    """Keyword-only construction, copied vectors, no pickling: the shared pydrake surface."""

    __slots__ = ()
    _ids: ClassVar[tuple[str, ...]] = ("id_A", "id_B")
    _vectors: ClassVar[tuple[str, ...]] = ()
    _scalar: ClassVar[str] = ""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        name = type(self).__name__
        if args:
            raise TypeError(
                f"{incompatible_arguments('__init__')}. The following argument types "
                f"are supported:\n    1. reimpl.geometry.{name}(**kwargs)\n\n"
                f"Invoked with: {', '.join(repr(a) for a in args)}"
            )
        self._reset()
        for key, value in kwargs.items():
            if key not in {*self._ids, self._scalar, *self._vectors}:
                raise AttributeError(f"'reimpl.geometry.{name}' object has no attribute '{key}'")
            setattr(self, key, value)

    def _reset(self) -> None:
        raise NotImplementedError

    def __reduce__(self) -> Any:
        raise TypeError(f"cannot pickle 'reimpl.geometry.{type(self).__name__}' object")


def _vector_property(name: str) -> property:
    slot = f"_{name}"

    def get(self: Any) -> Vector3:
        return getattr(self, slot).copy()  # type: ignore[no-any-return]

    def set_(self: Any, value: object) -> None:
        setattr(self, slot, _vector3(type(self).__name__, name, value))

    return property(get, set_)


def _scalar_property(name: str) -> property:
    slot = f"_{name}"

    def get(self: Any) -> float:
        return getattr(self, slot)  # type: ignore[no-any-return]

    def set_(self: Any, value: object) -> None:
        setattr(self, slot, _float(type(self).__name__, value))

    return property(get, set_)


class PenetrationAsPointPair(_QueryResult):
    """A penetrating pair (A, B): ``depth = |p_WCa − p_WCb| ≥ 0``, ``nhat_BA_W`` out of B into A.

    ``p_WCa`` is A's point deepest in B and ``p_WCb`` B's point deepest in A,
    so ``p_WCb = p_WCa + depth · nhat_BA_W`` up to the engine's precision.
    """

    __slots__ = ("_depth", "_nhat_BA_W", "_p_WCa", "_p_WCb", "id_A", "id_B")
    _vectors = ("p_WCa", "p_WCb", "nhat_BA_W")
    _scalar = "depth"

    id_A: GeometryId
    id_B: GeometryId
    _depth: float
    _p_WCa: Vector3
    _p_WCb: Vector3
    _nhat_BA_W: Vector3

    depth = _scalar_property("depth")
    p_WCa = _vector_property("p_WCa")
    p_WCb = _vector_property("p_WCb")
    nhat_BA_W = _vector_property("nhat_BA_W")

    def _reset(self) -> None:
        self.id_A = self.id_B = GeometryId._from_value(0)
        self._depth = -1.0
        self._p_WCa, self._p_WCb, self._nhat_BA_W = np.zeros(3), np.zeros(3), np.zeros(3)

    @classmethod
    def _make(
        cls, id_A: GeometryId, id_B: GeometryId, depth: float, vectors: npt.NDArray[np.float64]
    ) -> PenetrationAsPointPair:
        """A result from the engine: ``vectors`` rows are p_WCa, p_WCb, nhat_BA_W (kept)."""
        pair = object.__new__(cls)
        pair.id_A, pair.id_B, pair._depth = id_A, id_B, depth
        pair._p_WCa, pair._p_WCb, pair._nhat_BA_W = vectors[0], vectors[1], vectors[2]
        return pair

    def _swap(self) -> None:
        """(A, B) → (B, A): ids and points trade places, ``nhat_BA_W → −nhat_BA_W``."""
        self.id_A, self.id_B = self.id_B, self.id_A
        self._p_WCa, self._p_WCb = self._p_WCb, self._p_WCa
        self._nhat_BA_W = -self._nhat_BA_W


class SignedDistancePair(_QueryResult):
    """φ(A, B) with witnesses: ``p_ACa`` on ∂A in A's frame, ``p_BCb`` on ∂B in B's frame.

    ``distance = φ`` (negative when penetrating); ``nhat_BA_W`` is the direction
    of fastest increase of φ when A moves, ``(p_WCa − p_WCb) / φ`` when φ ≠ 0.
    """

    __slots__ = ("_distance", "_nhat_BA_W", "_p_ACa", "_p_BCb", "id_A", "id_B")
    _vectors = ("p_ACa", "p_BCb", "nhat_BA_W")
    _scalar = "distance"

    id_A: GeometryId
    id_B: GeometryId
    _distance: float
    _p_ACa: Vector3
    _p_BCb: Vector3
    _nhat_BA_W: Vector3

    distance = _scalar_property("distance")
    p_ACa = _vector_property("p_ACa")
    p_BCb = _vector_property("p_BCb")
    nhat_BA_W = _vector_property("nhat_BA_W")

    def _reset(self) -> None:
        self.id_A = self.id_B = GeometryId._from_value(0)
        self._distance = 0.0
        self._p_ACa, self._p_BCb, self._nhat_BA_W = np.zeros(3), np.zeros(3), np.zeros(3)

    @classmethod
    def _make(
        cls, id_A: GeometryId, id_B: GeometryId, distance: float, vectors: npt.NDArray[np.float64]
    ) -> SignedDistancePair:
        """A result from the engine: ``vectors`` rows are p_ACa, p_BCb, nhat_BA_W (kept)."""
        pair = object.__new__(cls)
        pair.id_A, pair.id_B, pair._distance = id_A, id_B, distance
        pair._p_ACa, pair._p_BCb, pair._nhat_BA_W = vectors[0], vectors[1], vectors[2]
        return pair

    def _swap(self) -> None:
        """(A, B) → (B, A): ids and witnesses trade places, ``nhat_BA_W → −nhat_BA_W``."""
        self.id_A, self.id_B = self.id_B, self.id_A
        self._p_ACa, self._p_BCb = self._p_BCb, self._p_ACa
        self._nhat_BA_W = -self._nhat_BA_W


class SignedDistanceToPoint(_QueryResult):
    """φ_G(Q) of a geometry G and a query point Q: ``p_GN`` the nearest point of ∂G (in G's
    frame), ``distance`` (negative inside G) and ``grad_W``, ∇φ in the world frame."""

    __slots__ = ("_distance", "_grad_W", "_p_GN", "id_G")
    _ids = ("id_G",)
    _vectors = ("p_GN", "grad_W")
    _scalar = "distance"

    id_G: GeometryId
    _distance: float
    _p_GN: Vector3
    _grad_W: Vector3

    distance = _scalar_property("distance")
    p_GN = _vector_property("p_GN")
    grad_W = _vector_property("grad_W")

    def _reset(self) -> None:
        self.id_G = GeometryId._from_value(0)
        self._distance = 0.0
        self._p_GN, self._grad_W = np.zeros(3), np.zeros(3)

    @classmethod
    def _make(
        cls, id_G: GeometryId, p_GN: Vector3, distance: float, grad_W: Vector3
    ) -> SignedDistanceToPoint:
        """A result from the engine (the vectors are kept)."""
        result = object.__new__(cls)
        result.id_G, result._distance = id_G, distance
        result._p_GN, result._grad_W = p_GN, grad_W
        return result


PenetrationAsPointPair_ = scalar_template(
    "reimpl.geometry", "PenetrationAsPointPair_", PenetrationAsPointPair
)
SignedDistancePair_ = scalar_template("reimpl.geometry", "SignedDistancePair_", SignedDistancePair)
SignedDistanceToPoint_ = scalar_template(
    "reimpl.geometry", "SignedDistanceToPoint_", SignedDistanceToPoint
)
