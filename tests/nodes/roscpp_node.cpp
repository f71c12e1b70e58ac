// A real roscpp node for the ROS 1 tests and benchmarks (built by tests/support/ros1.py with g++).
//
//   roscpp_node talk NAME PERIOD_MS
//       logs "debug N", "info N", "warn N", "error N", "fatal N" (ROS_DEBUG .. ROS_FATAL) every
//       PERIOD_MS; says {"event": "ready"} on stdout once running.
//   roscpp_node flood TOPIC RATE SECONDS SUBSCRIBERS
//       publishes rosgraph_msgs/Log on TOPIC: RATE a second (0: as fast as it can) for SECONDS,
//       once SUBSCRIBERS subscribers are connected; says {"event": "matched"} then
//       {"event": "done", "sent": N, "seconds": S}.
//
// Either ends when its stdin closes.
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>

#include <atomic>
#include <cstdio>
#include <iostream>
#include <string>
#include <thread>

static std::atomic<bool> stdin_closed(false);

static void watch_stdin() {
  std::string line;
  while (std::getline(std::cin, line)) {
  }
  stdin_closed = true;
}

static int talk(int period_ms) {
  ros::NodeHandle node;
  std::printf("{\"event\": \"ready\", \"pid\": %d}\n", static_cast<int>(getpid()));
  std::fflush(stdout);
  ros::AsyncSpinner spinner(1);  // serves get_loggers / set_logger_level
  spinner.start();
  for (int count = 1; ros::ok() && !stdin_closed; ++count) {
    ROS_DEBUG("debug %d", count);
    ROS_INFO("info %d", count);
    ROS_WARN("warn %d", count);
    ROS_ERROR("error %d", count);
    ROS_FATAL("fatal %d", count);
    ros::WallDuration(period_ms / 1000.0).sleep();
  }
  return 0;
}

static int flood(const std::string& topic, double rate, double seconds, int subscribers) {
  ros::NodeHandle node;
  ros::Publisher publisher = node.advertise<rosgraph_msgs::Log>(topic, 100000);
  std::printf("{\"event\": \"ready\", \"pid\": %d}\n", static_cast<int>(getpid()));
  std::fflush(stdout);
  while (ros::ok() && !stdin_closed && static_cast<int>(publisher.getNumSubscribers()) < subscribers) {
    ros::WallDuration(0.01).sleep();
  }
  std::printf("{\"event\": \"matched\"}\n");
  std::fflush(stdout);
  ros::WallDuration(0.5).sleep();
  rosgraph_msgs::Log message;
  message.level = rosgraph_msgs::Log::INFO;
  message.name = "/flood";
  message.file = "/opt/robot/src/flood_publisher.cpp";
  message.function = "void FloodPublisher::on_timer()";
  message.line = 42;
  message.topics.push_back(topic);
  const ros::WallTime start = ros::WallTime::now();
  long sent = 0;
  while (ros::ok() && !stdin_closed) {
    const double elapsed = (ros::WallTime::now() - start).toSec();
    if (elapsed >= seconds) break;
    long due = rate > 0 ? static_cast<long>(elapsed * rate) + 1 : sent + 100;
    if (sent >= due) {
      ros::WallDuration(0.0005).sleep();
      continue;
    }
    for (; sent < due; ++sent) {
      message.header.stamp = ros::Time::now();
      message.msg = "flood message " + std::to_string(sent) + ": planner cycle took 12.5 ms, 32 poses, ok";
      publisher.publish(message);
    }
  }
  const double took = (ros::WallTime::now() - start).toSec();
  std::printf("{\"event\": \"done\", \"sent\": %ld, \"seconds\": %.3f}\n", sent, took);
  std::fflush(stdout);
  while (ros::ok() && !stdin_closed) ros::WallDuration(0.05).sleep();
  return 0;
}

int main(int argc, char** argv) {
  std::thread(watch_stdin).detach();
  if (argc >= 4 && std::string(argv[1]) == "talk") {
    ros::init(argc, argv, argv[2], ros::init_options::NoSigintHandler);
    return talk(std::stoi(argv[3]));
  }
  if (argc >= 6 && std::string(argv[1]) == "flood") {
    ros::init(argc, argv, "flood", ros::init_options::NoSigintHandler);
    return flood(argv[2], std::stod(argv[3]), std::stod(argv[4]), std::stoi(argv[5]));
  }
  std::fprintf(stderr, "usage: roscpp_node talk NAME PERIOD_MS | flood TOPIC RATE SECONDS SUBSCRIBERS\n");
  return 2;
}
