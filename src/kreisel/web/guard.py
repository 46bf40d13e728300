"""Who may talk to the viewer, and how much they may send: an ASGI middleware in front of the app.

A local server is reachable from every web page the user opens: a page from another origin can open a
WebSocket to it (browsers do not apply the same-origin policy to WebSockets) and a domain that
re-resolves to the server's address (DNS rebinding) can read its answers; and every local user or process
can connect to it. :class:`Guard` therefore accepts a request only when

- its ``Host`` header names the server itself, with the server's port when that is known: ``127.0.0.1``,
  ``localhost`` or ``[::1]``, the host it was started with, names the user allowed, and, on a wildcard
  interface (``0.0.0.0``), this machine's names and the address the request arrived at: never a foreign
  domain, whatever it resolves to;
- its ``Origin`` header, when a browser sends one, is the server's own origin ``http://<that host>``; and
- it carries the server's token (when it has one), as Jupyter asks: ``?token=...`` in the URL (the answer
  then sets a cookie, which the page's own requests and WebSockets send), the cookie, or an
  ``Authorization: token ...`` header.

Everything else is refused with 403 (HTTP) or a refused WebSocket handshake, before the app sees it.
Request bodies larger than ``max_body`` bytes are refused with 413 from their ``Content-Length`` alone,
or, for a chunked body without one, as soon as the bytes read pass the limit.
"""

from __future__ import annotations

import hmac
import json
import socket
import urllib.parse

__all__ = ["host_name", "machine_names", "cookie_name", "Refused", "Guard", "LOOPBACK", "WILDCARDS"]

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


def machine_names():
    """This machine's names and the addresses they resolve to, as ``Host`` headers name them.

    What a user on the network types to reach a viewer listening on every interface (``0.0.0.0``).
    """
    names = {socket.gethostname()}
    names.add(socket.getfqdn(next(iter(names))))
    names |= {name + ".local" for name in list(names) if "." not in name}
    addresses = set()
    for name in names:
        try:
            addresses |= {info[4][0] for info in socket.getaddrinfo(name, None)}
        except OSError:
            continue
    return tuple(host_name(n) for n in sorted(names | addresses) if n)


def cookie_name(port):
    """The token cookie of the server on ``port``: browsers share cookies across a host's ports."""
    return "kreisel-token" if port is None else f"kreisel-token-{port}"


class Refused(Exception):
    """A request the guard refuses: HTTP ``status`` and ``detail``."""

    def __init__(self, status, detail):
        super().__init__(detail)
        self.status, self.detail = status, detail


