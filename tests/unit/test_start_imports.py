"""What the app imports for its first frame: not the dialogs' screens, the file formats and
readers, or a TOML reader, which load the first time they are used (about 35 ms of CPU at
start, docs/performance.md "Start-up"). Checked in a clean interpreter, the app run headless
to its first frame: the modules it loaded, not those loaded before it (coverage, in CI, reads
its settings with tomllib as the interpreter starts)."""

import subprocess
import sys

#: Modules the first frame does without, by the start of their names.
LOADED_WHEN_USED = (
    "console_tui.model.formats",
    "console_tui.sources.files",
    "console_tui.ui.screens.detail",
    "console_tui.ui.screens.summary",
    "console_tui.ui.screens.mark_list",
    "console_tui.ui.screens.columns_dialog",
    "console_tui.ui.screens.file_dialogs",
    "console_tui.ui.screens.load_problems",
    "tomllib",
    "tomli",
)

FIRST_FRAME = """
import asyncio, sys
before = set(sys.modules)  # Python's own start-up, and coverage's in CI (it reads TOML)
from console_tui.model.store.log_store import LogStore
from console_tui.ui.app import ConsoleApp

async def main():
    app = ConsoleApp(store=LogStore(), keymap_file=sys.argv[1])
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        assert app.screen.query("LogTable"), "no table on the first screen"

asyncio.run(main())
print("\\n".join(sorted(set(sys.modules) - before)))
"""


def test_the_first_frame_loads_no_dialog_file_format_or_toml_reader(tmp_path):
    result = subprocess.run(
        [sys.executable, "-c", FIRST_FRAME, str(tmp_path / "no-keymap.toml")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 0, result.stderr[-2000:]
    loaded = result.stdout.split()
    assert "console_tui.ui.widgets.log_table" in loaded  # the check sees the app's modules
    early = [name for name in loaded if name.startswith(LOADED_WHEN_USED)]
    assert early == []
