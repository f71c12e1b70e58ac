"""The console's controllers: one plain object a concern (intake, table, rules, files, panes,
search, jumps, toggles, overview).

``ConsoleScreen`` (``console_screen``) makes each with the ``ConsoleContext`` (``context``: the
store, the view, the table, the marks, the clock, the ``Host`` it asks to notify, to show a
screen, to run work in the background; ``changed()`` for the status line; the announcements)
and the few things only it drives. Each declares its commands (``COMMANDS``: the keys, the
palette; ``command_table``) and subscribes to the announcements it follows (``announcements``);
the screen's message handlers hand the widgets' messages over. No controller reads the app's
or the screen's namespace.
"""
