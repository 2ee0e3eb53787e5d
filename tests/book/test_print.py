"""The print edition (``_ext/print_edition.py``): the whole book and one PDF per page, as a teacher prints them.

Checked on the build in ``_build/html`` (or ``SCARA_BOOK_HTML``): the PDFs exist and every page links to them; the
page counts agree with the manifest; every figure and every numbered equation of the web pages is in the PDF,
a slider figure as small multiples and an animation as a strip of frames, each labelled with its step; every
font is embedded; no page is blank and nothing is cut at the sheet's edges; every internal link (contents,
cross-references, citations) leads to a destination in the same PDF, and none leads back to the build's local
server. Pages rendered with ``pdftoppm`` go to ``_build/screenshots/print_*.png`` to look at.

Needs poppler-utils (``pdftoppm``, ``pdftotext``, ``pdffonts``) and pypdf; outside CI, without them (or without a
build) the tests skip with the reason, under ``CI=true`` they fail.
"""
from __future__ import annotations

import html as htmlmod
import io
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
HTML = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html"))
PRINT = HTML / "_downloads" / "print"
SHOTS = HTML.parent / "screenshots"
MM = 72 / 25.4  # PDF points per millimetre


def _unavailable(reason: str):
    if os.environ.get("CI", "").lower() == "true":
        pytest.fail(f"the print edition cannot be checked under CI=true: {reason}")
    pytest.skip(reason)


@pytest.fixture(scope="module")
def manifest():
    if not (PRINT / "manifest.json").is_file():
        _unavailable(f"no print edition in {PRINT} (build the book with Chromium installed)")
    for tool in ("pdftoppm", "pdftotext", "pdffonts"):
        if shutil.which(tool) is None:
            _unavailable(f"{tool} not found (apt-get install poppler-utils)")
    return json.loads((PRINT / "manifest.json").read_text())


@pytest.fixture(scope="module")
def book(manifest):
    from pypdf import PdfReader

    return PdfReader(io.BytesIO((PRINT / manifest["book"]).read_bytes()))


@pytest.fixture(scope="module")
def page_texts(manifest):
    """The text of each page of the whole book (pdftotext), in order."""
    out = subprocess.run(["pdftotext", "-layout", str(PRINT / manifest["book"]), "-"], check=True,
                         capture_output=True, text=True).stdout
    return out.split("\f")[:-1]


def _words(text: str) -> str:
    return re.sub(r"\s+", " ", text)


def test_page_counts(manifest, book):
    n = len(book.pages)
    assert n == manifest["book_pages"], f"the manifest says {manifest['book_pages']} pages, the PDF has {n}"
    assert 100 <= n <= 400, f"the whole book prints on {n} pages"
    from pypdf import PdfReader

    previous_last = 4  # a title page and the contents come first
    for p in manifest["pages"]:
        first, last = p["first_page"], p["last_page"]
        assert first > previous_last, f"{p['pdf']} starts at page {first}, inside the page before it"
        pdf = PdfReader(io.BytesIO((PRINT / p["pdf"]).read_bytes()))
        assert len(pdf.pages) == last - first + 1 >= 1, f"{p['pdf']}: {len(pdf.pages)} pages for {first}..{last}"
        previous_last = last
    assert previous_last == n, f"the last page's PDF ends at page {previous_last} of {n}"


def test_every_page_links_to_its_print(manifest):
    for p in manifest["pages"]:
        page = (HTML / (p["page"] + ".html")).read_text()
        links = dict(re.findall(r'class="reference download (print-book-link|print-page-link)" href="([^"]+)"', page))
        assert set(links) == {"print-book-link", "print-page-link"}, f"{p['page']}: print links {links}"
        for href in links.values():
            target = (HTML / p["page"]).parent / htmlmod.unescape(href)
            assert target.resolve().is_file(), f"{p['page']}: the link {href} leads to no file"
        assert links["print-page-link"].endswith(p["pdf"]), f"{p['page']}: its own PDF is {links['print-page-link']}"


def _html_figures(page: str) -> list[str]:
    text = (HTML / (page + ".html")).read_text()
    return re.findall(r'<span class="caption-number">(Fig\. [A-Z0-9.]+?) ?</span>', text)


def _html_equations(page: str) -> list[str]:
    text = (HTML / (page + ".html")).read_text()
    return re.findall(r'<span class="eqno">(\([A-Z0-9.]+\))', text)


def test_every_figure_and_equation_is_printed(manifest, page_texts):
    for p in manifest["pages"]:
        text = _words(" ".join(page_texts[p["first_page"] - 1:p["last_page"]]))
        web = _html_figures(p["page"])
        printed = [f["caption"] for f in p["figures"]]
        assert printed == web, f"{p['page']}: the web page has figures {web}, the print {printed}"
        for cap in web:
            assert f"{cap} " in text + " ", f"{p['pdf']}: the caption of {cap} is not in the PDF's text"
        for eq in _html_equations(p["page"]):
            assert eq in text, f"{p['pdf']}: equation {eq} is not in the PDF's text"
        for f in p["figures"]:
            if f["kind"] == "still":
                continue
            want = min(f["of"], {"animation": 6, "slider": 4}.get(f["kind"], f["of"]))
            assert len(f["labels"]) >= min(want, 3) and len(set(f["labels"])) == len(f["labels"]), \
                f"{p['page']}: {f['caption']} ({f['kind']}, {f['of']} steps) printed as {f['labels']}"
            for label in f["labels"]:
                assert _words(label) in text, f"{p['pdf']}: {f['caption']}'s step {label!r} is not in the PDF"


