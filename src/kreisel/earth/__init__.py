"""earth layer of kreisel."""

__all__ = []
