"""A run's ``rosout.log`` (ROS 1's format) with storms, as a post-mortem opens one.

Every 6 s: a storm of 50 repeats from ``/talker`` (its text names the cycle, so each burst
is a storm of its own), ten distinct INFO lines from ``/listener``, a WARN from
``/planner`` and, every fourth cycle from the second, an ERROR (``plan failed <cycle>``).
330 cycles make 20,213 lines; with storms collapsed, 12 rows a cycle (13 with an ERROR).
"""

from __future__ import annotations

from pathlib import Path

BASE_S = 1_795_000_000  # 11:06:40 UTC
CYCLES = 330
STORM = 50


def error_cycles(cycles: int = CYCLES) -> list[int]:
    return [cycle for cycle in range(cycles) if cycle % 4 == 1]


def write_storm_log(path: Path, cycles: int = CYCLES) -> int:
    """Write the log to ``path``; how many lines."""
    lines = []
    heard = 0
    for cycle in range(cycles):
        t = BASE_S + 6 * cycle
        for k in range(STORM):
            lines.append(
                f"{t + k * 0.01:.9f} INFO /talker [talker.py:20(main)] [topics: /rosout, /chatter] "
                f"queue full in burst {cycle}, dropping a message"
            )
        for k in range(10):
            heard += 1
            lines.append(f"{t + 1 + k * 0.1:.9f} INFO /listener [listener.py:9(cb)] [topics: /rosout] heard {heard}")
        lines.append(f"{t + 3:.9f} WARN /planner [planner.py:40(plan)] [topics: /rosout] slow plan {cycle}")
        if cycle % 4 == 1:
            lines.append(f"{t + 4:.9f} ERROR /planner [planner.py:50(plan)] [topics: /rosout] plan failed {cycle}")
    path.write_text("\n".join(lines) + "\n")
    return len(lines)


def rows_before(cycle: int) -> int:
    """Rows (storms collapsed, every level shown) before ``cycle``'s first."""
    return 12 * cycle + sum(1 for c in error_cycles(cycle))


def error_number(cycle: int) -> int:
    """The ``#`` (line number) of ``cycle``'s ERROR."""
    return 61 * cycle + sum(1 for c in error_cycles(cycle)) + 62


def write_node_logs(folder: Path, cycles: int = CYCLES, offset_s: float = 0.0008) -> int:
    """Beside ``rosout.log`` in ``folder``: ``/talker``'s and ``/listener``'s own console
    output (roslaunch's ``<node>-<N>-stdout.log``, rospy's format: times to the microsecond),
    each message printed ``offset_s`` after the stamp it published; how many lines."""
    talker, listener = [], []
    heard = 0
    for cycle in range(cycles):
        t = BASE_S + 6 * cycle + offset_s
        for k in range(STORM):
            talker.append(f"[INFO] [{t + k * 0.01:.6f}]: queue full in burst {cycle}, dropping a message")
        for k in range(10):
            heard += 1
            listener.append(f"[INFO] [{t + 1 + k * 0.1:.6f}]: heard {heard}")
    (folder / "talker-1-stdout.log").write_text("\n".join(talker) + "\n")
    (folder / "listener-2-stdout.log").write_text("\n".join(listener) + "\n")
    return len(talker) + len(listener)
