"""The direct rosgraph_msgs/Log decoder field for field against genpy, the serializer rospy uses."""

from __future__ import annotations

import json
import random
import subprocess
import textwrap

import pytest

from console_tui.model.formats.ros1_log_msg import MD5SUM, Ros1LogDecoder, encode_log

from support.formats import random_ros1_log
from support.ros1 import SYSTEM_PYTHON, ros1_missing

pytestmark = pytest.mark.ros1

GENPY = textwrap.dedent(
    """
    import io, json, sys
    import rospy
    from rosgraph_msgs.msg import Log
    from std_msgs.msg import Header
    out = {"md5sum": Log._md5sum, "messages": [], "decoded": []}
    request = json.load(sys.stdin)
    for m in request["make"]:
        stamp = rospy.Time(*divmod(m["stamp_ns"], 1_000_000_000))
        log = Log(header=Header(seq=m["seq"], stamp=stamp, frame_id=m["frame_id"]),
                  level=m["level"], name=m["name"], msg=m["msg"], file=m["file"], function=m["function"],
                  line=m["line"], topics=m["topics"])
        buffer = io.BytesIO()
        log.serialize(buffer)
        out["messages"].append(buffer.getvalue().hex())
    for data in request["read"]:
        log = Log().deserialize(bytes.fromhex(data))
        out["decoded"].append([log.header.stamp.secs, log.header.stamp.nsecs, log.level, log.name, log.msg,
                               log.file, log.function, log.line, list(log.topics)])
    print(json.dumps(out))
    """
)


def test_decoder_and_encoder_agree_with_genpy():
    reason = ros1_missing()
    if reason:
        pytest.skip(reason)
    rng = random.Random(1)
    made = [random_ros1_log(rng) for _ in range(200)]
    ours = [encode_log(**m) for m in made]
    result = subprocess.run(
        [SYSTEM_PYTHON, "-c", GENPY],
        input=json.dumps({"make": made, "read": [data.hex() for data in ours]}),
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 0, result.stderr
    answer = json.loads(result.stdout)
    assert answer["md5sum"] == MD5SUM
    decoder = Ros1LogDecoder()
    for m, data, mine in zip(made, answer["messages"], ours, strict=True):
        assert bytes.fromhex(data) == mine  # our encoder writes what genpy writes
        record = decoder.decode(bytes.fromhex(data), "/rosout")
        assert (record.stamp_ns, record.node, record.msg, record.file, record.function, record.line) == (
            m["stamp_ns"],
            m["name"],
            m["msg"],
            m["file"],
            m["function"],
            m["line"],
        )
        assert record.level == {1: 10, 2: 20, 4: 30, 8: 40, 16: 50}[m["level"]]
        assert record.topics == ",".join(m["topics"])
    assert [d[3:5] for d in answer["decoded"]] == [[m["name"], m["msg"]] for m in made]
