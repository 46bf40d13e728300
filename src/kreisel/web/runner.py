"""Where the viewer's runs happen: worker processes that a run's time limit or its client can stop.

A run's cost is not known before it is made (a stiff heavy top or a huge torque makes the adaptive
integrator take ever smaller steps, and compiled loops do not return to Python), so no up-front check can
bound it. Each run therefore happens in a worker process of a small pool: at most ``slots`` runs at once,
each stopped after ``wall_seconds`` (and, inside the worker, after ``max_steps`` integration steps). A stop (time limit, client gone, ``cancel``) first asks the worker to
stop between two chunks and, if it does not answer within ``grace_seconds``, ends its process; a fresh
worker takes its place. The event loop never runs numerical work.

Waiting costs no thread: a request waiting for a slot polls for it on the event loop, so a flood of
waiting requests cannot delay the admitted runs or its own refusals. The blocking reads of the workers'
pipes run in the runner's own small thread pool (one thread per slot and one spare per slot for a
stopped worker's last reply), never in asyncio's shared default pool.

A job names a function of :mod:`kreisel.web.session` run in the worker: ``"run"`` and ``"export"``
answer one message, ``"stream"`` one message per chunk. The worker sends ``("message", m)`` for each,
``("error", status, detail)`` for a refused or failed run, and ``("end",)`` when the job is over; the
parent may send ``"stop"`` at any time.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import multiprocessing
import threading
import time

from .limits import Limits

__all__ = ["Limits", "Stopped", "Runner"]

#: How often a request waiting for a slot looks for one, s.
POLL_SECONDS = 0.05


class Stopped(Exception):
    """A job that did not finish: ``status`` (HTTP) and ``detail`` say why."""

    def __init__(self, status, detail):
        super().__init__(detail)
        self.status, self.detail = status, detail


def _work(conn):
    """The worker's loop: run jobs from ``conn`` until the parent closes it (runs in the child process)."""
    from . import session

    while True:
        try:
            job = conn.recv()
        except (EOFError, OSError):
            return
        if job == "stop":  # for a job that had already ended when the parent asked it to stop
            continue
        name, args = job
        try:
            answer = getattr(session, name)(*args)
            messages = answer if name == "stream" else iter([answer])
            for message in messages:
                conn.send(("message", message))
                if conn.poll() and conn.recv() == "stop":
                    break
        except session.RunRefused as exc:
            conn.send(("error", 422, str(exc)))
        except session.ScenarioError as exc:
            conn.send(("error", 400, str(exc)))
        except Exception as exc:  # the integrator failed midway (step size collapse, ...): say so
            conn.send(("error", 422, f"the run failed: {exc}"))
        conn.send(("end",))


class _Worker:
    def __init__(self, context):
        self.conn, child = context.Pipe()
        self.process = context.Process(target=_work, args=(child,), daemon=True, name="kreisel-viewer-run")
        self.process.start()
        child.close()
        self.pending = None  # a receive still waiting for the worker's reply after a stop

    def end(self):
        """End the process now (it may be in compiled code that never returns)."""
        self.process.kill()
        self.process.join()
        self.conn.close()


