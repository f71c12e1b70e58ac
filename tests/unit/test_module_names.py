"""One name per idea: no two modules of ``console_tui`` share a file name, except a ROS 1 and
a ROS 2 module of one job in a ``ros1/``/``ros2/`` pair (``sources/ros1/live_source.py`` and
``sources/ros2/live_source.py``)."""

from collections import defaultdict
from pathlib import Path

import console_tui

PACKAGE = Path(console_tui.__file__).parent


def _pair_key(path: Path) -> str:
    """The path with ``ros1``/``ros2`` folded into one, so the two halves of a pair meet."""
    return "/".join("ros*" if part in ("ros1", "ros2") else part for part in path.parts)


def test_no_two_modules_share_a_file_name():
    by_name: dict[str, set[str]] = defaultdict(set)
    for path in PACKAGE.rglob("*.py"):
        if path.name != "__init__.py":
            by_name[path.name].add(_pair_key(path.relative_to(PACKAGE)))
    shared = {name: sorted(places) for name, places in by_name.items() if len(places) > 1}
    assert shared == {}, f"module file names used twice: {shared}"
