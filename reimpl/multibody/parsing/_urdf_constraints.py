"""URDF's Drake force elements and constraints, read for their errors (Drake 1.51.1, measured).

``<drake:linear_bushing_rpy>``, ``<drake:linear_spring_damper>``,
``<drake:ball_constraint>`` and ``<drake:tendon_constraint>`` (read in that
order, after the robot's ``<frame>``s) name frames, bodies and joints of the
robot and give numbers in ``value`` attributes. Their children are read in
the order listed below; the first problem stops the parse:

==============================  ===========================================================
 a child that is                 Drake's error
==============================  ===========================================================
 missing                         ``Unable to find the <t> tag`` (element's line)
 a frame/body without ``name``   ``Unable to read the 'name' attribute for the <t> tag``
 a frame/body not in the robot   ``Frame: x specified for <t> does not exist in the model.``
                                 (``Body: x ...``), at the child's line
 a vector without ``value``      ``Unable to read the 'value' attribute for the <t> tag``
 a number without ``value``      the same (at the child's line, for a spring; the element's,
                                 for a tendon)
==============================  ===========================================================

Then the plant's own checks, by pydrake's messages: a bushing's four
vectors must be >= 0; a spring's free length > 0, stiffness and damping >= 0
(checked by the parser); a ball constraint needs two bodies; a tendon needs
one joint at least, no joint twice, one-dof joints, lower <= upper,
stiffness > 0 and damping >= 0. reimpl's plant holds no force elements nor
constraints: nothing is added.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._urdf_values import Values, vector
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["ConstraintReader"]

_BUSHING = "drake:linear_bushing_rpy"
_SPRING = "drake:linear_spring_damper"
_BALL = "drake:ball_constraint"
_TENDON = "drake:tendon_constraint"
_FAILURE = "Failure at external/drake+/multibody/"


def _demand(where: str, line: int, function: str, condition: str) -> SystemExit:
    """How pydrake 1.51.1 reports a DRAKE_THROW_UNLESS in these constructors (measured)."""
    return SystemExit(f"{_FAILURE}{where}:{line} in {function}(): condition '{condition}' failed.")


class ConstraintReader:
    """Reads one robot's bushings, springs, ball and tendon constraints."""

    def __init__(self, plant: Any, instance: Any, diagnostics: Diagnostics) -> None:
        self.plant, self.instance, self.diagnostics = plant, instance, diagnostics
        self.values = Values(diagnostics)

    def read_all(self, robot: XmlElement) -> None:
        readers: tuple[tuple[str, Callable[[XmlElement], None]], ...] = (
            (_BUSHING, self._bushing),
            (_SPRING, self._spring),
            (_BALL, self._ball),
            (_TENDON, self._tendon),
        )
        for tag, read in readers:
            for element in children(robot, tag):
                read(element)

    # ------------------------------------------------------------- children
    def _child(self, element: XmlElement, tag: str) -> XmlElement:
        nodes = children(element, tag)
        if not nodes:
            raise self.diagnostics.error(f"Unable to find the <{tag}> tag", element.line)
        return nodes[0]

    def _vector(self, element: XmlElement, tag: str) -> list[float]:
        node = self._child(element, tag)
        values = vector(node, "value", 3)
        if values is None:
            raise self.diagnostics.error(
                f"Unable to read the 'value' attribute for the <{tag}> tag", element.line
            )
        return values

    def _named(
        self, element: XmlElement, tag: str, kind: str, exists: Callable[[str], bool]
    ) -> str:
        node = self._child(element, tag)
        name = node.get("name")
        if name is None:
            raise self.diagnostics.error(
                f"Unable to read the 'name' attribute for the <{tag}> tag", node.line
            )
        if not exists(name):
            raise self.diagnostics.error(
                f"{kind}: {name} specified for <{tag}> does not exist in the model.", node.line
            )
        return name

    def _frame(self, element: XmlElement, tag: str) -> str:
        return self._named(
            element, tag, "Frame", lambda n: self.plant.HasFrameNamed(n, self.instance)
        )

    def _body(self, element: XmlElement, tag: str) -> str:
        return self._named(
            element, tag, "Body", lambda n: self.plant.HasBodyNamed(n, self.instance)
        )

    def _number(self, element: XmlElement, tag: str, at_child: bool) -> float:
        node = self._child(element, tag)
        value = self.values.scalar(node, "value")
        if value is None:
            raise self.diagnostics.error(
                f"Unable to read the 'value' attribute for the <{tag}> tag",
                node.line if at_child else element.line,
            )
        return value

    # ------------------------------------------------------------- elements
    def _bushing(self, element: XmlElement) -> None:
        self._frame(element, "drake:bushing_frameA")
        self._frame(element, "drake:bushing_frameC")
        quantities = ("torque_stiffness", "torque_damping", "force_stiffness", "force_damping")
        read = {q: self._vector(element, f"drake:bushing_{q}") for q in quantities}
        for quantity, values in read.items():
            if min(values) < 0:
                raise _demand(
                    "tree/linear_bushing_roll_pitch_yaw.cc",
                    _BUSHING_LINES[quantity],
                    "LinearBushingRollPitchYaw",
                    f"{quantity}_constants.minCoeff() >= 0",
                )

    def _spring(self, element: XmlElement) -> None:
        prefix = "drake:linear_spring_damper_"
        self._body(element, f"{prefix}body_A")
        self._body(element, f"{prefix}body_B")
        self._vector(element, f"{prefix}p_AP")
        self._vector(element, f"{prefix}p_BQ")
        for quantity, strictly in (("free_length", True), ("stiffness", False), ("damping", False)):
            tag = f"{prefix}{quantity}"
            value = self._number(element, tag, at_child=True)
            if (value <= 0 and strictly) or value < 0:
                sign = "strictly positive" if strictly else "non-negative"
                raise self.diagnostics.error(
                    f"The 'value' attribute for the <{tag}> tag must be {sign}.",
                    children(element, tag)[0].line,
                )

    def _ball(self, element: XmlElement) -> None:
        body_A = self._body(element, "drake:ball_constraint_body_A")
        body_B = self._body(element, "drake:ball_constraint_body_B")
        self._vector(element, "drake:ball_constraint_p_AP")
        self._vector(element, "drake:ball_constraint_p_BQ")
        if body_A == body_B:
            raise RuntimeError(
                f"Invalid set of parameters for constraint between bodies '{body_A}' and "
                f"'{body_B}'. For a ball constraint, points P and Q must be on two distinct "
                "bodies, i.e. body_A != body_B must be satisfied."
            )

    def _tendon(self, element: XmlElement) -> None:
        d = self.diagnostics
        joints = []
        for node in children(element, "drake:tendon_constraint_joint"):
            name = node.get("name")
            if name is None:
                raise d.error(
                    f'The tag <{node.tag}> does not specify the required attribute "name".',
                    node.line,
                )
            if not self.plant.HasJointNamed(name, self.instance):
                raise d.error(
                    f"<{_TENDON}>: Joint '{name}' specified for <{node.tag}> does not exist in "
                    "the model.",
                    element.line,
                )
            if self.values.scalar(node, "a") is None:
                raise d.error(
                    f"Unable to read the 'a' attribute for the <{node.tag}> tag", node.line
                )
            joints.append(self.plant.GetJointByName(name, self.instance))
        quantities = ("offset", "lower_limit", "upper_limit", "stiffness", "damping")
        values = {q: self._number(element, f"{_TENDON}_{q}", at_child=False) for q in quantities}
        self._check_tendon(joints, values)

    @staticmethod
    def _check_tendon(joints: list[Any], values: dict[str, float]) -> None:
        """MultibodyPlant::AddTendonConstraint's checks, in its order."""
        where, function = "plant/multibody_plant.cc", "AddTendonConstraint"
        if not joints:
            raise _demand(where, 754, function, "joints.size() > 0")
        if len({int(j.index()) for j in joints}) != len(joints):
            raise RuntimeError(
                "AddTendonConstraint(): Duplicated joint in `joints`. `joints` must be a unique "
                "set of JointIndex."
            )
        if any(j.num_velocities() != 1 for j in joints):
            raise _demand(where, 770, function, "this->get_joint(joints[i]).num_velocities() == 1")
        checks = (
            (values["lower_limit"] <= values["upper_limit"], 790, "*lower_limit <= *upper_limit"),
            (values["stiffness"] > 0.0, 793, "*stiffness > 0.0"),
            (values["damping"] >= 0.0, 799, "*damping >= 0.0"),
        )
        for holds, line, condition in checks:
            if not holds:
                raise _demand(where, line, function, condition)


#: Bushing quantity -> line of its DRAKE_THROW_UNLESS in linear_bushing_roll_pitch_yaw.cc.
_BUSHING_LINES = {
    "torque_stiffness": 43,
    "torque_damping": 44,
    "force_stiffness": 45,
    "force_damping": 46,
}
