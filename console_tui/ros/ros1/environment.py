"""Where the ROS 1 master is and who we are on the network, from the user's environment.

As rospy reads it: ``ROS_MASTER_URI`` (default ``http://localhost:11311/``); the address to
advertise from ``ROS_HOSTNAME``, else ``ROS_IP``, else the host name (a host name that is
only a loopback name gives way to a non-loopback address of this machine). The address to
bind: loopback when the advertised address is loopback, ``ROS_IP`` itself when it is set
(only that interface), else every interface.
"""

from __future__ import annotations

import itertools
import os
import socket
from collections.abc import Mapping
from dataclasses import dataclass
from urllib.parse import urlsplit

DEFAULT_MASTER_URI = "http://localhost:11311/"
#: Our nodes' names start with this; the logger pane and ``loggers list`` leave them out.
NODE_PREFIX = "/console_tui_"
_names = itertools.count(1)


@dataclass(frozen=True)
class Ros1Environment:
    master_uri: str
    #: The host name or address other nodes reach us at.
    advertise: str
    #: The address our servers listen on.
    bind: str
    #: ``ROS_MASTER_URI`` was not set: the default is in use.
    master_defaulted: bool = False

    @classmethod
    def from_environ(cls, environ: Mapping[str, str] | None = None) -> Ros1Environment:
        environ = os.environ if environ is None else environ
        master = environ.get("ROS_MASTER_URI", "").strip()
        hostname = environ.get("ROS_HOSTNAME", "").strip()
        ip = environ.get("ROS_IP", "").strip()
        advertise = hostname or ip or _host_name()
        if _is_loopback(advertise):
            bind = "127.0.0.1"
        elif ip and not hostname:
            bind = ip
        else:
            bind = "0.0.0.0"
        return cls(master or DEFAULT_MASTER_URI, advertise, bind, master_defaulted=not master)

    def master_host(self) -> str:
        return urlsplit(self.master_uri).hostname or ""


def new_node_name() -> str:
    """A node name unique to this process and call: ``/console_tui_<pid>_<n>``."""
    return f"{NODE_PREFIX}{os.getpid()}_{next(_names)}"


def _is_loopback(address: str) -> bool:
    return address == "localhost" or address.startswith("127.") or address == "::1"


def _host_name() -> str:
    try:
        name = socket.gethostname()
    except OSError:
        name = ""
    if name and not _is_loopback(name):
        return name
    return _local_address() or "localhost"


def _local_address() -> str:
    """A non-loopback IPv4 address of this machine, or ""."""
    try:
        infos = socket.getaddrinfo(socket.gethostname(), None, socket.AF_INET)
    except OSError:
        return ""
    for info in infos:
        address = str(info[4][0])
        if not _is_loopback(address):
            return address
    return ""
