"""Who may talk to the viewer, and how much they may send: an ASGI middleware in front of the app.

A local server is reachable from every web page the user opens: a page from another origin can open a
WebSocket to it (browsers do not apply the same-origin policy to WebSockets) and a domain that
re-resolves to 127.0.0.1 (DNS rebinding) can read its answers. :class:`Guard` therefore accepts a request
only when

- its ``Host`` header names the server itself: ``127.0.0.1``, ``localhost`` or ``[::1]`` (or the host it
  was started with), with the server's port when that is known; and
- its ``Origin`` header, when a browser sends one, is the server's own origin ``http://<that host>``.

Everything else is refused with 403 (HTTP) or a refused WebSocket handshake, before the app sees it.
Request bodies larger than ``max_body`` bytes are refused with 413 from their ``Content-Length`` alone,
or, for a chunked body without one, as soon as the bytes read pass the limit.
"""

from __future__ import annotations

import json

__all__ = ["host_name", "Refused", "Guard", "LOOPBACK", "WILDCARDS"]

LOOPBACK = ("127.0.0.1", "localhost", "[::1]")
WILDCARDS = ("0.0.0.0", "::", "")


def host_name(host):
    """``host`` as it appears in a ``Host`` header: IPv6 addresses in brackets, lower case.

    Examples
    --------
    >>> host_name("::1"), host_name("LocalHost")
    ('[::1]', 'localhost')
    """
    host = host.lower()
    return f"[{host}]" if ":" in host and not host.startswith("[") else host


class Refused(Exception):
    """A request the guard refuses: HTTP ``status`` and ``detail``."""

    def __init__(self, status, detail):
        super().__init__(detail)
        self.status, self.detail = status, detail


class Guard:
    """ASGI middleware: Host and Origin checks and a body-size limit (see the module docstring).

    Parameters
    ----------
    app : ASGI app
    host : str
        The interface the server listens on; its name is accepted besides the loopback names. A
        wildcard (``0.0.0.0``, ``::``) accepts any ``Host``, but still only same-origin browser requests.
    port : int, optional
        The server's port; ``None`` accepts any port (an app not yet bound, e.g. under a test client).
    max_body : int
        Largest request body in bytes.

    Examples
    --------
    >>> guard = Guard(None, port=8000)
    >>> guard.refusal({"host": "127.0.0.1:8000", "origin": "http://127.0.0.1:8000"}) is None
    True
    >>> guard.refusal({"host": "127.0.0.1:8000", "origin": "http://127.0.0.1:58771"})
    'origin http://127.0.0.1:58771 is not this server (http://127.0.0.1:8000)'
    >>> guard.refusal({"host": "rebound.example:8000"})
    'host rebound.example:8000 is not this server (127.0.0.1, localhost or [::1] on port 8000)'
    """

    def __init__(self, app, host="127.0.0.1", port=None, max_body=1_000_000):
        self.app = app
        self.any_host = host in WILDCARDS
        self.names = tuple(dict.fromkeys(LOOPBACK + (host_name(host),))) if not self.any_host else LOOPBACK
        self.port = port
        self.max_body = max_body

    def refusal(self, headers):
        """Why a request with (lower-case) ``headers`` is refused, or None when it is accepted."""
        host = headers.get("host", "").lower()
        name, _, port = host.rpartition(":") if not host.endswith("]") else (host, "", "")
        if not name:  # no port in the header
            name, port = host, ""
        good_port = self.port is None or port == str(self.port)
        if not self.any_host and not (name in self.names and good_port):
            where = ", ".join(self.names[:-1]) + f" or {self.names[-1]}"
            on = f" on port {self.port}" if self.port is not None else ""
            return f"host {host or '(none)'} is not this server ({where}{on})"
        origin = headers.get("origin")
        if origin is not None and origin.lower() != f"http://{host}":
            return f"origin {origin} is not this server (http://{host})"
        return None

    async def __call__(self, scope, receive, send):
        if scope["type"] not in ("http", "websocket"):
            return await self.app(scope, receive, send)
        headers = {key.decode("latin-1").lower(): value.decode("latin-1") for key, value in scope["headers"]}
        try:
            reason = self.refusal(headers)
            if reason is not None:
                raise Refused(403, f"refused: {reason}")
            if scope["type"] == "http":
                receive = await self._bounded(headers, receive)
        except Refused as refused:
            if scope["type"] == "websocket":
                # closing before the handshake is answered refuses it with HTTP 403
                await send({"type": "websocket.close", "code": 1008, "reason": refused.detail[:120]})
            else:
                await _reply(send, refused.status, refused.detail)
            return
        await self.app(scope, receive, send)

    async def _bounded(self, headers, receive):
        """``receive`` for a body within the limit; Refused (413) before reading more than the limit."""
        limit = self.max_body
        too_big = f"request body larger than {limit} bytes"
        length = headers.get("content-length")
        if length is not None:
            if not length.isdigit():
                raise Refused(400, f"Content-Length must be a number of bytes, got {length!r}")
            if int(length) > limit:
                raise Refused(413, too_big)
            return receive
        if "transfer-encoding" not in headers:
            return receive
        # a chunked body has no announced length: read it here, counting, and replay it to the app
        body, more = [], True
        size = 0
        while more:
            message = await receive()
            if message["type"] != "http.request":
                return _replay([message], receive)
            size += len(message.get("body", b""))
            if size > limit:
                raise Refused(413, too_big)
            body.append(message.get("body", b""))
            more = message.get("more_body", False)
        return _replay([{"type": "http.request", "body": b"".join(body), "more_body": False}], receive)


def _replay(messages, receive):
    """``messages`` first, then whatever ``receive`` gives (after the body: the client leaving)."""
    pending = list(messages)

    async def replayed():
        return pending.pop(0) if pending else await receive()

    return replayed


async def _reply(send, status, detail):
    body = json.dumps({"detail": detail}).encode()
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]})
    await send({"type": "http.response.body", "body": body})
