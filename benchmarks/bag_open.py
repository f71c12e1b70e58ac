"""Opening the log messages of recordings full of images: time and bytes read.

    .venv/bin/python benchmarks/bag_open.py [--image-mb 300] [--logs-per-image 10] [--dir DIR]

Writes three recordings of the same content -- ``/camera/image`` (1 MB images, about
``--image-mb`` of them), ``/rosout`` (``--logs-per-image`` log messages after each image)
and ``/chatter`` -- as rosbag2 MCAP and sqlite3 (with rosbags) and as a ROS 1 bag
(rosbags' ROS 1 writer, uncompressed chunks as 'rosbag record' writes by default).
Then, for each, with the file dropped from the page cache first (posix_fadvise), it
opens the log messages with console-tui (``open_log_file`` + every batch) and, for
contrast, with the plain library call that reads whole chunks (rosbags
``Reader.messages`` on the log connections), and prints: file size, log messages,
seconds, and bytes read (``rchar``: bytes the process asked read(2) for; ``disk``:
``read_bytes``, what came from storage).
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from _report import machine_line

from console_tui.model.store.record import LogRecord
from console_tui.sources.files import open_log_file

from support.recordings import write_ros1_bag, write_rosbag2

IMAGE_BYTES = 1_000_000


def io_counters() -> tuple[int, int]:
    with open("/proc/self/io") as stats:
        values = dict(line.split(": ") for line in stats.read().splitlines())
    return int(values["rchar"]), int(values["read_bytes"])


def drop_cache(path: Path) -> None:
    files = [path] if path.is_file() else [p for p in path.rglob("*") if p.is_file()]
    for file in files:
        fd = os.open(file, os.O_RDONLY)
        try:
            os.fsync(fd)
            os.posix_fadvise(fd, 0, 0, os.POSIX_FADV_DONTNEED)
        finally:
            os.close(fd)


def measure(path: Path, read) -> tuple[int, float, int, int]:
    drop_cache(path)
    rchar0, disk0 = io_counters()
    start = time.perf_counter()
    count = read(path)
    seconds = time.perf_counter() - start
    rchar1, disk1 = io_counters()
    return count, seconds, rchar1 - rchar0, disk1 - disk0


def read_with_console_tui(path: Path) -> int:
    with open_log_file(path) as log_file:
        return sum(len(batch) for batch in log_file.batches())


def read_with_library(path: Path) -> int:
    if path.suffix == ".bag":
        from rosbags.rosbag1 import Reader
    else:
        from rosbags.rosbag2 import Reader
    with Reader(path) as reader:
        wanted = [c for c in reader.connections if c.topic == "/rosout"]
        return sum(1 for _ in reader.messages(connections=wanted))


def size_of(path: Path) -> int:
    return path.stat().st_size if path.is_file() else sum(p.stat().st_size for p in path.rglob("*") if p.is_file())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--image-mb", type=int, default=300, help="about how many MB of images (1 MB each)")
    parser.add_argument("--logs-per-image", type=int, default=10)
    parser.add_argument("--dir", help="where to write the recordings (default: a temporary directory, removed)")
    args = parser.parse_args()

    base = Path(args.dir) if args.dir else Path(tempfile.mkdtemp(prefix="bag_open."))
    base.mkdir(parents=True, exist_ok=True)
    count = args.image_mb * args.logs_per_image
    records = [
        LogRecord(
            1_700_000_000_000_000_000 + i * 10_000_000,
            (10, 20, 30, 40, 50)[i % 5],
            f"node{i % 7}",
            f"log message {i}: something happened",
            "/ws/src/node.py",
            "tick",
            100 + i % 50,
        )
        for i in range(count)
    ]
    try:
        print(f"writing recordings in {base} ...", file=sys.stderr)
        recordings = {
            "rosbag2 MCAP": _rosbag2(base / "mcap", records, "mcap", args.logs_per_image),
            "rosbag2 sqlite3": _rosbag2(base / "sqlite3", records, "sqlite3", args.logs_per_image),
            "ROS 1 bag": write_ros1_bag(
                base / "run.bag",
                records,
                chatter_every=args.logs_per_image,
                image_bytes=IMAGE_BYTES,
                image_every=args.logs_per_image,
            ),
        }
        rows = []
        for name, path in recordings.items():
            size = size_of(path)
            for reader_name, read in (
                ("console-tui", read_with_console_tui),
                ("rosbags messages()", read_with_library),
            ):
                got, seconds, rchar, disk = measure(path, read)
                rows.append((name, reader_name, size, got, seconds, rchar, disk))
        print("\n" + machine_line())
        header = ("recording", "reader", "file MB", "log msgs", "seconds", "read MB", "% of file", "disk MB")
        print("| " + " | ".join(header) + " |")
        print("|" + "---|" * len(header))
        for name, reader_name, size, got, seconds, rchar, disk in rows:
            print(
                f"| {name} | {reader_name} | {size / 1e6:.0f} | {got:,} | {seconds:.2f} | {rchar / 1e6:.1f} | "
                f"{100 * rchar / size:.1f}% | {disk / 1e6:.1f} |"
            )
    finally:
        if not args.dir:
            shutil.rmtree(base, ignore_errors=True)


def _rosbag2(path: Path, records: list[LogRecord], storage: str, logs_per_image: int) -> Path:
    """Records on /rosout with a 1 MB image after every ``logs_per_image`` of them."""
    return write_rosbag2(
        path,
        records,
        storage=storage,
        chatter_every=logs_per_image,
        image_bytes=IMAGE_BYTES,
        images_per_log=1,
        image_every=logs_per_image,
    )


if __name__ == "__main__":
    main()
