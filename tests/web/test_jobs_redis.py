"""Jobs through RQ on a real Redis: a ``redis-server`` on a free loopback port in a temporary
folder, two ``weave-cut worker`` processes; kits come back byte-identical to ``run_job``'s
(which test_jobs holds equal to the command line's files), both workers take jobs, the queue
is bounded and a client that leaves cancels its job. Skipped where redis-server is missing,
except in CI (.ci/run installs it)."""

from __future__ import annotations

import asyncio
import socket
import subprocess
import sys
import time

import pytest

from tests.test_readback import program
from tests.web.test_jobs_queue import gone
from weavecut.web.jobs import JobSpec, QueueFull, run_job
from weavecut.web.queues import open_queue

redis = pytest.importorskip("redis")
rq = pytest.importorskip("rq")
pytestmark = pytest.mark.slow  # a Redis server and workers (its tests stay together)


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for(condition, what: str, seconds: float = 60) -> None:
    for _ in range(int(seconds / 0.05)):
        if condition():
            return
        time.sleep(0.05)
    raise AssertionError(f"never: {what}")


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """(URL of db 0, a connection) of a redis-server that two weave-cut workers serve."""
    folder = tmp_path_factory.mktemp("redis")
    port = free_port()
    redis_server = subprocess.Popen(
        [program("redis-server"), "--bind", "127.0.0.1", "--port", str(port), "--save", "",
         "--appendonly", "no", "--dir", str(folder)],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"redis://127.0.0.1:{port}/0"
    connection = redis.Redis.from_url(url)

    def answers():
        try:
            return connection.ping()
        except redis.exceptions.ConnectionError:
            return False

    workers = []
    try:
        wait_for(answers, "redis-server answers")
        for name in ("worker-a", "worker-b"):
            log = open(folder / f"{name}.log", "w")
            workers.append(subprocess.Popen(
                [sys.executable, "-m", "weavecut", "worker", "--queue", url, "--name", name,
                 "--cpu-seconds", "120", "--memory", "2000"], stdout=log, stderr=log))
        wait_for(lambda: len(rq.Worker.all(connection=connection)) == 2, "both workers listen")
        yield url, connection
    finally:
        for worker in workers:
            worker.terminate()  # RQ's warm shutdown
        for worker in workers:
            try:
                worker.wait(30)
            except subprocess.TimeoutExpired:
                worker.kill()
                worker.wait()
        redis_server.terminate()
        redis_server.wait(30)


KITS = [JobSpec("kit", "strands", ("square-grid", "--size", "27cm")),
        JobSpec("kit", "strands", ("square-grid", "--laser-card", "--palette", "maritime-4")),
        JobSpec("kit", "puzzle", ("--levels", "3")),
        JobSpec("preview", "puzzle", ()),
        JobSpec("kit", "strands", ("pentagon", "--size", "27cm")),
        JobSpec("kit", "strands", ("square-grid", "--size", "27"))]  # a usage error


def test_two_workers_make_the_kits_byte_identical(server):
    url, connection = server

    async def main():
        queue = open_queue(url, workers=2, cpu_seconds=120, memory_mb=2000, waiting=20)
        try:
            started = time.perf_counter()
            results = await asyncio.gather(*(queue.run(spec) for spec in KITS))
            return results, time.perf_counter() - started
        finally:
            await queue.close()

    results, seconds = asyncio.run(main())
    for spec, result in zip(KITS, results):
        assert result == run_job(spec), spec
    assert [r.status for r in results] == [200] * 5 + [400]
    done = {w.name: w.successful_job_count for w in rq.Worker.all(connection=connection)}
    print(f"{len(KITS)} jobs in {seconds:.1f} s, jobs per worker: {done}")
    assert sum(done.values()) >= len(KITS) and min(done.values()) >= 1
    assert rq.Queue("weave-cut", connection=connection).count == 0
    assert not [k for k in connection.keys("rq:job:*")]  # the server removed what it took


def test_a_queue_that_no_worker_serves_fills_up_and_a_leaving_client_cancels(server):
    url, connection = server
    idle = url.rsplit("/", 1)[0] + "/1"  # the workers serve db 0 only

    async def main():
        queue = open_queue(idle, workers=2, cpu_seconds=60, memory_mb=2000, waiting=2)
        waiting = [asyncio.create_task(queue.run(spec)) for spec in KITS[:2]]
        jobs = rq.Queue("weave-cut", connection=queue.connection)
        for _ in range(1200):
            if jobs.count == 2:
                break
            await asyncio.sleep(0.05)
        try:
            with pytest.raises(QueueFull) as full:
                await queue.run(KITS[2])
        finally:
            for task in waiting:
                task.cancel()
            await asyncio.gather(*waiting, return_exceptions=True)
        left = jobs.count
        await queue.close()
        return full.value, left

    full, left = asyncio.run(main())
    assert full.retry_after >= 1
    assert left == 0  # the cancelled jobs left the queue


def test_a_running_job_whose_client_leaves_is_stopped(server):
    url, connection = server

    async def main():
        queue = open_queue(url, workers=2, cpu_seconds=120, memory_mb=2000, waiting=5)
        task = asyncio.create_task(queue.run(JobSpec("kit", "puzzle", ("--levels", "5"))))
        started = rq.registry.StartedJobRegistry("weave-cut", connection=connection)
        for _ in range(1200):
            ids = started.get_job_ids()
            if ids and rq.job.Job.fetch(ids[0], connection=connection).meta.get("child"):
                break
            await asyncio.sleep(0.05)
        job = rq.job.Job.fetch(ids[0], connection=connection)
        child = job.meta["child"]  # the process that runs the job, on this machine
        task.cancel()
        with pytest.raises(asyncio.CancelledError):
            await task
        for _ in range(1200):
            if gone(child):
                break
            await asyncio.sleep(0.05)
        after = await queue.run(KITS[3])
        await queue.close()
        return child, after

    child, after = asyncio.run(main())
    assert gone(child)  # long before the 20 s of CPU the job takes
    assert after.ok  # the workers go on
