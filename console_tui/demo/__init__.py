"""The built-in demo: real nodes in child processes, logging like a small robot (rclpy nodes,
or with ``--ros1`` rospy nodes on a roscore of their own)."""
