"""Input checking shared by every layer.

Each public function validates its arguments *before* any work starts and
raises ``ValueError``/``TypeError`` naming the argument and the expectation.
"""

from __future__ import annotations

import numbers
import os
import warnings
from types import TracebackType
from collections.abc import Callable
from typing import Any, NoReturn

import numpy as np
from numpy.typing import ArrayLike, NDArray

FRAMES = ("space", "body")

#: numpy dtype kinds accepted as real numbers: bool, signed and unsigned integers, floats, and
#: object arrays of real Python numbers (not of strings, which float() would parse)
REAL_KINDS = "biufO"


#: Largest angle (rad) a body or frame may turn through over the requested times: beyond
#: ~1e15 rad the rounding of the angle alone (1e-16 of it) is more than 0.1 rad.
MAX_TURN = 1e15


def refuse_long_turn(turn: float, names: str, what: str, unresolved: str = "fixes its attitude") -> None:
    """Raise ValueError naming ``names`` if ``turn`` (rad, or NaN/inf) exceeds :data:`MAX_TURN`.

    ``what`` is the subject of the message ("the body turns through up to", "a 2 m pendulum swings
    through a phase of"), ``unresolved`` what double precision no longer does beyond the limit.
    """
    if not turn <= MAX_TURN:
        raise ValueError(f"{names} are out of range: {what} {turn:.3g} rad, more than {MAX_TURN:g} rad, "
                         f"where double precision no longer {unresolved}")

#: Longest rotation angle (rad) that kreisel computes a rotation of when the angle is itself the
#: result of arithmetic: the length |ψ| of a rotation vector (or twist), a power ``p θ``, an
#: interpolation parameter times an angle. Such an angle carries a rounding error of about
#: 1.1e-16 of its size, and the rotation depends on it modulo 2π: beyond 1e8 rad the error
#: exceeds 1e-8 rad (the rate maps' singularity tolerance), and by ~6e16 rad it exceeds 2π, so a
#: finite answer would be noise. Every entry point refuses such angles (:func:`refuse_long_angle`)
#: before work starts; an angle the user gives directly (Euler angles, ``from_screw``) is exact
#: and is not limited.
ROTVEC_RANGE = 1e8


def refuse_long_angle(longest: float, name: str, what: str = "|psi|") -> None:
    """ValueError naming ``name`` if the longest computed angle ``longest`` exceeds :data:`ROTVEC_RANGE`.

    ``what`` says which angle (``"|psi|"``, ``"the rotation part |omega|"``, ``"|p| times the angle of q"``).
    NaN is not caught here: callers check finiteness first.
    """
    if longest > ROTVEC_RANGE:
        raise ValueError(
            f"{name} is out of range: {what} = {longest:.3g} rad exceeds {ROTVEC_RANGE:g} rad, beyond which the "
            "rotation depends on the angle modulo 2*pi, which the rounding of so large an angle does not "
            "determine; reduce the angle modulo 2*pi first (a rotation vector to |psi| <= pi: the same rotation)"
        )


def as_float_array(x: ArrayLike, name: str, tail: tuple[int, ...] | None = None,
                   finite: bool = True) -> NDArray[np.float64]:
    """Return ``x`` as a float64 array, checking its trailing shape.

    Parameters
    ----------
    x : array_like
        The user's input.
    name : str
        Argument name used in error messages.
    tail : tuple of int, optional
        Required trailing shape, e.g. ``(4,)`` for quaternions or ``(3, 3)``
        for matrices.
    finite : bool
        Refuse NaN and infinities.

    Complex, date/time, string and other non-real dtypes are refused, not
    converted: numpy would drop an imaginary part (with only a warning) or
    turn dates into day counts.
    """
    try:
        raw = np.asarray(x)
        if raw.dtype.kind not in REAL_KINDS:
            raise TypeError(f"{name} must be real numbers, got an array of dtype {raw.dtype}")
        if raw.dtype.kind == "O":
            bad = next((v for v in raw.flat if not isinstance(v, numbers.Real)), None)
            if bad is not None:
                raise TypeError(f"{name} must be real numbers, got an element of type {type(bad).__name__}")
        a = raw.astype(np.float64, copy=False)
    except (TypeError, ValueError) as exc:
        if "must be real numbers" in str(exc):
            raise
        raise TypeError(f"{name} must be a real numeric array, got {type(x).__name__}") from exc
    if tail is not None:
        k = len(tail)
        if a.ndim < k or a.shape[a.ndim - k:] != tuple(tail):
            want = "(..., " + ", ".join(str(n) for n in tail) + ")"
            raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    if finite and not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite (no NaN or inf)")
    return a


