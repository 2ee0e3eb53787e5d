"""Local Sphinx extension: what the reader sees on a phone, in dark mode, with a screen reader and in search.

Adds two static files to every page (``_ext/reader_static``):

- ``reader.css``:
  - an equation too wide for the room its number leaves goes on a line of its own under the number (at any
    width), so that no term sits under the number;
  - tables: padded cells (neighbouring numbers never run together), numbers never broken over two lines,
    see-through striped rows, a compact style for a table wider than its box, dark colours in dark mode;
  - a scroll cue (a shadow on the edge where the content continues) on every box that scrolls sideways;
  - the arrow of a figure's dropdown in the theme's text colour in dark mode;
- ``reader.js``:
  - the plotly figures follow the theme's light/dark switch (backgrounds, text, grid lines, and trace
    colours too dark to read on a dark page), and switch back; a slider's transparent font (the hidden step
    labels of an animation) stays transparent;
  - the text column: marks the table cells that hold a number and keeps numbers with a signed exponent whole
    (in the live panels' tables too, as they are rewritten), gives an inline formula wider than its line a line
    of its own (smaller to fit, or scrolling), marks tables wider than their box as compact, and marks the
    edges of every sideways-scrolling box where its content continues (the scroll cues);
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
