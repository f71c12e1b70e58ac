"""Logger levels of ROS 1 nodes, through their ``get_loggers``/``set_logger_level`` services."""
