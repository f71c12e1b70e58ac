#!/usr/bin/env python3
"""Intake benchmark: how many Log messages a subscriber keeps up with, and how many it loses.

Real rclpy publisher processes (1 and 4) send pre-serialized ``rcl_interfaces/msg/Log``
messages with ``/rosout``'s QoS on a test topic, as fast as they can ("max") and at fixed
total rates. In the same run, one after another against the same publishers, these
subscribers (each a process of its own, started fresh) count what they receive:

- ``intake``: console-tui's intake as ``console-tui`` runs it: the live source in the intake
  process, its batches read from the pipe into an ``IntakeQueue`` drained every 50 ms into
  a ``LogStore`` as the app does (its CPU includes the intake process's);
- ``raw-ee``: a raw (serialized) subscription on rclpy's EventsExecutor, counting only
  (RELIABLE, TRANSIENT_LOCAL, KEEP_LAST 10000), the ceiling a Python subscriber reaches;
- ``typed-spin``: a typed subscription spun by ``rclpy.spin`` (rqt_console's pattern).

The whole app, headless at 160x48 and drawing, with a probe measuring event-loop stalls
and Up/End keys measuring key-to-effect times (first with nothing arriving, ``--floor``
seconds, then while the messages arrive), and the logger levels' rclpy context as
``console-tui`` has it:

- ``app``: with the intake process (as ``console-tui`` runs);
- ``app-thread``: with the intake in a thread of the app's own process (the design before);
- ``app-thread-batched``: the same, its thread waking less often for bigger batches.

Also: ``intake-thread`` (the live source in a thread of the subscriber's process, no UI),
``intake-typed`` (the typed fallback path, in the intake process), ``intake-ee`` (the
decoder and queue fed by an EventsExecutor callback) and ``typed-ee``. Received/s counts
what arrived while the publishers sent; lost is what was sent and never arrived once
everything settled; the status bar's count is what the source reported. Every process
uses ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a ROS_DOMAIN_ID of its own.

    python benchmarks/intake.py                      # the table (about 5 minutes)
    python benchmarks/intake.py --kinds intake app app-thread raw-ee typed-spin   # the designs
    python benchmarks/intake.py --sustained 600      # the app: 0 lost at 20k/s for 10 minutes?
    python benchmarks/intake.py --sustained 600 --publishers 4 --rates 10000
    python benchmarks/intake.py --publishers 1 --rates max --duration 3

The publishers publish from Python through rclpy (about 10 us of their CPU a message, 7 of
them in rcl and Fast DDS); with ``--publisher c`` they publish the same messages from a loop
in C through rcl (``c_flood.c``, built with the compiler the take loop uses), without
Python's share, as a node in C++ would:

    python benchmarks/intake.py --sustained 600 --rates 50000 --publisher c

A fleet (``--domains N``): the publishers in each of N ROS 2 domains (``--domain`` and the
next ones), ``--publishers`` in each, and the console reading all of them as ``console-tui
--domain ...`` does, an intake process per domain (kinds ``intake`` and ``app`` only); the
rates are the total over every domain. The issue's row, four domains at 5,000/s each:

    python benchmarks/intake.py --sustained 60 --domains 4
"""

from __future__ import annotations

import argparse
import json
import os
import random
import selectors
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).parent))
from _probe import cpu_by_thread, process_cpu
from _probe import threads_table as cpu_table
from _report import ros_environment, ros_header, run_under_header, table, verdict

TOPIC = "/console_tui_bench_log"
QUEUE_DEPTH = 10_000
DEFAULT_KINDS = ("intake", "raw-ee", "typed-spin")
#: The console's intake in its own process (as console-tui runs it), alone or under the app.
PROCESS_KINDS = {"intake", "intake-typed", "app"}
#: The whole app, headless and drawing.
APP_KINDS = {"app", "app-thread", "app-thread-batched"}
ALL_KINDS = (
    *DEFAULT_KINDS,
    "intake-thread",
    "app",
    "app-thread",
    "app-thread-batched",
    "intake-typed",
    "intake-ee",
    "typed-ee",
)
BATCHED_COALESCE_S = 0.02
APP_PREFILL = 10_000
DEFAULT_RATES = ("max", "1000", "5000", "20000", "50000")
TARGET_VS_RAW_EE = 0.95
STALL_OVER_FLOOR_MS = 10.0
KEY_TARGET_MS = 100.0
TARGET_VS_TYPED = 5.0
LOSSLESS_RATE = 20_000
#: Subscribers that say how long stopping took (the intake's ``stop()``).
STOP_REPORTING_KINDS = {"intake", "intake-thread", "intake-typed", "intake-ee", *APP_KINDS}


def say(**fields: Any) -> None:
    print(json.dumps(fields), flush=True)


# -- the publisher process ---------------------------------------------------------------------


#: The levels of a pool's messages: ``mixed`` (every level, INFO most), or ``debug`` (a robot
#: logging at DEBUG: every message DEBUG but the pool's first, an ERROR; ``level_filter.py``).
POOL_LEVELS = ("mixed", "debug")


