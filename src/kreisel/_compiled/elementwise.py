"""Array operations declared once: a scalar kernel and the one declaration that broadcasts it.

An array operation of kreisel (``quat_inverse``, ``rotvec_to_matrix``,
``se3`` composition, ...) is written as

- a **kernel**: the formula, written once for one element, taking plain
  numbers (an input's components in C order, then the parameters) and
  returning its output's components as a tuple (or one number), compiled
  with :data:`kernel`;
- a **declaration**: :func:`elementwise`, naming the inputs (their core
  shapes and what they must hold, :class:`Input`), the parameters and the
  output's core shape.

The declaration generates everything else: the input checks with their
messages, broadcasting over leading batch axes, the serial loop for small
batches and the multi-core ``prange`` loop for large ones, ``out=``, and the
refusal of a result that overflows. Every kreisel result is a new ordinary
numpy array (or the caller's ``out``).

How a call runs
    The inputs are converted to float64 (a wrong shape or type is refused by
    name), broadcast, and passed to the loop as flat C-ordered arrays; an
    input without batch axes (one rotation applied to many vectors) is read
    in place for every element. The loop computes every element and, as it
    goes, checks what each input must hold (finite, a nonzero quaternion, a
    rotation vector in range, a matrix orthogonal to rounding) and that each
    result is finite: one pass over memory for the check and the work. Only
    when some element fails does the slow path run: each input's full check
    raises the ``ValueError`` naming the argument, a matrix within tolerance
    is projected onto the nearest rotation and the loop runs again, and what
    is left is a finite result that overflowed, refused naming the inputs.
    With ``out=`` the checks run first, so that a refused call leaves ``out``
    (which may be an input) untouched.
Generated loops
    The loops are Python source generated from the declaration
    (:attr:`ArrayOperation.source`), compiled on first use for one signature
    each (flat read-only float64 inputs), and cached on disk
    (:mod:`.cache`); the kernels are compiled into them.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import inspect
import math
from collections.abc import Callable, Sequence
from typing import Any, TypeVar, cast

import numpy as np
from numba import njit, prange, types
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float_array
from . import cache, inlined
from .outputs import check_out, with_out_entry

#: Batches with at least this many elements run on all cores; below, waking the threads costs more than it saves.
PARALLEL_THRESHOLD = 2**14
#: Elements per piece of the multi-core loop.
PIECE = 2**13
# Indices are unsigned: numba then omits its test for negative (wrap-around) indices, whose branch
# per access kept LLVM from vectorising the loops.
_ZERO, _ONE = np.uint64(0), np.uint64(1)

#: Kernel flavour: inlined into the generated loops at numba's level, so that a loop over a kernel too large
#: for LLVM to inline (an exponential, a logarithm) still vectorises; compiled there with the loops' numpy
#: error model (a division by zero gives inf or NaN, which the loop's result check catches, instead of raising).
kernel = inlined

_BIG = "1.7976931348623157e308"

#: A stub or public function: the decorators return a function of the same type.
_F = TypeVar("_F", bound=Callable[..., Any])


@dataclasses.dataclass(frozen=True)
class Kind:
    """What an input must hold: its in-loop condition and its full check.

    Parameters
    ----------
    condition : callable
        ``condition(names) -> str``: a Python expression over the names of an
        element's components that is true where the element is acceptable
        (generated into the loop; no branch, so that the loop vectorises).
    check : callable
        ``check(array, name) -> array``: the full check, raising the
        ``ValueError`` that names the argument; may return a corrected array
        (nearly orthogonal matrices are projected).
    """

    condition: Callable[[Sequence[str]], str]
    check: Callable[[NDArray[np.float64], str], NDArray[np.float64]]


@dataclasses.dataclass(frozen=True)
class Input:
    """One input of a declaration: its argument name, core shape and :class:`Kind`."""

    name: str
    shape: tuple[int, ...]
    kind: Kind


@dataclasses.dataclass(frozen=True)
class Parameter:
    """A parameter passed to every element's kernel unchanged: its argument name and numba type."""

    name: str
    type: Any


