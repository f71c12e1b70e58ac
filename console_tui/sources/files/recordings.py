"""Opening recordings: rosbag2 (MCAP, sqlite3, a directory of either) and ROS 1 bags.

``open_recording`` picks the reader: ``mcap_file`` (MCAP, index-guided), ``rosbag2_file``
(sqlite3 and compressed rosbag2, through ``rosbags``), ``ros1_bag_file``; what they share is
in ``recording_file``. Where the index gives a log message's exact place in an uncompressed
chunk (ROS 1 bags, MCAP with message indexes), just that message is read, so a recording full
of images costs little more than its log messages. Compressed chunks that hold log messages
are read whole (decompression needs the whole chunk).
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from ...model.formats import FormatError
from ...model.store.record import LogRecord
from .log_file import Cancel, LogFile
from .mcap_file import McapFile
from .recording_file import MISSING_EXTRA
from .ros1_bag_file import Ros1BagFile
from .rosbag2_file import Rosbag2File


class ChainedFile(LogFile):
    """Several files read one after another as one (the files of a split rosbag2 recording)."""

    def __init__(self, path: Path, source: str, parts: list[LogFile], kind: str, title: str) -> None:
        super().__init__(path, source)
        self.parts = parts
        self.kind, self.title, self.unit = kind, title, "files"
        self.total = len(parts)
        self.topics = sorted({t for p in parts for t in getattr(p, "topics", [])})
        for part in parts:
            part.problems = self.problems

    @property
    def fraction(self) -> float:
        return (self.done + (self.parts[self.done].fraction if self.done < len(self.parts) else 0)) / self.total

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        for part in self.parts:
            yield from part.batches(cancel)
            self.done += 1
            if cancel is not None and cancel.is_set():
                return

    def close(self) -> None:
        for part in self.parts:
            part.close()


def open_recording(path: Path, source: str, kind: str) -> LogFile:
    """Open a recording of ``kind`` (``ros1-bag``, ``mcap``, ``sqlite3``, ``rosbag2`` for a
    directory). Raises ``FormatError`` with a message for the user."""
    try:
        import mcap  # noqa: F401
        import rosbags  # noqa: F401
    except ImportError:
        raise FormatError(f"{path.name}: {MISSING_EXTRA}") from None
    if kind == "ros1-bag":
        return Ros1BagFile(path, source)
    if kind == "mcap":
        return McapFile(path, source)
    if kind == "sqlite3":
        if path.suffix != ".db3":
            raise FormatError(f"{path.name}: an SQLite database, but not a rosbag2 .db3 file")
        return Rosbag2File(path, source)
    if kind == "rosbag2":
        return _open_rosbag2_directory(path, source)
    raise FormatError(f"{path.name}: unknown recording kind {kind!r}")


def _open_rosbag2_directory(path: Path, source: str) -> LogFile:
    """A rosbag2 directory: plain MCAP files are read with the index-guided reader,
    anything else (sqlite3, compressed) through rosbags."""
    metadata_path = path / "metadata.yaml"
    if not metadata_path.exists():
        mcaps = sorted(path.glob("*.mcap"))
        if len(mcaps) == 1:
            return McapFile(mcaps[0], source)
        raise FormatError(f"{path.name}: a directory, but not a rosbag2 recording (no metadata.yaml)")
    from ruamel.yaml import YAML

    try:
        info = YAML(typ="safe").load(metadata_path.read_text())["rosbag2_bagfile_information"]
        storage = info.get("storage_identifier", "")
        compressed = (info.get("compression_mode") or "").lower() not in ("", "none")
        files = [path / Path(name).name for name in info.get("relative_file_paths", [])]
    except Exception as error:
        raise FormatError(f"{path.name}: its metadata.yaml is unreadable: {error}") from None
    if storage == "mcap" and not compressed and files and all(f.exists() for f in files):
        parts: list[LogFile] = [McapFile(f, source) for f in files]
        return parts[0] if len(parts) == 1 else ChainedFile(path, source, parts, "mcap", "rosbag2 MCAP")
    return Rosbag2File(path, source)