def test_fonts_are_embedded(manifest):
    rows = subprocess.run(["pdffonts", str(PRINT / manifest["book"])], check=True, capture_output=True,
                          text=True).stdout.splitlines()[2:]
    assert rows, "pdffonts lists no font"
    # the columns: name, type (one or two words), encoding, emb, sub, uni, object, ID
    bare = [r for r in rows if r.split()[-5] != "yes"]
    assert not bare, f"fonts not embedded: {bare}"


def _render(pdf: Path, dpi: int, first: int | None = None, last: int | None = None) -> list[np.ndarray]:
    """Pages of ``pdf`` as grey images (0 black, 255 white), through pdftoppm."""
    args = ["pdftoppm", "-gray", "-r", str(dpi)]
    if first:
        args += ["-f", str(first), "-l", str(last or first)]
    raw = subprocess.run(args + [str(pdf)], check=True, capture_output=True).stdout
    pages, i = [], 0
    while i < len(raw):  # a stream of binary PGMs: P5 width height 255 pixels
        head = re.match(rb"P5\s+(\d+)\s+(\d+)\s+(\d+)\s", raw[i:i + 40])
        w, h = int(head.group(1)), int(head.group(2))
        start = i + head.end()
        pages.append(np.frombuffer(raw[start:start + w * h], dtype=np.uint8).reshape(h, w))
        i = start + w * h
    return pages


def test_no_page_blank_or_cut(manifest):
    dpi = 30
    pages = _render(PRINT / manifest["book"], dpi)
    assert len(pages) == manifest["book_pages"]
    band = int(10 / 25.4 * dpi)  # the outer 10 mm of the 16 mm side margins stay white
    head = int(14 / 25.4 * dpi)  # the header and footer sit in the top and bottom margins
    for k, img in enumerate(pages, start=1):
        body = img[head:-head, band:-band]
        assert (body < 160).sum() > 50, f"page {k} of the book is blank"
        for side, strip in (("left", img[:, :band]), ("right", img[:, -band:])):
            assert strip.min() > 200, f"page {k}: something is cut at the {side} edge of the sheet"
    # a few pages to look at: the contents and the first sheet of each chapter with small multiples or frames
    SHOTS.mkdir(parents=True, exist_ok=True)
    pick = {2} | {p["first_page"] + 1 for p in manifest["pages"]
                  if any(f["kind"] in ("slider", "animation") for f in p["figures"])}
    for k in sorted(pick):
        subprocess.run(["pdftoppm", "-png", "-r", "60", "-f", str(k), "-l", str(k), "-singlefile",
                        str(PRINT / manifest["book"]), str(SHOTS / f"print_p{k:03d}")], check=True)


def test_links_stay_inside_the_book(manifest, book):
    names = {n.lstrip("/") for n in book.named_destinations}
    internal, external = 0, []
    for k, page in enumerate(book.pages, start=1):
        for annot in page.get("/Annots") or []:
            a = annot.get_object()
            if a.get("/Subtype") != "/Link":
                continue
            if "/Dest" in a:
                dest = str(a["/Dest"]).lstrip("/")
                assert dest in names, f"page {k}: a link to {dest!r}, which the PDF does not hold"
                internal += 1
            uri = str((a.get("/A") or {}).get("/URI", ""))
            if uri:
                external.append(uri)
    assert internal >= 200, f"only {internal} internal links (contents, cross-references, citations)"
    local = [u for u in external if re.match(r"(https?://(127\.0\.0\.1|localhost)|file:)", u)]
    assert not local, f"links into the build's local server or files: {local[:5]}"


def test_contents_bibliography_and_outline(manifest, book, page_texts):
    contents = _words(" ".join(page_texts[:manifest["pages"][0]["first_page"] - 1]))
    assert "Contents" in contents
    title = re.search(r'^title:\s*"?(.*?)"?\s*$', (ROOT / "_config.yml").read_text(), re.M).group(1)
    assert title in _words(page_texts[0]), f"the title page does not give the book's title {title!r}"
    headless = [k for k, t in enumerate(page_texts, start=1) if title not in _words(t)]
    assert not headless, f"pages without the book's title as their running head: {headless[:10]}"
    for p in manifest["pages"]:
        title = _words(p["title"])
        assert re.search(re.escape(title) + r" \.* ?" + str(p["first_page"]) + r"\b", contents), \
            f"the contents do not give {title!r} at page {p['first_page']}"
    refs = next(p for p in manifest["pages"] if p["page"].endswith("references"))
    bib = _words(" ".join(page_texts[refs["first_page"] - 1:refs["last_page"]]))
    assert "Siciliano" in bib and "Corke" in bib, "the bibliography is not printed"
    assert len(book.outline) >= len(manifest["pages"]), "the PDF's bookmarks do not list the chapters"
