#!/usr/bin/env python3
"""Make a big ROS 2 node log file (rcutils' default format) for the history benchmarks.

    .venv/bin/python benchmarks/make_big_log.py /tmp/big.log                  # 20,000,000 lines, about 3 GB
    .venv/bin/python benchmarks/make_big_log.py /tmp/1m.log --records 1000000

The lines are what rcl's file sink writes with ``RCUTILS_CONSOLE_OUTPUT_FORMAT`` unset:
``[INFO] [1700000000.123456789] [robot.nav.node_3]: 17: goal received ...``, 40 nodes,
mostly INFO (5% DEBUG, 10% WARN, 4% ERROR, 1% FATAL: ``store.py``'s mix), messages of
60-120 characters that each carry their number (so no two are alike), stamps 10 µs to 2 ms
apart. Every 100,000th message spans three lines (a message with newlines in it, as rcutils
writes one). Message ``--needle-at`` (default: the 1,000th) holds the word ``NEEDLE``, found
nowhere else: the far match of ``big_file.py``'s search. Never commit the file: it is made in
seconds where it is needed (``big_file.py`` makes it when it is missing).
"""

from __future__ import annotations

import argparse
import random
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from store import WORDS

LEVELS = ["DEBUG"] * 5 + ["INFO"] * 80 + ["WARN"] * 10 + ["ERROR"] * 4 + ["FATAL"]
NEEDLE = "NEEDLE"
#: Lines written at a time.
BLOCK = 20_000


def make(path: Path, records: int, *, needle_at: int = 1_000, seed: int = 1) -> int:
    """Write ``records`` records to ``path``; the bytes written."""
    rng = random.Random(seed)
    nodes = [f"robot.{rng.choice(['nav', 'perception', 'hw', 'ui'])}.node_{i}" for i in range(40)]
    phrases = [" ".join(rng.choice(WORDS) for _ in range(20)) for _ in range(1024)]
    stamp = 1_700_000_000_000_000_000
    written = 0
    with open(path, "wb") as out:
        for start in range(0, records, BLOCK):
            lines = []
            for number in range(start + 1, min(start + BLOCK, records) + 1):
                stamp += 10_000 + (number * 7919) % 2_000_000
                text = f"{number}: {phrases[number * 31 % 1024]}"[: 60 + number % 61]
                if number == needle_at:
                    text = f"{number}: {NEEDLE} the far match"
                elif number % 100_000 == 0:
                    text += "\n  continued on a second line\n  and a third"
                seconds, nanos = divmod(stamp, 1_000_000_000)
                level = LEVELS[(number * 2654435761) % 100]
                lines.append(f"[{level}] [{seconds}.{nanos:09d}] [{nodes[number * 13 % 40]}]: {text}\n")
            data = "".join(lines).encode()
            out.write(data)
            written += len(data)
    return written


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("path", type=Path)
    parser.add_argument("--records", type=int, default=20_000_000)
    parser.add_argument("--needle-at", type=int, default=1_000, help="the message that holds NEEDLE")
    args = parser.parse_args()
    began = time.perf_counter()
    size = make(args.path, args.records, needle_at=args.needle_at)
    seconds = time.perf_counter() - began
    print(f"{args.path}: {args.records:,} records, {size / 1e9:.2f} GB in {seconds:.0f} s")


if __name__ == "__main__":
    main()
