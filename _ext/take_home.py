"""Local Sphinx extension: the course to take home.

When an HTML build finishes, the course's sources are packed into one deterministic zip (sorted entries, fixed
timestamps and permissions, no caches, no build, no virtual environment), written to
``_downloads/scara-course.zip`` in the output folder. Every page of the book ends with a short block linking to
it, and to the print edition (``print_edition.py``) where the build makes one.

The zip holds one folder, ``scara-course/``: the chapters (``book/*.ipynb`` as JupyterLab reads them, written by
``lab_copy`` from the sources and the numbers the build gave every label: glued numbers as inline expressions,
captions, references as links with the book's text, outputs cleared; ``book/*.md``), the package (``scara/``
without ``__pycache__``), ``pyproject.toml``, ``requirements.txt`` (whose ``-e .`` installs the package from the
unpacked folder), ``references.bib``, the benchmarks' stored results (``benchmarks/results.json``, which the
verification appendix reads), the arm's model files the appendix links to (``book/scara.urdf`` and
``book/scara.xml``, written by ``model_files`` from ``scara.export``, so the appendix's links work in JupyterLab too)
and a README (``take_home/README.md``) whose one command installs everything
and opens the chapters in JupyterLab. The book's configuration stays out: the book is built from the sources.
"""
from __future__ import annotations

import io
import json
import zipfile
from pathlib import Path

from model_files import model_files  # beside this file, on the book's extension path

ZIP_NAME = "scara-course.zip"
ZIP_DIR = "_downloads"
TOP = "scara-course"
FIXED_TIME = (1980, 1, 1, 0, 0, 0)  # the earliest time a zip can hold: the archive is the same on every build
SKIP_PARTS = {"__pycache__", ".ipynb_checkpoints", "_build", ".venv", "venv", ".pytest_cache", ".hypothesis"}
SKIP_SUFFIXES = {".pyc", ".pyo", ".nbi", ".nbc", ".so"}


def _clear_outputs(raw: bytes) -> bytes:
    """A notebook with its outputs and execution counts cleared (unchanged bytes when already clear)."""
    nb = json.loads(raw)
    dirty = False
    for cell in nb.get("cells", []):
        if cell.get("cell_type") == "code" and (cell.get("outputs") or cell.get("execution_count") is not None):
            cell["outputs"], cell["execution_count"] = [], None
            dirty = True
    if not dirty:
        return raw
    return (json.dumps(nb, indent=1, ensure_ascii=False) + "\n").encode()


def _members(root: Path, notebooks: dict[str, bytes | None] | None = None) -> dict[str, bytes]:
    """Archive path (under the top folder) -> content, for every file the take-home course holds; ``notebooks``
    (``book/NAME.ipynb`` or ``.md`` -> bytes, or None to leave a page out) replaces the book's pages by their
    JupyterLab copies (``lab_copy.lab_copies``)."""
    files: list[Path] = []
    files += sorted((root / "book").glob("*.ipynb")) + sorted((root / "book").glob("*.md"))
    files += [p for p in sorted((root / "scara").rglob("*")) if p.is_file()]
    # the course, not the book's build: its chapters are the JupyterLab copies, which the book does not build from
    files += [root / n for n in ("pyproject.toml", "requirements.txt", "references.bib")]
    files += [root / "benchmarks" / "results.json"]  # the verification appendix reads the stored comparison
    out: dict[str, bytes] = {}
    for p in files:
        rel = p.relative_to(root)
        if not p.is_file() or SKIP_PARTS.intersection(rel.parts) or p.suffix in SKIP_SUFFIXES:
            continue
        if any(part.startswith(".") for part in rel.parts):
            continue
        data = p.read_bytes()
        if notebooks and rel.as_posix() in notebooks:  # the JupyterLab copy (None: replaced by a notebook)
            if notebooks[rel.as_posix()] is None:
                continue
            data = notebooks[rel.as_posix()]
        elif p.suffix == ".ipynb":
            data = _clear_outputs(data)
        out[rel.as_posix()] = data
    # the model files beside the chapters, where the JupyterLab copy's links find them (lab_copy.DOWNLOAD)
    for name, text in model_files().items():
        out[f"book/{name}"] = text.encode("utf-8")
    for name, data in (notebooks or {}).items():  # a page the copy writes as a notebook (the introduction)
        if data is not None and name not in out:
            out[name] = data
    readme = root / "take_home" / "README.md"
    if not readme.is_file():  # building from the unpacked course itself: its README is the template
        readme = root / "README.md"
    if readme.is_file():
        out["README.md"] = readme.read_bytes()
    return out


def build_zip(root: Path, notebooks: dict[str, bytes] | None = None) -> bytes:
    """The take-home zip for the sources under ``root``, as bytes (the same bytes for the same sources and
    ``notebooks``, the chapters' JupyterLab copies)."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", compression=zipfile.ZIP_DEFLATED, compresslevel=9) as zf:
        members = _members(root, notebooks)
        for name in sorted(members):
            info = zipfile.ZipInfo(f"{TOP}/{name}", date_time=FIXED_TIME)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o100644 << 16  # a regular file, rw-r--r--
            info.create_system = 3  # unix, whatever the building machine
            zf.writestr(info, members[name], compresslevel=9)
    return buf.getvalue()


def _pack(app):
    app._take_home = app.builder.format == "html"


def _write(app, exc):
    """The zip, once the build has given every label its number: the chapters as JupyterLab copies."""
    if exc is None and getattr(app, "_take_home", False):
        from lab_copy import lab_copies  # noqa: PLC0415 - beside this file, on the book's extension path

        dest = Path(app.outdir) / ZIP_DIR / ZIP_NAME
        dest.parent.mkdir(parents=True, exist_ok=True)
        dest.write_bytes(build_zip(Path(app.srcdir), lab_copies(app)))


BLOCK = """
<div class="admonition tip take-home" id="take-home">
<p class="admonition-title">Take the course home</p>
<p>Download <a class="reference download take-home-link" href="{href}" download>{name}</a>: every chapter as a
notebook, with the <code>scara</code> package. Unpack it and, in its folder <code>{top}/</code>, run the one
command of its <code>README.md</code> (Python 3.11) to open the chapters live in JupyterLab.</p>
{print_line}</div>
"""


def _page_context(app, pagename, templatename, context, doctree):
    if doctree is None or not getattr(app, "_take_home", False) or "pathto" not in context:
        return  # generated pages (search, index) carry no link
    from print_edition import links  # noqa: PLC0415 - beside this file: the print edition's line, if built

    href = context["pathto"](f"{ZIP_DIR}/{ZIP_NAME}", 1)
    context["body"] = (context.get("body") or "") + BLOCK.format(
        href=href, name=ZIP_NAME, top=TOP, print_line=links(app, context["pathto"], pagename))


def setup(app):
    app.connect("builder-inited", _pack)
    app.connect("html-page-context", _page_context)
    app.connect("build-finished", _write)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1.0"}
