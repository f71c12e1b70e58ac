#!/usr/bin/python3
"""Warns, then dies of an exception: its traceback on stderr, exit status 1."""

import time

import rospy

rospy.init_node("dier")
time.sleep(2.0)
rospy.logwarn("about to die")
time.sleep(1.0)
raise ValueError("the dier gave up")
