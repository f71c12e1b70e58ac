"""Exclude and highlight rules (rqt_console's filters), rule sets, the query line, rules files.

One module per rule kind; ``ruleset`` holds the semantics; ``query`` compiles the query
line to the same rules; ``rulesfile`` reads and writes TOML rule sets.
"""

from .custom import CustomRule
from .location import LocationRule
from .message import MessageRule
from .node import NodeRule
from .pattern_match import TextMatch
from .robot import RobotRule
from .rule import Rule, RuleError
from .ruleset import Decoration, Entry, Role, RuleSet, exclude, highlight
from .severity import SeverityRule
from .time_range import TimeRangeRule

__all__ = [
    "CustomRule",
    "Decoration",
    "Entry",
    "LocationRule",
    "MessageRule",
    "NodeRule",
    "RobotRule",
    "Role",
    "Rule",
    "RuleError",
    "RuleSet",
    "SeverityRule",
    "TextMatch",
    "TimeRangeRule",
    "exclude",
    "highlight",
]
