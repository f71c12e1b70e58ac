#!/usr/bin/python3
"""Prints three lines and logs three messages (its stdout goes to its -stdout.log), then spins."""

import time

import rospy

rospy.init_node("printer")
time.sleep(2.0)  # its /rosout publisher connected before it logs
for number in range(3):
    print(f"printed line {number}")
    rospy.loginfo(f"logged message {number}")
    time.sleep(0.2)
print("printer done")
rospy.spin()
