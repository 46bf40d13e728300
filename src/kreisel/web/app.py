"""The ASGI app of ``kreisel serve``: the built front end and a JSON API that runs kreisel.

Endpoints (all JSON unless noted):

``GET /api/presets``                 name, title and description of every preset
``GET /api/presets/{name}``          its scenario TOML
``GET /api/initial``                 the scenario given to :func:`serve` (TOML or null)
``POST /api/scenario``               ``{"form": {...}}`` -> ``{"toml": ...}``
``POST /api/run``                    ``{"preset": name}`` | ``{"toml": text}`` | ``{"form": {...}}`` -> the run
``POST /api/export?format=nc|csv``   same body -> the trajectory file (attachment)
``WebSocket /api/stream``            same body as the first message -> the run in chunks (below)

Invalid scenarios answer 400 and work over the limits answers 422, with the reason in ``detail``.
A body may add ``"exact": true`` to use the closed form of the free top instead of an integrator.

The stream runs in a worker thread one chunk of samples at a time (the event loop stays free) and sends
``start``, then ``chunk`` messages as soon as each is computed, then ``done`` with the drift summary (see
:func:`kreisel.web.session.stream`); it allows :data:`~kreisel.web.session.MAX_STREAM_SAMPLES` samples
instead of the one-shot reply's :data:`~kreisel.web.session.MAX_SAMPLES`. The client may send
``"cancel"`` (or ``{"type": "cancel"}``) at any time: the stream stops after the chunk in progress and
answers ``{"type": "cancelled", "samples": sent}``. A request that is refused gets
``{"type": "error", "status": 400|404|422, "detail": reason}`` before any work, then the socket closes
with code 1008 (policy violation); a run that fails midway sends an error with status 500 and closes
with 1011; a finished or cancelled stream closes with 1000.
Nothing reads or writes the user's files except the export, which writes to a private temporary folder.
"""

from __future__ import annotations

import asyncio
import json
import pathlib
import tempfile
import tomllib

from fastapi import FastAPI, HTTPException, Query, WebSocket, WebSocketDisconnect
from fastapi.responses import FileResponse, HTMLResponse, JSONResponse
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel, Field, ValidationError
from starlette.background import BackgroundTask
from starlette.concurrency import run_in_threadpool

from . import session
from .presets import PRESETS, preset_text

STATIC = pathlib.Path(__file__).parent / "static"
MAX_TOML_CHARS = 100_000

_MISSING_BUNDLE = """<!doctype html><meta charset="utf-8"><title>kreisel viewer</title>
<p>The viewer's front end has not been built. From the repository, run <code>make web</code>
(needs Node.js and npm), then start <code>kreisel serve</code> again.</p>"""


class Form(BaseModel):
    """The viewer's form: a rigid body with principal moments, optionally a heavy top."""

    title: str | None = Field(None, max_length=200)
    moments: list[float] = Field(min_length=3, max_length=3)
    omega: list[float] = Field(min_length=3, max_length=3)
    euler_deg: list[float] | None = Field(None, min_length=3, max_length=3)
    mgl: float = 0.0
    lever_axis: int = Field(2, ge=0, le=2)
    method: str | None = None
    t_end: float = 30.0
    n_samples: int = 1501
    dt: float | None = None


class RunRequest(BaseModel):
    """Exactly one of a preset name, scenario TOML text or form fields."""

    preset: str | None = None
    toml: str | None = Field(None, max_length=MAX_TOML_CHARS)
    form: Form | None = None
    exact: bool = False


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
        if request.form.method is not None and request.form.method not in session.METHODS:
            raise HTTPException(400, f"form.method must be one of {', '.join(session.METHODS)}, "
                                     f"got {request.form.method!r}")
        return session.scenario_toml(request.form.model_dump())
    return request.toml


def _checked(call, *args):
    try:
        return call(*args)
    except session.RunRefused as exc:
        raise HTTPException(422, str(exc)) from None
    except session.ScenarioError as exc:
        raise HTTPException(400, str(exc)) from None


def _validation_detail(exc):
    return "; ".join(f"{'.'.join(str(p) for p in e['loc']) or 'request'}: {e['msg']}" for e in exc.errors())


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


