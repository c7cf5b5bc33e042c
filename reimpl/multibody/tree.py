"""Model elements: indices, scoped names, rigid bodies, frames and joints.

Drake counterpart: drake/multibody/tree (as bound in ``pydrake.multibody.tree``).
An element is made on its own (a joint, a FixedOffsetFrame) or by the plant
(a body and its frame); once added to a MultibodyPlant it has an index there
and belongs to one model instance:

- a body belongs to the instance it was added to; its frame to the same one;
- a joint belongs to the instance of its child frame ``frame_on_child``;
- a FixedOffsetFrame to the instance it was given, else to its parent frame's.

Filtering and naming read a joint's type and its two bodies, a body's name
and instance. Kinematics (reimpl.multibody.kinematics) reads the frames'
fixed poses, the joints' axes, a screw's pitch and a weld's X_FM; once the
plant is finalized, a joint's positions start at ``position_start()`` in a
plant context's q, and the joint's accessors (``set_angle``, ``SetPose``, ...)
read and write that slice. Limits, dampings and masses are accepted as
pydrake accepts them and are stored, never used.
"""

from __future__ import annotations

import itertools
import math
import numbers
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
import numpy.typing as npt

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._release import release
from reimpl._template import TemplateClass
from reimpl.common._drake_demand import failed_demand
from reimpl.common._pybind_text import no_constructor
from reimpl.math import RigidTransform, RotationMatrix
from reimpl.multibody import kinematics
from reimpl.multibody._errors import MultibodyPlantError
from reimpl.multibody._joint_checks import check_joint_parameters

__all__ = [
    "BallRpyJoint",
    "BallRpyJoint_",
    "Body",
    "BodyIndex",
    "Body_",
    "FixedOffsetFrame",
    "FixedOffsetFrame_",
    "Frame",
    "FrameIndex",
    "Frame_",
    "Joint",
    "JointIndex",
    "Joint_",
    "ModelInstanceIndex",
    "PlanarJoint",
    "PlanarJoint_",
    "PrismaticJoint",
    "PrismaticJoint_",
    "QuaternionFloatingJoint",
    "QuaternionFloatingJoint_",
    "RevoluteJoint",
    "RevoluteJoint_",
    "RigidBody",
    "RigidBodyFrame",
    "RigidBodyFrame_",
    "RigidBody_",
    "RotationalInertia",
    "RotationalInertia_",
    "RpyFloatingJoint",
    "RpyFloatingJoint_",
    "ScopedName",
    "ScrewJoint",
    "ScrewJoint_",
    "SpatialInertia",
    "SpatialInertia_",
    "UnitInertia",
    "UnitInertia_",
    "UniversalJoint",
    "UniversalJoint_",
    "WeldJoint",
    "WeldJoint_",
    "default_model_instance",
    "world_frame_index",
    "world_index",
    "world_model_instance",
]

_OWNER = "reimpl.multibody.tree"

#: The value of a default-constructed (invalid) index, as pydrake prints it.
_INVALID_INDEX = -1234567
#: The index of an element not (yet) added to a plant (measured: ``RigidBody('x').index()``
#: is ``BodyIndex(-1)`` on pydrake 1.51.1 and 1.58.0).
_UNADDED_INDEX = -1

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
        self._index = _UNADDED_INDEX
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

    #: Added by Finalize, not by the user (floating joints, mobilizer frames).
    _ephemeral: bool = False

    def is_ephemeral(self) -> bool:
        return self._ephemeral

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

    def EvalPoseInWorld(self, context: Any) -> RigidTransform:
        X_WB: RigidTransform = self.GetParentPlant().EvalBodyPoseInWorld(context, self)
        return X_WB

    def _inboard_joint(self) -> Joint | None:
        plant = self.GetParentPlant()
        index = plant._forest.inboard_joint(self._index) if plant._forest is not None else None
        return None if index is None else plant.get_joint(JointIndex(index))

    def is_floating_base_body(self) -> bool:
        """Whether Finalize gave this body its floating joint (measured: a user's
        RpyFloatingJoint to the world does not count)."""
        joint = self._inboard_joint()
        return joint is not None and joint.is_ephemeral()

    def is_floating(self) -> bool:
        """Deprecated in pydrake 1.51.1 for ``is_floating_base_body``."""
        return self.is_floating_base_body()

    def has_quaternion_dofs(self) -> bool:
        joint = self._inboard_joint()
        return joint is not None and joint.kTypeName == "quaternion_floating"

    # ------------------------------------------------- floating base body
    # Where a floating base body's joint keeps its state; pydrake 1.51.1's errors
    # (measured): RuntimeError before Finalize, SystemExit for another body.
    def _floating_joint(self, method: str) -> Joint:
        plant = self.GetParentPlant()
        if not plant.is_finalized():
            raise MultibodyPlantError(
                f"From '{method}'. The model to which this rigid body belongs must be "
                "finalized. See MultibodyPlant::Finalize()."
            )
        joint = self._inboard_joint()
        if joint is None or not joint.is_ephemeral():
            raise failed_demand(f"RigidBody.{method}.floating")
        return joint

    def floating_positions_start(self) -> int:
        return self._floating_joint("floating_positions_start").position_start()

    def floating_velocities_start_in_v(self) -> int:
        return self._floating_joint("floating_velocities_start_in_v").velocity_start()

    def floating_position_suffix(self, position_index_in_body: int) -> str:
        joint = self._floating_joint("floating_position_suffix")
        if not 0 <= position_index_in_body < joint.num_positions():
            raise failed_demand("RigidBody.floating_position_suffix.index")
        return joint.position_suffix(position_index_in_body)

    def floating_velocity_suffix(self, velocity_index_in_body: int) -> str:
        joint = self._floating_joint("floating_velocity_suffix")
        if not 0 <= velocity_index_in_body < joint.num_velocities():
            raise failed_demand("RigidBody.floating_velocity_suffix.index")
        return joint.velocity_suffix(velocity_index_in_body)


