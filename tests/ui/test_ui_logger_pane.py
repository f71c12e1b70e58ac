"""Pilot tests of the logger levels pane without ROS: keys, focus, what it shows for a given state.

The pane's state is fed through its public methods (nodes, levels, temporary levels), as
its ``LoggerControl`` would; what ROS does is tested in test_e2e_logger_pane.py.
"""

from __future__ import annotations

import re
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from functools import partial

from textual.pilot import Pilot

from console_tui.model.loggers.logger_levels import ENABLE_LOGGER_SERVICE_HINT, TemporaryLevel
from console_tui.model.loggers.logger_pane_state import NO_ROS_TEXT
from console_tui.ui.screens.temporary_level import TemporaryLevelScreen
from console_tui.ui.widgets.logger_pane import LoggerPane

from support import ui
from support.feed import GRAPH, PLANNER, feed_logger_pane, records
from support.ui import cursor_number, frame_drawn, option_lines, pick_node, screen_text, table_rows, type_text, until

make_app = partial(ui.make_app, clock=lambda: 100.0)  # nodes include navigation.planner and its costmap


@asynccontextmanager
async def fed_pane() -> AsyncIterator[tuple[Pilot, LoggerPane]]:
    """The app running at 140x30, its pane opened with ``l`` and given the fixed state of
    ``feed_logger_pane``: the pilot and the pane."""
    app = make_app()
    async with app.run_test(size=(140, 30)) as pilot:
        pane = app.main.logger_pane
        await pilot.press("l")
        feed_logger_pane(pane)
        await pilot.pause()
        yield pilot, pane


def notice(pane: LoggerPane) -> str:
    return str(pane.notice_line.content)


def pane_text(app) -> list[str]:
    """The logger pane's part of each terminal row, as the screen shows it."""
    region = app.main.logger_pane.region
    lines = screen_text(app).splitlines()[region.y : region.bottom]  # below the timeline
    return [line[region.x :].lstrip("▏").strip() for line in lines]


def pane_says(app, text: str) -> bool:
    """Whether the pane shows ``text``, wrapped over its rows or not."""
    return text in " ".join(" ".join(pane_text(app)).split())


async def test_l_toggles_the_pane_escape_gives_the_table_the_keys_and_the_table_follows():
    app = make_app()
    async with app.run_test(size=(120, 30)) as pilot:
        await until(pilot, lambda: cursor_number(app) == 100, what="the table")
        assert "Logger levels" not in screen_text(app)
        await pilot.press("l")
        await until(pilot, lambda: pane_says(app, "Logger levels · nodes"), what="the pane")
        app.main.intake.add_records(records(20, start=100))
        await until(pilot, lambda: max(table_rows(app)) == 120, what="the table following with the pane open")
        await pilot.press("escape", "space")  # the table's keys work with the pane open
        await until(pilot, lambda: "PAUSED" in screen_text(app).splitlines()[-2], what="the table paused")
        assert pane_says(app, "Logger levels · nodes")
        await pilot.press("l")
        await until(pilot, lambda: "Logger levels" not in screen_text(app), what="the pane closed")
        await pilot.press("space")  # the table has the keys again
        await until(pilot, lambda: "PAUSED" not in screen_text(app).splitlines()[-2], what="the table resumed")


async def test_without_ros_the_pane_says_so_and_keys_do_no_harm():
    app = make_app()
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.press("l")
        await until(pilot, lambda: pane_says(app, NO_ROS_TEXT), what="the pane saying there is no ROS")
        await pilot.press("d", "t", "x")
        await pilot.press("L")
        await until(pilot, lambda: pane_says(app, "No node in the ROS graph logs as"), what="the pane's answer to L")
        assert "Temporary level for" not in screen_text(app), "t opened no dialog"
        assert app.main.logger_pane.state.notice_is_error


