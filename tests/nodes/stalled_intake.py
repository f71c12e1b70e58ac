"""console-tui's live intake whose consumer stalls: how much does ROS hold meanwhile?

Runs in a process of its own, so that its RosRuntime is the first to start Fast DDS (which
reads its profiles once per process). The intake's first batch blocks in ``put`` until a
line arrives on stdin, as if the UI had stopped taking records; then everything the
middleware held is taken. Prints ``ready`` once a publisher is matched, then ``received``
with the count and the loss the source saw.
"""

import json
import sys
import threading
import time

from console_tui.model.intake_queue import IntakeQueue
from console_tui.sources.ros2.live_source import LiveLogSource
from console_tui.sources.ros2.runtime import RosRuntime


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
    deadline = time.monotonic() + 20
    received = 0
    while time.monotonic() < deadline and received < expected:
        received += len(queue.drain())
        time.sleep(0.05)
    time.sleep(0.5)
    received += len(queue.drain())
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
            }
        ),
        flush=True,
    )
    source.stop()
    runtime.shutdown()


if __name__ == "__main__":
    main()
