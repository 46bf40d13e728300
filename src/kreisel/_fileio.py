"""Atomic file output shared by every layer that writes files.

A file kreisel writes is either the complete new content or untouched: the
data go to a temporary file in the destination directory, are flushed to
disk (``fsync``), and the temporary file then replaces the destination in one
``os.replace`` (atomic on POSIX and Windows). After an error or Ctrl-C the
user's previous file is still there and no half-written file is left behind.

The written file gets the permissions any other program's output would: those
of the file it replaces, or ``0o666`` less the user's umask for a new file
(temporary files themselves are created private, ``0o600``).

A process killed outright (SIGKILL, power loss) cannot remove its temporary
file. Temporaries are named ``.NAME.kreisel-PID-RANDOM`` plus the suffix of
their destination ``NAME`` (writers that pick a format by suffix still see it); the next write to the same destination deletes those
whose writing process no longer runs on this machine, or that are older than
:data:`STALE_AFTER` seconds, so a killed write leaves nothing behind for long.
"""

from __future__ import annotations

import contextlib
import os
import pathlib
import re
import stat
import tempfile
import time

#: CF-convention labels (units, long_name) of every variable kreisel writes to NetCDF (xarray,
#: Panoply and ncview show them): those of a trajectory and of the Foucault and strapdown datasets.
CF_LABELS = {
    "time": ("s", "time"),
    "q": ("1", "attitude quaternion, body to space, scalar first"),
    "omega": ("rad/s", "angular velocity, body components"),
    "omega_space": ("rad/s", "angular velocity, space components"),
    "angular_momentum": ("kg m2/s", "angular momentum, space components"),
    "energy": ("J", "rotational kinetic energy"),
    "inertia": ("kg m2", "inertia tensor, body axes"),
    "position": ("m", "centre-of-mass position, space components"),
    "velocity": ("m/s", "centre-of-mass velocity, space components"),
    "swing_azimuth": ("rad", "swing-plane azimuth, counter-clockwise from east"),
    "tilt": ("rad", "string angle from the vertical"),
    "q_true": ("1", "true attitude quaternion, scalar first"),
    "q_estimate": ("1", "strapdown attitude quaternion, scalar first"),
    "attitude_error": ("rad", "attitude error rotation vector, body components"),
}


def cf_labelled(dataset):
    """A copy of the ``xarray.Dataset`` with CF ``units`` and ``long_name`` on the variables of :data:`CF_LABELS`.

    Examples
    --------
    >>> import xarray as xr
    >>> cf_labelled(xr.Dataset({"omega": ("time", [0.0, 1.0])}))["omega"].attrs
    {'units': 'rad/s', 'long_name': 'angular velocity, body components'}
    """
    dataset = dataset.copy()
    for name in list(dataset.variables):
        if name in CF_LABELS:
            units, long_name = CF_LABELS[name]
            dataset[name].attrs.update(units=units, long_name=long_name)
    return dataset


STALE_AFTER = 24 * 3600.0
"""Age in seconds after which a temporary of a killed write is deleted whatever its process id says."""

_TEMPORARY = re.compile(r"\.(?P<name>.+)\.kreisel-(?P<pid>\d+)-[A-Za-z0-9_]+(\.[^.]*)?")


def temporary_prefix(path):
    """Prefix of the temporary names of writes to ``path`` (this process), for ``mkstemp``/``mkdtemp``.

    Give the temporary the destination's suffix (see :func:`remove_stale_temporaries`).

    Examples
    --------
    >>> import os
    >>> temporary_prefix("out/traj.nc") == f".traj.nc.kreisel-{os.getpid()}-"
    True
    """
    return f".{pathlib.Path(path).name}.kreisel-{os.getpid()}-"


