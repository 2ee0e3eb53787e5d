"""The course to take home: the zip the book build writes, the link to it on every page, and that it installs.

With the book built (``_build/html``), checks that ``_downloads/scara-course.zip`` exists and holds the
chapters (outputs cleared), the package without caches, ``requirements.txt`` and the README with its one
command (and the same steps for Windows); that a chapter page links to it; that the build's zip is the same
bytes the extension packs from the sources now (deterministic); that, unpacked in a temporary folder, the
package installs from the unpacked folder into a fresh virtual environment (no dependencies, no network: the
running environment's libraries are made visible to it) and ``import scara; scara.pose(...)`` runs from the
unpacked copy; and, as a learner does it, that the README's own command, taken from the README's text, installs
the course into a fresh ``.venv`` of the unpacked folder (from the package index, as pip is configured: about a
minute), that its last part starts JupyterLab there (as root too, as in a container) and that chapter 1 runs
top to bottom in a fresh kernel of that ``.venv`` without a cell error, importing the unpacked ``scara``.

Without a build, :func:`test_pins_fall_in_the_ranges` still checks that every pin of ``requirements.txt`` (the
course) and ``requirements-dev.txt`` (the book and the tests) falls in its range in ``pyproject.toml``, and that
every library the package's ranges name for the course is pinned.

Outside CI a missing build skips with the reason; with ``CI=true`` it fails.
"""
from __future__ import annotations

import html.parser
import json
import os
import re
import shutil
import socket
import subprocess
import sys
import sysconfig
import time
import tomllib
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
#: the README's one command (Linux, macOS): the install, then JupyterLab on the chapters (as root too)
INSTALL = "python3 -m venv .venv && .venv/bin/python -m pip install -r requirements.txt"
START = ".venv/bin/jupyter lab --allow-root book/"
COMMAND = f"{INSTALL} && {START}"
#: the same three steps on Windows (PowerShell or the Command Prompt), one line each
WINDOWS = ("py -3.11 -m venv .venv", r".\.venv\Scripts\python -m pip install -r requirements.txt",
           r".\.venv\Scripts\jupyter lab book")
#: the line of the README that holds its one command (as .ci/run finds the repository README's test command)
COMMAND_LINE = re.compile(r"^python3 -m venv \.venv && .*/jupyter lab .*book/$", re.M)
#: the chapter the installed course runs
RUN_CHAPTER = "01_kinematics.ipynb"


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
    for chapter in sorted(p.name for p in (ROOT / "book").glob("*.ipynb")):
        assert f"book/{chapter}" in rel, f"{chapter} is missing from the zip"
    # the introduction, as the book's page or as the notebook the JupyterLab copy makes of it
    assert {"book/intro.md", "book/intro.ipynb"} & rel, "the introduction is missing from the zip"
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
    assert COMMAND_LINE.findall(readme) == [COMMAND], "the one command is not alone on its line, or not once"
    lines = {line.strip() for line in readme.splitlines()}
    for step in WINDOWS:
        assert step in lines, f"the README does not give the Windows step {step!r} on a line of its own"
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


# --------------------------------------------------------------------------------------------------
# the pins and the ranges
# --------------------------------------------------------------------------------------------------
def _name(requirement: str) -> str:
    """A requirement's project name, normalised (PEP 503: ``Jupyter_Client`` -> ``jupyter-client``)."""
    return re.sub(r"[-_.]+", "-", re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)", requirement).group(1)).lower()


def _pins(path: Path) -> dict[str, str]:
    """``name -> version`` of every ``name==version`` line of a requirements file (comments, ``-r``, ``-e`` aside)."""
    pins = {}
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if not line or line.startswith("-"):
            continue
        assert "==" in line, f"{path.name}: {line!r} is not an exact pin"
        name, version = line.split("==")
        assert _name(name) not in pins, f"{path.name} pins {name} twice"
        pins[_name(name)] = version.strip()
    return pins


