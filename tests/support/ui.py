"""Driving the app in tests as a person does: fixed records, keys, and the screen as text.

The screen is read here and nowhere else: ``screen_text`` (what the terminal shows, as text),
``widget_lines`` (a widget's rows of it), ``style_at`` (a cell's colours), ``terminal_output``
(what the app would write to the terminal). Waits end when a condition holds: ``until`` for a
condition, ``frame_drawn`` for the frame that shows what was asked of the screen so far.
"""

from __future__ import annotations

import asyncio
import contextlib
import io
import re
import time
from collections.abc import AsyncIterator, Callable

from rich.cells import cell_len
from rich.console import Console
from textual.keys import _character_to_key
from textual.pilot import Pilot

from console_tui.model.store.log_store import DEFAULT_MAX_MESSAGES, LogStore
from console_tui.ui.app import ConsoleApp

from support.feed import records
from support.rosproc import PATIENCE_S


def make_app(count: int = 100, *, max_messages: int = DEFAULT_MAX_MESSAGES, **options) -> ConsoleApp:
    """The app over ``count`` fixed records (``support.feed``), times in UTC."""
    store = LogStore(max_messages=max_messages)
    store.extend_records(records(count))
    options.setdefault("utc", True)
    return ConsoleApp(store=store, **options)


_RUN_TEST = ConsoleApp.run_test


@contextlib.asynccontextmanager
async def run_test_when_ready(app: ConsoleApp, *args, **kwargs) -> AsyncIterator[Pilot]:
    """``App.run_test``, giving the pilot once the console's panes hidden at start are mounted
    (``ConsoleScreen.ready_for_keys``; the app's ``run_test`` in every UI test, see conftest)."""
    async with _RUN_TEST(app, *args, **kwargs) as pilot:
        await until(pilot, lambda: app.main.ready_for_keys or not app.is_running, what="the hidden panes mounted")
        yield pilot


async def until(
    pilot, condition: Callable[[], object], timeout: float = PATIENCE_S, what: str | Callable[[], str] = "the app"
) -> None:
    """Let the app run, a frame at a time, until ``condition()`` holds; fail after ``timeout``
    seconds (one generous deadline: the wait ends as soon as the condition holds), saying
    ``what`` was awaited (a callable: what it says at that moment)."""
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what() if callable(what) else what}")
        await pilot.pause(0.02)


async def until_shown(pilot, *texts: str, timeout: float = PATIENCE_S) -> str:
    """Let the app run until the screen shows every one of ``texts``; the screen as text then."""
    app = pilot.app
    await until(
        pilot,
        lambda: all(text in screen_text(app) for text in texts),
        timeout,
        what=lambda: f"{texts} on the screen, which shows:\n{screen_text(app)}",
    )
    return screen_text(app)


async def frame_drawn(pilot, *widgets, timeout: float = PATIENCE_S) -> None:
    """Until the screen has drawn what was asked of it so far: every message already sent
    handled (``Pilot.pause``), then the screen refreshed (``wait_for_refresh``: its callback
    runs after Textual's next compositor update, or at once when nothing is left to draw).
    ``widgets``: ones whose own work ``Pilot.pause`` does not wait for (a scrollbar is no
    child of its widget), each waited through first.

    What a timer of the app does later is not waited for: wait for a condition that shows it
    (``until``). A check that something is *not* drawn waits first for a sign that the frame
    which would have drawn it came (what it follows, shown), then for this, then looks."""
    await pilot.pause()
    for node in (*widgets, pilot.app.screen):
        await asyncio.wait_for(node.wait_for_refresh(), timeout)


def _screen_update(app, color_system: str | None):
    """The update that draws the whole screen now (every screen on the stack), and a
    terminal-sized console to render it.

    The one use of Textual's privates to read the screen (checked against Textual 8.2.8):
    ``Screen._compositor.render_update(full=True, screen_stack=App._background_screens)`` is
    what ``App.export_screenshot`` renders too, but that public call gives SVG only. Parsed
    back to text it gives the same text, 8 times slower at 80x24 and 25 times at 200x50
    (9 ms and 45 ms a read, against 1.1 and 1.7), and the tests read the screen in every turn
    of their waits; and the escape sequences the terminal would get (``terminal_output``)
    are in no public call of a headless app.
    """
    width, height = app.size
    console = Console(
        width=width,
        height=height,
        file=io.StringIO(),
        force_terminal=True,
        color_system=color_system,
        record=True,
        legacy_windows=False,
    )
    return app.screen._compositor.render_update(full=True, screen_stack=app._background_screens), console


def screen_text(app) -> str:
    """What the terminal shows now, as plain text: one line per terminal row, every
    screen on the stack composed as the terminal gets it."""
    update, console = _screen_update(app, None)
    console.print(update)
    return console.export_text(styles=False)


def terminal_output(app) -> str:
    """What the app would write to the terminal to draw the screen now (escape sequences for
    colours and cursor moves included): the headless driver writes nothing, so this renders
    the same update the real driver is given."""
    update, console = _screen_update(app, "truecolor")
    return update.render_segments(console)


#: The sequences Textual itself writes: CSI (colours, cursor moves) and nothing else.
_OWN_SEQUENCES = re.compile(r"\x1b\[[0-?]*[ -/]*[@-~]")


def foreign_controls(output: str) -> list[str]:
    """Control characters in ``output`` that are not part of Textual's own CSI sequences
    (line ends aside): an OSC, a bell, any ESC from the content."""
    rest = _OWN_SEQUENCES.sub("", output).replace("\r", "").replace("\n", "")
    return sorted({repr(c) for c in rest if ord(c) < 0x20 or 0x7F <= ord(c) <= 0x9F})


