"""The ROS 1 frame loop in C (``compiled_frames``): it reads what the Python decoder reads,
refuses what it refuses, stops where it stops; it is built once into the cache, and without a
compiler (or switched off) the Python decoder reads every frame. No ROS is needed."""

from __future__ import annotations

import random
import socket
import struct
import time

import pytest

from console_tui.model.formats.ros1_log_msg import Ros1LogDecoder, Ros1LogError, encode_log
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record_batch import ColumnsBuilder
from console_tui.sources.ros1 import compiled_frames
from console_tui.sources.ros1.socket_reader import Connection, Ros1Intake

from support.compiled import as_in_a_new_process, built_once_then_cached, not_loaded_from_a_shared_cache
from support.formats import random_ros1_log


@pytest.fixture
def fresh(monkeypatch, tmp_path):
    """``compiled_frames`` as in a new process, with an empty cache in ``tmp_path``."""
    return as_in_a_new_process(compiled_frames, monkeypatch, tmp_path)


@pytest.fixture(scope="module")
def frame_loop(tmp_path_factory):
    saved = compiled_frames._loaded
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.mktemp("cache")))
        patch.delenv(compiled_frames.SWITCH, raising=False)
        compiled_frames._loaded = None
        loop, problem = compiled_frames.load()
        compiled_frames._loaded = saved
    if loop is None:
        pytest.skip(f"the frame loop cannot be built here: {problem}")
    return loop


def _framed(message: bytes) -> bytes:
    return struct.pack("<I", len(message)) + message


def _hostile_stream(seed: int, count: int) -> bytes:
    """Random Log messages, some cut short, some with bytes changed, some repeated, framed."""
    rng = random.Random(seed)
    frames: list[bytes] = []
    for _ in range(count):
        data = encode_log(**random_ros1_log(rng))
        roll = rng.random()
        if roll < 0.1:
            data = data[: rng.randint(0, len(data))]
        elif roll < 0.25:
            changed = bytearray(data)
            for _ in range(rng.randint(1, 4)):
                changed[rng.randrange(len(changed))] = rng.getrandbits(8)
            data = bytes(changed)
        frames.append(_framed(data))
        if rng.random() < 0.5:
            frames.append(frames[-1])  # the caches serve the repeat
    return b"".join(frames)


def _read(stream: bytes, loop, cut: int, max_length: int = 1 << 20):
    """What a decoder (``loop``: the frame loop, or None) makes of ``stream`` received ``cut``
    bytes at a time: the records, the refusals, the bytes left, and the error that broke it."""
    decoder = Ros1LogDecoder(intern_limit=40, frame_loop=loop)  # small caches: they start over
    batch = ColumnsBuilder()
    refused: list[tuple[bytes, str]] = []
    pending = b""
    broke = ""
    for start in range(0, len(stream), cut):
        data = pending + stream[start : start + cut]
        try:
            end = decoder.decode_frames(data, 0, "/t", batch, lambda d, e: refused.append((d, str(e))), max_length)
        except Ros1LogError as error:
            broke = str(error)
            break
        pending = data[end:]
    return batch.columns().records(), refused, pending, broke


@pytest.mark.parametrize("cut", [1, 7, 300, 1 << 18])
def test_it_reads_and_refuses_what_the_python_decoder_does(frame_loop, cut):
    stream = _hostile_stream(seed=cut, count=600 if cut > 1 else 60)
    python = _read(stream, None, cut)
    assert python[1], "the stream should hold messages to refuse"
    assert _read(stream, frame_loop, cut) == python


def test_a_stream_broken_by_an_absurd_length_breaks_as_in_python(frame_loop):
    good = _framed(encode_log(stamp_ns=3, level=2, name="/n", msg="before"))
    stream = good * 3 + struct.pack("<I", 1 << 30) + good
    python = _read(stream, None, len(stream))
    assert python[3].startswith("a message of 1,073,741,824 bytes announced")
    assert _read(stream, frame_loop, len(stream)) == python


def test_too_short_frames_and_huge_claims_inside_a_frame_are_refused(frame_loop):
    good = encode_log(stamp_ns=1, level=4, name="/n", msg="ok", file="f", function="g", topics=["/x"])
    lying_name = good[:17] + struct.pack("<I", 0xFFFFFFFF) + good[21:]  # len(name) past the end
    lying_frame_id = good[:12] + struct.pack("<I", 0xFFFFFFF0) + good[16:]
    stream = b"".join(_framed(d) for d in (good, b"\x00" * 10, lying_name, lying_frame_id, good, b""))
    records, refused, pending, broke = _read(stream, frame_loop, len(stream))
    assert [r.msg for r in records] == ["ok", "ok"] and records[0].topics == "/x"
    assert len(refused) == 4 and pending == b"" and broke == ""
    assert _read(stream, None, len(stream)) == (records, refused, pending, broke)


