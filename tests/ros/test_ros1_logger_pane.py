"""The logger levels pane on ROS 1, end to end: the real app over a real roscore, the native
ROS 1 source and logger control, rospy and roscpp nodes; keys typed, the screen read."""

from __future__ import annotations

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.ui.app import ConsoleApp

from support.ros1 import ROSCPP_LOGGER
from support.rosproc import pid_alive
from support.ui import screen_text, type_text, until

pytestmark = pytest.mark.ros1


@pytest.fixture
def live(roscore):
    from console_tui.control.ros1.logger_control import Ros1LoggerControl
    from console_tui.sources.ros1.live_source import Ros1LiveSource

    queue = IntakeQueue()
    control = Ros1LoggerControl(call_timeout=3.0)
    app = ConsoleApp(queue=queue, sources=[Ros1LiveSource(queue)], utc=True, logger_control=control)
    yield app
    control.close()


def debug_rows(app, node: str) -> list:
    return [r for r in app.main.store if r.node == node and r.level == 10]


def pane_line(app, text: str) -> str:
    """The screen line holding ``text`` (the pane is on the right: its part of the line)."""
    return next((line for line in screen_text(app).splitlines() if text in line), "")


async def test_pane_lists_ros1_nodes_reads_on_enter_and_sets_debug(live, ros1_nodes, roscpp_binary):
    py = ros1_nodes.rospy("rospy_node.py", "py_talker", "--period", "0.1")
    cpp = ros1_nodes.roscpp("talk", "cpp_talker", "100")
    py.expect("ready")
    cpp_pid = cpp.expect("ready")["pid"]
    app = live
    async with app.run_test(size=(160, 40)) as pilot:
        pane = app.main.logger_pane
        await until(pilot, lambda: {"/py_talker", "/cpp_talker"} <= {r.node for r in app.main.store}, what="rows")
        assert "ROS 1 http://127.0.0.1:" in screen_text(app)  # the status line says which ROS and where
        await pilot.press("l")
        await until(
            pilot,
            lambda: all(name in screen_text(app) for name in ("/cpp_talker", "/py_talker", "/rosout")),
            what="the nodes in the pane",
        )
        assert "/console_tui_" not in screen_text(app).split("Logger levels")[1]

        # Highlighting a node reads nothing (get_loggers can crash roscpp): the pane says how to.
        assert pane.selected == "/cpp_talker"
        await until(pilot, lambda: "⏎/r read its loggers" in screen_text(app), what="the hint")
        assert pane.rows() == []

        # roscpp: set by typed name, no get_loggers, DEBUG rows appear.
        await pilot.press("a")
        await type_text(pilot, ROSCPP_LOGGER)
        await pilot.press("enter", "d")
        await until(pilot, lambda: "DEBUG" in pane_line(app, ROSCPP_LOGGER), what="the level shown")
        await until(pilot, lambda: len(debug_rows(app, "/cpp_talker")) >= 3, what="roscpp DEBUG rows")
        await until(pilot, lambda: "debug " in screen_text(app), what="DEBUG rows on screen")
        await pilot.press("i")
        await until(pilot, lambda: "INFO" in pane_line(app, ROSCPP_LOGGER), what="INFO again")
        assert pid_alive(cpp_pid)

        # rospy: Enter on the node reads its loggers; 'rosout' to DEBUG by key.
        await pilot.press("left", "down")
        assert pane.selected == "/py_talker"
        await pilot.press("enter")
        await until(pilot, lambda: "rospy.core" in screen_text(app), what="the rospy node's loggers")
        names = [row.name for row in pane.rows()]
        assert "rosout" in names and "rospy" in names
        while pane.highlighted_logger != "rosout":
            await pilot.press("down")
        await pilot.press("d")
        await until(pilot, lambda: "DEBUG" in pane_line(app, "rosout "), what="rosout at DEBUG")
        await until(pilot, lambda: len(debug_rows(app, "/py_talker")) >= 3, what="rospy DEBUG rows")

        # ROS 1 loggers cannot be unset: said plainly.
        await pilot.press("u")
        await until(pilot, lambda: "cannot be unset" in screen_text(app), what="the refusal")
        await pilot.press("i")
        await until(pilot, lambda: "INFO" in pane_line(app, "rosout "), what="rosout at INFO")

        # L on a table row opens the pane on that row's node (ROS 1 rows name their node).
        await pilot.press("escape")
        assert app.main.table.has_focus
        await pilot.press("up")  # the cursor stays on this row while rows arrive
        record = app.main.store.get(app.main.table.cursor_seq)
        await pilot.press("L")
        assert pane.selected == record.node
