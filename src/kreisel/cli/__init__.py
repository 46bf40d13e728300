"""The ``kreisel`` command line."""

from .app import app, run

__all__ = ["app", "run"]
