"""Work-arounds for Textual bugs, until they are fixed upstream (each with a test).

Each patches a private part of Textual, so each checks at import that what it replaces is
what it was written against (the function's qualified name and a hash of its source, as in
the Textual release tested); one that does not match is not installed, and
``console-tui --version`` says which (``fixes_text``). The Textual releases pyproject.toml
admits are the ones tested; moving that range means checking each fix again (its test
fails on a new hash) and updating ``source_hash`` below.

What each fix is for, what Textual 8.2.8 does wrong, a reproduction and the upstream issue
ready to file: docs/textual-fixes.md (a section per fix, titled by what it patches).
"""

from __future__ import annotations

import hashlib
import inspect
import linecache
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import textual
from rich.style import Style
from textual.binding import BindingsMap, Keymap, KeymapApplyResult
from textual.drivers._writer_thread import WriterThread
from textual.drivers.linux_driver import LinuxDriver
from textual.reactive import Reactive
from textual.screen import Screen
from textual.strip import Strip
from textual.widgets import OptionList

_original_move_page = OptionList._move_page
_original_apply_keymap = BindingsMap.apply_keymap
_original_sigcont = LinuxDriver._sigcont_application
_original_divide = Strip.divide


def _move_page(self: OptionList, direction: int) -> None:
    try:
        _original_move_page(self, direction)  # type: ignore[arg-type]
    except (KeyError, IndexError):  # no lines laid out yet
        if direction < 0:
            self.action_first()
        else:
            self.action_last()


def _apply_keymap(self: BindingsMap, keymap: Keymap) -> KeymapApplyResult:
    places: dict[str, int] = {}
    by_id: dict[str, int] = {}
    for place, (key, bindings) in enumerate(self.key_to_bindings.items()):
        places[key] = place
        for binding in bindings:
            if binding.id is not None:
                by_id.setdefault(binding.id, place)
    result = _original_apply_keymap(self, keymap)
    ending = len(places)

    def place_of(item: tuple[str, list]) -> int:
        key, bindings = item
        if key in places:
            return places[key]
        return min((by_id[b.id] for b in bindings if b.id in by_id), default=ending)

    ordered = sorted(self.key_to_bindings.items(), key=place_of)
    self.key_to_bindings.clear()
    self.key_to_bindings.update(ordered)
    return result


def _write_until_stopped(self: WriterThread) -> None:
    """``WriterThread.run`` that survives the terminal going away: after a failed write it
    drops the rest, but keeps taking from the queue until ``stop()``, so no writer blocks."""
    get = self._queue.get
    writing = True
    while (text := get()) is not None:
        if not writing:
            continue
        try:
            self._file.write(text)
            if self._queue.qsize() == 0:
                self._file.flush()
        except (OSError, ValueError):  # EIO: the terminal is gone; ValueError: the file closed
            writing = False
    if writing:
        try:
            self._file.flush()
        except (OSError, ValueError):
            pass


def _sigcont_application(self: LinuxDriver, *args: object) -> None:
    writer = self._writer_thread
    if writer is None or not writer.is_alive():  # suspended (Ctrl+Z): come back
        _original_sigcont(self, *args)


def _crop_extend(self: Strip, start: int, end: int, style: Style | None) -> Strip:
    cache_key = (start, end, style)
    cached = self._crop_extend_cache.get(cache_key)
    if cached is not None:
        return cached
    strip = self.extend_cell_length(end, style).crop(start, end)
    if strip is not self:  # the strip itself: caching it would make a cycle
        self._crop_extend_cache[cache_key] = strip
    return strip


def _divide(self: Strip, cuts: Iterable[int]) -> Sequence[Strip]:
    whole = self.cell_length
    cuts = [cut for cut in cuts if cut <= whole]
    if cuts == [whole]:  # the strip itself: caching ``[self]`` would make a cycle
        return [self]
    return _original_divide(self, cuts)


def _set_attribute(owner: type, name: str, value: object) -> Callable[[], None]:
    def install() -> None:
        setattr(owner, name, value)

    return install


def _no_focus_repaint() -> None:
    Screen.focused._repaint = False  # a change of focus: no repaint of the whole screen


@dataclass(frozen=True)
class Fix:
    """One work-around: what it relies on, how it is installed, where it stands upstream."""

    #: What it patches, as ``--version`` names it.
    name: str
    #: The Textual function the fix replaces or relies on, and its ``__qualname__``.
    target: Callable[..., object]
    qualname: str
    #: The first 16 hex digits of the SHA-256 of ``source_of(target)`` in the Textual
    #: release tested.
    source_hash: str
    install: Callable[[], None]
    #: The upstream issue or pull request, or "not yet reported — <the bug in one line>" (the
    #: issue's text, ready to file: docs/textual-fixes.md).
    upstream: str


