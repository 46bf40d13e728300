"""Run the viewer with uvicorn: a socket bound first so that port 0 can pick a free port."""

from __future__ import annotations

import socket
import threading
import urllib.parse
import webbrowser

from .._optional import require
from .connections import HEADER_SECONDS, http_protocol
from .guard import WILDCARDS

__all__ = ["bind", "websocket_support", "make_server", "url_of", "serve"]


def bind(host="127.0.0.1", port=0):
    """A listening TCP socket on ``host:port`` (port 0: a free port chosen by the system)."""
    if not isinstance(port, int) or not 0 <= port <= 65535:
        raise ValueError(f"port must be an integer in 0..65535, got {port!r}")
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
    except OSError as exc:
        sock.close()
        raise ValueError(f"cannot listen on {host}:{port} ({exc.strerror})") from None
    sock.listen(128)
    return sock


def websocket_support():
    """Whether uvicorn can serve WebSockets here (it needs the ``websockets`` or ``wsproto`` package).

    Without one, ``/api/stream`` cannot be reached and the page falls back to one-shot JSON runs.
    """
    import importlib.util

    return any(importlib.util.find_spec(name) is not None for name in ("websockets", "wsproto"))


def make_server(app, header_seconds=HEADER_SECONDS, max_connections=None):
    """A uvicorn server for ``app``; run it with ``.run(sockets=[sock])`` on a socket from :func:`bind`.

    WebSocket messages are limited to the app's body limit, so a huge run request is refused by uvicorn
    before it is buffered. A request's headers must arrive within ``header_seconds``, and at most
    ``max_connections`` connections are held at once (default
    :func:`kreisel.web.connections.max_connections`): see :mod:`kreisel.web.connections`.
    """
    uvicorn = require("uvicorn", extra="viewer", feature="the viewer (kreisel serve)")
    limits = getattr(getattr(app.state, "viewer", None), "limits", None)
    size = {"ws_max_size": limits.max_body} if limits is not None else {}
    return uvicorn.Server(uvicorn.Config(app, log_level="warning", lifespan="off",
                                         http=http_protocol(header_seconds, max_connections), **size))


def url_of(sock, token=None, host=None):
    """The viewer's address on ``sock`` (by ``host``, default its address), with ``?token=`` when it has a ``token``.

    A wildcard address is given as the loopback address: a browser on this machine reaches it there.
    """
    address, port = sock.getsockname()[:2]
    host = host or {"0.0.0.0": "127.0.0.1", "::": "::1"}.get(address, address)
    query = f"?token={urllib.parse.quote(token, safe='')}" if token else ""
    return f"http://{'[' + host + ']' if ':' in host else host}:{port}/{query}"


def serve(scenario=None, host="127.0.0.1", port=0, open_browser=True, recording=None, token=None, allow_hosts=()):
    """Serve the viewer until interrupted; prints its URL and optionally opens a browser.

    Parameters
    ----------
    scenario : str or path-like, optional
        A scenario TOML file, or the name of a bundled one (``kreisel examples``), shown first (checked
        before the server starts).
    host : str
        Interface to listen on; the default keeps the viewer private to this machine. Only requests
        that name this host (or a loopback name) with the server's port, from the server's own pages,
        are answered (``kreisel.web.guard``); a wildcard such as ``0.0.0.0`` makes the viewer
        reachable from other machines (by this machine's names and addresses) and prints a warning.
    port : int
        TCP port; 0 picks a free one.
    open_browser : bool
        Open the default web browser at the URL once the server listens.
    recording : str or path-like, optional
        A recording (see :func:`kreisel.io.read_imu`) shown first: one with an accelerometer and a reference
        attitude (BROAD's motion capture) replays kreisel's estimated attitude beside the reference, with
        the error angle; any other is fitted with the free top (see ``kreisel fit``).
    token : str, optional
        The secret every request must carry; by default a random one, in the URL printed and opened
        (the page keeps it in a cookie). ``""``: no token, any local process may use the viewer.
    allow_hosts : sequence of str
        More names by which the viewer may be reached (e.g. a name this machine has on the network).

    Examples
    --------
    Bad input is refused before any socket is opened or server started (a real
    call blocks until Ctrl+C, so only refusals are shown here):

    >>> serve(port=70000, open_browser=False)
    Traceback (most recent call last):
        ...
    ValueError: port must be an integer in 0..65535, got 70000
    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "spin.toml")
    >>> with open(path, "w") as fh:
    ...     _ = fh.write("[body]\\nmoment = [1.0, 2.0, 3.0]\\n")
    >>> serve(path, open_browser=False)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    kreisel.io.scenario.ScenarioError: ...: body.moment: unknown key (expected one of: ...)
    """
    from .app import create_app
    from .session import MAX_SAMPLES, load

    require("uvicorn", extra="viewer", feature="the viewer (kreisel serve)")  # before any work

    text = None
    if scenario is not None:
        from ..io.bundled import scenario_path
        from ..io.scenario import ScenarioError
        from ..io.schema import read_text

        # a file, or a bundled scenario's name, read as `kreisel simulate` reads it
        try:
            path = scenario_path(scenario)
        except FileNotFoundError as exc:
            raise ValueError(str(exc)) from None
        text = read_text(path, ScenarioError, "scenario")
        load(text, path=path)
    data = None
    if recording is not None:
        from ..io.gyro import GyroFileError, read_gyro

        try:
            data = read_gyro(recording)
        except OSError as exc:
            raise ValueError(f"recording: cannot read {recording} ({exc.strerror or exc})") from None
        except GyroFileError as exc:
            raise ValueError(f"recording: {exc}") from None
    sock = bind(host, port)
    try:
        app = create_app(text, host=host, port=sock.getsockname()[1], recording=data, token=token,
                         allow_hosts=allow_hosts)
    except (TypeError, ValueError):
        sock.close()
        raise
    url = url_of(sock, app.state.viewer.token)
    server = make_server(app)
    if host in WILDCARDS:
        print(f"warning: --host {host} serves the viewer to every machine that can reach this one (by this "
              "machine's names and addresses, and --allow-host names); "
              + ("whoever has the URL below" if app.state.viewer.token else "anyone on the network")
              + " can run simulations on it. Use the default 127.0.0.1 unless you mean that.", flush=True)
    print(f"kreisel viewer at {url}  (Ctrl+C to stop)", flush=True)
    if host in WILDCARDS:
        print(f"  from other machines: {url_of(sock, app.state.viewer.token, socket.gethostname())}", flush=True)
    if not websocket_support():
        print("note: runs are not streamed (install the `websockets` package); each comes in one reply of at "
              f"most {MAX_SAMPLES} samples", flush=True)
    if open_browser:
        threading.Timer(0.5, webbrowser.open, args=(url,)).start()
    try:
        server.run(sockets=[sock])
    finally:
        sock.close()
        app.state.viewer.runner.close()
