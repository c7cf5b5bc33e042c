"""Drake's common utilities that the collision-filtering subset touches (pydrake.common)."""

__all__: list[str] = []
