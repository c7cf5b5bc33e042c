"""Model elements: indices, scoped names, rigid bodies, frames and joints.

Drake counterpart: drake/multibody/tree (as bound in ``pydrake.multibody.tree``).
An element is made on its own (a joint, a FixedOffsetFrame) or by the plant
(a body and its frame); once added to a MultibodyPlant it has an index there
and belongs to one model instance:

- a body belongs to the instance it was added to; its frame to the same one;
- a joint belongs to the instance of its child frame ``frame_on_child``;
- a FixedOffsetFrame to the instance it was given, else to its parent frame's.

Only what filtering and naming read is kept: a joint's type and its two
bodies, a body's name and instance. Axes, limits, dampings, masses and poses
are accepted as pydrake accepts them and are stored, never used.
"""

from __future__ import annotations

import math
import numbers
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.math import RigidTransform
from reimpl.multibody._errors import MultibodyPlantError

__all__ = [
    "BallRpyJoint",
    "BodyIndex",
    "FixedOffsetFrame",
    "Frame",
    "FrameIndex",
    "Joint",
    "JointIndex",
    "ModelInstanceIndex",
    "PlanarJoint",
    "PrismaticJoint",
    "QuaternionFloatingJoint",
    "RevoluteJoint",
    "RigidBody",
    "RigidBodyFrame",
    "RotationalInertia",
    "RpyFloatingJoint",
    "ScopedName",
    "ScrewJoint",
    "SpatialInertia",
    "UnitInertia",
    "UniversalJoint",
    "WeldJoint",
    "default_model_instance",
    "world_frame_index",
    "world_index",
    "world_model_instance",
]

_OWNER = "reimpl.multibody.tree"

#: The value of a default-constructed (invalid) index, as pydrake prints it.
_INVALID_INDEX = -1234567

# ----------------------------------------------------------------- Indices


class _TypeSafeIndex:
    """An integer index of one element kind; compares and hashes as its value."""

    __slots__ = ("_value",)

    def __init__(self, value: int = _INVALID_INDEX) -> None:
        self._value = int(value)

    def is_valid(self) -> bool:
        return self._value >= 0

    def __int__(self) -> int:
        return self._value

    def __index__(self) -> int:
        return self._value

    def __eq__(self, other: object) -> bool:
        if isinstance(other, _TypeSafeIndex | int):
            return self._value == int(other)
        return NotImplemented

    def __lt__(self, other: object) -> bool:
        if isinstance(other, _TypeSafeIndex | int):
            return self._value < int(other)
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self._value)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._value})"


class ModelInstanceIndex(_TypeSafeIndex):
    """Identifies a model instance of one plant (0 world, 1 default)."""

    __slots__ = ()


class BodyIndex(_TypeSafeIndex):
    """Identifies a rigid body of one plant (0 is the world body)."""

    __slots__ = ()


class FrameIndex(_TypeSafeIndex):
    """Identifies a frame of one plant (0 is the world frame)."""

    __slots__ = ()


class JointIndex(_TypeSafeIndex):
    """Identifies a joint of one plant, in the order joints were added."""

    __slots__ = ()


def world_model_instance() -> ModelInstanceIndex:
    return ModelInstanceIndex(0)


def default_model_instance() -> ModelInstanceIndex:
    return ModelInstanceIndex(1)


def world_index() -> BodyIndex:
    return BodyIndex(0)


def world_frame_index() -> FrameIndex:
    return FrameIndex(0)


# ------------------------------------------------------------- ScopedName

_DELIMITER = "::"


class ScopedName:
    """A name ``namespace::element``; the element never holds the delimiter.

    >>> ScopedName.Parse("a::b::c").get_namespace()
    'a::b'
    """

    __slots__ = ("_element", "_namespace")

    def __init__(self, namespace_name: str = "", element_name: str = "") -> None:
        if not _well_placed(namespace_name, element_name):
            raise RuntimeError(
                f"Cannot create a ScopedName('{namespace_name}', '{element_name}') with "
                "mis-placed delimiters"
            )
        self._namespace = namespace_name
        self._element = element_name

    @staticmethod
    def Make(namespace_name: str, element_name: str) -> ScopedName | None:
        """The name, or None where the constructor would raise."""
        if not _well_placed(namespace_name, element_name):
            return None
        return ScopedName(namespace_name, element_name)

    @staticmethod
    def Join(name1: str, name2: str) -> ScopedName:
        """``name1::name2``, either part possibly empty or itself scoped."""
        return ScopedName.Parse(_DELIMITER.join(n for n in (name1, name2) if n))

    @staticmethod
    def Parse(scoped_name: str) -> ScopedName:
        namespace, _, element = scoped_name.rpartition(_DELIMITER)
        return ScopedName(namespace, element)

    def get_namespace(self) -> str:
        return self._namespace

    def get_element(self) -> str:
        return self._element

    def get_full(self) -> str:
        return _DELIMITER.join(n for n in (self._namespace, self._element) if n)

    def to_string(self) -> str:
        return self.get_full()

    def set_namespace(self, namespace_name: str) -> None:
        if not _well_placed(namespace_name, self._element):
            raise RuntimeError(f"Cannot set namespace to '{namespace_name}'")
        self._namespace = namespace_name

    def set_element(self, element_name: str) -> None:
        if not _well_placed(self._namespace, element_name):
            raise RuntimeError(f"Cannot set element to '{element_name}'")
        self._element = element_name

    def __str__(self) -> str:
        return self.get_full()

    def __repr__(self) -> str:
        return f"ScopedName('{self._namespace}', '{self._element}')"


