"""so3 layer of kreisel."""

__all__ = []