class Frame(_Element):
    """A frame fixed to a body."""

    _index_type = FrameIndex
    _body: RigidBody

    def __init__(self, *args: object, **kwargs: object) -> None:
        raise no_constructor(f"{_OWNER}.Frame")

    def body(self) -> RigidBody:
        return self._body

    def is_world_frame(self) -> bool:
        return self._index == 0 and self._plant is not None

    def is_body_frame(self) -> bool:
        return False

    def GetFixedPoseInBodyFrame(self) -> RigidTransform:
        """X_BF, the pose of this frame in its body's frame."""
        return RigidTransform()

    def GetFixedOffsetPoseInBody(self, X_FQ: RigidTransform) -> RigidTransform:
        """X_BQ = X_BF · X_FQ."""
        return self.GetFixedPoseInBodyFrame() @ X_FQ

    def CalcPoseInBodyFrame(self, context: Any) -> RigidTransform:
        return self.GetFixedPoseInBodyFrame()

    def CalcOffsetPoseInBody(self, context: Any, X_FQ: RigidTransform) -> RigidTransform:
        return self.GetFixedOffsetPoseInBody(X_FQ)

    def CalcPoseInWorld(self, context: Any) -> RigidTransform:
        """X_WF = X_WB · X_BF at the context's positions."""
        X_WB: RigidTransform = self.GetParentPlant().EvalBodyPoseInWorld(context, self._body)
        return X_WB @ self.GetFixedPoseInBodyFrame()

    def CalcPose(self, context: Any, frame_M: Frame) -> RigidTransform:
        """X_MF, this frame's pose in ``frame_M``."""
        X_MF: RigidTransform = self.GetParentPlant().CalcRelativeTransform(context, frame_M, self)
        return X_MF

    # The rotations: the rotation part of the poses above.
    def GetFixedRotationMatrixInBodyFrame(self) -> RotationMatrix:
        """R_BF."""
        return self.GetFixedPoseInBodyFrame().rotation()

    def GetFixedRotationMatrixInBody(self, R_FQ: RotationMatrix) -> RotationMatrix:
        """R_BQ = R_BF · R_FQ."""
        return self.GetFixedRotationMatrixInBodyFrame() @ R_FQ

    def CalcRotationMatrixInBodyFrame(self, context: Any) -> RotationMatrix:
        return self.CalcPoseInBodyFrame(context).rotation()

    def CalcOffsetRotationMatrixInBody(self, context: Any, R_FQ: RotationMatrix) -> RotationMatrix:
        return self.GetFixedRotationMatrixInBody(R_FQ)

    def CalcRotationMatrixInWorld(self, context: Any) -> RotationMatrix:
        return self.CalcPoseInWorld(context).rotation()

    def CalcRotationMatrix(self, context: Any, frame_M: Frame) -> RotationMatrix:
        """R_MF."""
        return self.CalcPose(context, frame_M).rotation()


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

    def GetFixedPoseInBodyFrame(self) -> RigidTransform:
        """X_BF = X_BP · X_PF."""
        return self._parent.GetFixedPoseInBodyFrame() @ self._X_PF


# -------------------------------------------------------- Scalar templates
# ``RigidBody_[float] is RigidBody`` and so on, for every class pydrake binds as a
# scalar template (measured on pydrake 1.51.1). Bound lazily, so that this block
# may stand before the joint classes it names. ``Body`` and ``Body_`` are
# pydrake's other names for ``RigidBody`` and ``RigidBody_``.


