"""The app with sources that misbehave: one that cannot start, one that fails to stop, one
that reports losses and a problem. Each says so on the screen; none takes the app down."""

from __future__ import annotations

import re

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record_batch import RecordColumns
from console_tui.sources.status import SourceStatus
from console_tui.ui.app import ConsoleApp

from support.feed import records
from support.ui import screen_text, until


class Source:
    """A source as the app sees one: ``start``, ``stop`` and a ``status`` snapshot."""

    def __init__(self, status: SourceStatus | None = None, *, start_error: str = "", stop_error: str = "") -> None:
        self.status = status or SourceStatus()
        self.start_error = start_error
        self.stop_error = stop_error
        self.calls: list[str] = []

    def start(self) -> None:
        self.calls.append("start")
        if self.start_error:
            raise OSError(self.start_error)

    def stop(self) -> None:
        self.calls.append("stop")
        if self.stop_error:
            raise RuntimeError(self.stop_error)


class CannotStart(Source):
    pass


def status_line(app: ConsoleApp) -> str:
    """The status line: it starts with the state (at 80 columns, "3/3 shown" may read "3/3")."""
    return next(
        line for line in screen_text(app).splitlines() if line.lstrip().startswith(("FOLLOW", "SCROLL", "PAUSED"))
    )


async def test_a_source_that_cannot_start_is_named_on_screen_and_the_rest_runs():
    queue = IntakeQueue()
    broken = CannotStart(start_error="no route to the robot")
    good = Source(SourceStatus(topic="/rosout", publishers=2, path="raw+cdr", running=True))
    app = ConsoleApp(store=LogStore(), queue=queue, sources=[broken, good], utc=True)
    async with app.run_test(size=(140, 30), notifications=True) as pilot:
        await until(pilot, lambda: "Could not start CannotStart" in screen_text(app), what="the notification")
        assert "no route to the robot" in screen_text(app)
        assert good.calls == ["start"], "the next source started all the same"
        queue.put(RecordColumns.from_records(records(3)))
        await until(pilot, lambda: "3/3 shown" in status_line(app), what="records from the queue")
        assert "/rosout 2 pubs  raw+cdr" in status_line(app)
        await pilot.press("space")
        assert "PAUSED" in status_line(app), "keys still work"
    assert broken.calls == ["start", "stop"] and good.calls == ["start", "stop"]


async def test_a_source_that_fails_to_stop_does_not_keep_the_others_running_or_the_app_alive():
    first = Source(stop_error="stuck")
    second = Source()
    app = ConsoleApp(store=LogStore(), queue=IntakeQueue(), sources=[first, second])
    async with app.run_test(size=(100, 24)) as pilot:
        await until(pilot, lambda: second.calls == ["start"])
        await pilot.press("q")
    assert first.calls == ["start", "stop"] and second.calls == ["start", "stop"]
    assert app.return_code in (None, 0)


async def test_losses_and_a_problem_of_a_source_show_in_the_status_line():
    status = SourceStatus(
        topic="/rosout_agg",
        publishers=1,
        path="typed",
        lost=12,
        lost_qos=7,
        lost_queue=5,
        problem="1 publisher(s) on /rosout_agg offer a QoS no subscription can match",
        running=True,
    )
    source = Source(status)
    app = ConsoleApp(store=LogStore(), queue=IntakeQueue(), sources=[source])
    async with app.run_test(size=(220, 24)) as pilot:
        await until(pilot, lambda: "/rosout_agg" in status_line(app))
        line = status_line(app)
        assert "/rosout_agg 1 pub " in line
        assert "12 lost (7 in the middleware, 5 UI behind)" in line
        assert "offer a QoS no subscription can match" in line and line.rstrip().endswith("typed")
        source.status = SourceStatus(topic="/rosout_agg", publishers=3, path="typed", running=True)
        await until(pilot, lambda: "/rosout_agg 3 pubs  typed" in status_line(app), what="the new status")
        assert "lost" not in status_line(app)