def _ranges(*groups: str) -> dict[str, str]:
    """``name -> specifier`` of pyproject.toml's ``dependencies`` (group ``""``) and the named extras, with the
    extras they name (``scara[fast,widgets]``) followed."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    extras = project["optional-dependencies"]
    out, todo, seen = {}, list(groups), set()
    while todo:
        group = todo.pop()
        if group in seen:
            continue
        seen.add(group)
        for req in project["dependencies"] if group == "" else extras[group]:
            name = _name(req)
            if name == "scara":
                todo += re.search(r"\[(.*)\]", req).group(1).split(",")
                continue
            assert ";" not in req, f"{req}: the course's ranges carry no environment markers"
            out[name] = req[len(re.match(r"\s*[A-Za-z0-9._-]+", req).group(0)):].strip()
    return out


def test_pins_fall_in_the_ranges():
    """Every pin of the course (requirements.txt) and of everything else (requirements-dev.txt) falls in its
    range in pyproject.toml; every library the ranges name for the course is pinned by the course's file, and
    every one they name for the book and the tests by one of the two; the course's file installs the package
    (``-e .``, its last line) and the other includes it."""
    from packaging.specifiers import SpecifierSet
    from packaging.version import Version

    course_file, dev_file = ROOT / "requirements.txt", ROOT / "requirements-dev.txt"
    course, dev = _pins(course_file), _pins(dev_file)
    assert course_file.read_text().strip().splitlines()[-1] == "-e .", "requirements.txt must end with -e ."
    assert "-r requirements.txt" in dev_file.read_text().splitlines(), "requirements-dev.txt must include the course"
    assert not set(course) & set(dev), f"pinned in both files: {sorted(set(course) & set(dev))}"
    every = {**course, **dev}
    course_ranges = _ranges("", "course")
    missing = sorted(set(course_ranges) - set(course))
    assert not missing, f"the course's ranges name libraries requirements.txt does not pin: {missing}"
    all_ranges = _ranges("", "course", "book", "test")
    missing = sorted(set(all_ranges) - set(every))
    assert not missing, f"the book's and the tests' ranges name libraries no requirements file pins: {missing}"
    outside = [f"{name}=={every[name]} (pyproject: {name}{spec})" for name, spec in sorted(all_ranges.items())
               if Version(every[name]) not in SpecifierSet(spec)]
    assert not outside, f"pins outside their ranges: {outside}"
    assert not set(_ranges("book", "test")) - set(_ranges("", "course")) & set(course), \
        "the course's file pins a library only the book or the tests need"


# --------------------------------------------------------------------------------------------------
# the README's one command, as a learner runs it
# --------------------------------------------------------------------------------------------------
def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _plain_env(**extra) -> dict:
    """This process's environment without what would point a child at the running environment (its virtual
    environment, its ``PYTHONPATH``) or at another compile cache."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "NUMBA_CACHE_DIR",
                                                             "PYTHONHOME", "PIP_REQUIRE_VIRTUALENV")}
    env.update(extra)
    return env


def _start_lab(course: Path, start: str, tmp: Path, timeout: float = 180.0) -> str:
    """Run the README's start command in ``course`` (with a free port, no browser, no token added to its end)
    until JupyterLab answers; return the server's log. The server is stopped before returning."""
    port = _free_port()
    cmd = f"{start} --no-browser --ServerApp.ip=127.0.0.1 --ServerApp.port={port} --ServerApp.port_retries=0 " \
          "--IdentityProvider.token= --ServerApp.password= --LabApp.news_url="
    env = _plain_env(JUPYTER_CONFIG_DIR=str(tmp / "config"), JUPYTER_RUNTIME_DIR=str(tmp / "runtime"),
                     JUPYTERLAB_WORKSPACES_DIR=str(tmp / "workspaces"), IPYTHONDIR=str(tmp / "ipython"))
    log_path = tmp / "lab.log"
    with open(log_path, "w") as log:
        proc = subprocess.Popen(["bash", "-c", f"exec {cmd}"], cwd=course, stdout=log, stderr=subprocess.STDOUT,
                                env=env, start_new_session=True)
        from jupyterlab_driver import stop_process_group, wait_until_up  # noqa: PLC0415 - beside this file

        try:
            wait_until_up(f"http://127.0.0.1:{port}", proc, timeout, log_path)
        except RuntimeError as exc:
            pytest.fail(f"`{start}`: {exc}")
        finally:
            stop_process_group(proc)
    return log_path.read_text()


