"""Slow and many connections: request headers time out, connections are capped, a flood is logged once."""

import logging
import socket

import httpx
import pytest

from kreisel.web import create_app
from kreisel.web.connections import http_protocol, max_connections

from .conftest import RELAXED, authorization, free_port, served

HEADER_SECONDS = 1.0
CAP = 50
HALF_SENT = 200


class _Log(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.messages = []

    def emit(self, record):
        self.messages.append(record.getMessage())


def _closed_by_server(sock):
    """Wait (at most 30 s) for the server to close ``sock``; True when it did."""
    sock.settimeout(30)
    try:
        return sock.recv(1024) == b""
    except ConnectionResetError:
        return True
    except TimeoutError:
        return False


@pytest.fixture(scope="module")
def besieged():
    """A viewer with a short header timeout and a small connection cap: (URL, port, app, log)."""
    port = free_port()
    app = create_app(port=port, limits=RELAXED)
    log = _Log()
    with served(app, port, header_seconds=HEADER_SECONDS, max_connections=CAP) as url:
        logging.getLogger("uvicorn.error").addHandler(log)  # after the server configured its logging
        try:
            yield url, port, app, log
        finally:
            logging.getLogger("uvicorn.error").removeHandler(log)


def test_half_sent_requests_are_closed_and_the_viewer_still_answers(besieged):
    # the reproducer: requests whose headers never end used to stay open forever, and enough of them
    # took every file descriptor of the process
    url, port, app, log = besieged
    partial = f"GET /api/methods HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Slow: ".encode()
    socks = []
    try:
        for _ in range(HALF_SENT):
            sock = socket.create_connection(("127.0.0.1", port), timeout=30)
            socks.append(sock)
            try:
                sock.sendall(partial)
            except (BrokenPipeError, ConnectionResetError):
                pass  # beyond the cap: closed before it sent anything
        assert all(_closed_by_server(sock) for sock in socks)
    finally:
        for sock in socks:
            sock.close()
    answer = httpx.get(url + "api/methods", headers=authorization(app), timeout=30)
    assert answer.status_code == 200 and "rk4" in answer.json()
    floods = [m for m in log.messages if "connections at once" in m]
    assert len(floods) == 1, log.messages
    assert any(f"the flood is over ({HALF_SENT - CAP} connections were refused)" in m for m in log.messages), \
        log.messages


def test_headers_sent_a_byte_at_a_time_do_not_keep_a_connection(besieged):
    url, port, _, _ = besieged
    request = f"GET /api/methods HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n".encode() + b"X-Slow: " + b"a" * 1000
    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        sock.settimeout(0.05)
        sent = 0
        try:
            for byte in request:
                sock.sendall(bytes([byte]))
                sent += 1
                try:
                    if sock.recv(1024) == b"":
                        break
                except TimeoutError:
                    continue
        except (BrokenPipeError, ConnectionResetError):
            pass
    # each byte waits 50 ms for an answer: the whole request would take 50 s, ten times the limit
    assert sent < len(request)


def test_a_kept_alive_connection_waits_no_longer_for_its_next_request(besieged):
    url, port, app, _ = besieged
    token = app.state.viewer.token
    head = f"GET /api/methods HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nAuthorization: token {token}\r\n"
    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        sock.sendall((head + "\r\n").encode())
        answer = b""
        while b"rk4" not in answer:
            answer += sock.recv(65536)
        assert answer.startswith(b"HTTP/1.1 200")
        sock.sendall(head.encode())  # the next request, never finished
        assert _closed_by_server(sock)


def test_protocol_options_are_checked():
    assert 8 <= max_connections() <= 1000
    with pytest.raises(ValueError, match="header_seconds"):
        http_protocol(0.0)
