"""An SDFormat ``<collision>``'s proximity properties, and Drake's checks of them (1.51.1).

``<drake:proximity_properties>`` may hold ``drake:rigid_hydroelastic`` or
``drake:compliant_hydroelastic`` (not both; ``drake:soft_hydroelastic`` is
refused), and numbers: ``drake:mesh_resolution_hint``,
``drake:hydroelastic_modulus`` (ignored, with a warning, on a rigid
geometry), ``drake:hunt_crossley_dissipation`` (≥ 0),
``drake:point_contact_stiffness`` (> 0), ``drake:mu_dynamic`` and
``drake:mu_static``, ``drake:relaxation_time`` (≥ 0),
``drake:hydroelastic_margin`` (≥ 0). Without a friction there, the legacy
``<surface><friction><ode><mu>``/``<mu2>`` give it (1 by default); a
friction is μ_static ≥ μ_dynamic ≥ 0.

reimpl keeps the role and the friction (``material``/``coulomb_friction``);
the other values are checked, not stored (contact is outside its subset).
"""

from __future__ import annotations

from collections.abc import Callable

from reimpl.geometry import ProximityProperties
from reimpl.multibody.parsing._xml import XmlElement, children
from reimpl.multibody.plant import CoulombFriction

__all__ = ["collision_properties"]

_COLLISION_ELEMENTS = frozenset(
    {"drake:proximity_properties", "geometry", "laser_retro", "pose", "surface"}
)
_PROXIMITY_ELEMENTS = frozenset({
    "drake:rigid_hydroelastic", "drake:compliant_hydroelastic", "drake:soft_hydroelastic",
    "drake:mesh_resolution_hint", "drake:hydroelastic_modulus", "drake:hydroelastic_margin",
    "drake:hunt_crossley_dissipation", "drake:relaxation_time", "drake:point_contact_stiffness",
    "drake:mu_dynamic", "drake:mu_static",
})  # fmt: skip


def _fmt(value: float) -> str:
    """fmt's ``{}`` of a double: the shortest repr (``0.1``, ``500000000``)."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _friction(static: float, dynamic: float) -> CoulombFriction:
    """CoulombFriction's checks (Drake's messages), then the friction."""
    if dynamic < 0:
        raise RuntimeError(f"The given dynamic friction is negative: {_fmt(dynamic)}")
    if static < 0:
        raise RuntimeError(f"The given static friction is negative: {_fmt(static)}")
    if dynamic > static:
        raise RuntimeError(
            f"The given dynamic friction ({_fmt(dynamic)}) is greater than the given static "
            f"friction ({_fmt(static)}); dynamic friction must be less than or equal to static "
            "friction."
        )
    return CoulombFriction(static_friction=static, dynamic_friction=dynamic)


def _number(element: XmlElement, tag: str) -> float | None:
    found = children(element, tag)
    return float((found[0].text or "").split()[0]) if found else None


def collision_properties(
    collision: XmlElement,
    check: Callable[[XmlElement, frozenset[str]], None],
    error: Callable[[XmlElement, str], Exception],
    warn: Callable[[XmlElement, str], None],
) -> ProximityProperties:
    """MakeProximityPropertiesForCollision: the checks, then the proximity properties."""
    check(collision, _COLLISION_ELEMENTS)
    properties = ProximityProperties()
    friction: CoulombFriction | None = None
    for drake in children(collision, "drake:proximity_properties")[:1]:
        check(drake, _PROXIMITY_ELEMENTS)
        if children(drake, "drake:soft_hydroelastic"):
            raise error(
                collision,
                "A <collision> geometry has defined the unsupported tag "
                "<drake:soft_hydroelastic>. Please change it to <drake:compliant_hydroelastic>.",
            )
        rigid = bool(children(drake, "drake:rigid_hydroelastic"))
        if rigid and children(drake, "drake:compliant_hydroelastic"):
            raise error(
                collision,
                "A <collision> geometry has defined mutually-exclusive tags "
                "<drake:rigid_hydroelastic> and <drake:compliant_hydroelastic>. Only one can be "
                "provided.",
            )
        friction = _drake_properties(drake, rigid, error, warn)
    if friction is None:
        friction = _ode_friction(collision)
    else:
        _check_legacy_friction(collision, check, warn)
    properties.AddProperty("material", "coulomb_friction", friction)
    return properties


def _drake_properties(
    drake: XmlElement,
    rigid: bool,
    error: Callable[[XmlElement, str], Exception],
    warn: Callable[[XmlElement, str], None],
) -> CoulombFriction | None:
    """ParseProximityProperties' checks; the friction it gives, if any."""
    modulus = _number(drake, "drake:hydroelastic_modulus")
    if modulus is not None and rigid:
        warn(
            drake,
            "Rigid geometries defined with the tag drake:rigid_hydroelastic should not contain "
            f"the tag drake:hydroelastic_modulus. The specified value ({_fmt(modulus)}) will be "
            "ignored.",
        )
    dissipation = _number(drake, "drake:hunt_crossley_dissipation")
    stiffness = _number(drake, "drake:point_contact_stiffness")
    mu_dynamic = _number(drake, "drake:mu_dynamic")
    mu_static = _number(drake, "drake:mu_static")
    friction = None
    if mu_dynamic is not None:
        friction = _friction(mu_static if mu_static is not None else mu_dynamic, mu_dynamic)
    elif mu_static is not None:
        friction = _friction(mu_static, mu_static)
    if dissipation is not None and dissipation < 0:
        raise RuntimeError(f"The dissipation can't be negative; given {_fmt(dissipation)}")
    if stiffness is not None and stiffness <= 0:
        raise RuntimeError(
            f"The point_contact_stiffness must be strictly positive; given {_fmt(stiffness)}"
        )
    relaxation = _number(drake, "drake:relaxation_time")
    if relaxation is not None and relaxation < 0:
        raise error(drake, f"The relaxation time can't be negative; given {_fmt(relaxation)}")
    margin = _number(drake, "drake:hydroelastic_margin")
    if margin is not None and margin < 0:
        raise error(drake, f"The hydroelastic margin can't be negative; given {_fmt(margin)}")
    return friction


def _ode_friction(collision: XmlElement) -> CoulombFriction:
    """MakeCoulombFrictionFromSdfCollisionOde: ``<mu>`` and ``<mu2>`` (1 by default)."""
    ode = [
        o
        for surface in children(collision, "surface")[:1]
        for friction in children(surface, "friction")[:1]
        for o in children(friction, "ode")[:1]
    ]
    if not ode:
        return _friction(1.0, 1.0)
    mu = _number(ode[0], "mu")
    mu2 = _number(ode[0], "mu2")
    return _friction(1.0 if mu is None else mu, 1.0 if mu2 is None else mu2)


def _check_legacy_friction(
    collision: XmlElement,
    check: Callable[[XmlElement, frozenset[str]], None],
    warn: Callable[[XmlElement, str], None],
) -> None:
    """With drake's friction, ``<surface><friction><ode><mu*>`` is ignored, with a warning."""
    for surface in children(collision, "surface")[:1]:
        check(surface, frozenset({"friction"}))
        for friction in children(surface, "friction")[:1]:
            check(friction, frozenset({"ode"}))
            for ode in children(friction, "ode")[:1]:
                check(ode, frozenset({"mu", "mu2"}))
                if children(ode, "mu") or children(ode, "mu2"):
                    warn(
                        ode,
                        f"In <collision name='{collision.get('name', '')}'>: When drake contact "
                        "parameters are fully specified in the <drake:proximity_properties> tag, "
                        "the <surface><friction><ode><mu*> tags are ignored.",
                    )
