"""The runtime's Fast DDS reader profile: used only when the user has none of their own."""

import pytest

from console_tui.ros.ros2.rclpy_loader import RosUnavailable
from console_tui.ros.ros2.runtime import FASTDDS_PROFILE, check_domain_id, reader_profile_environment

from support.rosproc import NODES, PATIENCE_S, NodeProcess, wait_until

#: What talker.py says on stderr after a burst through its logger (its ``BURST_LOGGED``).
BURST_LOGGED = "talker: burst logged"
#: What rcl says on stderr of each log message it could not publish on /rosout.
NOT_PUBLISHED = "Failed to publish log message to rosout"


def test_profile_added_under_fast_dds_when_the_user_has_none(tmp_path):
    profile = str(FASTDDS_PROFILE)
    assert reader_profile_environment({}, tmp_path, fast_dds_2=False) == {"FASTDDS_DEFAULT_PROFILES_FILE": profile}
    both = {"FASTDDS_DEFAULT_PROFILES_FILE": profile, "FASTRTPS_DEFAULT_PROFILES_FILE": profile}
    assert reader_profile_environment({}, tmp_path, fast_dds_2=True) == both  # Jazzy's Fast DDS 2.14 reads the second
    assert reader_profile_environment({"ROS_DISTRO": "jazzy"}, tmp_path) == both
    assert reader_profile_environment({"ROS_DISTRO": "kilted"}, tmp_path) == {"FASTDDS_DEFAULT_PROFILES_FILE": profile}
    assert FASTDDS_PROFILE.is_file() and "max_samples" in FASTDDS_PROFILE.read_text()


def test_the_users_own_profiles_and_other_rmws_are_left_alone(tmp_path):
    assert reader_profile_environment({"FASTDDS_DEFAULT_PROFILES_FILE": "/mine.xml"}, tmp_path) == {}
    assert reader_profile_environment({"FASTRTPS_DEFAULT_PROFILES_FILE": "/mine.xml"}, tmp_path) == {}
    assert reader_profile_environment({"RMW_IMPLEMENTATION": "rmw_cyclonedds_cpp"}, tmp_path) == {}
    (tmp_path / "DEFAULT_FASTDDS_PROFILES.xml").write_text("<dds/>")
    assert reader_profile_environment({}, tmp_path) == {}


def burst_into_a_stalled_intake(nodes, count: int, *, keep_it_all: bool = False, then_one_more: bool = False) -> dict:
    """A talker logs one message, on which the intake stalls, then ``count`` more in a burst;
    then the intake goes on. Returns what it says it received (``count``, ``lost``, ``lost_qos``).

    ``keep_it_all``: the talker keeps the whole burst in its writer until the console has it
    (its own /rosout publisher, as deep as the burst, with room for it in Fast DDS).
    ``then_one_more``: once the intake has taken what the middleware held, the talker logs one
    more message, after which every message of the burst that did not come shows as a gap.
    Through the logger (not ``keep_it_all``), ``unpublished`` is how many messages rcl said it
    could not publish on /rosout (Fast DDS refused them): never sent, so never lost by us."""
    if keep_it_all:
        profile = str(NODES / "deep_writer_profile.xml")
        env = {**nodes.env, "FASTDDS_DEFAULT_PROFILES_FILE": profile, "FASTRTPS_DEFAULT_PROFILES_FILE": profile}
        args = ("--own-rosout", str(count + 1))
        talker = nodes.add(NodeProcess("talker.py", "--name", "burst_talker", *args, env=env))
    else:
        talker = nodes.start("talker.py", "--name", "burst_talker")
        talker.count_stderr(BURST_LOGGED, NOT_PUBLISHED)
    talker.expect("ready")
    reader = nodes.start("stalled_intake.py", str(count + 1), *(["--then-one-more"] if then_one_more else []))
    reader.expect("ready")
    talker.send({"cmd": "log", "level": "info", "msg": "first: the intake stalls on it"})
    reader.expect("stalled")
    talker.send({"cmd": "burst", "count": count})
    talker.expect("burst", timeout=2 * PATIENCE_S)
    reader.send({"cmd": "go"})
    if then_one_more:
        reader.expect("drained", timeout=2 * PATIENCE_S)
        talker.send({"cmd": "log", "level": "info", "msg": "one more"})
        talker.expect("logged")
        reader.send({"cmd": "go"})
    got = reader.expect("received", timeout=2 * PATIENCE_S)
    if not keep_it_all:
        assert wait_until(lambda: talker.stderr_counts[BURST_LOGGED] == 1), "the talker's stderr after its burst"
        got["unpublished"] = talker.stderr_counts[NOT_PUBLISHED]
    return got


