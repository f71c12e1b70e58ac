"""A real rospy node for the ROS 1 live tests (run with the system Python, Debian's rospy).

    rospy_node.py NAME [--period S] [--debug] [--publish TOPIC]

Logs "debug N" .. "fatal N" (rospy.logdebug .. logfatal) every ``--period`` seconds (0:
never); with ``--debug`` its level starts at DEBUG. ``--publish TOPIC`` also publishes a
std_msgs/String there. Says ``{"event": "ready", "pid": ...}`` once running; each stdin
line ``{"log": LEVEL, "msg": TEXT}`` logs once and answers ``{"event": "logged"}``. Ends
when stdin closes.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import threading

import rospy

LOG = {
    "debug": rospy.logdebug,
    "info": rospy.loginfo,
    "warn": rospy.logwarn,
    "error": rospy.logerr,
    "fatal": rospy.logfatal,
}


def say(event: str, **fields) -> None:
    print(json.dumps({"event": event, **fields}), flush=True)


def read_commands(done: threading.Event) -> None:
    for line in sys.stdin:
        try:
            command = json.loads(line)
        except json.JSONDecodeError:
            continue
        if "log" in command:
            LOG[command["log"]](command["msg"])
            say("logged")
    done.set()


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("name")
    parser.add_argument("--period", type=float, default=0.2)
    parser.add_argument("--debug", action="store_true")
    parser.add_argument("--publish", metavar="TOPIC")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node(args.name, log_level=rospy.DEBUG if args.debug else rospy.INFO, disable_signals=True)
    publisher = None
    if args.publish:
        from std_msgs.msg import String

        publisher = rospy.Publisher(args.publish, String, queue_size=10)
    done = threading.Event()
    threading.Thread(target=read_commands, args=(done,), daemon=True).start()
    say("ready", pid=os.getpid())
    count = 0
    while not done.wait(args.period if args.period > 0 else 0.2):
        if publisher is not None:
            publisher.publish(f"chatter {count}")
        if args.period <= 0:
            continue
        count += 1
        for level, log in LOG.items():
            log(f"{level} {count}")
    rospy.signal_shutdown("stdin closed")


if __name__ == "__main__":
    main()
