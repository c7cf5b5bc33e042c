"""MuJoCo ``<actuator>``: motors and position actuators, read for Drake 1.51.1's checks.

Every ``<motor>``, then every ``<position>`` (so motors come first whatever the
order), each (measured on pydrake 1.51.1):

1. ``name`` defaults to ``motor<n>``, n the plant's number of actuators; the
   class's defaults (``class``, else ``main``) of that element are applied;
2. without ``joint``: ``The motor 'N' does not use the 'joint' transmission
   specification. Currently only the 'joint' attribute is supported.  This
   motor will be ignored.``, and nothing more;
3. the control and force limits (``ctrlrange``/``ctrllimited``,
   ``forcerange``/``forcelimited``, read as a joint's ``range``/``limited``):
   the effort limit is the smaller of max(upper, −lower) of each limited one
   (∞ if neither); lower > upper is warned about and ignored, lower ≠ −upper
   is warned about;
4. warnings for the attributes in ``_UNSUPPORTED``;
5. MultibodyPlant::AddJointActuator on the model instance's joint of that
   name (a missing joint: GetJointByName's error; a joint without one degree
   of freedom, a name taken in the instance, an effort limit that is not > 0:
   Drake's errors);
6. ``gear``: its first number is the gear ratio (neither 1 nor 6 numbers is
   warned about); the joint's ``armature`` / ratio² is the rotor inertia;
7. for ``<position>``: ``kp`` (1) and ``kd`` (0), which set_controller_gains
   demands finite and >= 0 (a SystemExit), then warnings for ``dampratio``,
   ``timeconst`` and ``inheritrange``.

Then ``<general>``, ``<velocity>``, ``<intvelocity>``, ``<damper>``,
``<cylinder>``, ``<muscle>``, ``<adhesion>`` and ``<plugin>`` are warned about.
reimpl's plant keeps no actuators: each is checked, and its name remembered
per plant (for the next default name and the uniqueness check) by the MuJoCo
reader alone, so a URDF transmission's actuator is not counted.
"""

from __future__ import annotations

import math
import weakref
from typing import Any

from reimpl.geometry._drake_text import shortest
from reimpl.multibody.parsing import _mjcf_values as values
from reimpl.multibody.parsing._mjcf_context import MjcfContext
from reimpl.multibody.parsing._mjcf_defaults import apply_defaults
from reimpl.multibody.parsing._mjcf_joints import read_limits
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["read_actuator"]

_UNSUPPORTED = (
    "group",
    "lengthrange",
    "cranklength",
    "jointinparent",
    "tendon",
    "cranksite",
    "slidersite",
    "site",
    "refsite",
    "user",
    "dyntype",
    "gaintype",
    "biastype",
    "dynprm",
    "gainprm",
    "biasprm",
)
_POSITION_UNSUPPORTED = ("dampratio", "timeconst", "inheritrange")
_UNSUPPORTED_ELEMENTS = (
    "general",
    "velocity",
    "intvelocity",
    "damper",
    "cylinder",
    "muscle",
    "adhesion",
    "plugin",
)
_GAINS = (
    "Failure at external/drake+/multibody/tree/joint_actuator.cc:{} in set_controller_gains(): "
)

#: plant -> the (model instance, name) of each actuator MuJoCo files added to it
_ADDED: weakref.WeakKeyDictionary[Any, list[tuple[int, str]]] = weakref.WeakKeyDictionary()


