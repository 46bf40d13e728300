"""Parameter sweeps in chunks on Dask, with retries, checkpoints and resumption.

A sweep evaluates ``function(**chunk_parameters, **constants)`` over the outer
product of 1-D parameter arrays (the grid). The grid is flattened in C order
and cut into chunks of ``chunk_size`` points; each chunk is one task. The
function receives, for every grid parameter, a 1-D array with the values of
the chunk's points, and returns a mapping ``{variable: array}`` whose first
axis runs over those points (trailing axes are allowed). The chunks are
assembled into an :class:`xarray.Dataset` with one dimension per grid
parameter, in the grid's order.

Where the chunks run (``scheduler=``):

``None``
    A :class:`distributed.LocalCluster` of worker *processes* (one thread
    each) started for the sweep and closed after it.
``"tcp://host:8786"``
    An existing Dask scheduler; the workers must be able to import kreisel
    and the sweep function.
a :class:`distributed.Client`
    Used as is and left open.
``"serial"``
    In the calling process, no Dask (the reference the distributed run must
    reproduce exactly, and the baseline for the Dask overhead).

Robustness: a chunk whose task raises (or whose worker died too often,
``KilledWorker``) is resubmitted up to ``retries`` times, each failure is
reported to the progress callback; chunks still failing are listed in a
:class:`SweepError` raised after every other chunk has finished. A worker that
dies mid-task is replaced by the nanny and its task rerun by the scheduler.
Finished chunks are written, as they arrive, to a checkpoint directory by
the client process (so the workers need no shared file system); a sweep
started again with the same function, grid, constants and chunk size loads
them instead of computing them again.
"""

from __future__ import annotations

import collections
import collections.abc
import contextlib
import dataclasses
import functools
import hashlib
import inspect
import json
import logging
import math
import os
import pathlib
import pickle
import shutil
import types
import uuid
import warnings
import zipfile

import numpy as np

from .._fileio import atomic_output, remove_stale_temporaries, temporary_prefix
from .._optional import require

__all__ = ["SweepError", "SweepProgress", "write_dataset", "sweep", "SERIAL"]

SERIAL = "serial"
_CHECKPOINT_META = "sweep.json"
_OUTPUT_SUFFIXES = (".zarr", ".nc")


class SweepError(RuntimeError):
    """Chunks that still failed after their retries.

    Attributes
    ----------
    failures : dict
        ``{chunk index: exception}`` of the chunks that failed for good.
    """

    def __init__(self, message, failures):
        super().__init__(message)
        self.failures = failures


@dataclasses.dataclass(frozen=True)
class SweepProgress:
    """One event of a running sweep, passed to the ``progress`` callback.

    ``event`` is ``"resumed"`` (chunk loaded from the checkpoint), ``"discarded"``
    (its checkpoint file was unreadable or made by other code, and it is computed
    again), ``"done"``,
    ``"retry"`` (the chunk failed and was resubmitted) or ``"failed"`` (no
    retries left); ``done`` counts the chunks finished so far (resumed ones
    included) out of ``total``; ``message`` describes a failure.

    Examples
    --------
    A ``progress`` callback receives one event per chunk:

    >>> from kreisel.sweep import lagrange_apex_locus
    >>> events = []
    >>> ds = sweep(lagrange_apex_locus, {"phi_dot": [0.0, 2.0], "psi_dot": [10.0]}, chunk_size=1,
    ...            scheduler="serial", progress=events.append)
    >>> [(e.event, e.done, e.total) for e in events]
    [('done', 1, 2), ('done', 2, 2)]
    """

    event: str
    chunk: int
    done: int
    total: int
    message: str = ""


# ---- grid ------------------------------------------------------------------------------
def _check_grid(grid, constants):
    if not isinstance(grid, collections.abc.Mapping) or not grid:
        raise TypeError(f"grid must be a non-empty mapping {{name: 1-D values}}, got {type(grid).__name__}")
    out = {}
    for name, values in grid.items():
        if not isinstance(name, str) or not name.isidentifier():
            raise ValueError(f"grid: parameter names must be Python identifiers, got {name!r}")
        array = np.asarray(values)
        if array.ndim != 1 or array.size == 0 or array.dtype.kind not in "iuf":
            raise ValueError(f"grid[{name!r}] must be a non-empty 1-D array of numbers, got {values!r}")
        if not np.all(np.isfinite(array)):
            raise ValueError(f"grid[{name!r}] must be finite")
        out[name] = array
    clash = sorted(set(out) & set(constants))
    if clash:
        raise ValueError(f"constants: {clash[0]!r} is also a grid parameter")
    return out


