"""frames layer of kreisel."""

__all__ = []
