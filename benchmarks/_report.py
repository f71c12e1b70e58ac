"""What every benchmark prints: the machine it ran on, and Markdown tables."""

from __future__ import annotations

import os
import platform
import sys
import time
from collections.abc import Callable, Sequence
from typing import TypeVar

T = TypeVar("T")


def cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as info:
            for line in info:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def load_average() -> str:
    try:
        return " ".join(f"{value:.2f}" for value in os.getloadavg())
    except OSError:
        return "n/a"


def machine_line() -> str:
    """One line naming the CPU, the cores, the OS, Python and the load right now."""
    return (
        f"Machine: {cpu_model()}, {os.cpu_count()} cores, {platform.system()} {platform.release()}, "
        f"Python {sys.version.split()[0]}; load average {load_average()}"
    )


def ros_line(env: dict[str, str]) -> str:
    """Which rclpy and RMW a ROS benchmark ran with: ``rclpy 9.1.2, RMW rmw_fastrtps_cpp (default)``."""
    from importlib.metadata import version

    return f"rclpy {version('rclpy')}, RMW {env.get('RMW_IMPLEMENTATION', 'rmw_fastrtps_cpp (default)')}"


def ros_header(title: str, env: dict[str, str], details: str) -> list[str]:
    """The lines a ROS benchmark's report starts with: its title, the machine, rclpy and RMW, and ``details``."""
    return [f"## {title}", "", machine_line(), f"{ros_line(env)}; {details}"]


def ros_environment(domain: int, **more: str) -> dict[str, str]:
    """The environment of a ROS benchmark's processes: this one's, on ROS_DOMAIN_ID ``domain``,
    discovery on this machine only (ROS_AUTOMATIC_DISCOVERY_RANGE; the older ROS_LOCALHOST_ONLY dropped)."""
    env = {**os.environ, "ROS_DOMAIN_ID": str(domain), "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", **more}
    env.pop("ROS_LOCALHOST_ONLY", None)
    return env


def run_under_header(header: list[str], run: Callable[[], T]) -> T:
    """``run()``, its ``header`` on stderr before (to see what runs) and on stdout after, then
    the load average at the end and how long it took; returns what ``run`` returned."""
    print("\n".join(header), file=sys.stderr, flush=True)
    started = time.monotonic()
    result = run()
    print("\n".join(header))
    print(f"Load average at the end: {os.getloadavg()[0]:.2f} (run took {time.monotonic() - started:.0f} s)")
    print()
    return result


def table(headers: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A Markdown table; numbers right-aligned."""
    cells = [[str(cell) for cell in row] for row in rows]
    widths = [max([len(header), *(len(row[i]) for row in cells)]) for i, header in enumerate(headers)]
    numeric = [all(_is_number(row[i]) for row in cells) and bool(cells) for i in range(len(headers))]

    def line(values: Sequence[str]) -> str:
        parts = [v.rjust(w) if num else v.ljust(w) for v, w, num in zip(values, widths, numeric, strict=False)]
        return "| " + " | ".join(parts) + " |"

    rule = (
        "|"
        + "|".join(("-" * (w + 1) + ":") if num else ("-" * (w + 2)) for w, num in zip(widths, numeric, strict=False))
        + "|"
    )
    return "\n".join([line(headers), rule, *(line(row) for row in cells)])


def _is_number(text: str) -> bool:
    return text.replace(",", "").replace(".", "", 1).replace("-", "", 1).replace("%", "").replace("x", "").isdigit()


def verdict(met: bool, shortfall: str) -> str:
    """``met``, or ``MISSED`` and by how much."""
    return "met" if met else f"MISSED ({shortfall})"