def as_float(x: ArrayLike, name: str, finite: bool = True) -> float:
    """Return ``x``, a single real number, as a float; an array of another shape is refused naming ``name``."""
    a = as_float_array(x, name, finite=finite)
    if a.ndim:
        raise ValueError(f"{name} must be a single number, got an array of shape {a.shape}")
    return float(a)


def sample_times(t: ArrayLike) -> NDArray[np.float64]:
    """``t`` as a one-dimensional float array of at least one time, else ValueError naming ``t``.

    A trajectory of no samples has no initial state to measure drift from, nor a time span to show.
    """
    a = as_float_array(t, "t")
    if a.ndim != 1 or a.size == 0:
        raise ValueError(f"t must be one-dimensional with at least one time, got shape {a.shape}")
    return a


def positive_array(x: ArrayLike, name: str, allow_zero: bool = False,
                   allow_inf: bool = False) -> NDArray[np.float64]:
    """:func:`as_float_array` of a quantity that must be > 0 (or >= 0: ``allow_zero``), else ValueError naming it.

    Infinities are refused (as :func:`as_float_array` does) unless ``allow_inf``,
    for a bound whose default ``inf`` means none; NaN never passes.
    """
    a = as_float_array(x, name, finite=not allow_inf)
    bad = ~(a >= 0) if allow_zero else ~(a > 0)  # NaN is bad too
    if np.any(bad):
        raise ValueError(f"{name} must be {'>= 0' if allow_zero else '> 0'}, got {float(a[bad].flat[0])!r}")
    return a


def positive_float(x: ArrayLike, name: str, allow_inf: bool = False) -> float:
    """:func:`as_float` of a quantity that must be > 0, else ValueError naming it (as :func:`positive_array`)."""
    value = as_float(x, name, finite=not allow_inf)
    positive_array(value, name, allow_inf=allow_inf)
    return value


def float_in_range(x: ArrayLike, name: str, low: float, high: float) -> float:
    """:func:`as_float` of a number in ``[low, high)``, else ValueError naming it and the range (NaN is outside)."""
    value = as_float(x, name, finite=False)
    if not low <= value < high:
        raise ValueError(f"{name} must be in [{low:g}, {high:g}), got {value!r}")
    return value


def check_flag(flag: object, name: str) -> bool:
    """Return ``flag``, which must be ``True`` or ``False`` (numpy's too), else TypeError naming ``name``.

    Truthiness is not accepted: ``scalar_first="no"`` or ``degrees=None`` would
    silently pick a convention the caller did not ask for.
    """
    if not isinstance(flag, bool | np.bool_):
        raise TypeError(f"{name} must be True or False, got {flag!r}")
    return bool(flag)


def check_frame(frame: object) -> bool:
    """Return True for ``frame="body"``, False for ``"space"``; refuse anything else."""
    if frame not in FRAMES:
        raise ValueError(f"frame must be 'space' or 'body', got {frame!r}")
    return frame == "body"


def check_tolerance(tol: float, name: str = "tol") -> float:
    """``tol`` as a float in [0, 1) (a singularity threshold on a sine or a determinant), or ValueError."""
    return float_in_range(tol, name, 0.0, 1.0)


def warn_if_any(mask: NDArray[np.bool_], category: type[Warning], message: str) -> None:
    """Issue ``category`` once, counting the samples, when any entry of ``mask`` (set to NaN by the caller) is set."""
    if mask.any():
        count = int(mask.sum())
        warnings.warn(f"{message} ({count} of {mask.size} samples; entries set to NaN)", category, stacklevel=3)