def test_repeated_strings_are_shared(frame_loop):
    decoder = Ros1LogDecoder(frame_loop=frame_loop)
    batch = ColumnsBuilder()
    message = _framed(encode_log(stamp_ns=5, level=2, name="/node", msg="a", file="f.cpp", function="fn"))
    decoder.decode_frames(message * 3, 0, "/t", batch, lambda _d, e: pytest.fail(str(e)))
    assert len(batch) == 3 and batch.nodes[0] is batch.nodes[2] and batch.tails[0] is batch.tails[2]
    assert batch.stamps == [5, 5, 5] and batch.levels == [20, 20, 20] and batch.sources == ["/t"] * 3


def test_it_is_built_once_and_then_loaded_from_the_cache(fresh, monkeypatch):
    built_once_then_cached(compiled_frames, fresh, monkeypatch, "frame_loop")


def test_without_a_compiler_it_says_why_and_python_decodes(fresh, monkeypatch):
    monkeypatch.setenv("CC", "/nonexistent/cc")
    assert compiled_frames.load() == (None, "no C compiler (cc)")
    intake = Ros1Intake(IntakeQueue())
    intake.start()
    try:
        deadline = time.monotonic() + 60
        while intake._compiled_pending:
            assert time.monotonic() < deadline
            time.sleep(0.01)
        assert not intake.compiled and intake.compiled_note == "no C compiler (cc)"
    finally:
        intake.stop()


def test_it_can_be_switched_off(fresh, monkeypatch):
    monkeypatch.setenv(compiled_frames.SWITCH, "0")
    assert compiled_frames.load() == (None, "CONSOLE_TUI_COMPILED_FRAMES=0")


def test_a_cache_writable_by_others_is_not_loaded_from(fresh):
    name = f"frame_loop_{compiled_frames.build_key()}{compiled_frames.c_build.suffix()}"
    not_loaded_from_a_shared_cache(compiled_frames, fresh, name)


def test_through_the_loop_a_broken_stream_ends_its_connection_only(frame_loop, monkeypatch):
    """Over real sockets, the frame loop in use: a message that cannot be read is counted and
    skipped, a length no Log has ends that publisher's connection, and another publisher's
    messages go on arriving."""
    monkeypatch.setattr(compiled_frames, "_loaded", (frame_loop, ""))
    queue = IntakeQueue()
    closed: list[tuple[str, str]] = []
    intake = Ros1Intake(queue, on_closed=lambda c, reason: closed.append((c.caller_id, reason)))
    intake.start()
    bad_ours, bad = socket.socketpair()
    good_ours, good = socket.socketpair()
    records: list = []

    def arrived(count: int) -> bool:
        deadline = time.monotonic() + 60
        while len(records) < count and time.monotonic() < deadline:
            records.extend(queue.drain())
            time.sleep(0.01)
        return len(records) >= count

    try:
        intake.add(Connection(bad_ours, "/rosout", "http://bad:1/", "/bad"))
        intake.add(Connection(good_ours, "/rosout", "http://good:1/", "/good"))
        message = encode_log(stamp_ns=1, level=2, name="/bad", msg="readable", file="f", function="g")
        bad.sendall(_framed(message) + _framed(message[:30]) + _framed(message))
        assert arrived(2) and intake.compiled
        assert intake.lost_undecodable == 1 and "truncated" in intake.last_problem
        bad.sendall(struct.pack("<I", 1 << 30) + b"\x00" * 64)
        for number in range(3):
            good.sendall(_framed(encode_log(stamp_ns=10 + number, level=4, name="/good", msg=f"still {number}")))
        assert arrived(5)
        deadline = time.monotonic() + 60
        while not closed and time.monotonic() < deadline:
            time.sleep(0.01)
        assert closed == [("/bad", "a message of 1,073,741,824 bytes announced: not a Log stream")]
        assert [r.msg for r in records] == ["readable", "readable", "still 0", "still 1", "still 2"]
        assert [c.caller_id for c in intake.connections()] == ["/good"]
    finally:
        intake.stop()
        bad.close()
        good.close()
