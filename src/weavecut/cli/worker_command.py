"""``weave-cut worker``: run web jobs from a Redis queue (``weave-cut serve --queue``)."""

from __future__ import annotations

import click

from .common import CONTEXT

URL_SCHEMES = ("redis://", "rediss://", "unix://")


@click.command("worker", context_settings=CONTEXT)
@click.option("--queue", "url", required=True, metavar="redis://HOST:PORT/DB",
              help="The Redis server that weave-cut serve --queue sends jobs to.")
@click.option("--cpu-seconds", type=click.IntRange(1, 86_400), default=120, show_default=True,
              help="CPU time a job may take (the server's limit applies too, the lower wins).")
@click.option("--memory", "memory_mb", type=click.IntRange(64, 1 << 20), default=2048,
              show_default=True, help="Memory in MB a job may take beyond the loaded program.")
@click.option("--name", default=None, help="The worker's name in Redis [default: RQ's].")
@click.option("--burst", is_flag=True, help="Stop when the queue is empty.")
def worker_command(url: str, cpu_seconds: int, memory_mb: int, name: str | None,
                   burst: bool) -> None:
    """Run the jobs of a web app's queue (weave-cut serve --queue), each in its own process
    within --cpu-seconds and --memory; start as many workers, on as many machines, as the
    jobs need.

    \b
    Examples:
      weave-cut serve --queue redis://127.0.0.1:6379/0
      weave-cut worker --queue redis://127.0.0.1:6379/0 --cpu-seconds 60 --memory 1024
    """
    if not url.startswith(URL_SCHEMES):
        raise click.BadParameter(f"{url!r} is not a Redis URL like redis://HOST:PORT/DB",
                                 param_hint="'--queue'")
    from redis import Redis
    from redis.exceptions import RedisError

    from ..web import redis_queue, warm  # noqa: F401 - warm: the jobs' modules, loaded once

    connection = Redis.from_url(url)
    try:
        connection.ping()
    except (RedisError, OSError) as exc:
        raise click.ClickException(f"cannot reach Redis at {url}: {exc}") from exc
    redis_queue.WORKER_LIMITS[:] = [cpu_seconds, memory_mb]
    worker = redis_queue.JobWorker([redis_queue.QUEUE], connection=connection, name=name)
    worker.work(burst=burst)
