"""One job in a child process with a CPU-time and a memory limit, and what its end means.

The child (``child_main``) is forked from a warm parent that has weave-cut loaded (``warm``):
the embedded queue's forkserver, or an RQ work horse. It sets its limits, runs ``run_job``
with its temporary files in the folder ``jobdir`` that the parent made (so the parent removes
them whatever happens), and writes the result there (``RESULT``, written whole or not at all).
The parent then reads it with ``outcome``, which turns a child that did not write one (killed
by its CPU limit, or ended by a signal) into a one-line answer.

- CPU: RLIMIT_CPU = the limit (SIGXCPU ends the child, its default action), hard limit one
  second later (SIGKILL, should the child block SIGXCPU), RLIMIT_CORE = 0 (no core file).
- Memory: RLIMIT_AS = the address space the child has at its start (the loaded program,
  shared with the parent) + ``memory_mb``: what a job may add. weave-cut's own memory
  estimates read that limit (``budget.memory_limit``) and refuse larger work before it starts
  (422, with the numbers); an allocation that fails anyway is a MemoryError, 422 too.
"""

from __future__ import annotations

import os
import signal
import tempfile
from dataclasses import replace
from pathlib import Path

from .jobs import OUT_OF_MEMORY, JobResult, JobSpec, failed, run_job

RESULT = "result"  # the file the child writes its result to, in the job's folder


def wall_seconds(cpu_seconds: int) -> int:
    """The wall-clock time a job may take: twice its CPU time and half a minute (a job that
    waits, rather than computes, is stopped too); an hour without a CPU limit."""
    return 2 * cpu_seconds + 30 if cpu_seconds > 0 else 3600


def too_long(spec: JobSpec, seconds: int) -> JobResult:
    return failed(422, f"the {kind_of(spec)} took more than {seconds} s; {_hint(spec)}")


def _hint(spec: JobSpec) -> str:
    return ("simplify the drawing or mesh" if spec.kind == "read" else
            "try fewer levels or a smaller size, or run it with the weave-cut command")


def kind_of(spec: JobSpec) -> str:
    return {"preview": "preview", "read": "reading of the upload"}.get(spec.kind, "kit")


def set_limits(cpu_seconds: int, memory_mb: int) -> None:
    """Limit this process to ``cpu_seconds`` of CPU and ``memory_mb`` MB of address space
    beyond what it has now (no limit where 0)."""
    import resource

    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    if cpu_seconds > 0:
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_seconds, cpu_seconds + 1))
    if memory_mb > 0:
        resource.setrlimit(resource.RLIMIT_AS, (_address_space() + (memory_mb << 20),) * 2)


def _address_space() -> int:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")


def child_main(spec: JobSpec, jobdir: str, cpu_seconds: int, memory_mb: int) -> None:
    """Run ``spec`` under the limits; its result goes to ``jobdir/RESULT``."""
    from ..fileio import write_atomic
    from ..subdivision.hierarchy import keep_freed_memory

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent ends a job, not the terminal
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    set_limits(cpu_seconds, memory_mb)
    keep_freed_memory()  # as the command line does
    tempfile.tempdir = jobdir
    if spec.kind == "read":
        from .uploads import read_job

        result = read_job(spec)
    else:
        result = run_job(spec)
    if result.error == OUT_OF_MEMORY and memory_mb > 0:
        result = replace(result, error=f"the {kind_of(spec)} needed more than the {memory_mb} "
                         "MB of memory a job may use")
    write_atomic(Path(jobdir) / RESULT, result.to_bytes())


def outcome(spec: JobSpec, jobdir: str | Path, exitcode: int | None, cpu_seconds: int,
            memory_mb: int) -> JobResult:
    """The result the child left in ``jobdir``, or what its ``exitcode`` (negative: the
    signal) means."""
    try:
        return JobResult.from_bytes((Path(jobdir) / RESULT).read_bytes())
    except (OSError, ValueError):
        pass
    what = kind_of(spec)
    if exitcode == -signal.SIGXCPU and cpu_seconds > 0:  # its default action ends the child
        return failed(422, f"the {what} took more than {cpu_seconds} s of CPU; {_hint(spec)}")
    how = (f"signal {signal.Signals(-exitcode).name}" if exitcode is not None and exitcode < 0
           else f"status {exitcode}")
    hint = f" (it may have run out of the {memory_mb} MB of memory a job may use)" \
        if memory_mb > 0 else ""
    return failed(500, f"the {what} job ended with {how}{hint}")
