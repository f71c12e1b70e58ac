"""Subcommands of ``console-tui`` that run without the terminal UI."""
