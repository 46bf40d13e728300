"""tops layer of kreisel."""

__all__ = []
