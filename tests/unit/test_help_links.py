"""The documentation links in ``--help`` (``DOCS_URL`` + page + anchor) lead to a page and a
heading of docs/, as MkDocs names them."""

from __future__ import annotations

import re

import pytest

from console_tui.cli import SUBCOMMANDS, build_parser, completion_parser
from console_tui.commands.arguments import DOCS_URL

from support.docs import DOCS, slug


def help_texts() -> list[str]:
    commands = next(a for a in completion_parser()._actions if a.dest == "verb")
    return [build_parser().format_help(), *(commands.choices[verb].format_help() for verb in SUBCOMMANDS)]


def test_every_docs_link_in_the_help_resolves():
    links = {link for text in help_texts() for link in re.findall(re.escape(DOCS_URL) + r"[\w./#-]*", text)}
    assert f"{DOCS_URL}rules/#the-query-line" in links
    assert f"{DOCS_URL}headless/#the-rosout-node-console-tui-rosout" in links
    for link in links:
        page, _, anchor = link.removeprefix(DOCS_URL).partition("#")
        if not page:
            continue
        path = DOCS / f"{page.strip('/')}.md"
        if not path.exists():
            pytest.fail(f"{link}: no {path.name} in docs/")
        headings = [slug(line.lstrip("#")) for line in path.read_text().splitlines() if line.startswith("#")]
        assert not anchor or anchor in headings, f"{link}: no such heading in {path.name}"
