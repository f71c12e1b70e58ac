"""The README is what a newcomer reads in five minutes, and every link in it leads somewhere,
also on the package index (where a relative link leads nowhere): its links are web addresses
of the project's, each checked against the file here that it names.

The pages under docs/ are checked by ``mkdocs build --strict`` in scripts/test (broken links
and anchors fail the build); this checks the README, which MkDocs does not build.
"""

from __future__ import annotations

import re

import pytest

from support.docs import DOCS, ROOT, headings, local_target

README = ROOT / "README.md"
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def readme_links() -> list[str]:
    text = re.sub(r"```.*?```", "", README.read_text(encoding="utf-8"), flags=re.S)  # code holds no links
    return LINK.findall(text)


def test_the_readme_is_short() -> None:
    assert len(README.read_text(encoding="utf-8").splitlines()) <= 300


def test_the_readme_links_to_the_docs_and_shows_the_app() -> None:
    targets = [local_target(link) for link in readme_links()]
    assert any(t and t[0].parent == DOCS for t in targets)
    assert any(t and t[0].parent.name == "screenshots" for t in targets)


@pytest.mark.parametrize("link", readme_links())
def test_every_readme_link_resolves_and_works_off_the_repository(link: str) -> None:
    assert re.match(r"^https://", link), f"{link}: a relative link breaks on the package index"
    target = local_target(link)
    if target is None:
        pytest.skip("a web address outside the project: not fetched in tests")
    path, anchor = target
    assert path.exists(), f"README links to {link}: no {path.relative_to(ROOT)} here"
    if anchor:
        assert anchor in headings(path), f"README links to {link}: no such heading in {path.name}"


def test_every_docs_page_is_in_the_site() -> None:
    """A page left out of mkdocs.yml's nav would only be a warning: every page is listed."""
    nav = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    pages = {p.name for p in DOCS.glob("*.md")}
    assert pages, "docs/ has no pages"
    missing = sorted(p for p in pages if p not in nav)
    assert not missing, f"pages not in mkdocs.yml's nav: {missing}"