async def test_q_starts_stopping_the_sources_at_once_and_the_app_waits_for_them():
    """The sources' processes end while Textual takes the screen down, not after it; and
    the app is not done before they have stopped."""
    import threading

    class SlowToStop(Source):
        def __init__(self) -> None:
            super().__init__()
            self.began = threading.Event()
            self.release = threading.Event()
            self.stopped = threading.Event()

        def stop(self) -> None:
            super().stop()
            self.began.set()
            self.release.wait(5)
            self.stopped.set()

    source = SlowToStop()
    app = ConsoleApp(store=LogStore(), queue=IntakeQueue(), sources=[source])
    async with app.run_test(size=(100, 24)) as pilot:
        await until(pilot, lambda: source.calls == ["start"])
        await pilot.press("q")
        assert source.began.wait(5), "q began stopping the source"
        source.release.set()
    assert source.stopped.is_set(), "the app waited for the source to stop"
    assert source.calls == ["start", "stop"]


@pytest.mark.parametrize(
    ("origin", "path", "taken_by", "loop"),
    [
        ("ROS 2 domain 7", "raw+cdr", "raw+cdr: rclpy's take, the CDR decoded directly", "the take loop in C"),
        ("ROS 1 http://robot:11311/", "tcpros", "tcpros: ROS 1's TCPROS, read directly", "the frame loop in C"),
    ],
)
async def test_the_summary_says_what_each_source_reads_how_and_what_it_lost(origin, path, taken_by, loop):
    status = SourceStatus(
        topic="/rosout",
        publishers=3,
        origin=origin,
        path=path,
        path_note="no C compiler (cc)",
        lost=12,
        lost_qos=12,
        running=True,
    )
    helper = Source(SourceStatus(path="demo: 4 nodes"))  # reads no topic: not a source of messages
    queue = IntakeQueue()
    store = LogStore()
    app = ConsoleApp(store=store, queue=queue, sources=[Source(status), helper], utc=True)
    async with app.run_test(size=(80, 24)) as pilot:
        queue.put(RecordColumns.from_records(records(3)))
        # (at 80 columns a ROS 1 master's address leaves no room for the count on the status line)
        await until(pilot, lambda: len(store) == 3, what="records from the queue")
        await pilot.press("S")
        await until(pilot, lambda: "Summary: 3 messages kept" in screen_text(app), what="the summary")
        lines = [line.strip(" █▊▎") for line in screen_text(app).splitlines()]
    start = lines.index("Source: /rosout, 3 publishers")
    assert lines[start + 1 : start + 5] == [
        origin,
        f"taken by {taken_by}",
        f"{loop} is not used: no C compiler (cc)",
        "lost: 12 lost (12 in the middleware)",
    ]
    assert sum(line.startswith("Source:") for line in lines) == 1, "the demo's nodes are no source of messages"


def ros1_demo_sources() -> list[Source]:
    """What ``console-tui --demo --ros1`` runs: its roscore and nodes, and the live source."""
    demo = SourceStatus(path="demo: roscore on port 41231, 4 rospy nodes", running=True)
    live = SourceStatus(
        topic="/rosout_agg", publishers=5, origin="ROS 1 http://127.0.0.1:41231/", path="tcpros", running=True
    )
    return [Source(demo), Source(live)]


async def test_the_status_line_keeps_source_and_state_at_100_and_80_columns():
    """Narrow terminals: the parts that matter least are shortened, then left out; the
    state, the topic, its publishers and the master stay (they showed only at 170 columns)."""
    store = LogStore()
    store.extend_records(records(40))
    for size, expected, gone in [
        ((100, 30), ["FOLLOW", "40/40", "/rosout_agg 5 pubs", "127.0.0.1:41231", "demo"], ["roscore on port"]),
        ((80, 24), ["FOLLOW", "40/40", "/rosout_agg 5", "127.0.0.1:41231"], ["roscore on port"]),
        ((220, 30), ["40/40 shown", "demo: roscore on port 41231, 4 rospy nodes", "ROS 1 http://127.0.0.1:41231/"], []),
    ]:
        app = ConsoleApp(store=store, queue=IntakeQueue(), sources=ros1_demo_sources())
        async with app.run_test(size=size) as pilot:
            await until(pilot, lambda app=app: "/rosout_agg" in screen_text(app), what="the status line")
            line = next(line for line in screen_text(app).splitlines() if "FOLLOW" in line)
            assert all(part in line for part in expected), (size, line)
            assert not any(part in line for part in gone), (size, line)
            assert "…" not in line, (size, line)  # shortened by parts, never cut in the middle
            footer = screen_text(app).splitlines()[-1]
            assert not re.search(r"(^|\s)\S ?▏", footer), footer  # a key never shows without what it does