def _chunk_parameters(grid, shape, lo, hi):
    """Values of every grid parameter at the flat (C-order) points lo..hi-1."""
    index = np.unravel_index(np.arange(lo, hi), shape)
    return {name: values[i] for (name, values), i in zip(grid.items(), index)}


def _run_chunk(function, parameters, constants):
    """Evaluate one chunk (runs on a worker) and check the shape of what came back."""
    result = function(**parameters, **constants)
    count = len(next(iter(parameters.values())))
    if not isinstance(result, collections.abc.Mapping) or not result:
        raise TypeError(f"the sweep function must return a non-empty mapping {{name: array}}, "
                        f"got {type(result).__name__}")
    out = {}
    for name, value in result.items():
        array = np.asarray(value)
        if array.ndim < 1 or array.shape[0] != count:
            raise ValueError(f"sweep function result {name!r}: first axis must be the {count} points of the "
                             f"chunk, got shape {array.shape}")
        out[str(name)] = array
    return out


# ---- identity and checkpoint ------------------------------------------------------------
def _describe_function(function):
    if isinstance(function, functools.partial):
        return f"{_describe_function(function.func)}(*{function.args!r}, **{sorted(function.keywords.items())!r})"
    owner = function if hasattr(function, "__qualname__") else type(function)
    return f"{owner.__module__}.{owner.__qualname__}"


def _code_digest(code, digest):
    """Feed what a code object computes (bytecode, constants, names, nested code) into ``digest``."""
    digest.update(code.co_code)
    digest.update(repr(code.co_names).encode())
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            _code_digest(const, digest)
        else:
            digest.update(repr(const).encode())


def _state_digest(value, digest):
    try:
        digest.update(pickle.dumps(value, protocol=4))
    except Exception:  # an unpicklable closure value or attribute: its type is all that can be told
        digest.update(type(value).__qualname__.encode())


def _code_fingerprint(function):
    """Hash of the code and bound values that decide what ``function`` returns.

    The source of the function and of its whole module (helpers it calls), or the bytecode where no
    source exists; its defaults and closure values; a partial's arguments; a callable object's state.
    """
    digest = hashlib.sha256()
    if isinstance(function, functools.partial):
        digest.update(_code_fingerprint(function.func).encode())
        _state_digest((function.args, sorted(function.keywords.items())), digest)
        return digest.hexdigest()
    function = getattr(function, "py_func", function)  # a numba dispatcher: its Python function
    if not isinstance(function, (types.FunctionType, types.MethodType)):
        _state_digest(getattr(function, "__dict__", None), digest)
        function = type(function).__call__
    function = getattr(function, "__func__", function)
    try:
        digest.update(inspect.getsource(inspect.getmodule(function) or function).encode())
        digest.update(inspect.getsource(function).encode())
    except (OSError, TypeError):  # defined in an interactive session or by exec: no source to read
        pass
    code = getattr(function, "__code__", None)
    if code is not None:
        _code_digest(code, digest)
        _state_digest((function.__defaults__, function.__kwdefaults__), digest)
        for cell in function.__closure__ or ():
            try:
                _state_digest(cell.cell_contents, digest)
            except ValueError:  # an empty cell
                pass
    return digest.hexdigest()


def _sweep_key(function, grid, constants, chunk_size):
    """(what is swept, what computes it): the function's name, grid, constants and chunking; and the
    code that determines each chunk's result, with kreisel's version."""
    from .._version import __version__

    digest = hashlib.sha256()
    digest.update(_describe_function(function).encode())
    for name, values in grid.items():
        digest.update(name.encode())
        digest.update(str(values.dtype).encode())
        digest.update(np.ascontiguousarray(values).tobytes())
    digest.update(repr(sorted(constants.items())).encode())
    digest.update(str(chunk_size).encode())
    return digest.hexdigest(), f"kreisel {__version__}, code {_code_fingerprint(function)[:16]}"


