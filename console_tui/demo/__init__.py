"""The built-in demo: real rclpy nodes in child processes, logging like a small robot."""
