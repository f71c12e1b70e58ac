"""Logger levels of ROS 2 nodes, through their logger services (rclpy)."""
