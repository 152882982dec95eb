"""Jobs through RQ on Redis, for more than one machine: ``weave-cut serve --queue
redis://HOST:PORT/DB`` enqueues, ``weave-cut worker --queue redis://...`` on any machine runs.

The server side (``RedisQueue``) bounds the jobs waiting in the queue (QueueFull beyond
``waiting``), enqueues ``perform(spec, cpu_seconds, memory_mb)`` with a wall-clock timeout
and a time to live in the queue, and waits for the result on RQ's result stream. A client
that leaves cancels its job: a waiting job leaves the queue (RQ's cancel), a running one is
stopped (RQ's stop-job command: the worker kills its work horse), and one that a worker has
just taken is stopped by its horse, which looks at ``cancel_key`` twice a second.

The worker side (``JobWorker``, RQ's forking Worker) loads weave-cut once (``warm``) and
forks a work horse per job, as RQ does; the horse forks the job's own child with its CPU and
memory limits (``limits.child_main``) and waits for it, so a job that dies by its limit is
still answered (422) by the horse, whose RQ bookkeeping runs without limits. The limits are
the lower of the worker's (``--cpu-seconds``, ``--memory``) and the server's.

RQ moves jobs and results as pickles: anyone who can write to the Redis server can run code
on the workers. Keep it on a private network, with a password (``redis://:PASSWORD@HOST``).
"""

from __future__ import annotations

import asyncio
import math
import os
import re
import select
import shutil
import signal
import tempfile
import time
from pathlib import Path

from rq import Queue, Worker, get_current_job
from rq.exceptions import InvalidJobOperation, NoSuchJobError
from rq.job import Job, JobStatus
from rq.results import Result

from .jobs import JobResult, JobSpec, QueueFull, failed
from .limits import child_main, outcome, too_long, wall_seconds

QUEUE = "weave-cut"
RESULT_TTL = 600  # seconds RQ keeps a result the server did not collect
QUEUED_TTL = 600  # seconds a job may wait for a worker
FIRST_GUESS = 5.0  # seconds a job takes, until jobs have been timed
WORKER_LIMITS = [0, 0]  # this worker's --cpu-seconds and --memory (0: none), set by the command
JOB_ID = re.compile(r"[A-Za-z0-9_-]{1,100}")


def _least(a: int, b: int) -> int:
    """The lower of two limits, where 0 is none."""
    return min(n for n in (a, b) if n > 0) if a > 0 or b > 0 else 0


def job_folder(job_id: str) -> Path:
    """The folder of RQ job ``job_id``'s files on the worker."""
    if not JOB_ID.fullmatch(job_id):
        raise ValueError(f"{job_id!r} is not an RQ job id")
    return Path(tempfile.gettempdir()) / f"weave-cut-rq-{job_id}"


def cancel_key(job_id: str) -> str:
    """The Redis key that says job ``job_id``'s client left."""
    return f"weave-cut:cancelled:{job_id}"


def perform(spec: JobSpec, cpu_seconds: int, memory_mb: int) -> JobResult:
    """Run ``spec`` in a child of this work horse, with limits; its result. The child is
    killed when the job's client leaves (``cancel_key``, looked at twice a second)."""
    cpu = _least(cpu_seconds, WORKER_LIMITS[0])
    memory = _least(memory_mb, WORKER_LIMITS[1])
    current = get_current_job()
    if current is not None and current.connection.exists(cancel_key(current.id)):
        return failed(499, "the client left before the job started")
    jobdir = job_folder(current.id if current else f"local-{os.getpid()}")
    jobdir.mkdir(mode=0o700)
    try:
        pid = os.fork()
        if pid == 0:  # pragma: no cover - the child ends in os._exit
            code = 1
            try:
                child_main(spec, str(jobdir), cpu, memory)
                code = 0
            finally:
                os._exit(code)
        try:
            if current is not None:
                current.meta["child"] = pid
                current.save_meta()
            status = _wait(pid, lambda: current is not None
                           and current.connection.exists(cancel_key(current.id)))
        except BaseException:  # RQ's timeout, or the horse is stopped: the child goes too
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            raise
        if status is None:
            return failed(499, "the client left; the job was stopped")
        return outcome(spec, jobdir, -os.WTERMSIG(status) if os.WIFSIGNALED(status)
                       else os.WEXITSTATUS(status), cpu, memory)
    finally:
        shutil.rmtree(jobdir, ignore_errors=True)


