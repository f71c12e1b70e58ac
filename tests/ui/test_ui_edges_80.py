"""At 80 columns, the edges of the screen: the node panel keeps a ROS 1 name's end, as the
table does; the summary cuts a message where its box ends, not before; a notification leaves
the status line's counters readable; the help's and the summary's scrollbars sit at their
box's edge, never a stray glyph inside it."""

from __future__ import annotations

import re

from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.ui.app import ConsoleApp

from support.feed import BASE_NS
from support.ui import frame_drawn, make_app, screen_text, until, until_shown

ROS1_NODES = ["/navigation/planner", "/sensors/lidar_driver", "/count_and_log"]


def ros1_app(count: int = 60) -> ConsoleApp:
    store = LogStore()
    store.extend_records(
        LogRecord(
            BASE_NS + i * 100_000_000,
            40 if i % 10 == 9 else 20,
            ROS1_NODES[i % len(ROS1_NODES)],
            f"{i} is divisible by {i % 7 + 1}, and this message goes on past the box",
        )
        for i in range(count)
    )
    return ConsoleApp(store=store, utc=True)


async def test_the_node_panel_keeps_the_end_of_a_ros1_name():
    app = ros1_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.press("ctrl+n")
        await until(pilot, lambda: "Nodes: 3" in screen_text(app), what="the node panel")
        pane = [line[line.index("▏") :] for line in screen_text(app).splitlines() if "▏" in line]
        text = "\n".join(pane)
        assert "on/planner " in text and "dar_driver " in text, text  # their ends, which tell them apart
        assert "/navigation/pl…" not in text, text


async def test_the_summary_cuts_a_message_where_its_box_ends():
    app = ros1_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.press("S")
        await until(pilot, lambda: "Summary:" in screen_text(app), what="the summary")
        line = next(line for line in screen_text(app).splitlines() if " ERROR " in line)
        assert "9 is divisible" in line, line
        assert re.search(r"divisible[^ ]*…█", line), line  # cut at the box's border, no room left over


async def test_a_notification_leaves_the_status_line_readable():
    app = make_app(30)
    async with app.run_test(size=(80, 24), notifications=True) as pilot:
        await until(pilot, lambda: "30/30" in screen_text(app), what="the status line")
        before = screen_text(app).splitlines()[-2:]
        app.notify("something happened that the person should read now", timeout=30)
        await until(pilot, lambda: "something happened" in screen_text(app), what="the toast")
        assert screen_text(app).splitlines()[-2:] == before  # the status line and the keys, whole


def floating_glyphs(app) -> list[str]:
    """Box lines with a scrollbar glyph that stands apart from the box's right border."""
    return [line for line in screen_text(app).splitlines() if re.search(r" [▁▂▃▄▅▆▇]+ +█ *$", line)]


async def test_the_help_and_summary_scrollbars_sit_at_their_boxs_edge():
    app = ros1_app(400)
    async with app.run_test(size=(80, 24)) as pilot:
        await until_shown(pilot, "# Time")
        for key, first in (("question_mark", "console-tui shows every node's"), ("S", "Summary: 400 messages")):
            await pilot.press(key)
            await until_shown(pilot, first)
            assert "# Time" not in screen_text(app), "the box covers the table's header"
            top = screen_text(app).splitlines()[4]
            await pilot.press("pagedown", "down")
            await pilot.wait_for_scheduled_animations()  # a page scrolled, if there is one below
            await frame_drawn(pilot)
            if key == "question_mark":
                assert screen_text(app).splitlines()[4] != top, "the help did not scroll"
            assert not floating_glyphs(app), "\n".join(screen_text(app).splitlines())
            await pilot.press("escape")
            await until_shown(pilot, "# Time")  # the table again, where the box was
