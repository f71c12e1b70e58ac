"""``console-tui serve`` in a real headless Chromium: the page, the keys, the tab's process,
the access token. The screen is read from xterm.js's rows in the page's DOM."""

from __future__ import annotations

import http.client
import os
import signal
from pathlib import Path

import pytest
from conftest import next_domain_id

from console_tui.model.store.record import LogRecord

from support.browser import Browser, ServeProcess, alive, browser_missing, children, descendants, wait_for
from support.warehouse import STORE_MISSING, chdb_address, ship_records

pytestmark = pytest.mark.skipif(browser_missing() is not None, reason=f"no browser test: {browser_missing()}")

DATA = Path(__file__).parent.parent / "data"
KNOWN_FILE = DATA / "rqt_console_ros2.csv"
#: Where the browser's screenshot is saved when this is set (screenshots/ for the README).
SCREENSHOT_FOLDER = os.environ.get("CONSOLE_TUI_BROWSER_SCREENSHOTS")


@pytest.fixture(scope="module")
def server_env(tmp_path_factory) -> dict[str, str]:
    return {**os.environ, "XDG_CONFIG_HOME": str(tmp_path_factory.mktemp("config"))}


@pytest.fixture(scope="module")
def server(server_env):
    """One server for the known file, on 127.0.0.1 (no token)."""
    process = ServeProcess(str(KNOWN_FILE), env=server_env)
    yield process
    process.stop()


@pytest.fixture(scope="module")
def browser():
    chromium = Browser()
    yield chromium
    chromium.quit()


@pytest.fixture
def tab(server, browser):
    """A fresh tab on the known file, its rows shown; closed at the end."""
    handle = browser.open(server.url, new_tab=True)
    browser.wait_for_text("timer fired", "11/11 shown")
    yield handle
    if handle in browser.driver.window_handles and len(browser.driver.window_handles) > 1:
        browser.driver.switch_to.window(handle)
        browser.driver.close()
        browser.driver.switch_to.window(browser.driver.window_handles[0])


def test_the_page_shows_the_rows_of_a_known_file(server, browser, tab):
    screen = browser.screen()
    for text in ("# Time", "hello", 'say "hi"; bye', "path C:\\dir\\", "timer fired", "cpp_node", "11/11 shown"):
        assert text in screen
    assert "rqt_console_ros2.csv" in screen
    if SCREENSHOT_FOLDER:
        browser.driver.save_screenshot(str(Path(SCREENSHOT_FOLDER) / "browser.png"))


def test_the_page_loads_nothing_from_another_host(server, browser, tab):
    """Everything the page asked for came from the server it was opened from (a robot is
    often offline): the Resource Timing entries name no other host."""
    hosts = browser.driver.execute_script(
        "return performance.getEntriesByType('resource').map((entry) => new URL(entry.name).host)"
    )
    assert hosts, "the page loaded no resource at all"
    assert set(hosts) == {f"127.0.0.1:{server.port}"}
    # The font it draws with is the one the server ships, and it loaded.
    assert browser.driver.execute_script(
        "return [...document.fonts].some((face) => face.family.includes('Roboto Mono') && face.status === 'loaded')"
    )


def test_a_query_hides_the_right_rows(browser, tab):
    browser.type("/")
    browser.type("level>=error\n")
    screen = browser.wait_for_text("2/11 shown")
    assert "first line↵second" in screen  # the ERROR
    assert "path C:\\dir\\" in screen  # the FATAL
    for hidden in ("hello", 'say "hi"; bye', "timer fired", "ends with a newline"):
        assert hidden not in screen


def test_question_mark_shows_the_help(browser, tab):
    browser.type("?")
    screen = browser.wait_for_text("console-tui shows every node's log messages in one table", "Follow tail")
    assert "table.follow" in screen


def test_y_copies_to_the_browser_clipboard(browser, tab):
    """``y`` in a message's details reaches the page's clipboard (xterm.js's OSC 52 handler
    calls navigator.clipboard.writeText; here it is recorded, a headless page has no
    clipboard of its own to read back)."""
    browser.driver.execute_script(
        "window.__copied = null; navigator.clipboard.writeText = async (text) => { window.__copied = text; };"
    )
    browser.type("\n")  # the selected row: the newest, followed
    browser.wait_for_text("ends with a newline")
    browser.type("y")
    copied = wait_for(lambda: browser.driver.execute_script("return window.__copied"), "the copied text")
    assert copied.startswith("ends with a newline")


