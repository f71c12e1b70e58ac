"""The coverage floor only goes up: scripts/test fails a whole run below it (README, Development)."""

import sys

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from support.formats import DATA

#: The lowest the floor may ever be; raise both together, never lower them.
LOWEST_FLOOR = 93.0


def test_the_coverage_floor_is_set_and_never_lowered():
    pyproject = DATA.parent.parent / "pyproject.toml"
    report = tomllib.loads(pyproject.read_text())["tool"]["coverage"]["report"]
    assert report["fail_under"] >= LOWEST_FLOOR
