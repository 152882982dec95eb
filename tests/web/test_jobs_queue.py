"""The embedded queue: every job in its own child with a CPU and a memory limit; a job over
either answers 422 and the queue goes on; at most ``waiting`` jobs wait; a cancelled job's
child is killed and its folder removed."""

from __future__ import annotations

import asyncio
import os

import pytest

from weavecut.web.jobs import JobSpec, QueueFull, run_job
from weavecut.web.local_queue import LocalQueue, job_folders
from weavecut.web.queues import open_queue

QUICK = JobSpec("preview", "strands", ("square-grid",))
SLOW = JobSpec("kit", "puzzle", ("--levels", "5"))  # tens of seconds of CPU


def run(coroutine):
    return asyncio.run(coroutine)


async def until(condition, what: str) -> None:
    """Wait (in steps of 10 ms, at most a minute) until ``condition()``."""
    for _ in range(6000):
        if condition():
            return
        await asyncio.sleep(0.01)
    raise AssertionError(f"never: {what}")


def limited(tmp_path, workers: int, waiting: int) -> LocalQueue:
    """A queue whose limits a slow job stays within, with its job folders in ``tmp_path``."""
    return LocalQueue(workers=workers, cpu_seconds=120, memory_mb=2000, waiting=waiting,
                      folder=tmp_path)


async def running(queue: LocalQueue) -> asyncio.Task:
    """A task that runs a slow job on ``queue``, once the job's child has started."""
    before = len(queue.pids())
    task = asyncio.create_task(queue.run(SLOW))
    await until(lambda: len(queue.pids()) > before, "the job runs")
    return task


def gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


def test_open_queue_without_a_url_is_the_embedded_queue(tmp_path):
    queue = open_queue(None, workers=1, cpu_seconds=30, memory_mb=500, waiting=0)
    assert isinstance(queue, LocalQueue)
    run(queue.close())


def test_a_job_in_a_child_gives_what_it_gives_in_process(tmp_path):
    async def main():
        queue = limited(tmp_path, workers=1, waiting=1)
        try:
            return await queue.run(QUICK), await queue.run(
                JobSpec("kit", "strands", ("square-grid", "--size", "27")))
        finally:
            await queue.close()

    preview, refused = run(main())
    assert preview == run_job(QUICK)
    assert (refused.status, refused.error) == (400, run_job(
        JobSpec("kit", "strands", ("square-grid", "--size", "27"))).error)
    assert job_folders(tmp_path) == []


def then_quick(tmp_path, cpu_seconds: int, memory_mb: int, *specs: JobSpec) -> list:
    """The results of ``specs`` and then of a quick job, in turn on one queue."""
    async def main():
        queue = LocalQueue(workers=1, cpu_seconds=cpu_seconds, memory_mb=memory_mb, waiting=2,
                           folder=tmp_path)
        try:
            return [await queue.run(spec) for spec in (*specs, QUICK)]
        finally:
            await queue.close()

    results = run(main())
    assert results[-1].ok and results[-1].body == run_job(QUICK).body  # the queue goes on
    assert job_folders(tmp_path) == []
    return results[:-1]


def test_over_its_cpu_limit_a_job_answers_422_and_the_queue_goes_on(tmp_path):
    [cpu] = then_quick(tmp_path, 1, 2000, SLOW)  # tens of seconds of CPU
    assert (cpu.status, cpu.error.split(";")[0]) == (422, "the kit took more than 1 s of CPU")


@pytest.mark.slow
def test_over_its_memory_limit_a_job_answers_422_and_the_queue_goes_on(tmp_path):
    memory, estimate = then_quick(
        tmp_path, 120, 60,
        # no estimate refuses it: an allocation fails (a MemoryError) under RLIMIT_AS
        JobSpec("kit", "strands", ("pentagon-flower",)),
        # refused by weave-cut's own estimate, which reads the limit
        JobSpec("kit", "levels", ("pentagon", "--levels", "9", "--size", "2048")))
    assert (memory.status, memory.error) == (
        422, "the kit needed more than the 60 MB of memory a job may use")
    assert estimate.status == 422 and "address-space limit" in estimate.error


