"""Which file ``v`` opens for a message, and the editor command that opens it.

A message's file is often a bare name: rospy logs ``r1node.py``, without its folder. Such a
name is never looked up in the console's working directory (a different file of the same
name may be there): only in the run's folders, those of the log files and folders opened.
"""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
from collections.abc import Iterable
from pathlib import Path

from ..model.inert_text import one_line


def run_folders(opened: Iterable[str]) -> list[Path]:
    """The folders a message's relative file name may resolve under: each opened folder, and the
    folder of each opened file; in order, each once."""
    folders: list[Path] = []
    for name in opened:
        path = Path(name).expanduser()
        folder = path if path.is_dir() else path.parent
        try:
            folder = folder.resolve()
        except OSError:
            continue
        if folder not in folders:
            folders.append(folder)
    return folders


def find_code_file(file: str, folders: Iterable[Path]) -> tuple[str | None, str]:
    """The path to open for a message's ``file``, or None and why not, in words."""
    if os.path.isabs(file):
        if os.path.isfile(file):
            return file, ""
        return None, f"{one_line(file, 300)} is not on this machine (logged elsewhere, on a robot?)."
    looked = list(folders)
    for folder in looked:
        candidate = folder / file
        try:
            if candidate.is_file() and candidate.resolve().is_relative_to(folder):
                return str(candidate), ""
        except (OSError, ValueError):
            continue
    where = ", ".join(one_line(str(folder), 200) for folder in looked[:3]) or "no run folder (no log file was opened)"
    return None, (
        f"{one_line(file, 200)} names no folder; looked for it in the run's folders: {where}. "
        "Not found (the console's working directory is not searched)."
    )


def editor_command(path: str, line: int) -> tuple[list[str] | None, str]:
    """``$VISUAL`` (else ``$EDITOR``, else ``vi``) at ``line`` of ``path``: ``vim +42 file``;
    or None and why, when there is no such program here."""
    variable = "VISUAL" if os.environ.get("VISUAL") else "EDITOR" if os.environ.get("EDITOR") else ""
    editor = os.environ.get(variable, "") if variable else ""
    try:
        words = shlex.split(editor)
    except ValueError:  # unbalanced quotes: the whole value names the editor
        words = [editor.strip()]
    if not words:
        if shutil.which("vi") is None:
            return None, "No editor: set $VISUAL or $EDITOR (vi is not installed either)."
        words = ["vi"]
    elif shutil.which(words[0]) is None:
        return None, f"The editor {one_line(words[0], 200)} (${variable}) was not found: is it installed, on PATH?"
    return [*words, *([f"+{line}"] if line > 0 else []), path], ""


def run_editor(command: list[str], **options: object) -> subprocess.CompletedProcess | OSError:
    """The editor's run, or the error that kept it from starting: returned, never raised, so
    that the app's suspended screen always comes back."""
    try:
        return subprocess.run(command, check=False, **options)  # type: ignore[call-overload,no-any-return]
    except OSError as error:
        return error
