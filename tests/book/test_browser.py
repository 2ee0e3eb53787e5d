"""The built book in a real browser, offline.

Serves ``_build/html`` on 127.0.0.1, aborts every other request, opens every page in Debian's Chromium
(headless, through Playwright) and fails on: an external or failed request, a console error or page error,
math MathJax did not typeset, a plotly figure that did not render, and, on every chapter page, a static
slider that does not change its figure when moved. A screenshot of each page goes to ``_build/screenshots/``.

Outside CI a missing Chromium or a missing build skips with the reason; with ``CI=true`` they fail.
"""
from __future__ import annotations

import functools
import http.server
import os
import re
import shutil
import threading
from pathlib import Path

import pytest

from jupyterlab_driver import ARGS, CHROMIUM  # one place for the browser's path and flags

ROOT = Path(__file__).resolve().parents[2]
HTML = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html"))  # another build can be tested
SHOTS = HTML.parent / "screenshots"
IN_CI = os.environ.get("CI", "").lower() == "true"


def _unavailable(reason: str):
    if IN_CI:
        pytest.fail(f"browser test cannot run under CI=true: {reason}")
    pytest.skip(reason)


def _book_pages() -> list[str]:
    """Every page of the book proper: the files named in _toc.yml, as built HTML paths."""
    toc = (ROOT / "_toc.yml").read_text()
    files = re.findall(r"(?:root|file):\s*(\S+)", toc)
    return [f + ".html" for f in files]


@pytest.fixture(scope="module")
def server():
    if not (HTML / "index.html").exists():
        _unavailable(f"the book is not built ({HTML}/index.html missing): run jupyter-book build . first")

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    handler = functools.partial(Quiet, directory=str(HTML))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}/"
    httpd.shutdown()


