"""The ROS 2 intake: the live log stream, through rclpy."""
