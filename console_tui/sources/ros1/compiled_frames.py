"""The ROS 1 frame loop in C (``frame_loop.c``), compiled on this machine the first time it is needed.

Decoding a ``rosgraph_msgs/Log`` frame in Python costs about a microsecond: most of what
the ROS 1 intake spends a message. The loop in C reads the frames whose node and log
statement the Python decoder has cached (nearly all of them) for a fifth of that, and hands
every other frame to the Python decoder (``Ros1LogDecoder.decode_frames``), which keeps the
rules for what is readable. It needs only a C compiler and Python's headers, and is built and
cached as ``c_build`` does for the intake's loops in C. Without them (or with
``CONSOLE_TUI_COMPILED_FRAMES=0``) the Python decoder reads every frame.

The build runs beside the intake: ``start_loading()`` starts it, ``loaded_now()`` says
whether it is done, and meanwhile the Python decoder reads the frames.
"""

from __future__ import annotations

import hashlib
import os
import sys
import threading
from pathlib import Path

from ...model.formats.ros1_log_msg import FrameLoop
from ...system import c_build

SOURCE = Path(__file__).with_name("frame_loop.c")
MODULE = "console_tui_frame_loop"
STEM = "frame_loop"
#: ``0`` keeps the Python decoder for every frame (to compare the two, or if the C loop misbehaves).
SWITCH = "CONSOLE_TUI_COMPILED_FRAMES"
BUILD_TIMEOUT_S = 60.0

_loaded: tuple[FrameLoop | None, str] | None = None
_build_lock = threading.Lock()
_state_lock = threading.Lock()
_loading: threading.Thread | None = None


def load() -> tuple[FrameLoop | None, str]:
    """The compiled frame loop and ``""`` (or a note on how it was built), or ``None`` and
    why not (built once, then cached)."""
    global _loaded
    with _build_lock:
        if _loaded is None:
            try:
                _loaded = _load()
            except Exception as error:  # never worth stopping the intake for
                _loaded = None, f"{type(error).__name__}: {error}"
        return _loaded


def start_loading() -> None:
    """What ``load()`` does, on a thread of its own (once); ``loaded_now()`` says when it is done."""
    global _loading
    with _state_lock:
        if _loaded is not None or _loading is not None:
            return
        _loading = threading.Thread(target=load, name="console-tui-frame-loop-build", daemon=True)
    _loading.start()


def loaded_now() -> tuple[FrameLoop | None, str] | None:
    """What ``load()`` gave, or ``None`` while it is still building."""
    return _loaded


def _load() -> tuple[FrameLoop | None, str]:
    if os.environ.get(SWITCH, "1") == "0":
        return None, f"{SWITCH}=0"
    module, note = c_build.load_or_build(f"{STEM}_{build_key()}{c_build.suffix()}", STEM, MODULE, build)
    return (None if module is None else module.frames), note


def build_key() -> str:
    """What the built file depends on: the C source and this Python."""
    digest = hashlib.sha256(SOURCE.read_bytes())
    digest.update(f"{sys.version}|{c_build.suffix()}".encode())
    return digest.hexdigest()[:16]


def build(target: Path) -> str:
    """Compile ``frame_loop.c`` into ``target``; ``""``, or what went wrong."""
    return c_build.compile_module(SOURCE, target, BUILD_TIMEOUT_S)
