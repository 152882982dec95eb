"""The Redis queue's guards (each disabled once by ``tests/hand_audit/guards.py``, #34): a job
folder is named by a job id only, a job whose client left is answered 499 and not run (or
stopped), a job that vanished from the queue is answered 503 instead of waited for, and the
fallback wait (no pidfd) reads a child's end. Jobs go to the real workers of
``test_jobs_redis``'s server."""

from __future__ import annotations

import asyncio
import os
import tempfile
import time

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tests.web.test_jobs_redis import server, wait_for  # noqa: F401  (the fixture)
from weavecut.web import redis_queue
from weavecut.web.jobs import JobResult, JobSpec, failed
from weavecut.web.queues import open_queue
from weavecut.web.redis_queue import QUEUE, cancel_key, job_folder, perform

rq = pytest.importorskip("rq")
pytestmark = pytest.mark.slow

QUICK = JobSpec("preview", "strands", ("square-grid",))
SLOW = JobSpec("kit", "puzzle", ("--levels", "5"))  # tens of seconds of CPU


@given(st.text(max_size=120))
def test_a_job_folder_is_named_by_a_job_id_only(job_id):
    try:
        folder = job_folder(job_id)
    except ValueError as exc:
        assert "is not an RQ job id" in str(exc)
        assert not redis_queue.JOB_ID.fullmatch(job_id)
        return
    assert folder.parent == type(folder)(tempfile.gettempdir())
    assert folder.name == f"weave-cut-rq-{job_id}" and "/" not in job_id and job_id not in (
        "", ".", "..")


@pytest.mark.parametrize("job_id", ["", "..", "../../etc", "a/b", "x" * 101, "id\n"])
def test_a_path_is_no_job_id(job_id):
    with pytest.raises(ValueError):
        job_folder(job_id)


def result_of(job, seconds: float = 120) -> JobResult:
    """What a worker returned for ``job`` (an RQ job enqueued directly)."""
    wait_for(lambda: job.latest_result() is not None, "the job ends", seconds)
    result = job.latest_result()
    assert result.type == result.Type.SUCCESSFUL, result.exc_string
    return result.return_value


def test_a_job_whose_client_left_before_it_started_is_not_run(server):  # noqa: F811
    url, connection = server
    queue = rq.Queue(QUEUE, connection=connection)
    connection.set(cancel_key("left-early"), 1, ex=600)
    job = queue.enqueue(perform, QUICK, 120, 2000, job_id="left-early", result_ttl=600)
    try:
        assert result_of(job) == failed(499, "the client left before the job started")
    finally:
        job.delete()


def test_a_running_job_whose_client_leaves_answers_499(server):  # noqa: F811
    url, connection = server
    queue = rq.Queue(QUEUE, connection=connection)
    job = queue.enqueue(perform, SLOW, 120, 2000, job_id="leaves-later", result_ttl=600)
    try:
        wait_for(lambda: job.get_meta(refresh=True).get("child"), "the job's child runs", 120)
        connection.set(cancel_key(job.id), 1, ex=600)
        result = result_of(job)
        assert (result.status, result.error) == (499, "the client left; the job was stopped")
    finally:
        job.delete()


def test_a_job_gone_from_the_queue_is_answered_not_waited_for(server):  # noqa: F811
    url, connection = server
    idle = url.rsplit("/", 1)[0] + "/2"  # the workers serve db 0 only

    async def main():
        queue = open_queue(idle, workers=1, cpu_seconds=60, memory_mb=2000, waiting=2)
        task = asyncio.create_task(queue.run(QUICK))
        jobs = rq.Queue(QUEUE, connection=queue.connection)
        for _ in range(1200):
            if jobs.job_ids:
                break
            await asyncio.sleep(0.05)
        rq.job.Job.fetch(jobs.job_ids[0], connection=queue.connection).delete()
        try:
            return await asyncio.wait_for(task, 60)
        finally:
            await queue.close()

    result = asyncio.run(main())
    assert result.status == 503
    assert result.error.startswith("no weave-cut worker took the job (is one running for")


def test_without_a_pidfd_the_wait_reads_the_childs_end(monkeypatch):
    monkeypatch.delattr(os, "pidfd_open", raising=False)
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        os._exit(3)
    looked = []

    def cancelled() -> bool:  # the end is seen within a look or two, never 100
        looked.append(time.monotonic())
        if len(looked) > 100:
            raise AssertionError("the child's end was never seen")
        return False

    status = redis_queue._wait(pid, cancelled)
    assert os.WIFEXITED(status) and os.WEXITSTATUS(status) == 3
