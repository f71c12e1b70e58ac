"""Logger levels of a ROS graph's nodes: the control every ROS shares (``control.py``, its
thread, calls and temporary levels), with how calls fail (``errors.py``), what it tells its
listeners (``events.py``), the graph as watched (``graph.py``), one call moved on
(``calls.py``), helpers over futures (``futures.py``), and a fleet's robots seen as one
(``fleet_control.py``). Each ROS subclasses the control: ``sources/ros2/logger_control.py``,
``sources/ros1/logger_control.py``."""
