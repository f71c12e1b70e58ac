"""console-tui's live intake whose consumer stalls: how much does ROS hold meanwhile?

Runs in a process of its own, so that its RosRuntime is the first to start Fast DDS (which
reads its profiles once per process). The intake's first batch blocks in ``put`` until a
line arrives on stdin, as if the UI had stopped taking records; then everything the
middleware held is taken. Prints ``ready`` once a publisher is matched, then ``received``
with the count, the loss the source saw and which ``burst N`` messages are missing.

    stalled_intake.py EXPECTED [--then-one-more]

``--then-one-more``: once what the middleware held is taken, prints ``drained`` and waits for
a line on stdin, after which the publisher logs one more message (``one more``); ``received``
comes once that message is here. A message lost at the very end of a burst shows only as a
gap before a later one, so with it every loss is counted, not only the ones Fast DDS reported.
"""

import json
import sys
import threading
import time

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.ros.ros2.runtime import RosRuntime
from console_tui.sources.ros2.live_source import LiveLogSource

#: Nothing more arrived or was counted lost for this long: the middleware holds no more.
QUIET_S = 5.0
#: The message the publisher logs after the burst with ``--then-one-more``.
ONE_MORE = "one more"


class StalledQueue(IntakeQueue):
    """Blocks the intake thread in its first ``put`` until released."""

    def __init__(self) -> None:
        super().__init__()
        self.release = threading.Event()
        self.stalled = threading.Event()

    def put(self, batch):
        if not self.stalled.is_set():
            self.stalled.set()
            self.release.wait(60)
        super().put(batch)


def missing_bursts(records, count: int) -> list[list[int]]:
    """Which of ``burst 0`` to ``burst COUNT-1`` did not arrive, as ``[first, last]`` runs."""
    arrived = {int(r.msg.split()[1]) for r in records if r.msg.startswith("burst ")}
    runs: list[list[int]] = []
    for number in sorted(set(range(count)) - arrived):
        if runs and runs[-1][1] == number - 1:
            runs[-1][1] = number
        else:
            runs.append([number, number])
    return runs


def main() -> None:
    runtime = RosRuntime()
    queue = StalledQueue()
    source = LiveLogSource(runtime, queue, topic="/rosout")
    source.start()
    while source.status.publishers < 1:
        time.sleep(0.05)
    print(json.dumps({"event": "ready"}), flush=True)
    queue.stalled.wait()
    print(json.dumps({"event": "stalled"}), flush=True)
    sys.stdin.readline()  # the publisher's burst is over
    queue.release.set()
    expected = int(sys.argv[1])
    # Until every message is here or counted lost, or nothing more came for QUIET_S (Fast DDS
    # may report the last gap late, or never), within a deadline generous for a busy machine.
    records: list = []
    deadline = time.monotonic() + 60
    progress_at, seen = time.monotonic(), (0, 0)
    while len(records) + source.status.lost < expected and time.monotonic() < deadline:
        records += queue.drain()
        now = (len(records), source.status.lost)
        if now != seen:
            progress_at, seen = time.monotonic(), now
        elif time.monotonic() - progress_at > QUIET_S:
            break
        time.sleep(0.05)
    if "--then-one-more" in sys.argv:
        print(json.dumps({"event": "drained", "count": len(records), "lost": source.status.lost}), flush=True)
        sys.stdin.readline()  # the publisher has logged one more
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            taken = queue.drain()
            records += taken
            if any(r.msg == ONE_MORE for r in taken):
                break
            time.sleep(0.05)
    time.sleep(0.5)  # anything beyond what was sent would show
    records += queue.drain()
    received = len(records)
    status = source.status
    print(
        json.dumps(
            {
                "event": "received",
                "count": received,
                "lost": status.lost,
                "lost_qos": status.lost_qos,
                # What each count saw (lost_qos is the larger), for a failure to show.
                "loss_events": source.counts.lost_qos,
                "sequence_gaps": source.counts.lost_gaps,
                "missing": missing_bursts(records, expected - 1)[:20],
            }
        ),
        flush=True,
    )
    source.stop()
    runtime.shutdown()


if __name__ == "__main__":
    main()
