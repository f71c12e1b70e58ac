"""The web server of ``console-tui serve``: textual-serve's ``Server``, with three changes.

- Every request passes the access rules of ``serve_access`` first (a middleware).
- The page is console-tui's own (``serve_page/app_index.html``): it loads nothing from the
  internet (textual-serve 1.1.3's page links its web font from a public font host; the same
  font ships in textual-serve's own static folder and is served from there), builds its websocket address from the address the browser used (so
  ``ssh -L`` and a server on 0.0.0.0 work), and says so when its connection is lost.
- Each tab's console ends with its tab, bounded in time (killed if it does not quit), and
  ends the tab when it quits or dies; on Ctrl-C every console is ended before the server
  stops.

textual-serve has no public handle on a tab's process nor on its message loop: the three
names used here (``Server._make_app``, ``Server._process_messages``, ``AppService._process``)
are checked by ``check_upstream`` when the server is made, so another textual-serve release
fails at once with a clear message instead of serving something unchecked (the ``[web]``
extra pins the tested range). What each is for, and the upstream issue that would let this
module drop them: docs/textual-fixes.md, "textual-serve: private names".
"""

from __future__ import annotations

import asyncio
import logging
import signal
import sys
from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import Any

from aiohttp import web
from textual_serve.app_service import AppService
from textual_serve.server import Server

from ..model.inert_text import one_line
from .serve_access import TOKEN_PARAMETER, Access

#: Where the page's template is (textual-serve renders ``app_index.html`` from it).
PAGE_FOLDER = Path(__file__).with_name("serve_page")
#: How long a console has to quit once its tab is gone, before it is killed.
QUIT_TIMEOUT_S = 10.0
#: The first size of a tab's console is bounded (the browser says it in the URL).
MAX_COLUMNS, MAX_ROWS = 1000, 500

log = logging.getLogger("console-tui serve")


def check_upstream() -> None:
    """The textual-serve internals this module relies on are there (see the module)."""
    missing = [
        name
        for name, present in (
            ("Server._make_app", callable(getattr(Server, "_make_app", None))),
            ("Server._process_messages", callable(getattr(Server, "_process_messages", None))),
            ("AppService._process", "_process" in vars(AppService("true", **_NO_IO))),
        )
        if not present
    ]
    if missing:
        raise RuntimeError(
            f"this textual-serve release lacks {', '.join(missing)}: install the tested one with "
            "pip install 'console-tui[web]'"
        )


async def _nothing(*_: object) -> None:
    return None


_NO_IO: dict[str, Any] = {"write_bytes": _nothing, "write_str": _nothing, "close": _nothing, "download_manager": None}


def _size(text: str | None, default: int, largest: int) -> int:
    try:
        value = int(text or default)
    except ValueError:
        return default
    return min(max(value, 1), largest)