class _Checkpoint:
    """Finished chunks as ``chunk-NNNNNN.npz`` files next to a ``sweep.json`` naming the sweep.

    ``key`` is (what is swept, what computes it) from :func:`_sweep_key`. Chunks of the same sweep made
    by other code (the function was edited, kreisel was upgraded) are deleted and listed by :meth:`load`
    among the discarded ones; a checkpoint of another sweep is refused.
    """

    def __init__(self, directory, key, description):
        self.directory = pathlib.Path(directory)
        self.outdated = {}
        sweep_key, code = key
        meta = self.directory / _CHECKPOINT_META
        if meta.exists():
            stored = json.loads(meta.read_text(encoding="utf-8"))
            if stored.get("key") != sweep_key:
                raise ValueError(f"checkpoint: {str(self.directory)!r} holds chunks of a different sweep "
                                 f"({stored.get('description', '?')}); remove it or choose another directory")
            if stored.get("code") == code:
                return
            for path in sorted(self.directory.glob("chunk-*.npz")):
                self.outdated[int(path.stem.split("-")[1])] = (
                    f"checkpoint file {path.name} was computed by other code ({stored.get('code', 'unknown')}; "
                    f"now {code}); computing the chunk again")
                path.unlink()
        else:
            if not self.directory.parent.is_dir():
                raise ValueError(f"checkpoint: directory {str(self.directory.parent)!r} does not exist")
            self.directory.mkdir(exist_ok=True)
        with atomic_output(meta) as tmp:
            tmp.write_text(json.dumps({"key": sweep_key, "code": code, "description": description}),
                           encoding="utf-8")

    def _path(self, chunk):
        return self.directory / f"chunk-{chunk:06d}.npz"

    def load(self, n_chunks, sink=None):
        """``({chunk: arrays}, {chunk: why it was discarded})`` of the chunk files on disk.

        A chunk file that cannot be read whole (empty, truncated, corrupted by a
        crash of the disk or of another program) is deleted, so that its chunk
        is computed again. With ``sink``, each chunk read is handed to
        ``sink(chunk, arrays)`` and not kept (its value in the mapping is None).
        """
        found, discarded = {}, dict(self.outdated)
        for chunk in range(n_chunks):
            path = self._path(chunk)
            if not path.exists():
                continue
            try:
                with np.load(path, allow_pickle=False) as data:
                    found[chunk] = {name: data[name] for name in data.files}
                if not found[chunk]:
                    raise ValueError("it holds no arrays")
            except (OSError, ValueError, EOFError, KeyError, zipfile.BadZipFile) as exc:
                found.pop(chunk, None)
                size = path.stat().st_size
                discarded[chunk] = (f"checkpoint file {path.name} ({size} bytes) is unreadable "
                                    f"({type(exc).__name__}: {exc or 'empty'}); computing the chunk again")
                path.unlink(missing_ok=True)
                continue
            if sink is not None:
                sink(chunk, found[chunk])
                found[chunk] = None
        return found, discarded

    def save(self, chunk, result):
        with atomic_output(self._path(chunk)) as tmp:
            with open(tmp, "wb") as fh:  # a file object: np.savez would append ".npz" to a name
                np.savez(fh, **result)

    def remove(self):
        shutil.rmtree(self.directory, ignore_errors=True)


# ---- executors ---------------------------------------------------------------------------
class _SerialExecutor:
    """Runs chunks one after another in this process, in submission order."""

    def __init__(self):
        self.queue = collections.deque()

    def submit(self, chunk, function, parameters, constants):
        self.queue.append((chunk, function, parameters, constants))

    def completed(self):
        while self.queue:
            chunk, function, parameters, constants = self.queue.popleft()
            try:
                yield chunk, _run_chunk(function, parameters, constants), None
            except Exception as exc:  # noqa: BLE001 -- any failure of user code is retried and reported
                yield chunk, None, exc


