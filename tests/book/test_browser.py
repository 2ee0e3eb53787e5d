"""The built book in a real browser, offline.

Serves ``_build/html`` on 127.0.0.1, aborts every other request, opens every page in Debian's Chromium
(headless, through Playwright) and fails on: an external or failed request, a console error or page error,
math MathJax did not typeset, a plotly figure that did not render or has no text alternative (its caption as
an ``aria-label``), overlapping text in a figure (``page_checks.py``), and, on every chapter page, a static
slider that does not change its figure when moved. At phone width (390 px) every display equation must fit
the column and no table may be cut off. The figures must follow the theme's dark mode, and search results
must read as text, not TeX. Screenshots go to ``_build/screenshots/``: each page, and each figure alone
(``figure_<name>.png``).

Outside CI a missing Chromium or a missing build skips with the reason; with ``CI=true`` they fail.
"""
from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest

from jupyterlab_driver import ARGS, CHROMIUM  # one place for the browser's path and flags
from page_checks import LAPTOP, PHONE, book_pages, layout_problems, serve, settle
from page_checks import unavailable as _unavailable

ROOT = Path(__file__).resolve().parents[2]
HTML = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html"))  # another build can be tested
SHOTS = HTML.parent / "screenshots"


def _book_pages() -> list[str]:
    """Every page of the book proper: the files named in _toc.yml, as built HTML paths."""
    return [f + ".html" for f in book_pages(ROOT)]


@pytest.fixture(scope="module")
def server():
    if not (HTML / "index.html").exists():
        _unavailable(f"the book is not built ({HTML}/index.html missing): run jupyter-book build . first")
    httpd, url = serve(HTML)
    yield url
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
                    return c ? c.textContent.trim() : ''; })(),
  label: gd.getAttribute('aria-label') || ''
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
    pg.wait_for_function("() => !document.querySelector('.math') || (window.MathJax && MathJax.startup && MathJax.startup.promise)", timeout=120000)
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
    unlabelled = [f["id"] for f in figs if len(f["label"]) < 20]
    assert not unlabelled, f"{page}: figures without a text alternative (aria-label): {unlabelled}"
    settle(pg)
    problems = layout_problems(pg, LAPTOP)
    assert not problems, f"{page} at {LAPTOP} px:\n  " + "\n  ".join(problems)

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
    for fig_id in pg.evaluate("() => Array.from(document.querySelectorAll('figure[id^=\"fig-\"]')).map(f => f.id)"):
        figure = pg.locator(f'figure[id="{fig_id}"]')
        figure.scroll_into_view_if_needed()
        figure.screenshot(path=str(SHOTS / f"figure_{fig_id}.png"))  # one file per figure, to look at
    context.close()

    assert not external, f"{page}: requests to other hosts: {external[:5]}"
    assert not failed, f"{page}: failed requests: {failed[:5]}"
    assert not console, f"{page}: console errors: {console[:5]}"
    assert not errors, f"{page}: page errors: {errors[:5]}"


ANIMATIONS = """() => Array.from(document.querySelectorAll('.plotly-graph-div'))
  .filter(gd => (gd.layout.updatemenus || []).some(m => (m.buttons || []).some(b => b.method === 'animate')))
  .map(gd => gd.id)"""


@pytest.mark.parametrize("page", ["book/intro.html", "book/03_trajectory.html", "book/04_clik.html",
                                  "book/06_control.html", "book/07_interaction.html"])
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


def _open(browser, server, page, width, dark=False):
    context = browser.new_context(viewport={"width": width, "height": 900})
    context.route("**/*", lambda r: r.continue_() if r.request.url.startswith(server) else r.abort())
    if dark:  # the theme reads the reader's choice from localStorage before it draws the page
        context.add_init_script("localStorage.setItem('mode', 'dark'); localStorage.setItem('theme', 'dark');")
    pg = context.new_page()
    pg.goto(_page_url(server, page), wait_until="load")
    settle(pg)
    return context, pg


@pytest.mark.parametrize("page", _book_pages())
def test_page_fits_a_phone(page, server, browser):
    """At 390 px every display equation fits the column (long ones are split over lines), no table is cut off
    (a wide one scrolls in its own box) and no two labels of a figure overlap. A screenshot of each page at
    that width goes to ``_build/screenshots/phone_<page>.png``."""
    context, pg = _open(browser, server, page, PHONE)
    problems = layout_problems(pg, PHONE)
    SHOTS.mkdir(parents=True, exist_ok=True)
    pg.screenshot(path=str(SHOTS / f"phone_{Path(page).stem}.png"), full_page=True)
    context.close()
    assert not problems, f"{page} at {PHONE} px:\n  " + "\n  ".join(problems)


FIGURE_COLOURS = """() => Array.from(document.querySelectorAll('.js-plotly-plot')).map(gd => {
  const lum = (c) => { const x = scaraReader.luminance(c); return x === null ? null : Math.round(x * 1000) / 1000; };
  const full = gd._fullLayout;
  const traces = (gd._fullData || []).flatMap(t => ['line', 'marker'].map(k => t[k] && t[k].color)
      .filter(c => typeof c === 'string'));
  return {id: gd.id, paper: full.paper_bgcolor, plot: full.plot_bgcolor, font: lum(full.font.color),
          darkest: Math.min(1, ...traces.map(lum).filter(x => x !== null)),
          page: lum(getComputedStyle(document.body).backgroundColor)};
})"""


#: the pages whose figures are checked in the dark theme one by one (and back in light): the three with the most figures
DARK_FIGURES = ("book/03_trajectory.html", "book/06_control.html", "book/07_interaction.html")


