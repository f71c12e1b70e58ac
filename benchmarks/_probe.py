"""What the benchmarks of the running app measure with: event-loop stalls, frames drawn, keys
answered, and the CPU and memory of processes."""

from __future__ import annotations

import asyncio
import os
import re
import time
from collections import Counter
from typing import Any

from _report import table


class StallProbe:
    """A task that sleeps 1 ms at a time; how late it wakes is how long the loop was busy.
    For each stall, ``loop_cpu`` holds the CPU the event loop's thread used in it, and
    ``loop_waits`` how long that thread waited for a core (its run-queue delay, from
    ``/proc/thread-self/schedstat``; 0 where there is none): a stall with little of either
    was the thread blocked (on the GIL, a lock), not working or waiting for a core."""

    def __init__(self, *, keep_samples: bool = True) -> None:
        #: Each stall, and the loop's CPU and wait in it (``keep_samples``: else these stay
        #: empty, and the probe's memory stays the same however long it runs, as a 30-minute
        #: run's RSS needs: about 100 MB of floats otherwise). ``longest`` and ``percentile``
        #: answer either way.
        self.keep_samples = keep_samples
        self.stalls: list[float] = []
        self.loop_cpu: list[float] = []
        self.loop_waits: list[float] = []
        #: Stalls counted by their length in steps of 10 µs (for ``percentile``).
        self._counted: Counter[int] = Counter()
        self._longest = (0.0, 0.0, 0.0)
        self._running = False
        self._task: asyncio.Task | None = None

    def start(self) -> None:
        self._running = True
        self._task = asyncio.create_task(self._run())

    async def _run(self) -> None:
        try:
            schedstat = os.open("/proc/thread-self/schedstat", os.O_RDONLY)
        except OSError:
            schedstat = -1

        def run_delay() -> float:
            if schedstat < 0:
                return 0.0
            return int(os.pread(schedstat, 100, 0).split()[1]) / 1e9

        try:
            while self._running:
                before, cpu_before, waited_before = time.perf_counter(), time.thread_time(), run_delay()
                await asyncio.sleep(0.001)
                stall = time.perf_counter() - before - 0.001
                cpu, waited = time.thread_time() - cpu_before, run_delay() - waited_before
                self._counted[max(int(stall * 100_000), 0)] += 1
                if stall > self._longest[0]:
                    self._longest = (stall, cpu, waited)
                if self.keep_samples:
                    self.stalls.append(stall)
                    self.loop_cpu.append(cpu)
                    self.loop_waits.append(waited)
        finally:
            if schedstat >= 0:
                os.close(schedstat)

    def clear(self) -> None:
        self.stalls.clear()
        self.loop_cpu.clear()
        self.loop_waits.clear()
        self._counted.clear()
        self._longest = (0.0, 0.0, 0.0)

    def longest(self) -> tuple[float, float, float]:
        """The longest stall, the loop's CPU in it and its wait for a core (seconds)."""
        return self._longest

    def percentile(self, share: float) -> float:
        """The stall below which ``share`` of them lie (to 10 µs; 0 for none)."""
        total = sum(self._counted.values())
        if not total:
            return 0.0
        rank, seen = min(int(share * total), total - 1), 0
        for step in sorted(self._counted):
            seen += self._counted[step]
            if seen > rank:
                return step / 100_000
        return 0.0

    async def stop(self) -> list[float]:
        self._running = False
        if self._task is not None:
            await self._task
        return self.stalls


def count_frames(widget: Any) -> list[float]:
    """Times at which ``widget`` is drawn from now on (its ``render_lines`` is wrapped)."""
    frames: list[float] = []
    original = widget.render_lines

    def counting_render_lines(crop):
        frames.append(time.perf_counter())
        return original(crop)

    widget.render_lines = counting_render_lines
    return frames


