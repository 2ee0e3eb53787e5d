"""Local Sphinx extension: make every page of the book work with no network.

- ``plotly.min.js`` is copied from the installed plotly package (so it always matches the Python side) into
  ``_static/`` and loaded as a plain script in the head of the pages that hold a figure, before the figures'
  inline scripts run.
- MathJax comes from ``sphinx-mathjax-offline`` (local ``mathjax_path``).
- Saved ipywidgets state is dropped: the pages show a live panel's own HTML (``page_panels``), not its widgets.
- Duplicate inline scripts (stock pages declare sphinx-thebe's configuration twice, which logs a
  SyntaxError in the browser) are dropped.
"""
from __future__ import annotations

import shutil
from pathlib import Path

PLOTLY_JS = "plotly.min.js"
WIDGET_STATE = "application/vnd.jupyter.widget-state+json"


def _plotly_source() -> Path:
    import plotly

    return Path(plotly.__file__).parent / "package_data" / PLOTLY_JS


def _copy_plotly(app, exc):
    if exc is None and app.builder.format == "html":
        dest = Path(app.outdir) / "_static" / PLOTLY_JS
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(_plotly_source(), dest)


def _page_context(app, pagename, templatename, context, doctree):
    body = context.get("body", "") or ""
    if "plotly-graph-div" in body or "data-scara-panel" in body:
        app.add_js_file(PLOTLY_JS, priority=100)
    scripts = context.get("script_files")
    if scripts:
        seen, unique = set(), []
        for s in scripts:
            if getattr(s, "attributes", {}).get("type") == WIDGET_STATE:
                continue  # saved widget state: the pages show the page panels, not widgets
            key = (getattr(s, "filename", None) or "", tuple(sorted(getattr(s, "attributes", {}).items())))
            if key in seen:
                continue
            seen.add(key)
            unique.append(s)
        scripts[:] = unique


def setup(app):
    app.connect("html-page-context", _page_context, priority=900)  # after the handlers that add scripts
    app.connect("build-finished", _copy_plotly)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1.0"}
