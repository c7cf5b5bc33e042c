"""The parts of ``pydrake.multibody`` that collision filtering depends on.

``reimpl.multibody.tree`` holds the elements of a model (model instances,
rigid bodies, frames, joints) and ``reimpl.multibody.plant`` the
MultibodyPlant that owns them, registers their geometry with a SceneGraph
and, at Finalize, declares Drake's automatic collision filters.

reimpl does no dynamics: masses, axes and poses are stored as given and only
topology and names are read. A body's geometry lives on the body's
SceneGraph frame, so every statement about bodies is a statement about
frames: F(B) below is the SceneGraph frame of body B, and F(world) is the
world frame, whose geometries are all the anchored ones.
"""

__all__: list[str] = []