def _well_placed(namespace: str, element: str) -> bool:
    return (
        _DELIMITER not in element
        and not namespace.startswith(_DELIMITER)
        and not namespace.endswith(_DELIMITER)
    )


# ------------------------------------------------------------- Inertias
# N.B. reimpl does no dynamics: inertias are stored as given, never checked.


def _is_real(value: object) -> bool:
    return isinstance(value, numbers.Real)


_is_real.__name__ = "float"


def _is_vector(size: int) -> Any:
    def check(value: object) -> bool:
        try:
            return np.asarray(value, dtype=float).shape in {(size,), (size, 1)}
        except (TypeError, ValueError):
            return False

    check.__name__ = f"numpy.ndarray[numpy.float64[{size}, 1]]"
    return check


def _vector(value: object) -> npt.NDArray[np.float64]:
    return np.asarray(value, dtype=float).reshape(-1).copy()


class RotationalInertia:
    """Moments and products of inertia (stored only)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._moments = np.zeros(3)
        self._products = np.zeros(3)

        def set_moments(**moments: float) -> None:
            self._moments = np.array([moments[k] for k in ("Ixx", "Iyy", "Izz")], dtype=float)
            self._products = np.array(
                [moments.get(k, 0.0) for k in ("Ixy", "Ixz", "Iyz")], dtype=float
            )

        moments = (Param("Ixx", _is_real), Param("Iyy", _is_real), Param("Izz", _is_real))
        products = (Param("Ixy", _is_real), Param("Ixz", _is_real), Param("Iyz", _is_real))
        dispatch(
            f"{_OWNER}.RotationalInertia",
            "__init__",
            (
                Overload((), lambda: None),
                Overload(moments, set_moments),
                Overload(moments + products, set_moments),
            ),
            args,
            kwargs,
        )


class UnitInertia(RotationalInertia):
    """A rotational inertia per unit mass (stored only)."""


class SpatialInertia:
    """Mass, center of mass and unit inertia of a body (stored only)."""

    def __init__(
        self,
        mass: float,
        p_PScm_E: npt.ArrayLike,
        G_SP_E: UnitInertia,
        skip_validity_check: bool = False,
    ) -> None:
        self._mass = float(mass)
        self._p = _vector(p_PScm_E)
        self._G = G_SP_E

    @staticmethod
    def Zero() -> SpatialInertia:
        return SpatialInertia(0.0, np.zeros(3), UnitInertia())

    @staticmethod
    def NaN() -> SpatialInertia:
        return SpatialInertia(math.nan, np.full(3, math.nan), UnitInertia())

    @staticmethod
    def MakeFromCentralInertia(
        mass: float, p_PScm_E: npt.ArrayLike, I_SScm_E: RotationalInertia
    ) -> SpatialInertia:
        return SpatialInertia(mass, p_PScm_E, UnitInertia(), skip_validity_check=True)

    @staticmethod
    def SolidSphereWithMass(mass: float, radius: float) -> SpatialInertia:
        return SpatialInertia(mass, np.zeros(3), UnitInertia())

    @staticmethod
    def SolidSphereWithDensity(density: float, radius: float) -> SpatialInertia:
        return SpatialInertia(density * 4.0 / 3.0 * math.pi * radius**3, np.zeros(3), UnitInertia())

    @staticmethod
    def SolidBoxWithMass(mass: float, lx: float, ly: float, lz: float) -> SpatialInertia:
        return SpatialInertia(mass, np.zeros(3), UnitInertia())

    def get_mass(self) -> float:
        return self._mass

    def get_com(self) -> npt.NDArray[np.float64]:
        return self._p.copy()

    def get_unit_inertia(self) -> UnitInertia:
        return self._G

    def IsZero(self) -> bool:
        return self._mass == 0.0 and not self._p.any()

    def __repr__(self) -> str:
        return "SpatialInertia.Zero()" if self.IsZero() else "SpatialInertia(...)"


# -------------------------------------------------------------- Elements


class _Element:
    """What every element of a plant has: a plant, an index, a model instance."""

    _index_type: ClassVar[type[_TypeSafeIndex]] = _TypeSafeIndex
    #: The MultibodyPlant that added it (typed Any: the plant module imports this one).
    _plant: Any
    _index: int
    _model_instance: ModelInstanceIndex
    _name: str

    def _init_element(self, name: str, model_instance: ModelInstanceIndex) -> None:
        self._plant = None
        self._index = _INVALID_INDEX
        self._name = str(name)
        self._model_instance = ModelInstanceIndex(int(model_instance))

    def _adopt(self, plant: Any, index: int) -> None:
        self._plant = plant
        self._index = index

    def name(self) -> str:
        return self._name

    def index(self) -> Any:
        return self._index_type(self._index)

    def model_instance(self) -> ModelInstanceIndex:
        return ModelInstanceIndex(int(self._model_instance))

    def GetParentPlant(self) -> Any:
        if self._plant is None:
            raise MultibodyPlantError(
                f"{type(self).__name__} '{self._name}' was not added to a plant"
            )
        return self._plant

    def scoped_name(self) -> ScopedName:
        """``instance name::name``, with the instance's current name."""
        return ScopedName(
            self.GetParentPlant().GetModelInstanceName(self._model_instance), self._name
        )

    def is_ephemeral(self) -> bool:
        return False

    def __repr__(self) -> str:
        return (
            f"<{type(self).__name__} name='{self._name}' index={self._index} "
            f"model_instance={int(self._model_instance)}>"
        )


