"""The FastAPI app: the page, the JSON API, the SSE stream of a job, and the run files.

Routes (all behind `Guard`):

    GET  /                          the page (static/index.html; app.js, app.css in /static)
    GET  /api/info                  models, examples, limits
    GET  /api/jobs                  every job, newest first, and what each model's queue holds
    POST /api/jobs                  {"description", "provider"?, "model"?} -> the queued job
    GET  /api/jobs/{id}             one job (its queue position while it waits)
    POST /api/jobs/{id}/cancel      take it out of the queue, or stop it at its next stage
    GET  /api/jobs/{id}/events      SSE: the job's progress events, then its end
    GET  /api/runs/{id}             the run's script, attempts, spec, conformity and files
    GET  /runs/{id}/files/{name}    one file of the run's own folder
    GET  /runs/{id}/download.zip    scenario.scenic, .xosc, .xodr, report.json, replay.html
    POST /api/check                 {"script", "name"?, "agent"?} -> the validator's verdict
                                    (+ replay, + the agent's driving metrics)
    GET  /checks/{id}/files/{name}  a checked script's replay
    GET  /api/health                liveness (and the checks under way), for scripts and tests

Run folders are read only through `store` and `safefs` (no links followed, sizes bounded);
script checks run in a check process (`checker`), so no request's parsing holds the loop.
"""

from __future__ import annotations

import logging
import mimetypes
import threading
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from importlib import resources
from pathlib import Path
from typing import Any, BinaryIO

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse, Response, StreamingResponse
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel
from sse_starlette.sse import EventSourceResponse
from starlette.concurrency import run_in_threadpool

from arise import __version__
from arise.errors import AriseError
from arise.generate.extract import check_description
from arise.generate.pipeline import Generator
from arise.llm.settings import Settings, load_settings
from arise.serve.board import JobBoard, RunnerFactory
from arise.serve.checker import ScriptChecker
from arise.serve.checks import admit_script
from arise.serve.choices import REPLAY, ModelChoice, model_choices
from arise.serve.config import ServeConfig
from arise.serve.driving import admit_agent, agent_choices
from arise.serve.errors import BadInput, InputTooLarge, ServeError
from arise.serve.events import event_json
from arise.serve.examples import examples
from arise.serve.guard import Guard
from arise.serve.lanes import Runner
from arise.serve.safefs import stream
from arise.serve.store import RunStore, new_id
from arise.serve.view import run_view
from arise.validate import WorkerPool

log = logging.getLogger("arise.serve")

#: Files of a run or a check are shown as what they are, never as a page that could act
#: on the server's origin: HTML (the replay) runs sandboxed, with inline code only.
FILE_CSP = (
    "sandbox allow-scripts; default-src 'none'; script-src 'unsafe-inline'; "
    "style-src 'unsafe-inline'; img-src data: blob:"
)
PAGE_CSP = (
    "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' data:; "
    "frame-src 'self'; connect-src 'self'; object-src 'none'; base-uri 'none'; "
    "frame-ancestors 'none'"
)
TEXT_TYPES = {
    ".scenic": "text/plain; charset=utf-8",
    ".json": "application/json",
    ".xosc": "application/xml",
    ".xodr": "application/xml",
    ".html": "text/html; charset=utf-8",
}
#: Seconds between keep-alive comments on an idle event stream.
STREAM_PING = 15


class GenerateBody(BaseModel):
    description: str
    provider: str | None = None
    model: str | None = None


class CheckBody(BaseModel):
    script: str
    name: str | None = None
    # A built-in driving agent in the ego's seat (its metrics come with the verdict).
    agent: str | None = None


def generator_factory(config: ServeConfig, pool: WorkerPool) -> RunnerFactory:
    """A warm Generator per model, on the server's shared worker pool."""

    def make(choice: ModelChoice) -> Runner:
        if choice.provider == REPLAY:
            update: dict[str, Any] = {"provider": None, "model": None, "replay": config.replay}
        else:
            update = {"provider": choice.provider, "model": choice.model, "replay": None}
        return Generator(config.options.model_copy(update=update), pool=pool)

    return make