class ConsoleServer(Server):
    """Serves ``command`` (a shell command line: one console-tui per tab) under ``access``;
    ``banner`` is printed once the server listens."""

    def __init__(self, command: str, *, host: str, port: int, access: Access, banner: str, max_consoles: int) -> None:
        check_upstream()
        super().__init__(command, host=host, port=port, title="console-tui", templates_path=PAGE_FOLDER)
        self.access = access
        self.banner = banner
        #: Consoles running at once, at most (each is a process, with its demo nodes).
        self.max_consoles = max_consoles
        #: The tasks serving open tabs (cancelled when the server stops).
        self.sessions: set[asyncio.Task[Any]] = set()

    def serve(self, debug: bool = False) -> None:
        """Until Ctrl-C, SIGTERM or SIGHUP (the SSH session it runs in drops)."""
        loop = asyncio.new_event_loop()
        asyncio.set_event_loop(loop)  # textual-serve's serve() takes this loop
        loop.add_signal_handler(signal.SIGHUP, self.request_exit)
        super().serve(debug)

    def initialize_logging(self) -> None:
        # Warnings and errors only, plainly: no access log, no logo.
        logging.basicConfig(level=logging.WARNING, format="console-tui serve: %(message)s", stream=sys.stderr)

    async def _make_app(self) -> web.Application:
        app = await super()._make_app()
        app.middlewares.append(self._guard)
        return app

    @web.middleware
    async def _guard(
        self, request: web.Request, handler: Callable[[web.Request], Awaitable[web.StreamResponse]]
    ) -> web.StreamResponse:
        access = self.access
        query_token = request.query.get(TOKEN_PARAMETER)
        refusal = access.refusal(
            host=request.headers.get("Host", ""),
            origin=request.headers.get("Origin"),
            websocket=request.path == "/ws" or request.headers.get("Upgrade", "").lower() == "websocket",
            query_token=query_token,
            cookie_token=request.cookies.get(access.cookie_name),
        )
        if refusal is not None:
            # The path is the requester's text: inert and short on the server's terminal.
            what = one_line(f"{request.method} {request.path}", 200)
            log.warning("%s from %s: %s", what, request.remote, refusal.split(";")[0])
            return web.Response(status=403, text=refusal + "\n")
        response = await handler(request)
        if access.token_ok(query_token) and not response.prepared:
            # The page's own requests (its script, font, websocket) carry the token from here on.
            response.set_cookie(access.cookie_name, query_token or "", httponly=True, samesite="Strict", path="/")
        if not response.prepared:
            response.headers.setdefault("Cache-Control", "no-store")
        return response

    async def on_startup(self, app: web.Application) -> None:
        print(self.banner, flush=True)

    async def on_shutdown(self, app: web.Application) -> None:
        """Ctrl-C or SIGTERM: every tab's console is ended (each bounded by QUIT_TIMEOUT_S)."""
        sessions = list(self.sessions)
        for task in sessions:
            task.cancel()
        if sessions:
            await asyncio.wait(sessions, timeout=QUIT_TIMEOUT_S + 5)
            print(f"console-tui serve: stopped, {len(sessions)} console(s) ended", flush=True)
        else:
            print("console-tui serve: stopped", flush=True)

    async def handle_websocket(self, request: web.Request) -> web.WebSocketResponse:
        """One tab: its own console process, ended with the tab (and the tab with it)."""
        if len(self.sessions) >= self.max_consoles:
            log.warning("a new tab refused: %d consoles run already (--max-consoles)", len(self.sessions))
            raise web.HTTPServiceUnavailable(text=f"refused: {len(self.sessions)} consoles run already\n")
        websocket = web.WebSocketResponse(heartbeat=15)
        width = _size(request.query.get("width"), 80, MAX_COLUMNS)
        height = _size(request.query.get("height"), 24, MAX_ROWS)
        await websocket.prepare(request)
        service = AppService(
            self.command,
            write_bytes=websocket.send_bytes,
            write_str=websocket.send_str,
            close=lambda: _close(websocket),
            download_manager=self.download_manager,
            debug=self.debug,
        )
        task = asyncio.current_task()
        if task is not None:
            self.sessions.add(task)
        try:
            await service.start(width, height)
            process: asyncio.subprocess.Process = service._process  # type: ignore[assignment]  # checked: check_upstream
            messages = asyncio.ensure_future(self._process_messages(websocket, service))
            ended = asyncio.ensure_future(process.wait())
            try:
                # The tab closes (messages end) or the console quits or dies (ended).
                await asyncio.wait({messages, ended}, return_when=asyncio.FIRST_COMPLETED)
            finally:
                messages.cancel()
                ended.cancel()
        except asyncio.CancelledError:
            pass  # the server stops
        except Exception as error:
            log.error("a console failed: %s", error)
        finally:
            if task is not None:
                self.sessions.discard(task)
            await end_console(service)
            await websocket.close()
        return websocket


async def _close(websocket: web.WebSocketResponse) -> None:
    await websocket.close()


async def end_console(service: AppService) -> None:
    """Ask the tab's console to quit; kill it if it has not within QUIT_TIMEOUT_S."""
    process = getattr(service, "_process", None)
    try:
        await asyncio.wait_for(service.stop(), QUIT_TIMEOUT_S)
        if process is not None:
            await asyncio.wait_for(process.wait(), QUIT_TIMEOUT_S)
    except (asyncio.TimeoutError, OSError, RuntimeError):
        pass
    if process is not None and process.returncode is None:
        log.warning("a console did not quit within %.0f s: killed", QUIT_TIMEOUT_S)
        try:
            process.kill()
        except ProcessLookupError:
            return
        await process.wait()
