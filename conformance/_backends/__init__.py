"""Implementations under test: the loader, SceneGraphBackend, and the reimpl and pydrake APIs."""
