"""The ROS 2 demo's own domain: one that nothing on this machine uses, so that the demo's
nodes (``/navigation/planner``, FATAL messages) never reach the user's graph, a second
console or a recording on the user's domain.

A domain in use on this machine has UDP sockets bound on its ports: every DDS
(Fast DDS, Cyclone DDS, Connext) maps domain ``d`` to the ports ``7400 + 250 d`` to
``7400 + 250 d + 249`` (the RTPS port mapping). Domains 1 to 101 keep those ports below
Linux's ephemeral ports; the user's own ``ROS_DOMAIN_ID`` is never taken, used or not.
"""

from __future__ import annotations

import os
import socket
from collections.abc import Callable, Iterable
from pathlib import Path

PORT_BASE = 7400
DOMAIN_GAIN = 250
#: Domains whose ports stay below the ephemeral ports on Linux (32768 and up).
DEMO_DOMAINS = range(1, 102)
_PROC_UDP = (Path("/proc/net/udp"), Path("/proc/net/udp6"))


class NoFreeDomain(RuntimeError):
    """Every candidate domain is in use on this machine."""


def domain_ports(domain: int) -> range:
    start = PORT_BASE + DOMAIN_GAIN * domain
    return range(start, start + DOMAIN_GAIN)


def bound_udp_ports(tables: Iterable[Path] = _PROC_UDP) -> set[int] | None:
    """The local ports of every UDP socket on this machine (Linux's ``/proc/net/udp``), or
    None where that cannot be read."""
    ports: set[int] = set()
    read_any = False
    for table in tables:
        try:
            lines = table.read_text().splitlines()[1:]
        except OSError:
            continue
        read_any = True
        for line in lines:
            fields = line.split()
            if len(fields) > 1 and ":" in fields[1]:
                try:
                    ports.add(int(fields[1].rsplit(":", 1)[1], 16))
                except ValueError:
                    continue
    return ports if read_any else None


def _first_port_taken(domain: int) -> bool:
    """Where ``/proc`` cannot be read: whether the first participant's port is taken."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        try:
            probe.bind(("127.0.0.1", domain_ports(domain).start + 10))
        except OSError:
            return True
    return False


def domain_in_use() -> Callable[[int], bool]:
    """Whether a domain has sockets bound on this machine, as seen now."""
    ports = bound_udp_ports()
    if ports is None:
        return _first_port_taken
    return lambda domain: any(port in ports for port in domain_ports(domain))


def free_domain(
    user_domain: str | None = None,
    *,
    in_use: Callable[[int], bool] | None = None,
    start: int | None = None,
) -> int:
    """A domain for the demo: not the user's (``ROS_DOMAIN_ID``, default 0), none of whose
    ports is bound on this machine. Looked for from ``start`` on (by default a place that
    depends on this process's id, so that two demos started together pick different ones)."""
    try:
        user = int((os.environ.get("ROS_DOMAIN_ID", "") if user_domain is None else user_domain).strip() or 0)
    except ValueError:
        user = 0
    in_use = domain_in_use() if in_use is None else in_use
    candidates = list(DEMO_DOMAINS)
    offset = (os.getpid() if start is None else start) % len(candidates)
    for domain in candidates[offset:] + candidates[:offset]:
        if domain != user and not in_use(domain):
            return domain
    raise NoFreeDomain(
        f"no free ROS 2 domain for the demo: domains {DEMO_DOMAINS.start}-{DEMO_DOMAINS.stop - 1} are all in use"
    )
