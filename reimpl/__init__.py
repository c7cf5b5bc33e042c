"""reimpl: a readable, executable statement of Drake's SceneGraph collision filtering.

It is written for clarity, not speed: each module is one of Drake's nouns and
each docstring quotes the set formula it implements. Its subpackages mirror
pydrake's module paths (``reimpl.geometry``, ``reimpl.math``,
``reimpl.systems.framework``), so a pydrake script runs on it with its imports
switched.

Conventions used throughout:

- ``G`` the proximity geometries, ``A`` the anchored ones, ``D`` the dynamic ones;
- ``C`` the candidate pairs: C = (Gₚ × Gₚ) − (Aₚ × Aₚ) − Fₚ − Iₚ − U, where
  ``Fₚ`` are same-frame pairs, ``Iₚ`` self pairs and ``U`` user-filtered pairs;
- ``a, b`` are geometry ids; ``set_A, set_B`` GeometrySets; ``P`` the pairs a
  statement speaks about.
"""

__all__: list[str] = []
