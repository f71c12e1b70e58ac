"""A stand-in for ``ros2 launch`` (which does not install here from PyPI) for the tests of
``console-tui run``: it starts each ``NAME=COMMAND`` given as launch would, and prints what
launch prints on a terminal, in launch 3.7.1's words and screen format (see
tests/data/launch_output/README.md): ``[INFO] [NAME-N]: process started with pid [P]``, each
line a process writes on stdout or stderr after ``[NAME-N] ``, ``process has finished cleanly``
or ``process has died [pid P, exit code C, cmd '...'].`` (an ERROR), and on SIGINT (sent to
the whole group, as a terminal's Ctrl+C is) ``user interrupted with ctrl-c (SIGINT)``.

    python mini_launch.py NAME='COMMAND ARG...' ...
"""

from __future__ import annotations

import shlex
import signal
import subprocess
import sys
import threading

_lock = threading.Lock()


def say(line: str) -> None:
    with _lock:
        print(line, flush=True)


def relay(name: str, stream) -> None:
    for raw in stream:
        say(f"[{name}] {raw.decode(errors='replace').rstrip(chr(10))}")


def main() -> None:
    say("[INFO] [launch]: Default logging verbosity is set to INFO")
    children = []
    for number, spec in enumerate(sys.argv[1:], 1):
        executable, _, command = spec.partition("=")
        name = f"{executable}-{number}"
        argv = shlex.split(command)
        process = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        say(f"[INFO] [{name}]: process started with pid [{process.pid}]")
        readers = [threading.Thread(target=relay, args=(name, s)) for s in (process.stdout, process.stderr)]
        for reader in readers:
            reader.start()
        children.append((name, argv, process, readers))

    def interrupted(_signum, _frame) -> None:
        say("[WARNING] [launch]: user interrupted with ctrl-c (SIGINT)")

    signal.signal(signal.SIGINT, interrupted)
    for name, argv, process, readers in children:
        code = process.wait()
        for reader in readers:
            reader.join()
        if code == 0:
            say(f"[INFO] [{name}]: process has finished cleanly [pid {process.pid}]")
        else:
            say(f"[ERROR] [{name}]: process has died [pid {process.pid}, exit code {code}, cmd '{' '.join(argv)}'].")


if __name__ == "__main__":
    main()
