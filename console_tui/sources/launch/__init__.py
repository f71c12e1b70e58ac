"""Running a launch and reading what it prints (``console-tui run -- COMMAND``): see ``launch_source``."""
