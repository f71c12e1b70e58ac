"""The ROS 1 intake, without rospy: the graph thread, the topics' connections, one thread
reading their sockets (frames decoded in C when built), repeats dropped."""
