"""ROS 1 spoken natively (no rospy): the environment, XML-RPC to the master and to nodes, our
own slave API, TCPROS for topics and services. Needs the standard library only, so it works
against any ROS 1 master from any Python 3.10+, with nothing from ROS 1 installed."""
