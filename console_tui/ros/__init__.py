"""Where the ROS graphs are and how to talk to them, for the intake and the control alike:
which ROS (``ros_version.py``), a fleet's robots (``fleet.py``), the ROS log directory
(``log_dir.py``), ROS 1's wire (``ros1/``) and ROS 2's rclpy runtime (``ros2/``)."""
