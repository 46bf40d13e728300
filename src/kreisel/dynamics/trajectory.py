"""The result of every simulation and exact solution: :class:`Trajectory`."""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array


class Trajectory:
    """Attitude and angular velocity of a rigid body sampled at times ``t``.

    Arrays carry batch axes first, then time: ``q`` is ``(batch..., n, 4)``
    (body -> space, scalar first), ``omega`` is ``(batch..., n, 3)`` in body
    components (seed 三.1, ω′).

    Parameters
    ----------
    t : (n,) array_like
        Sample times in seconds.
    q : (..., n, 4) array_like
        Unit quaternions, body -> space.
    omega : (..., n, 3) array_like
        Body-frame angular velocity ω′ in rad/s.
    inertia : (..., 3) or (..., 3, 3) array_like
        Inertia tensor in body axes (principal moments are expanded to a
        diagonal tensor), kg m².
    meta : dict, optional
        Free-form description (method, step, body, ...), kept on export.

    Examples
    --------
    >>> import numpy as np
    >>> tr = Trajectory([0.0, 1.0], [[1, 0, 0, 0]] * 2, [[0, 0, 1]] * 2, [1, 2, 3])
    >>> float(tr.energy[0])
    1.5
    """

    def __init__(self, t, q, omega, inertia, meta=None, **extra):
        self.t = as_float_array(t, "t")
        if self.t.ndim != 1:
            raise ValueError(f"t must be one-dimensional, got shape {self.t.shape}")
        self.q = as_float_array(q, "q", tail=(self.t.size, 4), finite=False)
        self.omega = as_float_array(omega, "omega", tail=(self.t.size, 3), finite=False)
        inertia = as_float_array(inertia, "inertia")
        if inertia.shape[-1:] == (3,) and (inertia.ndim == 1 or inertia.shape[-2:] != (3, 3)):
            inertia = inertia[..., :, None] * np.eye(3)
        if inertia.shape[-2:] != (3, 3):
            raise ValueError(f"inertia must have shape (..., 3) or (..., 3, 3), got {inertia.shape}")
        self.inertia = inertia
        self.meta = dict(meta or {})
        for key, value in extra.items():
            setattr(self, key, np.asarray(value))
        self._extra = tuple(extra)

    def __len__(self):
        return self.t.size

    def __repr__(self):
        batch = self.q.shape[:-2]
        b = f", batch={batch}" if batch else ""
        return f"Trajectory(n={self.t.size}, t=[{self.t[0]:g}, {self.t[-1]:g}]{b})"

    @property
    def batch_shape(self):
        """Leading batch shape (``()`` for a single body)."""
        return self.q.shape[:-2]

    def _inertia_t(self):
        # inertia broadcast against the time axis: (..., 1, 3, 3)
        return self.inertia[..., None, :, :]

    @property
    def angular_momentum_body(self):
        """J′ = I ω′ in body components (seed 四.4)."""
        return np.einsum("...ij,...j->...i", self._inertia_t(), self.omega)

    @property
    def energy(self):
        """Rotational kinetic energy T = ½ ω′·I ω′ (seed 五.2)."""
        return 0.5 * np.einsum("...i,...i->...", self.omega, self.angular_momentum_body)
