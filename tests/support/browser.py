"""``console-tui serve`` in a real process, and a real headless Chromium to look at it.

Chromium and its driver are Debian's (``chromium``, ``chromium-driver``; scripts/test
installs them), driven with selenium. Every request goes to 127.0.0.1.

The page draws the terminal on a canvas; the tests read what it shows from xterm.js's own
rows in the DOM (its screen-reader rows, switched on for the test): a hook put in the page
before its script runs keeps the page's terminal object so the test can switch them on.
"""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import Any

from support.ros1 import own_port

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
#: The flags that work here: nothing leaves the machine, nothing is kept between runs.
CHROMIUM_FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--window-size=1200,760",
)

#: Keeps the page's xterm.js terminals (``window.__terminals``): textual.js sets
#: ``this.terminal = new Terminal(...)``, and a setter on Object.prototype sees it.
TERMINAL_HOOK = """
window.__terminals = [];
Object.defineProperty(Object.prototype, "terminal", {
  configurable: true,
  get() { return undefined; },
  set(value) {
    Object.defineProperty(this, "terminal", {value, writable: true, configurable: true, enumerable: true});
    if (value && value.buffer && value.options) { window.__terminals.push(value); }
  },
});
"""


def browser_missing() -> str | None:
    """Why the browser tests cannot run here, or None."""
    for path in (CHROMIUM, CHROMEDRIVER):
        if not os.access(path, os.X_OK):
            return f"{path} is missing (apt-get install chromium chromium-driver; scripts/test does it)"
    for module, extra in (("selenium", "test"), ("textual_serve", "web")):
        if importlib.util.find_spec(module) is None:
            return f"{module} is not installed (pip install -e '.[{extra}]')"
    return None


def wait_for(condition: Callable[[], Any], what: str, timeout: float = 60.0) -> Any:
    """Poll ``condition`` until it returns something true; fail saying ``what`` after ``timeout``."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.1)


def children(pid: int) -> set[int]:
    """The live processes whose parent is ``pid`` (from /proc)."""
    found = set()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        fields = stat[stat.rfind(")") + 2 :].split()
        if int(fields[1]) == pid and fields[0] != "Z":
            found.add(int(entry.name))
    return found


def descendants(pid: int) -> set[int]:
    found: set[int] = set()
    todo = [pid]
    while todo:
        for child in children(todo.pop()):
            if child not in found:
                found.add(child)
                todo.append(child)
    return found


def alive(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat[stat.rfind(")") + 2 :].split()[0] != "Z"


class ServeProcess:
    """``console-tui serve --port P ARGS`` in a process of its own; ``url`` is what it printed."""

    def __init__(self, *args: str, env: dict[str, str], host: str | None = None) -> None:
        self.port = own_port()
        command = [sys.executable, "-m", "console_tui", "serve", "--port", str(self.port)]
        if host is not None:
            command += ["--host", host]
        self.process = subprocess.Popen(
            [*command, *args],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            env=env,
            text=True,
            errors="replace",
        )
        self.output: deque[str] = deque(maxlen=400)
        threading.Thread(target=self._read, daemon=True).start()
        banner = wait_for(lambda: self.printed(r"http://\S+"), "the server's URL", timeout=90)
        printed = re.search(r"\?token=(\S+)", banner)
        self.token = printed.group(1) if printed else None
        self.url = f"http://127.0.0.1:{self.port}/" + (f"?token={self.token}" if self.token else "")
        # It prints before it listens: the page is there once a request is answered.
        wait_for(self._answers, "the server to listen", timeout=30)

    def _read(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self.output.append(line.rstrip("\n"))

    def printed(self, pattern: str) -> str | None:
        for line in list(self.output):
            if re.search(pattern, line):
                return line
        return None

    def _answers(self) -> bool:
        try:
            with socket.create_connection(("127.0.0.1", self.port), timeout=2):
                return True
        except OSError:
            return False

    def text(self) -> str:
        return "\n".join(self.output)

    def interrupt(self, stop: int = signal.SIGINT, timeout: float = 60.0) -> int:
        """Ctrl-C (or ``stop``); returns the exit status."""
        self.process.send_signal(stop)
        return self.process.wait(timeout)

    def stop(self) -> None:
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(30)
            except subprocess.TimeoutExpired:
                for pid in descendants(self.process.pid):
                    try:
                        os.kill(pid, signal.SIGKILL)
                    except ProcessLookupError:
                        pass
                self.process.kill()
                self.process.wait()


class Browser:
    """A headless Chromium of its own (a fresh profile), driven by selenium."""

    def __init__(self) -> None:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service

        self.profile = tempfile.mkdtemp(prefix="console-tui-chromium-")
        options = webdriver.ChromeOptions()
        options.binary_location = CHROMIUM
        for flag in (*CHROMIUM_FLAGS, f"--user-data-dir={self.profile}"):
            options.add_argument(flag)
        self.driver = webdriver.Chrome(options=options, service=Service(CHROMEDRIVER))

    def open(self, url: str, *, new_tab: bool = False) -> str:
        """Open ``url`` (in a new tab when asked); returns the tab's handle."""
        if new_tab:
            self.driver.switch_to.new_window("tab")
        # Each tab needs the hook of its own.
        self.driver.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument", {"source": TERMINAL_HOOK})
        self.driver.get(url)
        return str(self.driver.current_window_handle)

    def screen(self) -> str:
        """The rows xterm.js shows, one per line (its screen-reader rows in the DOM)."""
        rows = self.driver.execute_script(
            """
            const terminal = (window.__terminals || [])[0];
            if (!terminal) { return null; }
            if (!terminal.options.screenReaderMode) { terminal.options.screenReaderMode = true; }
            const tree = document.querySelector(".xterm-accessibility-tree");
            return tree ? Array.from(tree.children, (row) => row.textContent) : null;
            """
        )
        return "\n".join(rows or [])

    def wait_for_text(self, *texts: str, timeout: float = 60.0) -> str:
        """Wait until the screen shows every one of ``texts``; returns the screen."""
        return str(
            wait_for(
                lambda: (screen := self.screen()) and all(t in screen for t in texts) and screen,
                f"{texts!r} on the screen",
                timeout,
            )
        )

    def wait_for_no_text(self, *texts: str, timeout: float = 60.0) -> str:
        return str(
            wait_for(
                lambda: (screen := self.screen()) and not any(t in screen for t in texts) and screen,
                f"{texts!r} gone from the screen",
                timeout,
            )
        )

    def type(self, keys: str) -> None:
        """Keys into the terminal (as a person types them)."""
        from selenium.webdriver.common.by import By

        self.driver.find_element(By.CSS_SELECTOR, ".xterm-helper-textarea").send_keys(keys)

    def quit(self) -> None:
        try:
            self.driver.quit()
        finally:
            shutil.rmtree(self.profile, ignore_errors=True)
