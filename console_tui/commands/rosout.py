"""``console-tui rosout``: the rosout node for ROS 2 (``/rosout_agg`` and ``rosout.log``).

Runs until Ctrl-C or SIGTERM, then flushes rosout.log and exits 0. What it does is in
``rosout_aggregator.py``; the file's format in ``console_tui.model.formats.rosout_log``.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import time
from collections.abc import Sequence
from pathlib import Path

from ..model.formats.rosout_log import ROS2_HEADER
from ..model.formats.rotating_file import RotatingFile
from ..model.inert_text import plural
from ..ros.log_dir import ros_log_dir
from ..ros.ros2.rclpy_loader import RosUnavailable
from ..ros.ros2.runtime import start_ros2
from ..system.signal_stop import SignalStop
from .arguments import DOCS_URL, EXIT_NO_ROS, command_parser, domain_id, parse_size, positive_int, size_text

EXIT_OK = 0
EXIT_ERROR = 1
EXIT_USAGE = 2

DEFAULT_MAX_SIZE = 100 << 20  # ROS 1 rosout's max_file_size
DEFAULT_KEEP = 10  # ROS 1 rosout's max_backup_index
LOG_NAME = "rosout.log"


def build_parser() -> argparse.ArgumentParser:
    from .rosout_aggregator import DEFAULT_DEPTH, DEFAULT_NODE_NAME, DEFAULT_REPORT_S

    parser = command_parser(
        "rosout",
        (
            "The rosout node for ROS 2. Takes every node's /rosout messages (with the console's QoS, "
            "so none is missed), republishes each on /rosout_agg (RELIABLE, TRANSIENT_LOCAL, a deep "
            "history: a console started later gets it at once) and appends it to rosout.log in a new "
            "directory under the ROS log directory ($ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log). "
            "It never reads /rosout_agg, so aggregators never feed each other. Runs until Ctrl-C or "
            "SIGTERM. The file's format is described in the documentation (link below)."
        ),
        f"""exit status:
  {EXIT_OK}  stopped by Ctrl-C or SIGTERM
  {EXIT_ERROR}  rosout.log cannot be created
  {EXIT_USAGE}  bad command line, or ROS 2 (rclpy) is not available (the same number in every command)

documentation: {DOCS_URL}headless/#the-rosout-node-console-tui-rosout""",
    )
    parser.add_argument(
        "--depth",
        type=positive_int,
        default=DEFAULT_DEPTH,
        metavar="N",
        help=f"messages kept for consoles that start later (default {DEFAULT_DEPTH:,}; Fast DDS hands "
        "20,000 to a new console within seconds, much more takes long)",
    )
    parser.add_argument(
        "--log-dir",
        metavar="DIR",
        help="write DIR/rosout.log (appending) instead of a new rosout-<date>-<pid> directory in the log directory",
    )
    parser.add_argument("--no-log", action="store_true", help="do not write rosout.log, only republish")
    parser.add_argument(
        "--max-size",
        type=parse_size,
        default=DEFAULT_MAX_SIZE,
        metavar="SIZE",
        help=f"rotate rosout.log when it would grow past SIZE (default {size_text(DEFAULT_MAX_SIZE)}; 10K, 1G)",
    )
    parser.add_argument(
        "--keep",
        type=int,
        default=DEFAULT_KEEP,
        metavar="N",
        help=f"rotated files kept: rosout.log.1 (newest) .. rosout.log.N (default {DEFAULT_KEEP})",
    )
    parser.add_argument(
        "--domain",
        metavar="N",
        type=domain_id,
        help="the ROS 2 domain to run on (default: $ROS_DOMAIN_ID's); one rosout node a domain",
    )
    parser.add_argument(
        "--name", default=DEFAULT_NODE_NAME, metavar="NAME", help=f"the node's name (default {DEFAULT_NODE_NAME})"
    )
    parser.add_argument(
        "--report-every",
        type=float,
        default=DEFAULT_REPORT_S,
        metavar="SECONDS",
        help=f"log the counts on the node's own /rosout this often (default {DEFAULT_REPORT_S:g}; 0: never)",
    )
    return parser


def run_directory(log_dir: Path, now: float | None = None, pid: int | None = None) -> Path:
    """A new directory for one run: ``<log dir>/rosout-YYYY-MM-DD-HH-MM-SS-<pid>``."""
    stamp = time.strftime("%Y-%m-%d-%H-%M-%S", time.localtime(time.time() if now is None else now))
    return log_dir / f"rosout-{stamp}-{os.getpid() if pid is None else pid}"


def main(argv: Sequence[str]) -> int:
    parser = build_parser()
    args = parser.parse_args(list(argv))
    if args.keep < 0:
        parser.error("--keep must be 0 or more")
    if args.max_size < 1024:
        parser.error("--max-size must be at least 1K")
    try:
        runtime = start_ros2(args.domain)
    except RosUnavailable as error:
        print(f"console-tui rosout: {error}", file=sys.stderr)
        return EXIT_NO_ROS
    log = None
    if not args.no_log:
        directory = Path(args.log_dir) if args.log_dir else run_directory(ros_log_dir())
        log = RotatingFile(directory / LOG_NAME, max_bytes=args.max_size, keep=args.keep, header=ROS2_HEADER)
        if log.error:
            print(f"console-tui rosout: cannot write rosout.log: {log.error}", file=sys.stderr)
            runtime.shutdown()
            return EXIT_ERROR
    from .rosout_aggregator import RosoutAggregator

    stop = SignalStop()
    previous = {sig: signal.signal(sig, stop.on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        aggregator = RosoutAggregator(
            runtime, depth=args.depth, log=log, node_name=args.name, report_s=args.report_every
        )
        where = f", writing {log.path}" if log is not None else ""
        print(f"console-tui rosout: /rosout -> /rosout_agg (history {args.depth:,}){where}", file=sys.stderr)
        aggregator.run(stop)
        counts = aggregator.counts()
        summary = (
            f"console-tui rosout: {plural(counts.received, 'message')} republished, {counts.written:,} written, "
            f"{counts.lost + counts.not_written:,} lost"
        )
        if counts.not_written and log is not None:
            summary += f" ({counts.not_written:,} not written to rosout.log: {log.error or 'write failed'})"
        print(summary, file=sys.stderr)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        runtime.shutdown()
    return EXIT_OK
