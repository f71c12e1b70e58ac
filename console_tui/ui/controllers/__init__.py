"""The console's controllers: one plain object a concern (intake, table, rules, files, panes,
search, jumps, toggles, overview).

``ConsoleScreen`` (``console_screen``) makes each with the few things it works on passed in
(the store, the view, the table widget, other widgets, the controllers it hands on to, the
clock, a status callback, and the ``Host`` it asks to notify, to show a screen, to run work in
the background); the app's actions and the screen's message handlers hand over to them. No
controller reads the app's or the screen's namespace.
"""
