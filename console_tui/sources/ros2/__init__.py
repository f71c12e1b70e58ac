"""The ROS 2 source: the live log stream and the graph, through rclpy."""
