"""A real rclpy node for tests, driven by JSON commands on stdin, reporting on stdout.

    talker.py --name NAME [--namespace NS] [--volatile] [--own-rosout [DEPTH]] [--no-logger-service] [--debug]

``--volatile`` makes the node's ``/rosout`` publisher VOLATILE: through ``rosout_qos_profile``
where rclpy has it (Kilted), else (Jazzy) the node's logger does not publish and the node
publishes each message on ``/rosout`` itself with the same fields, through a VOLATILE publisher
of its own. ``--own-rosout`` makes the node publish on ``/rosout`` itself that way with rosout's
own QoS (RELIABLE, TRANSIENT_LOCAL, depth 1000, or DEPTH): then ``burst`` waits until every
subscriber has acknowledged every message before it answers (``"acked": true``), so a test
knows that the burst has reached the subscribers' histories. A DEPTH as large as a burst keeps
all of it until then (with Fast DDS room for it: deep_writer_profile.xml); with rosout's 1,000,
on a busy machine, subscribers were told that some of a 20,000 burst were lost.

Prints ``{"event": "ready", "logger": ..., "pid": ...}`` once up. Commands (one JSON object a
line): ``{"cmd": "log_all", "tag": T}`` logs one message at each severity, from a function
of its own each, and prints ``{"event": "logged", "messages": [...]}`` with every field;
``{"cmd": "log", "level": "info", "msg": M}`` logs one; both take ``"child": NAME`` to log
through the child logger ``<node logger>.NAME``; ``{"cmd": "periodic", "period": S}`` logs
DEBUG and INFO ``tick N`` every S seconds; ``{"cmd": "block", "seconds": S}`` keeps the
node's executor busy for S seconds (services go unanswered), printing ``{"event":
"blocking"}`` as it starts; ``{"cmd": "burst", "count": N}`` logs INFO ``burst 0`` to ``burst N-1``
at once and prints ``{"event": "burst", "count": N, "acked": ...}``; through the logger (no
``--own-rosout``), ``BURST_LOGGED`` on stderr follows whatever rcl said there of messages it
could not publish on /rosout. EOF on stdin ends it.
"""

from __future__ import annotations

import argparse
import inspect
import json
import os
import sys
import threading

import rclpy
from rclpy.duration import Duration
from rclpy.executors import SingleThreadedExecutor
from rclpy.logging import LoggingSeverity
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

FILE = os.path.abspath(__file__)
_print_lock = threading.Lock()


#: Said on stderr once a burst through the logger is done.
BURST_LOGGED = "talker: burst logged"


def say(**fields) -> None:
    with _print_lock:
        print(json.dumps(fields), flush=True)


def _record(level: int, msg: str, back: int = 1) -> dict:
    frame = inspect.currentframe().f_back
    return {"level": level, "msg": msg, "file": FILE, "function": frame.f_code.co_name, "line": frame.f_lineno + back}


#: Set when the node publishes its own /rosout messages (``--volatile`` without rclpy's
#: ``rosout_qos_profile``): ``(node, publisher)``.
OWN_ROSOUT: list = []


def _logged(logger, record: dict) -> dict:
    if OWN_ROSOUT:
        from rcl_interfaces.msg import Log

        node, publisher = OWN_ROSOUT
        if logger.get_effective_level() <= record["level"]:
            fields = {key: record[key] for key in ("level", "msg", "file", "function", "line")}
            publisher.publish(Log(stamp=node.get_clock().now().to_msg(), name=logger.name, **fields))
    return record


def log_debug(logger, msg: str) -> dict:
    record = _record(10, msg)
    logger.debug(msg)
    return _logged(logger, record)


def log_info(logger, msg: str) -> dict:
    record = _record(20, msg)
    logger.info(msg)
    return _logged(logger, record)


def log_warning(logger, msg: str) -> dict:
    record = _record(30, msg)
    logger.warning(msg)
    return _logged(logger, record)


def log_error(logger, msg: str) -> dict:
    record = _record(40, msg)
    logger.error(msg)
    return _logged(logger, record)


def log_fatal(logger, msg: str) -> dict:
    record = _record(50, msg)
    logger.fatal(msg)
    return _logged(logger, record)


