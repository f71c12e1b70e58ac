"""The topics ROS log messages travel on, in ROS 1 and ROS 2 alike."""

from __future__ import annotations

#: Every node publishes its log messages here.
ROSOUT = "/rosout"
#: The rosout node's republished stream of every node's messages (ROS 1; ``console-tui rosout`` in ROS 2).
ROSOUT_AGG = "/rosout_agg"
