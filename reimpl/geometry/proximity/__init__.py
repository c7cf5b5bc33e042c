"""The proximity engine's narrowphase math, apart from FCL (Drake: geometry/proximity/).

Internal to ``reimpl.geometry.proximity_engine``, the one module that imports
python-fcl; these modules are pure Python and numpy, each one concept:

* ``transforms``: 3-vectors, rotations and X_WG as floats, X₁·X₂ as Drake rounds it;
* ``distance_to_point``: φ_G(Q), its nearest point and gradient (Drake's DistanceToPoint);
* ``mpr``: libccd's Minkowski Portal Refinement on FCL's support functions;
* ``distance_to_shape_touching``: nhat_BA_W when φ ≈ 0 (Drake's touching rules);
* ``narrowphase``: which of those (or FCL) answers a pair, in Drake's labelling;
* ``sphere_sphere``: the sphere–sphere closed forms for many pairs at once.
"""

__all__: list[str] = []