def _template(name: str, cls: Callable[[], type]) -> TemplateClass:
    template = TemplateClass(_OWNER, name)
    template.add_lazy(lambda: template.add_instantiation(float, cls()))
    return template


BallRpyJoint_ = _template("BallRpyJoint_", lambda: BallRpyJoint)
FixedOffsetFrame_ = _template("FixedOffsetFrame_", lambda: FixedOffsetFrame)
Frame_ = _template("Frame_", lambda: Frame)
Joint_ = _template("Joint_", lambda: Joint)
PlanarJoint_ = _template("PlanarJoint_", lambda: PlanarJoint)
PrismaticJoint_ = _template("PrismaticJoint_", lambda: PrismaticJoint)
QuaternionFloatingJoint_ = _template("QuaternionFloatingJoint_", lambda: QuaternionFloatingJoint)
RevoluteJoint_ = _template("RevoluteJoint_", lambda: RevoluteJoint)
RigidBodyFrame_ = _template("RigidBodyFrame_", lambda: RigidBodyFrame)
RigidBody_ = _template("RigidBody_", lambda: RigidBody)
RotationalInertia_ = _template("RotationalInertia_", lambda: RotationalInertia)
RpyFloatingJoint_ = _template("RpyFloatingJoint_", lambda: RpyFloatingJoint)
ScrewJoint_ = _template("ScrewJoint_", lambda: ScrewJoint)
SpatialInertia_ = _template("SpatialInertia_", lambda: SpatialInertia)
UnitInertia_ = _template("UnitInertia_", lambda: UnitInertia)
UniversalJoint_ = _template("UniversalJoint_", lambda: UniversalJoint)
WeldJoint_ = _template("WeldJoint_", lambda: WeldJoint)
Body = RigidBody
Body_ = RigidBody_


# ---------------------------------------------------------------- Joints


def _no_mobilizer(method: str) -> SystemExit:
    """pydrake's SystemExit for a joint accessor that needs its mobilizer, before Finalize
    (the demand ``Joint.<method>.mobilizer``, measured)."""
    return failed_demand(f"Joint.{method}.mobilizer")


#: Whether a joint's position_start() and velocity_start() are -1 before Finalize (Drake
#: 1.57 on); up to 1.56 they fail a demand (measured on 1.51.1 and 1.52.0 to 1.58.0).
_START_BEFORE_FINALIZE = release.has("joint-start-before-finalize-since-1.57")


def _sized(method: str, value: Any, size: int) -> npt.NDArray[np.float64]:
    """``value`` as a float vector of ``size``; pybind11's TypeError otherwise."""
    if not _is_vector(size)(value):
        raise TypeError(
            f"{method}(): incompatible function arguments. Expected "
            f"numpy.ndarray[numpy.float64[{size}, 1]], got {value!r}"
        )
    return _vector(value)


def _pose(R: npt.NDArray[np.float64], p: npt.ArrayLike) -> RigidTransform:
    return RigidTransform(RotationMatrix(R), np.asarray(p, dtype=float))