async def test_nodes_marks_loggers_and_levels_as_shown():
    async with fed_pane() as (pilot, pane):
        app = pilot.app
        await until(pilot, lambda: pane_says(app, "Loggers of /navigation/planner"), what="the fed pane")
        shown = pane_text(app)
        nodes = shown[1:5]
        assert nodes[0] == "/count_and_log" and nodes[1] == "/navigation/planner"
        assert nodes[2].startswith("/power/battery_monitor") and nodes[2].endswith("no logger services")
        assert nodes[3].startswith("/sensors/lidar_driver") and nodes[3].endswith("checking…")
        rows = {line.split()[0]: line for line in shown[shown.index("Loggers of /navigation/planner") + 1 :] if line}
        assert rows["navigation.planner"].endswith("DEBUG")
        assert rows[".costmap"].endswith("inherited (DEBUG)"), "a child logger seen in the records, inheriting"
        assert rows['""'].endswith("INFO") and '"" (default)' in rows['""']
        assert pane.highlighted_logger == "navigation.planner"
        # A node without the services: the hint; a node still being checked: says so.
        assert pane.node_list.has_focus and pane.selected == PLANNER
        await pilot.press("down")  # /power/battery_monitor
        await until(pilot, lambda: pane_says(app, ENABLE_LOGGER_SERVICE_HINT), what="the hint on the screen")
        assert pane.selected == "/power/battery_monitor"
        assert pane.rows() == [] and not pane_says(app, "navigation.planner DEBUG")
        await pilot.press("down")  # /sensors/lidar_driver
        await until(
            pilot,
            lambda: pane_says(app, "Checking whether /sensors/lidar_driver offers logger services"),
            what="the check on the screen",
        )
        # A click on a node selects it.
        await pilot.click("#logger-nodes", offset=(2, 1))
        assert pane.selected == PLANNER
        # The node leaves the graph.
        pane.show_nodes(GRAPH[:1])
        assert pane.selected is None and f"{PLANNER} left the ROS graph" in notice(pane)


async def test_arrows_move_between_the_lists_and_keys_pick_the_logger():
    async with fed_pane() as (pilot, pane):
        await pilot.press("right")
        assert pane.logger_list.has_focus
        await pilot.press("down")
        assert pane.highlighted_logger == "navigation.planner.costmap"
        await pilot.press("left")
        assert pane.node_list.has_focus and pane.selected == PLANNER
        await pilot.press("down")
        assert pane.selected == "/power/battery_monitor"
        await pilot.press("up", "enter")
        assert pane.selected == PLANNER and pane.logger_list.has_focus


async def test_a_typed_logger_name_is_offered_and_highlighted():
    async with fed_pane() as (pilot, pane):
        await pilot.press("a")
        assert pane.name_input.has_focus
        await pilot.press(*"navigation.planner.extra", "enter")
        assert pane.logger_list.has_focus and pane.highlighted_logger == "navigation.planner.extra"
        await frame_drawn(pilot)
        assert next(line for line in option_lines(pane.logger_list) if "extra" in line).endswith("?"), "not read yet"
        pane.show_levels(PLANNER, {"navigation.planner.extra": 0})
        await frame_drawn(pilot)
        assert next(line for line in option_lines(pane.logger_list) if "extra" in line).endswith("inherited (DEBUG)")
        await pilot.press("a", "x", "escape")  # Escape in the box drops the text, back to the loggers
        assert pane.logger_list.has_focus and pane.name_input.value == ""


async def test_temporary_level_shows_its_countdown():
    async with fed_pane() as (pilot, pane):
        pane.show_temporaries([TemporaryLevel(PLANNER, "navigation.planner.costmap", 10, 0, deadline=165.2)])
        await frame_drawn(pilot)
        row = next(line for line in option_lines(pane.logger_list) if ".costmap" in line)
        assert row.endswith("DEBUG for 1:06")  # 65.2 s left on the app's clock, rounded up


async def test_key_on_a_table_row_opens_the_pane_on_its_node_and_logger():
    app = make_app(10)
    async with app.run_test(size=(140, 30)) as pilot:
        pane = app.main.logger_pane
        pane.show_nodes(GRAPH)
        row = next(i for i in range(10) if app.main.store.get(i).node == "navigation.planner.costmap")
        await pilot.press("home", *["down"] * row)
        await until(pilot, lambda: cursor_number(app) == row + 1, what="the cursor on the costmap's row")
        await pilot.press("L")
        await until(pilot, lambda: pane_says(app, f"Loggers of {PLANNER}"), what="the pane on the row's node")
        assert pane.highlighted_logger == "navigation.planner.costmap" and pane.logger_list.has_focus


