"""Local Sphinx extension: what the reader sees on a phone, in dark mode, with a screen reader and in search.

Adds two static files to every page (``_ext/reader_static``):

- ``reader.css``: on a narrow screen an equation's number goes on its own line above the equation, so the
  equation has the whole column (a 390 px phone leaves about 358 px);
- ``reader.js``:
  - the plotly figures follow the theme's light/dark switch (backgrounds, text, grid lines, and trace
    colours too dark to read on a dark page), and switch back;
  - each figure gets a text alternative for assistive technology: an ``aria-label`` holding its caption;
  - search results show text, not raw TeX: the summaries that Sphinx cuts from a page's HTML hold the math
    source (``\\(J_A\\)``), which is turned into plain text (``J_A``, Greek letters as letters).
"""
from __future__ import annotations

from pathlib import Path

STATIC = Path(__file__).parent / "reader_static"


def _static_path(app):
    app.config.html_static_path.append(str(STATIC))


def setup(app):
    app.connect("builder-inited", _static_path)
    app.add_css_file("reader.css")
    app.add_js_file("reader.js", priority=900)  # after plotly and Sphinx's own scripts
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1.0"}
