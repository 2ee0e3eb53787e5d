"""Local Sphinx extension: the book on paper, as PDF, printed from the built pages by Chromium.

When an HTML build finishes, every page of the book is opened in Chromium (headless, through Playwright) at
the width of an A4 page, as a reader's browser draws it: MathJax typesets the math and plotly draws the
figures. ``print_static/prepare.js`` then turns each page into print: a figure becomes a vector image; a
figure with a slider (or a menu) becomes small multiples, a few of its steps side by side with the step's
value under each; an animation becomes a strip of frames with their times; live panels become a line of
text; folded solutions print open. The pages are joined into one document with a title page and a table of
contents whose page numbers come from a first print (the PDF's own destinations), and links between pages
become links inside the PDF. Written to ``_downloads/print/``:

- ``scara-book.pdf``, the whole book, with bookmarks (the PDF outline) and page numbers;
- one PDF per page of the book, ``<page>.pdf`` (``03_trajectory.pdf``), for handouts: that page's pages of the
  whole book (each chapter starts on a new sheet), with the book's page numbers and the links that stay inside it;
- ``manifest.json``: per page, what was printed (each figure's kind and the steps or frames shown) and the
  page count of each PDF, which ``tests/book/test_print.py`` checks against the PDFs.

Every page of the book links to the whole book and to its own PDF, beside the take-home download
(``take_home.py`` writes that block and asks :func:`links` for these lines).

Why Chromium and not Sphinx's LaTeX builder: the figures are plotly figures, drawn by JavaScript, and the
math is MathJax; Chromium prints exactly what a reader sees, from the same HTML, with no TeX installation
(a few hundred MB). Printing needs Chromium and Playwright, which the browser test already needs. Where
Chromium is missing the build says so and writes no print edition (and the pages carry no print link);
under ``CI=true`` that is an error. Run alone on a build: ``python _ext/print_edition.py _build/html``.
"""
from __future__ import annotations

import functools
import hashlib
import html
import http.server
import json
import os
import re
import shutil
import threading
from pathlib import Path

STATIC = Path(__file__).parent / "print_static"
OUT_DIR = "_downloads/print"
BOOK_PDF = "scara-book.pdf"
CHROMIUM = os.environ.get("SCARA_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"]
PRINT_WIDTH = 680                  # CSS px of an A4 page between 16 mm margins (178 mm at 96 px per inch)
MULTIPLES, FRAMES = 4, 6           # steps printed of a slider figure, frames of an animation
MARGIN = {"top": "18mm", "bottom": "18mm", "left": "16mm", "right": "16mm"}
FOOTER = ('<div style="font-size:8pt;width:100%;text-align:center;color:#444;font-family:sans-serif">'
          '<span class="pageNumber"></span></div>')
HEADER = ('<div style="font-size:7.5pt;width:100%;padding:0 16mm;color:#666;font-family:sans-serif">'
          '{title}</div>')


def available() -> str | None:
    """None when this machine can print the book, else why not."""
    if not (Path(CHROMIUM).exists() or shutil.which(CHROMIUM)):
        return f"Chromium not found at {CHROMIUM} (apt-get install chromium)"
    try:
        import playwright.sync_api  # noqa: F401, PLC0415
    except ImportError:
        return "playwright (Python) is not installed"
    return None


def book_pages(root: Path) -> list[str]:
    """The pages of the book in reading order (``_toc.yml``), as paths under the build without ``.html``."""
    return re.findall(r"(?:root|file):\s*(\S+)", (root / "_toc.yml").read_text())


def serve(folder: Path):
    """Serve ``folder`` on 127.0.0.1 (a free port) from a daemon thread: ``(server, base URL)``."""
    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(folder)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    return httpd, f"http://127.0.0.1:{httpd.server_address[1]}/"


# A page is ready when MathJax has typeset it and plotly has drawn every figure.
MATH_READY = ("() => !document.querySelector('.math') || !!(window.MathJax && MathJax.startup"
              " && MathJax.startup.promise)")
