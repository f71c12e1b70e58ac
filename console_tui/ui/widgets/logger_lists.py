"""The logger levels pane's two lists: the graph's nodes, and the selected node's loggers."""

from __future__ import annotations

from rich.table import Table
from rich.text import Text
from textual.widgets import OptionList
from textual.widgets.option_list import Option

from ...model.levels import Severity, severity_name
from ...model.logger_levels import GraphNode, LoggerRow, LoggerSource, format_remaining
from ..plain import plain

_LEVEL_STYLE = {10: "dim", 20: "green", 30: "yellow", 40: "red", 50: "bold red"}
_OPTION_PREFIX = "logger:"


class NodeList(OptionList):
    """The graph's nodes; the highlighted one is the pane's selected node."""

    def show(self, nodes: tuple[GraphNode, ...], checking: frozenset[str], selected: str | None) -> None:
        options = [Option(node_prompt(node, node.fqn in checking), id=node.fqn) for node in nodes]
        with self.prevent(OptionList.OptionHighlighted):
            self.set_options(options)
            if selected is not None:
                self.highlighted = self.get_option_index(selected)


class LoggerList(OptionList):
    """The selected node's loggers and their levels; level keys act on the highlighted one."""

    @property
    def highlighted_logger(self) -> str | None:
        option = self.highlighted_option
        return None if option is None else logger_of_option(option)

    def show(self, rows: list[LoggerRow], own: str, now: float, highlight: str | None) -> None:
        """These rows, keeping the highlight on ``highlight`` (or where it was)."""
        if highlight is None:
            highlight = self.highlighted_logger
        options = [
            Option(_two_columns(plain(logger_label(row, own)), level_cell(row, now)), id=option_id(row.name))
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


def node_prompt(node: GraphNode, checking: bool) -> Table:
    if node.has_logger_services:
        marker = Text("")
    elif checking:
        marker = Text("checking…", style="dim italic")
    else:
        marker = Text("no logger services", style="yellow")
    return _two_columns(plain(node.fqn), marker)


def logger_label(row: LoggerRow, own: str) -> str:
    """How a logger's name reads in the list: children relative to the node's logger."""
    if row.source is LoggerSource.DEFAULT:
        return '"" (default)'
    if row.source is LoggerSource.CHILD and row.name.startswith(own + "."):
        return "  ." + row.name[len(own) + 1 :]
    return row.name


def level_cell(row: LoggerRow, now: float) -> Text:
    """A logger's level: ``DEBUG``, ``inherited (INFO)``, ``?``, or ``DEBUG for 25s`` while temporary."""
    if row.temporary is not None:
        temporary = row.temporary
        text = Text(severity_name(temporary.level), style=_LEVEL_STYLE.get(temporary.level, ""))
        text.append(" for ")
        text.append(format_remaining(temporary.remaining(now)), style="bold")
        return text
    if row.level == Severity.UNSET:
        return Text(row.level_text, style="italic dim")
    return Text(row.level_text, style=_LEVEL_STYLE.get(row.level or 0, "dim"))


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
