"""A real rospy node for the ROS 1 recording tests (run with the system Python).

Waits until /rosout has two subscribers (the rosout node and 'rosbag record'), publishes
a few /chatter strings, logs one message at each level plus a multi-line one, prints
``{"event": "logged", "messages": [...]}`` with every field, and exits a second later.
"""

from __future__ import annotations

import inspect
import json
import os
import sys
import time

import rospy
import rospy.impl.rosout as rosout
from std_msgs.msg import String

LEVELS = {rospy.logdebug: 1, rospy.loginfo: 2, rospy.logwarn: 4, rospy.logerr: 8, rospy.logfatal: 16}


def main() -> None:
    rospy.init_node("ros1_talker", log_level=rospy.DEBUG)
    chatter = rospy.Publisher("/chatter", String, queue_size=10)
    deadline = time.time() + 30
    while time.time() < deadline:
        publisher = getattr(rosout, "_rosout_pub", None)
        if publisher is not None and publisher.get_num_connections() >= 2 and chatter.get_num_connections() >= 1:
            break
        time.sleep(0.05)
    else:
        print(json.dumps({"event": "error", "what": "nobody subscribed to /rosout"}), flush=True)
        sys.exit(1)
    for index in range(3):
        chatter.publish(String(data=f"chatter {index}"))
    messages = []
    for function in LEVELS:
        messages.append(log_here(function, f"{function.__name__} message"))
    messages.append(log_here(rospy.logwarn, 'multi\nline "quoted"; semi;\nnaïve ✓ 日本語'))
    print(json.dumps({"event": "logged", "messages": messages}), flush=True)
    time.sleep(1.0)


def log_here(function, msg: str) -> dict:
    record = {"level": LEVELS[function], "msg": msg, "file": os.path.basename(__file__), "function": "log_here"}
    record["line"] = inspect.currentframe().f_lineno + 1
    function(msg)
    return record


if __name__ == "__main__":
    main()