def message_pool(index: int, size: int = 512, levels: str = "mixed") -> list[bytes]:
    """Realistic serialized Log messages: a few nodes, files and functions, 60-120 char texts."""
    from rcl_interfaces.msg import Log
    from rclpy.serialization import serialize_message

    rng = random.Random(index)
    words = [
        "goal",
        "plan",
        "costmap",
        "laser",
        "scan",
        "tf",
        "frame",
        "odom",
        "map",
        "timeout",
        "received",
        "sending",
        "ok",
        "failed",
        "retry",
    ]
    pool = []
    for number in range(size):
        message = Log()
        now = time.time_ns()
        message.stamp.sec, message.stamp.nanosec = divmod(now, 1_000_000_000)
        message.level = rng.choice([10, 20, 20, 20, 30, 40, 50])
        if levels == "debug":
            message.level = 40 if number == 0 else 10
        message.name = f"bench.publisher{index}.{rng.choice(['planner', 'controller', 'driver', 'camera'])}"
        text = f"[{number}] " + " ".join(rng.choice(words) for _ in range(30))
        message.msg = text[: rng.randint(60, 120)]
        message.file = f"/opt/robot/src/{rng.choice(['nav', 'perception', 'hw'])}/src/module_{rng.randint(0, 5)}.cpp"
        message.function = rng.choice(["on_timer", "update", "publish_state", "handle_goal", "spin_some"])
        message.line = rng.randint(1, 2000)
        pool.append(bytes(serialize_message(message)))
    return pool


def rosout_qos():
    from rclpy.duration import Duration
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

    return QoSProfile(
        history=HistoryPolicy.KEEP_LAST,
        depth=1000,
        reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL,
        lifespan=Duration(seconds=10),
    )


def subscriber_qos():
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

    return QoSProfile(
        history=HistoryPolicy.KEEP_LAST,
        depth=QUEUE_DEPTH,
        reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL,
    )


def run_publisher(index: int, topic: str = TOPIC, loop: str = "python", levels: str = "mixed") -> None:
    """A publisher process; ``loop`` "c" publishes from ``c_flood.c`` (see there), else from
    Python; ``levels``: the pool's (``message_pool``)."""
    import rclpy
    from rcl_interfaces.msg import Log
    from rclpy.node import Node
    from rclpy.signals import SignalHandlerOptions

    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = Node(f"bench_publisher_{index}")
    publisher = node.create_publisher(Log, topic, rosout_qos())
    pool = message_pool(index, levels=levels)
    mask = len(pool) - 1
    publish = publisher.publish
    flood = load_c_flood() if loop == "c" else None
    say(event="ready")
    for raw in sys.stdin:
        command = json.loads(raw)
        if command["cmd"] == "matched":
            deadline = time.monotonic() + 30
            while publisher.get_subscription_count() != command["count"] and time.monotonic() < deadline:
                time.sleep(0.02)
            say(event="matched", count=publisher.get_subscription_count())
        elif command["cmd"] == "go" and flood is not None:
            sent, failed, elapsed = flood(
                publisher.handle.pointer, pool, float(command["rate"]), float(command["duration"])
            )
            say(event="done", sent=sent, failed=failed, elapsed=elapsed)
        elif command["cmd"] == "go":
            rate, duration = float(command["rate"]), float(command["duration"])
            sent = failed = 0
            start = time.perf_counter()
            end = start + duration
            now = start
            while now < end:
                due = sent + failed + 100 if rate <= 0 else int((now - start) * rate)
                while sent + failed < due:
                    try:
                        publish(pool[(sent + failed) & mask])
                        sent += 1
                    except Exception:  # Fast DDS refuses when its history is full of unacknowledged messages
                        failed += 1
                if rate > 0:
                    time.sleep(0.0005)
                now = time.perf_counter()
            say(event="done", sent=sent, failed=failed, elapsed=time.perf_counter() - start)
    node.destroy_node()
    rclpy.try_shutdown()


def load_c_flood() -> Callable[..., tuple[int, int, float]]:
    """``c_flood.c``'s ``flood``, built against the rcl rclpy loaded, in a temporary directory
    that is gone once the built module is loaded."""
    from console_tui.sources.ros2.compiled_take import loaded_rcl, rcl_flags
    from console_tui.system import c_build

    library = loaded_rcl()
    flags = rcl_flags(library) if library is not None else "rclpy's librcl.so is not loaded"
    if isinstance(flags, str):
        raise SystemExit(f"--publisher c: {flags}")
    with tempfile.TemporaryDirectory(prefix="c-flood-") as folder:
        target = Path(folder) / f"c_flood{c_build.suffix()}"
        problem = c_build.compile_module(Path(__file__).with_name("c_flood.c"), target, 120.0, flags)
        if problem:
            raise SystemExit(f"--publisher c: {problem}")
        return c_build.import_built("c_flood", target).flood


# -- the subscriber processes ------------------------------------------------------------------


class Counter:
    """What a reference subscriber's callback counts."""

    def __init__(self) -> None:
        self.count = 0

    def __call__(self, _message: Any) -> None:
        self.count += 1


