"""nav layer of kreisel."""

__all__ = []