def remove_stale_temporaries(path, now=None):
    """Delete the temporaries of killed writes to ``path``; return the paths removed.

    A temporary is stale when the process that wrote it has ended (its id is
    not running) or when it is older than :data:`STALE_AFTER` seconds (the
    process id may have been reused, or it belongs to another machine sharing
    the directory). Directories (stores written in place of a file) are
    removed with their contents.

    Examples
    --------
    A temporary left by a process that no longer runs is removed; one of this
    process, still writing, is kept:

    >>> import pathlib, tempfile
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "map.png"
    >>> dead = target.with_name(".map.png.kreisel-999999999-x1.png")
    >>> alive = target.parent / (temporary_prefix(target) + "x2.png")
    >>> _ = dead.write_bytes(b"half"), alive.write_bytes(b"half")
    >>> [p.name for p in remove_stale_temporaries(target)], alive.exists()
    (['.map.png.kreisel-999999999-x1.png'], True)
    """
    import shutil

    path = pathlib.Path(path)
    now = time.time() if now is None else now
    removed = []
    try:
        candidates = list(path.parent.glob(f".{glob_escape(path.name)}.kreisel-*"))
    except OSError:
        return removed
    for candidate in candidates:
        match = _TEMPORARY.fullmatch(candidate.name)
        if match is None or match["name"] != path.name:
            continue
        try:
            age = now - candidate.lstat().st_mtime
        except OSError:
            continue
        if _running(int(match["pid"])) and age < STALE_AFTER:
            continue
        try:
            if candidate.is_dir() and not candidate.is_symlink():
                shutil.rmtree(candidate)
            else:
                candidate.unlink()
        except OSError:
            continue  # another process cleaned it up, or it is not ours to remove
        removed.append(candidate)
    return removed


def glob_escape(name):
    """``name`` with the glob metacharacters ``*?[`` made literal."""
    return re.sub(r"([*?\[])", r"[\1]", name)


def _running(pid):
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, OSError):
        return True  # exists but belongs to someone else, or cannot tell: keep it
    return True


def output_mode(path):
    """Permission bits for a file written to ``path``: those of the file it replaces, else 0o666 less the umask.

    Examples
    --------
    >>> import os, pathlib, tempfile
    >>> old = os.umask(0o022)
    >>> oct(output_mode(pathlib.Path(tempfile.mkdtemp()) / "new.txt"))
    '0o644'
    >>> _ = os.umask(old)
    """
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except OSError:
        return 0o666 & ~_umask()


def _umask():
    # reading the umask means setting it; /proc gives it without that race where available
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o077)
    os.umask(mask)
    return mask


def _fsync(path):
    """Flush ``path`` (a file, or every file of a directory tree) to disk."""
    path = pathlib.Path(path)
    files = [path] if not path.is_dir() else [p for p in path.rglob("*") if p.is_file()]
    for file in files:
        with open(file, "rb") as fh:
            os.fsync(fh.fileno())


def _fsync_directory(directory):
    """Make a rename in ``directory`` durable (POSIX; a no-op where directories cannot be opened)."""
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


@contextlib.contextmanager
def atomic_output(path):
    """Yield a temporary path; move it onto ``path`` when the block succeeds.

    The block writes the temporary file (or replaces it by a directory); it is
    flushed to disk, given the destination's permissions (see the module
    docstring) and renamed onto ``path``. Temporaries of earlier writes to
    ``path`` that were killed are removed first.

    Parameters
    ----------
    path : str or os.PathLike
        Final destination. Its directory must exist.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "out.txt"
    >>> with atomic_output(target) as tmp:
    ...     _ = tmp.write_text("done")
    >>> target.read_text()
    'done'
    """
    path = pathlib.Path(path)
    if not path.parent.is_dir():
        raise ValueError(f"path: directory {str(path.parent)!r} does not exist")
    remove_stale_temporaries(path)
    fd, tmp = tempfile.mkstemp(prefix=temporary_prefix(path), suffix=path.suffix or ".tmp", dir=path.parent)
    os.close(fd)
    tmp = pathlib.Path(tmp)
    try:
        yield tmp
        _fsync(tmp)
        if not tmp.is_dir():
            os.chmod(tmp, output_mode(path))
        os.replace(tmp, path)
        _fsync_directory(path.parent)
    finally:
        tmp.unlink(missing_ok=True)