def serve_commands(count, publishers, extra=dict) -> None:
    """Answer the orchestrator on stdin until it says quit (or closes stdin)."""
    for raw in sys.stdin:
        command = json.loads(raw)
        if command["cmd"] == "publishers":
            deadline = time.monotonic() + 30
            while publishers() < command["count"] and time.monotonic() < deadline:
                time.sleep(0.02)
            say(event="publishers", count=publishers())
        elif command["cmd"] == "count":
            say(**{"event": "count", "count": count(), "cpu": time.process_time(), **extra()})
        elif command["cmd"] == "quit":
            return


class FleetSources:
    """A fleet's intake processes, one a domain, counted as one source by this benchmark."""

    def __init__(self, queue: Any, domains: int, first_domain: int) -> None:
        from console_tui.ros.fleet import Robot
        from console_tui.ros.ros_version import ROS2
        from console_tui.sources.live import open_fleet

        self.robots = [Robot(f"d{first_domain + i}", ROS2, domain=first_domain + i) for i in range(domains)]
        self.sources = [live.source for live in open_fleet(queue, self.robots, topic=TOPIC)]

    def start(self) -> None:
        for source in self.sources:
            source.start()

    def stop(self) -> None:
        for source in self.sources:
            source.stop()

    @property
    def pids(self) -> list[int]:
        return [source.pid for source in self.sources if source.pid]

    @property
    def status(self) -> Any:
        from dataclasses import replace

        statuses = [source.status for source in self.sources]
        # What the one queue dropped is in every source's lost_queue: counted once.
        lost = sum(s.lost - s.lost_queue for s in statuses) + max(s.lost_queue for s in statuses)
        return replace(
            statuses[0],
            publishers=sum(s.publishers for s in statuses),
            lost=lost,
            path=f"{statuses[0].path} x{len(statuses)} domains",
        )


def console_source(kind: str, queue: Any, domains: int = 1, first_domain: int = 0) -> tuple[Any, Any]:
    """The console's intake for ``kind``, feeding ``queue``: the source, and the rclpy runtime
    it runs on in this process (None when it runs in the intake process); with ``domains``
    over 1, a fleet's (``FleetSources``)."""
    if domains > 1:
        return FleetSources(queue, domains, first_domain), None
    if kind in PROCESS_KINDS:
        from console_tui.sources.intake_process.parent import ProcessSource

        args = ["--typed"] if kind == "intake-typed" else []
        return ProcessSource(queue, "ros2", topic=TOPIC, args=args), None
    from console_tui.ros.ros2.runtime import RosRuntime
    from console_tui.sources import coalesce
    from console_tui.sources.ros2 import live_source

    if kind == "app-thread-batched":  # fewer wake-ups of the intake thread, bigger batches
        coalesce.BELOW = live_source.MAX_BATCH
        coalesce.FAST_S = coalesce.SLOW_S = BATCHED_COALESCE_S
    runtime = RosRuntime()
    return live_source.LiveLogSource(runtime, queue, TOPIC), runtime


def intake_pids(source: Any) -> list[int]:
    """The source's intake processes (a fleet has one a domain; a thread's source none)."""
    pid = getattr(source, "pid", None)
    return getattr(source, "pids", None) or ([pid] if pid else [])


def cpu_seconds(source: Any) -> float:
    """CPU used by this process and, if the source has them, its intake processes."""
    return time.process_time() + intake_cpu_seconds(source)


def intake_cpu_seconds(source: Any) -> float:
    """CPU used by the source's intake processes (0 when it runs in this process)."""
    return sum(process_cpu(each) for each in intake_pids(source))


def run_intake_subscriber(kind: str, domains: int = 1, first_domain: int = 0) -> None:
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.model.store.log_store import LogStore

    queue = IntakeQueue()
    store = LogStore()
    source, runtime = console_source(kind, queue, domains, first_domain)
    stop = threading.Event()

    def app_drain() -> None:  # what the app's timer does
        while not stop.wait(0.05):
            for batch in queue.drain_batches():
                store.extend(batch)

    drain = threading.Thread(target=app_drain, daemon=True)
    source.start()
    drain.start()
    say(event="ready")

    def loss() -> dict[str, Any]:
        status = source.status
        return {
            "lost_reported": status.lost,
            "path": status.path,
            "stored": store.end_seq,
            "cpu": cpu_seconds(source),
            "cpu_intake": intake_cpu_seconds(source),
            "intake_pids": intake_pids(source),
        }

    serve_commands(lambda: queue.received, lambda: source.status.publishers, loss)
    stop.set()
    drain.join()
    began = time.monotonic()
    source.stop()
    if runtime is not None:
        runtime.shutdown()
    say(event="stopped", seconds=time.monotonic() - began)


