"""Each widget and screen lists its keys and component classes in its docstring, Textual's
way, and the lists say what the code binds: a key added to ``BINDINGS`` must be documented,
a table left behind by keys or classes taken away must go. Their messages are dataclasses,
as Textual's own are."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil
import re

import pytest
from textual.binding import Binding
from textual.message import Message
from textual.widget import Widget

import console_tui.ui


def all_widgets() -> list[type[Widget]]:
    """The widgets and screens defined in ``console_tui.ui``."""
    found = []
    for module_info in pkgutil.walk_packages(console_tui.ui.__path__, "console_tui.ui."):
        module = importlib.import_module(module_info.name)
        for _name, cls in inspect.getmembers(module, inspect.isclass):
            if cls.__module__ == module.__name__ and issubclass(cls, Widget):
                found.append(cls)
    return found


def ui_classes() -> list[type[Widget]]:
    """Those with keys or component classes of their own."""
    return [cls for cls in all_widgets() if "BINDINGS" in cls.__dict__ or "COMPONENT_CLASSES" in cls.__dict__]


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


@pytest.mark.parametrize("cls", all_widgets(), ids=lambda cls: cls.__name__)
def test_no_table_without_keys_or_classes_and_no_styled_class_undeclared(cls):
    doc = inspect.getdoc(cls) or ""
    if table_rows(doc, "Key"):
        assert "BINDINGS" in cls.__dict__, f"{cls.__name__}: its docstring lists keys it does not bind"
    if table_rows(doc, "Class"):
        assert "COMPONENT_CLASSES" in cls.__dict__, f"{cls.__name__}: its docstring lists classes it does not have"
    styled = set(re.findall(r"\.([a-z0-9-]+--[a-z0-9-]+)", cls.__dict__.get("DEFAULT_CSS", "")))
    assert styled <= cls.COMPONENT_CLASSES, f"{cls.__name__}: styles {sorted(styled - cls.COMPONENT_CLASSES)}"


@pytest.mark.parametrize("cls", all_widgets(), ids=lambda cls: cls.__name__)
def test_messages_are_dataclasses_like_textuals(cls):
    for name, message in vars(cls).items():
        if inspect.isclass(message) and issubclass(message, Message) and "__init__" in vars(message):
            assert dataclasses.is_dataclass(message), f"{cls.__name__}.{name}: a hand-written __init__"
