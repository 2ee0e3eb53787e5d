"""Local Sphinx extension: the arm's model files to download.

When an HTML build finishes, ``scara.export`` writes the book's arm (no payload) as ``_downloads/scara.urdf``
(URDF: RViz, MoveIt, Pinocchio) and ``_downloads/scara.xml`` (MJCF: MuJoCo) in the output folder, from
``to_urdf()`` and ``to_mjcf()``. The files exist only in the build: the package is their one definition, so the
sources hold no copy that could fall behind it. The verification appendix links to both.
"""
from __future__ import annotations

from pathlib import Path

DIR = "_downloads"
#: file name -> the function of ``scara.export`` that writes it
FILES = {"scara.urdf": "to_urdf", "scara.xml": "to_mjcf"}


def model_files() -> dict[str, str]:
    """File name -> text of every model file the build writes (the book's arm, no payload)."""
    from scara import export  # noqa: PLC0415 - the package the book is built from

    return {name: getattr(export, function)() for name, function in FILES.items()}


def _write(app, exc):
    if exc is None and app.builder.format == "html":
        out = Path(app.outdir) / DIR
        out.mkdir(parents=True, exist_ok=True)
        for name, text in model_files().items():
            (out / name).write_text(text, encoding="utf-8")


def setup(app):
    app.connect("build-finished", _write)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1.0"}
