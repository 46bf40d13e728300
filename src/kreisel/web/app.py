"""The ASGI app of ``kreisel serve``: the built front end and a JSON API that runs kreisel.

Endpoints (all JSON unless noted):

``GET /api/presets``                 name, title and description of every preset
``GET /api/presets/{name}``          its scenario TOML
``GET /api/methods``                 the integrators a run may name (those of :func:`kreisel.simulate`)
``GET /api/initial``                 the scenario given to :func:`serve` (TOML or null)
``POST /api/scenario``               ``{"form": {...}}`` -> ``{"toml": ...}``
``POST /api/run``                    ``{"preset": name}`` | ``{"toml": text}`` | ``{"form": {...}}`` -> the run
``POST /api/export?format=nc|csv``   same body -> the trajectory file (attachment)
``WebSocket /api/stream``            same body as the first message -> the run in chunks (below)
``POST /api/fit``                    ``{"text": recording, "name", "start", "stop", "bias"}`` -> the free top
                                     fitted to a gyroscope recording, as a run (:func:`kreisel.web.session.fit`)
``GET /api/recording``               the recording given to :func:`serve`: fitted, or, when it has an
                                     accelerometer and a reference attitude, its estimated attitude beside
                                     the reference (:func:`kreisel.web.session.attitude_replay`); or null

Only the server's own pages may use it: requests whose ``Host`` or ``Origin`` is not the server, or that
do not carry the server's token, are refused with 403 and bodies over the size limit with 413, before they are read (:mod:`kreisel.web.guard`).
Every refusal is a 4xx JSON answer with the reason in ``detail``: 400 for an invalid scenario, 404 for an
unknown preset, 422 for a malformed request, work over the limits or a run that failed, 503 when all run
slots are busy. Every body field has a strict type (``"exact": "yes"`` is refused, not read as true).
A body may add ``"exact": true`` to use the closed form of the free top instead of an integrator.

Runs happen in worker processes (:mod:`kreisel.web.runner`): each is stopped after the wall-clock limit,
when it has taken its budget of integration steps, and when its client goes away; only a few run at once.

The stream sends ``start``, then ``chunk`` messages as soon as each is computed, then ``done`` with the
first integrals (see :func:`kreisel.web.session.stream`); it allows
:data:`~kreisel.web.session.MAX_STREAM_SAMPLES` samples instead of the one-shot reply's
:data:`~kreisel.web.session.MAX_SAMPLES`. The client may send ``"cancel"`` (or ``{"type": "cancel"}``) at
any time: the stream stops after the chunk in progress and answers ``{"type": "cancelled", "samples":
sent}``. A request that is refused gets ``{"type": "error", "status": 4xx, "detail": reason}`` before any
work, then the socket closes with code 1008 (policy violation) and the reason; a run that fails or runs out
of time midway sends an error and closes with 1011 and the reason; a finished or cancelled stream closes
with 1000. Nothing reads or writes the user's files except the export, which writes to a private
temporary folder.
"""

from __future__ import annotations

import asyncio
import json
import pathlib
import secrets
import tempfile
import tomllib
from typing import Annotated, Literal

from .._optional import require

require("fastapi", extra="viewer", feature="the viewer (kreisel serve)")

from fastapi import FastAPI, HTTPException, Query, Request, WebSocket, WebSocketDisconnect
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, HTMLResponse, JSONResponse
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel, ConfigDict, Field, ValidationError
from starlette.background import BackgroundTask
from starlette.exceptions import HTTPException as StarletteHTTPException

from . import session
from .guard import Guard
from .presets import PRESETS, preset_text
from .runner import Limits, Runner, Stopped

__all__ = ["Form", "RunRequest", "Viewer", "create_app", "STATIC", "MAX_TOML_CHARS"]

STATIC = pathlib.Path(__file__).parent / "static"
MAX_TOML_CHARS = 100_000

_MISSING_BUNDLE = """<!doctype html><meta charset="utf-8"><title>kreisel viewer</title>
<p>The viewer's front end is missing from this installation (src/kreisel/web/static/). From a clone of
the repository, run <code>make web</code> (needs Node.js and npm), then start <code>kreisel serve</code>
again.</p>"""