class Guard:
    """ASGI middleware: Host, Origin and token checks and a body-size limit (see the module docstring).

    Parameters
    ----------
    app : ASGI app
    host : str
        The interface the server listens on; its name is accepted besides the loopback names. On a
        wildcard (``0.0.0.0``, ``::``) this machine's names (:func:`machine_names`) and the address a
        request arrived at are accepted too.
    port : int, optional
        The server's port; ``None`` accepts any port (an app not yet bound, e.g. under a test client).
    max_body : int
        Largest request body in bytes.
    token : str, optional
        The secret every request must carry; ``None`` or ``""``: none needed.
    allow_hosts : sequence of str
        More names (or addresses) the ``Host`` header may give, e.g. a name this machine has on the network.

    Examples
    --------
    >>> guard = Guard(None, port=8000)
    >>> guard.refusal({"host": "127.0.0.1:8000", "origin": "http://127.0.0.1:8000"}) is None
    True
    >>> guard.refusal({"host": "127.0.0.1:8000", "origin": "http://127.0.0.1:58771"})
    'origin http://127.0.0.1:58771 is not this server (http://127.0.0.1:8000)'
    >>> guard.refusal({"host": "rebound.example:8000"})
    'host rebound.example:8000 is not this server (127.0.0.1, localhost or [::1] on port 8000)'
    >>> Guard(None, port=8000, token="s3cret").refusal({"host": "localhost:8000"})
    'this viewer needs its token: open the URL that kreisel serve printed (with ?token=...)'
    """

    def __init__(self, app, host="127.0.0.1", port=None, max_body=1_000_000, token=None, allow_hosts=()):
        self.app = app
        self.any_host = host in WILDCARDS
        local = machine_names() if self.any_host else (host_name(host),)
        self.names = tuple(dict.fromkeys(LOOPBACK + local + tuple(host_name(h) for h in allow_hosts)))
        self.port = port
        self.max_body = max_body
        self.token = token or None
        self.cookie = cookie_name(port)

    def refusal(self, headers, query=b"", server=None):
        """Why a request with (lower-case) ``headers`` is refused, or None when it is accepted.

        ``query`` is its query string and ``server`` the address it arrived at (ASGI's ``scope["server"]``).
        """
        host = headers.get("host", "").lower()
        name, _, port = host.rpartition(":") if not host.endswith("]") else (host, "", "")
        if not name:  # no port in the header
            name, port = host, ""
        good_port = self.port is None or port == str(self.port)
        # on a wildcard the address the client connected to is this machine's: an address names no domain
        arrived = self.any_host and server is not None and name == host_name(server[0])
        if not ((name in self.names or arrived) and good_port):
            shown = self.names if len(self.names) <= 6 else self.names[:5] + ("...",)
            where = ", ".join(shown[:-1]) + f" or {shown[-1]}"
            on = f" on port {self.port}" if self.port is not None else ""
            return f"host {host or '(none)'} is not this server ({where}{on})"
        origin = headers.get("origin")
        if origin is not None and origin.lower() != f"http://{host}":
            return f"origin {origin} is not this server (http://{host})"
        if self.token is not None and not self.carries_token(headers, query):
            return "this viewer needs its token: open the URL that kreisel serve printed (with ?token=...)"
        return None

    def carries_token(self, headers, query=b""):
        """Whether a request with ``headers`` and query string ``query`` gives the server's token."""
        given = []
        scheme, _, value = headers.get("authorization", "").partition(" ")
        if scheme.lower() in ("token", "bearer"):
            given.append(value.strip())
        cookies = [part.strip().partition("=") for part in headers.get("cookie", "").split(";")]
        given += [value for key, _, value in cookies if key == self.cookie]
        given += urllib.parse.parse_qs(query.decode("latin-1")).get("token", [])
        # constant time: a wrong guess learns nothing from how long the refusal took
        return any(hmac.compare_digest(value.encode(), self.token.encode()) for value in given)

    async def __call__(self, scope, receive, send):
        if scope["type"] not in ("http", "websocket"):
            return await self.app(scope, receive, send)
        headers = {key.decode("latin-1").lower(): value.decode("latin-1") for key, value in scope["headers"]}
        try:
            reason = self.refusal(headers, scope.get("query_string", b""), scope.get("server"))
            if reason is not None:
                raise Refused(403, f"refused: {reason}")
            if scope["type"] == "http":
                receive = await self._bounded(headers, receive)
                send = self._with_cookie(scope.get("query_string", b""), send)
        except Refused as refused:
            if scope["type"] == "websocket":
                # closing before the handshake is answered refuses it with HTTP 403
                await send({"type": "websocket.close", "code": 1008, "reason": refused.detail[:120]})
            else:
                await _reply(send, refused.status, refused.detail)
            return
        await self.app(scope, receive, send)

    def _with_cookie(self, query, send):
        """``send`` that sets the token cookie on a page opened with ``?token=``, so that it need not repeat it."""
        if self.token is None or b"token=" not in query:
            return send
        cookie = f"{self.cookie}={self.token}; Path=/; HttpOnly; SameSite=Strict".encode()

        async def sending(message):
            if message["type"] == "http.response.start":
                message = {**message, "headers": [*message.get("headers", []), (b"set-cookie", cookie)]}
            await send(message)

        return sending

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
