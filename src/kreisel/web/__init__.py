"""``kreisel serve``: a local web viewer of rigid bodies and tops, computed by kreisel.

:func:`create_app` builds the ASGI app (static front end + JSON API, see ``kreisel.web.app``);
:func:`serve` runs it with uvicorn on the loopback interface.
"""

from .app import create_app
from .server import serve

__all__ = ["create_app", "serve"]