async def test_help_and_command_palette_offer_the_pane():
    app = make_app(5)
    async with app.run_test(size=(100, 40)) as pilot:
        titles = [command.palette_title for command in app.commands.palette()]
        assert "Logger levels" in titles and "Logger levels of this row's node" in titles
        groups = dict(app.binding_groups())
        assert any(b.action == "set_level(10)" for b in groups["Logger levels pane"])
        await pilot.press("question_mark")
        await until(pilot, lambda: "Change keys in" in screen_text(app), what="the help")
        await pilot.press("escape", "ctrl+p")
        await type_text(pilot, "logger levels")
        await until(pilot, lambda: "Logger levels of this row's node" in screen_text(app), what="the palette")
        await pilot.press("enter")
        await until(pilot, lambda: pane_says(app, "Logger levels · nodes"), what="the pane")


async def test_temporary_level_dialog():
    app = make_app(5)
    async with app.run_test(size=(100, 30)) as pilot:
        results: list = []
        title = "Temporary level for n on /n"
        app.push_screen(TemporaryLevelScreen("/n", "n", 30), results.append)
        await until(pilot, lambda: title in screen_text(app), what="the dialog")
        await pilot.press("enter")
        await until(pilot, lambda: results == [(10, 30.0)], what="DEBUG for 30 s chosen")
        assert title not in screen_text(app)
        app.push_screen(TemporaryLevelScreen("/n", "n", 30), results.append)
        await until(pilot, lambda: title in screen_text(app), what="the dialog")
        await pilot.press("down", "down", "0", "enter")
        await until(pilot, lambda: "above 0" in screen_text(app), what="0 s refused, on the screen")
        assert title in screen_text(app) and len(results) == 1, "the dialog stays open"
        await pilot.press("backspace", "1", ".", "5", "enter")
        await until(pilot, lambda: results[-1] == (30, 1.5), what="WARN for 1.5 s chosen")
        assert title not in screen_text(app)
        app.push_screen(TemporaryLevelScreen("/n", "n", 30), results.append)
        await until(pilot, lambda: title in screen_text(app), what="the dialog")
        await pilot.press("escape")
        await until(pilot, lambda: title not in screen_text(app), what="the dialog cancelled")
        assert results[-1] is None


async def test_the_graph_is_watched_only_while_the_pane_is_open():
    from support.memory_control import MemoryControl, MemoryNode

    control = MemoryControl([MemoryNode("/watched_node")])
    control.remote_graph = True  # as a ROS 1 master's
    app = make_app(logger_control=control)
    try:
        async with app.run_test(size=(120, 30)) as pilot:
            await until(pilot, lambda: cursor_number(app) == 100, what="the table")
            assert not control.graph_watched  # closed: the master is not asked for nodes
            await pilot.press("l")
            await until(pilot, lambda: pane_says(app, "watched_node"), what="the node listed")
            assert control.graph_watched
            await pilot.press("l")
            await until(pilot, lambda: not control.graph_watched, what="the watch ended")
    finally:
        control.close()


async def test_a_rows_node_asked_for_before_the_graph_is_known_is_shown_when_it_comes():
    from support.memory_control import MemoryControl, MemoryNode

    control = MemoryControl([MemoryNode("/power/battery_monitor")])  # the last row's node
    control.remote_graph = True  # as a ROS 1 master's: nothing known until the pane opens
    app = make_app(logger_control=control)
    try:
        async with app.run_test(size=(140, 30)) as pilot:
            await until(pilot, lambda: cursor_number(app) == 100, what="the table")
            assert not control.graph_watched and not app.main.logger_pane.state.nodes
            await pilot.press("L")
            await until(
                pilot, lambda: app.main.logger_pane.selected == "/power/battery_monitor", what="the row's node selected"
            )
            assert pane_says(app, "battery_monitor")
    finally:
        control.close()