FIGURES_READY = """() => Array.from(document.querySelectorAll('.plotly-graph-div')).every(
  gd => !!gd._fullLayout && gd.querySelectorAll('.main-svg').length > 0)"""


def settle(pg, timeout: float = 120000) -> None:
    """Wait until MathJax has typeset the page and every plotly figure is drawn (and redrawn at this width)."""
    pg.wait_for_function(MATH_READY, timeout=timeout)
    pg.evaluate("() => window.MathJax && MathJax.startup ? MathJax.startup.promise.then(() => true) : true")
    pg.wait_for_function(FIGURES_READY, timeout=timeout)
    pg.evaluate("() => Promise.all(Array.from(document.querySelectorAll('.plotly-graph-div'))"
                ".map(gd => window.Plotly ? Plotly.Plots.resize(gd) : null))")
    pg.wait_for_timeout(200)


def _stem(page: str) -> str:
    return page.rsplit("/", 1)[-1]


def _read_pages(browser, url: str, pages: list[str]) -> list[dict]:
    """Each page, drawn at print width and turned into print by ``prepare.js``."""
    script = (STATIC / "prepare.js").read_text()
    stems = [_stem(p) for p in pages]

    def read(page: str) -> dict:
        ctx = browser.new_context(viewport={"width": PRINT_WIDTH + 80, "height": 1000})
        ctx.route("**/*", lambda r: r.continue_() if r.request.url.startswith(url) else r.abort())
        try:
            pg = ctx.new_page()
            errors: list[str] = []
            pg.on("pageerror", lambda e: errors.append(str(e)))
            pg.goto(url + page + ".html", wait_until="load")
            pg.wait_for_selector("article.bd-article", state="attached")
            settle(pg)
            title = pg.evaluate("() => (document.querySelector('article h1') || {}).textContent || document.title")
            done = pg.evaluate(script, {"stem": _stem(page), "pages": stems, "multiples": MULTIPLES,
                                        "frames": FRAMES, "width": PRINT_WIDTH})
        finally:
            ctx.close()
        if errors:
            raise RuntimeError(f"printing {page}: the page raised {errors[0]}")
        return {"page": page, "stem": _stem(page), "title": title.replace("#", "").strip(), **done}

    from sphinx.util import logging  # noqa: PLC0415

    out = []
    for page in pages:
        try:
            out.append(read(page))
        except Exception as exc:  # noqa: BLE001 - a browser's hiccup on a busy machine: once more, then it stands
            logging.getLogger(__name__).info(f"print edition: reading {page} again after: {exc}")
            out.append(read(page))
    return out


def _head(styles: str, sheets: list[str]) -> str:
    links = "\n".join(f'<link rel="stylesheet" href="{html.escape(s)}">' for s in sheets)
    return (f'<!DOCTYPE html><html lang="en" data-theme="light" data-mode="light"><head><meta charset="utf-8">'
            f"<title>The SCARA arm</title>{links}\n<style>{styles}</style>\n"
            f'<link rel="stylesheet" href="../_print/print.css"></head>')


def compose(chapters: list[dict], title: str, numbers: dict[str, int] | None = None, toc: bool = True) -> str:
    """One printable HTML document of ``chapters`` (from :func:`_read_pages`): a title page and a table of
    contents (with page numbers once ``numbers`` gives them, destination name -> page), then each page."""
    styles = "\n".join(dict.fromkeys(c["styles"] for c in chapters))
    sheets = list(dict.fromkeys(s for c in chapters for s in c["sheets"]))
    parts = [_head(styles, sheets), "<body>"]
    if toc:
        parts.append(f'<section class="print-title"><h1 class="print-book-title">{html.escape(title)}</h1>'
                     '<p class="print-subtitle">The print edition of the course book: every chapter, its figures '
                     "(a slider figure at a few of its steps, an animation as a strip of frames) and its solutions.</p>"
                     "</section>")
        parts.append('<nav class="print-toc"><h2>Contents</h2><ol>')
        for c in chapters:
            dest = "page--" + c["stem"]
            num = (numbers or {}).get(dest, "")
            parts.append(f'<li class="toc-chapter"><a href="#{dest}"><span>{html.escape(c["title"])}</span>'
                         f'<span class="toc-page">{num}</span></a>')
            secs = c.get("sections", [])
            if secs:
                parts.append("<ol>")
                for sid, text in secs:
                    num = (numbers or {}).get(sid, "")
                    parts.append(f'<li><a href="#{sid}"><span>{html.escape(text)}</span>'
                                 f'<span class="toc-page">{num}</span></a></li>')
                parts.append("</ol>")
            parts.append("</li>")
        parts.append("</ol></nav>")
    for c in chapters:
        parts.append(f'<section class="print-chapter" id="page--{c["stem"]}">{c["html"]}</section>')
    parts.append("</body></html>")
    return "\n".join(parts)


