"""Bundled scenario files (``kreisel examples``)."""

__all__ = []
