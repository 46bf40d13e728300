"""The ``kreisel`` command as a user runs it: ``python -m kreisel`` in a subprocess, on this tree's package."""

import os
import pathlib
import subprocess
import sys

import pytest

import kreisel as kr
from kreisel.cli._output import COMPILING

SRC = pathlib.Path(kr.__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def kreisel():
    """``kreisel(*args, cwd=None, stdin=None, env=None)``: run ``python -m kreisel ARGS``; the completed process.

    Output is text; ``stdin`` is text fed to standard input; ``env`` adds to or overrides the caller's environment,
    in which ``PYTHONPATH`` points at this tree's package and ``COLUMNS=200`` keeps help and tables unwrapped.
    """

    def run(*args, cwd=None, stdin=None, env=None):
        environment = dict(os.environ, PYTHONPATH=str(SRC), COLUMNS="200")
        environment.update(env or {})
        return subprocess.run([sys.executable, "-m", "kreisel", *map(str, args)], cwd=cwd, env=environment,
                              input=stdin, capture_output=True, text=True, timeout=600)

    return run


@pytest.fixture(scope="session")
def usage_error():
    """``usage_error(process, *fragments)``: assert a refusal as the user sees it.

    Exit status 2, no traceback, and on standard error one ``error:`` line naming every fragment (a first run's
    compile notice aside).
    """

    def check(process, *fragments):
        assert process.returncode == 2, (process.stdout, process.stderr)
        assert "Traceback" not in process.stderr
        lines = [line for line in process.stderr.strip().splitlines() if line != COMPILING]
        assert len(lines) == 1 and lines[0].startswith("error: "), process.stderr
        for fragment in fragments:
            assert fragment in lines[0], (fragment, lines[0])

    return check


@pytest.fixture
def serve(interrupt):
    """``with serve(*args, cwd=...) as (url, token)``: ``kreisel serve ARGS --port 0 --no-browser`` running.

    ``url`` is the printed address without its query, ``token`` the ``?token=...`` query it carries; the server is
    stopped as Ctrl+C stops it when the block ends.
    """
    import contextlib
    import re

    @contextlib.contextmanager
    def running(*args, cwd=None):
        server = subprocess.Popen([sys.executable, "-m", "kreisel", "serve", *map(str, args), "--port", "0",
                                   "--no-browser"], cwd=cwd, env=dict(os.environ, PYTHONPATH=str(SRC)),
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            found = next(filter(None, (re.search(r"(http://127\.0\.0\.1:\d+/)(\?token=[\w-]+)", line)
                                       for line in server.stdout)), None)
            assert found, "kreisel serve did not print its URL"
            yield found.groups()
        finally:
            interrupt(server, 60)

    return running
