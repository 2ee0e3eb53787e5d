"""The arm's model files to download (``_ext/model_files.py``): the book build writes ``_downloads/scara.urdf`` and
``_downloads/scara.xml`` from ``scara.export``, and the verification appendix links to both.

With the book built (``_build/html``), checks that both files exist and are, byte for byte, ``to_urdf()`` and
``to_mjcf()`` of the package now (the book's arm, no payload), and that the appendix's links lead to them. Without
a build, checks that the extension writes what ``scara.export`` writes and that no copy of the files is kept in the
sources (the package is their one definition). Outside CI a missing build skips with the reason; with ``CI=true``
it fails.
"""
from __future__ import annotations

import html.parser
import json
import os
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from scara.export import to_mjcf, to_urdf

ROOT = Path(__file__).resolve().parents[2]
HTML = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html"))
DOWNLOADS = HTML / "_downloads"
APPENDIX = HTML / "book" / "appendix_verification.html"
IN_CI = os.environ.get("CI", "").lower() == "true"
#: file name -> (the text it must hold, the root element of its format)
EXPECTED = {"scara.urdf": (to_urdf, "robot"), "scara.xml": (to_mjcf, "mujoco")}
#: folders of the sources that could hold a stray copy (the build, environments and git aside)
SOURCES = ("book", "scara", "_ext", "take_home", "benchmarks", "tests")


def _extension():
    sys.path.insert(0, str(ROOT / "_ext"))
    try:
        import model_files  # noqa: PLC0415 - the book's local extension, beside the others in _ext/
    finally:
        sys.path.remove(str(ROOT / "_ext"))
    return model_files


@pytest.fixture(scope="module")
def built() -> Path:
    if not (HTML / "index.html").exists():
        reason = f"the book is not built ({HTML}/index.html missing): run jupyter-book build . first"
        if IN_CI:
            pytest.fail(f"model-file test cannot run under CI=true: {reason}")
        pytest.skip(reason)
    return HTML


def test_extension_writes_what_the_package_exports():
    files = _extension().model_files()
    assert set(files) == set(EXPECTED)
    for name, (export, root) in EXPECTED.items():
        assert files[name] == export(), f"{name} is not scara.export's text"
        assert ET.fromstring(files[name]).tag == root, f"{name} is not a <{root}> document"


def test_no_copy_in_the_sources():
    stray = sorted(str(p.relative_to(ROOT)) for folder in SOURCES for name in EXPECTED
                   for p in (ROOT / folder).rglob(name))
    assert not stray, f"generated model files kept in the sources (the build writes them): {stray}"


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_build_wrote_the_file(built, name):
    path = DOWNLOADS / name
    assert path.is_file(), f"the book build wrote no {path}"
    export, _ = EXPECTED[name]
    assert path.read_text(encoding="utf-8") == export(), (
        f"{path} differs from scara.export now (is the build older than the package? rebuild)")


class _Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.links: list[tuple[str, dict]] = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        href = attrs.get("href")
        if tag == "a" and href and href.split("?")[0].rsplit("/", 1)[-1] in EXPECTED:
            self.links.append((href, attrs))


def test_appendix_links_to_both_files(built):
    assert APPENDIX.is_file(), f"the appendix is not built: {APPENDIX}"
    parser = _Links()
    parser.feed(APPENDIX.read_text(encoding="utf-8"))
    linked = {}
    for href, attrs in parser.links:
        target = (APPENDIX.parent / href.split("?")[0]).resolve()
        assert target.is_file(), f"the appendix links to {href}, which the build did not write"
        assert target.parent == DOWNLOADS.resolve(), f"the appendix links to {href}, not to the build's downloads"
        assert "download" in attrs, f"the link to {href} does not download the file"
        linked[target.name] = href
    assert set(linked) == set(EXPECTED), f"the appendix links to {sorted(linked)}, not to {sorted(EXPECTED)}"


def test_take_home_copy_holds_the_files_its_appendix_links(built):
    """In the take-home zip, the appendix's links lead to the same files, beside the chapter, so JupyterLab opens
    them (a markdown link there; JupyterLab serves no file outside the folder it was started in, ``book/``)."""
    import posixpath
    import re
    import zipfile

    with zipfile.ZipFile(DOWNLOADS / "scara-course.zip") as zf:
        top = zf.namelist()[0].split("/", 1)[0]
        nb = json.loads(zf.read(f"{top}/book/appendix_verification.ipynb"))
        text = "\n".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")
        assert "_downloads/" not in text, "the take-home appendix still links into the book's _downloads folder"
        linked = set()
        for href in re.findall(r"\]\(([^)\s]+)\)", text):
            if posixpath.basename(href) not in EXPECTED:
                continue
            member = posixpath.normpath(posixpath.join(top, "book", href))
            assert member in zf.namelist(), f"the take-home appendix links to {href}, which the zip does not hold"
            export, _ = EXPECTED[posixpath.basename(member)]
            assert zf.read(member).decode("utf-8") == export(), f"the take-home copy's {member} is not scara.export's"
            linked.add(posixpath.basename(member))
    assert linked == set(EXPECTED), f"the take-home appendix links to {sorted(linked)}, not to {sorted(EXPECTED)}"
