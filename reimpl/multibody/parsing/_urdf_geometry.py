"""URDF ``<visual>`` and ``<collision>``: shapes, names, roles (Drake 1.51.1, measured).

A ``<geometry>`` uses its first shape in this order, whatever the document
order: box, sphere, cylinder, capsule, drake:capsule, mesh, drake:ellipsoid
(none: ``Warning: geometry element does not have a recognizable shape type``,
an error at the ``<geometry>`` line). A mesh with a ``<drake:declare_convex/>``
child is a Convex, else a Mesh; its ``scale`` holds one number (uniform) or
three (see ``_urdf_values``). Missing measures give Drake's messages at the
shape's line (``Missing sphere attribute: radius``, ``Missing ellipsoid
attribute: 'a'``, ``Mesh element has no filename tag``).

Each element reads, in Drake's order (an error stops the parse):

=============  ===============================================================
 element        checks, in order
=============  ===============================================================
 visual         ``<geometry>`` present; ``<origin>``; the shape;
                ``drake:illustration_properties`` / ``drake:perception_properties``
                ``enabled`` is ``true`` or ``false``; both false: a warning and
                no geometry; ``<material>`` (``_urdf_materials``); every
                ``drake:accepting_renderer`` has a ``name``; the name
 collision      ``<verbose>`` warned; ``<geometry>`` present; ``<origin>``; a
                ``group`` attribute warned; the shape;
                ``drake:proximity_properties`` (``drake:soft_hydroelastic`` is
                an error, so are rigid and compliant together; each value
                child needs one number in ``value``; negative relaxation time
                and margin are errors, so are a negative dissipation, a
                stiffness <= 0 and CoulombFriction's own checks); without a
                friction there, ``<drake_compliance>``'s; the name
=============  ===============================================================

The name is the ``name`` attribute (even ``""``), else the shape's type name
(``Box``, ``Convex``, ...); within one link and role a taken name gets the
first free ``_1``, ``_2``, ... (a warning when it was given), up to ``_9999``.
A visual gets the illustration and perception roles unless disabled, a
collision the proximity role.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from reimpl._release import release
from reimpl.geometry import (
    Box,
    Capsule,
    Convex,
    Cylinder,
    Ellipsoid,
    GeometryInstance,
    IllustrationProperties,
    Mesh,
    PerceptionProperties,
    ProximityProperties,
    Shape,
    Sphere,
)
from reimpl.geometry._drake_text import shortest
from reimpl.math import RigidTransform
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._mesh_scale import ANISOTROPIC_MESH, refuses_mesh_scale
from reimpl.multibody.parsing._urdf_materials import MaterialMap
from reimpl.multibody.parsing._urdf_values import Values, origin, scan_double, vector
from reimpl.multibody.parsing._xml import XmlElement, children
from reimpl.multibody.plant import CoulombFriction

__all__ = ["GeometryReader", "ParsedGeometry"]

#: Drake's kDefaultNumericSuffixLimit: names are salted with _1 .. _9999.
_SUFFIX_LIMIT = 10000
#: Since 1.15 a taken name, given or default, gets ``_<i>``; up to 1.14 only a default
#: (shape) name gets a suffix, ``<i>`` with no underscore, and a given name is used as
#: it is, and a link's visuals and collisions share one set of names (so a collision
#: box after a visual box is ``Box1``) (default-geometry-name-underscore-since-1.15:
#: measured on pydrake 1.12.0 and 1.14.0,
#: ``Sphere``, ``Sphere1``, and 1.15.0, ``Sphere``, ``Sphere_1``; Drake PR #19029).
_RENAMING = release.has("default-geometry-name-underscore-since-1.15")
_PROXIMITY = "drake:proximity_properties"


@dataclass(frozen=True)
class ParsedGeometry:
    """A geometry to register: the instance (with its roles' properties) and its role."""

    role: str  # "visual" | "collision"
    instance: GeometryInstance
    properties: ProximityProperties | None = None


@dataclass
class _Names:
    """The names taken on one link, in one role."""

    taken: set[str] = field(default_factory=set)


class GeometryReader:
    """Reads a link's visuals and collisions."""

    def __init__(
        self,
        diagnostics: Diagnostics,
        resolve: Callable[[str, int], str],
        materials: MaterialMap,
    ) -> None:
        self.diagnostics = diagnostics
        self.values = Values(diagnostics)
        self.resolve = resolve
        self.materials = materials

    # ------------------------------------------------------------- elements
    def visual(self, element: XmlElement, link: str, names: set[str]) -> ParsedGeometry | None:
        """One ``<visual>``; None when both its visual roles are disabled."""
        d = self.diagnostics
        geometry = _first(element, "geometry")
        if geometry is None:
            raise d.error(f"Link {link} has a visual element without geometry.", element.line)
        X_BG = _origin(element)
        shape = self._shape(geometry)
        illustration = self._enabled(element, "drake:illustration_properties")
        perception = self._enabled(element, "drake:perception_properties")
        if not illustration and not perception:
            d.warning(
                f"Visual geometry in link '{link}' has both illustration and perception "
                "properties disabled. This geometry will be ignored by Drake.",
                element.line,
            )
            return None
        material = _first(element, "material")
        if material is not None:
            rgba = self.materials.read(material, name_required=False).rgba
            if rgba is not None and not all(0 <= v <= 1 for v in rgba):
                values = ", ".join(f"{c}={shortest(v)}" for c, v in zip("rgba", rgba, strict=True))
                raise RuntimeError(
                    f"Rgba values must be within the range [0, 1]. Values provided: ({values})"
                )
        for accepting in children(element, "drake:accepting_renderer"):
            if accepting.get("name") is None:
                raise d.error(
                    "<drake:accepting_renderer> tag given without any name", accepting.line
                )
        name = self._name("visual", element, shape, names)
        instance = GeometryInstance(X_PG=X_BG, shape=shape, name=name)
        if illustration:
            instance.set_illustration_properties(IllustrationProperties())
        if perception:
            instance.set_perception_properties(PerceptionProperties())
        return ParsedGeometry("visual", instance)

    def collision(self, element: XmlElement, link: str, names: set[str]) -> ParsedGeometry:
        """One ``<collision>``."""
        d = self.diagnostics
        _warn_unsupported_child(d, element, "verbose")
        geometry = _first(element, "geometry")
        if geometry is None:
            raise d.error(f"Link '{link}' has a collision element without geometry", element.line)
        X_BG = _origin(element)
        if element.get("group") is not None:
            d.warning(
                "A link has specified the 'group' attribute on the <collision> tag. Drake "
                "doesn't make use of that attribute and all instances will be ignored.",
                element.line,
            )
        shape = self._shape(geometry)
        properties = self._proximity(element, link)
        name = self._name("collision", element, shape, names)
        instance = GeometryInstance(X_PG=X_BG, shape=shape, name=name)
        return ParsedGeometry("collision", instance, properties)

    # --------------------------------------------------------------- shapes
    def _shape(self, geometry: XmlElement) -> Shape:
        for tag, make in _SHAPES:
            shape_element = _first(geometry, tag)
            if shape_element is not None:
                return make(self, shape_element)
        raise self.diagnostics.error(
            "Warning: geometry element does not have a recognizable shape type", geometry.line
        )

    def _measure(self, element: XmlElement, attribute: str, shown: str) -> float:
        value = self.values.scalar(element, attribute)
        if value is None:
            kind = element.tag.removeprefix("drake:")
            raise self.diagnostics.error(f"Missing {kind} attribute: {shown}", element.line)
        return value

    def _box(self, element: XmlElement) -> Shape:
        size = vector(element, "size", 3)
        if size is None:
            raise self.diagnostics.error("Missing box attribute: size", element.line)
        return Box(*size)

    def _sphere(self, element: XmlElement) -> Shape:
        return Sphere(self._measure(element, "radius", "radius"))

    def _cylinder(self, element: XmlElement) -> Shape:
        radius = self._measure(element, "radius", "radius")
        return Cylinder(radius, self._measure(element, "length", "length"))

    def _capsule(self, element: XmlElement) -> Shape:
        radius = self._measure(element, "radius", "radius")
        return Capsule(radius, self._measure(element, "length", "length"))

    def _ellipsoid(self, element: XmlElement) -> Shape:
        a, b, c = (self._measure(element, axis, f"'{axis}'") for axis in "abc")
        return Ellipsoid(a, b, c)

    def _mesh(self, element: XmlElement) -> Shape:
        filename = element.get("filename")
        if filename is None:
            raise self.diagnostics.error("Mesh element has no filename tag", element.line)
        path = self.resolve(filename, element.line)
        scale = self.values.three_vector(element, "scale") or [1.0, 1.0, 1.0]
        if refuses_mesh_scale(scale):
            raise self.diagnostics.error(ANISOTROPIC_MESH, element.line)
        kind = Convex if _first(element, "drake:declare_convex") is not None else Mesh
        return kind(filename=path, scale3=scale)

    # ---------------------------------------------------------------- roles
    def _enabled(self, element: XmlElement, tag: str) -> bool:
        """Whether the role of ``tag`` is on: ``enabled`` absent, or exactly true/false."""
        node = _first(element, tag)
        value = None if node is None else node.get("enabled")
        if node is None or value is None or value == "true":
            return True
        if value == "false":
            return False
        raise self.diagnostics.error(
            f"Invalid value '{value}' for {tag} enabled attribute. Expected 'true' or 'false'.",
            node.line,
        )

    def _proximity(self, element: XmlElement, link: str) -> ProximityProperties:
        properties = ProximityProperties()
        node = _first(element, _PROXIMITY)
        if node is not None:
            _ProximityReader(self.diagnostics, self.values, node).read(properties)
        if properties.HasProperty("material", "coulomb_friction"):
            if _first(element, "drake_compliance") is not None:
                self.diagnostics.warning(
                    "A link has specified collision properties using both "
                    "<drake:proximity_properties> and <drake_compliance> tags. The "
                    "<drake_compliance> tag is ignored in this case and is generally "
                    "dispreferred. Consider removing all instances of <drake_compliance> in "
                    "favor of <drake:proximity_properties>.",
                    element.line,
                )
        else:
            friction = _compliance_friction(self.diagnostics, element, link)
            properties.AddProperty("material", "coulomb_friction", friction)
        return properties

    def _name(self, role: str, element: XmlElement, shape: Shape, names: set[str]) -> str:
        """Drake's ParseGeometryName: the given name or the shape's, salted to be unique."""
        given = element.get("name")
        base = given if given is not None else type(shape).__name__
        name = base
        suffix = 0
        if not _RENAMING:
            return self._name_up_to_1_14(element, base, given is not None, names)
        while name in names:
            suffix += 1
            if suffix >= _SUFFIX_LIMIT:
                raise self.diagnostics.error(
                    f"Too many geometries with identical name '{base}'", element.line
                )
            name = f"{base}_{suffix}"
        if name != base and given is not None:
            self.diagnostics.warning(
                f"{role} name '{base}' has already been used, renaming to '{name}' instead",
                element.line,
            )
        names.add(name)
        return name

    def _name_up_to_1_14(self, element: XmlElement, base: str, given: bool, names: set[str]) -> str:
        """Drake 1.14's MakeDefaultGeometryName: a given name as it is, else the shape's
        name, then ``<shape><i>`` for the first free i."""
        name = base
        suffix = 0
        while not given and name in names:
            suffix += 1
            if suffix >= _SUFFIX_LIMIT:
                raise self.diagnostics.error(
                    "Too many identical geometries with default names.", element.line
                )
            name = f"{base}{suffix}"
        names.add(name)
        return name


#: Shape tags in the order Drake looks for them.
_SHAPES: tuple[tuple[str, Callable[[GeometryReader, XmlElement], Shape]], ...] = (
    ("box", GeometryReader._box),
    ("sphere", GeometryReader._sphere),
    ("cylinder", GeometryReader._cylinder),
    ("capsule", GeometryReader._capsule),
    ("drake:capsule", GeometryReader._capsule),
    ("mesh", GeometryReader._mesh),
    ("drake:ellipsoid", GeometryReader._ellipsoid),
)


class _ProximityReader:
    """``<drake:proximity_properties>``: Drake's ParseProximityProperties and its checks."""

    def __init__(self, diagnostics: Diagnostics, values: Values, node: XmlElement) -> None:
        self.diagnostics, self.values, self.node = diagnostics, values, node

    def value(self, tag: str) -> float | None:
        child = _first(self.node, tag)
        if child is None:
            return None
        value = self.values.scalar(child, "value")
        if value is None:
            raise self.diagnostics.error(
                f"Unable to read the 'value' attribute for the <{tag}> tag", child.line
            )
        return value

    def read(self, properties: ProximityProperties) -> None:
        d, node = self.diagnostics, self.node
        soft = _first(node, "drake:soft_hydroelastic")
        if soft is not None:
            raise d.error(
                "Collision geometry uses the tag <drake:soft_hydroelastic>, which is no longer "
                "supported. Please change it to <drake:compliant_hydroelastic>.",
                soft.line,
            )
        rigid = _first(node, "drake:rigid_hydroelastic")
        compliant = _first(node, "drake:compliant_hydroelastic")
        if rigid is not None and compliant is not None:
            raise d.error(
                "Collision geometry has defined mutually-exclusive tags "
                "<drake:rigid_hydroelastic> and <drake:compliant_hydroelastic> on lines "
                f"{rigid.line} and {compliant.line}, respectively. Only one can be provided.",
                node.line,
            )
        hint = self.value("drake:mesh_resolution_hint")
        if hint is not None:
            properties.AddProperty("hydroelastic", "resolution_hint", hint)
        modulus = self.value("drake:hydroelastic_modulus")
        if modulus is not None and rigid is not None:
            d.warning(
                "Rigid geometries defined with the tag drake:rigid_hydroelastic should not "
                "contain the tag drake:hydroelastic_modulus. The specified value "
                f"({shortest(modulus)}) will be ignored.",
                node.line,
            )
        elif modulus is not None:
            properties.AddProperty("hydroelastic", "hydroelastic_modulus", modulus)
        self._contact_material(properties)
        relaxation = self.value("drake:relaxation_time")
        if relaxation is not None and relaxation < 0:
            raise d.error(
                f"The relaxation time can't be negative; given {shortest(relaxation)}", node.line
            )
        if relaxation is not None:
            properties.AddProperty("material", "relaxation_time", relaxation)
        margin = self.value("drake:hydroelastic_margin")
        if margin is not None and margin < 0:
            raise d.error(
                f"The hydroelastic margin can't be negative; given {shortest(margin)}", node.line
            )
        if margin is not None:
            properties.AddProperty("hydroelastic", "margin", margin)

    def _contact_material(self, properties: ProximityProperties) -> None:
        """Drake's AddContactMaterial, after reading all four values."""
        dissipation = self.value("drake:hunt_crossley_dissipation")
        stiffness = self.value("drake:point_contact_stiffness")
        mu_dynamic = self.value("drake:mu_dynamic")
        mu_static = self.value("drake:mu_static")
        friction = None
        if mu_static is not None:  # N.B. One coefficient alone is both.
            friction = _friction(mu_static, mu_dynamic if mu_dynamic is not None else mu_static)
        elif mu_dynamic is not None:
            friction = _friction(mu_dynamic, mu_dynamic)
        if dissipation is not None:
            if dissipation < 0:
                raise RuntimeError(
                    f"The dissipation can't be negative; given {shortest(dissipation)}"
                )
            properties.AddProperty("material", "hunt_crossley_dissipation", dissipation)
        if stiffness is not None:
            if stiffness <= 0:
                raise RuntimeError(
                    "The point_contact_stiffness must be strictly positive; given "
                    f"{shortest(stiffness)}"
                )
            properties.AddProperty("material", "point_contact_stiffness", stiffness)
        if friction is not None:
            properties.AddProperty("material", "coulomb_friction", friction)


def _friction(static: float, dynamic: float) -> CoulombFriction:
    """CoulombFriction with Drake's checks of sign (dynamic first), then of order."""
    for kind, value in (("dynamic", dynamic), ("static", static)):
        if value < 0:
            raise RuntimeError(f"The given {kind} friction is negative: {shortest(value)}")
    return CoulombFriction(static_friction=static, dynamic_friction=dynamic)


def _compliance_friction(d: Diagnostics, element: XmlElement, link: str) -> CoulombFriction:
    """The legacy ``<drake_compliance>`` friction (Drake's default 1, 1 without it)."""
    compliance = _first(element, "drake_compliance")
    if compliance is None:
        return CoulombFriction(static_friction=1.0, dynamic_friction=1.0)
    for tag in ("youngs_modulus", "dissipation"):
        if _first(compliance, tag) is not None:
            d.warning(
                f"A link has specified the <{tag}> tag under the <drake_compliance> tag. Drake "
                "no longer makes use of that tag and all instances will be ignored.",
                compliance.line,
            )
    found: dict[str, float] = {}
    for kind in ("static", "dynamic"):
        node = _first(compliance, f"{kind}_friction")
        if node is not None:
            number = None if node.text is None else scan_double(node.text)
            if number is None:
                raise d.error(f"Unable to parse {kind}_friction for link {link}", node.line)
            found[kind] = number
    if len(found) == 1:
        raise d.error(
            f"Link '{link}': When specifying coefficient of friction, both static and dynamic "
            "coefficients must be defined",
            compliance.line,
        )
    if not found:
        return CoulombFriction(static_friction=1.0, dynamic_friction=1.0)
    return _friction(found["static"], found["dynamic"])


def _first(element: XmlElement, tag: str) -> XmlElement | None:
    found = children(element, tag)
    return found[0] if found else None


def _origin(element: XmlElement) -> RigidTransform:
    node = _first(element, "origin")
    return origin(node) if node is not None else RigidTransform()


def _warn_unsupported_child(d: Diagnostics, element: XmlElement, tag: str) -> None:
    node = _first(element, tag)
    if node is not None:
        d.warning(
            f"The tag '{tag}' found as a child of '{element.tag}' is currently unsupported "
            "and will be ignored.",
            node.line,
        )