def _run_chapter(course: Path, chapter: str, tmp: Path) -> list[str]:
    """Execute ``book/<chapter>`` of ``course`` top to bottom in a fresh kernel of ``course/.venv`` (working
    directory ``book/``, an empty compile cache), as *Restart Kernel and Run All* does; a cell error fails the
    test. A last cell, added here, prints where ``scara`` was imported from; return that cell's output lines."""
    import nbformat
    from jupyter_client.kernelspec import KernelSpecManager
    from jupyter_client.manager import KernelManager
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError

    spec = tmp / "kernels" / "take-home"
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [str(course / ".venv" / "bin" / "python"), "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "the take-home course", "language": "python"}))
    km = KernelManager(kernel_name="take-home", kernel_spec_manager=KernelSpecManager(kernel_dirs=[str(spec.parent)]))
    path = course / "book" / chapter
    nb = nbformat.read(path, as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell("import pathlib, scara; print(pathlib.Path(scara.__file__).resolve())"))
    client = NotebookClient(nb, km=km, timeout=600, allow_errors=False,
                            resources={"metadata": {"path": str(path.parent)}})
    try:
        client.execute(env=_plain_env(IPYTHONDIR=str(tmp / "ipython"), JUPYTER_RUNTIME_DIR=str(tmp / "runtime")))
    except CellExecutionError as exc:
        pytest.fail(f"{chapter} of the installed take-home course failed:\n{str(exc)[-4000:]}")
    return "".join(o.get("text", "") for o in nb.cells[-1].outputs).splitlines()


def test_readme_command_installs_the_course_and_runs_a_chapter(archive, tmp_path):
    """The README's one command, read from the README of the unpacked zip: its install part (everything before
    ``&& .venv/bin/jupyter lab``) run as it stands in the unpacked folder, then its start part, which must
    bring JupyterLab up (as root too: the tests run as root in CI's container), then chapter 1 run in the new
    ``.venv``. Only the course is installed: none of the book's toolchain or the tests' libraries."""
    archive.extractall(tmp_path)
    course = tmp_path / TOP
    readme = (course / "README.md").read_text()
    found = COMMAND_LINE.findall(readme)
    assert len(found) == 1, f"the README's one command (python3 -m venv .venv && ... jupyter lab ... book/): {found}"
    install, sep, start = found[0].rpartition(" && ")
    assert sep and start.startswith(".venv/bin/jupyter lab "), f"the command does not end in JupyterLab: {found[0]}"
    t0 = time.monotonic()
    done = subprocess.run(["bash", "-c", install], cwd=course, capture_output=True, text=True, env=_plain_env(),
                          timeout=900)
    took = time.monotonic() - t0
    assert done.returncode == 0, f"`{install}` failed:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    print(f"\n`{install}`: {took:.0f} s")
    listed = subprocess.run([str(course / ".venv" / "bin" / "python"), "-m", "pip", "list", "--format=json"],
                            capture_output=True, text=True, check=True, env=_plain_env()).stdout
    installed = {_name(d["name"]) for d in json.loads(listed)}
    pinned = set(_pins(ROOT / "requirements.txt")) | {"scara"}
    assert pinned <= installed, f"not installed: {sorted(pinned - installed)}"
    # what the book and the tests add to the course (JupyterLab's server reads and runs notebooks itself: nbformat,
    # nbclient and jupyter_client are the course's too)
    added = set(_ranges("book", "test")) - set(_ranges("", "course")) - {"nbformat", "nbclient", "jupyter-client"}
    brought = sorted(installed & added)
    assert not brought, f"the course's install brought the book's or the tests' libraries: {brought}"

    _start_lab(course, start, tmp_path)

    t0 = time.monotonic()
    where = _run_chapter(course, RUN_CHAPTER, tmp_path)
    print(f"{RUN_CHAPTER}, Run All in the installed course (empty compile cache): {time.monotonic() - t0:.1f} s")
    assert where and Path(where[-1]).is_relative_to(course.resolve()), \
        f"the chapter imported scara from {where}, not from the unpacked course"
