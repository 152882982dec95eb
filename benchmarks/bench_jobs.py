"""Web jobs: what starting a job costs, and a kit's latency through each queue, cold and
cached.

- Start: jobs that do almost nothing (``stats pentagon --levels 1``, which needs numpy only,
  and the square grid's ``strands --preview``, which needs the paper model's libraries), run in
  this process (the work), in a child forked from the embedded queue's warm parent, and as a
  fresh ``python -m weavecut`` process (what a queue without a warm parent would pay); the
  median of ``--repeat`` runs each, wall and CPU time (the CPU time of the forked child
  before the job starts is its start cost; on a busy machine the wall times stretch).
- Kits: the square-grid paper model (``strands square-grid --size 27cm``) and the puzzle
  (``puzzle --levels 3``) through the embedded queue and through RQ (a redis-server on a free
  loopback port and ``--workers`` ``weave-cut worker`` processes, when redis-server is
  installed): cold (the job runs, then is kept in the cache) and cached (the cache answers).

    python benchmarks/bench_jobs.py [--repeat 15] [--workers 2]
"""

from __future__ import annotations

import argparse
import asyncio
import os
import resource
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from weavecut.web.cache import Cache
from weavecut.web.jobs import JobSpec, command_line, run_job
from weavecut.web.queues import open_queue

TINY = JobSpec("preview", "stats", ("pentagon", "--levels", "1"))  # numpy only
SMALL = JobSpec("preview", "strands", ("square-grid",))  # the paper model's libraries
KITS = {"paper model": JobSpec("kit", "strands", ("square-grid", "--size", "27cm")),
        "puzzle": JobSpec("kit", "puzzle", ("--levels", "3"))}


def median_ms(times: list[float]) -> str:
    return f"{1000 * statistics.median(times):7.1f} ms"


def timed(fn, repeat: int) -> list[float]:
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return out


async def timed_async(fn, repeat: int) -> list[float]:
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        await fn()
        out.append(time.perf_counter() - t0)
    return out


def _traced_child_main(spec, jobdir, cpu_seconds, memory_mb):
    """``limits.child_main``, recording the child's CPU time before and during the job."""
    import resource

    from weavecut.web import limits

    before = resource.getrusage(resource.RUSAGE_SELF)
    limits.child_main(spec, jobdir, cpu_seconds, memory_mb)
    after = resource.getrusage(resource.RUSAGE_SELF)
    cpu = [r.ru_utime + r.ru_stime for r in (before, after)]
    Path(jobdir, "..", f"cpu-{os.getpid()}").write_text(f"{cpu[0]} {cpu[1] - cpu[0]}")


def cpu_of(argv: list[str], folder: str) -> tuple[float, float]:
    """Wall and CPU seconds (user + system) of one run of ``argv``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(argv, cwd=folder, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def start_costs(spec: JobSpec, repeat: int) -> None:
    from weavecut.web import local_queue

    run_job(spec)  # load the commands
    work = timed(lambda: run_job(spec), repeat)
    work_cpu = []
    for _ in range(repeat):
        t0 = time.process_time()
        run_job(spec)
        work_cpu.append(time.process_time() - t0)
    folder = tempfile.mkdtemp()

    async def forked():
        local_queue.child_main = _traced_child_main
        queue = local_queue.LocalQueue(workers=1, cpu_seconds=60, memory_mb=1000, waiting=1,
                                       folder=folder)
        await queue.run(spec)  # the warm parent starts
        try:
            return await timed_async(lambda: queue.run(spec), repeat)
        finally:
            await queue.close()

    child = asyncio.run(forked())
    child_cpu = [tuple(map(float, p.read_text().split())) for p in Path(folder).glob("cpu-*")]
    argv = [sys.executable, "-m", "weavecut", *command_line(spec)]
    fresh, fresh_cpu = zip(*(cpu_of(argv, folder) for _ in range(repeat)))
    shutil.rmtree(folder)
    job = statistics.median(work_cpu)
    print(f"a job ({' '.join(command_line(spec))}), median of {repeat} (load average "
          f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores):")
    print(f"  in this process (the work)        wall {median_ms(work)}   CPU "
          f"{median_ms(work_cpu)}")
    print(f"  forked from the warm parent       wall {median_ms(child)}   CPU before the job "
          f"{median_ms([c for c, _ in child_cpu])}, in it {median_ms([j for _, j in child_cpu])}")
    print(f"  a fresh python -m weavecut        wall {median_ms(list(fresh))}   CPU "
          f"{median_ms(list(fresh_cpu))}, less the job's {median_ms([c - job for c in fresh_cpu])}")


async def kit_latency(url: str | None, label: str, workers: int, cache_dir: Path) -> None:
    queue = open_queue(url, workers=workers, cpu_seconds=120, memory_mb=2000, waiting=20)
    cache = Cache(cache_dir / label, 1 << 30)
    try:
        await queue.run(TINY)  # warm: the forkserver, or the workers' first job
        for name, spec in KITS.items():
            t0 = time.perf_counter()
            result = await queue.run(spec)
            cache.put(spec.key(), result)
            cold = time.perf_counter() - t0
            t0 = time.perf_counter()
            again = cache.get(spec.key())
            cached = time.perf_counter() - t0
            assert again == result and result.ok, result.error
            print(f"  {label:9} {name:12} cold {cold:6.2f} s   cached {1000 * cached:6.1f} ms"
                  f"   ({len(result.body) / 1024:,.0f} KiB)")
    finally:
        await queue.close()


def redis_up(folder: Path, workers: int):
    """(url, processes) of a redis-server on a free port and its weave-cut workers."""
    import redis
    from rq import Worker

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    procs = [subprocess.Popen([shutil.which("redis-server"), "--bind", "127.0.0.1", "--port",
                               str(port), "--save", "", "--appendonly", "no", "--dir",
                               str(folder)], stdout=subprocess.DEVNULL)]
    url = f"redis://127.0.0.1:{port}/0"
    connection = redis.Redis.from_url(url)
    for _ in range(600):
        try:
            if connection.ping():
                break
        except redis.exceptions.ConnectionError:
            time.sleep(0.05)
    for n in range(workers):
        procs.append(subprocess.Popen([sys.executable, "-m", "weavecut", "worker", "--queue",
                                       url, "--name", f"bench-{n}"],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    while len(Worker.all(connection=connection)) < workers:
        time.sleep(0.1)
    return url, procs


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=15)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    for spec in (TINY, SMALL):
        start_costs(spec, args.repeat)
    folder = Path(tempfile.mkdtemp())
    print("kits (the cache: a Cache on local disk):")
    try:
        asyncio.run(kit_latency(None, "embedded", args.workers, folder))
        if shutil.which("redis-server") is None:
            print("  redis    (redis-server is not installed)")
            return 0
        url, procs = redis_up(folder, args.workers)
        try:
            asyncio.run(kit_latency(url, "redis", args.workers, folder))
        finally:
            for p in reversed(procs):
                p.terminate()
                p.wait(60)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
