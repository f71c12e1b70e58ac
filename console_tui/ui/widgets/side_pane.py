"""A pane beside the table: shown and hidden with a key, Escape gives the table its focus back."""

from __future__ import annotations

from textual.containers import Vertical
from textual.message import Message
from textual.widget import Widget

from ..focus import focus_now


class SidePane(Vertical):
    """Hidden until opened. Subclasses say what takes focus (``focus_target``) and may do
    work when opened or closed (``when_opened``, ``when_closed``)."""

    DEFAULT_CSS = """
    SidePane { display: none; }
    SidePane.-open { display: block; }
    """

    class Leave(Message):
        """Escape in the pane, or the pane closed with focus in it: the table takes focus."""

    @property
    def is_open(self) -> bool:
        return self.has_class("-open")

    @property
    def has_focus_within(self) -> bool:
        focused = self.screen.focused if self.is_mounted else None
        return focused is not None and self in focused.ancestors_with_self

    def focus_target(self) -> Widget:
        return self

    def when_opened(self) -> None:
        """Called as the pane opens."""

    def when_closed(self) -> None:
        """Called as the pane closes."""

    def open(self, focus: bool = True) -> None:
        if not self.is_open:
            self.add_class("-open")
            self.when_opened()
        if focus and not self.has_focus_within:
            focus_now(self.focus_target())

    def close(self) -> None:
        if self.is_open:
            had_focus = self.has_focus_within
            self.remove_class("-open")
            self.when_closed()
            if had_focus:
                self.post_message(self.Leave())

    def toggle(self) -> None:
        if self.is_open:
            self.close()
        else:
            self.open()

    def action_leave(self) -> None:
        self.post_message(self.Leave())


class RightPane(SidePane):
    """A side pane on the table's right (the node panel, the logger levels pane): a title
    (class ``pane-title``) on top, its keys (class ``pane-keys``) at the foot."""

    DEFAULT_CSS = """
    RightPane {
        height: 100%;
        background: $surface;
        border-left: vkey $border-blurred;
        padding: 0 0 0 1;
        &:focus-within { border-left: vkey $border; }
        & > .pane-title { text-style: bold; color: $text-primary; height: 1; }
        & > Input { margin: 0; }
        & > .pane-keys { height: auto; color: $text-muted; }
    }
    """
