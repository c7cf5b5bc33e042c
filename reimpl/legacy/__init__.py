"""The filter representations of Drake's RigidBodyTree era (removed in v0.23), and exact
mappings between them and today's pairwise filters.

Three ways to say which pairs of elements are filtered, F:

- **pairwise** (SceneGraph today): F is a set of pairs, declared with
  ExcludeBetween/ExcludeWithin; the candidates are C = (G × G) − … − F.
- **bitmask groups** (``CollisionFilterGroups``): a pair is filtered iff
  ``(m_a & i_b) | (m_b & i_a) ≠ 0``; constant cost, at most 127 user groups.
- **cliques** (``CollisionCliques``): a pair is filtered iff
  ``cliques(a) ∩ cliques(b) ≠ ∅``; unbounded ids, cost linear in the clique
  lists (seed 002's short-circuits aside).

RigidBodyTree used groups (from the unprefixed URDF tags, ``urdf``) and
cliques (``auto_cliques``: one body's elements; adjacent bodies through a
non-floating joint, the world *not* exempt) together with the anchored-pair
rule (``LegacyFilter``). ``mappings`` converts exactly between the three.
Names are PEP 8: this is not a pydrake surface.
"""

from __future__ import annotations

from reimpl.legacy._errors import (
    DuplicateGroupError,
    LegacyError,
    LegacyUrdfError,
    MappingInputError,
    TooManyGroupsError,
    UniversalGroupError,
    UnknownCliqueError,
    UnknownGroupError,
    UnknownLinkError,
)
from reimpl.legacy.auto_cliques import (
    BodyGraph,
    JointEdge,
    anchored_bodies,
    auto_cliques,
    body_graph,
)
from reimpl.legacy.collision_cliques import CollisionCliques, sorted_vectors_have_intersection
from reimpl.legacy.collision_filter_groups import (
    UNIVERSAL,
    CollisionFilterGroups,
    format_mask,
    mask_table,
)
from reimpl.legacy.legacy_filter import LegacyFilter
from reimpl.legacy.mappings import (
    clique_cover_lower_bound,
    group_lower_bound,
    groups_to_cliques,
    to_cliques,
    to_groups,
)
from reimpl.legacy.urdf import (
    LegacyModel,
    LegacyUrdf,
    legacy_model,
    load_legacy_urdf,
    read_legacy_urdf,
)

__all__ = [
    "UNIVERSAL",
    "BodyGraph",
    "CollisionCliques",
    "CollisionFilterGroups",
    "DuplicateGroupError",
    "JointEdge",
    "LegacyError",
    "LegacyFilter",
    "LegacyModel",
    "LegacyUrdf",
    "LegacyUrdfError",
    "MappingInputError",
    "TooManyGroupsError",
    "UniversalGroupError",
    "UnknownCliqueError",
    "UnknownGroupError",
    "UnknownLinkError",
    "anchored_bodies",
    "auto_cliques",
    "body_graph",
    "clique_cover_lower_bound",
    "format_mask",
    "group_lower_bound",
    "groups_to_cliques",
    "legacy_model",
    "load_legacy_urdf",
    "mask_table",
    "read_legacy_urdf",
    "sorted_vectors_have_intersection",
    "to_cliques",
    "to_groups",
]
