"""Hostile input in the app (issue 17): file names with terminal escapes, markup in what
files and messages hold, the clipboard, invisible characters, the command palette's PageUp.
Nothing may crash the app or reach the terminal or the clipboard raw."""

from __future__ import annotations

import base64
import json
import re

from textual.command import CommandList, CommandPalette
from textual.widgets import Checkbox, Input

from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.sources.files.loader import FileProgress, LoadProgress
from console_tui.ui.app import ConsoleApp
from console_tui.ui.screens.detail import DetailScreen
from console_tui.ui.screens.load_problems import ProblemsScreen
from console_tui.ui.screens.quick_rule import QuickRuleScreen
from console_tui.ui.screens.rule_editor import RuleEditor

from support.ui import foreign_controls, screen_text, terminal_output, type_text, until, until_shown

TITLE = "\x1b]0;PWNED\x07"
CLIPBOARD = "\x1b]52;c;cm0gLXJmIH4=\x07"  # sets the clipboard to "rm -rf ~"
CONTROLS = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def app_with(*msgs: str, **options) -> ConsoleApp:
    store = LogStore()
    store.extend_records(
        LogRecord(stamp_ns=1_795_000_000_000_000_000 + i, level=20, node="n", msg=msg) for i, msg in enumerate(msgs)
    )
    return ConsoleApp(store=store, utc=True, **options)


def assert_inert(app) -> str:
    """The screen as text has no control character, and what the app would write to the
    terminal has none but Textual's own colour and cursor sequences."""
    text = screen_text(app)
    assert not CONTROLS.search(text.replace("\n", "")), f"control characters on screen: {text!r}"
    assert foreign_controls(terminal_output(app)) == []
    return text


async def test_escapes_in_a_file_name_never_reach_the_terminal(tmp_path):
    hostile = tmp_path / f"run{TITLE}{CLIPBOARD}.log"
    hostile.write_text("[INFO] [1.000000000] [n]: fine\n[INFO] [2.0")  # a problem that names the file
    app = ConsoleApp(files=[str(hostile)], utc=True)
    async with app.run_test(size=(160, 40), notifications=True) as pilot:
        await until(pilot, lambda: "with problems" in screen_text(app), what="the load notification")
        text = assert_inert(app)
        assert "␛]0;PWNED␇" in text  # shown, as visible stand-ins
        # The load bar names the file being read.
        app.main.load_bar.show_progress([LoadProgress((FileProgress(hostile.name, "", 0.5, 0),), 10, False, False)])
        await pilot.pause()
        assert "Loading 1 file: run␛]0;PWNED␇" in assert_inert(app)
        app.main.load_bar.show_progress([])
        await pilot.press("exclamation_mark")
        await until(pilot, lambda: isinstance(app.screen, ProblemsScreen), what="the problems screen")
        await pilot.pause()
        assert "PWNED" in assert_inert(app)


async def test_markup_in_file_content_and_problems_is_shown_as_text(tmp_path):
    path = tmp_path / "marked.jsonl"
    lines = [
        json.dumps({"stamp_ns": 1, "msg": "[/]", "node": "[bold]n[/bold]"}),
        json.dumps({"stamp_ns": "[/]", "msg": "m"}),  # a problem that quotes the value
        json.dumps({"stamp_ns": 3, "msg": "m", "level": "[@click=app.quit]x[/]"}),
    ]
    path.write_text("\n".join(lines) + "\n")
    app = ConsoleApp(files=[str(path)], utc=True)
    async with app.run_test(size=(160, 40), notifications=True) as pilot:
        await until(pilot, lambda: "with problems" in screen_text(app), what="the load notification")
        text = assert_inert(app)
        assert "[bold]n[/bold]" in text and "is not an integer: '[/]'" in text
        await pilot.press("exclamation_mark")
        await until(pilot, lambda: isinstance(app.screen, ProblemsScreen), what="the problems screen")
        app.notify("[/] a [@click=app.quit]markup[/] notification")
        await until_shown(pilot, "[/] a [@click=app.quit]markup[/] notification")
        assert "[/] a [@click=app.quit]markup[/] notification" in screen_text(app)
        assert app.is_running


