"""console-tui: a fast, keyboard-first ROS log console for the terminal."""

__version__ = "0.1.0"
