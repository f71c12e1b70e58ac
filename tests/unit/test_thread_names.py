"""Our threads carry their names into the operating system (``top -H``, ``/proc``)."""

from __future__ import annotations

import sys
import threading
from pathlib import Path

import pytest

from console_tui.system.thread_names import NAME_BYTES, os_name, os_named


def test_the_os_name_drops_the_prefix_and_fits_the_kernel() -> None:
    assert os_name("console-tui-intake-pipe") == b"ct-intake-pipe"
    assert os_name("console-tui-loggers") == b"ct-loggers"
    assert os_name("worker") == b"ct-worker"
    assert len(os_name("console-tui-a-very-long-thread-name")) == NAME_BYTES


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="thread names in /proc are Linux's")
def test_a_thread_started_with_os_named_shows_its_name_in_proc() -> None:
    seen: list[str] = []

    def read_own_name() -> None:
        seen.append(Path(f"/proc/self/task/{threading.get_native_id()}/comm").read_text().strip())

    thread = threading.Thread(target=os_named(read_own_name), name="console-tui-intake-pipe")
    thread.start()
    thread.join()
    assert seen == ["ct-intake-pipe"]
    main_name = Path(f"/proc/self/task/{threading.get_native_id()}/comm").read_text().strip()
    assert main_name != "ct-intake-pipe"  # only the thread itself is renamed


def test_os_named_passes_arguments_and_the_result_through() -> None:
    assert os_named(lambda a, b=0: a + b)(2, b=3) == 5