def _wait(pid: int, cancelled) -> int | None:
    """The wait status of child ``pid``, or None if ``cancelled()`` turned true first (the
    child is then killed). Woken by the child's end (a pidfd, Linux), else looks every
    0.1 s."""
    fd = os.pidfd_open(pid) if hasattr(os, "pidfd_open") else None
    try:
        looks = 0
        while True:
            if fd is not None:
                if select.select([fd], [], [], 0.5)[0]:
                    break
            else:
                done, status = os.waitpid(pid, os.WNOHANG)
                if done:
                    return status
                time.sleep(0.1)
            looks += 1
            if (fd is not None or looks % 5 == 0) and cancelled():
                os.kill(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
                return None
    finally:
        if fd is not None:
            os.close(fd)
    return os.waitpid(pid, 0)[1]


class JobWorker(Worker):
    """RQ's forking worker; removes a job's folder when its horse was killed (a stop)."""

    def execute_job(self, job: Job, queue: Queue) -> None:
        try:
            super().execute_job(job, queue)
        finally:
            shutil.rmtree(job_folder(job.id), ignore_errors=True)


class RedisQueue:
    """The job queue on the Redis server at ``url`` (``jobs.open_queue(url, ...)``)."""

    def __init__(self, url: str, *, cpu_seconds: int, memory_mb: int, waiting: int) -> None:
        from redis import Redis

        self.url = url
        self.cpu_seconds, self.memory_mb, self.waiting = cpu_seconds, memory_mb, waiting
        self.connection = Redis.from_url(url)
        self.queue = Queue(QUEUE, connection=self.connection)
        self.timeout = wall_seconds(cpu_seconds)
        self._enqueue = asyncio.Lock()  # the count and the enqueue of one server, in turn
        self._mean = FIRST_GUESS

    def retry_after(self, queued: int) -> int:
        workers = max(1, Worker.count(queue=self.queue))
        return max(1, math.ceil(self._mean * (queued + 1) / workers))

    async def run(self, spec: JobSpec) -> JobResult:
        loop = asyncio.get_running_loop()
        started = loop.time()
        try:
            async with self._enqueue:
                queued = await asyncio.to_thread(lambda: self.queue.count)
                if queued >= self.waiting:
                    raise QueueFull(await asyncio.to_thread(self.retry_after, queued))
                job = await asyncio.to_thread(
                    self.queue.enqueue, perform, spec, self.cpu_seconds, self.memory_mb,
                    job_timeout=self.timeout, result_ttl=RESULT_TTL, failure_ttl=RESULT_TTL,
                    ttl=QUEUED_TTL, description=f"weave-cut {spec.command} ({spec.kind})")
        except QueueFull:
            raise
        except Exception as exc:  # noqa: BLE001 - Redis unreachable: an answer, not a crash
            return failed(503, f"the job queue cannot be reached: {type(exc).__name__}: {exc}")
        try:
            result = await self._wait(spec, job, started + QUEUED_TTL + self.timeout + 60)
            self._mean = 0.8 * self._mean + 0.2 * (loop.time() - started)
            return result
        except asyncio.CancelledError:
            await asyncio.shield(asyncio.to_thread(self._cancel, job))
            raise
        finally:
            await asyncio.shield(asyncio.to_thread(self._forget, job))

    async def _wait(self, spec: JobSpec, job: Job, deadline: float) -> JobResult:
        loop = asyncio.get_running_loop()
        while True:
            result = await asyncio.to_thread(job.latest_result, 1)  # blocks up to 1 s
            if result is not None:
                return self._answer(spec, result)
            try:
                status = await asyncio.to_thread(job.get_status)
            except (NoSuchJobError, InvalidJobOperation):  # rq 2 raises the latter when the
                status = None  # job's key is gone (its queued TTL passed, or it was deleted)
            if status in (None, JobStatus.CANCELED, JobStatus.STOPPED) \
                    or loop.time() > deadline:
                return failed(503, f"no weave-cut worker took the job (is one running for "
                              f"{self.url}?); try again later")

    def _answer(self, spec: JobSpec, result: Result) -> JobResult:
        if result.type == Result.Type.SUCCESSFUL and isinstance(result.return_value, JobResult):
            return result.return_value
        text = (result.exc_string or "").strip()
        if "JobTimeoutException" in text:
            return too_long(spec, self.timeout)
        last = text.splitlines()[-1] if text else "no result"
        return failed(500, f"the worker could not run the job: {last}")

    def _cancel(self, job: Job) -> None:
        """Take a waiting job out of the queue; stop one that runs (RQ's stop-job, and
        ``cancel_key``, which the job's horse looks at, for one a worker took meanwhile)."""
        from rq.command import send_stop_job_command

        try:
            self.connection.set(cancel_key(job.id), 1, ex=QUEUED_TTL + self.timeout + 60)
            status = job.get_status()
            if status in (JobStatus.QUEUED, JobStatus.DEFERRED, JobStatus.SCHEDULED):
                job.cancel()
            elif status == JobStatus.STARTED:
                send_stop_job_command(self.connection, job.id)
        except Exception:  # noqa: BLE001 - best effort: it may have ended meanwhile
            pass

    def _forget(self, job: Job) -> None:
        """Remove a job that has ended, and its results, from Redis (RQ's TTLs remove the
        others)."""
        try:
            if job.get_status() in (JobStatus.FINISHED, JobStatus.FAILED):
                job.delete()
                self.connection.delete(Result.get_key(job.id), cancel_key(job.id))
        except Exception:  # noqa: BLE001 - best effort
            pass

    async def close(self) -> None:
        self.connection.close()