def _static(name: str) -> Path:
    return Path(str(resources.files(__package__).joinpath("static", name)))


def _file_response(name: str, opened: tuple[BinaryIO, int]) -> Response:
    """An opened run file (see `RunStore.file`), streamed as what its name says it is."""
    handle, size = opened
    media = TEXT_TYPES.get(Path(name).suffix) or mimetypes.guess_type(name)[0]
    return StreamingResponse(
        stream(handle, size),
        media_type=media or "application/octet-stream",
        headers={
            "Content-Security-Policy": FILE_CSP,
            "Cache-Control": "no-cache",
            "Content-Length": str(size),
        },
    )


def admit_description(text: str, limit: int) -> str:
    """The description as it will run, or a clear refusal (413 too long, 422 unusable)."""
    text = text.strip()
    if len(text) > limit:
        raise InputTooLarge(
            f"the description is {len(text)} characters long; the limit is {limit} "
            "(one scenario per description)"
        )
    refusal = check_description(text)
    if refusal:
        raise BadInput(refusal)
    return text


def create_app(
    config: ServeConfig,
    *,
    pool: WorkerPool | None = None,
    make_runner: RunnerFactory | None = None,
    settings: Settings | None = None,
) -> FastAPI:
    """The app for one configuration. Tests give a pool and a runner factory (a fake);
    by default the app makes its pool (warmed at start) and a Generator per model."""
    choices = model_choices(settings or load_settings(), config.replay)
    state: dict[str, Any] = {}

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        own_pool = pool is None
        active = pool or WorkerPool(size=config.workers)
        if own_pool:  # the first check need not wait for Scenic to import
            threading.Thread(target=active.warm, name="warm pool", daemon=True).start()
        board = JobBoard(
            RunStore(config.runs_dir),
            choices,
            make_runner or generator_factory(config, active),
            config.max_queued,
        )
        checker = ScriptChecker(
            active,
            budget=config.check_parse_seconds,
            slots=config.workers,
            max_waiting=config.max_queued_checks,
        )
        if own_pool:  # nor for its check process to import what it needs
            threading.Thread(target=checker.warm, name="warm checks", daemon=True).start()
        checks = RunStore(config.runs_dir / "checks", root_may_link=False)
        state.update(board=board, pool=active, checks=checks, checker=checker)
        try:
            yield
        finally:
            checker.close()
            board.close()
            if own_pool:
                active.close()

    app = FastAPI(title="arise", version=__version__, lifespan=lifespan, docs_url=None)
    app.mount("/static", StaticFiles(packages=[(__package__, "static")]), name="static")

    def board() -> JobBoard:
        found: JobBoard = state["board"]
        return found

    @app.exception_handler(ServeError)
    async def serve_error(request: Request, error: ServeError) -> JSONResponse:
        return JSONResponse({"error": str(error)}, status_code=error.status)

    @app.exception_handler(AriseError)
    async def arise_error(request: Request, error: AriseError) -> JSONResponse:
        return JSONResponse({"error": str(error)}, status_code=422)

    @app.exception_handler(RequestValidationError)
    async def invalid(request: Request, error: RequestValidationError) -> JSONResponse:
        problems = []
        for item in error.errors()[:3]:
            where = ".".join(str(p) for p in item.get("loc", ()) if p != "body")
            problems.append(f"{where}: {item.get('msg')}" if where else str(item.get("msg")))
        return JSONResponse(
            {"error": "the request cannot be read: " + "; ".join(problems)}, status_code=422
        )

    @app.exception_handler(Exception)
    async def crashed(request: Request, error: Exception) -> JSONResponse:
        log.exception("%s %s failed", request.method, request.url.path)
        return JSONResponse(
            {"error": f"internal error ({type(error).__name__}); the server's log has details"},
            status_code=500,
        )

    @app.get("/", include_in_schema=False)
    async def page() -> Response:
        return FileResponse(
            _static("index.html"),
            media_type="text/html; charset=utf-8",
            headers={"Content-Security-Policy": PAGE_CSP, "Cache-Control": "no-cache"},
        )

    @app.get("/favicon.ico", include_in_schema=False)
    async def favicon() -> Response:
        return Response(status_code=204)

    def checker() -> ScriptChecker:
        found: ScriptChecker = state["checker"]
        return found

    @app.get("/api/health")
    async def health() -> dict[str, Any]:
        return {"ok": True, "jobs": len(board().jobs()), "checks": checker().counts()}

    @app.get("/api/info")
    async def info() -> dict[str, Any]:
        ready = next((c for c in choices if c.ready), None)
        preferred = next(
            (
                c
                for c in choices
                if c.ready and c.provider == config.provider and config.model in (None, c.model)
            ),
            ready,
        )
        return {
            "version": __version__,
            "models": [c.as_dict() for c in choices],
            "default": preferred.as_dict() if preferred else None,
            "examples": examples(),
            "agents": agent_choices(),
            "limits": {
                "description_chars": config.max_description_chars,
                "script_bytes": config.max_script_bytes,
                "queued_per_model": config.max_queued,
            },
        }

    @app.get("/api/jobs")
    async def jobs() -> dict[str, Any]:
        found = board()
        return {"jobs": [found.describe(job) for job in found.jobs()], "queue": found.queue()}

    @app.post("/api/jobs", status_code=201)
    async def submit(body: GenerateBody) -> dict[str, Any]:
        text = admit_description(body.description, config.max_description_chars)
        found = board()
        job = found.submit(text, found.choose(body.provider, body.model))
        return found.describe(job)

    @app.get("/api/jobs/{job_id}")
    async def job(job_id: str) -> dict[str, Any]:
        found = board()
        return found.describe(found.get(job_id))

    @app.post("/api/jobs/{job_id}/cancel")
    async def cancel(job_id: str) -> dict[str, Any]:
        found = board()
        return found.describe(found.cancel(job_id))

    @app.get("/api/jobs/{job_id}/events")
    async def events(job_id: str, request: Request) -> EventSourceResponse:
        followed = board().get(job_id)

        async def stream() -> AsyncIterator[dict[str, str]]:
            seen = 0
            while True:
                version = followed.signal.version
                finished = followed.finished_state
                for event in followed.events_after(seen):
                    seen += 1
                    yield {"event": event.event.value, "data": event_json(event)}
                if finished or await request.is_disconnected():
                    return
                await followed.signal.wait(version, STREAM_PING)

        return EventSourceResponse(stream(), ping=STREAM_PING)

    @app.get("/api/runs/{run_id}")
    async def run(run_id: str) -> dict[str, Any]:
        found = board()
        job = found.get(run_id)

        def read() -> dict[str, Any]:
            with found.store.open(run_id) as folder:
                return run_view(folder)

        view = await run_in_threadpool(read)
        return {"job": found.describe(job), **view}

    @app.get("/runs/{run_id}/files/{name}", include_in_schema=False)
    async def run_file(run_id: str, name: str) -> Response:
        return _file_response(name, board().store.file(run_id, name))

    @app.get("/runs/{run_id}/download.zip", include_in_schema=False)
    async def download(run_id: str) -> Response:
        data = await run_in_threadpool(board().store.zip_bytes, run_id)
        return Response(
            data,
            media_type="application/zip",
            headers={"Content-Disposition": f'attachment; filename="arise-{run_id}.zip"'},
        )

    @app.post("/api/check")
    async def check(body: CheckBody) -> dict[str, Any]:
        text = admit_script(body.script, config.max_script_bytes)
        agent = admit_agent(body.agent)
        checks: RunStore = state["checks"]
        check_id = new_id()
        folder = checks.folder(check_id, create=True)
        options = config.options
        result = await checker().check(text, folder, options.map_dir, options.check_timeout, agent)
        return {**result, "id": check_id, "name": body.name}

    @app.get("/checks/{check_id}/files/{name}", include_in_schema=False)
    async def check_file(check_id: str, name: str) -> Response:
        checks: RunStore = state["checks"]
        return _file_response(name, checks.file(check_id, name))

    return app


def guarded(config: ServeConfig, app: FastAPI) -> Guard:
    """The app behind the token, host and size checks: what uvicorn serves."""
    return Guard(
        app, token=config.token, loopback=config.loopback, max_body=config.max_request_bytes
    )
