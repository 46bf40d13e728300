"""Preset scenarios of the viewer: bundled scenario files of :mod:`kreisel.io`, in the order the menu shows."""

from __future__ import annotations

from ..io import example_path

__all__ = ["preset_text", "PRESETS"]

PRESETS = ("tennis_racket", "symmetric_top", "lagrange_cusps", "lagrange_loops", "sleeping_top", "fast_top",
           "kovalevskaya", "foucault")


def preset_text(name):
    """TOML text of preset ``name`` (one of :data:`PRESETS`)."""
    if name not in PRESETS:
        raise ValueError(f"preset must be one of {', '.join(PRESETS)}, got {name!r}")
    return example_path(name).read_text(encoding="utf-8")
