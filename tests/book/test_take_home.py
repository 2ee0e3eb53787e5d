"""The course to take home: the zip the book build writes, the link to it on every page, and that it installs.

With the book built (``_build/html``), checks that ``_downloads/scara-course.zip`` exists and holds the
chapters (outputs cleared), the package without caches, ``requirements.txt`` and the README with its one
command; that a chapter page links to it; that the build's zip is the same bytes the extension packs from the
sources now (deterministic); and that, unpacked in a temporary folder, the package installs from the unpacked
folder into a fresh virtual environment (no dependencies, no network: the running environment's libraries are
made visible to it) and ``import scara; scara.pose(...)`` runs from the unpacked copy.

Outside CI a missing build skips with the reason; with ``CI=true`` it fails.
"""
from __future__ import annotations

import html.parser
import json
import os
import subprocess
import sys
import sysconfig
import venv
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HTML = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html"))
ZIP = HTML / "_downloads" / "scara-course.zip"
TOP = "scara-course"
CHAPTER = HTML / "book" / "01_kinematics.html"
IN_CI = os.environ.get("CI", "").lower() == "true"
COMMAND = "python3 -m venv .venv && .venv/bin/python -m pip install -r requirements.txt && .venv/bin/jupyter lab book/"


@pytest.fixture(scope="module")
def archive() -> zipfile.ZipFile:
    if not (HTML / "index.html").exists():
        reason = f"the book is not built ({HTML}/index.html missing): run jupyter-book build . first"
        if IN_CI:
            pytest.fail(f"take-home test cannot run under CI=true: {reason}")
        pytest.skip(reason)
    assert ZIP.is_file(), f"the book build wrote no {ZIP}"
    with zipfile.ZipFile(ZIP) as zf:
        yield zf


def _names(zf: zipfile.ZipFile) -> list[str]:
    return zf.namelist()


def test_zip_holds_the_course(archive):
    names = _names(archive)
    assert names == sorted(names), "entries are not sorted"
    assert all(n.startswith(TOP + "/") for n in names), "everything sits in one top folder"
    rel = {n[len(TOP) + 1:] for n in names}
    # the JupyterLab copies: the introduction (a MyST notebook) is a notebook there
    for chapter in sorted(p.name for p in (ROOT / "book").glob("*.ipynb")) + ["intro.ipynb", "notation.md"]:
        assert f"book/{chapter}" in rel, f"{chapter} is missing from the zip"
    for f in ("README.md", "requirements.txt", "pyproject.toml", "references.bib", "scara/__init__.py",
              "scara/kinematics.py"):
        assert f in rel, f"{f} is missing from the zip"
    package = {p.relative_to(ROOT).as_posix() for p in (ROOT / "scara").rglob("*.py") if "__pycache__" not in p.parts}
    missing = sorted(package - rel)
    assert not missing, f"package modules missing (is the build older than the sources? rebuild): {missing}"
    for bad in ("__pycache__", "_build", ".venv", ".ipynb_checkpoints", ".pyc", ".egg-info"):
        assert not [n for n in names if bad in n], f"{bad} in the zip"
    assert all(i.date_time == (1980, 1, 1, 0, 0, 0) for i in archive.infolist()), "timestamps are not fixed"
    assert ZIP.stat().st_size < 2_000_000, f"the zip is {ZIP.stat().st_size} bytes"


def test_zip_content(archive):
    for name in (n for n in archive.namelist() if n.endswith(".ipynb")):
        nb = json.loads(archive.read(name))
        code = [c for c in nb["cells"] if c["cell_type"] == "code"]
        assert all(not c.get("outputs") for c in code), f"{name} carries outputs"
    readme = archive.read(f"{TOP}/README.md").decode()
    assert COMMAND in readme, "the README does not give the one command"
    reqs = archive.read(f"{TOP}/requirements.txt").decode().splitlines()
    assert "-e ." in [r.strip() for r in reqs], "requirements.txt does not install the package from its folder"
    assert archive.read(f"{TOP}/requirements.txt") == (ROOT / "requirements.txt").read_bytes()


def test_zip_is_deterministic(archive):
    sys.path.insert(0, str(ROOT / "_ext"))
    try:
        import take_home
    finally:
        sys.path.remove(str(ROOT / "_ext"))
    first, second = take_home.build_zip(ROOT), take_home.build_zip(ROOT)
    assert first == second, "two packs of the same sources differ"


class _Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.hrefs: list[str] = []

    def handle_starttag(self, tag, attrs):
        href = dict(attrs).get("href")
        if tag == "a" and href and href.split("?")[0].endswith("scara-course.zip"):
            self.hrefs.append(href)


@pytest.mark.parametrize("page", ["book/01_kinematics.html", "book/intro.html"])
def test_pages_link_to_the_zip(archive, page):
    parser = _Links()
    parser.feed((HTML / page).read_text(encoding="utf-8"))
    assert parser.hrefs, f"{page} has no link to scara-course.zip"
    for href in parser.hrefs:
        target = ((HTML / page).parent / href).resolve()
        assert target == ZIP.resolve(), f"{page} links to {href}, not to the zip"
        assert target.is_file()


def test_unpacked_course_installs_and_imports(archive, tmp_path):
    archive.extractall(tmp_path)
    course = tmp_path / TOP
    env = tmp_path / "venv"
    venv.EnvBuilder(with_pip=True, symlinks=True).create(env)
    py = env / "bin" / "python"
    purelib = subprocess.run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                             capture_output=True, text=True, check=True).stdout.strip()
    # The running environment's libraries (numpy, scipy, plotly, setuptools), appended as a plain path: its own
    # .pth files (among them the repository's editable scara) are not processed, so `scara` can only come from
    # the unpacked course.
    Path(purelib, "zz_running_env.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    environ = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    environ.update(PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    done = subprocess.run([py, "-m", "pip", "install", "--no-deps", "--no-build-isolation", "-e", str(course)],
                          capture_output=True, text=True, env=environ, cwd=tmp_path, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    check = ("import scara, pathlib; print(pathlib.Path(scara.__file__).resolve());"
             " print(scara.pose([0, 0, 0.5, 0]))")
    ran = subprocess.run([py, "-c", check], capture_output=True, text=True, env=environ, cwd=tmp_path, timeout=120)
    assert ran.returncode == 0, ran.stdout + ran.stderr
    where = Path(ran.stdout.splitlines()[0])
    assert where.is_relative_to(course.resolve()), f"scara was imported from {where}, not from the unpacked course"
