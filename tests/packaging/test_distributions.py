"""What a packager gets: ``python -m build`` makes the sdist, then the wheel from it (so the
sdist builds); the wheel's METADATA has the classifiers, project URLs and licence files; the
sdist holds what it takes to run the tests (tests/, LICENSE, CHANGELOG.md, screenshots/);
``twine check`` passes. Needs the ``build`` and ``twine`` packages (the test extra) and the
package index for the build's setuptools; about 15-30 s."""

from __future__ import annotations

import email
import shutil
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
#: What a working tree holds beside the sources (venvs, caches, builds).
NOT_SOURCES = (
    ".git",
    ".venv*",
    "__pycache__",
    "*.egg-info",
    "build",
    "dist",
    "site",
    ".*_cache",
    "mutants",
    ".hypothesis",
    "*.so",
    ".coverage*",
    "htmlcov",
)

pytest.importorskip("build", reason="pip install build (the test extra) to build the distributions")


@pytest.fixture(scope="module")
def dist(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("dist")
    # Built from a copy: tests running beside this one write caches into the tree.
    tree = tmp_path_factory.mktemp("tree") / "console-tui"
    shutil.copytree(REPO, tree, ignore=shutil.ignore_patterns(*NOT_SOURCES))
    result = subprocess.run(
        [sys.executable, "-m", "build", "--outdir", str(out), str(tree)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    return out


def the(directory: Path, pattern: str) -> Path:
    (path,) = directory.glob(pattern)
    return path


def test_wheel_metadata(dist):
    with zipfile.ZipFile(the(dist, "*.whl")) as wheel:
        names = wheel.namelist()
        (metadata_name,) = [n for n in names if n.endswith(".dist-info/METADATA")]
        metadata = email.message_from_bytes(wheel.read(metadata_name))
    assert metadata["License-Expression"] == "Apache-2.0"
    assert set(metadata.get_all("License-File")) == {"LICENSE", "NOTICE"}
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    classifiers = metadata.get_all("Classifier")
    assert "Environment :: Console" in classifiers and "Topic :: System :: Logging" in classifiers
    urls = dict(url.split(", ", 1) for url in metadata.get_all("Project-URL"))
    assert {"Homepage", "Documentation", "Source", "Issues", "Changelog"} <= urls.keys()
    assert all(url.startswith("https://") for url in urls.values())
    assert metadata["Author"] == "console-tui developers" and "ros2" in metadata["Keywords"]
    requires = metadata.get_all("Requires-Dist")
    assert any(r.startswith(("textual<8.3,>=8.2.8", "textual>=8.2.8,<8.3")) for r in requires)
    assert any(r.startswith("argcomplete") for r in requires) and any(r.startswith("platformdirs") for r in requires)
    # Package data: the styles, the ROS 1 demo's launch file, the take loop's C source.
    assert "console_tui/ui/app.tcss" in names and any(n.endswith(".c") for n in names)
    assert not any("__pycache__" in n or n.endswith(".so") for n in names)


def test_sdist_holds_what_the_tests_need(dist):
    with tarfile.open(the(dist, "*.tar.gz")) as sdist:
        names = {name.split("/", 1)[1] for name in sdist.getnames() if "/" in name}
    for needed in ("LICENSE", "NOTICE", "CHANGELOG.md", "README.md", "pyproject.toml", "requirements-test.txt"):
        assert needed in names
    assert "tests/conftest.py" in names and "tests/unit/test_cli_tail.py" in names
    assert any(n.startswith("tests/screens/__snapshots__/") for n in names)
    assert any(n.startswith("screenshots/") and n.endswith(".svg") for n in names)
    assert not any("__pycache__" in n or n.endswith((".pyc", ".so")) for n in names)


def test_twine_check_passes(dist):
    pytest.importorskip("twine", reason="pip install twine (the test extra)")
    files = [str(path) for path in sorted(dist.iterdir())]
    result = subprocess.run(
        [sys.executable, "-m", "twine", "check", "--strict", *files], capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 0, result.stdout + result.stderr
