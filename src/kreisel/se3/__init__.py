"""se3 layer of kreisel."""

__all__ = []
