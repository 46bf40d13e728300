"""The sweep files shipped with kreisel (package data, see :func:`kreisel.sweep.example_path`)."""

__all__ = []
