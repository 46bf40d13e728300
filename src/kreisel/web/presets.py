"""Preset scenarios of the viewer: the bundled examples plus the seed's free and heavy symmetric tops."""

from __future__ import annotations

from ..io import example_path

# Scenarios the io layer does not ship; the cusp and loop tops start at the same tilt and spin and
# differ only in the initial precession rate phi-dot (0 gives cusps, against the spin gives loops).
_EXTRA = {
    "symmetric_top": '''title = "Free symmetric top"
description = "I1 = I2: omega and the symmetry axis precess uniformly about J on the body and space cones (seed 五.7)."

[body]
moments = [1.0, 1.0, 2.0]

[initial]
omega = [0.4, 0.0, 1.0]
frame = "body"

[integration]
t_end = 40.0
n_samples = 2001
method = "dop853"
''',
    "lagrange_cusps": '''title = "Lagrange top: cusps"
description = "Heavy symmetric top released from rest at 30 degrees with spin: the apex traces cusps (seed 六.5)."

[body]
moments = [1.0, 1.0, 0.5]

[initial]
omega = [0.0, 0.0, 6.0]
frame = "body"

[initial.attitude]
euler = [0.0, 30.0, 0.0]
seq = "ZXZ"
degrees = true

[[torque]]
kind = "gravity"
weight = 1.0
lever = [0.0, 0.0, 1.0]

[integration]
t_end = 30.0
n_samples = 3001
method = "dop853"
''',
    "lagrange_loops": '''title = "Lagrange top: loops"
description = "Heavy symmetric top started precessing against its natural sense: the apex traces loops (seed 六.5)."

[body]
moments = [1.0, 1.0, 0.5]

[initial]
omega = [0.0, -0.6, 6.0]
frame = "body"

[initial.attitude]
euler = [0.0, 30.0, 0.0]
seq = "ZXZ"
degrees = true

[[torque]]
kind = "gravity"
weight = 1.0
lever = [0.0, 0.0, 1.0]

[integration]
t_end = 30.0
n_samples = 3001
method = "dop853"
''',
}

PRESETS = ("tennis_racket", "symmetric_top", "lagrange_cusps", "lagrange_loops", "sleeping_top", "fast_top",
           "kovalevskaya", "foucault")


def preset_text(name):
    """TOML text of preset ``name`` (one of :data:`PRESETS`)."""
    if name not in PRESETS:
        raise ValueError(f"preset must be one of {', '.join(PRESETS)}, got {name!r}")
    if name in _EXTRA:
        return _EXTRA[name]
    return example_path(name).read_text(encoding="utf-8")
