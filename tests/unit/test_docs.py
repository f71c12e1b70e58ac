"""The README is what a newcomer reads in five minutes, and every link in it leads somewhere.

The pages under docs/ are checked by ``mkdocs build --strict`` in scripts/test (broken links
and anchors fail the build); this checks the README, which MkDocs does not build.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def readme_links() -> list[str]:
    text = README.read_text(encoding="utf-8")
    text = re.sub(r"```.*?```", "", text, flags=re.S)  # code blocks hold no links
    return LINK.findall(text)


def test_the_readme_is_short() -> None:
    assert len(README.read_text(encoding="utf-8").splitlines()) <= 300


def test_the_readme_has_links_to_check() -> None:
    links = readme_links()
    assert any(link.startswith("docs/") for link in links)
    assert any(link.startswith("screenshots/") for link in links)


@pytest.mark.parametrize("link", readme_links())
def test_every_readme_link_resolves(link: str) -> None:
    if link.startswith(("http://", "https://")):
        pytest.skip("a web address: not fetched in tests")
    path, _, anchor = link.partition("#")
    target = (ROOT / path) if path else README
    assert target.exists(), f"README links to {link}, which does not exist"
    if anchor and target.suffix == ".md":
        assert anchor in headings(target), f"README links to #{anchor}, no such heading in {path}"


def headings(page: Path) -> set[str]:
    """The anchors MkDocs (and GitHub) give a page's headings, as far as these pages need."""
    anchors = set()
    for line in page.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            title = line.lstrip("#").strip().lower()
            title = re.sub(r"[^\w\- ]", "", title)
            anchors.add(re.sub(r"\s+", "-", title))
    return anchors


def test_every_docs_page_is_in_the_site() -> None:
    """A page left out of mkdocs.yml's nav would only be a warning: every page is listed."""
    nav = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    pages = {p.name for p in (ROOT / "docs").glob("*.md")}
    assert pages, "docs/ has no pages"
    missing = sorted(p for p in pages if p not in nav)
    assert not missing, f"pages not in mkdocs.yml's nav: {missing}"
