"""The intake: sources turn ROS messages and files into ``LogRecord`` batches for the model
(ROS 2, ROS 1, files, a fleet, the intake process)."""