Number = Annotated[float, Field(allow_inf_nan=False)]
Positive = Annotated[float, Field(gt=0.0, allow_inf_nan=False)]
Vector = Annotated[list[Number], Field(min_length=3, max_length=3)]


class Form(BaseModel):
    """The viewer's form: a rigid body with principal moments, optionally a heavy top (strict types)."""

    model_config = ConfigDict(strict=True, extra="forbid")

    title: Annotated[str, Field(max_length=200)] | None = None
    moments: Annotated[list[Positive], Field(min_length=3, max_length=3)]
    omega: Vector
    euler_deg: Vector | None = None
    mgl: Annotated[float, Field(ge=0.0, allow_inf_nan=False)] = 0.0
    lever_axis: Annotated[int, Field(ge=0, le=2)] = 2
    method: Literal[session.METHODS] | None = None
    t_end: Positive = 30.0
    n_samples: Annotated[int, Field(ge=2)] = 1501
    dt: Positive | None = None


class RunRequest(BaseModel):
    """Exactly one of a preset name, scenario TOML text or form fields."""

    model_config = ConfigDict(strict=True, extra="forbid")

    preset: Annotated[str, Field(max_length=100)] | None = None
    toml: Annotated[str, Field(max_length=MAX_TOML_CHARS)] | None = None
    form: Form | None = None
    exact: bool = False


class FitRequest(BaseModel):
    """A gyroscope recording's text (any layout :func:`kreisel.io.read_gyro` reads) and the fit options."""

    model_config = ConfigDict(strict=True, extra="forbid")

    text: str
    name: Annotated[str, Field(max_length=200)] = "upload"
    start: Number | None = None
    stop: Number | None = None
    bias: bool = True


def _scenario_text(request):
    given = [name for name in ("preset", "toml", "form") if getattr(request, name) is not None]
    if len(given) != 1:
        raise HTTPException(400, f"give exactly one of preset, toml, form (got {', '.join(given) or 'none'})")
    if request.preset is not None:
        try:
            return preset_text(request.preset)
        except ValueError as exc:
            raise HTTPException(404, str(exc)) from None
    if request.form is not None:
        return session.scenario_toml(request.form.model_dump())
    return request.toml


def _checked(call, *args):
    try:
        return call(*args)
    except session.RunRefused as exc:
        raise HTTPException(422, str(exc)) from None
    except session.ScenarioError as exc:
        raise HTTPException(400, str(exc)) from None


def _validation_detail(errors):
    return "; ".join(f"{'.'.join(str(p) for p in e['loc'] if p != 'body') or 'request'}: {e['msg']}"
                     for e in errors)


def _is_cancel(message):
    text = message.get("text")
    if text is None:
        return False
    if text.strip() == "cancel":
        return True
    try:
        return json.loads(text) == {"type": "cancel"}
    except ValueError:
        return False


async def _until_disconnected(request, gone):
    """Set ``gone`` when the HTTP client of ``request`` goes away."""
    while not await request.is_disconnected():
        await asyncio.sleep(0.2)
    gone.set()