class Joint(_Element):
    """A joint between the body of ``frame_on_parent`` and that of ``frame_on_child``.

    Subclasses differ, for filtering, only in ``kTypeName``; the plant reads
    that name through a table (see ``reimpl.multibody._default_filters``), and
    so does kinematics (``X_FM(q)``, see ``reimpl.multibody.kinematics``).
    Its positions q_J live in a plant context at
    ``[position_start(), position_start() + num_positions())``.
    """

    _index_type = JointIndex
    kTypeName: ClassVar[str] = ""
    #: (positions, velocities)
    _dofs: ClassVar[tuple[int, int]] = (0, 0)
    #: The positions a new joint defaults to.
    _zero_positions: ClassVar[tuple[float, ...]] = ()
    #: GetPositionNames' suffix of each position.
    _position_suffixes: ClassVar[tuple[str, ...]] = ()
    #: GetVelocityNames' suffix of each velocity.
    _velocity_suffixes: ClassVar[tuple[str, ...]] = ()
    #: (can_rotate, can_translate), as the joint's mobilizer reports them.
    _motion: ClassVar[tuple[bool, bool]] = (False, False)
    _frame_on_parent: Frame
    _frame_on_child: Frame
    _ephemeral: bool
    _default_q: npt.NDArray[np.float64]
    #: (position_start, velocity_start), set by the plant's Finalize.
    _starts: tuple[int, int] | None

    _parent_param: ClassVar[str] = "frame_on_parent"
    _child_param: ClassVar[str] = "frame_on_child"
    _parameters: dict[str, Any]

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        """Binds pydrake's overloads: name, the two frames, then one of ``_overloads()``."""
        cls = type(self)
        if cls is Joint:
            raise no_constructor(f"{_OWNER}.Joint")
        frames = (
            Param("name", instance_of(str)),
            Param(cls._parent_param, instance_of(Frame)),
            Param(cls._child_param, instance_of(Frame)),
        )

        def make(name: str, **bound: Any) -> None:
            parent = bound.pop(cls._parent_param)
            child = bound.pop(cls._child_param)
            check_joint_parameters(cls.kTypeName, bound)
            self._init_element(name, child.model_instance())
            self._frame_on_parent = parent
            self._frame_on_child = child
            self._ephemeral = False
            self._parameters = bound
            self._default_q = np.array(cls._zero_positions or [0.0] * cls._dofs[0], dtype=float)
            self._starts = None

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

    # ---------------------------------------------------------- positions
    def position_start(self) -> int:
        if self._starts is None:
            if _START_BEFORE_FINALIZE:
                return -1
            raise _no_mobilizer("position_start")
        return self._starts[0]

    def velocity_start(self) -> int:
        if self._starts is None:
            if _START_BEFORE_FINALIZE:
                return -1
            raise _no_mobilizer("velocity_start")
        return self._starts[1]

    def position_suffix(self, arg0: int) -> str:
        if self._starts is None:
            raise _no_mobilizer("position_suffix")
        return self._position_suffixes[arg0]

    def velocity_suffix(self, arg0: int) -> str:
        if self._starts is None:
            raise _no_mobilizer("velocity_suffix")
        return self._velocity_suffixes[arg0]

    def can_rotate(self) -> bool:
        if self._starts is None:
            raise _no_mobilizer("can_rotate")
        return self._motion[0]

    def can_translate(self) -> bool:
        if self._starts is None:
            raise _no_mobilizer("can_translate")
        return self._motion[1]

    # ------------------------------------------------ limits and damping
    # Stored as given (after the constructor's checks), never used.
    def position_lower_limits(self) -> npt.NDArray[np.float64]:
        return np.full(
            self.num_positions(), float(self._parameters.get("pos_lower_limit", -math.inf))
        )

    def position_upper_limits(self) -> npt.NDArray[np.float64]:
        return np.full(
            self.num_positions(), float(self._parameters.get("pos_upper_limit", math.inf))
        )

    def velocity_lower_limits(self) -> npt.NDArray[np.float64]:
        return np.full(self.num_velocities(), -math.inf)

    def velocity_upper_limits(self) -> npt.NDArray[np.float64]:
        return np.full(self.num_velocities(), math.inf)

    def acceleration_lower_limits(self) -> npt.NDArray[np.float64]:
        return np.full(self.num_velocities(), -math.inf)

    def acceleration_upper_limits(self) -> npt.NDArray[np.float64]:
        return np.full(self.num_velocities(), math.inf)

    def default_damping_vector(self) -> npt.NDArray[np.float64]:
        """One damping per velocity: the constructor's ``damping`` for each, or a
        planar joint's three, or a floating joint's angular ×3 then translational ×3."""
        p = self._parameters
        if "angular_damping" in p:
            return np.array([p["angular_damping"]] * 3 + [p["translational_damping"]] * 3, float)
        if self.kTypeName == "planar":
            return _vector(p["damping"])
        return np.full(self.num_velocities(), float(p.get("damping", 0.0)))

    def default_positions(self) -> npt.NDArray[np.float64]:
        return self._default_q.copy()

    def set_default_positions(self, default_positions: npt.ArrayLike) -> None:
        self._default_q = _sized(
            "set_default_positions", default_positions, self.num_positions()
        ).copy()

    def _q(self, context: Any) -> npt.NDArray[np.float64]:
        """A view of this joint's positions in ``context`` (writes go to the context)."""
        start = self.position_start()
        q = self.GetParentPlant()._context_positions(context)
        return q[start : start + self.num_positions()]  # type: ignore[no-any-return]

    def _set_q(self, context: Any, first: int, values: npt.ArrayLike) -> Any:
        """Writes ``values`` from this joint's position ``first`` on; returns the joint."""
        values = np.asarray(values, dtype=float).reshape(-1)
        self._q(context)[first : first + len(values)] = values
        return self

    def _set_default(self, first: int, values: npt.ArrayLike) -> None:
        values = np.asarray(values, dtype=float).reshape(-1)
        self._default_q[first : first + len(values)] = values

    def GetOnePosition(self, context: Any) -> float:
        return float(self._q(context)[0])


def _real(name: str, default: Any = None) -> Param:
    return Param(name, _is_real) if default is None else Param(name, _is_real, default)


_axis = Param("axis", _is_vector(3))


def _unit(axis: Any) -> npt.NDArray[np.float64]:
    vector = _vector(axis)
    return vector / float(np.linalg.norm(vector))


