"""``console-tui ship URL``: a robot's log stream sent on to the log warehouse, nothing lost.

It reads the stream as ``tail`` does (the same live source and options) and sends every
record on as an OpenTelemetry log record: to a collector (``http(s)://``, OTLP over HTTP,
protobuf and gzip), or straight into the table ``otel_logs`` (``clickhouse(s)://``,
``chdb://``). Records go to a disk spool first and leave it only when the warehouse has taken
them (``warehouse.shipper``), so a warehouse away for an hour, a reboot or ``kill -9`` lose
nothing that reached the spool; the next start sends the rest. What it is doing goes to
standard error, a line at a time (and to ``--status FILE``, the latest line).
"""

from __future__ import annotations

import argparse
import hashlib
import signal
import socket
import sys
import time
from collections.abc import Mapping, Sequence

from ..model.atomic_file import atomic_output
from ..model.inert_text import one_line, plural
from ..model.rules.rulesfile import state_dir
from ..model.store.intake_queue import IntakeQueue
from ..ros.fleet import FleetError, check_robot_name, robot_name_for
from ..sources.live import LiveIntake, RosUnavailable, open_stream
from ..system.signal_stop import SignalStop
from ..warehouse.address import SHIPPABLE_SCHEMES, AddressError, parse_address
from ..warehouse.otlp_http import environment_headers
from ..warehouse.shipper import BATCH_RECORDS, Shipper, ShipState
from ..warehouse.spool import Spool, SpoolError
from ..warehouse.targets import open_target
from .arguments import (
    EXIT_NO_ROS,
    add_fleet_arguments,
    add_ros_version_arguments,
    check_fleet_arguments,
    command_parser,
    parse_size,
    positive_int,
    size_text,
)
from .live_reports import LiveReports

EXIT_OK = 0
EXIT_SPOOL = 1
EXIT_USAGE = 2
DEFAULT_SPOOL_SIZE = "256M"
#: How often the status line is written when something changed.
STATUS_EVERY_S = 10.0
#: How long stopping waits for the batch being sent.
STOP_TIMEOUT_S = 5.0

EPILOG = f"""URL:
  http://collector:4318      OTLP over HTTP (/v1/logs added when the URL has no path)
  clickhouse://host:8123/db  the table otel_logs (?table=NAME for another), made when missing
  clickhouses://host/db      the same over TLS
  chdb:///var/lib/logs       chDB: ClickHouse's engine on a local directory (one process at a time)

exit status:
  {EXIT_OK}  stopped by Ctrl-C or SIGTERM (what was not sent stays in the spool for the next start)
  {EXIT_SPOOL}  the spool cannot be used (another ship uses it, or it cannot be written)
  {EXIT_USAGE}  bad command line, or ROS is not available (the same number in every command)"""


def build_parser() -> argparse.ArgumentParser:
    parser = command_parser(
        "ship",
        "Send a robot's log stream (as 'console-tui tail' reads it) to the log warehouse: an "
        "OpenTelemetry collector or ClickHouse's table otel_logs. Every record goes to a disk "
        "spool first and is deleted only once the warehouse has taken it: an outage, a reboot or "
        "kill -9 lose nothing that reached the spool. Runs until Ctrl-C or SIGTERM.",
        EPILOG,
    )
    parser.add_argument("url", metavar="URL", help="where to send: http(s)://, clickhouse(s)://, chdb://")
    parser.add_argument(
        "--robot",
        metavar="NAME",
        help="the robot's name (service.namespace; default: this host's name); a fleet's robots keep their own",
    )
    parser.add_argument("--topic", metavar="NAME", help="the log topic (default /rosout_agg if published)")
    add_ros_version_arguments(parser)
    add_fleet_arguments(parser)
    parser.add_argument(
        "--header",
        metavar="K=V",
        action="append",
        default=[],
        help="an HTTP header for OTLP (an API key: --header Authorization='Bearer ...'); "
        "OTEL_EXPORTER_OTLP_HEADERS is read too",
    )
    parser.add_argument(
        "--spool",
        metavar="DIR",
        help="the spool directory (default: in $XDG_STATE_HOME/console-tui/spool, one for each URL)",
    )
    parser.add_argument(
        "--spool-size",
        metavar="SIZE",
        type=_size,
        default=parse_size(DEFAULT_SPOOL_SIZE),
        help=f"the spool's bound (default {DEFAULT_SPOOL_SIZE}); when full, the oldest batches go, counted as lost",
    )
    parser.add_argument(
        "--batch", metavar="N", type=positive_int, default=BATCH_RECORDS, help="records a batch at most"
    )
    parser.add_argument("--status", metavar="FILE", help="keep the latest status line in FILE too")
    parser.add_argument(
        "--status-every",
        metavar="S",
        type=float,
        default=STATUS_EVERY_S,
        help=f"seconds between status lines while something changes (default {STATUS_EVERY_S:g})",
    )
    return parser


