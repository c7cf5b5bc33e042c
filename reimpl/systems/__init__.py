"""Systems-framework stand-ins needed by SceneGraph scripts (pydrake.systems)."""
