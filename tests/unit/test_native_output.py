"""Output written to file descriptors 1 and 2 below Python (as Fast DDS and rcutils do)
while the app owns the terminal: caught as records, put back on stderr at the end."""

from __future__ import annotations

import io
import os
import sys

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.system.native_output import NODE, NativeOutput, level_of


def test_lines_written_to_the_descriptors_become_records_and_are_reported_at_the_end():
    queue = IntakeQueue()
    native = NativeOutput(queue)
    stdout_before, stderr_before = sys.__stdout__, sys.__stderr__
    native.start()
    try:
        assert sys.__stderr__ is not stderr_before, "the app draws on a copy of the terminal's descriptor"
        os.write(2, b"\x1b[31;1m[RTPS Error] \x1b[37mport too high\x1b[m\n")
        os.write(1, b"plain note\r\nhalf a li")
        os.write(1, b"ne\n\x1b]52;c;aGk=\x07 clipboard\n")
    finally:
        report = io.StringIO()
        native.stop(report)
    assert (sys.__stdout__, sys.__stderr__) == (stdout_before, stderr_before)
    records = queue.drain()
    assert [r.msg for r in records] == [
        "[RTPS Error] port too high",  # colours are style, not content
        "plain note",
        "half a line",
        "␛]52;c;aGk=␇ clipboard",  # any other escape is made visible, never sent on
    ]
    assert {r.node for r in records} == {NODE}
    assert records[0].level == 40 and records[1].level == 20
    assert "\x1b" not in "".join(r.msg for r in records)
    text = report.getvalue()
    assert text.startswith("console-tui: printed in this process while the console ran:")
    assert "[RTPS Error] port too high" in text and "\x1b" not in text


def test_nothing_caught_nothing_reported():
    native = NativeOutput(IntakeQueue())
    native.start()
    report = io.StringIO()
    native.stop(report)
    assert report.getvalue() == "" and native.caught == 0


def test_pause_gives_the_descriptors_back_and_resume_catches_again(capfd):
    queue = IntakeQueue()
    native = NativeOutput(queue)
    native.start()
    try:
        native.pause()
        os.write(2, b"for the editor's terminal\n")
        native.resume()
        os.write(2, b"caught again\n")
    finally:
        native.stop(io.StringIO())
    assert "for the editor's terminal" in capfd.readouterr().err
    assert [r.msg for r in queue.drain()] == ["caught again"]


def test_levels_from_the_words():
    assert level_of("2026-11-23 [XMLPARSER Error] realpath failed") == 40
    assert level_of("[WARN] [rcl]: something") == 30
    assert level_of("just text, terror-free") == 20


def test_a_console_in_a_browser_is_guarded_too(monkeypatch):
    """Under ``console-tui serve`` standard output is a pipe carrying the screen's frames (the
    Textual web driver's): native output there would break them, so it is caught as well."""
    monkeypatch.setenv("TEXTUAL_DRIVER", "textual.drivers.web_driver:WebDriver")
    assert NativeOutput.possible()
    monkeypatch.delenv("TEXTUAL_DRIVER")
    assert NativeOutput.possible() == (os.isatty(1) and os.isatty(2))