def _print(browser, url: str, folder: Path, doc: str, name: str, title: str) -> bytes:
    """``doc`` printed to PDF by Chromium (written beside the pages so that their relative links hold)."""
    path = folder / "book" / name
    path.write_text(doc, encoding="utf-8")
    try:
        ctx = browser.new_context()
        ctx.route("**/*", lambda r: r.continue_() if r.request.url.startswith(url) else r.abort())
        pg = ctx.new_page()
        pg.goto(url + "book/" + name, wait_until="load")
        pg.evaluate("() => document.fonts.ready.then(() => Promise.all(Array.from(document.images)"
                    ".map(i => i.decode().catch(() => null))))")
        data = pg.pdf(format="A4", margin=MARGIN, print_background=True, outline=True, tagged=True,
                      display_header_footer=True, footer_template=FOOTER,
                      header_template=HEADER.format(title=html.escape(title)))
        ctx.close()
    finally:
        path.unlink()
    return data


def _destinations(pdf: bytes) -> dict[str, int]:
    """Named destination -> page number (from 1) of a PDF Chromium printed."""
    import io  # noqa: PLC0415

    from pypdf import PdfReader  # noqa: PLC0415

    reader = PdfReader(io.BytesIO(pdf))
    return {name.lstrip("/"): reader.get_destination_page_number(d) + 1
            for name, d in reader.named_destinations.items()}


def _extract(pdf: bytes, first: int, last: int) -> bytes:
    """Pages ``first``..``last`` (from 1) of ``pdf`` as a PDF of their own, with the book's page numbers, the
    links that stay inside those pages and none that would lead out of them."""
    import io  # noqa: PLC0415

    from pypdf import PdfReader, PdfWriter  # noqa: PLC0415
    from pypdf.generic import ArrayObject, NameObject  # noqa: PLC0415

    reader = PdfReader(io.BytesIO(pdf))
    kept = {n.lstrip("/") for n, d in reader.named_destinations.items()
            if first <= reader.get_destination_page_number(d) + 1 <= last}

    def inside(annot) -> bool:
        dest = annot.get_object().get("/Dest")
        return dest is None or str(dest).lstrip("/") in kept

    writer = PdfWriter()
    writer.append(reader, pages=(first - 1, last))
    for page in writer.pages:
        if "/Annots" in page:
            page[NameObject("/Annots")] = ArrayObject([a for a in page["/Annots"].get_object() if inside(a)])
    buf = io.BytesIO()
    writer.write(buf)
    return buf.getvalue()


def _pages(pdf: bytes) -> int:
    import io  # noqa: PLC0415

    from pypdf import PdfReader  # noqa: PLC0415

    return len(PdfReader(io.BytesIO(pdf)).pages)


