"""``console-tui ship`` when things go wrong, with a real ROS 2 node: a collector (rotel) away
for 60 s, the shipper killed with SIGKILL, a collector answering 503 with ``Retry-After``, a
spool that fills up. Counted, said, and nothing lost that the spool held."""

from __future__ import annotations

import time

import pytest

from support.otlp_receiver import OtlpReceiver
from support.rosproc import PATIENCE_S, wait_until
from support.rotel import ROTEL_MISSING, Rotel
from support.ship_process import ShipProcess, number_after
from support.warehouse import STORE_MISSING

pytestmark = [
    pytest.mark.ros2,
    pytest.mark.skipif(bool(STORE_MISSING or ROTEL_MISSING), reason=STORE_MISSING or ROTEL_MISSING or "-"),
]

#: How long the collector is away: the issue's 60 s, as it is. The shipper's pauses grow to
#: 30 s (``MAX_BACKOFF_S``), so an outage this long is met with its longest pauses.
OUTAGE_S = 60.0


def reading(line: str) -> bool:
    return "reading /rosout (1 publisher" in line


@pytest.fixture
def talker(nodes):
    process = nodes.start("talker.py", "--name", "faulty")
    process.expect("ready")
    return process


def burst(talker, count: int, tag: str) -> None:
    talker.send({"cmd": "burst", "count": count})
    talker.expect_next("burst", PATIENCE_S)


def bursts(receiver: OtlpReceiver) -> set[str]:
    return {body for body in receiver.bodies() if body.startswith("burst ")}


def test_a_collector_away_for_60_s_loses_nothing(talker, ros_env, tmp_path):
    receiver = OtlpReceiver()
    collector = Rotel(receiver.url, tmp_path)
    ship = ShipProcess(ros_env, collector.url, tmp_path / "spool", "--robot", "r1")
    try:
        ship.wait_for(reading)
        burst(talker, 500, "before")
        assert wait_until(lambda: len(bursts(receiver)) == 500, PATIENCE_S)
        collector.stop()
        gone_at = time.monotonic()
        burst(talker, 2_000, "during")  # "burst 0" .. "burst 1999" again: counted by arrival
        ship.wait_for(lambda line: "retrying in" in line and number_after(line, "spooled") >= 2_000)
        time.sleep(max(OUTAGE_S - (time.monotonic() - gone_at), 0))
        collector.start()
        ship.wait_for(lambda line: number_after(line, "sent") == 2_500 and number_after(line, "spooled") == 0, 120)
    finally:
        code = ship.stop()
        collector.stop()
        receiver.close()
    assert code == 0
    arrived = [body for body in receiver.bodies() if body.startswith("burst ")]
    assert len(arrived) >= 2_500 and len(set(arrived)) == 2_000  # each message of each burst
    assert "lost 0" in ship.lines[-1]


def test_killed_with_sigkill_then_started_again_sends_what_the_spool_held(talker, ros_env, tmp_path):
    receiver = OtlpReceiver()
    receiver.refuse(10**6)  # a collector not taking anything yet
    ship = ShipProcess(ros_env, receiver.url, tmp_path / "spool", "--robot", "r1")
    again = None
    try:
        ship.wait_for(reading)
        burst(talker, 3_000, "spooled")
        ship.wait_for(lambda line: number_after(line, "spooled") == 3_000)
        ship.kill()
        receiver.accept()
        again = ShipProcess(ros_env, receiver.url, tmp_path / "spool", "--robot", "r1")
        again.wait_for(lambda line: number_after(line, "sent") == 3_000 and number_after(line, "spooled") == 0)
    finally:
        ship.kill()
        code = again.stop() if again is not None else None
        receiver.close()
    assert code == 0
    assert bursts(receiver) == {f"burst {i}" for i in range(3_000)}


def test_a_collector_answering_503_with_retry_after_is_waited_for(talker, ros_env, tmp_path):
    receiver = OtlpReceiver()
    receiver.refuse(2, 503, "2")
    ship = ShipProcess(ros_env, receiver.url, tmp_path / "spool", "--robot", "r1")
    try:
        ship.wait_for(reading)
        burst(talker, 100, "busy")
        ship.wait_for(lambda line: number_after(line, "sent") == 100 and number_after(line, "spooled") == 0)
    finally:
        code = ship.stop()
        receiver.close()
    assert code == 0
    assert bursts(receiver) == {f"burst {i}" for i in range(100)}
    statuses = [status for _, status in receiver.requests]
    assert statuses[:3] == [503, 503, 200]
    times = [at for at, _ in receiver.requests]
    assert times[1] - times[0] >= 1.9 and times[2] - times[1] >= 1.9  # as the collector asked
    assert any("retrying in 2 s: HTTP 503: busy" in line for line in ship.lines)


def test_a_full_spool_drops_the_oldest_counted_and_said(talker, ros_env, tmp_path):
    receiver = OtlpReceiver()
    receiver.refuse(10**6)
    ship = ShipProcess(
        ros_env, receiver.url, tmp_path / "spool", "--robot", "r1", "--spool-size", "16K", "--batch", "100"
    )
    try:
        ship.wait_for(reading)
        burst(talker, 4_000, "full")
        line = ship.wait_for(
            lambda line: (
                "dropped from the full spool" in line
                and number_after(line, "spooled") + number_after(line, "lost") == 4_000
            )
        )
        lost = number_after(line, "lost")
        receiver.accept()
        ship.wait_for(lambda line: number_after(line, "spooled") == 0 and number_after(line, "sent") == 4_000 - lost)
    finally:
        code = ship.stop()
        receiver.close()
    assert code == 0
    assert 0 < lost < 4_000
    # What arrived is what the spool held: the newest, none twice.
    assert sorted(bursts(receiver), key=lambda body: int(body.split()[1])) == [f"burst {i}" for i in range(lost, 4_000)]