def run_app_subscriber(kind: str, domains: int = 1, first_domain: int = 0) -> None:
    """The whole app, headless at 160x48 and drawing, with the console's intake (``app``: in
    its process, as ``console-tui`` runs it; ``app-thread``: in a thread of the app's process,
    the design before) and the logger levels' rclpy context, as ``console-tui`` has them.
    Measures event-loop stalls and key-to-effect times between ``mark`` commands."""
    import asyncio
    import gc

    from _probe import KeyProbe, StallProbe, count_frames, percentile, process_rss_mb

    from console_tui.control.ros2.logger_control import Ros2LoggerControl
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.ros.ros2.runtime import RosRuntime
    from console_tui.sources.intake_process.synthetic import synthetic_record
    from console_tui.ui.app import ConsoleApp

    queue = IntakeQueue()
    source, runtime = console_source(kind, queue, domains, first_domain)
    cleanups: list[Any] = []
    if isinstance(source, FleetSources):  # as console-tui --domain ... has it
        from console_tui.control.fleet_control import open_fleet_loggers

        control: Any = open_fleet_loggers(source.robots, cleanups)
        app = ConsoleApp(queue=queue, sources=source.sources, logger_control=control, robots=source.robots)
    else:
        runtime = runtime or RosRuntime()
        cleanups.append(runtime.shutdown)
        control = Ros2LoggerControl(runtime)
        app = ConsoleApp(queue=queue, sources=[source], logger_control=control)
    # Rows for the keys to move over before anything arrives (not counted as received).
    app.main.store.extend_records([synthetic_record(number) for number in range(APP_PREFILL)])
    quit_event = threading.Event()
    state: dict[str, Any] = {}

    def stats() -> dict[str, Any]:
        stalls, keys = state["stalls"].stalls, state["keys"].latencies
        longest, longest_cpu, longest_wait = state["stalls"].longest()
        pids = intake_pids(source)
        return {
            "lost_reported": source.status.lost,
            "path": source.status.path + (" (process)" if pids else " (thread)"),
            "stored": app.main.store.end_seq,
            "cpu": cpu_seconds(source),
            "cpu_intake": intake_cpu_seconds(source),
            "intake_pids": pids,
            "stall_max": longest * 1000,
            "stall_max_cpu": longest_cpu * 1000,
            "stall_max_wait": longest_wait * 1000,
            "stall_p99": percentile(stalls, 0.99) * 1000,
            "key_median": percentile(keys, 0.5) * 1000,
            "key_max": max(keys, default=0.0) * 1000,
            "keys": len(keys),
            "rss_app": process_rss_mb(os.getpid()),
            "rss_intake": sum(process_rss_mb(each) for each in pids),
            "gc_longest": app.collection_policy.longest * 1000,
            "gc_longest_cpu": app.collection_policy.longest_cpu * 1000,
        }

    def mark() -> None:
        state["stalls"].clear()
        state["keys"].latencies = []
        app.collection_policy.longest = 0.0

    async def main() -> None:
        async with app.run_test(size=(160, 48)):
            frames = count_frames(app.main.table)
            state["stalls"] = StallProbe()
            state["keys"] = KeyProbe(app, app.main.table, frames)
            state["stalls"].start()
            state["keys"].start()
            say(event="ready")
            while not quit_event.is_set():
                await asyncio.sleep(0.05)
                del frames[:-100]  # keep the list short
            state["keys"].stop()
            await state["stalls"].stop()
            state["quit_at"] = time.monotonic()
        state["stopped_at"] = time.monotonic()

    def commands() -> None:
        for raw in sys.stdin:
            command = json.loads(raw)
            if command["cmd"] == "mark":
                mark()
                say(event="marked")
            elif command["cmd"] == "publishers":
                deadline = time.monotonic() + 30
                while source.status.publishers < command["count"] and time.monotonic() < deadline:
                    time.sleep(0.02)
                say(event="publishers", count=source.status.publishers)
            elif command["cmd"] == "count":
                say(event="count", count=queue.received, **stats())
            elif command["cmd"] == "quit":
                break
        quit_event.set()

    threading.Thread(target=commands, daemon=True).start()
    gc.collect()
    asyncio.run(main())
    began = time.monotonic()
    control.close()
    for cleanup in reversed(cleanups):
        cleanup()
    say(event="stopped", seconds=time.monotonic() - state["quit_at"], app_seconds=began - state["quit_at"])


class EventsExecutorThread:
    """rclpy's EventsExecutor spinning ``node`` in a thread, by ``spin_once`` in a loop
    (its ``spin()`` cannot be stopped from another thread)."""

    def __init__(self, node: Any) -> None:
        from rclpy.experimental import EventsExecutor

        self.executor = EventsExecutor()
        self.executor.add_node(node)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        while not self._stop.is_set():
            self.executor.spin_once(timeout_sec=0.1)

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(5)
        self.executor.shutdown()


def run_intake_events_executor() -> None:
    """The intake's decoder, queue and store, fed by an EventsExecutor callback: the alternative design."""
    import rclpy
    from rcl_interfaces.msg import Log
    from rclpy.node import Node
    from rclpy.signals import SignalHandlerOptions

    from console_tui.model.formats.ros2_log_msg import LogDecoder
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.model.store.log_store import LogStore
    from console_tui.model.store.record_batch import RecordColumns

    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = Node("bench_intake_ee")
    queue, store, decode = IntakeQueue(), LogStore(), LogDecoder().decode
    pending: list = []

    def on_message(data: bytes) -> None:
        pending.append(decode(data, TOPIC))

    subscription = node.create_subscription(Log, TOPIC, on_message, subscriber_qos(), raw=True)
    stop = threading.Event()

    def app_drain() -> None:
        nonlocal pending
        while not stop.wait(0.05):
            batch, pending = pending, []
            queue.put(RecordColumns.from_records(batch))
            for columns in queue.drain_batches():
                store.extend(columns)

    spinner = EventsExecutorThread(node)
    drain = threading.Thread(target=app_drain, daemon=True)
    drain.start()
    say(event="ready")
    serve_commands(lambda: queue.received + len(pending), subscription.get_publisher_count)
    began = time.monotonic()
    stop.set()
    drain.join(5)
    spinner.stop()
    rclpy.try_shutdown()
    say(event="stopped", seconds=time.monotonic() - began)