class KeyProbe:
    """Presses keys in the running app and times each from the key to the first frame of
    ``table`` that shows its effect: Up (the cursor moves; following stops), then End (not
    timed) to follow the tail again. ``latencies`` holds the seconds; 2 s means no effect."""

    def __init__(self, app: Any, table: Any, frames: list[float], period: float = 0.25) -> None:
        self.app = app
        self.table = table
        self.frames = frames
        self.period = period
        self.latencies: list[float] = []
        self._task: asyncio.Task | None = None

    async def press_up(self) -> float:
        from textual import events

        table = self.table
        before = table.cursor_row
        pressed = time.perf_counter()
        self.app.post_message(events.Key("up", None))
        while time.perf_counter() - pressed < 2.0:
            await asyncio.sleep(0.001)
            if table.cursor_row != before or not table.following:
                drawn = [frame for frame in self.frames if frame > pressed]
                if drawn:
                    return drawn[0] - pressed
        return 2.0

    async def _run(self) -> None:
        from textual import events

        while True:
            self.latencies.append(await self.press_up())
            await asyncio.sleep(self.period / 2)
            self.app.post_message(events.Key("end", None))
            await asyncio.sleep(self.period / 2)

    def start(self) -> None:
        self._task = asyncio.create_task(self._run())

    def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()


def process_cpu(pid: int) -> float:
    """CPU seconds (user + system) a process has used so far; 0 if it is gone."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
            fields = stat.read().rsplit(")", 1)[1].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def process_rss_mb(pid: int | None) -> float:
    """A process's resident memory in MB; 0 if it is gone."""
    return _proc_kb(f"/proc/{pid}/status", "VmRSS:") / 1024 if pid else 0.0


def process_pss_mb(pid: int | None) -> float:
    """A process's proportional set size in MB (shared pages split between the processes
    that map them, so that processes add up honestly); 0 if it is gone."""
    return _proc_kb(f"/proc/{pid}/smaps_rollup", "Pss:") / 1024 if pid else 0.0


def _proc_kb(path: str, key: str) -> int:
    try:
        with open(path, encoding="ascii") as lines:
            for line in lines:
                if line.startswith(key):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def percentile(values: list[float], share: float) -> float:
    """The value below which ``share`` of ``values`` lie (0 for none)."""
    if not values:
        return 0.0
    ordered = sorted(values)
    return ordered[min(int(share * len(ordered)), len(ordered) - 1)]


def thread_cpu(pid: int) -> dict[str, float]:
    """CPU seconds each thread of a process has used so far, summed by the thread's name
    (``main`` for the process's first thread; threads the kernel knows by the process's
    own name are ``other threads``; numbers in names are ``#``, so that Fast DDS's
    ``dds.shm.7411`` and ``dds.shm.7413`` add up); empty if the process is gone."""
    ticks = os.sysconf("SC_CLK_TCK")
    used: dict[str, float] = {}
    try:
        tids = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return used
    main_name = ""
    rows = []
    for tid in tids:
        try:
            with open(f"/proc/{pid}/task/{tid}/stat", encoding="utf-8", errors="replace") as stat:
                text = stat.read()
        except OSError:
            continue
        name = text[text.index("(") + 1 : text.rindex(")")]
        fields = text.rsplit(")", 1)[1].split()
        seconds = (int(fields[11]) + int(fields[12])) / ticks
        if int(tid) == pid:
            main_name = name
        rows.append((int(tid), name, seconds))
    for tid, name, seconds in rows:
        label = "main" if tid == pid else ("other threads" if name == main_name else re.sub(r"\d+", "#", name))
        used[label] = used.get(label, 0.0) + seconds
    return used


def cpu_by_thread(roles: dict[str, list[int]]) -> dict[tuple[str, str], float]:
    """CPU seconds so far of every thread of the processes in each role, by (role, thread name)."""
    used: dict[tuple[str, str], float] = {}
    for role, pids in roles.items():
        for pid in pids:
            for name, seconds in thread_cpu(pid).items():
                used[role, name] = used.get((role, name), 0.0) + seconds
    return used


def threads_table(threads: dict[tuple[str, str], float], seconds: float, messages: int) -> str:
    """Where the CPU went over ``seconds`` (``cpu_by_thread``'s difference): each process's
    threads, in cores and in microseconds a message received; the threads that used under 1%
    of a core are summed."""
    seconds = seconds or 1.0
    messages = max(messages, 1)
    body, small = [], {}
    for (role, name), used in sorted(threads.items(), key=lambda item: -item[1]):
        if used / seconds < 0.01:
            small[role] = small.get(role, 0.0) + used
            continue
        body.append([role, name, f"{used / seconds:.2f}", f"{used / messages * 1e6:.1f}"])
    for role, used in small.items():
        body.append([role, "(the rest)", f"{used / seconds:.2f}", f"{used / messages * 1e6:.1f}"])
    total = sum(threads.values())
    body.append(["all", "", f"{total / seconds:.2f}", f"{total / messages * 1e6:.1f}"])
    return table(["process", "thread", "cores", "us/msg received"], body)
