"""The Starlette app of ``weave-cut serve``.

Routes: ``GET /`` (start page), ``GET /{command}`` (form and preview; options in the query under
the CLI's long option names), ``GET /{command}/check`` (the query checked by the command:
field messages, the command line, the recipe; JSON), ``GET /{command}/preview.svg``,
``GET /{command}/summary.json`` (the kit's figures; ``model``: whether it has a 3-D model),
``GET /{command}.zip`` (the kit), ``GET /{command}/model.glb`` (the kit's woven 3-D model, from
the same job; 404 if it has none: the page asks for it only when ``model`` says it has one),
``POST /upload`` (a drawing as the request body, read by a job like a kit; ``{"id": SHA256,
"kind": "surface" or "flat"}`` for ``input=upload:ID``: a surface in space makes a ball)
``/static/`` and ``/static/viewer/`` (the kit page's 3-D viewer scripts). A bad value answers
400 with the CLI's own message in the form's words (``refusals``; header ``X-Field``: the
form key it belongs to), an unknown command 404, a full queue 503 with Retry-After, anything
unexpected a plain 500 (the traceback goes to the log, never to the browser).

Every kit and preview is a job (``jobs.JobSpec``) run by the queue and kept in the cache by its
key; a client that leaves cancels its job.
"""

from __future__ import annotations

import asyncio
import contextlib
import io
import logging
import zipfile
from pathlib import Path

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.exceptions import HTTPException
from starlette.middleware import Middleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, PlainTextResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from ..kitpage.viewer import STATIC as VIEWER_STATIC
from . import forms, pages, queries, summary
from .refusals import in_form_words, said
from .uploads import MAX_BYTES, Store, UploadError, read_spec

from .jobs import JobSpec, QueueFull

STATIC = Path(__file__).resolve().parent / "static"
MAX_QUERY = 8192  # characters of a query string
POLICY = ("default-src 'self'; img-src 'self' blob: data:; style-src 'self'; "
          "script-src 'self'; connect-src 'self'; object-src 'none'; base-uri 'none'; "
          "form-action 'self'; frame-ancestors 'none'")
SVG_POLICY = "default-src 'none'; style-src 'unsafe-inline'; img-src data:"
log = logging.getLogger("weavecut.web")


class _Headers:
    """ASGI middleware: the content security policy and friends on every answer."""

    def __init__(self, app) -> None:
        self.app = app

    async def __call__(self, scope, receive, send) -> None:
        async def sending(message) -> None:
            if message["type"] == "http.response.start":
                headers = list(message.get("headers", []))
                names = {k.lower() for k, _ in headers}
                for k, v in (("content-security-policy", POLICY),
                             ("x-content-type-options", "nosniff"),
                             ("referrer-policy", "no-referrer"), ("x-frame-options", "DENY")):
                    if k.encode() not in names:
                        headers.append((k.encode(), v.encode()))
                message = {**message, "headers": headers}
            await send(message)

        await (self.app(scope, receive, sending) if scope["type"] == "http"
               else self.app(scope, receive, send))


def _items(request: Request) -> list[tuple[str, str]]:
    if len(request.url.query) > MAX_QUERY:
        raise forms.FormError(f"a query of {len(request.url.query):,} characters; at most "
                              f"{MAX_QUERY:,}")
    return request.query_params.multi_items()


def _refused(name: str, error: forms.FormError) -> Response:
    error = said(error, name)
    return PlainTextResponse(error.message, error.status,
                             headers={"X-Field": error.key} if error.key else None)


async def _unless_gone(request: Request, job):
    """Await ``job``; None (and the job cancelled) if the client disconnects first."""
    task = asyncio.ensure_future(job)

    async def gone() -> None:
        while (await request.receive())["type"] != "http.disconnect":
            pass

    watch = asyncio.ensure_future(gone())
    try:
        await asyncio.wait({task, watch}, return_when=asyncio.FIRST_COMPLETED)
    finally:
        watch.cancel()
    if task.done():
        return task.result()
    task.cancel()
    log.info("client left: job cancelled")
    return None


