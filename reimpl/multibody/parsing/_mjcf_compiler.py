"""MuJoCo ``<compiler>`` and ``<option>``, as Drake 1.51.1 reads them (detail_mujoco_parser.cc).

``<compiler>`` (every one, in order; a later one overrides):

==================  ===========================================================
 attribute           Drake's reading
==================  ===========================================================
 ``autolimits``      tinyxml2's bool (``true``/``True``/``TRUE``, ``false``...,
                     or a leading integer, nonzero true); anything else: true
 ``coordinate``      anything but ``local`` is an error (``Compiler attribute
                     coordinate=X is not supported yet.``)
 ``angle``           ``degree`` (the default) or ``radian``; else a warning
                     (``Unknown value X for the compiler `angle` attribute will
                     be ignored.  The existing value of `angle=degree` will
                     remain unchanged.``)
 ``assetdir``        the mesh folder; ``meshdir`` overrides it
 ``eulerseq``        three of ``xyzXYZ``, else ``Illegal value 'X' for the
                     eulerseq in compiler. Valid eulerseq are exactly three
                     characters from the set [x,y,z,X,Y,Z]``; up to 1.24 an
                     unsupported attribute, warned about after ``fitaabb``
                     (mjcf-eulerseq-since-1.25)
 ``inertiafromgeom`` a tinyxml2 bool, or ``auto``; else a warning (``The
                     attribute 'inertiafromgeom' found in a 'compiler' tag
                     cannot be interpreted as a boolean nor 'auto' and will be
                     ignored.``)
==================  ===========================================================

then warnings for the attributes in ``_COMPILER_UNSUPPORTED`` and a
``<lengthrange>`` child. ``<option gravity>`` sets the plant's gravity in
Drake; reimpl's plant has no gravity field, so it is read (3 numbers) and
kept nowhere. The option attributes in ``_OPTION_UNSUPPORTED`` and a
``<flag>`` child are warned about; the solver's own are ignored silently.
"""

from __future__ import annotations

import re

from reimpl._release import release
from reimpl.multibody.parsing import _mjcf_values as values
from reimpl.multibody.parsing._mjcf_context import InertiaFromGeom, MjcfContext
from reimpl.multibody.parsing._xml import XmlElement

__all__ = ["read_compiler", "read_option", "tinyxml_bool"]

#: Whether ``eulerseq`` is read (since 1.25) or warned about as unsupported (measured on
#: pydrake 1.24.0: the warning, and any value, even an illegal one, is ignored).
_READS_EULERSEQ = release.has("mjcf-eulerseq-since-1.25")
_COMPILER_UNSUPPORTED = (
    "boundmass",
    "boundinertia",
    "settotalmass",
    "balanceinertia",
    "strippath",
    "fitaabb",
    *(() if _READS_EULERSEQ else ("eulerseq",)),
    "texturedir",
    "discardvisual",
    "fusestatic",
    "alignfree",
    "inertiagrouprange",
)
_OPTION_UNSUPPORTED = (
    "timestep",
    "wind",
    "magnetic",
    "density",
    "viscosity",
    "integrator",
    "cone",
    "actuatorgroupdisable",
)
#: What C's ``sscanf("%d")`` reads (tinyxml2's ToInt); a ``0x`` prefix reads hex.
_INT = re.compile(r"[ \t\n\v\f\r]*[+-]?[0-9]")
_HEX = re.compile(r"[ \t\n\v\f\r]*0[xX]")
_BOOLS = {
    **dict.fromkeys(("true", "True", "TRUE"), True),
    **dict.fromkeys(("false", "False", "FALSE"), False),
}


def tinyxml_bool(text: str) -> bool | None:
    """tinyxml2's XMLUtil::ToBool: the text as a bool, or None where it is none."""
    if _HEX.match(text):
        digits = re.match(r"[ \t\n\v\f\r]*0[xX]([0-9a-fA-F]*)", text)
        assert digits is not None
        return int(digits.group(1) or "0", 16) != 0
    if _INT.match(text):
        number = re.match(r"[ \t\n\v\f\r]*([+-]?[0-9]+)", text)
        assert number is not None
        return int(number.group(1)) != 0
    return _BOOLS.get(text)


def _eulerseq(context: MjcfContext, node: XmlElement, sequence: str) -> None:
    if len(sequence) != 3 or any(ch not in "xyzXYZ" for ch in sequence):
        raise context.d.error(
            node,
            f"Illegal value '{sequence}' for the eulerseq in {node.tag}. Valid eulerseq are "
            "exactly three characters from the set [x,y,z,X,Y,Z]",
        )
    context.compiler.eulerseq = sequence


def _inertia_from_geom(context: MjcfContext, node: XmlElement, text: str) -> None:
    flag = tinyxml_bool(text)
    if flag is not None:
        context.compiler.inertia_from_geom = InertiaFromGeom.TRUE if flag else InertiaFromGeom.FALSE
    elif text == "auto":
        context.compiler.inertia_from_geom = InertiaFromGeom.AUTO
    else:
        context.d.warning(
            node,
            f"The attribute 'inertiafromgeom' found in a '{node.tag}' tag cannot be "
            "interpreted as a boolean nor 'auto' and will be ignored.",
        )


def read_compiler(context: MjcfContext, node: XmlElement) -> None:
    """ParseCompiler: the settings of one ``<compiler>``, in Drake's order."""
    compiler, d = context.compiler, context.d
    autolimits = node.get("autolimits")
    parsed = tinyxml_bool(autolimits) if autolimits is not None else None
    compiler.autolimits = True if parsed is None else parsed
    coordinate = values.string(node, "coordinate")
    if coordinate is not None and coordinate != "local":
        raise d.error(node, f"Compiler attribute coordinate={coordinate} is not supported yet.")
    angle = values.string(node, "angle")
    if angle in ("degree", "radian"):
        compiler.degrees = angle == "degree"
    elif angle is not None:
        current = "degree" if compiler.degrees else "radian"
        d.warning(
            node,
            f"Unknown value {angle} for the compiler `angle` attribute will be ignored.  The "
            f"existing value of `angle={current}` will remain unchanged.",
        )
    for attribute in ("assetdir", "meshdir"):
        folder = values.string(node, attribute)
        if folder is not None:
            compiler.meshdir = folder
    sequence = values.string(node, "eulerseq") if _READS_EULERSEQ else None
    if sequence is not None:
        _eulerseq(context, node, sequence)
    inertia = node.get("inertiafromgeom")
    if inertia is not None:
        _inertia_from_geom(context, node, inertia)
    d.warn_unsupported_attributes(node, _COMPILER_UNSUPPORTED)
    d.warn_unsupported_elements(node, ("lengthrange",))


def read_option(context: MjcfContext, node: XmlElement) -> None:
    """ParseOption: ``gravity`` read (kept nowhere: reimpl's plant has no gravity field)."""
    values.vector(node, "gravity", 3)
    context.d.warn_unsupported_attributes(node, _OPTION_UNSUPPORTED)
    context.d.warn_unsupported_elements(node, ("flag",))