class Runner:
    """A pool of worker processes that run the viewer's jobs within :class:`Limits`.

    Examples
    --------
    >>> import asyncio
    >>> from kreisel.web.presets import preset_text
    >>> runner = Runner(Limits(slots=1))
    >>> async def first_type():
    ...     async for message in runner.messages("stream", (preset_text("tennis_racket"), True, 1000)):
    ...         return message["type"]
    >>> asyncio.run(first_type())
    'start'
    >>> runner.close()
    """

    def __init__(self, limits=None):
        self.limits = limits or Limits()
        # never fork the server itself: it has threads (a forked lock may be held forever); a fork server
        # that has imported kreisel once starts each worker in milliseconds
        if "forkserver" in multiprocessing.get_all_start_methods():
            self.context = multiprocessing.get_context("forkserver")
            self.context.set_forkserver_preload([__name__.rpartition(".")[0] + ".session"])
        else:
            self.context = multiprocessing.get_context("spawn")
        self.idle = []
        self.busy = set()
        self.lock = threading.Lock()
        # a thread semaphore, not an asyncio one: requests may come from more than one event loop
        self.slots = threading.BoundedSemaphore(self.limits.slots)
        self.pipes = concurrent.futures.ThreadPoolExecutor(2 * self.limits.slots, "kreisel-viewer-pipe")

    @property
    def workers(self):
        """Process ids of the living workers (idle and busy)."""
        with self.lock:
            return [w.process.pid for w in self.idle + list(self.busy)]

    async def _acquire(self, stop):
        """A worker with a slot; None when ``stop`` is set first; Stopped (503) after ``queue_seconds``."""
        deadline = time.monotonic() + self.limits.queue_seconds
        while not self.slots.acquire(blocking=False):
            if stop is not None and stop.is_set():
                return None
            if time.monotonic() >= deadline:
                raise Stopped(503, f"the viewer is busy with {self.limits.slots} runs; try again when one is "
                                   "done")
            await asyncio.sleep(POLL_SECONDS)
        with self.lock:
            while self.idle and not self.idle[-1].process.is_alive():
                self.idle.pop().end()
            worker = self.idle.pop() if self.idle else None
        try:
            if worker is None:
                worker = await asyncio.get_running_loop().run_in_executor(self.pipes, _Worker, self.context)
        except BaseException:
            self.slots.release()
            raise
        with self.lock:
            self.busy.add(worker)
        return worker

    def _release(self, worker, healthy):
        with self.lock:
            self.busy.discard(worker)
            if healthy:
                self.idle.append(worker)
        if not healthy:
            worker.end()
        self.slots.release()

    async def messages(self, name, args, stop=None):
        """Run job ``name(*args)`` in a worker and yield its messages.

        ``stop`` (an :class:`asyncio.Event`) ends the job early: no more messages are yielded. Raises
        :class:`Stopped` for a refused or failed run, when the time limit is reached or no worker is free.
        """
        worker = await self._acquire(stop)
        if worker is None:
            return
        loop = asyncio.get_running_loop()
        deadline = loop.time() + self.limits.wall_seconds
        healthy = False
        try:
            worker.conn.send((name, args))
            while True:
                reply = await self._next(worker, deadline, stop)
                if reply is None:  # stopped: ask the worker to stop, end it if it does not
                    healthy = await self._stop(worker)
                    if stop is not None and stop.is_set():
                        return
                    raise Stopped(422, f"the run took longer than the viewer's limit of "
                                       f"{self.limits.wall_seconds:g} s and was stopped; shorten t_end, use fewer "
                                       "samples, or run it with `kreisel simulate`")
                if reply[0] == "end":
                    healthy = True
                    return
                if reply[0] == "dead":
                    raise Stopped(500, "the run's worker process ended unexpectedly (out of memory?)")
                if reply[0] == "error":
                    healthy = await self._finish(worker)
                    raise Stopped(reply[1], reply[2])
                yield reply[1]
        finally:
            self._release(worker, healthy)

    async def _next(self, worker, deadline, stop):
        """The worker's next reply, or None when ``stop`` is set or the deadline passes first."""
        loop = asyncio.get_running_loop()
        reply = loop.run_in_executor(self.pipes, _receive, worker.conn)
        waits = {reply}
        stopper = asyncio.ensure_future(stop.wait()) if stop is not None else None
        if stopper is not None:
            waits.add(stopper)
        try:
            done, _ = await asyncio.wait(waits, timeout=max(0.0, deadline - loop.time()),
                                         return_when=asyncio.FIRST_COMPLETED)
        finally:
            if stopper is not None:
                stopper.cancel()
        if reply in done:
            return reply.result()
        # the pending receive ends when the worker sends its next reply or its process is ended
        worker.pending = reply
        return None

    async def _stop(self, worker):
        """Ask ``worker`` to stop its job; True when it did so in time, else its process is ended."""
        try:
            worker.conn.send("stop")
        except OSError:
            return False
        try:
            return await asyncio.wait_for(self._drain(worker), self.limits.grace_seconds)
        except TimeoutError:
            return False

    async def _drain(self, worker):
        pending, worker.pending = worker.pending, None
        while True:
            reply = await pending if pending is not None else await asyncio.get_running_loop().run_in_executor(
                self.pipes, _receive, worker.conn)
            pending = None
            if reply[0] in ("end", "dead"):
                return reply[0] == "end"

    async def _finish(self, worker):
        try:
            return await asyncio.wait_for(self._drain(worker), self.limits.grace_seconds)
        except TimeoutError:
            return False

    def close(self):
        """End every worker process."""
        with self.lock:
            workers, self.idle = self.idle + list(self.busy), []
            self.busy.clear()
        for worker in workers:
            worker.end()
        self.pipes.shutdown(wait=False)


def _receive(conn):
    try:
        return conn.recv()
    except (EOFError, OSError):
        return ("dead",)