async def test_a_mixed_fleet_reads_a_ros2_robots_levels_on_highlight_and_a_ros1_robots_when_asked():
    from console_tui.control.fleet_control import FleetLoggerControl

    from support.memory_control import MemoryControl, MemoryNode

    ros2 = MemoryControl([MemoryNode("/arm_driver")])
    ros1 = MemoryControl([MemoryNode("/cart_driver")])
    ros1.read_when_asked = True  # as a ROS 1 master's nodes: get_loggers can crash roscpp
    control = FleetLoggerControl({"arm": ros2, "cart": ros1})
    app = make_app(logger_control=control)
    try:
        async with app.run_test(size=(140, 30)) as pilot:
            await until(pilot, lambda: cursor_number(app) == 100, what="the table")
            await pilot.press("l")
            await until(pilot, lambda: pane_says(app, "cart:/cart_driver"), what="both robots' nodes")
            await pick_node(pilot, "arm:/arm_driver")
            default_is = partial(re.search, r'^"" \(default\) +(\S+)$', flags=re.M)
            await until(
                pilot,
                lambda: (found := default_is("\n".join(pane_text(app)))) and found[1] == "INFO",
                what="the ROS 2 robot's levels, read at once",
            )
            await pick_node(pilot, "cart:/cart_driver")
            await until(pilot, lambda: pane_says(app, "Loggers of cart:/cart_driver"), what="the ROS 1 robot's node")
            assert pane_says(app, "read its loggers")
            assert default_is("\n".join(pane_text(app)))[1] == "?", "not read until asked"
            await pilot.press("r")
            await until(pilot, lambda: default_is("\n".join(pane_text(app)))[1] == "INFO", what="read when asked")
    finally:
        control.close()


async def test_the_logger_control_starts_when_the_pane_first_opens():
    """The app joins the ROS graph for logger levels (rclpy, a DDS participant: 44 MB) only
    once they are wanted: live records and time passing do not start it, opening the pane does."""
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.model.store.record_batch import RecordColumns
    from console_tui.sources.status import SourceStatus

    from support.feed import StaticSource
    from support.memory_control import MemoryControl, MemoryNode

    control = MemoryControl([MemoryNode("/talker")])
    queue = IntakeQueue()
    source = StaticSource(SourceStatus(topic="/rosout", publishers=1, running=True))
    now = [0.0]
    app = make_app(logger_control=control, queue=queue, sources=[source], clock=lambda: now[0])
    try:
        async with app.run_test(size=(120, 30)) as pilot:
            await until(pilot, lambda: cursor_number(app) == 100, what="the table")
            queue.put(RecordColumns.from_records(records(1, start=500)))
            await until(pilot, lambda: cursor_number(app) == 101, what="the live record")
            now[0] += 3600.0
            queue.put(RecordColumns.from_records(records(1, start=501)))  # a drain an hour later, shown
            await until(pilot, lambda: cursor_number(app) == 102, what="the live record an hour later")
            await frame_drawn(pilot)
            assert control._thread is None, "started before the pane opened"
            await pilot.press("l")
            await until(pilot, lambda: pane_says(app, "talker"), what="the node listed")
            assert control._thread is not None
    finally:
        control.close()


async def test_while_the_graph_is_discovered_the_pane_says_it_is_looking():
    """The first opening starts the control: until the graph was watched long enough, an empty
    node list says it is being looked for, then that there is none yet."""
    from support.memory_control import MemoryControl, StepClock

    clock = StepClock()
    control = MemoryControl([], clock=clock)
    control.graph_min_s, control.graph_quiet_s = 5.0, 2.0
    app = make_app(logger_control=control)
    try:
        async with app.run_test(size=(120, 30)) as pilot:
            await pilot.press("l")
            await pilot.pause()
            assert pane_says(app, "Looking for the ROS graph's nodes…"), "said as the pane opens, not a tick later"
            clock.now = 10.0
            await until(pilot, lambda: pane_says(app, "No nodes in the ROS graph yet."), what="none yet")
    finally:
        control.close()
