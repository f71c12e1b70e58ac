"""Sources turn ROS messages and files into ``LogRecord`` batches for the model."""
