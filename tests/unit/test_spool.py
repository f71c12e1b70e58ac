"""The disk spool: whole batches only, deleted only when taken, bounded with the oldest
dropped and counted, one process at a time, what is left found again after a restart."""

from __future__ import annotations

import os

import pytest

from console_tui.warehouse.spool import Spool, SpoolError, batch_token


def test_batches_come_out_oldest_first_and_survive_a_restart(tmp_path):
    spool = Spool(tmp_path, 1 << 20)
    first = spool.write(b"one", 1)
    second = spool.write(b"two!", 2)
    assert spool.oldest() == first
    assert spool.read(first) == b"one"
    spool.delete(first)
    spool.close()
    again = Spool(tmp_path, 1 << 20)
    assert again.oldest() == second
    assert again.state().records == 2
    assert again.write(b"three", 3).number == second.number + 1


def test_a_half_written_batch_is_not_in_the_spool(tmp_path):
    (tmp_path / ".tmp-000000000001-5.otlp.gz").write_bytes(b"cut")
    spool = Spool(tmp_path, 1 << 20)
    assert spool.oldest() is None
    assert not any(name.startswith(".tmp-") for name in os.listdir(tmp_path))


def test_a_full_spool_drops_the_oldest_never_the_one_being_sent(tmp_path):
    spool = Spool(tmp_path, 250)
    batches = [spool.write(bytes(100), 10) for _ in range(2)]
    spool.sending = batches[0].number
    spool.write(bytes(100), 10)  # 300 bytes: one must go, not the one being sent
    state = spool.state()
    assert (state.batches, state.dropped_batches, state.dropped_records) == (2, 1, 10)
    assert spool.oldest() == batches[0]


def test_one_process_a_spool(tmp_path):
    first = Spool(tmp_path, 1 << 20)
    with pytest.raises(SpoolError, match="another console-tui ship"):
        Spool(tmp_path, 1 << 20)
    first.close()
    Spool(tmp_path, 1 << 20).close()  # free again


def test_a_batch_has_the_same_token_each_time_and_no_other_batch_has_it():
    assert batch_token(b"abc") == batch_token(b"abc") != batch_token(b"abd")
