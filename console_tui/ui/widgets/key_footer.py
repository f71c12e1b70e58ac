"""The footer: Textual's, drawn again only when the keys it shows change.

Textual's ``Footer`` takes down and mounts again all of its keys (about 30 widgets here)
each time the screen's bindings may have changed, and a change of focus signals that twice:
21-46 ms of CPU each on this project's machines, with a layout after it, for a footer that
mostly shows the same keys (the search line: once on opening it, twice on closing it).
``KeyFooter`` composes again only when what it would show differs from what it shows.
"""

from __future__ import annotations

from collections.abc import Hashable

from textual.widgets import Footer


class KeyFooter(Footer):
    """``Footer`` that skips a recompose that would show the same keys."""

    def __init__(self) -> None:
        super().__init__()
        self._shown: Hashable = None
        self.recomposed = 0  #: how many times the keys were mounted again (for tests)

    def _keys(self) -> Hashable:
        """What ``compose`` would show now: each shown binding, enabled, tooltip and key,
        and the palette's entry."""
        app = self.app
        active = self.screen.active_bindings
        shown = tuple(
            (binding, enabled, tooltip, app.get_key_display(binding))
            for (_, binding, enabled, tooltip) in active.values()
            if binding.show
        )
        palette = None
        if self.show_command_palette and app.ENABLE_COMMAND_PALETTE:
            entry = active.get(app.COMMAND_PALETTE_BINDING)
            palette = entry[1:] if entry is not None else None
        return self._bindings_ready, shown, palette

    async def recompose(self) -> None:
        if not self.is_attached:
            return
        keys = self._keys()
        if keys == self._shown:
            return
        self._shown = keys
        self.recomposed += 1
        await super().recompose()
