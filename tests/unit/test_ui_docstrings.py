"""Each widget and screen lists its keys and component classes in its docstring, Textual's
way, and the lists say what the code binds: a key added to ``BINDINGS`` must be documented."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

import pytest
from textual.binding import Binding
from textual.widget import Widget

import console_tui.ui


def ui_classes() -> list[type[Widget]]:
    found = []
    for module_info in pkgutil.walk_packages(console_tui.ui.__path__, "console_tui.ui."):
        module = importlib.import_module(module_info.name)
        for _name, cls in inspect.getmembers(module, inspect.isclass):
            own = "BINDINGS" in cls.__dict__ or "COMPONENT_CLASSES" in cls.__dict__
            if cls.__module__ == module.__name__ and issubclass(cls, Widget) and own:
                found.append(cls)
    return found


def table_rows(doc: str, header: str) -> list[str]:
    """The first cells of the Markdown table whose header starts with ``header``."""
    lines = doc.splitlines()
    for index, line in enumerate(lines):
        if line.strip().startswith(f"| {header}"):
            rows = []
            for row in lines[index + 2 :]:
                if not row.strip().startswith("|"):
                    break
                rows.append(row.strip().split("|")[1].strip())
            return rows
    return []


@pytest.mark.parametrize("cls", ui_classes(), ids=lambda cls: cls.__name__)
def test_keys_and_component_classes_are_listed_in_the_docstring(cls):
    doc = inspect.getdoc(cls) or ""
    if "BINDINGS" in cls.__dict__:
        bound = {key.strip() for b in cls.BINDINGS if isinstance(b, Binding) for key in b.key.split(",")}
        documented = {key.strip() for cell in table_rows(doc, "Key") for key in re.split(r"[,/]", cell)}
        assert bound == documented, f"{cls.__name__}: bound {sorted(bound)}, documented {sorted(documented)}"
    if "COMPONENT_CLASSES" in cls.__dict__:
        listed = " ".join(table_rows(doc, "Class"))
        names = set(re.findall(r"`([a-z0-9-]+)`", listed))
        for name in cls.COMPONENT_CLASSES:
            prefix, _, _severity = name.rpartition("-")
            assert name in names or f"{prefix}-debug" in names, f"{cls.__name__}: {name} not in its docstring"