@pytest.fixture(scope="module")
def browser():
    if not (Path(CHROMIUM).exists() or shutil.which(CHROMIUM)):
        _unavailable(f"Chromium not found at {CHROMIUM} (apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _unavailable("playwright (Python) is not installed")
    with sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        yield b
        b.close()


# JavaScript run in the page -------------------------------------------------------------------------------
MATH_STATE = """() => {
  const all = Array.from(document.querySelectorAll('.math, .math-wrapper'));
  const untyped = all.filter(e => !e.querySelector('mjx-container'));
  const errors = document.querySelectorAll('mjx-merror').length;
  return {count: all.length, untyped: untyped.map(e => e.textContent.slice(0, 80)), errors};
}"""

FIGURE_STATE = """() => Array.from(document.querySelectorAll('.plotly-graph-div')).map(gd => ({
  id: gd.id,
  rendered: !!gd._fullLayout && gd.querySelectorAll('.main-svg').length > 0,
  traces: (gd._fullData || []).length,
  sliders: gd.querySelectorAll('.slider-container').length,
  caption: (() => { const f = gd.closest('figure'); const c = f && f.querySelector('figcaption');
                    return c ? c.textContent.trim() : ''; })()
}))"""

EXERCISES = """() => {
  const sec = document.getElementById('exercises');
  if (!sec) return -1;
  return sec.querySelectorAll('details.sd-dropdown, div.dropdown').length;
}"""

FIGURE_DIGEST = """(id) => {
  const gd = document.getElementById(id);
  const skip = (k, v) => (k.startsWith('_') || k === 'sliders') ? undefined
      : (ArrayBuffer.isView(v) ? Array.from(v) : v);
  return JSON.stringify(gd.data, skip) + JSON.stringify(gd.layout, skip);
}"""


def _page_url(server, page):
    return server + page


@pytest.mark.parametrize("page", _book_pages())
def test_page_offline(page, server, browser):
    external, failed, console, errors = [], [], [], []
    context = browser.new_context(viewport={"width": 1280, "height": 900})

    def route(r):
        if r.request.url.startswith(server) or r.request.url.startswith("data:") or r.request.url.startswith("blob:"):
            r.continue_()
        else:
            external.append(r.request.url)
            r.abort()

    context.route("**/*", route)
    pg = context.new_page()
    pg.on("requestfailed", lambda r: failed.append(f"{r.url} ({r.failure})") if r.url.startswith(server) else None)
    pg.on("console", lambda m: console.append(m.text) if m.type == "error" else None)
    pg.on("pageerror", lambda e: errors.append(str(e)))
    resp = pg.goto(_page_url(server, page), wait_until="load")
    assert resp is not None and resp.ok, f"{page}: HTTP {resp.status if resp else 'no response'}"

    # MathJax: wait for the typesetting promise, then every math element must hold typeset output
    pg.wait_for_function("() => !document.querySelector('.math') || (window.MathJax && MathJax.startup && MathJax.startup.promise)", timeout=30000)
    pg.evaluate("() => window.MathJax && MathJax.startup ? MathJax.startup.promise : null")
    math = pg.evaluate(MATH_STATE)
    assert not math["untyped"], f"{page}: {len(math['untyped'])} math elements not typeset, e.g. {math['untyped'][:3]}"
    assert math["errors"] == 0, f"{page}: {math['errors']} MathJax errors"

    # plotly figures rendered
    pg.wait_for_timeout(300)
    figs = pg.evaluate(FIGURE_STATE)
    bad = [f["id"] for f in figs if not f["rendered"] or f["traces"] == 0]
    assert not bad, f"{page}: figures not rendered: {bad}"

    uncaptioned = [f["id"] for f in figs if len(f["caption"]) < 20]
    assert not uncaptioned, f"{page}: {len(uncaptioned)} figures without a caption (use plots.publish + glue:figure)"

    name = Path(page).stem
    is_chapter = bool(re.match(r"\d\d_", name)) or name.startswith("appendix")
    if is_chapter:
        assert figs, f"{page}: a chapter page without any figure"
        n_solutions = pg.evaluate(EXERCISES)
        assert n_solutions >= 4, (f"{page}: the 'Exercises' section is missing or has fewer than four folded "
                                  f"solutions ({n_solutions})")
        with_slider = [f for f in figs if f["sliders"]]
        assert with_slider, f"{page}: no static slider figure (every chapter needs one that works without a kernel)"
        fid = with_slider[0]["id"]
        gd = pg.locator(f'[id="{fid}"]')
        gd.scroll_into_view_if_needed()
        before = pg.evaluate(FIGURE_DIGEST, fid)
        n = pg.evaluate("(id) => document.getElementById(id).layout.sliders[0].steps.length", fid)
        assert n >= 2, f"{page}: slider with {n} steps"
        start = pg.evaluate("(id) => document.getElementById(id).layout.sliders[0].active || 0", fid)
        # plotly draws only every k-th step label when they would overlap, so click the rail itself: its
        # far end is the last step (or the first, if the slider starts at the end)
        rail = gd.locator(".slider-container").first.locator(".slider-rail-touch-rect").bounding_box()
        target = 0 if start == n - 1 else n - 1
        x = rail["x"] + (6 if target == 0 else rail["width"] - 6)
        pg.mouse.click(x, rail["y"] + rail["height"] / 2)
        pg.wait_for_timeout(600)
        after = pg.evaluate(FIGURE_DIGEST, fid)
        active = pg.evaluate("(id) => document.getElementById(id).layout.sliders[0].active", fid)
        assert active == target, f"{page}: clicking the rail's end left the slider at step {active}, not {target}"
        assert after != before, f"{page}: moving the slider did not change the figure"

    SHOTS.mkdir(parents=True, exist_ok=True)
    pg.screenshot(path=str(SHOTS / f"{name}.png"), full_page=True)
    context.close()

    assert not external, f"{page}: requests to other hosts: {external[:5]}"
    assert not failed, f"{page}: failed requests: {failed[:5]}"
    assert not console, f"{page}: console errors: {console[:5]}"
    assert not errors, f"{page}: page errors: {errors[:5]}"


ANIMATIONS = """() => Array.from(document.querySelectorAll('.plotly-graph-div'))
  .filter(gd => (gd.layout.updatemenus || []).some(m => (m.buttons || []).some(b => b.method === 'animate')))
  .map(gd => gd.id)"""


@pytest.mark.parametrize("page", ["book/intro.html", "book/03_trajectory.html", "book/04_clik.html",
                                  "book/06_control.html"])
def test_animations_play(page, server, browser):
    """Every animation of the page plays offline: pressing its Play button makes the frames advance; a
    screenshot of each, taken while it plays, goes to ``_build/screenshots/``. The page stays under 3 MB."""
    size = (HTML / page).stat().st_size
    assert size <= 3 * 2**20, f"{page}: {size / 2**20:.2f} MB of HTML (limit 3 MB)"
    context = browser.new_context(viewport={"width": 1280, "height": 900})
    context.route("**/*", lambda r: r.continue_() if r.request.url.startswith(server) else r.abort())
    pg = context.new_page()
    pg.goto(_page_url(server, page), wait_until="load")
    pg.wait_for_timeout(500)
    ids = pg.evaluate(ANIMATIONS)
    assert ids, f"{page}: no animation (a figure with a Play button)"
    SHOTS.mkdir(parents=True, exist_ok=True)
    for fid in ids:
        gd = pg.locator(f'[id="{fid}"]')
        gd.scroll_into_view_if_needed()
        pg.evaluate("""(id) => { const gd = document.getElementById(id); gd.__frames = 0;
                                 gd.on('plotly_animatingframe', () => { gd.__frames += 1; }); }""", fid)
        gd.locator(".updatemenu-button", has_text="Play").first.click()
        pg.wait_for_timeout(2500)
        played = pg.evaluate("(id) => document.getElementById(id).__frames", fid)
        gd.screenshot(path=str(SHOTS / f"animation_{Path(page).stem}_{fid}.png"))
        gd.locator(".updatemenu-button", has_text="Pause").first.click()
        assert played >= 3, f"{page}: pressing Play on {fid} advanced {played} frames in 2.5 s"
    context.close()
