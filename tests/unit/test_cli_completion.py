"""Shell completion (argcomplete) for the app and every subcommand, driven through the
protocol a shell uses: ``_ARGCOMPLETE``, ``COMP_LINE`` and ``COMP_POINT`` in the environment,
the completions written to ``_ARGCOMPLETE_STDOUT_FILENAME`` (fd 8 in a real shell)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from console_tui.cli import ALIASES, SUBCOMMANDS, completion_parser

REPO = Path(__file__).resolve().parents[2]


def completions(tmp_path: Path, line: str) -> list[str]:
    out = tmp_path / "completions"
    env = {
        **os.environ,
        "PYTHONPATH": str(REPO),
        "_ARGCOMPLETE": "1",
        "_ARGCOMPLETE_IFS": "\n",
        "_ARGCOMPLETE_STDOUT_FILENAME": str(out),
        "COMP_LINE": line,
        "COMP_POINT": str(len(line)),
        "COMP_TYPE": "9",  # Tab
    }
    result = subprocess.run(
        [sys.executable, "-m", "console_tui"], env=env, capture_output=True, text=True, timeout=60, cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    return [word.strip() for word in out.read_text().split("\n") if word.strip()]


@pytest.mark.parametrize(
    ("line", "expected"),
    [
        ("console-tui lo", ["loggers"]),
        ("console-tui loggers s", ["set"]),
        ("console-tui loggers l", ["levels", "list"]),
        ("console-tui wat", ["watch"]),
        ("console-tui --de", ["--demo", "--demo-domain"]),
        ("console-tui tail --no-", ["--no-color", "--no-timestamp"]),
        ("console-tui clean --h", ["--help"]),
    ],
)
def test_the_protocol_completes_verbs_and_options(tmp_path, line, expected):
    assert sorted(completions(tmp_path, line)) == expected


def test_every_subcommand_and_its_options_complete(tmp_path):
    assert set(SUBCOMMANDS) | set(ALIASES) <= set(completions(tmp_path, "console-tui "))
    assert "--all" in completions(tmp_path, "console-tui loggers set --")


def test_the_completion_parser_holds_every_subcommands_own_parser():
    commands = next(a for a in completion_parser()._actions if a.dest == "verb")
    for verb in SUBCOMMANDS:
        assert commands.choices[verb].prog == f"console-tui {verb}"
