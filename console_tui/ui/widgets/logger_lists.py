"""The logger levels pane's two lists: the graph's nodes, and the selected node's loggers."""

from __future__ import annotations

from collections.abc import Mapping

from rich.style import Style
from rich.table import Table
from rich.text import Text
from textual.widgets import OptionList
from textual.widgets.option_list import Option

from ...model.levels import severity_level, severity_name
from ...model.loggers.logger_levels import GraphNode, LoggerRow, LoggerSource, format_remaining
from ..plain import plain
from ..severity_styles import severity_classes, severity_css

_OPTION_PREFIX = "logger:"


class GraphNodeList(OptionList):
    """The graph's nodes; the highlighted one is the pane's selected node.

    | Class | Description |
    | :- | :- |
    | `graph-node-list--checking` | "checking…": the node's logger services may yet appear. |
    | `graph-node-list--no-services` | "no logger services". |
    """

    DEFAULT_CSS = """
    GraphNodeList > .graph-node-list--checking { color: $foreground-muted; text-style: italic; }
    GraphNodeList > .graph-node-list--no-services { color: $text-warning; }
    """
    COMPONENT_CLASSES = {"graph-node-list--checking", "graph-node-list--no-services"}

    def show(self, nodes: tuple[GraphNode, ...], checking: frozenset[str], selected: str | None) -> None:
        styles = {name: self.get_component_rich_style(name, partial=True) for name in self.COMPONENT_CLASSES}
        options = [Option(node_prompt(node, node.fqn in checking, styles), id=node.fqn) for node in nodes]
        with self.prevent(OptionList.OptionHighlighted):
            self.set_options(options)
            if selected is not None:
                self.highlighted = self.get_option_index(selected)


class LoggerList(OptionList):
    """The selected node's loggers and their levels; level keys act on the highlighted one.

    | Class | Description |
    | :- | :- |
    | `logger-list--severity-debug` ... `logger-list--severity-fatal` | A logger's level. |
    | `logger-list--inherited` | A logger with no level of its own. |
    | `logger-list--countdown` | The time left of a temporary level. |
    """

    DEFAULT_CSS = """
    LoggerList > .logger-list--inherited { color: $foreground-muted; text-style: italic; }
    LoggerList > .logger-list--countdown { text-style: bold; }
    """ + severity_css("LoggerList", "logger-list--severity")
    COMPONENT_CLASSES = {*severity_classes("logger-list--severity"), "logger-list--inherited", "logger-list--countdown"}

    @property
    def highlighted_logger(self) -> str | None:
        option = self.highlighted_option
        return None if option is None else logger_of_option(option)

    def show(self, rows: list[LoggerRow], own: str, now: float, highlight: str | None) -> None:
        """These rows, keeping the highlight on ``highlight`` (or where it was)."""
        if highlight is None:
            highlight = self.highlighted_logger
        styles = {name: self.get_component_rich_style(name, partial=True) for name in self.COMPONENT_CLASSES}
        options = [
            Option(_two_columns(plain(logger_label(row, own)), level_cell(row, now, styles)), id=option_id(row.name))
            for row in rows
        ]
        names = [row.name for row in rows]
        if [logger_of_option(option) for option in self.options] == names:
            for index, option in enumerate(options):
                self.replace_option_prompt_at_index(index, option.prompt)
        else:
            with self.prevent(OptionList.OptionHighlighted):
                self.set_options(options)
        if highlight in names:
            self.highlighted = names.index(highlight)
        elif rows and self.highlighted is None:
            self.highlighted = 0


def node_prompt(node: GraphNode, checking: bool, styles: Mapping[str, Style]) -> Table:
    if node.has_logger_services:
        marker = Text("")
    elif checking:
        marker = Text("checking…", style=styles.get("graph-node-list--checking", ""))
    else:
        marker = Text("no logger services", style=styles.get("graph-node-list--no-services", ""))
    return _two_columns(plain(node.fqn), marker)


def logger_label(row: LoggerRow, own: str) -> str:
    """How a logger's name reads in the list: children relative to the node's logger."""
    if row.source is LoggerSource.DEFAULT:
        return '"" (default)'
    if row.source is LoggerSource.CHILD and row.name.startswith(own + "."):
        return "  ." + row.name[len(own) + 1 :]
    return row.name


def level_cell(row: LoggerRow, now: float, styles: Mapping[str, Style]) -> Text:
    """A logger's level: ``DEBUG``, ``inherited (INFO)``, ``?``, or ``DEBUG for 25s`` while temporary."""

    def level_style(level: int | None) -> Style | str:
        if not level:
            return styles.get("logger-list--inherited", "")
        return styles.get(f"logger-list--severity-{severity_level(level).style}", "")

    if row.temporary is not None:
        temporary = row.temporary
        text = Text(severity_name(temporary.level), style=level_style(temporary.level))
        text.append(" for ")
        text.append(format_remaining(temporary.remaining(now)), style=styles.get("logger-list--countdown", ""))
        return text
    return Text(row.level_text, style=level_style(row.level))


def _two_columns(left: Text | str, right: Text | str) -> Table:
    grid = Table.grid(expand=True)
    grid.add_column(ratio=1, no_wrap=True, overflow="ellipsis")
    grid.add_column(no_wrap=True, justify="right")
    grid.add_row(left, right)
    return grid


def option_id(logger: str) -> str:
    return _OPTION_PREFIX + logger


def logger_of_option(option: Option) -> str:
    return (option.id or _OPTION_PREFIX)[len(_OPTION_PREFIX) :]