class _OneDofLimits:
    """The scalar accessors of a one-dof joint's limits and damping (revolute, prismatic).

    A mixin before Joint: velocity and acceleration limits are always ±∞ in reimpl.
    """

    if TYPE_CHECKING:  # Provided by Joint.

        def position_lower_limits(self) -> npt.NDArray[np.float64]: ...
        def position_upper_limits(self) -> npt.NDArray[np.float64]: ...
        def default_damping_vector(self) -> npt.NDArray[np.float64]: ...

    def position_lower_limit(self) -> float:
        return float(self.position_lower_limits()[0])

    def position_upper_limit(self) -> float:
        return float(self.position_upper_limits()[0])

    def velocity_lower_limit(self) -> float:
        return -math.inf

    def velocity_upper_limit(self) -> float:
        return math.inf

    def acceleration_lower_limit(self) -> float:
        return -math.inf

    def acceleration_upper_limit(self) -> float:
        return math.inf

    def default_damping(self) -> float:
        return float(self.default_damping_vector()[0])


class RevoluteJoint(_OneDofLimits, Joint):
    """q = [θ]: X_FM = (R_a(θ), 0) about the unit axis a."""

    kTypeName = "revolute"
    _dofs = (1, 1)
    _position_suffixes = ("q",)
    _velocity_suffixes = ("w",)
    _motion = (True, False)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return (
            (_axis, _real("damping", 0.0)),
            (_axis, _real("pos_lower_limit"), _real("pos_upper_limit"), _real("damping", 0.0)),
        )

    def revolute_axis(self) -> npt.NDArray[np.float64]:
        return _unit(self._parameters["axis"])

    def get_angle(self, context: Any) -> float:
        return float(self._q(context)[0])

    def set_angle(self, context: Any, angle: float) -> RevoluteJoint:
        return self._set_q(context, 0, [angle])  # type: ignore[no-any-return]

    def get_default_angle(self) -> float:
        return float(self._default_q[0])

    def set_default_angle(self, angle: float) -> None:
        self._set_default(0, [angle])


class PrismaticJoint(_OneDofLimits, Joint):
    """q = [x]: X_FM = (I, x·a) along the unit axis a."""

    kTypeName = "prismatic"
    _dofs = (1, 1)
    _position_suffixes = ("x",)
    _velocity_suffixes = ("v",)
    _motion = (False, True)

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

    def translation_axis(self) -> npt.NDArray[np.float64]:
        return _unit(self._parameters["axis"])

    def get_translation(self, context: Any) -> float:
        return float(self._q(context)[0])

    def set_translation(self, context: Any, translation: float) -> PrismaticJoint:
        return self._set_q(context, 0, [translation])  # type: ignore[no-any-return]

    def get_default_translation(self) -> float:
        return float(self._default_q[0])

    def set_default_translation(self, translation: float) -> None:
        self._set_default(0, [translation])


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
    """q = [r, p, y]: X_FM = (R_rpy(r, p, y), 0)."""

    kTypeName = "ball_rpy"
    _dofs = (3, 3)
    _position_suffixes = ("qx", "qy", "qz")
    _velocity_suffixes = ("wx", "wy", "wz")
    _motion = (True, False)

    def default_damping(self) -> float:
        return float(self.default_damping_vector()[0])

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((_real("damping", 0.0),),)

    def get_angles(self, context: Any) -> npt.NDArray[np.float64]:
        return self._q(context).copy()

    def set_angles(self, context: Any, angles: npt.ArrayLike) -> BallRpyJoint:
        return self._set_q(context, 0, _sized("set_angles", angles, 3))  # type: ignore[no-any-return]

    def get_default_angles(self) -> npt.NDArray[np.float64]:
        return self._default_q.copy()

    def set_default_angles(self, angles: npt.ArrayLike) -> None:
        self._set_default(0, _sized("set_default_angles", angles, 3))


class UniversalJoint(Joint):
    """q = [θ₀, θ₁]: X_FM = (R_x(θ₀)·R_y(θ₁), 0)."""

    kTypeName = "universal"
    _dofs = (2, 2)
    _position_suffixes = ("qx", "qy")
    _velocity_suffixes = ("wx", "wy")
    _motion = (True, False)

    def default_damping(self) -> float:
        return float(self.default_damping_vector()[0])

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((_real("damping", 0.0),),)

    def get_angles(self, context: Any) -> npt.NDArray[np.float64]:
        return self._q(context).copy()

    def set_angles(self, context: Any, angles: npt.ArrayLike) -> UniversalJoint:
        return self._set_q(context, 0, _sized("set_angles", angles, 2))  # type: ignore[no-any-return]

    def get_default_angles(self) -> npt.NDArray[np.float64]:
        return self._default_q.copy()

    def set_default_angles(self, angles: npt.ArrayLike) -> None:
        self._set_default(0, _sized("set_default_angles", angles, 2))