async def _stream(websocket, chunk_samples):
    """Serve one streamed run on an accepted ``websocket`` (protocol in the module docstring)."""
    try:
        request = RunRequest.model_validate_json(await websocket.receive_text())
        messages = await run_in_threadpool(_checked, session.stream, _scenario_text(request), request.exact,
                                            chunk_samples)
    except WebSocketDisconnect:
        return
    except (HTTPException, ValidationError, KeyError) as exc:
        if isinstance(exc, HTTPException):
            status, detail = exc.status_code, exc.detail
        elif isinstance(exc, ValidationError):
            status, detail = 422, _validation_detail(exc)
        else:  # a binary frame: receive_text finds no "text"
            status, detail = 400, "send the run request as a JSON text message"
        await websocket.send_json({"type": "error", "status": status, "detail": detail})
        await websocket.close(code=1008, reason=detail[:120])
        return

    cancelled = asyncio.Event()

    async def listen():
        # cancel on request or when the client goes away; other messages are ignored
        while True:
            message = await websocket.receive()
            if message["type"] == "websocket.disconnect" or _is_cancel(message):
                cancelled.set()
                return

    listener = asyncio.create_task(listen())
    sent = 0
    try:
        while not cancelled.is_set():
            try:
                message = await run_in_threadpool(next, messages, None)
            except Exception as exc:  # the integrator failed midway (step size collapse, ...)
                await websocket.send_json({"type": "error", "status": 500, "detail": f"the run failed: {exc}"})
                await websocket.close(code=1011)
                return
            if message is None:
                await websocket.close(code=1000)
                return
            if cancelled.is_set():
                break
            await websocket.send_json(message)
            sent += len(message["t"]) if message["type"] == "chunk" else 0
        await websocket.send_json({"type": "cancelled", "samples": sent})
        await websocket.close(code=1000)
    except (WebSocketDisconnect, RuntimeError):
        return  # the client left while we were sending
    finally:
        listener.cancel()
        messages.close()


def create_app(scenario_text=None, chunk_samples=session.CHUNK_SAMPLES):
    """The viewer's FastAPI app; ``scenario_text`` (TOML) is offered as the initial scenario.

    ``chunk_samples`` is the number of samples per message of ``/api/stream``.

    Examples
    --------
    >>> from fastapi.testclient import TestClient
    >>> client = TestClient(create_app())
    >>> client.get("/api/presets").json()[0]["name"]
    'tennis_racket'
    """
    if not isinstance(chunk_samples, int) or chunk_samples < 2:
        raise ValueError(f"chunk_samples must be an integer >= 2, got {chunk_samples!r}")
    app = FastAPI(title="kreisel viewer", docs_url=None, redoc_url=None, openapi_url=None)

    @app.get("/", response_class=HTMLResponse)
    def index():
        page = STATIC / "index.html"
        if not page.is_file():
            return HTMLResponse(_MISSING_BUNDLE, status_code=503)
        return HTMLResponse(page.read_text(encoding="utf-8"))

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

    @app.get("/api/initial")
    def initial():
        return {"toml": scenario_text}

    @app.post("/api/scenario")
    def scenario(request: RunRequest):
        text = _scenario_text(request)
        _checked(session.load, text)
        return {"toml": text}

    @app.post("/api/run")
    def run(request: RunRequest):
        return JSONResponse(_checked(session.run, _scenario_text(request), request.exact))

    @app.websocket("/api/stream")
    async def stream(websocket: WebSocket):
        await websocket.accept()
        await _stream(websocket, chunk_samples)

    @app.post("/api/export")
    def export(request: RunRequest, format: str = Query("nc", pattern="^(nc|csv)$")):
        text = _scenario_text(request)
        # what the viewer streamed it can export: the file is written from one run held in memory
        scenario = _checked(session.load, text, session.MAX_STREAM_SAMPLES)
        if scenario.kind != "rigid_body":
            raise HTTPException(400, "only rigid-body runs export as a trajectory file")
        from ..io import save_result

        traj = _checked(lambda: session.Solver(scenario, request.exact).run())
        folder = tempfile.TemporaryDirectory(prefix="kreisel-export-")
        name = "".join(c if c.isalnum() else "_" for c in scenario.title.lower()).strip("_") or "trajectory"
        path = save_result(traj, pathlib.Path(folder.name) / f"{name}.{format}")
        return FileResponse(path, filename=path.name, background=BackgroundTask(folder.cleanup))

    if STATIC.is_dir():
        app.mount("/static", StaticFiles(directory=STATIC), name="static")
    return app