class _DaskExecutor:
    """Submits chunks to a distributed client and yields them as they complete."""

    def __init__(self, client, key):
        as_completed = require("distributed", extra="sweep", feature="kreisel.sweep").as_completed
        self.client = client
        self.key = key[:12]
        self.futures = {}
        self.attempt = collections.Counter()
        self.pending = as_completed()

    def submit(self, chunk, function, parameters, constants):
        self.attempt[chunk] += 1
        future = self.client.submit(_run_chunk, function, parameters, constants, pure=False,
                                    key=f"kreisel-sweep-{self.key}-{chunk}-{self.attempt[chunk]}")
        self.futures[future.key] = chunk
        self.pending.add(future)

    def completed(self):
        for future in self.pending:
            chunk = self.futures.pop(future.key)
            if future.status == "finished":
                result, error = future.result(), None
            else:
                result, error = None, future.exception()
            future.release()
            yield chunk, result, error


@dataclasses.dataclass
class _Session:
    executor: object
    close: object


def _open_session(scheduler, n_workers, threads_per_worker, key):
    if scheduler == SERIAL:
        return _Session(_SerialExecutor(), lambda: None)
    distributed = require("distributed", extra="sweep", feature="kreisel.sweep")
    Client, LocalCluster = distributed.Client, distributed.LocalCluster
    if isinstance(scheduler, Client):
        return _Session(_DaskExecutor(scheduler, key), lambda: None)
    if scheduler is None:
        workers = n_workers if n_workers is not None else min(2, os.cpu_count() or 1)
        # numba's parallel loops must not start a thread per core in every worker: one per Dask thread
        cluster = LocalCluster(n_workers=workers, threads_per_worker=threads_per_worker, processes=True,
                               dashboard_address=None, env={"NUMBA_NUM_THREADS": str(threads_per_worker)})
        client = Client(cluster)

        def close():
            client.close()
            # every task is done: a worker process slow to exit (numba and Dask to tear down on a loaded
            # machine) is killed after 4 s, which the nanny would log as a warning the user can do nothing about
            nanny = logging.getLogger("distributed.nanny")
            level = nanny.level
            nanny.setLevel(logging.ERROR)
            try:
                cluster.close()
            finally:
                nanny.setLevel(level)
        return _Session(_DaskExecutor(client, key), close)
    client = Client(scheduler)
    return _Session(_DaskExecutor(client, key), client.close)


def _check_scheduler(scheduler, n_workers, threads_per_worker):
    if scheduler is not None and scheduler != SERIAL and not isinstance(scheduler, str):
        if not isinstance(scheduler, require("distributed", extra="sweep", feature="kreisel.sweep").Client):
            raise TypeError(f"scheduler must be None, 'serial', an address string or a distributed.Client, "
                            f"got {type(scheduler).__name__}")
    for name, value in (("n_workers", n_workers), ("threads_per_worker", threads_per_worker)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
            raise ValueError(f"{name} must be a positive integer, got {value!r}")
    if n_workers is not None and scheduler is not None:
        raise ValueError("n_workers applies to the LocalCluster started when scheduler is None")


# ---- progress ------------------------------------------------------------------------------
class _Reporter:
    """Forwards events to the user's callback and to a rich progress bar."""

    def __init__(self, callback, console, total, title):
        self.callback, self.console, self.total, self.done = callback, console, total, 0
        self.bar = None
        if console is not None:
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

            self.bar = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                                TimeRemainingColumn(), console=console)
            self.task = self.bar.add_task(title, total=total)
            self.bar.start()

    def __call__(self, event, chunk, message=""):
        if event in ("done", "resumed"):
            self.done += 1
            if self.bar is not None:
                self.bar.update(self.task, completed=self.done)
        elif self.bar is not None:
            from rich.markup import escape

            self.bar.console.print(f"[yellow]chunk {chunk}: {event}[/yellow] {escape(str(message))}")
        if self.callback is not None:
            self.callback(SweepProgress(event, chunk, self.done, self.total, message))

    def close(self):
        if self.bar is not None:
            self.bar.stop()


