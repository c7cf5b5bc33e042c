"""Which mesh scales the parsers refuse, by release.

Up to Drake 1.39 the URDF and SDFormat parsers refuse a ``<mesh>`` whose three scale
factors are not all equal, at the ``<mesh>`` element, after resolving its file
(release fact mesh-nonuniform-scale-since-1.40: measured with a visual and a collision
mesh of scale '1 2 1' in each format on 1.12.0, 1.27.0, 1.30.0, 1.35.0-1.39.0, refused,
and 1.40.0, accepted).
"""

from __future__ import annotations

from collections.abc import Sequence

from reimpl._release import release

__all__ = ["ANISOTROPIC_MESH", "refuses_mesh_scale"]

#: The parsers' error for such a scale.
ANISOTROPIC_MESH = (
    "Drake meshes only support isotropic scaling. Therefore all three scaling factors must be "
    "exactly equal."
)


def refuses_mesh_scale(scale: Sequence[float]) -> bool:
    """Whether the release's parsers refuse a mesh of ``scale`` (x, y, z)."""
    return len(set(scale)) > 1 and not release.has("mesh-nonuniform-scale-since-1.40")
