"""The result of every simulation and exact solution: :class:`Trajectory`."""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _display
from .._html import html_table, number
from .._optional import require
from .._validation import as_float, as_float_array, check_frame, sample_times
from ..so3 import quat_apply
from ..so3.rotation import Rotation
from . import _trajectory_files

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr

__all__ = ["Trajectory"]

_VECTOR = ("x", "y", "z")
_QUAT = ("w", "x", "y", "z")


class Trajectory:
    """Attitude and angular velocity of a rigid body sampled at times ``t``.

    Arrays carry batch axes first, then time: ``q`` is ``(batch..., n, 4)``
    (body -> space, scalar first), ``omega`` is ``(batch..., n, 3)`` in body
    components (Theory §3.1, ω′).

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
    **extra : array_like
        Further arrays sampled at ``t`` (e.g. ``position`` and ``velocity``
        of a six-degree-of-freedom body), stored as attributes and exported.

    Examples
    --------
    >>> import numpy as np
    >>> tr = Trajectory([0.0, 1.0], [[1, 0, 0, 0]] * 2, [[0, 0, 1]] * 2, [1, 2, 3])
    >>> float(tr.energy[0])
    1.5
    """

    def __init__(self, t: ArrayLike, q: ArrayLike, omega: ArrayLike, inertia: ArrayLike,
                 meta: dict[str, Any] | None = None, **extra: ArrayLike) -> None:
        self.t = sample_times(t)
        self.q = as_float_array(q, "q", tail=(self.t.size, 4), finite=False)
        self.omega = as_float_array(omega, "omega", tail=(self.t.size, 3), finite=False)
        tensor = as_float_array(inertia, "inertia")
        if tensor.shape[-1:] == (3,) and (tensor.ndim == 1 or tensor.shape[-2:] != (3, 3)):
            tensor = tensor[..., :, None] * np.eye(3)
        if tensor.shape[-2:] != (3, 3):
            raise ValueError(f"inertia must have shape (..., 3) or (..., 3, 3), got {tensor.shape}")
        self.inertia = tensor
        self.meta = dict(meta or {})
        for key, value in extra.items():
            if hasattr(type(self), key) or key in vars(self):
                raise ValueError(f"extra array {key!r} would hide Trajectory.{key}; give it another name")
            setattr(self, key, np.asarray(value))
        self._extra = tuple(extra)

    def __len__(self) -> int:
        return self.t.size

    def __getitem__(self, index: Any) -> Trajectory:
        """The samples ``index`` picks along time (a slice, integer array or boolean mask) as a Trajectory.

        Batch axes are kept; ``meta`` and the extra arrays come along. A single integer is refused: a
        sample is not a trajectory (``traj[k:k + 1]`` is one, ``traj.q[..., k, :]`` its attitude).

        Examples
        --------
        >>> tr = Trajectory(np.arange(5.0), [[1, 0, 0, 0]] * 5, [[0, 0, 1]] * 5, [1, 2, 3])
        >>> tr[1:4].t.tolist(), tr[::2].t.tolist(), tr[tr.t > 2.5].t.tolist()
        ([1.0, 2.0, 3.0], [0.0, 2.0, 4.0], [3.0, 4.0])
        """
        if isinstance(index, (int, np.integer)) or (isinstance(index, np.ndarray) and index.ndim == 0):
            raise TypeError(f"Trajectory index must be a slice, an integer array or a boolean mask, got the integer "
                            f"{index!r}: traj[{index}:{index} + 1] is a trajectory of that one sample")
        if isinstance(index, tuple):
            raise TypeError("Trajectory index picks samples along time only; index the arrays (traj.q[...]) for more")
        try:
            picked = np.arange(self.t.size)[index]
        except (IndexError, TypeError, ValueError) as exc:
            raise IndexError(f"Trajectory index {index!r} does not pick samples of {self.t.size}: {exc}") from None
        if picked.ndim != 1:
            raise IndexError(f"Trajectory index must pick samples along one time axis, got shape {picked.shape}")
        if picked.size == 0:
            raise IndexError(f"Trajectory index {index!r} picks no sample of {self.t.size}")
        extra = {}
        for name in self._extra:
            value = np.asarray(getattr(self, name))
            axis = value.ndim - 2 if value.shape[-1:] == (3,) and value.ndim >= 2 else value.ndim - 1
            extra[name] = np.take(value, picked, axis=axis)
        return type(self)(self.t[picked], self.q[..., picked, :], self.omega[..., picked, :], self.inertia,
                          meta=self.meta, **extra)

    def between(self, t0: float, t1: float) -> Trajectory:
        """The samples at times ``t0 <= t <= t1`` (in the order held), as a Trajectory.

        Examples
        --------
        >>> tr = Trajectory(np.arange(11) / 4, [[1, 0, 0, 0]] * 11, [[0, 0, 1]] * 11, [1, 2, 3])
        >>> tr.between(0.4, 1.0).t.tolist()
        [0.5, 0.75, 1.0]
        """
        t0, t1 = as_float(t0, "t0"), as_float(t1, "t1")
        if t0 > t1:
            raise ValueError(f"t0 must be at most t1, got t0 = {t0!r} > t1 = {t1!r}")
        inside = (self.t >= t0) & (self.t <= t1)
        if not inside.any():
            raise ValueError(f"no sample lies in [t0, t1] = [{t0!r}, {t1!r}]; the trajectory spans "
                             f"t = {self.t.min()!r} … {self.t.max()!r}")
        return self[inside]

    @property
    def rotation(self) -> Rotation:
        """The attitudes as a :class:`kreisel.Rotation` of shape ``(batch..., n)`` (R maps body to space).

        Examples
        --------
        >>> tr = Trajectory([0.0, 1.0], [[1, 0, 0, 0], [np.cos(0.5), 0, 0, np.sin(0.5)]], [[0, 0, 1]] * 2, [1, 2, 3])
        >>> r = tr.rotation
        >>> len(r), round(float(r[1].magnitude()), 12)
        (2, 1.0)
        """
        return Rotation.from_quat(self.q)

    def __repr__(self) -> str:
        batch = self.q.shape[:-2]
        b = f", batch={batch}" if batch else ""
        return f"Trajectory(n={self.t.size}, t=[{self.t[0]:g}, {self.t[-1]:g}]{b})"

    def _repr_html_(self) -> str:
        rows: list[tuple[str, Any]] = [("samples", self.t.size), ("t", f"{self.t[0]:g} … {self.t[-1]:g} s")]
        if self.batch_shape:
            rows.append(("batch shape", self.batch_shape))
        else:
            rows += [("principal moments", number(np.linalg.eigvalsh(self.inertia)) + " kg m²"),
                     ("ω′(t0)", number(self.omega[0]) + " rad/s")]
            # the constructor takes NaN samples (a run stopped midway, a file with gaps): say where, since the
            # first integrals of such samples are not defined
            bad = ~(np.isfinite(self.q).all(axis=-1) & np.isfinite(self.omega).all(axis=-1))
            if bad.any():
                rows.append(("non-finite samples", f"{int(bad.sum())} of {bad.size}, the first at "
                                                   f"t = {self.t[bad][0]:g} s"))
            else:
                drift = self.drift()
                rows += [
                    ("T(t0)", number(self.energy[0]) + " J"),
                    ("J(t0)", number(self.angular_momentum_space[0]) + " kg m²/s"),
                    ("max relative change of T, |J|",
                     f"{number(drift['energy'], 3)}, {number(drift['angular_momentum'], 3)}"),
                ]
        rows += [(key, value) for key, value in self.meta.items()]
        rows += [("extra arrays", ", ".join(self._extra))] if self._extra else []
        return html_table("Trajectory", rows, note="quaternions scalar-first, R maps body to space; ω′ in body axes")

    def show(self, **options: Any) -> Any:
        """Play the trajectory in 3D in a notebook: :func:`kreisel.show` (needs ``pip install 'kreisel[notebook]'``).

        Body, principal axes, ω, J, the inertia (energy) ellipsoid on the invariable plane,
        polhode and herpolhode (Theory §5.5), with a time slider.

        Parameters
        ----------
        **options
            Passed to :func:`kreisel.show` (``max_samples``: longer trajectories are thinned evenly).

        Returns
        -------
        anywidget.AnyWidget
            The widget of ``kreisel.show(self, **options)``.

        Examples
        --------
        >>> import kreisel as kr
        >>> widget = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 10.0, 301), [0.1, 2.0, 0.1]).show()
        >>> len(widget.data["t"])
        301
        """
        return _display.player()(self, **options)

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """Leading batch shape (``()`` for a single body)."""
        return self.q.shape[:-2]

    def _inertia_t(self) -> NDArray[np.float64]:
        # inertia broadcast against the time axis: (..., 1, 3, 3)
        return self.inertia[..., None, :, :]

    @property
    def angular_momentum_body(self) -> NDArray[np.float64]:
        """J′ = I ω′ in body components (Theory §4.4)."""
        momentum: NDArray[np.float64] = np.einsum("...ij,...j->...i", self._inertia_t(), self.omega)
        return momentum

    @property
    def energy(self) -> NDArray[np.float64]:
        """Rotational kinetic energy T = ½ ω′·I ω′ (Theory §5.2)."""
        energy: NDArray[np.float64] = 0.5 * np.einsum("...i,...i->...", self.omega, self.angular_momentum_body)
        return energy

    def _to_space(self, v: NDArray[np.float64]) -> NDArray[np.float64]:
        """R v of body vectors ``v`` (..., n, 3); NaN at the samples whose q or v is not finite.

        The constructor takes such samples (a run stopped midway, a file with gaps); quat_apply refuses them.
        """
        finite = np.isfinite(self.q).all(axis=-1) & np.isfinite(v).all(axis=-1)
        if finite.all():
            return quat_apply(self.q, v)
        out = np.full(v.shape, np.nan)
        out[finite] = quat_apply(self.q[finite], v[finite])
        return out

    @property
    def omega_space(self) -> NDArray[np.float64]:
        """ω = R ω′ in space components (Theory §3.1)."""
        return self._to_space(self.omega)

    @property
    def angular_momentum_space(self) -> NDArray[np.float64]:
        """J = R J′ in space components; constant for a free body (Theory §4.4)."""
        return self._to_space(self.angular_momentum_body)

    def angular_momentum(self, frame: str = "space") -> NDArray[np.float64]:
        """Angular momentum J (``frame="space"``) or J′ (``frame="body"``), kg m²/s.

        Examples
        --------
        For a free body J is fixed in space while J′ = R⁻¹ J wanders through the
        body with the same length (Theory §4.4):

        >>> import kreisel as kr
        >>> tr = kr.simulate([1.0, 2.0, 3.0], np.linspace(0.0, 5.0, 6), [0.3, 0.2, 1.0])
        >>> J, J_body = tr.angular_momentum(), tr.angular_momentum(frame="body")
        >>> J[0].round(9).tolist()   # I ω0 at t = 0, identity attitude
        [0.3, 0.4, 3.0]
        >>> bool(np.allclose(J, J[0], rtol=0.0, atol=1e-10)), bool(np.allclose(J_body, J_body[0], atol=1e-3))
        (True, False)
        >>> bool(np.allclose(np.linalg.norm(J_body, axis=-1), np.linalg.norm(J[0]), rtol=1e-10))
        True
        """
        return self.angular_momentum_body if check_frame(frame) else self.angular_momentum_space

    def euler(self, seq: str, degrees: bool = False) -> NDArray[np.float64]:
        """Euler angles of the attitude in any sequence, e.g. ``"ZXZ"`` (Theory §2.3).

        Examples
        --------
        >>> tr = Trajectory([0.0], [[np.cos(0.3), 0, 0, np.sin(0.3)]], [[0, 0, 1]], [1, 1, 2])
        >>> np.round(tr.euler("ZYX")[0], 12) + 0.0
        array([0.6, 0. , 0. ])
        """
        from ..so3 import quat_to_euler

        return quat_to_euler(seq, self.q, degrees=degrees)

    def drift(self) -> dict[str, NDArray[np.float64]]:
        """Drift of the free-body first integrals over the trajectory (Theory §5.2).

        Returns
        -------
        dict of ndarray (batch shape)
            ``energy``: max |T − T0| / T0; ``angular_momentum``: max ||J| − |J0|| / |J0|;
            ``direction``: max angle (rad) between the space J and its initial direction;
            ``quaternion_norm``: max ||q| − 1|. Under a torque these measure the change
            the torque made, not an error.

        Examples
        --------
        >>> tr = Trajectory([0.0, 1.0], [[1, 0, 0, 0]] * 2, [[0, 0, 1]] * 2, [1, 2, 3])
        >>> {k: float(v) for k, v in tr.drift().items()}
        {'energy': 0.0, 'angular_momentum': 0.0, 'direction': 0.0, 'quaternion_norm': 0.0}
        """
        energy = self.energy
        j = self.angular_momentum_space
        size = np.linalg.norm(j, axis=-1)
        j0 = j[..., :1, :]
        s0 = size[..., :1]
        cross = np.linalg.norm(np.cross(j, j0), axis=-1)
        angle = np.arctan2(cross, np.einsum("...i,...i->...", j, j0))
        e0 = energy[..., :1]
        return {
            "energy": np.max(np.abs(energy - e0), axis=-1) / np.where(e0[..., 0] != 0, np.abs(e0[..., 0]), 1.0),
            "angular_momentum": np.max(np.abs(size - s0), axis=-1) / np.where(s0[..., 0] != 0, s0[..., 0], 1.0),
            "direction": np.max(angle, axis=-1),
            "quaternion_norm": np.max(np.abs(np.linalg.norm(self.q, axis=-1) - 1.0), axis=-1),
        }

    # ------------------------------------------------------------------ export

    def _batch_dims(self) -> tuple[str, ...]:
        return tuple(f"batch_{k}" for k in range(len(self.batch_shape)))

    def to_xarray(self) -> xr.Dataset:
        """An ``xarray.Dataset`` with dims ``(batch_k..., time, component)``.

        Variables ``q``, ``omega``, ``omega_space``, ``angular_momentum``
        (space), ``energy``, ``inertia`` and every extra array; ``meta`` goes to
        the attributes (values JSON-encoded).

        Examples
        --------
        >>> tr = Trajectory([0.0, 1.0], [[1, 0, 0, 0]] * 2, [[0, 0, 1]] * 2, [1, 2, 3])
        >>> ds = tr.to_xarray()
        >>> ds["omega"].dims
        ('time', 'axis')
        """
        xr = require("xarray", extra="io", feature="Trajectory.to_xarray")
        b = self._batch_dims()
        data = {
            "q": (b + ("time", "quaternion"), self.q),
            "omega": (b + ("time", "axis"), self.omega),
            "omega_space": (b + ("time", "axis"), self.omega_space),
            "angular_momentum": (b + ("time", "axis"), self.angular_momentum_space),
            "energy": (b + ("time",), self.energy),
            "inertia": (b[: self.inertia.ndim - 2] + ("axis", "axis_col"), self.inertia),
        }
        for name in self._extra:
            value = np.asarray(getattr(self, name))
            dims = b + ("time", "axis") if value.shape[-1:] == (3,) else b + ("time",)
            dims = dims[len(dims) - value.ndim:]
            data[name] = (dims, value)
        attrs = {"meta": json.dumps(self.meta, default=str), "extra": json.dumps(list(self._extra)),
                 "kreisel": "Trajectory: q body->space scalar-first; omega body components (rad/s)"}
        return xr.Dataset(data, coords={"time": self.t, "quaternion": list(_QUAT), "axis": list(_VECTOR),
                                        "axis_col": list(_VECTOR)}, attrs=attrs)

    @classmethod
    def from_xarray(cls, ds: xr.Dataset) -> Trajectory:
        """Rebuild a trajectory from :meth:`to_xarray` output.

        Examples
        --------
        A spin of 1 rad/s about z, with an extra array, survives the round trip:

        >>> tr = Trajectory([0.0, 1.0], [[1, 0, 0, 0], [np.cos(0.5), 0, 0, np.sin(0.5)]], [[0, 0, 1.0]] * 2,
        ...                 [1, 2, 3], meta={"method": "closed form"}, spin_angle=np.array([0.0, 1.0]))
        >>> back = Trajectory.from_xarray(tr.to_xarray())
        >>> bool(np.array_equal(back.q, tr.q)), back.meta, back.spin_angle.tolist()
        (True, {'method': 'closed form'}, [0.0, 1.0])
        >>> back.energy.tolist()   # ½ I3 ω3² = ½ · 3 · 1
        [1.5, 1.5]
        """
        extra_names = json.loads(ds.attrs.get("extra", "[]"))
        extra = {name: ds[name].values for name in extra_names}
        return cls(ds["time"].values, ds["q"].values, ds["omega"].values, ds["inertia"].values,
                   meta=json.loads(ds.attrs.get("meta", "{}")), **extra)

    def to_pandas(self) -> pd.DataFrame:
        """A ``pandas.DataFrame`` indexed by time (and by body for a batch).

        Columns ``q0..q3``, ``omega_1..3`` (body), ``omega_space_x..z``,
        ``J_x..z`` (space), ``energy`` and the extras.

        Examples
        --------
        >>> tr = Trajectory([0.0, 1.0], [[1, 0, 0, 0]] * 2, [[0, 0, 1]] * 2, [1, 2, 3])
        >>> list(tr.to_pandas().columns[:4])
        ['q0', 'q1', 'q2', 'q3']
        """
        pd = require("pandas", extra="io", feature="Trajectory.to_pandas")
        n = self.t.size
        columns = {}
        for k in range(4):
            columns[f"q{k}"] = self.q[..., k]
        for k in range(3):
            columns[f"omega_{k + 1}"] = self.omega[..., k]
        space = self.omega_space
        momentum = self.angular_momentum_space
        for k, c in enumerate(_VECTOR):
            columns[f"omega_space_{c}"] = space[..., k]
        for k, c in enumerate(_VECTOR):
            columns[f"J_{c}"] = momentum[..., k]
        columns["energy"] = self.energy
        for name in self._extra:
            value = np.asarray(getattr(self, name))
            if value.shape[-1:] == (3,) and value.ndim >= 2:
                for k, c in enumerate(_VECTOR):
                    columns[f"{name}_{c}"] = value[..., k]
            else:
                columns[name] = value
        flat = {key: np.reshape(v, -1) for key, v in columns.items()}
        if self.batch_shape:
            count = int(np.prod(self.batch_shape))
            index = pd.MultiIndex.from_arrays([np.repeat(np.arange(count), n), np.tile(self.t, count)],
                                              names=["body", "t"])
        else:
            index = pd.Index(self.t, name="t")
        return pd.DataFrame(flat, index=index)

    def save(self, path: str | os.PathLike[str]) -> None:
        """Write to NetCDF (``.nc``, via xarray's scipy engine), CSV (``.csv``) or Parquet (``.parquet``).

        CSV and Parquet hold one body; the inertia tensor, ``meta``, the names
        of the extra arrays and a SHA-256 checksum of the data go to the
        Parquet file's metadata, and beside a CSV (which stays plain CSV) to
        the sidecar ``NAME.csv.json``, so :meth:`load` restores and checks
        them. The file is written atomically (complete or untouched); an
        existing file at ``path`` is replaced, as by xarray's and pandas'
        writers (``kreisel simulate -o`` refuses one unless given ``--force``).

        Examples
        --------
        Numbers are written with 17 significant digits, so a CSV round trip is exact:

        >>> import os, tempfile
        >>> tr = Trajectory([0.0, 1.0], [[1, 0, 0, 0], [np.cos(0.5), 0, 0, np.sin(0.5)]], [[0, 0, 1.0]] * 2,
        ...                 [1, 2, 3], meta={"method": "closed form"})
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     tr.save(os.path.join(folder, "spin.csv"))
        ...     back = Trajectory.load(os.path.join(folder, "spin.csv"))
        >>> bool(np.array_equal(back.q, tr.q) and np.array_equal(back.inertia, tr.inertia)), back.meta
        (True, {'method': 'closed form'})
        """
        _trajectory_files.save(self, path)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Trajectory:
        """Read a file written by :meth:`save` (format from the extension).

        Examples
        --------
        NetCDF keeps a batch of bodies (here two spins about z at 1 and 2 rad/s):

        >>> import os, tempfile
        >>> angles = np.array([[0.0, 0.5], [0.0, 1.0]])   # half the rotation angle at t = 0, 1
        >>> q = np.stack([np.cos(angles), 0 * angles, 0 * angles, np.sin(angles)], axis=-1)
        >>> omega = np.array([[[0, 0, 1.0]] * 2, [[0, 0, 2.0]] * 2])
        >>> tr = Trajectory([0.0, 1.0], q, omega, [1, 2, 3])
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     tr.save(os.path.join(folder, "spins.nc"))
        ...     back = Trajectory.load(os.path.join(folder, "spins.nc"))
        >>> back.batch_shape, back.energy.tolist()   # ½ I3 ω3²
        ((2,), [[1.5, 1.5], [6.0, 6.0]])
        """
        return _trajectory_files.load(cls, path)
