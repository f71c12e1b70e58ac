"""The shipper's loop without ROS or network: records from the queue into the spool, batches
out of it as the warehouse answers (taken, try again when, refused, too large), the status."""

from __future__ import annotations

import gzip

import pytest

from console_tui.commands import ship
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.warehouse.otlp_encode import decode
from console_tui.warehouse.outcome import TAKEN, Outcome, retry_after_seconds
from console_tui.warehouse.shipper import Shipper
from console_tui.warehouse.spool import Spool


class Answers:
    """A warehouse that answers each batch from a list (then takes everything), and keeps what it took."""

    def __init__(self, *answers: Outcome) -> None:
        self.answers = list(answers)
        self.taken: list[str] = []
        self.tokens: list[str] = []

    def send(self, data: bytes, records: int, token: str) -> Outcome:
        self.tokens.append(token)
        answer = self.answers.pop(0) if self.answers else TAKEN
        if answer.taken:
            self.taken.extend(log.body for log in decode(gzip.decompress(data)))
        return answer

    def close(self) -> None:
        pass


def shipper_with(tmp_path, target, count: int = 10, **options) -> Shipper:
    queue = IntakeQueue()
    queue.put(RecordColumns.from_records([LogRecord(1_000 + i, 20, "/n", f"m{i}") for i in range(count)]))
    clock = [0.0]
    shipper = Shipper(queue, Spool(tmp_path / "spool", 1 << 20), target, host="h", clock=lambda: clock[0], **options)
    shipper.spool_queued()
    return shipper


def send_all(shipper: Shipper) -> list[float]:
    pauses = []
    while (batch := shipper.spool.oldest()) is not None:
        pauses.append(shipper.send_one(batch))
    return pauses


def test_retried_until_taken_honouring_retry_after_then_deleted(tmp_path):
    target = Answers(Outcome(False, retry=True, problem="HTTP 503"), Outcome(False, retry=True, retry_after=7.0))
    shipper = shipper_with(tmp_path, target, batch_records=4)
    pauses = send_all(shipper)
    assert 0.4 <= pauses[0] <= 0.6 and pauses[1] == 7.0  # backoff, then what the store asked
    assert target.taken == [f"m{i}" for i in range(10)]
    assert len(set(target.tokens)) == 3 and target.tokens[0] == target.tokens[1] == target.tokens[2]
    state = shipper.state()
    assert (state.sent, state.lost, state.spool.batches, state.problem) == (10, 0, 0, "")


def test_refused_for_good_is_counted_lost_and_a_too_large_batch_goes_in_halves(tmp_path):
    target = Answers(Outcome(False, problem="HTTP 400"), Outcome(False, retry=True, too_large=True))
    shipper = shipper_with(tmp_path, target, batch_records=5)
    send_all(shipper)
    assert shipper.state().refused == 5
    assert target.taken == [f"m{i}" for i in range(5, 10)]
    assert shipper.state().sent == 5


def test_status_lines():
    from console_tui.warehouse.shipper import ShipState
    from console_tui.warehouse.spool import SpoolState

    state = ShipState(1200, 1000, SpoolState(2, 200, 3000, 1, 50), 0, "HTTP 503: busy", 4.2, 3)
    line = ship.status_line(state, "reading /rosout (2 publishers)", intake_lost=7)
    assert line == (
        "sent 1,000, spooled 200 (2.9KB in 2 batches), lost 57 (7 before the spool, by the live source, "
        "50 dropped from the full spool); retrying in 4 s: HTTP 503: busy; reading /rosout (2 publishers)"
    )


@pytest.mark.parametrize(("value", "seconds"), [("3", 3.0), ("9999", 300.0), ("", None), ("soon", None)])
def test_retry_after(value, seconds):
    assert retry_after_seconds(value) == seconds


def test_retry_after_as_a_date():
    assert retry_after_seconds("Wed, 21 Oct 2015 07:28:10 GMT", now=1445412480.0) == 10.0


def test_the_command_line(tmp_path, capsys):
    for argv in (  # bad addresses and headers: test_warehouse_command_lines.py
        ["http://c:4318", "--header", "novalue"],
        ["http://c", "--robot", "-x"],
    ):
        with pytest.raises(SystemExit) as exit_:
            ship.main(argv)
        assert exit_.value.code == 2, argv
    held = Spool(tmp_path, 1 << 20)
    assert ship.main(["http://127.0.0.1:1", "--spool", str(tmp_path)]) == ship.EXIT_SPOOL
    held.close()
    assert "another console-tui ship uses the spool" in capsys.readouterr().err
