"""The console in a terminal, over an in-memory logger control with a temporary level set on
node /n, for the exit tests (test_hostile_exit.py).

    python console_with_levels.py RESULT_FILE [signal|error]

Writes ``ready`` to RESULT_FILE once the temporary level is set; at the very end, a JSON
line with the node's levels as they are left. ``error`` raises inside the app once ready.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from console_tui.model.store.log_store import LogStore
from console_tui.run_app import run_then_clean_up
from console_tui.ui.app import ConsoleApp

from support.memory_control import MemoryControl, MemoryNode

result = Path(sys.argv[1])
mode = sys.argv[2] if len(sys.argv) > 2 else "signal"
node = MemoryNode("/n")
node.levels["n"] = 20
control = MemoryControl([node], call_timeout=0.5)


class Console(ConsoleApp):
    def on_ready(self) -> None:
        self.commands.run("console.loggers")  # the logger levels pane: its first opening starts the control
        self.set_timer(0.3, self.set_level)

    def set_level(self) -> None:
        if control._thread is None:
            self.set_timer(0.2, self.set_level)
            return
        control.set_temporary("/n", "n", 10, 600).result(timeout=20)
        result.write_text("ready\n")
        if mode == "error":
            self.set_timer(0.3, self.fail)

    def fail(self) -> None:
        raise RuntimeError("an error inside the app")


app = Console(store=LogStore(), logger_control=control)
try:
    status = run_then_clean_up(app, [control.close])
finally:
    with result.open("a") as out:
        out.write(json.dumps({"levels": node.levels}) + "\n")
