"""The job queue the web app sends its jobs to: embedded, or RQ on Redis.

(Here, not in ``jobs``: the queues import ``jobs``, and ``jobs`` stays free of them.)
"""

from __future__ import annotations

from .jobs import JobQueue


def open_queue(url: str | None, *, workers: int, cpu_seconds: int, memory_mb: int,
               waiting: int) -> JobQueue:
    """The embedded queue (``url`` None): ``workers`` child processes at most; or RQ on the
    Redis server at ``url`` ("redis://host:port/db"), whose ``weave-cut worker`` processes
    run the jobs. Each job may use ``cpu_seconds`` of CPU and ``memory_mb`` MB of memory
    beyond the loaded program; at most ``waiting`` jobs wait, then QueueFull."""
    if url is None:
        from .local_queue import LocalQueue

        return LocalQueue(workers=workers, cpu_seconds=cpu_seconds, memory_mb=memory_mb,
                          waiting=waiting)
    from .redis_queue import RedisQueue

    return RedisQueue(url, cpu_seconds=cpu_seconds, memory_mb=memory_mb, waiting=waiting)
