import contextlib
import socket
import threading
import time

import pytest

from kreisel.web.runner import Limits

# the first run of a test session may compile the integrators (numba) inside a worker: no time limit bites
RELAXED = Limits(wall_seconds=900.0, queue_seconds=900.0)


@pytest.fixture(scope="module")
def app_client():
    """A factory of test clients that talk to the app as its own page would (Host 127.0.0.1); their run
    workers end with the module."""
    from fastapi.testclient import TestClient

    from kreisel.web import create_app

    class Local(TestClient):
        def websocket_connect(self, url, *args, headers=None, **kwargs):
            # the test client names itself "testserver" on WebSockets whatever its base_url
            return super().websocket_connect(url, *args, headers={"host": "127.0.0.1", **self.token,
                                                                  **(headers or {})}, **kwargs)

    apps = []

    def make(*args, limits=RELAXED, **kwargs):
        app = create_app(*args, limits=limits, **kwargs)
        apps.append(app)
        client = Local(app, base_url="http://127.0.0.1", headers=authorization(app))
        client.token = authorization(app)
        return client

    yield make
    for app in apps:
        app.state.viewer.runner.close()


def authorization(app):
    """The header that gives ``app``'s token, as a script would send it (none when it has no token)."""
    token = app.state.viewer.token
    return {"Authorization": f"token {token}"} if token else {}


def start_server(app, sock, **options):
    """Run ``app`` with uvicorn on ``sock`` in a background thread (``options`` of ``make_server``); the server
    and its thread."""
    from kreisel.web.server import make_server

    server = make_server(app, **options)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    deadline = time.monotonic() + 60
    while not server.started:
        if time.monotonic() > deadline or not thread.is_alive():
            raise RuntimeError("uvicorn did not start")
        time.sleep(0.05)
    return server, thread


@contextlib.contextmanager
def served(app, port, **options):
    """``app`` served by uvicorn on loopback ``port`` (``options`` of ``make_server``): its base URL."""
    from kreisel.web.server import bind, url_of

    sock = bind("127.0.0.1", port)
    server, thread = start_server(app, sock, **options)
    try:
        yield url_of(sock)
    finally:
        server.should_exit = True
        thread.join(timeout=30)
        sock.close()
        app.state.viewer.runner.close()


def free_port():
    """A loopback port nobody listens on now (an app must know its port before it is served)."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@pytest.fixture(scope="module")
def live_server():
    """The viewer served by uvicorn on a free loopback port in a background thread: (url, app)."""
    from kreisel.web import create_app
    from kreisel.web.server import bind, url_of

    sock = bind("127.0.0.1", 0)
    app = create_app(port=sock.getsockname()[1], limits=RELAXED)
    server, thread = start_server(app, sock)
    yield url_of(sock), app
    server.should_exit = True
    thread.join(timeout=30)
    sock.close()
    app.state.viewer.runner.close()


@pytest.fixture(scope="module")
def live_url(live_server):
    """The URL a browser opens: with the server's token, as ``kreisel serve`` prints it."""
    url, app = live_server
    return f"{url}?token={app.state.viewer.token}"
