"""Local Sphinx extension: the live panels run in the built pages, with no kernel.

- ``_static/scara-engine.js`` is generated at build time from the package's page programs
  (:func:`scara.page.assets.engine_source`: their kernels translated to JavaScript), one shared file that every
  page's Web Worker loads and the browser caches;
- ``_static/scara-panels.js`` and ``scara-panels.css`` (the mechanics: controls, scheduling, plotly.js) are copied
  from the package and loaded on the pages that hold a panel (an element ``data-scara-panel``, written by the
  panel cell's HTML output: :func:`scara.page.assets.panel_html`).
"""
from __future__ import annotations

import shutil
from pathlib import Path

MARK = "data-scara-panel"


def _page_context(app, pagename, templatename, context, doctree):
    if MARK in (context.get("body", "") or ""):
        from scara.page.assets import PANELS_JS  # noqa: PLC0415

        app.add_js_file(PANELS_JS, priority=950)
        app.add_css_file("scara-panels.css")


def _write_assets(app, exc):
    if exc is not None or app.builder.format != "html":
        return
    from scara.page.assets import ENGINE_JS, PANELS_JS, STATIC, engine_source  # noqa: PLC0415

    static = Path(app.outdir) / "_static"
    static.mkdir(parents=True, exist_ok=True)
    (static / ENGINE_JS).write_text(engine_source(), encoding="utf-8")
    for name in (PANELS_JS, "scara-panels.css"):
        shutil.copyfile(STATIC / name, static / name)


def setup(app):
    app.connect("html-page-context", _page_context)
    app.connect("build-finished", _write_assets)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1.0"}
