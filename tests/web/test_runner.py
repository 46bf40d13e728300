"""The run slots under a flood: admitted runs keep their speed, refusals come on time, leavers go quietly."""

import asyncio
import json
import logging
import time

from websockets.asyncio.client import connect

from kreisel.web import create_app
from kreisel.web.runner import Limits

from .conftest import authorization, free_port, served
from .test_security import RUNAWAY

# about a second of compiled fixed steps (2e6 of them) in ten chunks: the worker's work, not the transfer,
# sets how long it takes
RUN = {"form": {"moments": [1.0, 2.0, 3.0], "omega": [0.01, 1.0, 0.01], "mgl": 1.0, "method": "splitting4",
                "dt": 1e-5, "t_end": 20.0, "n_samples": 2000}}
QUEUE = 1.0
FLOOD = 90


async def _stream(url, headers, body):
    """Stream ``body``: (its last message, seconds from connecting to that message)."""
    start = time.monotonic()
    async with connect(url.replace("http", "ws") + "api/stream", additional_headers=headers, open_timeout=60,
                       max_size=None) as ws:
        await ws.send(json.dumps(body))
        while True:
            message = json.loads(await asyncio.wait_for(ws.recv(), 300))
            if message["type"] in ("done", "error"):
                return message, time.monotonic() - start


async def _admitted_and_flood(url, headers, runner, flood):
    admitted = [asyncio.create_task(_stream(url, headers, RUN)) for _ in range(2)]
    while len(runner.busy) < 2:
        await asyncio.sleep(0.01)
    refused = await asyncio.gather(*(_stream(url, headers, RUN) for _ in range(flood)))
    return await asyncio.gather(*admitted), refused


def test_a_flood_of_streams_neither_starves_the_admitted_runs_nor_delays_its_refusals():
    # the reproducer: 90 streams beyond the two slots used to take every thread of asyncio's default pool
    # (6 here) with their waits, so the admitted runs' chunks waited behind them and refusals came in waves
    port = free_port()
    app = create_app(port=port, chunk_samples=200,
                     limits=Limits(slots=2, wall_seconds=900.0, queue_seconds=QUEUE, max_steps=10**7))
    headers = authorization(app)
    runner = app.state.viewer.runner
    with served(app, port) as url:
        asyncio.run(_admitted_and_flood(url, headers, runner, 0))  # workers started, kernels loaded
        solo, _ = asyncio.run(_admitted_and_flood(url, headers, runner, 0))
        admitted, refused = asyncio.run(_admitted_and_flood(url, headers, runner, FLOOD))
    alone = max(seconds for _, seconds in solo)
    for message, seconds in admitted:
        assert message["type"] == "done", message
        assert seconds <= 2.0 * alone, (seconds, alone)
    assert len(refused) == FLOOD
    for message, seconds in refused:
        assert message["type"] == "error" and message["status"] == 503 and "busy" in message["detail"]
        assert seconds <= QUEUE + 2.0, seconds


class _Errors(logging.Handler):
    def __init__(self):
        super().__init__(logging.ERROR)
        self.records = []

    def emit(self, record):
        self.records.append(record)


async def _leave_while_waiting(url, headers, runner):
    async with connect(url.replace("http", "ws") + "api/stream", additional_headers=headers) as busy:
        await busy.send(json.dumps(RUNAWAY))
        while not runner.busy:
            await asyncio.sleep(0.01)
        async with connect(url.replace("http", "ws") + "api/stream", additional_headers=headers) as leaver:
            await leaver.send(json.dumps(RUN))
            await asyncio.sleep(0.2)
        # past the wait the leaver would have had: its refusal had nobody to go to
        await asyncio.sleep(QUEUE + 1.0)
        await busy.send("cancel")
        return json.loads(await asyncio.wait_for(busy.recv(), 60))


def test_a_client_that_leaves_while_waiting_for_a_slot_goes_quietly():
    port = free_port()
    app = create_app(port=port, limits=Limits(slots=1, wall_seconds=900.0, queue_seconds=QUEUE))
    runner = app.state.viewer.runner
    errors = _Errors()
    with served(app, port) as url:
        # after the server has configured its logging, which replaces the handlers
        logging.getLogger("uvicorn.error").addHandler(errors)
        try:
            last = asyncio.run(_leave_while_waiting(url, authorization(app), runner))
        finally:
            logging.getLogger("uvicorn.error").removeHandler(errors)
    assert last["type"] in ("start", "chunk", "cancelled")
    assert not errors.records, [record.getMessage() for record in errors.records]