def _size(text: str) -> int:
    size = parse_size(text)
    if size < 4096:
        raise argparse.ArgumentTypeError("a spool of less than 4K holds no batch")
    return size


def host_name() -> str:
    return socket.gethostname() or "localhost"


def default_robot() -> str:
    """This host's name as a robot's name (characters a name cannot hold become ``_``)."""
    name = host_name()
    try:
        return check_robot_name(name)
    except FleetError:
        return robot_name_for(name)


def default_spool(url_text: str) -> str:
    """The spool of a URL, by default: ``$XDG_STATE_HOME/console-tui/spool/<host>-<hash>``."""
    digest = hashlib.sha256(url_text.encode()).hexdigest()[:12]
    return str(state_dir() / "spool" / digest)


def status_line(state: ShipState, sources: str = "", *, intake_lost: int = 0) -> str:
    """``sent 1,200, spooled 0 (0), lost 0`` and what it waits for; ``intake_lost``: what the
    live sources lost before the spool (in the middleware, unreadable)."""
    spool = state.spool
    text = (
        f"sent {state.sent:,}, spooled {spool.records:,} ({_bytes(spool.size)} in "
        f"{plural(spool.batches, 'batch', 'batches')}), lost {state.lost + intake_lost:,}"
    )
    reasons = [f"{intake_lost:,} before the spool, by the live source"] if intake_lost else []
    if spool.dropped_records:
        reasons.append(f"{spool.dropped_records:,} dropped from the full spool")
    if state.refused:
        reasons.append(f"{state.refused:,} refused by the warehouse")
    if reasons:
        text += f" ({', '.join(reasons)})"
    if state.problem:
        text += f"; retrying in {state.retry_in:.0f} s: {one_line(state.problem, 200)}"
    if sources:
        text += f"; {sources}"
    return text


def _bytes(size: int) -> str:
    return f"{size} bytes" if size < 1024 else f"{size_text(size)}B"


