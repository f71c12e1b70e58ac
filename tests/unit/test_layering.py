"""The model imports neither Textual nor rclpy; checked in a clean interpreter."""

import subprocess
import sys
from pathlib import Path

import console_tui.model as model_package

MODEL_DIR = Path(model_package.__file__).parent


def test_model_imports_no_textual_and_no_rclpy():
    modules = sorted(
        "console_tui.model." + ".".join(p.relative_to(MODEL_DIR).with_suffix("").parts)
        for p in MODEL_DIR.rglob("*.py")
        if p.name != "__init__.py"
    )
    code = (
        "import sys, importlib\n"
        f"for name in {modules!r}: importlib.import_module(name)\n"
        "bad = sorted(m for m in sys.modules if m.split('.')[0] in ('textual', 'rclpy', 'rich', 'rcl_interfaces'))\n"
        "print(','.join(bad))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "", f"the model imported {result.stdout.strip()}"
