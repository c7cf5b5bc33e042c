"""Numbers in URDF attributes, read as Drake 1.51.1 reads them (detail_tinyxml.cc).

Drake splits an attribute into numbers with C++'s ``istringstream >> double``
in the classic locale: each number is the longest prefix of the form
``[+-]digits[.digits][(e|E)[+-]digits]`` after whitespace, and reading stops at
the first text that is no number, or whose value overflows. So ``"1abc"`` is
[1], ``"1.5.5"`` is [1.5, 0.5], ``"0x10"`` is [0], and ``"1e"``, ``"inf"``,
``"nan"``, ``"1e400"`` and ``""`` are [] (measured on pydrake 1.51.1).

=========================  ===================================================
 reader                     rule
=========================  ===================================================
 ``scalar``                 exactly one number, else the error ``Expected
                            single value for attribute 'a' got 't'`` (at the
                            element's line); absent: None
 ``vector``                 exactly ``n`` numbers, else a ValueError without a
                            source: ``Expected 3 values for attribute a got t``
 ``three_vector`` (scale)   with a space, a ``vector``; else one number for all
                            three axes, whose error names no source at all
 ``origin``                 ``xyz`` then ``rpy`` (vectors; default zero)
=========================  ===================================================
"""

from __future__ import annotations

import math
import re

from reimpl.math import RigidTransform, RollPitchYaw
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._xml import XmlElement

__all__ = ["Values", "convert_to_vector", "origin", "scan_double", "vector"]

#: What ``istream >> double`` takes for one number (libstdc++'s num_get grammar).
_NUMBER = re.compile(r"[ \t\n\v\f\r]*([+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]*)(?:[eE][+-]?[0-9]*)?)")


def convert_to_vector(text: str) -> list[float]:
    """Drake's ConvertToVector<double>: the numbers before the first failure."""
    values: list[float] = []
    pos = 0
    while (match := _NUMBER.match(text, pos)) is not None:
        try:
            value = float(match.group(1))
        except ValueError:  # "1e", "." and the like: num_get took it, strtod rejects it
            break
        if math.isinf(value):  # N.B. Overflow fails the stream.
            break
        values.append(value)
        pos = match.end()
    return values


#: What C's ``sscanf("%lf")`` (strtod) reads after whitespace: a decimal number, inf or nan.
_STRTOD = re.compile(
    r"[ \t\n\v\f\r]*([+-]?(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
    r"|inf(?:inity)?|nan))",
    re.IGNORECASE,
)


def scan_double(text: str) -> float | None:
    """tinyxml2's QueryDoubleText (``sscanf("%lf")``): the leading number, or None."""
    match = _STRTOD.match(text)
    return float(match.group(1)) if match else None


def vector(element: XmlElement, attribute: str, size: int) -> list[float] | None:
    """Drake's ParseVectorAttribute: ``size`` numbers, None if absent (ValueError if not)."""
    text = element.get(attribute)
    if text is None:
        return None
    values = convert_to_vector(text)
    if len(values) != size:
        raise ValueError(f"Expected {size} values for attribute {attribute} got {text}")
    return values


def origin(element: XmlElement) -> RigidTransform:
    """Drake's OriginAttributesToTransform: ``xyz`` (read first) and ``rpy`` of ``element``."""
    xyz = vector(element, "xyz", 3) or [0.0, 0.0, 0.0]
    rpy = vector(element, "rpy", 3) or [0.0, 0.0, 0.0]
    return RigidTransform(RollPitchYaw(rpy), xyz)


class Values:
    """Scalar attributes, whose errors go to ``diagnostics`` at the element's line."""

    def __init__(self, diagnostics: Diagnostics) -> None:
        self.diagnostics = diagnostics

    def scalar(self, element: XmlElement, attribute: str) -> float | None:
        """Drake's ParseScalarAttribute; None when absent (or no number, in a lenient policy)."""
        return _scalar(element, attribute, self.diagnostics, element.line)

    def three_vector(self, element: XmlElement, attribute: str) -> list[float] | None:
        """Drake's ParseThreeVectorAttribute (a mesh's ``scale``)."""
        text = element.get(attribute)
        if text is None:
            return None
        if " " in text:
            return vector(element, attribute, 3)
        value = _scalar(element, attribute, Diagnostics(None), None)
        return [value, value, value] if value is not None else None


def _scalar(
    element: XmlElement, attribute: str, diagnostics: Diagnostics, line: int | None
) -> float | None:
    text = element.get(attribute)
    if text is None:
        return None
    values = convert_to_vector(text)
    if len(values) != 1:
        raise diagnostics.error(
            f"Expected single value for attribute '{attribute}' got '{text}'", line
        )
    return values[0]