class Viewer:
    """The app's state: the initial scenario, the run limits, the worker pool and the token (or None)."""

    def __init__(self, scenario_text, chunk_samples, limits, token=None):
        self.scenario_text = scenario_text
        self.token = token
        self.chunk_samples = chunk_samples
        self.limits = limits
        self.runner = Runner(limits)

    def request(self, text):
        """The request in WebSocket message ``text``; HTTPException with the reason when malformed."""
        if len(text.encode()) > self.limits.max_body:
            raise HTTPException(413, f"request message larger than {self.limits.max_body} bytes")
        try:
            return RunRequest.model_validate_json(text)
        except ValidationError as exc:
            raise HTTPException(422, _validation_detail(exc.errors())) from None

    async def one(self, request, name, *args):
        """The single answer of job ``name``; stopped when the client of ``request`` leaves."""
        gone = asyncio.Event()
        watch = asyncio.create_task(_until_disconnected(request, gone))
        try:
            answers = [answer async for answer in self.runner.messages(name, args, gone)]
            if not answers:
                raise HTTPException(499, "the client went away")
            return answers[0]
        except Stopped as stopped:
            raise HTTPException(stopped.status, stopped.detail) from None
        finally:
            watch.cancel()

    async def stream(self, websocket):
        """Serve one streamed run on an accepted ``websocket`` (protocol in the module docstring)."""
        try:
            request = self.request(await websocket.receive_text())
            text = _scenario_text(request)
            _checked(session.load, text, session.MAX_STREAM_SAMPLES, request.exact)
        except WebSocketDisconnect:
            return
        except (HTTPException, KeyError) as exc:
            if isinstance(exc, HTTPException):
                status, detail = exc.status_code, exc.detail
            else:  # a binary frame: receive_text finds no "text"
                status, detail = 400, "send the run request as a JSON text message"
            await websocket.send_json({"type": "error", "status": status, "detail": detail})
            await websocket.close(code=1008, reason=_reason(detail))
            return

        stop = asyncio.Event()
        cancelled = False

        async def listen():
            # stop on request or when the client goes away; other messages are ignored
            nonlocal cancelled
            while True:
                message = await websocket.receive()
                if message["type"] == "websocket.disconnect" or _is_cancel(message):
                    cancelled = message["type"] != "websocket.disconnect"
                    stop.set()
                    return

        listener = asyncio.create_task(listen())
        sent = 0
        try:
            try:
                async for message in self.runner.messages("stream", (text, request.exact, self.chunk_samples,
                                                                     self.limits.max_steps), stop):
                    await websocket.send_json(message)
                    sent += len(message["t"]) if message["type"] == "chunk" else 0
            except Stopped as stopped:
                # the client may have left meanwhile (e.g. while waiting for a slot): then nobody hears it
                await websocket.send_json({"type": "error", "status": stopped.status, "detail": stopped.detail})
                await websocket.close(code=1011, reason=_reason(stopped.detail))
                return
            if cancelled:
                await websocket.send_json({"type": "cancelled", "samples": sent})
            if not stop.is_set() or cancelled:
                await websocket.close(code=1000)
        except (WebSocketDisconnect, RuntimeError, OSError):
            return  # the client left while we were sending
        finally:
            listener.cancel()


def _reason(detail):
    """A close-frame reason: at most 123 bytes of UTF-8."""
    data = detail.encode()
    return detail if len(data) <= 123 else data[:120].decode(errors="ignore") + "..."


