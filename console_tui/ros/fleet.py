"""A fleet: the robots one console reads at once, each a ROS 2 domain or a ROS 1 master.

On the command line, repeatable and mixable::

    --domain 3=picker  --master http://10.0.0.7:11311=forklift  --fleet fleet.toml

A fleet file lists robots, each with a name and a domain or a master, an optional log
topic and colour::

    [[robot]]
    name = "picker"
    domain = 3
    colour = "cyan"

    [[robot]]
    name = "forklift"
    master = "http://10.0.0.7:11311"
    topic = "/rosout"

``load_fleet`` reads and checks one (``FleetError`` says what is wrong and where);
``parse_domain`` and ``parse_master`` read the options. Each robot is read by an intake
process of its own (``sources.live.open_fleet``), its records named for the robot.
Nothing here imports ROS.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from ..model.toml_text import TomlError, loads_toml
from .ros_version import ROS1, ROS2

#: The highest DDS domain (as ``ros2.runtime.MAX_DOMAIN_ID``; this module imports no ROS).
MAX_DOMAIN_ID = 232
#: A robot's name: what the Robot column shows and ``robot:`` matches.
NAME_RE = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,31}")
#: The colours a fleet file may give a robot: the terminal's 16, or ``#rrggbb``.
COLOURS = frozenset(
    f"{bright}{name}"
    for bright in ("", "bright_")
    for name in ("black", "red", "green", "yellow", "blue", "magenta", "cyan", "white")
)
_HEX_COLOUR = re.compile(r"#[0-9a-fA-F]{6}")
#: A fleet file larger than this is not a fleet file.
MAX_FLEET_BYTES = 1 << 20


class FleetError(ValueError):
    """A ``--domain``, ``--master`` or fleet file that cannot be used; the text says why."""


@dataclass(frozen=True)
class Robot:
    """One source of a fleet: a ROS 2 ``domain`` or a ROS 1 ``master``, and its name."""

    name: str
    ros: int
    domain: int | None = None
    master: str = ""
    topic: str | None = None
    colour: str = ""

    @property
    def origin(self) -> str:
        """Which ROS and where: ``ROS 2 domain 3``, ``ROS 1 http://10.0.0.7:11311/``."""
        return f"ROS 2 domain {self.domain}" if self.ros == ROS2 else f"ROS 1 {self.master}"

    def environment(self, base: Mapping[str, str] | None = None) -> dict[str, str]:
        """The environment of this robot's intake process: ``base`` (default ours) pointed at it."""
        env = dict(os.environ if base is None else base)
        if self.ros == ROS2:
            env["ROS_DOMAIN_ID"] = str(self.domain)
            env["ROS_VERSION"] = "2"
        else:
            env["ROS_MASTER_URI"] = self.master
            env["ROS_VERSION"] = "1"
        return env


def _at(where: str) -> str:
    return f"{where}: " if where else ""


def _split_name(text: str) -> tuple[str, str]:
    """``VALUE=NAME`` -> (value, name); ``VALUE`` -> (value, "")."""
    value, equals, name = text.rpartition("=")
    if not equals:
        return text.strip(), ""
    name = name.strip()
    _check_name(name, "")
    return value.strip(), name


def robot_name_for(path: str | Path) -> str:
    """A robot's name from a file's or folder's name: ``picker/`` and ``picker.rosout.log`` are
    ``picker``; characters a name cannot hold become ``_``."""
    name = Path(path).name.split(".", 1)[0] if Path(path).name else Path(path).resolve().name
    cleaned = re.sub(r"[^A-Za-z0-9_.-]", "_", name).lstrip(".-")[:32]
    return cleaned or "robot"


def check_robot_name(name: str) -> str:
    """``name`` when it is a robot's name; else ``FleetError`` saying what one is."""
    return _check_name(name, "")


def _check_name(name: object, where: str) -> str:
    if not isinstance(name, str) or not NAME_RE.fullmatch(name):
        raise FleetError(
            f"{_at(where)}a robot's name is 1 to 32 letters, digits, '_', '.' or '-' (not starting with "
            f"'.' or '-'), got {name!r}"
        )
    return name


def _check_domain(value: object, where: str) -> int:
    if isinstance(value, str) and value.strip().isdigit():
        value = int(value)
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= MAX_DOMAIN_ID:
        raise FleetError(f"{_at(where)}a ROS 2 domain is a whole number from 0 to {MAX_DOMAIN_ID}, got {value!r}")
    return value