def print_book(html_dir: Path, root: Path, title: str) -> dict:
    """Print the book built in ``html_dir`` (sources in ``root``) to ``html_dir/_downloads/print``; returns the
    manifest it writes there."""
    from playwright.sync_api import sync_playwright  # noqa: PLC0415

    pages = book_pages(root)
    out = html_dir / OUT_DIR
    out.mkdir(parents=True, exist_ok=True)
    static = html_dir / "_print"
    static.mkdir(exist_ok=True)
    shutil.copy(STATIC / "print.css", static / "print.css")
    httpd, url = serve(html_dir)
    manifest = {"book": BOOK_PDF, "pages": []}
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
            chapters = _read_pages(browser, url, pages)
            # the first print finds each section's page; the second writes those numbers in the contents
            first = _print(browser, url, html_dir, compose(chapters, title), ".print-book.html", title)
            numbers = _destinations(first)
            book = _print(browser, url, html_dir, compose(chapters, title, numbers), ".print-book.html", title)
            browser.close()
        (out / BOOK_PDF).write_bytes(book)
        manifest["book_pages"] = _pages(book)
        numbers = _destinations(book)
        starts = [numbers["page--" + c["stem"]] for c in chapters] + [manifest["book_pages"] + 1]
        for c, start, end in zip(chapters, starts, starts[1:]):
            (out / f"{c['stem']}.pdf").write_bytes(_extract(book, start, end - 1))
            manifest["pages"].append({"page": c["page"], "title": c["title"], "pdf": f"{c['stem']}.pdf",
                                      "first_page": start, "last_page": end - 1, "figures": c["figures"]})
    finally:
        httpd.shutdown()
    (out / "manifest.json").write_text(json.dumps(manifest, indent=1))
    return manifest


def _fingerprint(html_dir: Path, root: Path) -> str:
    """A digest of what the print is made from: the built pages and the print's own files."""
    h = hashlib.sha256()
    for page in book_pages(root):
        h.update((html_dir / (page + ".html")).read_bytes())
    for f in sorted(STATIC.iterdir()) + [Path(__file__)]:
        h.update(f.read_bytes())
    return h.hexdigest()


# Sphinx ------------------------------------------------------------------------------------------------------
def _inited(app):
    why = available() if app.builder.format == "html" else "not an HTML build"
    app._print_edition = why is None
    if why and app.builder.format == "html":
        if os.environ.get("CI", "").lower() == "true":
            raise RuntimeError(f"the print edition cannot be built under CI=true: {why}")
        from sphinx.util import logging  # noqa: PLC0415

        logging.getLogger(__name__).info(f"print edition skipped: {why}")


def links(app, pathto, pagename: str) -> str:
    """The HTML line linking a page to the print edition (empty where none is built)."""
    if not getattr(app, "_print_edition", False):
        return ""
    book = pathto(f"{OUT_DIR}/{BOOK_PDF}", 1)
    own = pathto(f"{OUT_DIR}/{_stem(pagename)}.pdf", 1)
    return (f'<p class="print-edition">On paper: <a class="reference download print-book-link" href="{book}" '
            f'download>the whole book (PDF)</a>, or <a class="reference download print-page-link" href="{own}" '
            f"download>this page alone (PDF)</a>, to print as a handout.</p>")


def _finished(app, exc):
    if exc is not None or not getattr(app, "_print_edition", False):
        return
    from sphinx.util import logging  # noqa: PLC0415

    html_dir, root = Path(app.outdir), Path(app.srcdir)
    stamp = html_dir / OUT_DIR / ".fingerprint"
    digest = _fingerprint(html_dir, root)
    if stamp.is_file() and stamp.read_text() == digest and (html_dir / OUT_DIR / BOOK_PDF).is_file():
        logging.getLogger(__name__).info("print edition: up to date")
        return
    title = app.config.html_title or app.config.project  # Jupyter Book gives the title as html_title
    manifest = print_book(html_dir, root, title)
    stamp.write_text(digest)
    logging.getLogger(__name__).info(f"print edition: {manifest['book_pages']} pages, "
                                     f"{(html_dir / OUT_DIR / BOOK_PDF).stat().st_size / 2**20:.1f} MB")


def setup(app):
    app.connect("builder-inited", _inited)
    # after take_home and the others have written their files (priority: later runs later)
    app.connect("build-finished", _finished, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1.0"}


if __name__ == "__main__":
    import sys

    folder = Path(sys.argv[1]).resolve()
    m = print_book(folder, Path(__file__).resolve().parents[1], "The SCARA arm: modelling, planning and control")
    print(json.dumps({k: v for k, v in m.items() if k != "pages"}), [(p["pdf"], p["pdf_pages"]) for p in m["pages"]])
