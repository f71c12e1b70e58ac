"""Where the project's documentation lives, and how its links map back to files here."""

from __future__ import annotations

import re
from pathlib import Path

from console_tui.commands.arguments import DOCS_URL

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
#: The repository's files as the web serves them (the README's images on PyPI).
RAW_URL = "https://raw.githubusercontent.com/console-tui/console-tui/main/"
#: The repository's pages as the web shows them (LICENSE, CHANGELOG.md).
BLOB_URL = "https://github.com/console-tui/console-tui/blob/main/"


def slug(heading: str) -> str:
    """A heading's anchor as Python-Markdown's toc makes it."""
    text = re.sub(r"[^\w\s-]", "", heading).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def headings(page: Path) -> set[str]:
    """The anchors of a Markdown page's headings (outside code blocks)."""
    anchors, fence = set(), False
    for line in page.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            fence = not fence
        elif not fence and line.startswith("#"):
            anchors.add(slug(line.lstrip("#")))
    return anchors


def local_target(link: str) -> tuple[Path, str] | None:
    """The file here (and the anchor) a link of the project's points to; None for other links."""
    address, _, anchor = link.partition("#")
    if address.startswith(DOCS_URL):
        page = address.removeprefix(DOCS_URL).strip("/")
        return (DOCS / f"{page}.md" if page else DOCS / "index.md"), anchor
    for prefix in (RAW_URL, BLOB_URL):
        if address.startswith(prefix):
            return ROOT / address.removeprefix(prefix), anchor
    if re.match(r"^[a-z]+://", address):
        return None
    return (ROOT / address if address else ROOT / "README.md"), anchor
