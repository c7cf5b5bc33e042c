"""Attribute values in MuJoCo XML, read as Drake 1.51.1's MuJoCo parser reads them.

Drake reads numbers with ``ConvertToVector`` (C++ ``istringstream >> T``,
see ``_urdf_values``): the numbers before the first text that is none. The
readers (measured on pydrake 1.51.1):

=================  ===========================================================
 reader             rule
=================  ===========================================================
 ``string``         the text as written, ``""`` included; None when absent
 ``scalar``         exactly one number, else ``error: Expected single value
                    for attribute 'a' got 't'`` (RuntimeError, no source: the
                    parser passes no diagnostic policy); with no number at all
                    it is still that error
 ``integer``        as ``scalar``, read as ``int`` (``"1.5"`` is 1)
 ``vector``         exactly ``n`` numbers, else ``Expected n values for
                    attribute a got t`` (ValueError); None when absent
 ``numbers``        every number (``size``, ``friction``, ``gear``); [] when
                    absent
=================  ===========================================================
"""

from __future__ import annotations

import re

from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._urdf_values import convert_to_vector
from reimpl.multibody.parsing._xml import XmlElement

__all__ = ["integer", "integers", "numbers", "scalar", "string", "vector"]

#: What ``istream >> int`` takes: optional sign, digits (no point, no exponent).
_INTEGER = re.compile(r"[ \t\n\v\f\r]*([+-]?[0-9]+)")
_INT_RANGE = (-(2**31), 2**31 - 1)


def integers(text: str) -> list[int]:
    """Drake's ConvertToVector<int>: the integers before the first failure (or overflow)."""
    values: list[int] = []
    pos = 0
    while (match := _INTEGER.match(text, pos)) is not None:
        value = int(match.group(1))
        if not _INT_RANGE[0] <= value <= _INT_RANGE[1]:
            break
        values.append(value)
        pos = match.end()
    return values


def string(element: XmlElement, attribute: str) -> str | None:
    """ParseStringAttribute: the attribute's text, or None."""
    return element.get(attribute)


def numbers(element: XmlElement, attribute: str) -> list[float]:
    """ConvertToVector<double> of the attribute ([] when absent)."""
    return convert_to_vector(element.get(attribute) or "")


def _single(attribute: str, text: str, values: list[float] | list[int]) -> None:
    if len(values) != 1:
        raise Diagnostics(None).error(
            f"Expected single value for attribute '{attribute}' got '{text}'"
        )


def scalar(element: XmlElement, attribute: str) -> float | None:
    """ParseScalarAttribute<double> with Drake's default (throwing) policy."""
    text = element.get(attribute)
    if text is None:
        return None
    values = convert_to_vector(text)
    _single(attribute, text, values)
    return values[0]


def integer(element: XmlElement, attribute: str) -> int | None:
    """ParseScalarAttribute<int> with Drake's default (throwing) policy."""
    text = element.get(attribute)
    if text is None:
        return None
    values = integers(text)
    _single(attribute, text, values)
    return values[0]


def vector(element: XmlElement, attribute: str, size: int) -> list[float] | None:
    """ParseVectorAttribute: ``size`` numbers, None if absent (ValueError if not ``size``)."""
    text = element.get(attribute)
    if text is None:
        return None
    values = convert_to_vector(text)
    if len(values) != size:
        raise ValueError(f"Expected {size} values for attribute {attribute} got {text}")
    return values