async def test_markup_in_messages_reaches_the_quick_rule_choices_as_text():
    app = app_with("[bold]x[/bold]", "[/]", "[link=http://x]x")
    async with app.run_test(size=(160, 40), notifications=True) as pilot:
        await pilot.pause()
        await pilot.press("shift+up", "shift+up", "minus")
        await until(pilot, lambda: isinstance(app.screen, QuickRuleScreen), what="the quick rule choices")
        await pilot.pause()
        text = screen_text(app)
        assert "[/]" in text and "[bold]x[/bold]" in text and app.is_running


async def test_markup_in_a_bad_regex_is_shown_as_text():
    app = app_with("a", "b")
    async with app.run_test(size=(160, 40), notifications=True) as pilot:
        await pilot.pause()
        await pilot.press("slash")
        await type_text(pilot, "/[/]")
        await pilot.pause()
        assert "/[/]" in screen_text(app) and app.is_running
        await pilot.press("escape", "r", "a")
        await until(pilot, lambda: isinstance(app.screen, RuleEditor), what="the rule editor")
        editor = app.screen
        editor.query_one("#message-text", Input).focus()
        await type_text(pilot, "[/x")
        editor.query_one("#message-regex", Checkbox).value = True
        await pilot.press("enter")
        await pilot.pause()
        assert "Not applied: invalid regular expression '[/x'" in screen_text(app)
        assert app.is_running


async def test_copy_puts_no_control_character_on_the_clipboard():
    hostile = f"clear \x1b[2J title {TITLE} cr\rbell\x07 nul\x00 c1\x9b31m zw\u200b\nsecond line\tend"
    app = app_with("plain", hostile)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        written: list[str] = []
        app._driver.write = written.append  # the headless driver writes nothing: see what it is given
        await pilot.press("enter")
        await until(pilot, lambda: isinstance(app.screen, DetailScreen), what="the detail view")
        await pilot.press("y")
        await pilot.pause()
        payloads = [m.group(1) for chunk in written for m in re.finditer(r"\x1b\]52;c;([A-Za-z0-9+/=]*)\x07", chunk)]
        assert len(payloads) == 1
        copied = base64.b64decode(payloads[0]).decode("utf-8")
        assert not CONTROLS.search(copied), repr(copied)
        assert copied == "clear ␛[2J title ␛]0;PWNED␇ cr␍bell␇ nul␀ c1<U+009B>31m zw<U+200B>\nsecond line\tend"


async def test_invisible_characters_show_as_stand_ins():
    app = app_with("zero\u200bwidth", "line\u2028sep", "para\u2029sep", "tag\U000e0041s")
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        text = screen_text(app)
        for shown in ("zero<U+200B>width", "line<U+2028>sep", "para<U+2029>sep", "tag<U+E0041>s"):
            assert shown in text


async def test_page_up_in_the_command_palette_before_its_list_is_laid_out():
    app = app_with("a", "b")
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        await pilot.press("ctrl+p")
        await until(pilot, lambda: isinstance(app.screen, CommandPalette), what="the palette")
        await until(pilot, lambda: app.screen.query_one(CommandList).option_count > 0, what="the commands")
        # The state Textual 8.2.8 crashes in (KeyError: 0): options, one highlighted, but no
        # lines laid out, as while the palette's results come in.
        commands = app.screen.query_one(CommandList)
        commands.highlighted = 3
        commands.styles.display = "none"
        commands._clear_caches()
        await pilot.press("pageup")
        await pilot.press("pagedown")
        await pilot.pause()
        assert app.is_running and isinstance(app.screen, CommandPalette)
        commands.styles.display = "block"
        await pilot.press("escape")
        await pilot.pause()
        assert app.is_running
