"""What a reader sees on a built page, measured in the browser: used by ``test_browser.py`` and runnable alone.

Each check is a JavaScript function evaluated in the page once MathJax has typeset it and plotly has drawn
its figures; each returns a list of human-readable problems (empty when the page is clean):

- ``WIDE_EQUATIONS``: display equations wider than the text column (at 390 px they would need hidden
  sideways scrolling);
- ``WIDE_TABLES``: tables wider than the text column that are cut off (a table may scroll inside its box);
- ``LABEL_OVERLAPS``: two text labels of one figure whose bounding boxes overlap (annotations, text drawn on
  traces, the title, axis titles), a figure title that overlaps its legend, an axis title outside its figure.

:func:`layout_problems` adds the checks of ``figure_checks.py``, ``style_checks.py`` and ``text_checks.py``.

Run alone on a build (it serves the folder on 127.0.0.1 and opens each page at 390 and 1280 px, in the light
and the dark theme; every page of the book when none is named)::

    python tests/book/page_checks.py _build/html book/03_trajectory.html [more pages]
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "_ext"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from figure_checks import _COMMON, figure_problems  # noqa: E402
from print_edition import FIGURES_READY, book_pages, serve, settle  # noqa: E402, F401 - one page server, one wait for a drawn page
from style_checks import style_problems  # noqa: E402
from text_checks import text_problems  # noqa: E402

# the width of a phone and of a laptop, in CSS pixels
PHONE, LAPTOP = 390, 1280

WIDE_EQUATIONS = """() => {
  const out = [];
  document.querySelectorAll('div.math').forEach((box, i) => {
    const m = box.querySelector('mjx-container > mjx-math, mjx-container svg');
    if (!m) return;
    // a number floated right leaves the equation the rest of the line (on a phone it has a line of its own)
    const eqno = box.querySelector('.eqno');
    const floated = eqno && getComputedStyle(eqno).float !== 'none';
    const room = box.clientWidth - (floated ? eqno.getBoundingClientRect().width : 0);
    const width = m.getBoundingClientRect().width;
    if (width > room + 1) {
      const id = box.id || (box.querySelector('[id]') || {}).id || ('#' + (i + 1));
      out.push(`equation ${id} is ${Math.round(width)} px wide in a ${Math.round(room)} px column: `
               + box.textContent.replace(/\\s+/g, ' ').trim().slice(0, 60));
    }
  });
  return out;
}"""

WIDE_TABLES = """() => {
  const out = [];
  document.querySelectorAll('article table').forEach((t, i) => {
    // a wide table may scroll sideways inside its own box (as the theme's tables do), but never be cut off
    let box = t.parentElement, scrolls = false;
    for (; box && box.tagName !== 'ARTICLE'; box = box.parentElement) {
      const o = getComputedStyle(box).overflowX;
      if (o === 'auto' || o === 'scroll') { scrolls = true; break; }
      if (o === 'hidden' || o === 'clip') break;
    }
    const room = document.querySelector('article').clientWidth;
    const width = t.getBoundingClientRect().width;
    if (width > room + 1 && !scrolls)
      out.push(`table ${i + 1} is ${Math.round(width)} px wide in a ${room} px column and cut off: `
               + t.textContent.replace(/\\s+/g, ' ').trim().slice(0, 60));
  });
  return out;
}"""

# The text of a figure: annotations (subplot titles included), text drawn on traces, the title and the axis
# titles. Legend entries are checked as one box against the title. Hidden and empty texts are skipped.
LABEL_OVERLAPS = "() => {" + _COMMON + """
  const out = [];
  const visible = visibleBox;
  const overlap = (a, b, tol) => Math.min(a.right, b.right) - Math.max(a.left, b.left) > tol
                              && Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top) > tol;
  document.querySelectorAll('.plotly-graph-div').forEach(gd => {
    if (!gd._fullLayout) return;
    const name = gd.id;
    const labels = [];
    const take = (sel, kind) => gd.querySelectorAll(sel).forEach(el => {
      const r = visible(el);
      if (r) labels.push({kind, text: el.textContent.trim().slice(0, 40), r});
    });
    take('.annotation-text-g text, .annotation text', 'annotation');
    take('.textpoint text', 'trace text');
    take('.g-gtitle text, .gtitle', 'title');
    take('[class*="xtitle"], [class*="ytitle"]', 'axis title');
    const seen = new Set(), uniq = labels.filter(l => {
      const k = [l.text, Math.round(l.r.left), Math.round(l.r.top)].join('|');
      if (seen.has(k)) return false; seen.add(k); return true; });
    for (let i = 0; i < uniq.length; i++)
      for (let j = i + 1; j < uniq.length; j++)
        if (overlap(uniq[i].r, uniq[j].r, 1))
          out.push(`${name}: ${uniq[i].kind} "${uniq[i].text}" overlaps ${uniq[j].kind} "${uniq[j].text}"`);
    const legend = gd.querySelector('.legend');
    const lr = legend && visible(legend);
    if (lr) uniq.filter(l => l.kind === 'title' || l.kind === 'axis title').forEach(t => {
      if (overlap(t.r, lr, 1)) out.push(`${name}: ${t.kind} "${t.text}" overlaps the legend`);
    });
    const fr = gd.getBoundingClientRect();
    uniq.filter(l => l.kind === 'axis title' || l.kind === 'title').forEach(t => {
      if (t.r.left < fr.left - 1 || t.r.right > fr.right + 1 || t.r.top < fr.top - 1 || t.r.bottom > fr.bottom + 1)
        out.push(`${name}: ${t.kind} "${t.text}" spills out of the figure`);
    });
  });
  return out;
}"""

def layout_problems(pg, width: int, dark: bool = False) -> list[str]:
    """Every problem of the page at this viewport width (the page is loaded and settled, in the dark theme when
    ``dark``): the overlaps above, the figures' own checks (``figure_checks.py``), the style's (readouts, tables,
    equations and dropdowns: ``style_checks.py``) and, at a laptop's width, the text's (``text_checks.py``)."""
    problems = list(pg.evaluate(LABEL_OVERLAPS)) + figure_problems(pg, width) + style_problems(pg, width, dark)
    if width >= LAPTOP:
        problems += text_problems(pg)
    if width <= PHONE:
        problems += pg.evaluate(WIDE_EQUATIONS) + pg.evaluate(WIDE_TABLES)
    return problems


def unavailable(reason: str):
    """A browser test that cannot run: skipped with the reason, or failed under ``CI=true``."""
    if os.environ.get("CI", "").lower() == "true":
        pytest.fail(f"browser test cannot run under CI=true: {reason}")
    pytest.skip(reason)


def main(argv: list[str]) -> int:
    from playwright.sync_api import sync_playwright

    from jupyterlab_driver import ARGS, CHROMIUM

    folder, pages = Path(argv[0]), argv[1:]
    if not pages:  # the pages of the book, in reading order
        root = Path(__file__).resolve().parents[2]
        pages = [p + ".html" for p in book_pages(root)]
    httpd, url = serve(folder)
    found = 0
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        for page in pages:
            page = page if "/" in page else "book/" + page
            for dark in (False, True):
                for width in (PHONE, LAPTOP):
                    ctx = browser.new_context(viewport={"width": width, "height": 900})
                    ctx.route("**/*", lambda r: r.continue_() if r.request.url.startswith(url) else r.abort())
                    if dark:  # the theme reads the reader's choice before it draws the page
                        ctx.add_init_script("localStorage.setItem('mode', 'dark'); localStorage.setItem('theme', 'dark');")
                    pg = ctx.new_page()
                    pg.goto(url + page, wait_until="load")
                    settle(pg)
                    problems = layout_problems(pg, width, dark)
                    found += len(problems)
                    print(f"{page} at {width} px, {'dark' if dark else 'light'}: {len(problems)} problem(s)",
                          flush=True)
                    for p in problems:
                        print("   ", p, flush=True)
                    ctx.close()
        browser.close()
    httpd.shutdown()
    return 1 if found else 0


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).parent))
    sys.exit(main(sys.argv[1:]))
