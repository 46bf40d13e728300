"""``kreisel serve``: a local web viewer of rigid bodies and tops, computed by kreisel.

:func:`create_app` builds the ASGI app (static front end + JSON API, see ``kreisel.web.app``);
:func:`serve` runs it with uvicorn on the loopback interface.
"""

from .server import serve

__all__ = ["create_app", "serve"]


def __getattr__(name):
    # the app needs FastAPI (the viewer extra); kreisel.show uses this package's session module without it
    if name != "create_app":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from .app import create_app

    return create_app