def main(argv: Sequence[str]) -> int:
    parser = build_parser()
    args = parser.parse_args(list(argv))
    check_fleet_arguments(parser, args)
    if not args.url.lower().startswith(SHIPPABLE_SCHEMES):
        parser.error(f"URL: {args.url!r} is not http(s)://, clickhouse(s):// or chdb://")
    try:
        address = parse_address(args.url)
    except AddressError as error:
        parser.error(f"URL: {error}")
    robot = default_robot()
    if args.robot:
        try:
            robot = check_robot_name(args.robot)
        except FleetError as error:
            parser.error(f"--robot: {error}")
    headers = request_headers(parser, args.header)
    try:
        spool = Spool(args.spool or default_spool(address.text), args.spool_size)
    except SpoolError as error:
        _say(str(error))
        return EXIT_SPOOL
    queue = IntakeQueue()
    try:
        lives = open_stream(queue, args.robots, topic=args.topic, ros=args.ros)
    except RosUnavailable as error:
        spool.close()
        print(f"console-tui ship: {error}", file=sys.stderr)
        return EXIT_NO_ROS
    shipper = Shipper(
        queue, spool, open_target(address, headers), host=host_name(), robot=robot, batch_records=args.batch
    )
    stop = SignalStop()
    previous = {sig: signal.signal(sig, stop.on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        _say(f"shipping {'the fleet' if args.robots else robot}'s log to {address.text}, spool {spool.directory}")
        shipper.start()
        for live in lives:
            live.source.start()
        _run(shipper, lives, stop, args)
    finally:
        lost = intake_lost(lives)
        for live in lives:
            live.close()
        shipper.stop(STOP_TIMEOUT_S)
        _report(shipper, args.status, final=True, lost=lost)
        spool.close()
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    return EXIT_OK


def request_headers(
    parser: argparse.ArgumentParser, given: Sequence[str], environ: Mapping[str, str] | None = None
) -> dict[str, str]:
    """The HTTP headers sent to an OTLP collector: ``OTEL_EXPORTER_OTLP_HEADERS`` (and
    ``..._LOGS_HEADERS``), then each ``--header K=V`` (the command line wins); a ``--header``
    without ``=`` or a name exits 2 saying so."""
    headers = environment_headers(environ)
    for item in given:
        key, equals, value = item.partition("=")
        if not equals or not key.strip():
            parser.error(f"--header: expected K=V, got {item!r}")
        headers[key.strip()] = value
    return headers


def _run(shipper: Shipper, lives: Sequence[LiveIntake], stop: SignalStop, args: argparse.Namespace) -> None:
    reports = LiveReports(lives, _say)
    last_line = ""
    last_kind: tuple[bool, bool] = (False, False)
    last_at = 0.0
    while not stop.wait(0.25):
        reports.tell()
        state = shipper.state()
        lost = intake_lost(lives)
        kind = (bool(state.problem), bool(state.lost + lost))
        line = status_line(
            state, "; ".join(filter(None, [shipper.spool_problem, sources_text(lives)])), intake_lost=lost
        )
        now = time.monotonic()
        changed = _counts(line) != _counts(last_line)
        if kind != last_kind or (changed and now - last_at >= args.status_every):
            _report(shipper, args.status, line=line)
            last_line, last_kind, last_at = line, kind, now


def intake_lost(lives: Sequence[LiveIntake]) -> int:
    """What the live sources lost before anything reached the spool (their queue shared: once)."""
    statuses = [live.source.status for live in lives]
    if not statuses:
        return 0
    return int(sum(s.lost - s.lost_queue for s in statuses) + max(s.lost_queue for s in statuses))


def sources_text(lives: Sequence[LiveIntake]) -> str:
    """What the live sources read: ``reading /rosout (2 publishers)``, a fleet's robots each."""
    parts = []
    for live in lives:
        status = live.source.status
        robot = f"{status.robot} " if status.robot else ""
        topic = status.topic or "the log topic"
        parts.append(f"{robot}reading {topic} ({plural(status.publishers, 'publisher')})")
    return ", ".join(parts)


def _counts(line: str) -> str:
    """A status line without its countdown (a line is written again when its numbers change)."""
    return line.split("; retrying in", 1)[0]


def _report(shipper: Shipper, status_file: str | None, *, line: str = "", final: bool = False, lost: int = 0) -> None:
    text = line or status_line(shipper.state(), shipper.spool_problem, intake_lost=lost)
    if final:
        text = f"stopped: {text}"
    _say(text)
    if status_file:
        try:
            with atomic_output(status_file) as stream:
                stream.write(f"{time.strftime('%Y-%m-%dT%H:%M:%S')} {text}\n".encode())
        except OSError as error:
            _say(f"--status: cannot write {status_file}: {error.strerror or error}")


def _say(text: str) -> None:
    print(f"console-tui ship: {one_line(text, 500)}", file=sys.stderr, flush=True)
