"""Bundled scenario files (``kreisel examples``)."""