class PlanarJoint(Joint):
    """q = [x, y, θ]: X_FM = (R_z(θ), [x, y, 0])."""

    kTypeName = "planar"
    _dofs = (3, 3)
    _position_suffixes = ("x", "y", "qz")
    _velocity_suffixes = ("vx", "vy", "wz")
    _motion = (True, True)

    def default_damping(self) -> npt.NDArray[np.float64]:
        return self.default_damping_vector()

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((Param("damping", _is_vector(3), np.zeros(3)),),)

    def get_translation(self, context: Any) -> npt.NDArray[np.float64]:
        return self._q(context)[:2].copy()

    def set_translation(self, context: Any, p_FoMo_F: npt.ArrayLike) -> PlanarJoint:
        return self._set_q(context, 0, _sized("set_translation", p_FoMo_F, 2))  # type: ignore[no-any-return]

    def get_rotation(self, context: Any) -> float:
        return float(self._q(context)[2])

    def set_rotation(self, context: Any, theta: float) -> PlanarJoint:
        return self._set_q(context, 2, [theta])  # type: ignore[no-any-return]

    def set_pose(self, context: Any, p_FoMo_F: npt.ArrayLike, theta: float) -> PlanarJoint:
        self.set_translation(context, p_FoMo_F)
        return self.set_rotation(context, theta)

    def get_default_translation(self) -> npt.NDArray[np.float64]:
        return self._default_q[:2].copy()

    def get_default_rotation(self) -> float:
        return float(self._default_q[2])

    def set_default_translation(self, p_FoMo_F: npt.ArrayLike) -> None:
        self._set_default(0, _sized("set_default_translation", p_FoMo_F, 2))

    def set_default_rotation(self, theta: float) -> None:
        self._set_default(2, [theta])

    def set_default_pose(self, p_FoMo_F: npt.ArrayLike, theta: float) -> None:
        self.set_default_translation(p_FoMo_F)
        self.set_default_rotation(theta)


