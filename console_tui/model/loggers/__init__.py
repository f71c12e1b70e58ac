"""Logger levels as data, and the logger levels pane's state, without ROS or a screen."""
