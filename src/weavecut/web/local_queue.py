"""The embedded job queue: no server to install, bounded, every job in its own process.

At most ``workers`` jobs run at once, each in a child forked from a warm parent: the
multiprocessing forkserver, which imports ``weavecut.web.warm`` once and then forks a child
per job in milliseconds (a fresh interpreter would spend about a second importing weave-cut's
libraries). The child sets its CPU and memory limits (``limits.child_main``). At most
``waiting`` jobs wait for a free worker; one more raises QueueFull with the seconds after
which a retry may find room (from the mean run time of the last jobs).

Cancelling the task that awaits ``run`` (the client left) kills the child (SIGKILL) and
removes its folder, as does a job past its wall-clock time (``limits.wall_seconds``). A child
that dies by its limit answers a JobResult (422), and the queue goes on.

Like every forkserver, the children import the server's main module as ``__mp_main__``: a
script that opens the queue keeps its work under ``if __name__ == "__main__":`` (the
``weave-cut`` console script and ``python -m weavecut`` do).
"""

from __future__ import annotations

import asyncio
import math
import multiprocessing
import os
import shutil
import tempfile
import threading
from pathlib import Path

from .jobs import JobResult, JobSpec, QueueFull, failed
from .limits import child_main, outcome, too_long, wall_seconds

FIRST_GUESS = 5.0  # seconds a job takes, until jobs have been timed


class LocalQueue:
    """The embedded queue (``jobs.open_queue(None, ...)``)."""

    def __init__(self, *, workers: int, cpu_seconds: int, memory_mb: int, waiting: int,
                 folder: str | os.PathLike | None = None) -> None:
        if workers < 1 or waiting < 0:
            raise ValueError("a queue needs at least one worker and no negative wait")
        self.workers, self.waiting = workers, waiting
        self.cpu_seconds, self.memory_mb = cpu_seconds, memory_mb
        self.folder = folder  # where job folders go (default: the system's temporary folder)
        self._context = multiprocessing.get_context("forkserver")
        self._context.set_forkserver_preload(["weavecut.web.warm"])
        self._start_lock = threading.Lock()  # Process.start is not thread-safe
        self._slots = asyncio.Semaphore(workers)
        self._queued = 0
        self._mean = FIRST_GUESS
        self._running: dict[int, multiprocessing.process.BaseProcess] = {}
        self._closed = False

    def pids(self) -> list[int]:
        """The process ids of the running jobs."""
        return sorted(self._running)

    def queued(self) -> int:
        """How many jobs wait for a free worker."""
        return self._queued

    def retry_after(self) -> int:
        """Seconds until the jobs waiting now have probably started."""
        return max(1, math.ceil(self._mean * (self._queued + 1) / self.workers))

    def start(self) -> None:
        """Start the warm parent now (else the first job does; it takes a second or two)."""
        from multiprocessing import forkserver

        forkserver.ensure_running()

    async def run(self, spec: JobSpec) -> JobResult:
        if self._closed:
            raise RuntimeError("the job queue is closed")
        if self._slots.locked() and self._queued >= self.waiting:
            raise QueueFull(self.retry_after())
        self._queued += 1
        try:
            await self._slots.acquire()
        finally:
            self._queued -= 1
        try:
            return await self._run(spec)
        finally:
            self._slots.release()

    async def _run(self, spec: JobSpec) -> JobResult:
        loop = asyncio.get_running_loop()
        jobdir = tempfile.mkdtemp(prefix="weave-cut-job-", dir=self.folder)
        process = self._context.Process(
            target=child_main, args=(spec, jobdir, self.cpu_seconds, self.memory_mb),
            name="weave-cut job", daemon=True)
        started = loop.time()
        launch = loop.run_in_executor(None, self._start, process)
        try:
            try:
                await asyncio.shield(launch)
            except asyncio.CancelledError:  # let it start, then kill it below
                await asyncio.wait([launch])
                raise
            self._running[process.pid] = process
            ended = loop.create_future()
            loop.add_reader(process.sentinel, lambda: ended.done() or ended.set_result(None))
            try:
                await asyncio.wait_for(ended, wall_seconds(self.cpu_seconds))
            except asyncio.TimeoutError:  # waiting, not computing: killed below
                return too_long(spec, wall_seconds(self.cpu_seconds))
            finally:
                loop.remove_reader(process.sentinel)
            process.join()  # it has ended: this reads its exit status
            if self._closed:
                return failed(503, "the server is shutting down; try again")
            result = await asyncio.to_thread(outcome, spec, jobdir, process.exitcode,
                                             self.cpu_seconds, self.memory_mb)
            self._mean = 0.8 * self._mean + 0.2 * (loop.time() - started)
            return result
        finally:  # also when the awaiting task is cancelled: the child is killed
            self._end(process)
            shutil.rmtree(jobdir, ignore_errors=True)

    def _start(self, process) -> None:
        with self._start_lock:
            process.start()

    def _end(self, process) -> None:
        if process.pid is None:
            return
        if process.exitcode is None:
            process.kill()
            process.join()
        self._running.pop(process.pid, None)
        process.close()

    async def close(self) -> None:
        """Kill the running jobs; later calls to ``run`` fail."""
        self._closed = True
        for process in list(self._running.values()):
            if process.exitcode is None:
                process.kill()


def job_folders(folder: str | os.PathLike | None = None) -> list[Path]:
    """The job folders that exist in ``folder`` (for tests and cleanup checks)."""
    return sorted(Path(folder or tempfile.gettempdir()).glob("weave-cut-job-*"))
