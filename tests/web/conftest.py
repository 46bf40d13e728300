import threading
import time

import pytest


@pytest.fixture(scope="module")
def live_url():
    """The viewer served by uvicorn on a free loopback port in a background thread."""
    from kreisel.web import create_app
    from kreisel.web.server import bind, make_server, url_of

    sock = bind("127.0.0.1", 0)
    server = make_server(create_app())
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    deadline = time.monotonic() + 60
    while not server.started:
        if time.monotonic() > deadline or not thread.is_alive():
            raise RuntimeError("uvicorn did not start")
        time.sleep(0.05)
    yield url_of(sock)
    server.should_exit = True
    thread.join(timeout=30)
    sock.close()