def finite_condition(names: Sequence[str]) -> str:
    """Every component finite."""
    return " & ".join(f"(abs({n}) <= {_BIG})" for n in names)


def not_infinite_condition(names: Sequence[str]) -> str:
    """No component infinite (NaN allowed)."""
    return " & ".join(f"(not abs({n}) > {_BIG})" for n in names)


class ArrayOperation:
    """An array operation: a kernel broadcast over batches, with checks and ``out=`` (see the module)."""

    def __init__(self, name: str, kernel: Any, inputs: Sequence[Input], output: tuple[int, ...],
                 parameters: Sequence[Parameter] = (), singular: bool = False) -> None:
        self.name, self.kernel, self.output = name, kernel, tuple(output)
        self.inputs, self.parameters, self.singular = tuple(inputs), tuple(parameters), singular
        self.overflow: str | None = None
        self._widths = tuple(math.prod(i.shape) for i in self.inputs)
        self._width = math.prod(self.output)
        self.source = self._generate()
        self._loops: dict[str, Any] = {}
        self.single = self._single_element_path()

    def _generate(self) -> str:
        """Source of the serial loop over elements ``start..stop-1`` and the multi-core loop over pieces."""
        arrays = ", ".join(f"a{k}, s{k}" for k in range(len(self.inputs)))
        params = "".join(f"p{k}, " for k in range(len(self.parameters)))
        body, components, conditions = [], [], []
        for k, (item, width) in enumerate(zip(self.inputs, self._widths)):
            names = [f"x{k}_{c}" for c in range(width)]
            body.append(f"        j = uint64({width}) * (i * s{k})")
            body += [f"        {n} = a{k}[j + uint64({c})]" for c, n in enumerate(names)]
            components += names
            conditions.append(item.kind.condition(names))
        results = [f"r{c}" for c in range(self._width)]
        arguments = ", ".join(components + [f"p{k}" for k in range(len(self.parameters))])
        body.append(f"        {', '.join(results)}{',' if self._width == 1 and self.output else ''} = kernel({arguments})")
        body.append(f"        j = uint64({self._width}) * i")
        body += [f"        out[j + uint64({c})] = {r}" for c, r in enumerate(results)]
        conditions.append((not_infinite_condition if self.singular else finite_condition)(results))
        body.append("        ok &= " + " & ".join(f"({c})" for c in conditions))
        name = self.name
        reads = [line for line in body if " = a" in line or line.startswith("        j = ") and "* s" in line]
        return "\n".join([
            f"def {name}_valid({arrays}, n):",
            "    ok = True",
            "    for i in range(n):",
            *reads,
            "        ok &= " + " & ".join(f"({c})" for c in conditions[:-1]),
            "    return ok",
            "",
            "",
            f"def {name}_serial({arrays}, {params}out, start, stop):",
            "    ok = True",
            "    for i in range(start, stop):",
            *body,
            "    return ok",
            "",
            "",
            f"def {name}_parallel({arrays}, {params}out, piece):",
            f"    n = uint64(out.size // {self._width})",
            "    flags = np.empty((n + piece - uint64(1)) // piece, np.bool_)",
            "    for c in prange(flags.size):",
            "        start = uint64(c) * piece",
            f"        flags[c] = {name}_serial({arrays}, {params}out, start, min(n, start + piece))",
            "    return flags.all()",
            "",
        ])

    def _single_element_path(self) -> Callable[..., NDArray[np.float64] | None]:
        """``single(inputs..., parameters...)``: the result for one element already in float64, else None.

        Generated like the loops, so that a call on one rotation spends its
        time in the kernel rather than in generic argument handling: the test
        of each input is one expression, the loop gets the arrays themselves
        (a one-dimensional C-contiguous input is its own flat view) and a
        flat result is returned as it is.
        """
        names = [f"x{k}" for k in range(len(self.inputs))]
        params = [f"p{k}" for k in range(len(self.parameters))]
        tests = [f"type({n}) is ndarray and {n}.dtype is float64 and {n}.shape == {i.shape!r} "
                 f"and {n}.flags.c_contiguous" for n, i in zip(names, self.inputs)]
        flats = [f"{n}, ZERO" if len(i.shape) == 1 else f"{n}.reshape(-1), ZERO" for n, i in zip(names, self.inputs)]
        result = "result" if len(self.output) == 1 else f"result.reshape({self.output!r})"
        source = "\n".join([
            f"def single({', '.join(names + params)}):",
            f"    if {' and '.join(tests)}:",
            f"        result = empty({self._width})",
            f"        if serial({', '.join(flats + params)}, result, ZERO, ONE):",
            f"            return {result}",
            "    return None",
            "",
            "",
            "def serial(*args):",  # replaced by the compiled loop on the first call
            "    loop = namespace['serial'] = compiled()",
            "    return loop(*args)",
        ])
        namespace: dict[str, Any] = {"ndarray": np.ndarray, "float64": np.dtype(np.float64), "empty": np.empty,
                                     "ZERO": _ZERO, "ONE": _ONE, "compiled": lambda: self._loop("serial")}
        namespace["namespace"] = namespace
        exec(compile(source, f"<kreisel single element of {self.name}>", "exec"), namespace)
        return cast(Callable[..., "NDArray[np.float64] | None"], namespace["single"])

    def _loop(self, variant: str) -> Any:
        """The compiled serial or parallel loop (compiled or loaded from the cache on first use)."""
        loop = self._loops.get(variant)
        if loop is None:
            namespace: dict[str, Any] = {"__name__": __name__, "kernel": self.kernel, "np": np, "prange": prange,
                                          "uint64": types.uint64}
            exec(compile(self.source, f"<kreisel loops of {self.name}>", "exec"), namespace)
            flat_in = types.Array(types.float64, 1, "C", readonly=True)
            args = [t for _ in self.inputs for t in (flat_in, types.uint64)]
            args += [p.type for p in self.parameters]
            args.append(types.Array(types.float64, 1, "C"))
            serial = njit(nogil=True, error_model="numpy")(namespace[f"{self.name}_serial"])
            cache.attach(serial).compile(types.boolean(*args, types.uint64, types.uint64))
            serial.disable_compile()
            if variant == "valid":
                valid = njit(nogil=True, error_model="numpy")(namespace[f"{self.name}_valid"])
                cache.attach(valid).compile(types.boolean(*args[:2 * len(self.inputs)], types.uint64))
                valid.disable_compile()
                loop = valid
            elif variant == "serial":
                loop = serial
            else:
                namespace[f"{self.name}_serial"] = serial
                parallel = njit(parallel=True, error_model="numpy")(namespace[f"{self.name}_parallel"])
                cache.attach(parallel).compile(types.boolean(*args, types.uint64))
                parallel.disable_compile()
                loop = parallel
            self._loops[variant] = loop
        return loop

    def __call__(self, *args: Any, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """The operation of the inputs, then the parameters, positionally; ``out`` as documented."""
        count = len(self.inputs)
        if out is None and len(args) == count + len(self.parameters):
            single = self.single(*args)
            if single is not None:
                return single
        arrays: list[NDArray[np.float64]] = []
        for x, item in zip(args[:count], self.inputs):
            try:
                arrays.append(as_float_array(x, item.name, item.shape, finite=False))
            except (TypeError, ValueError):
                self._checked(arrays)  # the refusal of checking each argument in turn
                raise
        parameters = args[count:]
        batch = _broadcast([a.shape[: a.ndim - len(i.shape)] for a, i in zip(arrays, self.inputs)])
        shape = (*batch, *self.output)
        if out is not None:
            check_out(out, shape)
            if not self._run(arrays, parameters, batch, None):
                arrays = self._checked(arrays)
        result = np.empty(shape) if out is None else out
        if self._run(arrays, parameters, batch, result):
            return result
        if out is None:
            arrays = self._checked(arrays)
            if self._run(arrays, parameters, batch, result):
                return result
        if self.overflow is not None:
            raise ValueError(self.overflow)
        names = [i.name for i in self.inputs]
        subject = names[0] + " is" if len(names) == 1 else ", ".join(names[:-1]) + f" and {names[-1]} are"
        raise ValueError(f"{subject} out of range for {self.name}: the result overflows (beyond the largest "
                         "double, about 1.8e308)")

    def renamed(self, **names: str) -> ArrayOperation:
        """This operation with inputs renamed in its refusals (``v="vectors"``); the compiled loops are shared."""
        other = copy.copy(self)
        other.inputs = tuple(dataclasses.replace(i, name=names.get(i.name, i.name)) for i in self.inputs)
        return other

    def refusing(self, message: str) -> ArrayOperation:
        """This operation with ``message`` as its refusal of an overflowing result; the compiled loops are shared."""
        other = copy.copy(self)
        other.overflow = message
        return other

    def _checked(self, arrays: list[NDArray[np.float64]]) -> list[NDArray[np.float64]]:
        """The inputs after their full checks (which raise naming the argument)."""
        return [i.kind.check(a, i.name) for a, i in zip(arrays, self.inputs)]

    def _run(self, arrays: list[NDArray[np.float64]], parameters: tuple[Any, ...], batch: tuple[int, ...],
             result: NDArray[np.float64] | None) -> bool:
        """Fill ``result`` (shape ``batch + output``); whether every element passed its checks.

        With ``result`` None, only the inputs are checked.
        """
        n = math.prod(batch)
        if n == 0:
            return True
        contiguous = result is None or result.flags.c_contiguous
        flat_out = np.empty(0) if result is None else result.reshape(-1) if contiguous else np.empty(result.size)
        flat: list[Any] = []
        for a, item in zip(arrays, self.inputs):
            elements = math.prod(a.shape[: a.ndim - len(item.shape)])
            if elements != n and elements != 1:
                a, elements = np.broadcast_to(a, (*batch, *item.shape)), n
            a = np.ascontiguousarray(a).reshape(-1)
            if np.may_share_memory(a, flat_out) and not (
                    a.ctypes.data == flat_out.ctypes.data and a.size == flat_out.size and elements == n):
                a = a.copy()
            flat += [a, _ONE if elements == n else _ZERO]
        if result is None:
            return bool(self._loop("valid")(*flat, np.uint64(n)))
        if n >= PARALLEL_THRESHOLD:
            ok = self._loop("parallel")(*flat, *parameters, flat_out, np.uint64(PIECE))
        else:
            ok = self._loop("serial")(*flat, *parameters, flat_out, _ZERO, np.uint64(n))
        if not contiguous:
            result[...] = flat_out.reshape(result.shape)
        return bool(ok)


def _broadcast(batches: list[tuple[int, ...]]) -> tuple[int, ...]:
    """Broadcast batch shape (ValueError naming the shapes if there is none)."""
    first = batches[0]
    if all(b == first for b in batches):
        return first
    try:
        return tuple(np.broadcast_shapes(*batches))
    except ValueError:
        raise ValueError("the inputs' batch shapes " + ", ".join(map(str, batches))
                         + " do not broadcast together") from None


#: Every declared operation, by name: what tests and readers walk.
REGISTRY: dict[str, ArrayOperation] = {}


def declare(kernel: Any, inputs: Sequence[Input], output: tuple[int, ...], parameters: Sequence[Parameter] = (),
            name: str | None = None, singular: bool = False) -> ArrayOperation:
    """Declare an array operation (registered in :data:`REGISTRY` under ``name``, by default the kernel's).

    ``singular``: the kernel returns NaN where its result is undefined (a
    coordinate singularity that the caller reports), which is then a result,
    not a refusal; only infinite results are refused.
    """
    name = name or kernel.py_func.__name__.lstrip("_")
    if name in REGISTRY:
        raise ValueError(f"an array operation named {name} is declared already")
    operation = REGISTRY[name] = ArrayOperation(name, kernel, inputs, output, parameters, singular)
    return operation


def elementwise(kernel: Any, inputs: Sequence[Input], output: tuple[int, ...],
                parameters: Sequence[Parameter] = ()) -> Callable[[_F], _F]:
    """Make a public array function of a signature-and-docstring stub and :func:`declare`.

    The stub names the inputs, then the parameters, and takes a keyword-only
    ``out=None``; its body is its docstring, whose Parameters section gets
    the standard ``out`` entry. The function returned calls the declared
    operation; its ``__operation__`` is the declaration.

    Examples
    --------
    >>> from kreisel._compiled.checks import VECTOR
    >>> @kernel
    ... def _doubled(x, y, z):
    ...     return 2.0 * x, 2.0 * y, 2.0 * z
    >>> @elementwise(_doubled, [Input("v", (3,), VECTOR)], (3,))
    ... def doubled_vectors(v, *, out=None):
    ...     '''Twice ``v``.
    ...
    ...     Examples
    ...     --------
    ...     >>> doubled_vectors([1.0, 2.0, 3.0])
    ...     '''
    >>> doubled_vectors([[1.0, 2.0, 3.0], [0.5, 0.0, -1.0]])
    array([[ 2.,  4.,  6.],
           [ 1.,  0., -2.]])
    """

    def build(stub: _F) -> _F:
        wanted = [i.name for i in inputs] + [p.name for p in parameters]
        signature = inspect.signature(stub)
        positional = [p.name for p in signature.parameters.values() if p.kind is not p.KEYWORD_ONLY]
        if positional != wanted or "out" not in signature.parameters:
            raise TypeError(f"{stub.__name__} must take ({', '.join(wanted)}, *, out=None), got {signature}")
        operation = declare(kernel, inputs, output, parameters, name=stub.__name__)

        defaults = [signature.parameters[n].default for n in wanted]

        single, count = operation.single, len(wanted)

        @functools.wraps(stub)
        def function(*args: Any, out: NDArray[np.float64] | None = None, **keywords: Any) -> NDArray[np.float64]:
            if out is None and not keywords and len(args) == count:
                result = single(*args)
                if result is not None:
                    return result
            if keywords or len(args) > count:
                bound = signature.bind(*args, out=out, **keywords)
                args = tuple(bound.arguments.get(n, d) for n, d in zip(wanted, defaults))
            elif len(args) < count:
                if any(d is inspect.Parameter.empty for d in defaults[len(args):]):
                    signature.bind(*args, out=out)
                args = (*args, *defaults[len(args):])
            return operation(*args, out=out)

        if function.__doc__ is not None:
            function.__doc__ = with_out_entry(function.__doc__)
        function.__operation__ = operation  # type: ignore[attr-defined]
        return cast(_F, function)  # functools.wraps(stub): the stub's signature, the declaration's work

    return build


def uses(operation: ArrayOperation) -> Callable[[_F], _F]:
    """Mark a public function that prepares its arguments and calls ``operation`` (``__operation__``)."""

    def mark(function: _F) -> _F:
        function.__operation__ = operation  # type: ignore[attr-defined]
        return function

    return mark


__all__ = ["ArrayOperation", "Input", "Kind", "PARALLEL_THRESHOLD", "Parameter", "REGISTRY", "declare",
           "elementwise", "finite_condition", "kernel", "not_infinite_condition", "uses"]