def publish_burst(logger, count: int) -> None:
    """``burst 0`` to ``burst COUNT-1`` at INFO through the node's own /rosout publisher only."""
    from rcl_interfaces.msg import Log

    node, publisher = OWN_ROSOUT
    clock = node.get_clock()
    for number in range(count):
        publisher.publish(
            Log(stamp=clock.now().to_msg(), level=20, name=logger.name, msg=f"burst {number}", file=FILE, line=number)
        )


BY_LEVEL = {"debug": log_debug, "info": log_info, "warn": log_warning, "error": log_error, "fatal": log_fatal}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--name", required=True)
    parser.add_argument("--namespace", default="")
    parser.add_argument("--volatile", action="store_true", help="rosout QoS VOLATILE")
    parser.add_argument("--own-rosout", type=int, nargs="?", const=1000, help="publish /rosout itself, keeping DEPTH")
    parser.add_argument("--no-logger-service", action="store_true")
    parser.add_argument("--debug", action="store_true", help="start with the logger at DEBUG")
    args = parser.parse_args()

    rclpy.init()
    options = {"enable_logger_service": not args.no_logger_service}
    volatile = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE)
    durable = QoSProfile(
        depth=args.own_rosout or 1000,
        reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.TRANSIENT_LOCAL,
    )
    own_rosout = bool(args.own_rosout) or (
        args.volatile and "rosout_qos_profile" not in inspect.signature(Node.__init__).parameters
    )
    if own_rosout:
        options["enable_rosout"] = False
    elif args.volatile:
        options["rosout_qos_profile"] = volatile
    node = Node(args.name, namespace=args.namespace, **options)
    logger = node.get_logger()
    if own_rosout:
        from rcl_interfaces.msg import Log

        OWN_ROSOUT[:] = [node, node.create_publisher(Log, "/rosout", volatile if args.volatile else durable)]
    if args.debug:
        logger.set_level(LoggingSeverity.DEBUG)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    state = {"tick": 0, "timer": None, "block": None}
    stopping = threading.Event()

    def tick() -> None:
        state["tick"] += 1
        log_debug(logger, f"tick {state['tick']} debug")
        log_info(logger, f"tick {state['tick']} info")

    def read_commands() -> None:
        for raw in sys.stdin:
            try:
                command = json.loads(raw)
            except json.JSONDecodeError:
                continue
            kind = command.get("cmd")
            target = logger.get_child(command["child"]) if command.get("child") else logger
            if kind == "log_all":
                tag = command.get("tag", "")
                messages = [function(target, f"{tag} {name} message") for name, function in BY_LEVEL.items()]
                say(event="logged", messages=messages)
            elif kind == "log":
                message = BY_LEVEL[command.get("level", "info")](target, command.get("msg", ""))
                say(event="logged", messages=[message])
            elif kind == "burst":
                count = int(command.get("count", 1000))
                if OWN_ROSOUT:
                    publish_burst(logger, count)
                else:
                    for number in range(count):
                        logger.info(f"burst {number}")
                    # After rcl's complaints of messages it could not publish on /rosout.
                    print(BURST_LOGGED, file=sys.stderr, flush=True)
                acked = OWN_ROSOUT[1].wait_for_all_acked(Duration(seconds=60)) if OWN_ROSOUT else None
                say(event="burst", count=count, acked=acked)
            elif kind == "periodic":
                state["timer"] = node.create_timer(float(command.get("period", 0.1)), tick)
                say(event="periodic")
            elif kind == "block":
                seconds = float(command.get("seconds", 5))

                def block(seconds: float = seconds) -> None:
                    state["block"].cancel()
                    say(event="blocking")
                    stopping.wait(seconds)

                state["block"] = node.create_timer(0.0, block)
        stopping.set()
        executor.shutdown(timeout_sec=0)
        rclpy.try_shutdown()

    threading.Thread(target=read_commands, daemon=True).start()
    say(event="ready", logger=logger.name, pid=os.getpid(), node=node.get_fully_qualified_name())
    try:
        executor.spin()
    except Exception:
        pass
    finally:
        try:
            node.destroy_node()
        except Exception:
            pass
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
