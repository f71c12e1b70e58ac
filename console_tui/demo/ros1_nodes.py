"""ROS 1 demo nodes, one per process: ``/usr/bin/python3 .../ros1_nodes.py NAME``.

Run by the system Python, where Debian's (or a sourced Noetic's) rospy imports, never by
console-tui's own Python. Each node logs what ``behaviours.py`` says through rospy's logging
functions (logger ``rosout``; ``rosout.costmap`` for the planner's costmap), and exits when its
stdin closes, so the demo nodes never outlive the console that started them.
Kept to what Python 3.8 reads.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from functools import partial
from types import SimpleNamespace
from typing import Any


def _logger(rospy: Any, name: str = "") -> Any:
    """rclpy's logger methods as rospy's own functions (partials add no Python frame, so rospy
    finds the behaviour's file, function and line as the caller)."""
    named = {"logger_name": name} if name else {}
    return SimpleNamespace(
        debug=partial(rospy.logdebug, **named),
        info=partial(rospy.loginfo, **named),
        warning=partial(rospy.logwarn, **named),
        error=partial(rospy.logerr, **named),
        fatal=partial(rospy.logfatal, **named),
        get_child=lambda child: _logger(rospy, f"{name}.{child}" if name else child),
    )


def run(name: str) -> int:
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    from console_tui.demo.behaviours import DEMO_NODES

    node_name, namespace, set_up = DEMO_NODES[name]

    def exit_when_parent_goes() -> None:
        sys.stdin.read()
        # The console quit or died, and stops the demo's own master at the same time: there
        # is nothing to unregister from (and rospy's init_node would retry a master that went
        # away for ever), so the node ends at once and quitting does not wait for it.
        os._exit(0)

    threading.Thread(target=exit_when_parent_goes, daemon=True).start()
    if namespace:
        os.environ["ROS_NAMESPACE"] = namespace
    import rospy

    rospy.init_node(node_name, disable_signals=True)
    timers: list[Any] = []

    def every(seconds: float, callback: Any) -> None:
        timers.append(rospy.Timer(rospy.Duration(seconds), lambda _event: callback()))

    set_up(_logger(rospy), every)
    while not rospy.is_shutdown():  # until rospy is told to shut down (rosnode kill)
        time.sleep(0.2)
    for timer in timers:
        timer.shutdown()
    # rospy unregisters from the master as it shuts down, with no timeout: a master that is
    # itself going away would hold this node forever.
    closing = threading.Thread(target=rospy.signal_shutdown, args=("asked to shut down",), daemon=True)
    closing.start()
    closing.join(2.0)
    sys.stdout.flush()
    os._exit(0)


if __name__ == "__main__":
    raise SystemExit(run(sys.argv[1]) if len(sys.argv) == 2 else 2)
