"""Output files of the commands: refused before any work when they could not be written, then written."""

from __future__ import annotations

import contextlib
import os

import typer

from ._output import error_line, say, usage_error

__all__ = ["FIGURES", "FORCE_HELP", "check_output", "check_outputs_in", "writing"]

#: The figure formats a command's ``--plot`` or ``-o`` writes.
FIGURES = (".png", ".svg", ".pdf")
FORCE_HELP = "Replace existing output files (without it, an existing one is refused before any work)."


def check_output(option, target, force, suffixes=(), store=False):
    """Refuse, before any work, an output the command could not write or would replace unasked.

    A suffix not in ``suffixes`` (any case; none: any suffix), a missing or
    read-only directory, a directory in a file's place, and an existing file
    without ``--force`` are usage errors naming the option and the file, so
    that nothing the user had is replaced unless they say so; the writes
    themselves stay atomic (the old file is replaced only by a complete new
    one). ``store``: the output is a Zarr store, a directory, which
    ``--force`` replaces only if it is one.
    """
    if target is None:
        return
    if suffixes and target.suffix.lower() not in suffixes:
        usage_error(f"{option}: unsupported output {target.name!r} (expected {', '.join(suffixes)})")
    if not target.parent.is_dir():
        usage_error(f"{option}: directory {str(target.parent)!r} does not exist")
    if target.is_dir() and not (store and _is_zarr_store(target)):
        usage_error(f"{option}: {str(target)!r} is a directory; name a file to write"
                    if not store else f"{option}: {str(target)!r} is a directory but not a Zarr store; "
                                      "name a new .zarr to write")
    if os.path.lexists(target) and not force:
        usage_error(f"{option}: {str(target)!r} already exists; pass --force to replace it")
    _probe_directory(option, target)


def _probe_directory(option, target):
    """A directory the output's temporary file cannot be created in (read-only, no permission) is a usage error."""
    import tempfile

    from .._fileio import temporary_prefix

    try:
        fd, probe = tempfile.mkstemp(prefix=temporary_prefix(target), suffix=".probe", dir=target.parent)
    except OSError as exc:
        usage_error(f"{option}: cannot write in {str(target.parent)!r} ({exc.strerror or exc})")
    os.close(fd)
    os.unlink(probe)


@contextlib.contextmanager
def writing(option, target):
    """Write ``target`` in the block, then say so; an error of the file system (disk full) is one line, status 1."""
    try:
        yield
    except OSError as exc:
        error_line(f"{option}: cannot write {str(target)!r} ({exc.strerror or exc})")
        raise typer.Exit(1) from None
    say(f"wrote {target}")


def check_outputs_in(option, directory, names, force):
    """:func:`check_output` for the files ``names`` a command writes into ``directory`` (created if missing)."""
    if directory.is_dir():
        for name in names:
            check_output(option, directory / name, force)
    elif os.path.lexists(directory):
        usage_error(f"{option}: {str(directory)!r} is not a directory")


def _is_zarr_store(path):
    return any((path / name).is_file() for name in (".zgroup", ".zarray", "zarr.json"))
