"""The frames Finalize adds so that each joint's mobilizer can be a fast one (Drake 1.51.1).

A mobilizer joins a frame F on its inboard body to a frame M on its outboard
body: the joint's parent frame Jp and child frame Jc, or Jc and Jp for a
joint the tree reaches from its child (a reversed one: Jin, Jout below).
Drake's revolute and prismatic mobilizers move about or along an axis of F,
and its weld mobilizer wants F and M to coincide, so where the joint's own
frames do not serve, Finalize adds ephemeral FixedOffsetFrames in the joint's
model instance, named ``<joint>_<frame>_<F|M>`` (with a leading ``_`` until
no frame of that instance has the name), in the order the tree is walked
(measured on pydrake 1.51.1 and 1.58.0: names, bodies, poses,
``is_ephemeral()``). Welds get theirs since 1.39, revolute and prismatic joints
since 1.41 (drake's weld_joint.cc and revolute_joint.cc at those tags; 1.30
adds none: the release facts weld-mobilizer-frame-since-1.39 and
axial-mobilizer-frames-since-1.41):

==================  ===========================================  ================================
joint               when                                         frames (base frame: pose)
==================  ===========================================  ================================
revolute,           its unit axis, negated when reversed, is     F (Jin: R), M (Jout: R), with R
prismatic           not exactly +x, +y or +z                     taking z to the axis
                                                                 (MakeFromOneUnitVector)
weld                X_JpJc is not exactly the identity           F (Jp: X_JpJc), or reversed
                                                                 F (Jc: X_JpJc⁻¹)
==================  ===========================================  ================================
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import numpy.typing as npt

from reimpl._release import release
from reimpl.math import RigidTransform, RotationMatrix

__all__ = ["from_one_unit_vector", "mobilizer_frames"]

#: (suffix, the frame it is fixed to, its pose there)
FrameSpec = tuple[str, Any, RigidTransform]
#: (joint, whether it is modeled reversed) → the frames its mobilizer needs
Needs = Callable[[Any, bool], list[FrameSpec]]


def from_one_unit_vector(u: npt.NDArray[np.float64], axis_index: int) -> RotationMatrix:
    """R_AB whose column ``axis_index`` is the unit vector u, completed to a right-handed
    basis as Drake's RotationMatrix::MakeFromOneUnitVector does: with i the index of u's
    smallest |component| (the first on a tie), j = i + 1, k = j + 1 (mod 3), v = r·(a × u)
    for a = e_i and r = 1/√(1 − u_i²), then w = u × v = r·(e_i − u_i·u)."""
    i = int(np.argmin(np.abs(u)))
    j, k = (i + 1) % 3, (i + 2) % 3
    magnitude = float(np.sqrt(1.0 - u[i] * u[i]))
    r = 1.0 / magnitude
    s = -r * u[i]
    v, w = np.zeros(3), np.zeros(3)
    v[j], v[k] = -r * u[k], r * u[j]
    w[i], w[j], w[k] = magnitude, s * u[j], s * u[k]
    R = np.zeros((3, 3))
    R[:, axis_index] = u
    R[:, (axis_index + 1) % 3] = v
    R[:, (axis_index + 2) % 3] = w
    return RotationMatrix(R)


def _axial(axis: Callable[[Any], npt.NDArray[np.float64]]) -> Needs:
    def frames(joint: Any, reversed_: bool) -> list[FrameSpec]:
        u = -axis(joint) if reversed_ else axis(joint)
        if any(u[i] == 1.0 for i in range(3)):
            return []
        inboard, outboard = _ends(joint, reversed_)
        X = RigidTransform(from_one_unit_vector(u, 2))
        return [("F", inboard, X), ("M", outboard, X)]

    return frames


def _weld(joint: Any, reversed_: bool) -> list[FrameSpec]:
    X_JpJc = joint.X_FM()
    if X_JpJc.IsExactlyIdentity():
        return []
    if reversed_:
        return [("F", joint.frame_on_child(), X_JpJc.inverse())]
    return [("F", joint.frame_on_parent(), X_JpJc)]


def _ends(joint: Any, reversed_: bool) -> tuple[Any, Any]:
    """(Jin, Jout): the joint's frames on the inboard and the outboard body."""
    parent, child = joint.frame_on_parent(), joint.frame_on_child()
    return (child, parent) if reversed_ else (parent, child)


#: joint type name → (the release fact from which Finalize adds them, the frames its
#: mobilizer needs); none for the other types, nor before that release.
_NEEDS: dict[str, tuple[str, Needs]] = {
    "revolute": ("axial-mobilizer-frames-since-1.41", _axial(lambda j: j.revolute_axis())),
    "prismatic": ("axial-mobilizer-frames-since-1.41", _axial(lambda j: j.translation_axis())),
    "weld": ("weld-mobilizer-frame-since-1.39", _weld),
}


def mobilizer_frames(joint: Any, reversed_: bool) -> Iterator[FrameSpec]:
    """The frames Finalize adds for ``joint``, modeled in the direction ``reversed_`` says."""
    fact, needs = _NEEDS.get(joint.type_name(), (None, None))
    if fact is not None and needs is not None and release.has(fact):
        yield from needs(joint, reversed_)
