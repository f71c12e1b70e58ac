"""The ROS 2 demo's own domain: never the user's, never one with sockets bound on this
machine; ``--demo-domain`` checked before anything starts. No ROS needed."""

from __future__ import annotations

import socket
import subprocess
import sys

import pytest

from console_tui.demo.domain import NoFreeDomain, domain_in_use, domain_ports, free_domain


def test_never_the_users_domain_nor_one_in_use():
    busy = {5, 6}
    assert free_domain("4", in_use=busy.__contains__, start=3) == 7  # from 4: the user's, then 5, 6 busy
    assert free_domain("9", in_use=busy.__contains__, start=3) == 4
    assert free_domain("", in_use=lambda d: False, start=0) == 1  # unset: the user is on 0
    assert free_domain("junk", in_use=lambda d: False, start=0) == 1
    with pytest.raises(NoFreeDomain, match="all in use"):
        free_domain("0", in_use=lambda d: True)


def test_two_demos_started_together_look_from_different_places():
    assert free_domain("0", in_use=lambda d: False, start=10) != free_domain("0", in_use=lambda d: False, start=11)


def test_a_socket_bound_on_a_domains_ports_makes_it_in_use():
    ports = domain_ports(97)
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as taken:
        try:
            taken.bind(("127.0.0.1", ports.start + 123))
        except OSError:
            pytest.skip("that port is taken already")
        assert domain_in_use()(97)
        assert free_domain("0", start=96) != 97


@pytest.mark.parametrize(
    "args, says",
    [(["--demo-domain", "3"], "--demo-domain goes with --demo"), (["--demo", "--demo-domain", "300"], "0 to 232")],
)
def test_demo_domain_is_checked_first(args, says):
    result = subprocess.run([sys.executable, "-m", "console_tui", *args], capture_output=True, text=True, timeout=60)
    assert result.returncode == 2 and says in result.stderr