def batch_shape(shape: Any, name: str = "shape") -> tuple[int, ...]:
    """Return ``shape`` (``None``, a non-negative int or a sequence of them) as a tuple.

    Floats such as ``2.5`` (or ``2.0``), strings and negative sizes raise
    ``ValueError`` naming the argument, instead of numpy's ``TypeError``.
    """
    if shape is None:
        return ()
    given = (shape,) if np.ndim(shape) == 0 else shape
    items: tuple[Any, ...] | None
    try:
        items = tuple(given)
    except TypeError:
        items = None
    if items is None or not all(isinstance(n, (int, np.integer)) and not isinstance(n, bool) for n in items):
        raise ValueError(f"{name} must be None, a non-negative int or a tuple of them, got {shape!r}")
    if any(n < 0 for n in items):
        raise ValueError(f"{name} must have non-negative entries, got {shape!r}")
    return tuple(int(n) for n in items)


class out_of_range:
    """Context that turns an overflow of finite input into a ValueError naming the arguments.

    Inside the block numpy's overflow warnings are silenced; :meth:`check` then refuses results that
    came out non-finite (the true value exceeds the largest double, 1.8e308), saying so.

    Examples
    --------
    >>> import numpy as np
    >>> with out_of_range("omega and r", "the centripetal acceleration") as guard:
    ...     a = guard.check(np.float64(1e200) * np.float64(1e200))
    Traceback (most recent call last):
    ...
    ValueError: omega and r are out of range: the centripetal acceleration exceeds the largest double (1.8e308)
    """

    def __init__(self, names: str, what: str) -> None:
        self.names, self.what = names, what

    def __enter__(self) -> "out_of_range":
        # errstate, not seterr: numpy keeps it per thread and per context, so other threads keep their warnings
        self._errstate = np.errstate(over="ignore", invalid="ignore")
        self._errstate.__enter__()
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self._errstate.__exit__(kind, error, trace)

    def check(self, *values: Any) -> Any:
        """The values (one, or a tuple of several), refused when any entry is not finite."""
        for value in values:
            if not np.all(np.isfinite(value)):
                self.refuse()
        return values[0] if len(values) == 1 else values

    @property
    def message(self) -> str:
        """The refusal's words (also for an array operation's refusal of an overflowing result)."""
        return f"{self.names} are out of range: {self.what} exceeds the largest double (1.8e308)"

    def refuse(self) -> NoReturn:
        """Raise the refusal, for a result found out of range some other way (a lower layer's own refusal)."""
        raise ValueError(self.message)


def checked_callable(fn: Callable[..., Any], name: str) -> Callable[..., NDArray[np.float64]]:
    """``fn`` with its output checked at every call: a real, finite array of shape (3,).

    The compiled loop reads exactly three numbers from what a callable returns,
    so a wrong shape must never reach it; a non-finite value stops the run at
    once (instead of the step size collapsing towards it). Shared by the
    torque and force callables of :mod:`kreisel.dynamics` and the particle
    forces of :mod:`kreisel.frames`.
    """

    def call(t: float, *state: NDArray[np.float64]) -> NDArray[np.float64]:
        value = fn(t, *state)
        out = np.asarray(value)
        if out.dtype.kind not in "biuf":
            raise TypeError(f"{name} callable must return a real array of shape (3,), got "
                            f"{type(value).__name__} of dtype {out.dtype} at t = {float(t)!r}")
        if out.shape != (3,):
            raise ValueError(f"{name} callable must return shape (3,), got {out.shape} at t = {float(t)!r}")
        out = out.astype(np.float64)
        if not np.isfinite(out).all():
            raise ValueError(f"{name} callable returned a non-finite value {out} at t = {float(t)!r}")
        return out

    return call