def style_at(app, x: int, y: int):
    """The Rich style of the terminal cell at column ``x``, row ``y`` (colours, bold, reverse...)."""
    return app.screen.get_style_at(x, y)


def widget_lines(app, widget) -> list[str]:
    """The rows of ``widget``'s content as the screen shows them (inside its border, padding
    and scrollbars), each cut to the widget's width, trailing spaces dropped."""
    region = widget.scrollable_content_region
    lines = screen_text(app).splitlines()[region.y : region.bottom]
    return [columns(line, region.x, region.right).rstrip() for line in lines]


def option_lines(option_list) -> list[str]:
    """What an option list shows, line by line, as the screen shows it (``widget_lines``,
    at most one a option)."""
    return widget_lines(option_list.app, option_list)[: option_list.option_count]


def columns(line: str, start: int, end: int) -> str:
    """The part of a screen row from terminal column ``start`` to ``end``: columns, not
    characters (a wide character such as 漢 takes two)."""
    part, x = [], 0
    for char in line:
        if start <= x < end:
            part.append(char)
        x += cell_len(char)
    return "".join(part)


def steady_cursors(app) -> None:
    """Stop text cursors blinking, so a screen read at any moment shows them."""
    from textual.widgets import Input

    for widget in app.screen.query(Input):
        widget.cursor_blink = False


def line_with(app, text: str) -> tuple[int, str]:
    """The first terminal row showing ``text``, and that row; fails with the screen when none does."""
    lines = screen_text(app).splitlines()
    for y, line in enumerate(lines):
        if text in line:
            return y, line
    raise AssertionError(f"{text!r} is not on the screen:\n" + "\n".join(lines))


def cursor_after(app, text: str) -> bool:
    """Whether the cell just after ``text`` on the screen is drawn as a cursor: its
    background differs from that of the cell after it (the text box's own)."""
    y, line = line_with(app, text)
    x = line.index(text) + len(text)
    return style_at(app, x, y).bgcolor != style_at(app, x + 1, y).bgcolor


def toasts(app, severity: str = "") -> list[str]:
    """The notifications on the screen (``run_test(..., notifications=True)``), each as one
    line: its rows joined, as a person reads it; of one ``severity`` only (``"warning"``...)."""
    found = app.screen.query(f"Toast.-{severity}" if severity else "Toast")
    return [" ".join(line.strip() for line in widget_lines(app, toast) if line.strip()) for toast in found]


async def run_command(pilot, title: str) -> None:
    """Run the command palette's entry ``title`` as a person does: ctrl+p, the title typed,
    enter once the palette offers it first."""
    from textual.command import CommandList

    app = pilot.app

    def offered_first() -> bool:
        lists = app.screen.query(CommandList)
        return bool(lists) and lists.first().highlighted == 0 and widget_lines(app, lists.first())[0].strip() == title

    await pilot.press("ctrl+p")
    await type_text(pilot, title)
    await until(pilot, offered_first, what=f"the palette offering {title!r} first")
    await pilot.press("enter")


async def type_text(pilot, text: str) -> None:
    """Type ``text`` one key at a time, as a person does."""
    for char in text:
        await pilot.press(_key_name(char))


def _key_name(char: str) -> str:
    return _character_to_key(char)


async def pick_node(pilot, name: str) -> None:
    """Highlight the node ``name`` in the logger pane's node list (its loggers shown) with
    the arrow keys, as a person does; the list has the focus."""
    pane = pilot.app.main.logger_pane
    await pilot.press("home")
    for _ in range(pane.node_list.option_count):
        if pane.selected == name:
            return
        await pilot.press("down")
    assert pane.selected == name, f"{name} is not in the node list"


def type_ahead(app, text: str = "", keys: tuple[str, ...] = ()) -> None:
    """Queue ``keys`` (names) and then ``text`` all at once, as the terminal driver does when
    keys arrive while the app is busy: none is handled before the next is queued."""
    from textual import events

    for key in keys:
        app.post_message(events.Key(key, None))
    for char in text:
        app.post_message(events.Key(_key_name(char), char))


def table_rows(app) -> dict[int, tuple[int, str]]:
    """The table's rows on the screen: ``{number in the # column: (terminal row, its text)}``."""
    region = app.main.table.region
    rows = {}
    for y, line in enumerate(screen_text(app).splitlines()):
        words = columns(line, region.x, region.right).split()
        if region.y <= y < region.bottom and words and words[0].isdigit():
            rows[int(words[0])] = (y, line)
    return rows


def cursor_line(app) -> str | None:
    """The table's row drawn in the cursor's colours, as the screen shows it, or None when
    none is. While the table has the focus only: a blurred cursor's colour is blended."""
    table = app.main.table
    cursor = table.get_component_rich_style("log-table--cursor").bgcolor
    lines = screen_text(app).splitlines()
    drawn = [
        y for y in range(table.region.y, table.region.bottom) if style_at(app, table.region.x + 1, y).bgcolor == cursor
    ]
    assert len(drawn) <= 1, f"more than one row drawn as the cursor: {[lines[y] for y in drawn]}"
    return lines[drawn[0]] if drawn else None


def cursor_number(app) -> int | None:
    """The number in the # column of the table's row drawn in the cursor's colours
    (``cursor_line``), or None when none is."""
    line = cursor_line(app)
    if line is None:
        return None
    return next((number for number, (_, shown) in table_rows(app).items() if shown == line), None)
