"""How many connections the viewer holds, and for how long a request may take to arrive.

uvicorn waits forever for the headers of a request and accepts every connection until the process runs
out of file descriptors (then each failed accept logs a traceback). :func:`http_protocol` makes its
HTTP/1.1 protocol close a connection whose request headers are not complete within ``header_seconds``
(the first request, and each next one on a kept-alive connection), and close at once every connection
beyond ``max_connections`` (WebSockets included), saying so once per flood in the server's log.
"""

from __future__ import annotations

import logging

__all__ = ["HEADER_SECONDS", "max_connections", "http_protocol"]

#: Time a client has to send a request's headers, s.
HEADER_SECONDS = 10.0


def max_connections(cap=1000):
    """Connections the viewer holds at once: ``cap``, or half of what this process may open when that is less.

    The other half stays free for the worker processes' pipes, the static files and the listening socket.
    """
    try:
        import resource
    except ImportError:  # Windows: no descriptor limit to read
        return cap
    soft, _ = resource.getrlimit(resource.RLIMIT_NOFILE)
    return cap if soft == resource.RLIM_INFINITY else max(8, min(cap, soft // 2))


def http_protocol(header_seconds=HEADER_SECONDS, limit=None):
    """uvicorn's h11 protocol with a header timeout and a connection cap (``limit``, default :func:`max_connections`).

    Pass it as ``uvicorn.Config(app, http=http_protocol())``; every server gets its own class, which
    counts that server's floods.

    Examples
    --------
    >>> protocol = http_protocol(5.0, limit=100)
    >>> protocol.header_seconds, protocol.limit
    (5.0, 100)
    """
    import h11
    from uvicorn.protocols.http.h11_impl import H11Protocol

    if not 0 < header_seconds < float("inf"):
        raise ValueError(f"header_seconds must be a positive number of seconds, got {header_seconds!r}")
    logger = logging.getLogger("uvicorn.error")

    class BoundedH11Protocol(H11Protocol):
        flooded = 0  # connections refused in the current flood; 0: none

        def connection_made(self, transport):
            self.header_timer = None
            self.refused = len(self.connections) >= type(self).limit
            if self.refused:
                cls = type(self)
                if not cls.flooded:
                    logger.warning("kreisel viewer: %d connections at once; closing new ones until fewer are "
                                   "open (logged once per flood)", len(self.connections))
                cls.flooded += 1
                transport.abort()
                return
            super().connection_made(transport)
            self._await_headers()

        def connection_lost(self, exc):
            if self.refused:
                return
            self._cancel_header_timer()
            super().connection_lost(exc)
            cls = type(self)
            if cls.flooded and len(self.connections) < type(self).limit // 2:
                logger.warning("kreisel viewer: the flood is over (%d connections were refused)", cls.flooded)
                cls.flooded = 0

        def data_received(self, data):
            super().data_received(data)
            if self.conn.their_state is not h11.IDLE:  # headers complete (or a WebSocket took over)
                self._cancel_header_timer()

        def on_response_complete(self):
            super().on_response_complete()
            if not self.transport.is_closing() and self.conn.their_state is h11.IDLE:
                self._await_headers()

        def _await_headers(self):
            self._cancel_header_timer()
            self.header_timer = self.loop.call_later(type(self).header_seconds, self._headers_too_slow)

        def _cancel_header_timer(self):
            if self.header_timer is not None:
                self.header_timer.cancel()
                self.header_timer = None

        def _headers_too_slow(self):
            self.header_timer = None
            if self.conn.their_state is h11.IDLE and not self.transport.is_closing():
                self.transport.close()

    BoundedH11Protocol.header_seconds = float(header_seconds)
    BoundedH11Protocol.limit = max_connections() if limit is None else limit
    return BoundedH11Protocol
