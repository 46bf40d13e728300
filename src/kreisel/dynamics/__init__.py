"""dynamics layer of kreisel."""

__all__ = []
