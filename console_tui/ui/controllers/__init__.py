"""The app's controllers: one plain object a concern (search, jumps, rules, files, ...).

Each is made by ``ConsoleScreen`` (``console_screen``) with the few things it works on passed in (the store, the view,
the table widget, the clock, a status callback, the ``Host`` it asks to notify, to show a
screen, to run work in the background); the app's actions and message handlers hand over to
them. No controller reads the app's or the screen's namespace.
"""