# ---- assembly and output --------------------------------------------------------------------
def _check_chunk_variables(chunk, result, layout):
    """Refuse a chunk whose variables or trailing shapes differ from ``layout`` (the first chunk's)."""
    if set(result) != set(layout):
        raise ValueError(f"sweep function returned variables {sorted(result)} for chunk {chunk} but "
                         f"{sorted(layout)} for chunk 0")
    for name, array in result.items():
        if array.shape[1:] != layout[name][0]:
            raise ValueError(f"sweep function result {name!r}: trailing shape {array.shape[1:]} in chunk "
                             f"{chunk} differs from {layout[name][0]} in chunk 0")


def _assemble(grid, shape, chunk_size, results, variable_attrs, attrs):
    xr = require("xarray", extra="sweep", feature="kreisel.sweep")
    first = results[0]
    total = math.prod(shape)
    data = {}
    for name, array in first.items():
        data[name] = np.empty((total,) + array.shape[1:], dtype=array.dtype)
    layout = {name: (array.shape[1:], array.dtype) for name, array in first.items()}
    for chunk, result in results.items():
        _check_chunk_variables(chunk, result, layout)
        lo = chunk * chunk_size
        for name, array in result.items():
            data[name][lo:lo + array.shape[0]] = array
    dims = tuple(grid)
    variables = {}
    for name, flat in data.items():
        extra = tuple(f"{name}_dim_{i}" for i in range(flat.ndim - 1))
        variables[name] = xr.Variable(dims + extra, flat.reshape(shape + flat.shape[1:]),
                                      attrs=dict(variable_attrs.get(name, {})))
    return xr.Dataset(variables, coords={name: values for name, values in grid.items()}, attrs=attrs)


def sweep_needs(scheduler, output):
    """The ``(module, extra)`` pairs a sweep on ``scheduler`` writing ``output`` imports.

    In the form :func:`kreisel._optional.require_all` takes.

    Examples
    --------
    >>> sweep_needs(SERIAL, None), sweep_needs(None, "out.zarr")[-1]
    ([('xarray', 'sweep')], ('zarr', 'sweep'))
    """
    zarr = output is not None and pathlib.Path(output).suffix == ".zarr"
    return [(module, "sweep") for module, needed in (("xarray", True), ("distributed", scheduler != SERIAL),
                                                     ("zarr", zarr)) if needed]


def _check_output(output):
    if output is None:
        return None
    output = pathlib.Path(output)
    if output.suffix not in _OUTPUT_SUFFIXES:
        raise ValueError(f"output must end in .zarr or .nc, got {str(output)!r}")
    if not output.parent.is_dir():
        raise ValueError(f"output: directory {str(output.parent)!r} does not exist")
    return output


def write_dataset(dataset, output):
    """Write ``dataset`` to ``output`` (``.zarr`` directory or ``.nc`` file), replacing it atomically.

    NetCDF goes through a temporary file renamed onto the target. A Zarr store
    is a directory: it is written next to the target, then swapped in by two
    renames (the old store, if any, is moved aside first and deleted after),
    so readers never see a half-written store.

    Examples
    --------
    >>> import tempfile, pathlib, xarray as xr
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "a.nc"
    >>> write_dataset(xr.Dataset({"x": ("i", [1.0, 2.0])}), path)
    >>> float(xr.open_dataset(path).x.sum())
    3.0
    """
    output = _check_output(output)
    if output.suffix == ".nc":
        with atomic_output(output) as tmp:
            dataset.to_netcdf(tmp)
        return
    require("zarr", extra="sweep", feature="kreisel.sweep")
    with _zarr_store(output) as tmp:
        dataset.to_zarr(tmp, mode="w", zarr_format=2, consolidated=True)  # v2 + consolidated: widest reader support


@contextlib.contextmanager
def _zarr_store(output):
    """Yield a temporary store path next to ``output``; swap it in when the block succeeds.

    Two renames (the old store, if any, is moved aside first and deleted
    after), so readers never see a half-written store.
    """
    remove_stale_temporaries(output)  # stores left by a killed write
    tag = uuid.uuid4().hex[:8]
    tmp = output.with_name(f"{temporary_prefix(output)}{tag}.tmp")
    old = output.with_name(f"{temporary_prefix(output)}{tag}.old")
    try:
        yield tmp
        if output.exists():
            os.replace(output, old)
        os.replace(tmp, output)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
        shutil.rmtree(old, ignore_errors=True)


