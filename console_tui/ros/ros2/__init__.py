"""ROS 2 through rclpy: rclpy imported when it can be, and a context of this process's own."""