class _FloatingPose:
    """What the two 6-dof joints share: the rotation in the first positions, then
    p_FM = [x, y, z]. A mixin before Joint (it is no joint type of its own)."""

    _dofs: ClassVar[tuple[int, int]] = (6, 6)
    #: Where the translation starts in q_J.
    _translation_start: ClassVar[int] = 3
    _velocity_suffixes: ClassVar[tuple[str, ...]] = ("wx", "wy", "wz", "vx", "vy", "vz")
    _motion: ClassVar[tuple[bool, bool]] = (True, True)

    if TYPE_CHECKING:  # Provided by Joint.
        _default_q: npt.NDArray[np.float64]
        _parameters: dict[str, Any]

        def _q(self, context: Any) -> npt.NDArray[np.float64]: ...
        def _set_q(self, context: Any, first: int, values: npt.ArrayLike) -> Any: ...
        def _set_default(self, first: int, values: npt.ArrayLike) -> None: ...

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return ((_real("angular_damping", 0.0), _real("translational_damping", 0.0)),)

    def _rotation_q(self, R: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        raise NotImplementedError

    def default_angular_damping(self) -> float:
        return float(self._parameters["angular_damping"])

    def default_translational_damping(self) -> float:
        return float(self._parameters["translational_damping"])

    def get_translation(self, context: Any) -> npt.NDArray[np.float64]:
        return self._q(context)[self._translation_start :].copy()

    def SetTranslation(self, context: Any, p_FM: npt.ArrayLike) -> Any:
        return self._set_q(context, self._translation_start, _sized("SetTranslation", p_FM, 3))

    def SetOrientation(self, context: Any, R: RotationMatrix) -> Any:
        return self._set_q(context, 0, self._rotation_q(R.matrix()))

    def SetPose(self, context: Any, X_FM: RigidTransform) -> Any:
        self.SetOrientation(context, X_FM.rotation())
        return self.SetTranslation(context, X_FM.translation())

    def GetPose(self, context: Any) -> RigidTransform:
        return _pose(*kinematics.X_FM(self, self._q(context)))

    def get_default_translation(self) -> npt.NDArray[np.float64]:
        return self._default_q[self._translation_start :].copy()

    def _set_default_pose(self, X_FM: RigidTransform) -> None:
        self._set_default(0, self._rotation_q(X_FM.rotation().matrix()))
        self._set_default(self._translation_start, X_FM.translation())


class QuaternionFloatingJoint(_FloatingPose, Joint):
    """q = [qw, qx, qy, qz, x, y, z]: X_FM = (R(q/|q|), [x, y, z]).

    The one joint type Finalize's adjacency rule skips.
    """

    kTypeName = "quaternion_floating"
    _dofs = (7, 6)
    _translation_start = 4
    _zero_positions = (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    _position_suffixes = ("qw", "qx", "qy", "qz", "x", "y", "z")

    def _rotation_q(self, R: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return kinematics.quaternion_from_rotation(R)

    def set_default_translation(self, translation: npt.ArrayLike) -> None:
        self._set_default(4, _sized("set_default_translation", translation, 3))


class RpyFloatingJoint(_FloatingPose, Joint):
    """q = [r, p, y, x, y, z]: X_FM = (R_rpy(r, p, y), [x, y, z]).

    Unlike QuaternionFloatingJoint, its bodies are filtered as adjacent.
    """

    kTypeName = "rpy_floating"
    _position_suffixes = ("qx", "qy", "qz", "x", "y", "z")

    def _rotation_q(self, R: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return kinematics.rpy_from_rotation(R)

    def SetOrientation(self, context: Any, R_FM: RotationMatrix) -> Any:
        return super().SetOrientation(context, R_FM)

    def get_angles(self, context: Any) -> npt.NDArray[np.float64]:
        return self._q(context)[:3].copy()

    def set_angles(self, context: Any, angles: npt.ArrayLike) -> RpyFloatingJoint:
        return self._set_q(context, 0, _sized("set_angles", angles, 3))  # type: ignore[no-any-return]

    def get_default_angles(self) -> npt.NDArray[np.float64]:
        return self._default_q[:3].copy()

    def set_default_angles(self, angles: npt.ArrayLike) -> None:
        self._set_default(0, _sized("set_default_angles", angles, 3))

    def set_default_translation(self, p_FM: npt.ArrayLike) -> None:
        self._set_default(3, _sized("set_default_translation", p_FM, 3))


class ScrewJoint(Joint):
    """q = [θ]: X_FM = (R_a(θ), a·pitch·θ/2π) about and along the unit axis a (default z)."""

    kTypeName = "screw"
    _dofs = (1, 1)
    _position_suffixes = ("q",)
    _velocity_suffixes = ("w",)
    _motion = (True, True)

    def default_damping(self) -> float:
        return float(self.default_damping_vector()[0])

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        return (
            (_real("screw_pitch"), _real("damping")),
            (_axis, _real("screw_pitch"), _real("damping")),
        )

    def _axis(self) -> npt.NDArray[np.float64]:
        return _unit(self._parameters.get("axis", (0.0, 0.0, 1.0)))

    def screw_pitch(self) -> float:
        return float(self._parameters["screw_pitch"])

    def _translation_of(self, theta: float) -> float:
        return theta * self.screw_pitch() / (2 * math.pi)

    def _rotation_of(self, z: float) -> float:
        return z * 2 * math.pi / self.screw_pitch()

    def get_rotation(self, context: Any) -> float:
        return float(self._q(context)[0])

    def get_translation(self, context: Any) -> float:
        return self._translation_of(self.get_rotation(context))

    def set_translation(self, context: Any, translation: float) -> ScrewJoint:
        return self._set_q(context, 0, [self._rotation_of(translation)])  # type: ignore[no-any-return]

    def get_default_rotation(self) -> float:
        return float(self._default_q[0])

    def set_default_rotation(self, theta: float) -> None:
        self._set_default(0, [theta])

    def get_default_translation(self) -> float:
        return self._translation_of(self.get_default_rotation())

    def set_default_translation(self, z: float) -> None:
        self._set_default(0, [self._rotation_of(z)])


# ------------------------------------------------------------- curvilinear
# Neither class is bound in pydrake 1.51.1 (nor 1.58.0): a parsed curvilinear
# joint is seen there as a plain Joint whose type_name() is "curvilinear".
# They are reimpl's stand-ins for the C++ classes the URDF parser builds.

#: Where pydrake 1.51.1 reports PiecewiseTrajectory's DRAKE_DEMAND (SystemExit, measured).
_PIECEWISE_TRAJECTORY_DEMAND = (
    "Failure at external/drake+/common/trajectories/piecewise_trajectory.cc:19 in "
    "PiecewiseTrajectory(): condition 'breaks_[i] - breaks_[i - 1] >= kEpsilonTime' failed."
)
#: RotationMatrix's internal tolerance for orthonormality: 128 ε.
_ORTHONORMALITY_TOLERANCE = 128 * np.finfo(float).eps


class PiecewiseConstantCurvatureTrajectory:
    """A planar curve of line segments and circular arcs, by arc length s (C++ only).

    ``breaks`` are the arc lengths where pieces start (``breaks[0] = 0``), the
    piece from breaks[i] to breaks[i+1] turning at ``turning_rates[i]`` (1/m,
    0 for a line). At s = 0 the curve's frame M has x along the unit initial
    tangent t, z along the unit plane normal n and y = n × t. Checks, in
    Drake's order: each piece at least ε long (DRAKE_DEMAND: SystemExit),
    then ``The norm of the initial tangent is zero.``, ``The norm of the
    plane's normal is zero.``, and t · n within 128 ε of 0.
    """

    def __init__(
        self,
        breaks: Any,
        turning_rates: Any,
        initial_curve_tangent: Any,
        plane_normal: Any,
        *,
        initial_position: Any,
        is_periodic: bool,
    ) -> None:
        self._breaks = [float(b) for b in breaks]
        self._rates = [float(r) for r in turning_rates]
        if any(b - a < np.finfo(float).eps for a, b in itertools.pairwise(self._breaks)):
            raise SystemExit(_PIECEWISE_TRAJECTORY_DEMAND)
        if len(self._rates) != len(self._breaks) - 1:
            raise MultibodyPlantError(
                "The number of turning rates must be equal to the number of segments."
            )
        if self._breaks[0] != 0:
            raise MultibodyPlantError(
                "The first break must be 0, as the breaks are in arclength units."
            )
        t, n = _vector(initial_curve_tangent), _vector(plane_normal)
        if np.linalg.norm(t) == 0:
            raise MultibodyPlantError("The norm of the initial tangent is zero.")
        if np.linalg.norm(n) == 0:
            raise MultibodyPlantError("The norm of the plane's normal is zero.")
        if abs(float(t @ n)) > _ORTHONORMALITY_TOLERANCE:
            raise MultibodyPlantError(
                "The initial curve's tangent vector must be perpendicular to the plane's normal."
            )
        y = np.cross(n, t)
        R0 = np.column_stack([t / np.linalg.norm(t), y / np.linalg.norm(y), n / np.linalg.norm(n)])
        pose: kinematics.Pose = (R0, _vector(initial_position))
        self._break_poses = [pose]
        for i, rate in enumerate(self._rates):
            step = self._in_piece(rate, self._breaks[i + 1] - self._breaks[i])
            pose = kinematics.compose(pose, step)
            self._break_poses.append(pose)
        self._periodic = bool(is_periodic)

    def length(self) -> float:
        return self._breaks[-1]

    def is_periodic(self) -> bool:
        return self._periodic

    @staticmethod
    def _in_piece(rate: float, ds: float) -> kinematics.Pose:
        """X_MiM: ds along a piece turning at ``rate``, from the piece's start frame Mi."""
        theta = ds * rate
        R = kinematics.rotation_about(np.array([0.0, 0.0, 1.0]), theta)
        if rate == 0:
            return R, np.array([ds, 0.0, 0.0])
        return R, np.array([math.sin(theta) / rate, (1 - math.cos(theta)) / rate, 0.0])

    def calc_pose(self, s: float) -> kinematics.Pose:
        """X_AM(s); a periodic curve wraps s into [0, length), an open one extends its ends."""
        if self._periodic:
            s = s - self.length() * math.floor(s / self.length())
        clamped = min(max(s, 0.0), self.length())
        piece = min(
            max(i for i, b in enumerate(self._breaks) if b <= clamped), len(self._rates) - 1
        )
        step = self._in_piece(self._rates[piece], s - self._breaks[piece])
        return kinematics.compose(self._break_poses[piece], step)


class CurvilinearJoint(Joint):
    """q = [s]: X_FM is the curve's pose at arc length s (``curvilinear_path``).

    Limits: (-∞, ∞) for a periodic curve, else [0, length]. Negative damping
    is ``CurvilinearJoint joint damping must be nonnegative.``
    """

    kTypeName = "curvilinear"
    _dofs = (1, 1)
    _position_suffixes = ("q",)

    @classmethod
    def _overloads(cls) -> tuple[tuple[Param, ...], ...]:
        path = Param("curvilinear_path", instance_of(PiecewiseConstantCurvatureTrajectory))
        return ((path, _real("damping", 0.0)),)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        if self._parameters["damping"] < 0:
            raise MultibodyPlantError("CurvilinearJoint joint damping must be nonnegative.")

    def _X_FM(self, s: float) -> kinematics.Pose:
        path: PiecewiseConstantCurvatureTrajectory = self._parameters["curvilinear_path"]
        return path.calc_pose(s)


if not release.has("rpy-floating-joint-since-1.27"):  # bound since 1.27 (measured: 1.26.0, 1.27.0)
    del RpyFloatingJoint, RpyFloatingJoint_
    __all__ = [name for name in __all__ if name not in ("RpyFloatingJoint", "RpyFloatingJoint_")]