def _check_master(value: object, where: str) -> str:
    if not isinstance(value, str):
        raise FleetError(f"{_at(where)}a ROS 1 master is a URI such as http://10.0.0.7:11311, got {value!r}")
    uri = value.strip()
    if "://" not in uri:
        uri = f"http://{uri}"
    try:
        parts = urlsplit(uri)
        port = parts.port
    except ValueError:
        parts, port = None, None
    if parts is None or parts.scheme != "http" or not parts.hostname or port is None:
        raise FleetError(f"{_at(where)}a ROS 1 master is a URI such as http://10.0.0.7:11311, got {value!r}")
    return f"http://{parts.netloc}/"


def parse_domain(text: str) -> Robot:
    """``--domain N[=NAME]``: the robot on ROS 2 domain N (named ``domainN`` by default)."""
    value, name = _split_name(text)
    domain = _check_domain(value, "")
    return Robot(name or f"domain{domain}", ROS2, domain=domain)


def parse_master(text: str) -> Robot:
    """``--master URI[=NAME]``: the robot on that ROS 1 master (named ``HOST:PORT`` by default)."""
    value, name = _split_name(text)
    master = _check_master(value, "")
    return Robot(name or (urlsplit(master).netloc.replace(":", "_")), ROS1, master=master)


def load_fleet(path: str | Path) -> list[Robot]:
    """The robots of a fleet file; ``FleetError`` naming the file and what is wrong."""
    where = str(path)
    try:
        with open(path, "rb") as file:
            data = file.read(MAX_FLEET_BYTES + 1)
    except OSError as error:
        raise FleetError(f"{where}: cannot be read: {error.strerror or error}") from None
    if len(data) > MAX_FLEET_BYTES:
        raise FleetError(f"{where}: larger than {MAX_FLEET_BYTES // 1024} kB: not a fleet file")
    try:
        document = loads_toml(data.decode("utf-8"))
    except (UnicodeDecodeError, TomlError) as error:
        raise FleetError(f"{where}: not a TOML file: {error}") from None
    unknown = sorted(set(document) - {"robot"})
    if unknown:
        raise FleetError(f"{where}: unknown table {unknown[0]!r} (a fleet file has [[robot]] tables only)")
    items = document.get("robot")
    if not isinstance(items, list) or not items:
        raise FleetError(f"{where}: no robots (add [[robot]] tables with a name and a domain or a master)")
    robots = [_robot(item, f"{where}: robot {number}") for number, item in enumerate(items, 1)]
    check_fleet(robots, where)
    return robots


def _robot(item: Any, where: str) -> Robot:
    if not isinstance(item, dict):
        raise FleetError(f"{where}: expected a table")
    unknown = sorted(set(item) - {"name", "domain", "master", "topic", "colour", "color"})
    if unknown:
        raise FleetError(f"{where}: unknown field {unknown[0]!r} (fields: name, domain, master, topic, colour)")
    if "name" not in item:
        raise FleetError(f"{where}: needs a name")
    name = _check_name(item["name"], f"{where}: name")
    where = f"{where} ({name})"
    if ("domain" in item) == ("master" in item):
        raise FleetError(f"{where}: give either a domain (ROS 2) or a master (ROS 1)")
    topic = item.get("topic")
    if topic is not None and (not isinstance(topic, str) or not re.fullmatch(r"/[A-Za-z0-9_/~]+", topic)):
        raise FleetError(f"{where}: topic: a topic name such as /rosout, got {topic!r}")
    colour = item.get("colour", item.get("color", ""))
    if not isinstance(colour, str) or (colour and colour not in COLOURS and not _HEX_COLOUR.fullmatch(colour)):
        raise FleetError(f"{where}: colour: one of {', '.join(sorted(COLOURS))} or #rrggbb, got {colour!r}")
    if "domain" in item:
        return Robot(name, ROS2, domain=_check_domain(item["domain"], f"{where}: domain"), topic=topic, colour=colour)
    return Robot(name, ROS1, master=_check_master(item["master"], f"{where}: master"), topic=topic, colour=colour)


def check_fleet(robots: Sequence[Robot], where: str = "the fleet") -> None:
    """``FleetError`` when two robots share a name, a domain or a master."""
    names: dict[str, Robot] = {}
    origins: dict[str, Robot] = {}
    for robot in robots:
        if robot.name in names:
            raise FleetError(
                f"{where}: two robots are named {robot.name!r} ({names[robot.name].origin}, {robot.origin})"
            )
        if robot.origin in origins:
            raise FleetError(f"{where}: {origins[robot.origin].name!r} and {robot.name!r} are both {robot.origin}")
        names[robot.name] = origins[robot.origin] = robot