def _model_name(kit: bytes) -> str | None:
    """The woven 3-D model's name in the ZIP ``kit`` (its first ``.glb`` by name), None if
    it has none."""
    try:
        with zipfile.ZipFile(io.BytesIO(kit)) as z:
            return min((n for n in z.namelist() if n.endswith(".glb")), default=None)
    except zipfile.BadZipFile:
        return None


def create_app(queue, cache, folder: Path, hosts: list[str] | None = None) -> Starlette:
    """The app, its jobs run by ``queue`` (``jobs.open_queue``), results kept in ``cache``
    (``jobs.Cache``), uploads under ``folder/uploads``; ``hosts``: the Host names it answers
    (None: any)."""
    store = Store(Path(folder) / "uploads")
    running: dict[str, list] = {}  # job key -> [its task, how many requests wait for it]

    async def start(request: Request) -> Response:
        return HTMLResponse(pages.start())

    async def page(request: Request) -> Response:
        name = request.path_params["command"]
        try:
            forms.command(name)
        except forms.FormError as exc:
            return HTMLResponse(pages.not_found(exc.message), 404)
        raw: dict[str, str] = {}
        query, error = None, None
        try:
            items = _items(request)
            start = forms.STARTING.get(name)
            if start and all(k != start[0] for k, _ in items):
                items = [start, *items]
            for k, v in items:  # the first value, but a ticked box's after its hidden "off"
                raw[k] = v if raw.get(k) == "off" else raw.get(k, v)
            query = queries.parse(name, items, store)
        except forms.FormError as exc:
            error = said(exc, name)
        value = raw.get("input", "")
        offered = [(value[7:], "your drawing", store.kind(value[7:]))] \
            if forms.UPLOAD.fullmatch(value) else []
        return HTMLResponse(pages.command_page(name, raw, error, query, offered),
                            400 if error else 200)

    async def check(request: Request) -> Response:
        name = request.path_params["command"]
        from .equivalents import command_line, recipe

        try:
            query = queries.parse(name, _items(request), store)
        except forms.FormError as exc:
            exc = said(exc, name)
            return JSONResponse({"ok": False, "errors": {exc.key or "form": exc.message}},
                                exc.status)
        return JSONResponse({"ok": True, "errors": {}, "command_line": command_line(query),
                             "recipe": recipe(query)})

    async def job(request: Request, kind: str):
        """The JobResult of this request's ``kind`` job (from the cache, or run), or the
        Response that refuses it."""
        name = request.path_params["command"]
        try:
            query = queries.parse(name, _items(request), store)
        except forms.FormError as exc:
            return _refused(name, exc)
        spec = JobSpec(kind, name, query.args, await run_in_threadpool(query.job_files),
                       query.output if kind == "kit" else "")
        key = spec.key()
        result = await run_in_threadpool(cache.get, key)
        if result is not None:
            return result
        if key not in running:  # the same job asked twice at once runs once
            task = asyncio.ensure_future(queue.run(spec))
            running[key] = [task, 0]
            task.add_done_callback(
                lambda done: running.pop(key) if running.get(key, [None])[0] is done else None)
        entry = running[key]
        entry[1] += 1
        try:
            result = await _unless_gone(request, asyncio.shield(entry[0]))
        except QueueFull as exc:
            return PlainTextResponse("the server is busy making other kits; try again in a "
                                     "moment", 503, headers={"Retry-After": str(exc.retry_after)})
        finally:
            entry[1] -= 1
        if result is None:
            if entry[1] == 0:  # nobody waits for it any more
                entry[0].cancel()
                running.pop(key, None)
            return Response(status_code=499)
        if not result.ok:
            return _refused(name, forms.FormError(result.error, None, result.status))
        await run_in_threadpool(cache.put, key, result)
        return result

    async def preview(request: Request) -> Response:
        result = await job(request, "preview")
        if isinstance(result, Response):
            return result
        return Response(result.body, media_type=result.media_type,
                        headers={"Content-Security-Policy": SVG_POLICY})

    async def figures(request: Request) -> Response:
        result = await job(request, "kit")
        if isinstance(result, Response):
            return result
        model = await run_in_threadpool(_model_name, result.body)
        return JSONResponse({"figures": summary.figures(result.summary),
                             "warnings": summary.warnings(result.summary),
                             "model": model is not None, "summary": result.summary})

    async def kit(request: Request) -> Response:
        result = await job(request, "kit")
        if isinstance(result, Response):
            return result
        name = request.path_params["command"]
        return Response(result.body, media_type="application/zip", headers={
            "Content-Disposition": f'attachment; filename="weave-cut-{name}.zip"'})

    async def model(request: Request) -> Response:
        result = await job(request, "kit")
        if isinstance(result, Response):
            return result
        name = await run_in_threadpool(_model_name, result.body)
        if name is None:
            return PlainTextResponse("this kit has no 3-D model", 404)
        with zipfile.ZipFile(io.BytesIO(result.body)) as z:
            data = await run_in_threadpool(z.read, name)
        return Response(data, media_type="model/gltf-binary")

    async def upload(request: Request) -> Response:
        size = request.headers.get("content-length", "")
        if size.isdigit() and int(size) > MAX_BYTES:
            return PlainTextResponse(f"{int(size):,} bytes; an upload is at most "
                                     f"{MAX_BYTES >> 20} MiB", 413)
        data = bytearray()
        async for chunk in request.stream():
            data += chunk
            if len(data) > MAX_BYTES:
                return PlainTextResponse(f"more than {MAX_BYTES >> 20} MiB; an upload is at "
                                         f"most {MAX_BYTES >> 20} MiB", 413)
        data = bytes(data)
        try:
            ident, suffix = store.screen(data)  # the size and the first bytes only
        except UploadError as exc:
            return PlainTextResponse(in_form_words(exc.message, None), exc.status)
        if store.find(ident) is None:  # read in a job process, under a job's limits
            try:
                result = await _unless_gone(request, queue.run(read_spec(data, suffix)))
            except QueueFull as exc:
                return PlainTextResponse("the server is busy making kits; upload again in a "
                                         "moment", 503,
                                         headers={"Retry-After": str(exc.retry_after)})
            if result is None:
                return Response(status_code=499)
            if not result.ok:  # the reader's message; its process ended (>= 500): refused
                return PlainTextResponse(in_form_words(result.error, None),
                                         result.status if result.status < 500 else 422)
            await run_in_threadpool(store.keep, data, result.summary.get("kind", ""))
        return JSONResponse({"id": ident, "kind": store.kind(ident)})

    async def http_error(request: Request, exc: HTTPException) -> Response:
        if exc.status_code == 404 and "text/html" in request.headers.get("accept", ""):
            return HTMLResponse(pages.not_found(f"no page at {request.url.path[:80]}"), 404)
        return PlainTextResponse(str(exc.detail), exc.status_code, headers=exc.headers)

    async def crashed(request: Request, exc: Exception) -> Response:
        log.error("internal error on %s", request.url.path, exc_info=exc)
        message = ("internal error: the server's log has the details; please report it with "
                   "the link of this page")
        if "text/html" in request.headers.get("accept", ""):
            return HTMLResponse(pages.failed(message), 500)
        return PlainTextResponse(message, 500)

    @contextlib.asynccontextmanager
    async def lifespan(app):
        yield
        await queue.close()

    routes = [
        Route("/", start),
        Mount("/static/viewer", StaticFiles(directory=VIEWER_STATIC), name="viewer"),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
        Route("/upload", upload, methods=["POST"]),
        Route("/{command}.zip", kit),
        Route("/{command}/preview.svg", preview),
        Route("/{command}/summary.json", figures),
        Route("/{command}/model.glb", model),
        Route("/{command}/check", check),
        Route("/{command}", page),
    ]
    middleware = [Middleware(_Headers)]
    if hosts is not None:
        middleware.append(Middleware(TrustedHostMiddleware, allowed_hosts=hosts))
    return Starlette(routes=routes, middleware=middleware, lifespan=lifespan,
                     exception_handlers={HTTPException: http_error, Exception: crashed})