def create_app(scenario_text=None, chunk_samples=session.CHUNK_SAMPLES, host="127.0.0.1", port=None, limits=None,
               recording=None, token=None, allow_hosts=()):
    """The viewer's FastAPI app; ``scenario_text`` (TOML) is offered as the initial scenario.

    Parameters
    ----------
    scenario_text : str, optional
        Scenario TOML shown first.
    chunk_samples : int
        Samples per message of ``/api/stream``.
    host : str
        The interface the server listens on: requests must name it (or a loopback name) as their host.
    port : int, optional
        The server's port, required in the ``Host`` header when given.
    limits : Limits, optional
        Run slots, time limit and body size (``kreisel.web.runner.Limits``).
    recording : ImuRecording, optional
        A recording (:func:`kreisel.io.read_imu`) shown first: with an accelerometer and a reference
        attitude, its attitude estimated by kreisel replayed beside the reference; else the free top fitted.
    token : str, optional
        The secret every request must carry (see ``kreisel.web.guard``); by default a random one
        (``app.state.viewer.token``), as Jupyter makes; ``""``: none, any local process may use the viewer.
    allow_hosts : sequence of str
        More names the ``Host`` header may give (``kreisel.web.guard.Guard``).

    Examples
    --------
    >>> from fastapi.testclient import TestClient
    >>> app = create_app()
    >>> client = TestClient(app, base_url="http://127.0.0.1")
    >>> client.get("/api/presets").status_code
    403
    >>> client.get(f"/api/presets?token={app.state.viewer.token}").json()[0]["name"]
    'tennis_racket'
    >>> client.get("/api/presets", headers={"Origin": "http://evil.example"}).status_code
    403
    """
    if not isinstance(chunk_samples, int) or chunk_samples < 2:
        raise ValueError(f"chunk_samples must be an integer >= 2, got {chunk_samples!r}")
    limits = limits or Limits()
    if not isinstance(limits, Limits):
        raise TypeError(f"limits must be a kreisel.web.runner.Limits, got {type(limits).__name__}")
    if token is not None and not isinstance(token, str):
        raise TypeError(f"token must be a string (\"\": no token), got {type(token).__name__}")
    if isinstance(allow_hosts, str) or not all(isinstance(name, str) and name for name in allow_hosts):
        raise TypeError(f"allow_hosts must be a sequence of host names, got {allow_hosts!r}")
    token = secrets.token_urlsafe(32) if token is None else token or None
    viewer = Viewer(scenario_text, chunk_samples, limits, token)
    app = FastAPI(title="kreisel viewer", docs_url=None, redoc_url=None, openapi_url=None)
    app.state.viewer = viewer
    app.add_middleware(Guard, host=host, port=port, max_body=limits.max_body, token=token,
                       allow_hosts=tuple(allow_hosts))

    @app.exception_handler(RequestValidationError)
    async def invalid(request, exc):
        return JSONResponse({"detail": _validation_detail(exc.errors())}, status_code=422)

    @app.exception_handler(StarletteHTTPException)
    async def refused(request, exc):
        detail = exc.detail if isinstance(exc.detail, str) else json.dumps(exc.detail)
        return JSONResponse({"detail": detail}, status_code=exc.status_code, headers=exc.headers)

    @app.get("/", response_class=HTMLResponse)
    def index():
        page = STATIC / "index.html"
        if not page.is_file():
            return HTMLResponse(_MISSING_BUNDLE, status_code=503)
        return HTMLResponse(page.read_text(encoding="utf-8"))

    @app.get("/favicon.ico", include_in_schema=False)
    def favicon():
        icon = STATIC / "favicon.svg"
        if not icon.is_file():
            raise HTTPException(404, "no favicon in this installation")
        return FileResponse(icon, media_type="image/svg+xml")

    @app.get("/api/presets")
    def presets():
        out = []
        for name in PRESETS:
            data = tomllib.loads(preset_text(name))
            out.append({"name": name, "title": data.get("title", name), "description": data.get("description", "")})
        return out

    @app.get("/api/presets/{name}")
    def preset(name: str):
        try:
            return {"name": name, "toml": preset_text(name)}
        except ValueError as exc:
            raise HTTPException(404, str(exc)) from None

    @app.get("/api/methods")
    def methods():
        return list(session.METHODS)

    @app.get("/api/initial")
    def initial():
        return {"toml": viewer.scenario_text}

    @app.post("/api/scenario")
    def scenario(request: RunRequest):
        text = _scenario_text(request)
        _checked(session.load, text, session.MAX_STREAM_SAMPLES, request.exact)
        return {"toml": text}

    @app.post("/api/run")
    async def run(body: RunRequest, request: Request):
        text = _scenario_text(body)
        _checked(session.load, text, session.MAX_SAMPLES, body.exact)
        return JSONResponse(await viewer.one(request, "run", text, body.exact, viewer.limits.max_steps))

    @app.websocket("/api/stream")
    async def stream(websocket: WebSocket):
        await websocket.accept()
        await viewer.stream(websocket)

    @app.post("/api/fit")
    async def fit(body: FitRequest, request: Request):
        return JSONResponse(await viewer.one(request, "fit", body.text, body.name, body.start, body.stop, body.bias))

    @app.get("/api/recording")
    async def initial_recording(request: Request):
        if recording is None:
            return None
        if recording.accel is not None and recording.reference is not None:
            return JSONResponse(await viewer.one(request, "attitude_replay", recording))
        return JSONResponse(await viewer.one(request, "fit", recording, recording.source))

    @app.post("/api/export")
    async def export(body: RunRequest, request: Request, format: Literal["nc", "csv"] = Query("nc")):
        text = _scenario_text(body)
        # what the viewer streamed it can export: the file is written from one run held in memory
        scenario = _checked(session.load, text, session.MAX_STREAM_SAMPLES, body.exact)
        if scenario.kind != "rigid_body":
            raise HTTPException(400, "only rigid-body runs export as a trajectory file")
        folder = tempfile.TemporaryDirectory(prefix="kreisel-export-")
        try:
            path = pathlib.Path(await viewer.one(request, "export", text, body.exact, format, folder.name,
                                                     viewer.limits.max_steps))
        except BaseException:
            folder.cleanup()
            raise
        return FileResponse(path, filename=path.name, background=BackgroundTask(folder.cleanup))

    if STATIC.is_dir():
        app.mount("/static", StaticFiles(directory=STATIC), name="static")
    return app
