#!/usr/bin/env python3
"""What a ROS 1 message costs in the intake process before it is packed, stage by stage (no ROS).

The flood publisher's ``rosgraph_msgs/Log`` (about 200 bytes framed, one node, one log
statement) is serialized N times and cut into receive-sized chunks (``RECV_BYTES``); then,
chunk after chunk as the intake does, each stage is timed on its own: decoding the frames
(Python's decoder alone, then with the frame loop in C), making columns and dropping repeats.
What follows, the same for ROS 1 and ROS 2 (packing, the pipe, unpacking, storing, drawing):
``benchmarks/cost.py``. Young garbage collections run as in the intake process (``--gc
intake``) or at Python's defaults (``--gc default``, as the intake process had them before).
Each figure is the best of ``--repeat`` passes, in µs of the thread's CPU a message.

    .venv/bin/python benchmarks/ros1_stages.py
    .venv/bin/python benchmarks/ros1_stages.py --gc default
"""

from __future__ import annotations

import argparse
import gc
import struct
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).parent))

from _report import machine_line, table  # noqa: E402

from console_tui.model.formats.ros1_log_msg import Ros1LogDecoder, encode_log  # noqa: E402
from console_tui.model.store.record_batch import ColumnsBuilder  # noqa: E402
from console_tui.sources.intake_process.child import YOUNG_COLLECTION_THRESHOLD  # noqa: E402
from console_tui.sources.ros1 import compiled_frames  # noqa: E402
from console_tui.sources.ros1.dedupe import Deduplicator  # noqa: E402
from console_tui.sources.ros1.socket_reader import RECV_BYTES  # noqa: E402

STAGES = ("decode", "columns", "dedupe")


def flood_stream(count: int) -> bytes:
    """``count`` framed Log messages as tests/nodes/roscpp_node.cpp's flood sends them."""
    frames = []
    for number in range(count):
        body = encode_log(
            stamp_ns=1_700_000_000_000_000_000 + number * 10_000,
            level=2,
            name="/flood",
            msg=f"flood message {number}: planner cycle took 12.5 ms, 32 poses, ok",
            file="/opt/robot/src/flood_publisher.cpp",
            function="void FloodPublisher::on_timer()",
            line=42,
            topics=["/console_tui_bench_log"],
            seq=number,
        )
        frames.append(struct.pack("<I", len(body)) + body)
    return b"".join(frames)


def one_pass(chunks: list[bytes], frame_loop: object) -> dict[str, float]:
    """Seconds spent in each stage over every chunk."""
    decoder = Ros1LogDecoder(frame_loop=frame_loop)  # type: ignore[arg-type]
    dedupe = Deduplicator()
    spent = dict.fromkeys(STAGES, 0.0)
    clock = time.thread_time  # this thread's CPU: what a stage costs, not how long the machine made it wait
    pending = b""
    for chunk in chunks:
        began = clock()
        data = pending + chunk if pending else chunk
        builder = ColumnsBuilder()
        end = decoder.decode_frames(data, 0, "/rosout", builder, lambda _data, error: None)
        pending = data[end:]
        decoded = clock()
        columns = builder.columns()
        made = clock()
        dedupe.filter(columns, 0.0)
        filtered = clock()
        spent["decode"] += decoded - began
        spent["columns"] += made - decoded
        spent["dedupe"] += filtered - made
    return spent


def best_of(repeat: int, chunks: list[bytes], frame_loop: object) -> dict[str, float]:
    best: dict[str, float] = {}
    for _ in range(repeat):
        spent = one_pass(chunks, frame_loop)
        best = spent if not best else {stage: min(best[stage], spent[stage]) for stage in STAGES}
    return best


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--messages", type=int, default=200_000, help="messages a pass (default 200,000)")
    parser.add_argument("--repeat", type=int, default=5, help="passes; the best is shown (default 5)")
    parser.add_argument("--gc", choices=("intake", "default"), default="intake", help="young collections")
    args = parser.parse_args()
    loop, note = compiled_frames.load()
    stream = flood_stream(args.messages)
    chunks = [stream[start : start + RECV_BYTES] for start in range(0, len(stream), RECV_BYTES)]
    if args.gc == "intake":
        gc.freeze()
        _, middle, old = gc.get_threshold()
        gc.set_threshold(YOUNG_COLLECTION_THRESHOLD, middle, old)
    print(machine_line())
    print(f"{len(stream) / args.messages:.0f} bytes a framed message, {len(chunks)} chunks of {RECV_BYTES:,} bytes")
    paths = {"Python": best_of(args.repeat, chunks, None)}
    if loop is not None:
        paths["frame loop in C"] = best_of(args.repeat, chunks, loop)
    else:
        print(f"the frame loop in C: not built ({note})")
    rows = [[stage, *(f"{p[stage] / args.messages * 1e6:.3f}" for p in paths.values())] for stage in STAGES]
    rows.append(["all three", *(f"{sum(p.values()) / args.messages * 1e6:.3f}" for p in paths.values())])
    print(f"\nµs a message, best of {args.repeat}, young collections: {args.gc}:\n")
    print(table(["stage", *(f"decoded by {name}" for name in paths)], rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