def run_reference_subscriber(kind: str, topic: str = TOPIC) -> None:
    import rclpy
    from rcl_interfaces.msg import Log
    from rclpy.node import Node
    from rclpy.signals import SignalHandlerOptions

    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = Node(f"bench_{kind.replace('-', '_')}")
    counter = Counter()
    subscription = node.create_subscription(Log, topic, counter, subscriber_qos(), raw=kind == "raw-ee")
    say(event="ready")
    if kind == "typed-spin":
        spinner = threading.Thread(target=_spin_until_shutdown, args=(node,), daemon=True)
        spinner.start()
        serve_commands(lambda: counter.count, subscription.get_publisher_count)
        rclpy.try_shutdown()
        spinner.join(5)
    else:
        spinner = EventsExecutorThread(node)
        serve_commands(lambda: counter.count, subscription.get_publisher_count)
        spinner.stop()
        rclpy.try_shutdown()


def _spin_until_shutdown(node: Any) -> None:
    import rclpy

    try:
        rclpy.spin(node)
    except Exception:
        pass  # the context was shut down


# -- the orchestrator -----------------------------------------------------------------------------


class Child:
    """One benchmark process, talking JSON lines."""

    def __init__(self, role_args: list[str], env: dict[str, str]) -> None:
        self.process = subprocess.Popen(
            [sys.executable, __file__, *role_args],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=None if os.environ.get("BENCH_DEBUG") else subprocess.DEVNULL,
            env=env,
            text=True,
        )
        self._selector = selectors.DefaultSelector()
        self._selector.register(self.process.stdout, selectors.EVENT_READ)

    def send(self, **command: Any) -> None:
        self.process.stdin.write(json.dumps(command) + "\n")
        self.process.stdin.flush()

    def expect(self, event: str, timeout: float = 60.0) -> dict[str, Any]:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if not self._selector.select(max(0.0, deadline - time.monotonic())):
                continue
            line = self.process.stdout.readline()
            if not line:
                raise RuntimeError(f"{self.process.args[2:]} ended before saying {event!r}")
            try:
                item = json.loads(line)
            except json.JSONDecodeError:
                continue
            if item.get("event") == event:
                return item
        raise TimeoutError(f"{self.process.args[2:]} never said {event!r}")

    def ask(self, event: str, timeout: float = 60.0, **command: Any) -> dict[str, Any]:
        self.send(**command)
        return self.expect(event, timeout)

    def close(self, timeout: float = 10.0) -> None:
        try:
            self.process.stdin.close()
        except OSError:
            pass
        try:
            self.process.wait(timeout)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self._selector.close()


@dataclass
class Row:
    publishers: int
    rate: str
    kind: str
    sent: int
    seconds: float
    in_window: int
    received: int
    cpu: float
    #: Of ``cpu``, what the intake processes used (0 when the subscriber has none).
    cpu_intake: float = 0.0
    lost_reported: int | None = None
    path: str = ""
    stop_ms: float | None = None
    #: The whole app's figures (APP_KINDS): during the load, and with nothing arriving.
    app: dict[str, float] | None = None
    floor: dict[str, float] | None = None
    #: CPU seconds while the publishers sent, by (process, thread name).
    threads: dict[tuple[str, str], float] | None = None

    @property
    def received_per_s(self) -> float:
        return self.in_window / self.seconds

    @property
    def lost(self) -> int:
        return max(self.sent - self.received, 0)


def settle(subscriber: Child, quiet: float = 0.6, limit: float = 20.0) -> dict[str, Any]:
    """The subscriber's count once it stops growing."""
    last = subscriber.ask("count", cmd="count")
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        time.sleep(quiet)
        now = subscriber.ask("count", cmd="count")
        if now["count"] == last["count"]:
            return now
        last = now
    return last


def domain_environment(env: dict[str, str], number: int) -> dict[str, str]:
    """``env`` on the fleet's ``number``th domain (0: ``env``'s own)."""
    return {**env, "ROS_DOMAIN_ID": str(int(env["ROS_DOMAIN_ID"]) + number)}