def test_closing_the_tab_ends_its_console(server, browser, tab):
    before = children(server.process.pid)
    browser.open(server.url, new_tab=True)
    browser.wait_for_text("timer fired")
    consoles = children(server.process.pid) - before
    assert len(consoles) == 1, "one new console process for the new tab"
    browser.driver.close()
    browser.driver.switch_to.window(tab)
    (console,) = consoles
    wait_for(lambda: not alive(console), "the closed tab's console to end")
    assert before <= children(server.process.pid), "the other tab's console still runs"


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGHUP], ids=["ctrl-c", "sighup"])
def test_ctrl_c_ends_every_console_and_the_tab_says_its_connection_is_lost(server_env, browser, stop):
    """Ctrl-C, or SIGHUP (the SSH session the server runs in drops)."""
    server = ServeProcess(str(KNOWN_FILE), env=server_env)
    try:
        browser.open(server.url, new_tab=True)
        browser.wait_for_text("timer fired")
        consoles = descendants(server.process.pid)
        assert consoles
        assert server.interrupt(stop) == 0
        assert "stopped, 1 console(s) ended" in server.text()
        assert not [pid for pid in consoles if alive(pid)]
        lost = wait_for(
            lambda: (
                (
                    text := browser.driver.execute_script(
                        "const lost = document.getElementById('connection-lost');"
                        "return lost && lost.offsetParent !== null ? lost.textContent : null;"
                    )
                )
                and text
            ),
            "the page to say its connection is lost",
        )
        assert "Connection lost" in lost
    finally:
        server.stop()
        if len(browser.driver.window_handles) > 1:
            browser.driver.close()
            browser.driver.switch_to.window(browser.driver.window_handles[0])


def _status(port: int, path: str, headers: dict[str, str] | None = None) -> int:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    try:
        connection.request("GET", path, headers=headers or {})
        return connection.getresponse().status
    finally:
        connection.close()


def _websocket_headers(port: int) -> dict[str, str]:
    return {
        "Connection": "Upgrade",
        "Upgrade": "websocket",
        "Sec-WebSocket-Version": "13",
        "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ==",
        "Origin": f"http://127.0.0.1:{port}",
    }


def test_beyond_loopback_a_request_without_the_token_is_refused(server_env, browser):
    """Bound to 0.0.0.0, the server wants its token: refused without it, for the page, its
    files and the websocket alike (every request goes to 127.0.0.1)."""
    server = ServeProcess(str(KNOWN_FILE), env=server_env, host="0.0.0.0")
    try:
        assert server.token, "a token was generated and printed in the URL"
        assert "Requests without this token are refused" in server.text()
        port = server.port
        assert _status(port, "/") == 403
        assert _status(port, "/?token=wrong") == 403
        assert _status(port, "/static/js/textual.js") == 403
        assert _status(port, "/ws?width=80&height=24", _websocket_headers(port)) == 403
        assert not children(server.process.pid), "no console was started for a refused websocket"
        # A refused request is logged, its path made inert (aiohttp decodes %1B to ESC).
        assert _status(port, "/%1B%5B2J%1B%5D0%3Bowned%07") == 403
        wait_for(lambda: server.printed("owned"), "the refusal in the server's log")
        assert "\x1b" not in server.text() and "\x07" not in server.text()
        assert _status(port, f"/?token={server.token}") == 200
        assert (
            _status(port, "/ws", {**_websocket_headers(port), "Cookie": f"console_tui_token_{port}={server.token}"})
            == 101
        )
        # With it, the browser gets the whole console.
        browser.open(server.url, new_tab=True)
        browser.wait_for_text("timer fired", "11/11 shown")
    finally:
        if len(browser.driver.window_handles) > 1:
            browser.driver.close()
            browser.driver.switch_to.window(browser.driver.window_handles[0])
        server.stop()