@pytest.mark.parametrize("width", [PHONE, LAPTOP])
@pytest.mark.parametrize("page", _book_pages())
def test_page_in_dark_mode(page, width, server, browser):
    """In the dark theme, at both widths, every page passes the same checks as in light: among them animations
    whose time readout reads in the dark, dark tables and dropdown arrows that can be seen (``style_checks``).
    On the pages of :data:`DARK_FIGURES` (one load of the page serves both), every figure drops its white
    background, writes its text in a light colour and lightens trace colours too dark to see; switching back to
    light restores the figures. Screenshots of the dark page go to ``_build/screenshots/dark_<page>.png`` (1280 px)
    and ``dark_phone_<page>.png`` (390 px)."""
    context, pg = _open(browser, server, page, width, dark=True)
    assert pg.evaluate("() => document.documentElement.dataset.theme") == "dark"
    pg.wait_for_timeout(300)
    problems = layout_problems(pg, width, dark=True)
    if page in DARK_FIGURES:
        _figures_follow_dark_mode(pg, page, width)
    context.close()
    assert not problems, f"{page} at {width} px, dark:\n  " + "\n  ".join(problems)


def _figures_follow_dark_mode(pg, page, width):
    stem = Path(page).stem
    SHOTS.mkdir(parents=True, exist_ok=True)
    pg.wait_for_timeout(200)
    figs = pg.evaluate(FIGURE_COLOURS)
    assert figs and figs[0]["page"] < 0.1, f"{page}: the page itself is not dark ({figs[:1]})"
    for f in figs:
        paper = pg.evaluate("(c) => scaraReader.rgba(c)", f["paper"])
        assert paper[3] == 0 or pg.evaluate("(c) => scaraReader.luminance(c)", f["paper"]) < 0.1, \
            f"{page}: figure {f['id']} keeps a light background {f['paper']} in dark mode"
        assert f["font"] > 0.4, f"{page}: figure {f['id']} writes dark text ({f['font']}) in dark mode"
        assert f["darkest"] >= 0.08, f"{page}: figure {f['id']} draws a trace too dark to see ({f['darkest']})"
    pg.screenshot(path=str(SHOTS / (f"dark_{stem}.png" if width == LAPTOP else f"dark_phone_{stem}.png")),
                  full_page=True)
    if width == LAPTOP:  # and back: the reader switches to light, the figures follow
        pg.evaluate("() => { document.documentElement.dataset.theme = 'light'; }")
        pg.wait_for_timeout(800)
        light = pg.evaluate(FIGURE_COLOURS)
        bad = [f["id"] for f in light if pg.evaluate("(c) => scaraReader.luminance(c)", f["paper"]) < 0.9]
        assert not bad, f"{page}: figures {bad} stay dark after switching back to light"


@pytest.mark.parametrize("query", ["Jacobian", "inertia", "sliding"])
def test_search_reads_as_text(query, server, browser):
    """Search results list text, not the TeX source of the math they cut from a page (no \\( or _{ ... })."""
    context = browser.new_context(viewport={"width": LAPTOP, "height": 900})
    context.route("**/*", lambda r: r.continue_() if r.request.url.startswith(server) else r.abort())
    pg = context.new_page()
    pg.goto(server + "search.html?q=" + query, wait_until="load")
    pg.wait_for_function("() => document.querySelectorAll('#search-results p.context').length > 0", timeout=60000)
    pg.wait_for_timeout(1500)  # the summaries arrive one page at a time
    summaries = pg.evaluate("() => Array.from(document.querySelectorAll('#search-results p.context'))"
                            ".map(p => p.textContent)")
    context.close()
    assert len(summaries) >= 2, f"search for {query!r}: {len(summaries)} results with a summary"
    tex = [s for s in summaries if re.search(r"\\[()\[\]]|\\[A-Za-z]{2,}|[_^]\{", s)]
    assert not tex, f"search for {query!r}: summaries with raw TeX: {[t[:120] for t in tex[:3]]}"


SOLUTION_TITLES = """() => Array.from(document.querySelectorAll('.solution.dropdown')).map(s => s.id)"""


@pytest.mark.parametrize("page", ["book/01_kinematics.html", "book/04_clik.html", "book/appendix_verification.html"])
def test_a_click_anywhere_on_a_solutions_title_opens_it(page, server, browser):
    """Each folded solution opens from a click on the link in its title ("Exercise 4.1 (...)"), on its title's
    text and on its chevron, without leaving the solution for its exercise and without an error in the page;
    a second click folds it again."""
    context, pg = _open(browser, server, page, LAPTOP)
    errors = []
    pg.on("pageerror", lambda exc: errors.append(str(exc)))
    ids = pg.evaluate(SOLUTION_TITLES)
    assert ids, f"{page} has no folded solution"
    url = pg.url
    hidden = "(id) => document.getElementById(id).classList.contains('toggle-hidden')"
    for k, sid in enumerate(ids):
        box = pg.locator(f"[id='{sid}']")
        title = box.locator(":scope > .admonition-title")
        target = [title.locator("a").first, title, title.locator(".toggle-button")][k % 3]
        assert pg.evaluate(hidden, sid), f"{page}: {sid} is open before any click"
        target.click()
        pg.wait_for_timeout(150)
        assert not pg.evaluate(hidden, sid), f"{page}: a click on the title of {sid} left it folded"
        assert pg.url == url, f"{page}: a click on the title of {sid} went to {pg.url}"
        title.click(position={"x": 5, "y": 5})
        pg.wait_for_timeout(150)
        assert pg.evaluate(hidden, sid), f"{page}: a second click on the title of {sid} did not fold it"
    context.close()
    assert not errors, f"{page}: errors in the page: {errors}"