def memory_budget() -> int:
    """Bytes one result may take: half the machine's physical memory (16 GiB if it cannot be read)."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") // 2
    except (AttributeError, OSError, ValueError):
        return 2**34


def check_allocation(nbytes: float, what: str, remedy: str | None = None) -> None:
    """Refuse, before allocating, a result of ``nbytes`` bytes over :func:`memory_budget`.

    ``what`` describes the result in the message, e.g. ``"the output (1 × 1000000000 samples × 7 states)"``,
    ``remedy`` (optional) what the caller can do about it.
    """
    budget = memory_budget()
    if not nbytes <= budget:
        raise ValueError(f"{what} would need {_size(nbytes)}, more than the {_size(budget)} allowed "
                         "(half of this machine's memory)" + (f": {remedy}" if remedy else ""))


def _size(nbytes: float) -> str:
    for unit, size in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if nbytes >= size:
            return f"{nbytes / size:.3g} {unit}"
    return f"{nbytes:.0f} bytes"


#: Axis letter -> index, for Euler axis sequences.
AXES = {"x": 0, "y": 1, "z": 2}


def parse_sequence(seq: str) -> tuple[tuple[int, ...], bool]:
    """Parse an Euler axis sequence.

    Parameters
    ----------
    seq : str
        Three letters from ``xyz``, all uppercase (intrinsic) or all lowercase
        (extrinsic), no two adjacent letters equal ("ZXZ", "xyz", ...).

    Returns
    -------
    axes : tuple of 3 int
        Axis indices 0, 1, 2 for x, y, z, in the order written.
    intrinsic : bool

    Examples
    --------
    >>> parse_sequence("ZXZ")
    ((2, 0, 2), True)
    >>> parse_sequence("xyz")
    ((0, 1, 2), False)
    """
    if not isinstance(seq, str):
        raise ValueError(f"seq must be a 3-letter string of x, y, z, got {seq!r}")
    if len(seq) != 3:
        raise ValueError(f"seq must have exactly 3 letters, got {seq!r}")
    if not (seq.isupper() or seq.islower()):
        raise ValueError(f"seq must be all uppercase (intrinsic) or all lowercase (extrinsic), got {seq!r}")
    lower = seq.lower()
    if any(c not in AXES for c in lower):
        raise ValueError(f"seq may only contain the letters x, y, z, got {seq!r}")
    if lower[0] == lower[1] or lower[1] == lower[2]:
        raise ValueError(f"seq must not repeat an axis in adjacent positions, got {seq!r}")
    return tuple(AXES[c] for c in lower), seq.isupper()


#: Relative tolerance of every check on inertia input, at every entry point (``RigidBody``, the
#: ``inertia`` functions, ``simulate``/``simulate_batch``/``simulate_6dof``, the tops, the viewer):
#: a tensor is symmetric when max |I_jk - I_kj| <= INERTIA_TOLERANCE * max |I_jk|; principal moments
#: obey the triangle inequality when I_max - (I_j + I_k) <= INERTIA_TOLERANCE * (I_1 + I_2 + I_3),
#: and a moment counts as zero (a rod) when it is <= INERTIA_TOLERANCE * (I_1 + I_2 + I_3). Tensors
#: that went through a few floating-point operations (R I Rᵀ, mesh integration, sums of parts) carry
#: relative errors of order 1e-15, and printed tables nine significant digits; 1e-9 accepts both
#: while refusing any genuinely unphysical input. Documented for users in the user guide, section
#: "Which inertia input is accepted" (docs/user_guide/04_fixed_point.rst).
INERTIA_TOLERANCE = 1e-9


def _relative_to_largest(a: NDArray[np.float64], axes: tuple[int, ...]) -> NDArray[np.float64]:
    """``a`` divided by its largest absolute entry over ``axes`` (zero blocks stay zero): no overflow later."""
    scale = np.max(np.abs(a), axis=axes, keepdims=True)
    return a / np.where(scale > 0.0, scale, 1.0)


def check_inertia_tensor(tensor: ArrayLike, name: str) -> NDArray[np.float64]:
    """Validate ``(..., 3, 3)`` inertia tensors as symmetric and return their symmetric part.

    Symmetric means to within :data:`INERTIA_TOLERANCE` of the largest entry; the
    ``ValueError`` names ``name`` and gives the asymmetry. Definiteness and the
    triangle inequalities are properties of the principal moments:
    :func:`check_principal_moments`.

    Examples
    --------
    >>> check_inertia_tensor([[2.0, 1e-12, 0], [0, 2, 0], [0, 0, 3]], "I")[0, 1]
    np.float64(5e-13)
    """
    a = as_float_array(tensor, name, tail=(3, 3))
    unit = _relative_to_largest(a, (-2, -1))
    asymmetry = np.max(np.abs(unit - np.swapaxes(unit, -1, -2)), axis=(-2, -1), initial=0.0)
    if np.any(asymmetry > INERTIA_TOLERANCE):
        raise ValueError(f"{name} must be symmetric (I_jk = I_kj to within {INERTIA_TOLERANCE:g} of the largest "
                         f"entry); largest |I_jk - I_kj| is {float(np.max(asymmetry)):.3g} of the largest entry")
    # halves first: a + aᵀ would overflow for entries above half the largest double
    return 0.5 * a + 0.5 * np.swapaxes(a, -1, -2)


def check_principal_moments(moments: ArrayLike, name: str, definite: bool = True,
                            allow_unphysical: bool = False) -> NDArray[np.float64]:
    """Validate principal moments ``(..., 3)`` (any order) and return them as floats.

    The one rule for inertia input, to within :data:`INERTIA_TOLERANCE` of the
    sum of the moments: no moment is negative (``definite=True``: none is zero
    either, as Euler's equations need I⁻¹; an ideal thin rod has a zero moment),
    and the triangle inequalities I_i <= I_j + I_k hold (equality for a thin
    plate, Theory §4.1). ``allow_unphysical=True`` skips the triangle
    inequalities, for textbook test problems such as Hairer, Lubich and
    Wanner's free body with I = (2, 1, 2/3).

    Examples
    --------
    >>> check_principal_moments([1.0, 1.0, 2.0], "body")  # a thin plate
    array([1., 1., 2.])
    >>> check_principal_moments([1.0, 1.0, 5.0], "body")
    Traceback (most recent call last):
    ...
    ValueError: body: principal moments [1. 1. 5.] violate the triangle inequality I_i <= I_j + I_k ...
    """
    m = as_float_array(moments, name, tail=(3,))
    if m.size == 0:
        raise ValueError(f"{name}: an empty batch of bodies (shape {m.shape}); give at least one")
    unit = _relative_to_largest(m, (-1,))
    trace = np.sum(unit, axis=-1)
    smallest = np.min(unit, axis=-1)
    if definite:
        bad = smallest <= INERTIA_TOLERANCE * trace
        if np.any(bad):
            raise ValueError(f"{name}: principal moments {m[bad][0]} must all be positive (more than "
                             f"{INERTIA_TOLERANCE:g} of their sum: positive definite); a body whose mass lies "
                             "on a line (ideal thin rod) has a zero moment and no Euler equations")
    bad = smallest < -INERTIA_TOLERANCE * np.abs(trace)
    if np.any(bad):
        raise ValueError(f"{name}: principal moments {m[bad][0]} must not be negative (positive semi-definite, "
                         f"to within {INERTIA_TOLERANCE:g} of their sum)")
    if check_flag(allow_unphysical, "allow_unphysical"):
        return m
    excess = (2.0 * np.max(unit, axis=-1) - trace) / np.where(trace > 0.0, trace, 1.0)
    bad = excess > INERTIA_TOLERANCE
    if np.any(bad):
        raise ValueError(f"{name}: principal moments {m[bad][0]} violate the triangle inequality I_i <= I_j + I_k "
                         f"(the largest exceeds the sum of the other two by {float(excess[bad][0]):.3g} of the sum of "
                         f"all three, more than the tolerance {INERTIA_TOLERANCE:g}); no physical body has them")
    return m