def measure(args: argparse.Namespace, env: dict[str, str]) -> list[Row]:
    """For each publisher count and rate, each subscriber in turn (``--repeat`` rounds, medians)."""
    rows: list[Row] = []
    for count in args.publishers:
        publishers = [
            Child(
                ["--role", "publisher", "--index", str(domain * count + i), "--publisher", args.publisher],
                domain_environment(env, domain),
            )
            for domain in range(args.domains)
            for i in range(count)
        ]
        try:
            for child in publishers:
                child.expect("ready")
            for rate in args.rates:
                runs: dict[str, list[Row]] = {kind: [] for kind in args.kinds}
                for round_number in range(args.repeat):
                    shift = round_number % len(args.kinds)  # vary the order, so drifting load hits all alike
                    for kind in args.kinds[shift:] + args.kinds[:shift]:
                        runs[kind].append(measure_once(args, env, publishers, kind, rate))
                for kind in args.kinds:
                    ordered = sorted(runs[kind], key=lambda row: row.received_per_s)
                    rows.append(ordered[len(ordered) // 2])
        finally:
            for child in publishers:
                child.close()
    return rows


def measure_once(args: argparse.Namespace, env: dict[str, str], publishers: list[Child], kind: str, rate: str) -> Row:
    """One subscriber process, started fresh, measured at one rate."""
    fleet = ["--domains", str(args.domains), "--domain", str(args.domain)]
    subscriber = Child(["--role", "subscriber", "--kind", kind, *fleet], env)
    floor = None
    try:
        subscriber.expect("ready")
        subscriber.ask("publishers", cmd="publishers", count=len(publishers))
        for child in publishers:
            child.ask("matched", cmd="matched", count=1)
        before = settle(subscriber)  # publishers' TRANSIENT_LOCAL history, delivered on matching
        if kind in APP_KINDS and args.floor > 0:
            subscriber.ask("marked", cmd="mark")
            time.sleep(args.floor)  # nothing arriving: the floor this machine sets for stalls and keys
            floor = subscriber.ask("count", cmd="count")
            subscriber.ask("marked", cmd="mark")
        per_publisher = 0.0 if rate == "max" else float(rate) / len(publishers)
        roles = {
            "publisher": [child.process.pid for child in publishers],
            "subscriber": [subscriber.process.pid],
            "intake": before.get("intake_pids", []),
        }
        threads_before = cpu_by_thread(roles)
        for child in publishers:
            child.send(cmd="go", rate=per_publisher, duration=args.duration)
        done = [child.expect("done", args.duration + 120) for child in publishers]
        threads_after = cpu_by_thread(roles)
        window = subscriber.ask("count", cmd="count")
        after = settle(subscriber)
        subscriber.send(cmd="quit")
        stopped = subscriber.expect("stopped", 30) if kind in STOP_REPORTING_KINDS else None
    finally:
        subscriber.close()
        for child in publishers:  # the next subscriber starts once this one is gone
            child.ask("matched", cmd="matched", count=0)
    app_keys = (
        "stall_max",
        "stall_max_cpu",
        "stall_max_wait",
        "stall_p99",
        "key_median",
        "key_max",
        "keys",
        "rss_app",
        "rss_intake",
        "gc_longest",
        "gc_longest_cpu",
    )
    row = Row(
        publishers=len(publishers),
        rate=rate,
        kind=kind,
        sent=sum(d["sent"] for d in done),
        seconds=max(d["elapsed"] for d in done),
        in_window=window["count"] - before["count"],
        received=after["count"] - before["count"],
        cpu=after["cpu"] - before["cpu"],
        cpu_intake=after.get("cpu_intake", 0.0) - before.get("cpu_intake", 0.0),
        lost_reported=after["lost_reported"] - before["lost_reported"] if "lost_reported" in after else None,
        path=after.get("path", ""),
        stop_ms=stopped["seconds"] * 1000 if stopped else None,
        app={key: window[key] for key in app_keys} if kind in APP_KINDS else None,
        floor={key: floor[key] for key in app_keys} if floor else None,
        threads={key: threads_after[key] - threads_before.get(key, 0.0) for key in threads_after},
    )
    print(
        f"  {row.publishers} pub, {rate:>5}, {kind:<12}: sent {row.sent:>8,} received {row.received:>8,} "
        f"({row.received_per_s:,.0f}/s), lost {row.lost:,}"
        + (f", longest stall {row.app['stall_max']:.0f} ms, worst key {row.app['key_max']:.0f} ms" if row.app else ""),
        file=sys.stderr,
        flush=True,
    )
    return row


def threads_table(row: Row) -> str:
    """Where the CPU went while the publishers sent (``_probe.threads_table``)."""
    return cpu_table(row.threads or {}, row.seconds or 1.0, row.in_window)


CONSOLE_KINDS = {"intake", "intake-thread", "intake-typed", "intake-ee", *APP_KINDS}
#: Rows whose targets are the product's: the intake as console-tui runs it, alone and in the app.
PRODUCT_KINDS = {"intake", "app"}


def report(rows: list[Row], args: argparse.Namespace) -> str:
    by_key = {(r.publishers, r.rate, r.kind): r for r in rows}
    lines = []
    body = []
    for row in rows:
        raw_ee = by_key.get((row.publishers, row.rate, "raw-ee"))
        typed = by_key.get((row.publishers, row.rate, "typed-spin"))
        console = row.kind in CONSOLE_KINDS
        vs_raw = f"{row.received_per_s / raw_ee.received_per_s:.2f}" if console and raw_ee else ""
        vs_typed = f"{row.received_per_s / typed.received_per_s:.1f}x" if console and typed else ""
        cpu_per_message = f"{row.cpu / row.received * 1e6:.0f}" if row.received else "-"
        if row.received and row.cpu_intake:
            cpu_per_message += f" ({row.cpu_intake / row.received * 1e6:.0f})"
        reported = "" if row.lost_reported is None else f"{row.lost_reported:,}"
        body.append(
            [
                row.publishers,
                row.rate,
                row.kind + (f" ({row.path})" if row.path else ""),
                f"{row.sent / row.seconds:,.0f}",
                f"{row.received_per_s:,.0f}",
                f"{row.lost:,}",
                f"{100 * row.lost / row.sent:.1f}%" if row.sent else "-",
                reported,
                cpu_per_message,
                vs_raw,
                vs_typed,
            ]
        )
    headers = ["pubs", "offered/s", "subscriber", "sent/s", "received/s", "lost", "lost %"]
    headers += ["lost (status bar)", "CPU us/msg (intake's)", "÷ raw-ee", "÷ typed-spin"]
    lines.append(table(headers, body))
    app_rows = [row for row in rows if row.app is not None]
    if app_rows:
        lines += ["", "The whole app (headless at 160x48, drawing) while the messages arrive; in brackets, the same"]
        lines += ["app before the publishers start (nothing arriving: the floor this machine sets):", ""]
        lines.append(app_table(app_rows))
    for row in rows:
        if args.threads and row.threads and (row.kind in PRODUCT_KINDS or row.kind == "raw-ee"):
            lines += ["", f"Where the CPU went while sending ({row.kind}, {row.publishers} pub, {row.rate}/s):", ""]
            lines.append(threads_table(row))
    lines.append("")
    lines.append("Targets:")
    for row in rows:
        if row.kind in PRODUCT_KINDS:
            lines += targets(row, by_key)
    stops = [row.stop_ms for row in rows if row.stop_ms is not None and row.kind in PRODUCT_KINDS]
    if stops:
        lines.append(
            f"- stopping (the intake; for the app: from quit until the intake process is gone): at most "
            f"{max(stops):.0f} ms over {len(stops)} runs, target 1000: " + verdict(max(stops) <= 1000, "too slow")
        )
    return "\n".join(lines)


def app_table(rows: list[Row]) -> str:
    body = []
    for row in rows:
        app, floor = row.app or {}, row.floor or {}

        def both(key: str, app: dict = app, floor: dict = floor) -> str:
            return f"{app[key]:.0f} ({floor[key]:.0f})" if floor else f"{app[key]:.0f}"

        body.append(
            [
                row.publishers,
                row.rate,
                row.kind,
                both("stall_max"),
                f"{app['stall_max_cpu']:.0f}",
                f"{app.get('stall_max_wait', 0.0):.0f}",
                both("stall_p99"),
                both("key_median"),
                both("key_max"),
                int(app["keys"]),
                f"{app['gc_longest']:.0f} ({app['gc_longest_cpu']:.0f})",
                f"{app['rss_app']:.0f} + {app['rss_intake']:.0f}",
                f"{row.stop_ms:.0f}" if row.stop_ms is not None else "",
            ]
        )
    headers = [
        "pubs",
        "offered/s",
        "app",
        "longest stall ms",
        "its loop CPU ms",
        "its wait for a core ms",
        "stall p99 ms",
        "key median ms",
        "key worst ms",
    ]
    headers += ["keys", "longest gc ms (its CPU)", "RSS MB app + intake", "quit ms"]
    return table(headers, body)


def targets(row: Row, by_key: dict) -> list[str]:
    lines = []
    where = f"{row.kind}, {row.publishers} pub, {row.rate}/s"
    raw_ee = by_key.get((row.publishers, row.rate, "raw-ee"))
    if raw_ee:
        ratio = row.received_per_s / raw_ee.received_per_s
        lines.append(
            f"- {where}: >= {TARGET_VS_RAW_EE:.0%} of raw-ee: {ratio:.0%}, "
            + verdict(ratio >= TARGET_VS_RAW_EE, f"short by {100 * (TARGET_VS_RAW_EE - ratio):.0f} points")
        )
    typed = by_key.get((row.publishers, row.rate, "typed-spin"))
    if typed and row.rate == "max":
        ratio = row.received_per_s / typed.received_per_s
        lines.append(
            f"- {where}: >= 5x typed-spin: {ratio:.1f}x, "
            + verdict(ratio >= TARGET_VS_TYPED, f"short by {TARGET_VS_TYPED - ratio:.1f}x")
        )
    if row.rate != "max" and float(row.rate) <= LOSSLESS_RATE:
        lines.append(
            f"- {where} for {row.seconds:.0f} s: 0 lost: {row.lost:,} lost, "
            + verdict(row.lost == 0, f"{row.lost:,} lost, {100 * row.lost / row.sent:.2f}%")
        )
    if row.lost_reported is not None and row.lost_reported != row.lost:
        lines.append(f"- {where}: the status line said {row.lost_reported:,} lost where {row.lost:,} were")
    if row.app is not None and row.floor is not None:
        limit = row.floor["stall_max"] + STALL_OVER_FLOOR_MS
        stall = row.app["stall_max"]
        lines.append(
            f"- {where}: longest stall <= floor + {STALL_OVER_FLOOR_MS:.0f} ms ({limit:.0f}): {stall:.0f} ms, "
            + verdict(stall <= limit, f"over by {stall - limit:.0f} ms")
        )
    if row.app is not None and row.rate != "max":
        worst = row.app["key_max"]
        lines.append(
            f"- {where}: worst key to effect <= {KEY_TARGET_MS:.0f} ms: {worst:.0f} ms, "
            + verdict(worst <= KEY_TARGET_MS, f"over by {worst - KEY_TARGET_MS:.0f} ms")
        )
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--publishers", type=int, nargs="+", help="publisher process counts (default 1 4)")
    parser.add_argument(
        "--rates", nargs="+", help="total offered rates per second, or max (default max 1000 5000 20000 50000)"
    )
    parser.add_argument(
        "--kinds", nargs="+", choices=ALL_KINDS, help=f"subscribers (default {' '.join(DEFAULT_KINDS)})"
    )
    parser.add_argument("--duration", type=float, help="seconds of sending per measurement (default 5)")
    parser.add_argument("--repeat", type=int, default=1, help="rounds per measurement; the table shows medians")
    parser.add_argument(
        "--sustained",
        type=float,
        metavar="S",
        help="only the whole app (kind app) at 20k/s from 1 publisher for S seconds (flags above override)",
    )
    parser.add_argument(
        "--floor",
        type=float,
        default=5.0,
        metavar="S",
        help="app kinds: seconds measured with nothing arriving first, for the stall floor (default 5)",
    )
    parser.add_argument(
        "--threads",
        action="store_true",
        help="where the CPU went, thread by thread, for the intake, the app and raw-ee (on with --sustained)",
    )
    parser.add_argument(
        "--udp", action="store_true", help="Fast DDS over UDP only (default: its defaults, shared memory)"
    )
    parser.add_argument(
        "--domain", type=int, default=150 + os.getpid() % 80, help="ROS_DOMAIN_ID (default: from the pid)"
    )
    parser.add_argument(
        "--domains",
        type=int,
        default=1,
        metavar="N",
        help="a fleet: publishers in N domains (--domain and the next ones), read as console-tui --domain ... "
        "reads them (kinds intake and app; rates are totals)",
    )
    parser.add_argument(
        "--publisher",
        choices=["python", "c"],
        default="python",
        help="the publishers' loop: rclpy's publish from Python (default), or rcl's from C (c_flood.c), "
        "as cheap a publisher as a node in C++",
    )
    parser.add_argument("--pool", choices=POOL_LEVELS, default="mixed", help=argparse.SUPPRESS)  # level_filter.py
    parser.add_argument("--role", choices=["publisher", "subscriber"], help=argparse.SUPPRESS)
    parser.add_argument("--index", type=int, default=0, help=argparse.SUPPRESS)
    parser.add_argument("--kind", choices=ALL_KINDS, help=argparse.SUPPRESS)
    parser.add_argument("--topic", default=TOPIC, help=argparse.SUPPRESS)  # for benchmarks/rosout.py
    args = parser.parse_args()

    if args.role == "publisher":
        return run_publisher(args.index, args.topic, args.publisher, args.pool)
    if args.role == "subscriber":
        if args.kind in APP_KINDS:
            return run_app_subscriber(args.kind, args.domains, args.domain)
        if args.kind in ("intake", "intake-thread", "intake-typed"):
            return run_intake_subscriber(args.kind, args.domains, args.domain)
        if args.kind == "intake-ee":
            return run_intake_events_executor()
        return run_reference_subscriber(args.kind, args.topic)

    sustained = args.sustained is not None
    args.publishers = args.publishers or ([1] if sustained else [1, 4])
    args.rates = args.rates or ([str(LOSSLESS_RATE)] if sustained else list(DEFAULT_RATES))
    args.kinds = args.kinds or (["app"] if sustained else list(DEFAULT_KINDS))
    args.duration = args.duration or (args.sustained if sustained else 5.0)
    args.threads = args.threads or sustained
    if args.domains > 1 and not set(args.kinds) <= {"intake", "app"}:
        parser.error("--domains: only the kinds intake and app read a fleet")
    if args.domains < 1 or args.domain + args.domains - 1 > 232:
        parser.error("--domains: the domains --domain .. --domain+N-1 must lie within 0..232")
    env = ros_environment(args.domain)
    if args.udp:
        env["FASTDDS_BUILTIN_TRANSPORTS"] = "UDPv4"
    header = ros_header(
        "Intake benchmark (benchmarks/intake.py)",
        env,
        f"transport {'UDPv4' if args.udp else 'Fast DDS defaults (shared memory)'}; "
        f"{args.duration:g} s per measurement, median of {args.repeat}; messages {len(message_pool(0)[0])}-ish bytes serialized"
        + (
            f"; a fleet of {args.domains} domains from {args.domain}, the publishers counted over all."
            if args.domains > 1
            else "."
        ),
    )
    rows = run_under_header(header, lambda: measure(args, env))
    print(report(rows, args))


if __name__ == "__main__":
    main()
