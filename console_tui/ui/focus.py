"""Keys typed ahead go where the person meant them.

Textual passes each key to the focused widget's own message queue, and runs the key's binding
only when the key has come back up to the app; meanwhile the app has passed the keys behind it
to the same widget. And ``Widget.focus`` queues the focus change behind the keys already
waiting. So keys typed right after a key that moves the focus went to the widget focused
before: typing ``/error`` in the first second after launch, while the app was still busy
starting, opened the query line and sent ``e``, ``r``, ``r``, ``o``, ``r`` to the table (``r``
toggling the rules pane), and the query line stayed empty.

``run_bindings_now`` runs a key's binding as soon as the app takes the key, and ``focus_now``
moves the focus at once; the key after it then finds the focus where the binding put it.
"""

from __future__ import annotations

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
