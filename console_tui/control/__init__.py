"""Control of nodes: commands going out to a ROS graph (logger levels), apart from the intake.

The control every ROS shares (``control_thread.py``: its thread, calls and temporary levels),
with how calls fail (``errors.py``), what it tells its listeners (``events.py``), the graph as
watched (``graph.py``), one call moved on (``calls.py``), helpers over futures
(``futures.py``), and a fleet's robots seen as one (``fleet_control.py``). Each ROS subclasses
the control: ``control/ros2/logger_control.py``, ``control/ros1/logger_control.py``."""