class RigidBody(_Element):
    """A rigid body; its frame is its SceneGraph frame when the plant has one."""

    _index_type = BodyIndex

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        inertia = Param("M_BBo_B", instance_of(SpatialInertia), SpatialInertia.Zero())
        name = Param("body_name", instance_of(str))

        def make(
            body_name: str,
            M_BBo_B: SpatialInertia,
            model_instance: ModelInstanceIndex | None = None,
        ) -> None:
            if model_instance is None:
                model_instance = default_model_instance()
            self._init_element(body_name, model_instance)
            self._M_BBo_B = M_BBo_B
            self._body_frame = RigidBodyFrame._of(self)

        dispatch(
            f"{_OWNER}.RigidBody",
            "__init__",
            (
                Overload((name, inertia), make),
                Overload(
                    (name, Param("model_instance", instance_of(ModelInstanceIndex)), inertia), make
                ),
            ),
            args,
            kwargs,
        )

    def body_frame(self) -> RigidBodyFrame:
        return self._body_frame

    def default_spatial_inertia(self) -> SpatialInertia:
        return self._M_BBo_B

    def default_mass(self) -> float:
        return self._M_BBo_B.get_mass()


class Frame(_Element):
    """A frame fixed to a body."""

    _index_type = FrameIndex
    _body: RigidBody

    def __init__(self, *args: object, **kwargs: object) -> None:
        raise TypeError(f"{_OWNER}.Frame: No constructor defined!")

    def body(self) -> RigidBody:
        return self._body

    def is_world_frame(self) -> bool:
        return self._index == 0 and self._plant is not None

    def is_body_frame(self) -> bool:
        return False


class RigidBodyFrame(Frame):
    """The frame of a rigid body: same name and model instance as its body."""

    @classmethod
    def _of(cls, body: RigidBody) -> RigidBodyFrame:
        frame = object.__new__(cls)
        frame._init_element(body.name(), body.model_instance())
        frame._body = body
        return frame

    def is_body_frame(self) -> bool:
        return True