def _effort(context: MjcfContext, node: XmlElement, name: str) -> float:
    """The effort limit from the control and force limits (with Drake's warnings)."""
    ctrl_limited, ctrl = read_limits(context, node, "ctrlrange", "ctrllimited")
    force_limited, force = read_limits(context, node, "forcerange", "forcelimited")
    effort = math.inf
    for attribute, limited, (lower, upper) in (
        ("ctrlrange", ctrl_limited, ctrl),
        ("forcerange", force_limited, force),
    ):
        if not limited:
            continue
        if lower > upper:
            context.d.warning(
                node,
                f"The motor '{name}' specified a {attribute} attribute where lower limit > "
                "upper limit; these limits will be ignored.",
            )
            continue
        largest = max(upper, -lower)
        effort = min(effort, largest)
        if -lower != upper:
            context.d.warning(
                node,
                f"The motor '{name}' specified a {attribute} attribute where lower limit != "
                "-upper limit. Asymmetrical effort limits are not supported yet, so the larger "
                f"of the values {shortest(largest)} will be used.",
            )
    return effort


def _add(context: MjcfContext, name: str, joint: Any, effort: float) -> None:
    """MultibodyPlant::AddJointActuator's checks, in its order."""
    if joint.num_velocities() != 1:
        raise RuntimeError(
            f"Calling AddJointActuator with joint {joint.name()} failed -- this joint has "
            f"{joint.num_velocities()} degrees of freedom, and MultibodyPlant currently only "
            "supports actuators for single degree-of-freedom joints. See "
            "https://stackoverflow.com/q/71477852/9510020 for the common workarounds."
        )
    added = _ADDED.setdefault(context.plant, [])
    instance = int(joint.model_instance())
    if (instance, name) in added:
        raise RuntimeError(
            f"Model instance '{context.plant.GetModelInstanceName(joint.model_instance())}' "
            f"already contains a joint actuator named '{name}'. Joint actuator names must be "
            "unique within a given model."
        )
    if not effort > 0.0:
        raise RuntimeError(
            f"JointActuator effort limit must be strictly positive (not {shortest(effort)})"
        )
    added.append((instance, name))


def _gains(node: XmlElement) -> None:
    """set_controller_gains's demands on ``kp`` and ``kd``."""
    kp, kd = values.scalar(node, "kp"), values.scalar(node, "kd")
    p = 1.0 if kp is None else kp
    d = 0.0 if kd is None else kd
    for line, holds, condition in (
        (33, math.isfinite(p), "std::isfinite(gains.p)"),
        (34, math.isfinite(d), "std::isfinite(gains.d)"),
        (35, p >= 0.0, "gains.p >= 0.0"),
        (36, d >= 0.0, "gains.d >= 0.0"),
    ):
        if not holds:
            raise SystemExit(_GAINS.format(line) + f"condition '{condition}' failed.")


def _motor_or_position(context: MjcfContext, node: XmlElement) -> None:
    """ParseMotorOrPosition."""
    name = node.get("name")
    if name is None:
        name = f"motor{len(_ADDED.get(context.plant, []))}"
    class_name = node.get("class")
    apply_defaults(context, node.tag, "main" if class_name is None else class_name, node)
    joint_name = node.get("joint")
    if joint_name is None:
        context.d.warning(
            node,
            f"The motor '{name}' does not use the 'joint' transmission specification. "
            "Currently only the 'joint' attribute is supported.  This motor will be ignored.",
        )
        return
    effort = _effort(context, node, name)
    context.d.warn_unsupported_attributes(node, _UNSUPPORTED)
    joint = context.plant.GetJointByName(joint_name, context.instance)
    _add(context, name, joint, effort)
    gear = node.get("gear")
    if gear is not None and len(values.numbers(node, "gear")) not in (1, 6):
        context.d.warning(
            node, f"Expected either 1 value or 6 values for 'gear' attribute, but got {gear}."
        )
    if node.tag == "position":
        _gains(node)
        context.d.warn_unsupported_attributes(node, _POSITION_UNSUPPORTED)


def read_actuator(context: MjcfContext, node: XmlElement) -> None:
    """ParseActuator: motors, then position actuators, then the warnings."""
    for tag in ("motor", "position"):
        for element in children(node, tag):
            _motor_or_position(context, element)
    context.d.warn_unsupported_elements(node, _UNSUPPORTED_ELEMENTS)
