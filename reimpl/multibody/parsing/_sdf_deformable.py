"""SDFormat deformable links (``<drake:deformable_properties>``): Drake's checks, then refusal.

Deformable bodies are outside reimpl's subset, but which error a file gives
is not. Drake 1.51.1 (AddDeformableLinkFromSpecification) checks, in order:
the link's children; the properties (``drake:youngs_modulus`` > 0,
``drake:poissons_ratio`` in (−1, 0.5), ``drake:mass_damping`` ≥ 0,
``drake:stiffness_damping`` ≥ 0, ``drake:mass_density`` > 0, a known
``drake:material_model``); each ``<drake:wall_boundary_condition>``; exactly one
``<collision>``, a mesh, whose URI must resolve; its proximity properties; at
most one ``<visual>``. Only then does it register the body, which a continuous
plant refuses with ``Calls to RegisterDeformableBody() with a DeformableModel
belonging to a continuous MultibodyPlant are not allowed.`` On a discrete plant
reimpl raises ModelParseError ``reimpl does not support deformable bodies
(<link name='...'> with <drake:deformable_properties>)``. Without a SceneGraph
the link is skipped with Drake's warning.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from reimpl.multibody.parsing._diagnostics import ModelParseError
from reimpl.multibody.parsing._sdf_geometry import geometry_shape
from reimpl.multibody.parsing._sdf_scope import Reporter
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["refuse_deformable"]

_LINK = frozenset(
    {"pose", "collision", "visual", "drake:deformable_properties", "drake:wall_boundary_condition"}
)
_PROPERTIES = frozenset({
    "drake:youngs_modulus", "drake:poissons_ratio", "drake:mass_damping",
    "drake:stiffness_damping", "drake:mass_density", "drake:material_model",
})  # fmt: skip
_MATERIAL_MODELS = frozenset({"linear_corotated", "corotated", "neohookean", "linear"})
#: property -> (holds for a good value, Drake's message)
_CHECKS: dict[str, tuple[Callable[[float], bool], str]] = {
    "drake:youngs_modulus": (lambda v: v > 0, "Young's modulus must be positive."),
    "drake:poissons_ratio": (
        lambda v: -1 < v < 0.5,
        "Poisson's ratio must be in the range (-1, 0.5).",
    ),
    "drake:mass_damping": (lambda v: v >= 0, "Mass damping must be non-negative."),
    "drake:stiffness_damping": (lambda v: v >= 0, "Stiffness damping must be non-negative."),
    "drake:mass_density": (lambda v: v > 0, "Mass density must be positive."),
}
#: collision <drake:proximity_properties> -> its message when negative (Drake's "non‑negative"
#: holds a non-breaking hyphen, U+2011)
_DEFORMABLE_PROXIMITY = {
    "drake:mu_dynamic": "drake:mu_dynamic must be non\u2011negative",
    "drake:hunt_crossley_dissipation": "drake:hunt_crossley_dissipation must be non\u2011negative",
    "drake:relaxation_time": "drake:relaxation_time must be non\u2011negative",
}


def _number(element: XmlElement, tag: str) -> float | None:
    found = children(element, tag)
    return float((found[0].text or "").split()[0]) if found else None


def refuse_deformable(
    link: XmlElement,
    reporter: Reporter,
    resolve: Callable[[str], str],
    *,
    has_scene_graph: bool,
    plant: Any,
) -> None:
    """Drake's checks of a deformable link, then its refusal (see the module docstring)."""
    if not has_scene_graph:
        reporter.warn(
            link,
            "Cannot add a deformable link to a plant without a registered geometry source. "
            "The deformable link is ignored.",
        )
        return
    reporter.check_supported(link, _LINK)
    properties = children(link, "drake:deformable_properties")[0]
    _check_properties(properties, reporter)
    for condition in children(link, "drake:wall_boundary_condition"):
        for tag in ("drake:point_on_plane", "drake:outward_normal"):
            if not children(condition, tag):
                raise reporter.error(
                    condition, f"<{condition.tag}>: Unable to find the <{tag}> child tag."
                )
    collisions = children(link, "collision")
    if len(collisions) != 1:
        raise reporter.error(
            link, "Each deformable <link> must have exactly one <collision> element."
        )
    for geometry in children(collisions[0], "geometry")[:1]:
        reporter.check_supported(geometry, frozenset({"mesh"}))
        geometry_shape(geometry, reporter.check_supported, reporter.error, resolve)
    _check_proximity(collisions[0], reporter)
    if len(children(link, "visual")) > 1:
        raise reporter.error(link, "A deformable <link> may have at most one <visual> element.")
    if plant.time_step() == 0.0:
        raise RuntimeError(
            "Calls to RegisterDeformableBody() with a DeformableModel belonging to a continuous "
            "MultibodyPlant are not allowed."
        )
    raise ModelParseError(
        f"reimpl does not support deformable bodies (<link name='{link.get('name', '')}'> with "
        "<drake:deformable_properties>)"
    )


def _check_properties(properties: XmlElement, reporter: Reporter) -> None:
    """LoadDeformableConfig's checks."""
    reporter.check_supported(properties, _PROPERTIES)
    for tag, (good, message) in _CHECKS.items():
        value = _number(properties, tag)
        if value is not None and not good(value):
            raise reporter.error(properties, message)
    for model in children(properties, "drake:material_model")[:1]:
        name = (model.text or "").strip()
        if name not in _MATERIAL_MODELS:
            raise reporter.error(
                properties,
                f"Invalid <drake:material_model> value {name}. Must be 'linear', "
                "'linear_corotated', `neohookean`, or 'corotated'.",
            )


def _check_proximity(collision: XmlElement, reporter: Reporter) -> None:
    """MakeProximityForDeformableCollision's checks."""
    reporter.check_supported(collision, frozenset({"geometry", "drake:proximity_properties"}))
    for drake in children(collision, "drake:proximity_properties")[:1]:
        reporter.check_supported(drake, frozenset(_DEFORMABLE_PROXIMITY))
        for tag, message in _DEFORMABLE_PROXIMITY.items():
            value = _number(drake, tag)
            if value is not None and value < 0:
                raise reporter.error(drake, message)