class FixedOffsetFrame(Frame):
    """A frame F fixed to a parent frame P by X_PF (so fixed to P's body)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        def on_frame(
            name: str, P: Frame, X_PF: RigidTransform, model_instance: ModelInstanceIndex | None
        ) -> None:
            self._init_element(
                name, P.model_instance() if model_instance is None else model_instance
            )
            self._body = P.body()
            self._parent = P
            self._X_PF = RigidTransform(X_PF)

        def on_body(name: str, bodyB: RigidBody, X_BF: RigidTransform) -> None:
            on_frame(name, bodyB.body_frame(), X_BF, None)

        name = Param("name", instance_of(str))
        dispatch(
            f"{_OWNER}.FixedOffsetFrame",
            "__init__",
            (
                Overload(
                    (
                        name,
                        Param("P", instance_of(Frame)),
                        Param("X_PF", instance_of(RigidTransform)),
                        Param("model_instance", instance_of(ModelInstanceIndex), None),
                    ),
                    on_frame,
                ),
                Overload(
                    (
                        name,
                        Param("bodyB", instance_of(RigidBody)),
                        Param("X_BF", instance_of(RigidTransform)),
                    ),
                    on_body,
                ),
            ),
            args,
            kwargs,
        )

    def GetPoseInParentFrame(self) -> RigidTransform:
        return RigidTransform(self._X_PF)


# ---------------------------------------------------------------- Joints


class Joint(_Element):
    """A joint between the body of ``frame_on_parent`` and that of ``frame_on_child``.

    Subclasses differ, for filtering, only in ``kTypeName``; the plant reads
    that name through a table (see ``reimpl.multibody._default_filters``).
    """

    _index_type = JointIndex
    kTypeName: ClassVar[str] = ""
    #: (positions, velocities)
    _dofs: ClassVar[tuple[int, int]] = (0, 0)
    _frame_on_parent: Frame
    _frame_on_child: Frame
    _ephemeral: bool

    _parent_param: ClassVar[str] = "frame_on_parent"
    _child_param: ClassVar[str] = "frame_on_child"
    _parameters: dict[str, Any]

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        """Binds pydrake's overloads: name, the two frames, then one of ``_overloads()``."""
        cls = type(self)
        if cls is Joint:
            raise TypeError(f"{_OWNER}.Joint: No constructor defined!")
        frames = (
            Param("name", instance_of(str)),
            Param(cls._parent_param, instance_of(Frame)),
            Param(cls._child_param, instance_of(Frame)),
        )

        def make(name: str, **bound: Any) -> None:
            parent = bound.pop(cls._parent_param)
            child = bound.pop(cls._child_param)
            self._init_element(name, child.model_instance())
            self._frame_on_parent = parent
            self._frame_on_child = child
            self._ephemeral = False
            self._parameters = bound

        overloads = tuple(Overload(frames + extra, make) for extra in cls._overloads())
        dispatch(f"{_OWNER}.{cls.__name__}", "__init__", overloads, args, kwargs)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        """The parameters each constructor overload takes after the two frames."""
        return ((),)

    def type_name(self) -> str:
        return self.kTypeName

    def frame_on_parent(self) -> Frame:
        return self._frame_on_parent

    def frame_on_child(self) -> Frame:
        return self._frame_on_child

    def parent_body(self) -> RigidBody:
        return self._frame_on_parent.body()

    def child_body(self) -> RigidBody:
        return self._frame_on_child.body()

    def num_positions(self) -> int:
        return self._dofs[0]

    def num_velocities(self) -> int:
        return self._dofs[1]

    def is_ephemeral(self) -> bool:
        """True for the floating joints Finalize adds."""
        return self._ephemeral


def _real(name: str, default: Any = None) -> Param:
    return Param(name, _is_real) if default is None else Param(name, _is_real, default)


_axis = Param("axis", _is_vector(3))


class RevoluteJoint(Joint):
    kTypeName = "revolute"
    _dofs = (1, 1)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return (
            (_axis, _real("damping", 0.0)),
            (_axis, _real("pos_lower_limit"), _real("pos_upper_limit"), _real("damping", 0.0)),
        )


class PrismaticJoint(Joint):
    kTypeName = "prismatic"
    _dofs = (1, 1)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return (
            (
                _axis,
                _real("pos_lower_limit", -math.inf),
                _real("pos_upper_limit", math.inf),
                _real("damping", 0.0),
            ),
        )


class WeldJoint(Joint):
    kTypeName = "weld"
    _parent_param = "frame_on_parent_F"
    _child_param = "frame_on_child_M"

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((Param("X_FM", instance_of(RigidTransform)),),)

    def X_FM(self) -> RigidTransform:
        return RigidTransform(self._parameters["X_FM"])


class BallRpyJoint(Joint):
    kTypeName = "ball_rpy"
    _dofs = (3, 3)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((_real("damping", 0.0),),)


class UniversalJoint(Joint):
    kTypeName = "universal"
    _dofs = (2, 2)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((_real("damping", 0.0),),)


class PlanarJoint(Joint):
    kTypeName = "planar"
    _dofs = (3, 3)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((Param("damping", _is_vector(3), np.zeros(3)),),)


class QuaternionFloatingJoint(Joint):
    """6 dofs (7 positions). The one joint type Finalize's adjacency rule skips."""

    kTypeName = "quaternion_floating"
    _dofs = (7, 6)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((_real("angular_damping", 0.0), _real("translational_damping", 0.0)),)


class RpyFloatingJoint(Joint):
    """6 dofs; unlike QuaternionFloatingJoint, its bodies are filtered as adjacent."""

    kTypeName = "rpy_floating"
    _dofs = (6, 6)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((_real("angular_damping", 0.0), _real("translational_damping", 0.0)),)


class ScrewJoint(Joint):
    kTypeName = "screw"
    _dofs = (1, 1)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return (
            (_real("screw_pitch"), _real("damping")),
            (_axis, _real("screw_pitch"), _real("damping")),
        )
