"""Recordings for tests and benchmarks, written with rosbags (the library rosbag2 users
script with): /rosout among other topics, in MCAP or sqlite3."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from console_tui.model.store.record import LogRecord


def ros2_log_message(typestore, record: LogRecord):
    Log = typestore.types["rcl_interfaces/msg/Log"]
    Time = typestore.types["builtin_interfaces/msg/Time"]
    sec, nanosec = divmod(record.stamp_ns, 1_000_000_000)
    return Log(
        stamp=Time(sec=sec, nanosec=nanosec),
        level=record.level,
        name=record.node,
        msg=record.msg,
        file=record.file,
        function=record.function,
        line=record.line,
    )


def write_rosbag2(
    path: Path,
    records: Iterable[LogRecord],
    *,
    storage: str = "mcap",
    chatter_every: int = 1,
    image_bytes: int = 0,
    images_per_log: int = 0,
    image_every: int = 1,
    compress: str = "",
    log_topics: tuple[str, ...] = ("/rosout",),
) -> Path:
    """A rosbag2 directory with ``log_topics`` (the records), ``/chatter`` (a String after
    every ``chatter_every`` records) and, when ``image_bytes``, ``images_per_log``
    ``/camera/image`` Images of that size after every ``image_every``-th record. Returns the directory."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.rosbag2.writer import CompressionFormat, CompressionMode
    from rosbags.typesys import Stores, get_typestore

    typestore = get_typestore(Stores.LATEST)
    String = typestore.types["std_msgs/msg/String"]
    plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
    writer = Writer(path, version=9, storage_plugin=plugin)
    if compress:  # "message" (each message zstd) or "storage" (zstd MCAP chunks)
        writer.set_compression(CompressionMode[compress.upper()], CompressionFormat.ZSTD)
    image = None
    with writer:
        log_connections = [
            writer.add_connection(topic, "rcl_interfaces/msg/Log", typestore=typestore) for topic in log_topics
        ]
        chatter = writer.add_connection("/chatter", "std_msgs/msg/String", typestore=typestore)
        if image_bytes:
            camera = writer.add_connection("/camera/image", "sensor_msgs/msg/Image", typestore=typestore)
            image = typestore.serialize_cdr(camera_image(typestore, image_bytes), "sensor_msgs/msg/Image")
        for index, record in enumerate(records):
            data = typestore.serialize_cdr(ros2_log_message(typestore, record), "rcl_interfaces/msg/Log")
            for connection in log_connections:
                writer.write(connection, record.stamp_ns, data)
            if chatter_every and index % chatter_every == 0:
                text = typestore.serialize_cdr(String(data=f"chatter {index}"), "std_msgs/msg/String")
                writer.write(chatter, record.stamp_ns + 1, text)
            images = images_per_log if image is not None and index % image_every == 0 else 0
            for k in range(images):
                writer.write(camera, record.stamp_ns + 2 + k, image)
    return path


def write_ros1_bag(
    path: Path,
    records: Iterable[LogRecord],
    *,
    compression: str = "",
    chatter_every: int = 1,
    image_bytes: int = 0,
    image_every: int = 1,
) -> Path:
    """A ROS 1 bag with /rosout (``rosgraph_msgs/Log``), /chatter (a String after every
    ``chatter_every`` records) and, when ``image_bytes``, a ``/camera/image`` Image of that size
    after every ``image_every``-th record, written by rosbags; ``compression`` ``bz2`` or ``lz4``
    compresses its chunks."""
    from rosbags.rosbag1 import Writer
    from rosbags.typesys import Stores, get_typestore

    from console_tui.model.levels import to_ros1

    typestore = get_typestore(Stores.ROS1_NOETIC)
    Log = typestore.types["rosgraph_msgs/msg/Log"]
    Header = typestore.types["std_msgs/msg/Header"]
    Time = typestore.types["builtin_interfaces/msg/Time"]
    String = typestore.types["std_msgs/msg/String"]
    writer = Writer(path)
    if compression:
        writer.set_compression(Writer.CompressionFormat[compression.upper()])
    with writer:
        rosout = writer.add_connection("/rosout", "rosgraph_msgs/msg/Log", typestore=typestore)
        chatter = writer.add_connection("/chatter", "std_msgs/msg/String", typestore=typestore)
        if image_bytes:
            camera = writer.add_connection("/camera/image", "sensor_msgs/msg/Image", typestore=typestore)
            image = typestore.serialize_ros1(camera_image(typestore, image_bytes, seq=0), "sensor_msgs/msg/Image")
        for index, record in enumerate(records):
            sec, nanosec = divmod(record.stamp_ns, 1_000_000_000)
            message = Log(
                header=Header(seq=index, stamp=Time(sec=sec, nanosec=nanosec), frame_id=""),
                level=to_ros1(record.level),
                name=record.node,
                msg=record.msg,
                file=record.file,
                function=record.function,
                line=record.line,
                topics=["/chatter"],
            )
            writer.write(rosout, record.stamp_ns, typestore.serialize_ros1(message, "rosgraph_msgs/msg/Log"))
            if chatter_every and index % chatter_every == 0:
                text = typestore.serialize_ros1(String(data=f"chatter {index}"), "std_msgs/msg/String")
                writer.write(chatter, record.stamp_ns + 1, text)
            if image_bytes and index % image_every == 0:
                writer.write(camera, record.stamp_ns + 2, image)
    return path


def camera_image(typestore, image_bytes: int, **header: int):
    """A ``sensor_msgs/Image`` of about ``image_bytes`` (rgb8, 1024 pixels wide, the same random
    pixels every time) stamped 0 in frame ``camera``; ``header``: ROS 1's ``seq``."""
    import numpy as np

    Image = typestore.types["sensor_msgs/msg/Image"]
    Header = typestore.types["std_msgs/msg/Header"]
    Time = typestore.types["builtin_interfaces/msg/Time"]
    width = 1024
    height = max(1, image_bytes // (width * 3))
    pixels = np.random.default_rng(1).integers(0, 255, width * height * 3, dtype=np.uint8)
    return Image(
        header=Header(**header, stamp=Time(sec=0, nanosec=0), frame_id="camera"),
        height=height,
        width=width,
        encoding="rgb8",
        is_bigendian=0,
        step=width * 3,
        data=pixels,
    )
