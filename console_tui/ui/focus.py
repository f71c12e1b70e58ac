"""Keys typed ahead go where the person meant them.

Textual passes each key to the focused widget's own message queue, and runs the key's binding
only when the key has come back up to the app; meanwhile the app has passed the keys behind it
to the same widget. And ``Widget.focus`` queues the focus change behind the keys already
waiting. So keys typed right after a key that moves the focus would go to the widget focused
before: typing ``/error`` in the first second after launch, while the app is still busy
starting, would open the query line and send ``e``, ``r``, ``r``, ``o``, ``r`` to the table
(``r`` toggling the rules pane), leaving the query line empty.

A key that opens a dialog has the same trouble: the dialog's widgets mount, and its text box
takes the focus, a few turns of the event loop later, and the keys typed behind it meanwhile
would be lost (``o`` and a path typed at once would give an empty box).

``run_bindings_now`` runs a key's binding as soon as the app takes the key, ``focus_now``
moves the focus at once, and ``KeyGate`` holds the keys that arrive while the screen on top is
not ready for them yet, then lets them through in order.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from textual import events
from textual.app import App
from textual.dom import NoScreen
from textual.widget import Widget


async def run_bindings_now(app: App, event: events.Key) -> bool:
    """Run the binding of ``event``'s key along the focus chain now, as Textual would once the
    key had come back up to the app; False when no binding takes the key (then pass the key on
    as usual). Only for a focused widget that takes keys through bindings alone (not a text
    input). Uses Textual's own ``App._check_bindings`` (Textual is pinned for this reason too)."""
    if not app.app_focus:
        app.app_focus = True
    return await app._check_bindings(event.key, priority=True) or await app._check_bindings(event.key)


def focus_now(widget: Widget) -> None:
    """Give ``widget`` the focus before the next key is handled (as ``Widget.focus`` later,
    when it cannot take it yet)."""
    try:
        screen = widget.screen
        screen.set_focus(widget)
        if screen.focused is widget:
            return
    except NoScreen:  # not on a screen yet
        pass
    widget.focus()


#: Keys wait for a screen to take the focus at most this long, then go on as they are.
HOLD_AT_MOST_S = 1.0
_POLL_S = 0.01


def screen_ready(app: App) -> bool:
    """Whether the screen on top can take keys: ``screen_mounted``, and focused if anything in
    it can be."""
    screen = app.screen
    return screen_mounted(app) and (screen.focused is not None or not screen.focus_chain)


def screen_mounted(app: App) -> bool:
    """Whether the screen on top is mounted, with what it mounts after its first frame (a
    ``ready_for_keys`` of its own, which keys wait for however long it takes)."""
    screen = app.screen
    return screen.is_mounted and getattr(screen, "ready_for_keys", True)


class KeyGate:
    """Holds keys while the screen on top is not ready for them (a dialog just opened, the app
    still starting), and lets them through in the order they came once it is."""

    def __init__(self, app: App, clock: Callable[[], float] = time.monotonic) -> None:
        self.app = app
        self.clock = clock
        self.held: list[events.Key] = []
        self._since = 0.0

    def hold(self, event: events.Key) -> bool:
        """True when ``event`` is held (the caller then leaves it), False to handle it now."""
        if not self.held and screen_ready(self.app):
            return False
        self.held.append(events.Key(event.key, event.character))
        if len(self.held) == 1:
            self._since = self.clock()
            self.app.set_timer(_POLL_S, self._release)
        return True

    def _release(self) -> None:
        if not screen_mounted(self.app) or (not screen_ready(self.app) and self.clock() - self._since < HOLD_AT_MOST_S):
            self.app.set_timer(_POLL_S, self._release)
            return
        keys, self.held = self.held, []
        for key in keys:
            self.app.post_message(key)