def test_on_loopback_another_host_name_or_a_foreign_websocket_is_refused(server):
    """A page that points its own name at 127.0.0.1 (DNS rebinding), or another site's
    script opening the websocket, gets nothing."""
    port = server.port
    assert _status(port, "/", {"Host": f"localhost:{port}"}) == 200
    assert _status(port, "/", {"Host": f"attacker.example:{port}"}) == 403
    foreign = {**_websocket_headers(port), "Origin": "http://attacker.example"}
    assert _status(port, "/ws", foreign) == 403
    assert _status(port, "/ws", {k: v for k, v in _websocket_headers(port).items() if k != "Origin"}) == 403


def test_a_console_that_quits_closes_its_tab(server, browser):
    """``q`` in the page ends the console and the page says so."""
    before = children(server.process.pid)
    browser.open(server.url, new_tab=True)
    browser.wait_for_text("timer fired")
    (console,) = children(server.process.pid) - before
    browser.type("q")
    wait_for(lambda: not alive(console), "the console to quit")
    assert browser.driver.execute_script("return document.body.classList.contains('-closed')")
    browser.driver.close()
    browser.driver.switch_to.window(browser.driver.window_handles[0])


@pytest.mark.ros2
def test_closing_the_tab_of_a_demo_ends_its_console_and_its_demo_nodes(ros_env, tmp_path, browser):
    """``serve --demo``: each tab starts its own demo nodes (real ROS 2 processes, in a domain
    of the tests' own: left to itself the demo takes any free one, which a test starting later
    may be given), and they end with the tab, with the console's intake process."""
    demo_domain = str(next_domain_id())
    env = {**ros_env, "XDG_CONFIG_HOME": str(tmp_path / "config")}
    server = ServeProcess("--demo", "--demo-domain", demo_domain, env=env)
    try:
        browser.open(server.url, new_tab=True)
        browser.wait_for_text("count_and_log", "navigation.planner", timeout=90)
        (console,) = children(server.process.pid)
        started = descendants(console) | {console}
        assert len(started) >= 5, "the console, its intake process and the demo nodes"
        browser.driver.close()
        browser.driver.switch_to.window(browser.driver.window_handles[0])
        wait_for(lambda: not [pid for pid in started if alive(pid)], "the console and its demo nodes to end")
        assert server.process.poll() is None, "the server goes on"
    finally:
        server.stop()


def test_a_tab_beyond_max_consoles_is_refused_and_says_so(server_env, browser):
    server = ServeProcess("--max-consoles", "1", str(KNOWN_FILE), env=server_env)
    try:
        browser.open(server.url, new_tab=True)
        browser.wait_for_text("timer fired")
        assert len(children(server.process.pid)) == 1
        browser.open(server.url, new_tab=True)
        wait_for(
            lambda: browser.driver.execute_script("return document.body.classList.contains('-closed')"),
            "the second tab to say its connection is lost",
        )
        assert len(children(server.process.pid)) == 1, "no second console"
        assert "a new tab refused: 1 consoles run already" in server.text()
    finally:
        while len(browser.driver.window_handles) > 1:
            browser.driver.close()
            browser.driver.switch_to.window(browser.driver.window_handles[0])
        server.stop()


@pytest.mark.skipif(bool(STORE_MISSING), reason=STORE_MISSING or "-")
def test_a_log_warehouse_in_the_page(server_env, browser, tmp_path):
    """``console-tui serve -- chdb://DIR``: a tab's console reads the warehouse (chDB: one
    process at a time, so one tab)."""
    address = chdb_address(tmp_path / "warehouse")
    records = [
        LogRecord(1_765_000_000_000_000_000 + i * 1_000_000, 30 if i == 7 else 20, "nav", f"stored row {i}", robot="r2")
        for i in range(10)
    ]
    ship_records(address, records)
    server = ServeProcess("--", address.text, "--utc", env=server_env)
    try:
        browser.open(server.url, new_tab=True)
        screen = browser.wait_for_text("stored row 9", "10/10 shown")
        assert "stored row 0" in screen and "chdb://" in screen
    finally:
        while len(browser.driver.window_handles) > 1:
            browser.driver.close()
            browser.driver.switch_to.window(browser.driver.window_handles[0])
        server.stop()