def test_a_full_queue_raises_queue_full_with_a_retry_time(tmp_path):
    async def main():
        queue = limited(tmp_path, workers=1, waiting=1)
        first = await running(queue)
        waiting = asyncio.create_task(queue.run(QUICK))
        await until(lambda: queue.queued() == 1, "the second job waits")
        try:
            with pytest.raises(QueueFull) as full:
                await queue.run(QUICK)
        finally:
            first.cancel()
            results = await asyncio.gather(first, waiting, return_exceptions=True)
            await queue.close()
        return full.value, results

    full, (first, second) = run(main())
    assert full.retry_after >= 1 and "try again" in str(full)
    assert isinstance(first, asyncio.CancelledError)
    assert second.ok  # the waiting job ran once the first was cancelled


def test_cancelling_the_awaiting_task_kills_the_child_and_removes_its_folder(tmp_path):
    async def main():
        queue = limited(tmp_path, workers=2, waiting=0)
        task = await running(queue)
        pid = queue.pids()[0]
        assert not gone(pid) and len(job_folders(tmp_path)) == 1
        task.cancel()
        with pytest.raises(asyncio.CancelledError):
            await task
        killed, folders = gone(pid), job_folders(tmp_path)  # at once, not at close()
        try:
            return killed, folders, await queue.run(QUICK)
        finally:
            await queue.close()

    killed, folders, after = run(main())
    assert killed and folders == []
    assert after.ok


def test_workers_bound_the_jobs_that_run_at_once(tmp_path):
    async def main():
        queue = limited(tmp_path, workers=2, waiting=5)
        tasks = [asyncio.create_task(queue.run(SLOW)) for _ in range(3)]
        await until(lambda: len(queue.pids()) == 2 and queue.queued() == 1, "two run")
        most = len(queue.pids())
        for task in tasks:
            task.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)
        await queue.close()
        return most

    assert run(main()) == 2
    assert job_folders(tmp_path) == []


def _sleeps(spec, jobdir, cpu_seconds, memory_mb):
    """A job that waits instead of computing (no CPU limit stops it)."""
    import time

    time.sleep(20)  # far beyond the 1 s the test allows


def test_a_job_past_its_wall_clock_time_is_killed_and_answers_422(tmp_path, monkeypatch):
    from weavecut.web import local_queue

    monkeypatch.setattr(local_queue, "child_main", _sleeps)
    monkeypatch.setattr(local_queue, "wall_seconds", lambda cpu: 1)

    async def main():
        queue = limited(tmp_path, workers=1, waiting=0)
        pids = []
        task = asyncio.create_task(queue.run(QUICK))
        await until(lambda: queue.pids(), "the job runs")
        pids += queue.pids()
        try:
            return await task, pids
        finally:
            await queue.close()

    result, [pid] = run(main())
    assert (result.status, result.error.split(";")[0]) == (
        422, "the preview took more than 1 s")
    assert gone(pid) and job_folders(tmp_path) == []


def test_a_job_killed_by_closing_the_queue_answers_503_and_leaves_no_folder(tmp_path):
    """A server shutting down kills its running jobs: the answer says so (try again), not a
    job that died by its limits (422) or crashed (500)."""
    async def main():
        queue = limited(tmp_path, workers=1, waiting=0)
        task = await running(queue)
        pid = queue.pids()[0]
        await queue.close()
        result = await asyncio.wait_for(task, 60)
        with pytest.raises(RuntimeError, match="the job queue is closed"):
            await queue.run(QUICK)
        return result, pid

    result, pid = run(main())
    assert (result.status, result.error) == (503, "the server is shutting down; try again")
    assert gone(pid) and job_folders(tmp_path) == []
