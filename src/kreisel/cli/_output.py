"""What the ``kreisel`` command prints: plain text on rich consoles, errors, notices and progress.

Every string a command prints may hold the user's text (a file name, a
scenario title, a representation typed on the command line), so it goes
through :func:`plain`: rich reads neither markup (``[bold]``) nor emoji codes
(``:zzz:``) in it. rich is imported on first use, not with the module, so that
``kreisel --help`` does not load it.
"""

from __future__ import annotations

import contextlib
import functools

import typer

__all__ = ["COMPILING", "console", "plain", "say", "error_line", "usage_error", "note", "compile_notice",
           "progress"]

#: The notice printed (once, on standard error) when a command compiles kernels missing from the cache.
COMPILING = "compiling kreisel's kernels for this machine (first run only; `kreisel compile` does it ahead of time)"


@functools.cache
def console(stderr=False):
    """The rich console of standard output (standard error with ``stderr``), made on first use.

    Emoji codes are off: ``euler:ZZZ:`` is text, not a sleeping face.
    """
    from rich.console import Console

    return Console(stderr=stderr, highlight=False, emoji=False)


def plain(text):
    """``text`` as a rich Text, printed as it is: no markup, no emoji codes, no highlighting."""
    from rich.text import Text

    return Text(str(text))


def say(text):
    """Print ``text`` on standard output as it is."""
    console().print(plain(text), soft_wrap=True)


def note(text):
    """Print ``text`` on standard error as it is (what a command tells besides its results)."""
    console(stderr=True).print(plain(text), soft_wrap=True)


def error_line(message):
    """Print ``message`` on standard error after a red "error:"."""
    from rich.text import Text

    console(stderr=True).print(Text.assemble(("error:", "bold red"), " ", str(message)), soft_wrap=True)


def usage_error(message):
    """Print ``message`` as one line and exit with status 2."""
    error_line(message)
    raise typer.Exit(2)


@contextlib.contextmanager
def compile_notice():
    """Within the block, say :data:`COMPILING` once when numba compiles what the on-disk cache does not hold.

    numba announces each compilation (a miss of the cache, not a load from
    it) with its ``numba:compile`` event; the listener is removed after the
    block.
    """
    from numba.core import event

    class Notice(event.Listener):
        said = False

        def on_start(self, _):
            if not self.said:
                self.said = True
                note(COMPILING)

        def on_end(self, _):
            pass

    with event.install_listener("numba:compile", Notice()):
        yield


def progress():
    """A transient rich progress bar on standard error (a task's description, bar, percentage, times), or None.

    None where standard error is no terminal: piped, rich would leave an
    empty line where the bar was. Descriptions are text, not markup.
    """
    err = console(stderr=True)
    if not err.is_terminal:
        return None
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    columns = (TextColumn("{task.description}", markup=False), BarColumn(),
               TextColumn("{task.percentage:>3.0f} %"), TimeElapsedColumn(), TimeRemainingColumn())
    return Progress(*columns, console=err, transient=True)