def _flat_blocks(lo, hi, shape):
    """Cover the C-order flat points ``lo … hi-1`` of a grid of ``shape`` by rectangular blocks.

    Yields ``(region, start, count)``: a tuple of slices, one per axis, and
    the block's first point (counted from ``lo``) and number of points; a
    block's points are consecutive in C order. At most two blocks per axis.

    Examples
    --------
    >>> [(tuple((r.start, r.stop) for r in region), start, count)
    ...  for region, start, count in _flat_blocks(2, 9, (3, 4))]
    [(((0, 1), (2, 4)), 0, 2), (((1, 2), (0, 4)), 2, 4), (((2, 3), (0, 1)), 6, 1)]
    """
    if len(shape) == 1:
        if lo < hi:
            yield (slice(lo, hi),), 0, hi - lo
        return
    stride = math.prod(shape[1:])
    row, done = lo // stride, 0
    if lo % stride:  # the partial first row (perhaps also the last)
        end = min(hi, (row + 1) * stride)
        for region, start, count in _flat_blocks(lo - row * stride, end - row * stride, shape[1:]):
            yield (slice(row, row + 1),) + region, start, count
        row, done = row + 1, end - lo
    whole = max(0, (hi - row * stride) // stride)
    if whole:
        yield (slice(row, row + whole),) + tuple(slice(0, n) for n in shape[1:]), done, whole * stride
        row, done = row + whole, done + whole * stride
    if lo + done < hi:  # the partial last row
        for region, start, count in _flat_blocks(0, hi - row * stride, shape[1:]):
            yield (slice(row, row + 1),) + region, start + done, count


class _ZarrStream:
    """A sweep's ``.zarr`` output written chunk by chunk as the chunks arrive (``stream=True``).

    The store at ``path`` is laid out on the first chunk (its variables'
    trailing shapes and dtypes); each chunk is written into its part of every
    variable and dropped, so memory holds about one chunk whatever the
    sweep's size. A Zarr chunk spans about ``chunk_size`` grid points, so
    writing a sweep chunk reads and rewrites at most a few of them.
    """

    def __init__(self, path, grid, shape, chunk_size, variable_attrs, attrs):
        self.path, self.grid, self.shape, self.chunk_size = path, grid, shape, chunk_size
        self.variable_attrs, self.attrs = variable_attrs, attrs
        self.layout = self.group = None

    def _lay_out(self, first):
        xr = require("xarray", extra="sweep", feature="kreisel.sweep")
        dask_array = require("dask.array", extra="sweep", feature="kreisel.sweep")
        self.layout = {name: (array.shape[1:], array.dtype) for name, array in first.items()}
        grid_chunks, points = [], 1
        for n in reversed(self.shape):  # C order: whole trailing axes while they fit in chunk_size points
            size = max(1, min(n, self.chunk_size // points))
            grid_chunks.insert(0, size)
            points *= size
        variables = {}
        for name, (trailing, dtype) in self.layout.items():
            dims = tuple(self.grid) + tuple(f"{name}_dim_{i}" for i in range(len(trailing)))
            data = dask_array.zeros(self.shape + trailing, dtype=dtype, chunks=tuple(grid_chunks) + trailing)
            variables[name] = xr.Variable(dims, data, attrs=dict(self.variable_attrs.get(name, {})))
        template = xr.Dataset(variables, coords=dict(self.grid), attrs=self.attrs)
        template.to_zarr(self.path, mode="w", zarr_format=2, consolidated=False, compute=False)
        self.group = require("zarr", extra="sweep", feature="kreisel.sweep").open_group(self.path, mode="r+")

    def write(self, chunk, result):
        """Write the arrays of sweep chunk ``chunk`` into their places in the store."""
        if self.layout is None:
            self._lay_out(result)
        _check_chunk_variables(chunk, result, self.layout)
        lo = chunk * self.chunk_size
        for region, start, count in _flat_blocks(lo, lo + len(next(iter(result.values()))), self.shape):
            block = tuple(r.stop - r.start for r in region)
            for name, array in result.items():
                self.group[name][region] = array[start:start + count].reshape(block + array.shape[1:])

    def close(self):
        """Consolidate the metadata (one read opens the store)."""
        require("zarr", extra="sweep", feature="kreisel.sweep").consolidate_metadata(self.path)


def _default_checkpoint(output):
    return None if output is None else output.with_name(output.name + ".chunks")


def _chunk_label(parameters):
    return ", ".join(f"{name} {values.min():g}..{values.max():g}" for name, values in parameters.items())


# ---- the sweep ---------------------------------------------------------------------------------
def sweep(function, grid, *, constants=None, chunk_size=256, scheduler=None, n_workers=None,
          threads_per_worker=1, output=None, checkpoint=None, keep_checkpoint=False, retries=2,
          progress=None, console=None, variable_attrs=None, attrs=None, stream=False):
    """Evaluate ``function`` over a parameter grid in chunks, on Dask by default.

    Parameters
    ----------
    function : callable
        ``function(**parameters, **constants) -> {name: array}``; each grid
        parameter arrives as a 1-D array of the chunk's points, each result's
        first axis runs over those points. Must be picklable (a module-level
        function or a :func:`functools.partial` of one) unless ``scheduler``
        is ``"serial"``.
    grid : mapping of str to 1-D array_like
        Parameter values; the sweep covers their outer product, and the
        dataset's dimensions follow this order.
    constants : mapping, optional
        Keyword arguments passed unchanged to every call.
    chunk_size : int
        Grid points per task (default 256).
    scheduler : None, str or distributed.Client
        Where to run (see the module docstring): a new ``LocalCluster`` of
        worker processes (default), a scheduler address, a client, or
        ``"serial"``.
    n_workers : int, optional
        Worker processes of the default ``LocalCluster`` (default
        ``min(2, cpu count)``).
    threads_per_worker : int
        Threads per worker of the default ``LocalCluster`` (default 1).
    output : str or path, optional
        ``.zarr`` or ``.nc`` file written atomically when the sweep succeeds.
    checkpoint : str or path, optional
        Directory keeping finished chunks (default ``<output>.chunks`` when
        ``output`` is given, otherwise none). An existing checkpoint of the
        same sweep is resumed; one of another sweep is refused.
    keep_checkpoint : bool
        Keep the checkpoint directory after success (default: remove it).
    retries : int
        Resubmissions of a failing chunk before it is given up (default 2).
    progress : callable, optional
        Called with a :class:`SweepProgress` after every chunk event.
    console : rich.console.Console, optional
        Show a progress bar and failure messages on this console.
    variable_attrs : mapping, optional
        ``{variable: {attribute: value}}`` (units, long names) for the dataset.
    attrs : mapping, optional
        Global attributes of the dataset (strings or numbers).
    stream : bool
        For sweeps too large for memory: write each chunk into the ``.zarr``
        ``output`` as it arrives (resumed chunks likewise) and keep none in
        memory, which then holds about one chunk whatever the sweep's size.
        The store is swapped in when the sweep succeeds, as without
        ``stream``; the returned dataset reads it lazily (dask arrays) and
        holds the same values as the in-memory sweep's.

    Returns
    -------
    xarray.Dataset
        One variable per result name, dimensions = grid parameters (+ trailing
        ``<name>_dim_<i>`` axes), coordinates = the grid values.

    Raises
    ------
    SweepError
        Chunks that failed after their retries (the finished ones stay in
        the checkpoint).

    Examples
    --------
    >>> import numpy as np
    >>> def product(x, y, scale):
    ...     return {"z": scale * x * y}
    >>> ds = sweep(product, {"x": [1.0, 2.0], "y": [1.0, 10.0, 100.0]}, constants={"scale": 2.0},
    ...            chunk_size=4, scheduler="serial")
    >>> ds.z.dims, ds.z.values.tolist()
    (('x', 'y'), [[2.0, 20.0, 200.0], [4.0, 40.0, 400.0]])
    """
    if not callable(function):
        raise TypeError(f"function must be callable, got {type(function).__name__}")
    constants = dict(constants or {})
    grid = _check_grid(grid, constants)
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size must be a positive integer, got {chunk_size!r}")
    if isinstance(retries, bool) or not isinstance(retries, (int, np.integer)) or retries < 0:
        raise ValueError(f"retries must be a non-negative integer, got {retries!r}")
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable, got {type(progress).__name__}")
    _check_scheduler(scheduler, n_workers, threads_per_worker)
    output = _check_output(output)
    if not isinstance(stream, bool):
        raise TypeError(f"stream must be True or False, got {type(stream).__name__}")
    if stream and (output is None or output.suffix != ".zarr"):
        raise ValueError("stream=True writes the chunks into a .zarr output as they arrive: pass output='….zarr'")
    # what the run needs, checked before any chunk is computed
    for module, extra in sweep_needs(scheduler, output):
        require(module, extra=extra, feature="kreisel.sweep")
    chunk_size = int(chunk_size)
    shape = tuple(values.size for values in grid.values())
    total = math.prod(shape)
    n_chunks = -(-total // chunk_size)
    key = _sweep_key(function, grid, constants, chunk_size)
    description = f"{_describe_function(function)} over {' x '.join(f'{n}[{v.size}]' for n, v in grid.items())}"
    directory = checkpoint if checkpoint is not None else _default_checkpoint(output)
    store = _Checkpoint(directory, key, description) if directory is not None else None

    meta = {"sweep_function": _describe_function(function), "sweep_constants": json.dumps(constants, default=repr),
            "sweep_chunk_size": chunk_size, "sweep_chunks": n_chunks, **(attrs or {})}
    with contextlib.ExitStack() as finish:
        sink = None
        if stream:
            sink = _ZarrStream(finish.enter_context(_zarr_store(output)), grid, shape, chunk_size,
                               variable_attrs or {}, meta)
        results, discarded = store.load(n_chunks, sink and sink.write) if store is not None else ({}, {})
        if discarded and console is None:  # the console shows each discarded chunk; a library caller is warned
            warnings.warn(f"checkpoint: discarded {len(discarded)} of the chunks in {str(store.directory)!r} (first: "
                          f"{discarded[min(discarded)]})", stacklevel=2)
        report = _Reporter(progress, console, n_chunks, description)
        failures = {}
        try:
            for chunk, message in sorted(discarded.items()):
                report("discarded", chunk, message)
            for chunk in sorted(results):
                report("resumed", chunk)
            todo = [chunk for chunk in range(n_chunks) if chunk not in results]
            if todo:
                session = _open_session(scheduler, n_workers, threads_per_worker,
                                        hashlib.sha256("".join(key).encode()).hexdigest())
                try:
                    parameters = {chunk: _chunk_parameters(grid, shape, chunk * chunk_size,
                                                           min(total, (chunk + 1) * chunk_size)) for chunk in todo}
                    for chunk in todo:
                        session.executor.submit(chunk, function, parameters[chunk], constants)
                    failed_attempts = collections.Counter()
                    for chunk, result, error in session.executor.completed():
                        if error is None:
                            if store is not None:
                                store.save(chunk, result)
                            if sink is not None:  # written now, not kept
                                sink.write(chunk, result)
                                result = None
                            results[chunk] = result
                            report("done", chunk)
                            continue
                        failed_attempts[chunk] += 1
                        message = (f"({_chunk_label(parameters[chunk])}) attempt {failed_attempts[chunk]}: "
                                   f"{type(error).__name__}: {error}")
                        if failed_attempts[chunk] <= retries:
                            report("retry", chunk, message)
                            session.executor.submit(chunk, function, parameters[chunk], constants)
                        else:
                            failures[chunk] = error
                            report("failed", chunk, message)
                finally:
                    session.close()
        finally:
            report.close()
        if failures:
            first = min(failures)
            raise SweepError(f"{len(failures)} of {n_chunks} chunks failed after {retries} retries "
                             f"(first: chunk {first}, {type(failures[first]).__name__}: {failures[first]}); "
                             + ("finished chunks are kept in " + str(store.directory) if store is not None
                                else "pass checkpoint= to keep finished chunks"), failures)
        if sink is not None:
            sink.close()
    if stream:
        dataset = require("xarray", extra="sweep", feature="kreisel.sweep").open_zarr(output)
    else:
        dataset = _assemble(grid, shape, chunk_size, results, variable_attrs or {}, meta)
        if output is not None:
            write_dataset(dataset, output)
    if store is not None and not keep_checkpoint:
        store.remove()
    return dataset
