"""URDF ``<transmission>``: which joints get actuators (Drake 1.51.1, measured).

A transmission reads, in order (an error stops the parse; lines are the
transmission's unless said otherwise):

1. warnings for ``leftActuator``, ``rightActuator``, ``flexJoint``,
   ``rollJoint``, ``gap_joint``, ``passive_joint``,
   ``use_simulated_gripper_joint`` children, and for a ``mechanicalReduction``
   whose text is not the single number 1;
2. the type: the text of ``<type>``, else the ``type`` attribute (neither:
   ``Transmission element is missing a type.``); one without
   ``SimpleTransmission`` in it is warned about and skipped;
3. ``<actuator name>`` (its ``mechanicalReduction`` warned as above) and
   ``<joint name>``: ``Transmission is missing an actuator element.``, ``...
   an actuator name.``, ``... a joint element.``, ``... a joint name.``;
4. the joint must exist in the robot (``Transmission specifies joint 'j'
   which does not exist.`` at the ``<joint>`` line); a joint without positions
   (fixed) is warned about and skipped; a negative effort limit is an error,
   a zero one a warning and a skip;
5. the actuator is added (a name taken in the model instance is
   ``Model instance 'r' already contains a joint actuator named 'a'. Joint
   actuator names must be unique within a given model.``), then its
   ``drake:rotor_inertia value``, ``drake:gear_ratio value`` and
   ``drake:controller_gains p d`` are read.

reimpl's plant has no actuators: this reads and checks, and remembers the
names it would have added to the robot's model instance. pydrake crashes
(segfault) on an empty ``<type/>``; reimpl reads it as an empty type.
"""

from __future__ import annotations

from typing import Any

from reimpl.geometry._drake_text import shortest
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._urdf_joints import warn_unsupported_child
from reimpl.multibody.parsing._urdf_values import Values, convert_to_vector
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["TransmissionReader"]

_UNSUPPORTED = (
    "leftActuator",
    "rightActuator",
    "flexJoint",
    "rollJoint",
    "gap_joint",
    "passive_joint",
    "use_simulated_gripper_joint",
)
#: actuator child -> (attributes read, in order; how Drake names a missing one)
_ACTUATOR_VALUES: tuple[tuple[str, tuple[str, ...], str], ...] = (
    ("drake:rotor_inertia", ("value",), '"value"'),
    ("drake:gear_ratio", ("value",), '"value"'),
    ("drake:controller_gains", ("p", "d"), "'{}'"),
)


class TransmissionReader:
    """Reads one robot's transmissions; ``efforts`` are its joints' effort limits."""

    def __init__(
        self,
        plant: Any,
        instance: Any,
        diagnostics: Diagnostics,
        efforts: dict[str, float],
    ) -> None:
        self.plant, self.instance, self.diagnostics = plant, instance, diagnostics
        self.values = Values(diagnostics)
        self.efforts = efforts
        self.actuators: set[str] = set()

    def read(self, element: XmlElement) -> None:
        d = self.diagnostics
        for tag in _UNSUPPORTED:
            warn_unsupported_child(d, element, tag)
        self._mechanical_reduction(element)
        types = children(element, "type")
        kind = (types[0].text or "") if types else element.get("type")
        if kind is None:
            raise d.error("Transmission element is missing a type.", element.line)
        if "SimpleTransmission" not in kind:
            d.warning(
                "A <transmission> has a type that isn't 'SimpleTransmission'. Drake only "
                "supports 'SimpleTransmission'; all other transmission types will be ignored.",
                element.line,
            )
            return
        actuator = self._child(element, "actuator", "an actuator element")
        self._mechanical_reduction(actuator)
        actuator_name = self._name(actuator, "an actuator name")
        joint_node = self._child(element, "joint", "a joint element")
        joint_name = self._name(joint_node, "a joint name")
        if not self.plant.HasJointNamed(joint_name, self.instance):
            raise d.error(
                f"Transmission specifies joint '{joint_name}' which does not exist.",
                joint_node.line,
            )
        joint = self.plant.GetJointByName(joint_name, self.instance)
        if joint.num_positions() == 0:
            d.warning(
                f'Skipping transmission since it\'s attached to a fixed joint "{joint_name}".',
                joint_node.line,
            )
            return
        effort = self.efforts[joint_name]
        if effort < 0:
            raise d.error(
                f"Transmission specifies joint '{joint_name}' which has a negative effort limit.",
                joint_node.line,
            )
        if effort <= 0:
            d.warning(
                f'Skipping transmission since it\'s attached to joint "{joint_name}" which has a '
                f"zero effort limit {shortest(effort)}.",
                joint_node.line,
            )
            return
        self._add_actuator(actuator_name, joint)
        self._actuator_values(actuator, actuator_name)

    def _child(self, element: XmlElement, tag: str, what: str) -> XmlElement:
        nodes = children(element, tag)
        if not nodes:
            raise self.diagnostics.error(f"Transmission is missing {what}.", element.line)
        return nodes[0]

    def _name(self, element: XmlElement, what: str) -> str:
        name = element.get("name")
        if name is None:
            raise self.diagnostics.error(f"Transmission is missing {what}.", element.line)
        return name

    def _mechanical_reduction(self, element: XmlElement) -> None:
        nodes = children(element, "mechanicalReduction")
        if not nodes or nodes[0].text is None:
            return
        text = nodes[0].text
        if convert_to_vector(text) == [1.0]:
            return
        self.diagnostics.warning(
            f"A '{element.tag}' element contains a mechanicalReduction element with a value "
            f"'{text}' other than the default of 1. MultibodyPlant does not currently support "
            "non-default mechanical reductions.",
            nodes[0].line,
        )

    def _add_actuator(self, name: str, joint: Any) -> None:
        """MultibodyPlant::AddJointActuator's name check (reimpl keeps no actuator)."""
        if name in self.actuators:
            instance = self.plant.GetModelInstanceName(joint.model_instance())
            raise RuntimeError(
                f"Model instance '{instance}' already contains a joint actuator named '{name}'. "
                "Joint actuator names must be unique within a given model."
            )
        self.actuators.add(name)

    def _actuator_values(self, actuator: XmlElement, name: str) -> None:
        for tag, attributes, quoted in _ACTUATOR_VALUES:
            nodes = children(actuator, tag)
            if not nodes:
                continue
            for attribute in attributes:
                if self.values.scalar(nodes[0], attribute) is None:
                    shown = quoted.format(attribute)
                    raise self.diagnostics.error(
                        f"joint actuator {name}'s {tag} does not have a {shown} attribute!",
                        nodes[0].line,
                    )
