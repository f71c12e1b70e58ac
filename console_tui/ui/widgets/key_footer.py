"""The footer: the keys the focused widget and the screen answer, drawn as one line.

Textual's ``Footer`` is a container of one widget a key (about 30 here): each time the
screen's bindings may have changed (twice on every change of focus) it takes them down and
mounts them again, with a layout of the screen after it: the longest pauses of a search
(docs/decisions/0018-own-widgets.md). ``KeyFooter`` draws the same line (each key and what
it does, the palette's key on the right) as one strip, again only when what it shows
changes, and never asks for a layout. A click on a key presses it, as in Textual's.
"""

from __future__ import annotations

from collections.abc import Hashable

from rich.segment import Segment
from rich.style import Style
from textual.binding import Binding
from textual.strip import Strip
from textual.widget import Widget

#: A shown key: the key pressed on a click, the key as it reads, what it does, enabled.
FooterEntry = tuple[str, str, str, bool]


class KeyFooter(Widget, can_focus=False):
    """One line of keys: ``end Follow tail  ⏎ Details ...  ▏^p palette``.

    | Class | Description |
    | :- | :- |
    | `key-footer--key` | A key. |
    | `key-footer--description` | What the key does. |
    | `key-footer--disabled` | A key that does nothing now. |
    | `key-footer--separator` | The line before the palette's key. |
    """

    DEFAULT_CSS = """
    KeyFooter {
        dock: bottom;
        height: 1;
        color: $footer-foreground;
        background: $footer-background;
    }
    KeyFooter > .key-footer--key {
        color: $footer-key-foreground;
        background: $footer-key-background;
        text-style: bold;
    }
    KeyFooter > .key-footer--description {
        color: $footer-description-foreground;
        background: $footer-description-background;
    }
    KeyFooter > .key-footer--disabled { text-style: dim; }
    KeyFooter > .key-footer--separator { color: $foreground 20%; }
    """

    COMPONENT_CLASSES = {
        "key-footer--key",
        "key-footer--description",
        "key-footer--disabled",
        "key-footer--separator",
    }

    ALLOW_SELECT = False

    def __init__(self) -> None:
        super().__init__()
        self.entries: tuple[FooterEntry, ...] = ()
        self.palette: FooterEntry | None = None
        self.changes = 0  #: how many times the keys shown changed (for tests)
        self._line: tuple[Hashable, Strip] | None = None

    def on_mount(self) -> None:
        self.screen.bindings_updated_signal.subscribe(self, self._bindings_changed)
        self._bindings_changed(self.screen)

    def on_unmount(self) -> None:
        self.screen.bindings_updated_signal.unsubscribe(self)

    def _bindings_changed(self, screen: object) -> None:
        if not self.is_attached or screen is not self.screen:
            return
        app = self.app
        active = self.screen.active_bindings
        entries: list[FooterEntry] = []
        actions: set[str] = set()
        for _, binding, enabled, _ in active.values():
            if binding.show and binding.action not in actions:  # one key an action, as Textual's
                actions.add(binding.action)
                entries.append(self._entry(binding, enabled))
        palette = None
        if app.ENABLE_COMMAND_PALETTE and app.COMMAND_PALETTE_BINDING in active:
            _, binding, enabled, _ = active[app.COMMAND_PALETTE_BINDING]
            palette = self._entry(binding, enabled)
        if (tuple(entries), palette) != (self.entries, self.palette):
            self.entries, self.palette = tuple(entries), palette
            self.changes += 1
            self.refresh()

    def _entry(self, binding: Binding, enabled: bool) -> FooterEntry:
        return (binding.key.split(",")[0].strip(), self.app.get_key_display(binding), binding.description, enabled)

    def notify_style_update(self) -> None:
        super().notify_style_update()
        self._line = None

    def render_line(self, y: int) -> Strip:
        width = self.size.width
        key = (width, self.entries, self.palette, self.app.theme)
        if self._line is None or self._line[0] != key:
            self._line = (key, self._draw(width))
        return self._line[1]

    def _draw(self, width: int) -> Strip:
        style = self.rich_style
        look = {
            name: style + self.get_component_rich_style(f"key-footer--{name}", partial=True)
            for name in ("key", "description", "disabled", "separator")
        }
        palette: list[Segment] = []
        if self.palette is not None:
            palette = [Segment("▏", look["separator"]), *self._key_segments(self.palette, look, style, pad=False)]
        room = width - sum(len(segment.text) for segment in palette)
        keys: list[Segment] = []
        used = 0
        for entry in self.entries:  # whole keys only: never a key without what it does
            segments = self._key_segments(entry, look, style)
            needed = sum(len(segment.text) for segment in segments)
            if used + needed > room:
                break
            keys += segments
            used += needed
        if used < room:
            keys.append(Segment(" " * (room - used), style))
        return Strip([*keys, *palette]).crop(0, width)

    @staticmethod
    def _key_segments(entry: FooterEntry, look: dict[str, Style], base: Style, pad: bool = True) -> list[Segment]:
        """`` key `` and ``description `` with the click that presses the key."""
        key, shown, description, enabled = entry
        click = Style.from_meta({"@click": f"app.simulate_key({key!r})" if enabled else "app.bell"})
        dim = look["disabled"] if not enabled else Style()
        key_text = f" {shown} " if pad else f"{shown} "
        return [
            Segment(key_text, look["key"] + dim + click),
            Segment(f"{description} ", look["description"] + dim + click),
        ]
