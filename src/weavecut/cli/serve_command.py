"""``weave-cut serve``: the web app (``weavecut.web``) on this machine."""

from __future__ import annotations

import os
import socket
import threading
import webbrowser
from pathlib import Path

import click

from .common import CONTEXT

LOOPBACK = ("127.0.0.1", "localhost", "::1")
JOB_CPU_SECONDS = 300  # a kit takes seconds; the largest puzzle about a minute
JOB_MEMORY_MB = 4096
WAITING = 32  # jobs waiting for a worker before the app answers 503
CACHE_BYTES = 2 * 2**30


def default_cache() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "weave-cut" / "web"


@click.command("serve", context_settings=CONTEXT)
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to listen on; 0.0.0.0 shares the app on the workshop's network.")
@click.option("--port", type=click.IntRange(0, 65535), default=8000, show_default=True,
              help="Port to listen on (0: any free port).")
@click.option("--open", "open_browser", is_flag=True, help="Open the start page in a browser.")
@click.option("--queue", "queue_url", default=None, metavar="URL",
              help="redis://HOST:PORT/DB: send jobs through RQ on Redis, made by "
                   "'weave-cut worker' on any machine [default: worker processes here].")
@click.option("--workers", type=click.IntRange(1, 256), default=None,
              help="Kits made at once [default: the number of cores].")
@click.option("--waiting", type=click.IntRange(0, 100_000), default=WAITING, show_default=True,
              help="Kits that may wait for a worker; one more is answered 503 with "
                   "Retry-After (busy, try again).")
@click.option("--cache", "cache_dir", default=None, metavar="DIR",
              help="Folder for uploads and finished kits [default: ~/.cache/weave-cut/web].")
def serve_command(host, port, open_browser, queue_url, workers, waiting, cache_dir) -> None:
    """Serve the web app: a page per product with its options, a live preview, and the kit
    as a ZIP (the same files as the command line's). Prints the address; Ctrl-C stops it.

    \b
    Examples:
      weave-cut serve --open
      weave-cut serve --host 0.0.0.0 --port 8080 --workers 4
      weave-cut serve --queue redis://localhost:6379/0
    """
    import uvicorn

    from ..web.server import create_app

    from ..web.cache import Cache
    from ..web.queues import open_queue

    folder = Path(cache_dir) if cache_dir else default_cache()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        cache = Cache(folder / "results", CACHE_BYTES)
    except OSError as exc:
        raise click.ClickException(f"cannot use {folder} for the cache: {exc.strerror}") \
            from exc
    sock = _listen(host, port)
    queue = open_queue(queue_url, workers=workers or os.cpu_count() or 1,
                       cpu_seconds=JOB_CPU_SECONDS, memory_mb=JOB_MEMORY_MB, waiting=waiting)
    app = create_app(queue, cache, folder, list(LOOPBACK) if host in LOOPBACK else None)
    shown = socket.gethostname() if host in ("0.0.0.0", "::") else host
    url = f"http://{f'[{shown}]' if ':' in shown else shown}:{sock.getsockname()[1]}/"
    click.echo(f"weave-cut serves {url}  (Ctrl-C stops it)", err=False)
    if open_browser:
        threading.Timer(0.5, webbrowser.open, (url,)).start()
    server = uvicorn.Server(uvicorn.Config(app, log_level="warning", lifespan="on"))
    try:
        server.run(sockets=[sock])
    except KeyboardInterrupt:  # uvicorn stops cleanly, then raises the signal it caught
        pass
    click.echo("weave-cut: the web app stopped", err=True)


def _listen(host: str, port: int) -> socket.socket:
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((host, port))
        sock.listen(128)
    except (OSError, OverflowError) as exc:
        sock.close()
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
        raise click.ClickException(f"cannot listen on {host}:{port}: {why}") from exc
    sock.set_inheritable(True)
    return sock
