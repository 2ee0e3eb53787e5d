"""The bibliography: every entry of ``references.bib`` can be opened (a DOI or a stable link), every key the book
cites exists, and the references page lists the textbooks, the original papers and a reading per chapter."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from pybtex.database import parse_file

ROOT = Path(__file__).resolve().parents[2]
BIB = parse_file(str(ROOT / "references.bib"))
PAGE = (ROOT / "book" / "references.md").read_text()
CITE = re.compile(r"\{cite(?::[a-z]+)?\}`([^`]+)`")


def _book_texts():
    for path in sorted((ROOT / "book").iterdir()):
        if path.suffix == ".ipynb":
            cells = json.loads(path.read_text())["cells"]
            yield path.name, "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
        elif path.suffix == ".md":
            yield path.name, path.read_text()


@pytest.mark.parametrize("key", sorted(BIB.entries))
def test_every_entry_can_be_opened(key):
    fields = BIB.entries[key].fields
    doi, url = fields.get("doi"), fields.get("url")
    assert doi or url, f"{key}: neither a doi nor a url"
    if doi:
        assert re.fullmatch(r"10\.\d{4,9}/\S+", doi), (key, doi)
        assert not doi.lower().startswith("http"), (key, doi)  # the bare DOI: the bibliography makes the link
    if url:
        assert re.fullmatch(r"https?://[^\s{}]+", url), (key, url)


def test_the_books_cited_across_the_course_are_there():
    assert {"siciliano2009", "corke2023", "lynch2017", "spong2020", "slotine1991", "slotine1987", "khatib1987",
            "yoshikawa1985", "carpentier2019", "sciavicco1988", "siciliano1990"} <= set(BIB.entries)
    for key in ("siciliano2009", "corke2023", "lynch2017", "spong2020", "slotine1991"):
        assert BIB.entries[key].type == "book", key
    for key in ("slotine1987", "khatib1987", "yoshikawa1985", "sciavicco1988", "siciliano1990"):
        assert BIB.entries[key].type == "article", key


def test_every_citation_of_the_book_has_an_entry():
    cited = set()
    for name, text in _book_texts():
        for group in CITE.findall(text):
            for key in group.split(","):
                assert key.strip() in BIB.entries, (name, key)
                cited.add(key.strip())
    assert {"siciliano2009", "lynch2017", "spong2020", "corke2023"} <= cited


def test_references_page_sections():
    heads = re.findall(r"^## (.+)$", PAGE, flags=re.M)
    assert heads == ["Textbooks", "Original papers", "Further reading"]
    # the two bibliographies split the entries between them, each entry once
    filters = re.findall(r":filter: (.+)", PAGE)
    assert filters == ['type == "book"', 'type != "book"']
    # the further reading names a reading for every chapter and for the appendix
    reading = PAGE.split("## Further reading", 1)[1]
    for chapter in range(1, 7):
        assert f"**Chapter {chapter}," in reading, chapter
    assert "**Appendix," in reading
