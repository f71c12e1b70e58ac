"""The Textual work-arounds (``ui/textual_fixes.py``) check what they patch: each is
installed on the Textual tested, and skipped (and named by ``--version``) when its target
is not what it was written against. What each fixes is tested beside the behaviour
(test_ui_garbage, test_ui_focus_redraw, test_hostile_exit, ...)."""

from __future__ import annotations

import dataclasses
import inspect
import subprocess
import sys
from pathlib import Path

import pytest
from textual.binding import BindingsMap
from textual.drivers._writer_thread import WriterThread
from textual.drivers.linux_driver import LinuxDriver
from textual.screen import Screen
from textual.strip import Strip
from textual.widgets import OptionList

from console_tui.ui import textual_fixes
from console_tui.ui.textual_fixes import FIXES, check, fixes_text, install, source_of

REPO = Path(__file__).resolve().parents[2]

#: How each fix shows once installed.
INSTALLED = {
    "OptionList._move_page": lambda: OptionList._move_page is textual_fixes._move_page,
    "BindingsMap.apply_keymap": lambda: BindingsMap.apply_keymap is textual_fixes._apply_keymap,
    "WriterThread.run": lambda: WriterThread.run is textual_fixes._write_until_stopped,
    "LinuxDriver._sigcont_application": lambda: LinuxDriver._sigcont_application is textual_fixes._sigcont_application,
    "Strip.crop_extend": lambda: Strip.crop_extend is textual_fixes._crop_extend,
    "Strip.divide": lambda: Strip.divide is textual_fixes._divide,
    "Screen.focused repaint": lambda: Screen.focused._repaint is False,
}


def test_every_fix_is_listed_with_its_upstream_state():
    assert [fix.name for fix in FIXES] == list(INSTALLED)
    for fix in FIXES:
        assert fix.upstream.startswith(("https://github.com/Textualize/textual/", "not yet reported — "))


@pytest.mark.parametrize("fix", FIXES, ids=lambda fix: fix.name)
def test_installed_on_the_textual_tested(fix):
    assert check(fix) is None, "Textual changed what this fix patches: check the fix again"
    assert install([fix]) == {}
    assert INSTALLED[fix.name]()


@pytest.mark.parametrize("fix", FIXES, ids=lambda fix: fix.name)
def test_the_source_checked_is_the_whole_function(fix):
    # source_of reads the lines the code object spans instead of tokenizing the file: the
    # same text as inspect.getsource, closing brackets on their own lines included.
    assert source_of(fix.target) == inspect.getsource(fix.target)


@pytest.mark.parametrize("fix", FIXES, ids=lambda fix: fix.name)
def test_skipped_when_its_target_changed(fix):
    installed = []
    changed = dataclasses.replace(fix, source_hash="0" * 16, install=lambda: installed.append(1))
    skipped = install([changed])
    assert skipped == {fix.name: f"{fix.qualname} changed in Textual {textual_fixes.textual.__version__}"}
    assert installed == []

    def elsewhere() -> None:
        pass

    moved = dataclasses.replace(fix, target=elsewhere, install=lambda: installed.append(1))
    assert "is now test_skipped_when_its_target_changed.<locals>.elsewhere" in install([moved])[fix.name]
    assert installed == []


def test_version_names_the_skipped_fixes(monkeypatch):
    assert fixes_text().endswith(f": {len(FIXES)} of {len(FIXES)} work-arounds in use")
    first = FIXES[0]
    monkeypatch.setitem(textual_fixes._CHECKED, first, "OptionList._move_page changed in Textual 9.0.0")
    text = fixes_text()
    assert f"{len(FIXES) - 1} of {len(FIXES)} work-arounds in use" in text
    assert "skipped" in text and "OptionList._move_page (OptionList._move_page changed in Textual 9.0.0)" in text


def test_version_output():
    result = subprocess.run(
        [sys.executable, "-m", "console_tui", "--version"], capture_output=True, text=True, timeout=60, cwd=REPO
    )
    assert result.returncode == 0
    first, second = result.stdout.splitlines()
    assert first.startswith("console-tui ") and second.startswith("Textual ") and "work-arounds in use" in second