def test_a_stalled_console_loses_nothing_of_a_burst_of_20000(nodes):
    """The intake stops taking (as when the UI hogs the interpreter) while a node logs
    20,000 messages; Fast DDS holds them all for the console (its default holds 5,000).

    The node keeps the whole burst in its writer until the console has it. A node's rosout
    publisher keeps 1,000: on a busy machine (Jazzy, Fast DDS 2.14) the console was told that
    some of the burst were lost (Fast DDS's message-lost events, as many as the gaps in the
    sequence numbers) while its reader had room for all and none was dropped at its sockets;
    with the node keeping the whole burst nothing is lost. That loss is the node's, and counted."""
    result = burst_into_a_stalled_intake(nodes, 20_000, keep_it_all=True)
    assert (result["count"], result["lost"]) == (20_001, 0), f"{result}"


def test_with_fast_dds_defaults_a_stalled_console_counts_what_it_lost(nodes, tmp_path):
    """With the user's own Fast DDS profile (here: the defaults, 5,000 unread messages) the
    console does not raise the limit; what the middleware could not hold is counted as lost
    in the middleware: received + lost = sent. Sent is what the talker logged less what rcl
    could not publish (on a busy writer Fast DDS refuses some, and rcl says so on stderr);
    messages lost at the very end of the burst show only as a gap before a later message, so
    the talker logs one more once the intake has taken what was held."""
    profile = tmp_path / "defaults.xml"
    profile.write_text('<?xml version="1.0" encoding="UTF-8" ?><dds xmlns="http://www.eprosima.com"><profiles/></dds>')
    # Kilted's Fast DDS 3 reads the first name, Jazzy's Fast DDS 2.14 the second.
    nodes.env = {
        **nodes.env,
        "FASTDDS_DEFAULT_PROFILES_FILE": str(profile),
        "FASTRTPS_DEFAULT_PROFILES_FILE": str(profile),
    }
    result = burst_into_a_stalled_intake(nodes, 10_000, then_one_more=True)
    assert result["count"] < 10_002 and result["lost_qos"] > 0
    assert result["count"] + result["lost_qos"] == 10_002 - result["unpublished"], result
    assert result["lost"] == result["lost_qos"], "nothing else lost: the queue kept up, all decoded"


def test_a_domain_no_dds_can_use_is_refused_before_ros_starts():
    for fine in ({}, {"ROS_DOMAIN_ID": "0"}, {"ROS_DOMAIN_ID": "232"}, {"ROS_DOMAIN_ID": "abc"}):
        check_domain_id(fine)  # text is rcl's to refuse, with its own words
    with pytest.raises(RosUnavailable, match=r"ROS_DOMAIN_ID=233 is out of range: DDS domains go from 0 to 232"):
        check_domain_id({"ROS_DOMAIN_ID": "233"})


def test_the_fast_dds_of_this_rclpy_is_told_without_importing_it():
    import importlib.metadata
    import os

    from console_tui.ros.ros2.runtime import uses_fast_dds_2

    environ = {key: value for key, value in os.environ.items() if key != "ROS_DISTRO"}
    major = int(importlib.metadata.version("rclpy").split(".")[0])
    assert uses_fast_dds_2(environ) == (major < 9)


def test_a_deferred_runtime_starts_rclpy_at_its_first_use_and_the_app_imports_none_before(ros_env):
    """``open_live`` (the app, ``tail``) leaves rclpy unimported in this process: the app's
    own context is made when the logger levels start, after the first frame."""
    code = (
        "import sys\n"
        "from console_tui.model.store.intake_queue import IntakeQueue\n"
        "from console_tui.sources.live import open_live\n"
        "live = open_live(IntakeQueue(), ros=2)\n"
        "assert 'rclpy' not in sys.modules and 'importlib.metadata' not in sys.modules, 'imported'\n"
        "assert live.runtime.ok\n"
        "node = live.runtime.create_node('probe')\n"
        "assert 'rclpy' in sys.modules and node.get_name().startswith('_console_tui_probe')\n"
        "live.close()\n"
        "assert not live.runtime.ok\n"
    )
    import subprocess
    import sys

    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=PATIENCE_S, env=ros_env
    )
    assert result.returncode == 0, result.stderr[-3000:]