FIXES: tuple[Fix, ...] = (
    Fix(
        "OptionList._move_page",
        _original_move_page,
        "OptionList._move_page",
        "85f7f33005763486",
        _set_attribute(OptionList, "_move_page", _move_page),
        "not yet reported — OptionList PageUp/PageDown raises KeyError: 0 on a list with a "
        "highlighted option that has no size yet (the command palette while results arrive)",
    ),
    Fix(
        "BindingsMap.apply_keymap",
        _original_apply_keymap,
        "BindingsMap.apply_keymap",
        "9b73d1d65f808636",
        _set_attribute(BindingsMap, "apply_keymap", _apply_keymap),
        "not yet reported — apply_keymap moves every rebound binding to the end of the map, "
        "so the Footer shows it last (cut off)",
    ),
    Fix(
        "WriterThread.run",
        WriterThread.run,
        "WriterThread.run",
        "314021aab4f52726",
        _set_attribute(WriterThread, "run", _write_until_stopped),
        "not yet reported — after the terminal goes away (SIGHUP, EIO) the output thread dies "
        "and App.exit blocks for ever on its full queue",
    ),
    Fix(
        "LinuxDriver._sigcont_application",
        _original_sigcont,
        "LinuxDriver._sigcont_application",
        "1d7463a74df118a4",
        _set_attribute(LinuxDriver, "_sigcont_application", _sigcont_application),
        "not yet reported — SIGCONT resumes application mode in a driver that was never "
        "suspended (a second output thread, terminal modes written again)",
    ),
    Fix(
        "Strip.crop_extend",
        Strip.crop_extend,
        "Strip.crop_extend",
        "5e83b1f823fcb361",
        _set_attribute(Strip, "crop_extend", _crop_extend),
        "not yet reported — Strip.crop_extend caches a strip in itself when the crop is the "
        "whole strip: a reference cycle per strip drawn, freed only by a full collection",
    ),
    Fix(
        "Strip.divide",
        _original_divide,
        "Strip.divide",
        "f6764f25c39e144b",
        _set_attribute(Strip, "divide", _divide),
        "not yet reported — Strip.divide with one cut at the end caches [self] in the strip: "
        "a reference cycle per strip drawn",
    ),
    Fix(
        "Screen.focused repaint",
        Reactive._set,
        "Reactive._set",
        "8fa5e86bc412a062",
        _no_focus_repaint,
        "not yet reported — Screen.focused is a repainting reactive, so every change of focus "
        "repaints the whole screen though the widgets concerned repaint themselves",
    ),
)


def source_of(target: Callable[..., object]) -> str:
    """The source lines of a function, from its first line to the last its code reaches (its
    code object's positions): the text ``inspect.getsource`` gives, without tokenizing the
    file, which cost the first frame about 4 ms for these seven. Python 3.10 has no positions:
    ``inspect.getsource`` there."""
    code = inspect.unwrap(target).__code__
    positions = getattr(code, "co_positions", None)
    if positions is None:  # pragma: no cover - Python 3.10
        return inspect.getsource(target)
    lines = linecache.getlines(code.co_filename)
    ends = [end for _, end, _, _ in positions() if end is not None]
    if not lines or not ends:
        raise OSError(f"no source for {code.co_filename}")
    return "".join(lines[code.co_firstlineno - 1 : max(ends)])


def check(fix: Fix) -> str | None:
    """Why ``fix`` must not be installed on this Textual (its target is not what it was
    written against), or None."""
    qualname = getattr(fix.target, "__qualname__", None)
    if qualname != fix.qualname:
        return f"{fix.qualname} is now {qualname}"
    try:
        source = source_of(fix.target)
    except (OSError, TypeError, AttributeError):
        return f"the source of {fix.qualname} cannot be read"
    if hashlib.sha256(source.encode()).hexdigest()[:16] != fix.source_hash:
        return f"{fix.qualname} changed in Textual {textual.__version__}"
    return None


#: Checked once, at import, before anything is patched.
_CHECKED: dict[Fix, str | None] = {fix: check(fix) for fix in FIXES}


def install(fixes: Iterable[Fix]) -> dict[str, str]:
    """Install each fix whose target checks (idempotent); the others' names and reasons."""
    skipped = {}
    for fix in fixes:
        reason = _CHECKED[fix] if fix in _CHECKED else check(fix)
        if reason is None:
            fix.install()
        else:
            skipped[fix.name] = reason
    return skipped


def apply() -> dict[str, str]:
    """Install the work-arounds (idempotent); the skipped ones' names and reasons."""
    return install(FIXES)


def fixes_text() -> str:
    """A line for ``--version``: the Textual release, and which fixes are skipped and why."""
    skipped = {fix.name: reason for fix, reason in _CHECKED.items() if reason is not None}
    text = f"Textual {textual.__version__}: {len(FIXES) - len(skipped)} of {len(FIXES)} work-arounds in use"
    if skipped:
        text += "; skipped, as what they patch is not what they were written for: " + "; ".join(
            f"{name} ({reason})" for name, reason in skipped.items()
        )
    return text
