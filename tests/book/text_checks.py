"""What a reader reads on a built page, checked in the browser: the text's own defects, in the style of
``page_checks.py`` (each check is a JavaScript function evaluated in the settled page and returns a list of
human-readable problems, empty when the page is clean). :func:`text_problems` runs them all:

- ``EXERCISE_ANSWERS``: an exercise never shows its answer before its solution. Between an exercise's box and
  its solution's box nothing computed may be shown (a cell's output, a table, a figure), unless it is data the
  question needs: a figure or table whose own caption names the exercise, or which the exercise's statement
  refers to (a link to its number). A figure or table inside the exercise's box is part of the question.
- ``RAW_LABELS``: no label or role is left raw anywhere in the article, folded solutions and computed tables
  included: "(eq-...)", "fig-...", "{eq}", "{numref}", "??" (an unresolved reference). Code is not text.
- ``ONE_MEANING``: one meaning per symbol in a chapter, as the notation page declares the symbols (read from
  ``notation.html`` beside the page). A chapter may not be given a second meaning of a symbol: a row or an item
  that says a symbol "is also", "are also", "also the" something, or "alone is" something in a chapter; an
  item of *Symbols used twice* whose clauses (separated by ";") give one symbol (subscripts that are indices,
  ``a_1``, ``q_i``, count as one symbol ``a_•``; a clause without the symbol speaks of the item's) a meaning in
  one chapter twice; and a symbol declared "in one solution" or "in one exercise" of a chapter that the chapter
  uses in more than one exercise or solution. On a chapter's page the
  problems of that chapter are reported, on the notation page all of them.
- ``NUMBERING``: the figures, tables, exercises and equations of a page are numbered from 1 without a gap, each
  kind on its own, with the chapter's number or the appendix's letter in front (Fig. A.1, (A.1)).

Two checks run on the sources and on the build without a browser, in ``test_text.py``:
``test_no_output_between_an_exercise_and_its_solution`` (the notebooks' form of ``EXERCISE_ANSWERS``, with
:func:`exercise_output_problems`) and ``test_equal_quantities_print_equal`` (chapter 3's comparison of the three motions prints equal values
equal: the quill's peak speed of 0.05625 m/s is one number in two motions).

``page_checks.py`` runs them with the other checks, in the browser test or alone on a build.
"""
from __future__ import annotations

import json
import os
import re
from pathlib import Path


ROOT = Path(__file__).resolve().parents[2]
HTML = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html"))

EXERCISE_ANSWERS = r"""() => {
  const out = [];
  const article = document.querySelector('article') || document.body;
  const all = Array.from(article.querySelectorAll('*'));
  const pos = new Map(all.map((el, i) => [el, i]));
  const after = (el) => { let n = el; while (n.lastElementChild) n = n.lastElementChild; return pos.get(n); };
  const text = (el) => el.textContent.replace(/\s+/g, ' ').trim().slice(0, 60);
  article.querySelectorAll('div.exercise').forEach(ex => {
    const id = ex.id;
    const title = (ex.querySelector('.caption-number') || ex).textContent.trim();
    const sol = Array.from(article.querySelectorAll('div.solution')).find(
      s => s.querySelector(`.admonition-title a[href$="#${id}"]`));
    if (!sol) return;
    const from = after(ex), to = pos.get(sol);
    const cited = new Set(Array.from(ex.querySelectorAll('a[href*="#"]')).map(a => a.getAttribute('href').split('#')[1]));
    const shown = [];
    for (let i = from + 1; i < to; i++) {
      const el = all[i];
      if (!el.matches('div.cell_output, figure, div.figure, table')) continue;
      if (shown.some(s => s.contains(el))) continue;   // inside one met already
      if (el.matches('div.cell_output') && !el.textContent.trim() && !el.querySelector('img, svg, canvas, iframe, .plotly-graph-div')) continue;
      shown.push(el);
    }
    shown.forEach(el => {
      // data the question needs: the exercise refers to it, or its own caption names the exercise
      const holder = el.closest('figure, div.figure, table[id], div.pst-scrollable-table-container') || el;
      const ids = [holder.id, el.id, ...Array.from(el.querySelectorAll('[id]')).map(e => e.id)].filter(Boolean);
      if (ids.some(x => cited.has(x))) return;
      const caption = holder.querySelector('figcaption, caption, .caption');
      if (caption && caption.querySelector(`a[href$="#${id}"]`)) return;
      const kind = el.querySelector('table') || el.matches('table') ? 'a table'
                 : el.querySelector('.plotly-graph-div, img, svg') ? 'a figure' : 'an output';
      out.push(`${title} (${id}): ${kind} is shown between the question and its solution: ${text(el)}`);
    });
  });
  return out;
}"""

RAW_LABELS = r"""() => {
  const out = [];
  const article = document.querySelector('article') || document.body;
  const skip = 'pre, code, script, style, mjx-container, .MathJax, .math, .cell_input, .highlight, textarea';
  const walker = document.createTreeWalker(article, NodeFilter.SHOW_TEXT);
  const patterns = [/\((?:eq|fig|tab|ex|sec)-[\w-]+\)/, /\b(?:eq|fig|tab|ex)-[a-z0-9]+(?:-[a-z0-9]+)+\b/,
                    /\{(?:eq|numref|ref|doc|glue(?::\w+)?|cite(?::\w+)?|exercise|solution)\}/, /\?\?/];
  const seen = new Set();
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    const p = n.parentElement;
    if (!p || p.closest(skip)) continue;
    const t = n.textContent;
    for (const re of patterns) {
      const m = t.match(re);
      if (m && !seen.has(m[0])) {
        seen.add(m[0]);
        out.push(`raw label "${m[0]}" in the text: ...${t.slice(Math.max(0, m.index - 40), m.index + m[0].length + 20).replace(/\s+/g, ' ')}...`);
      }
    }
  }
  return out;
}"""

ONE_MEANING = r"""async () => {
  const out = [];
  const here = location.pathname.split('/').pop();
  const res = await fetch('notation.html');
  if (!res.ok) return [`the notation page cannot be read beside ${here}`];
  const doc = new DOMParser().parseFromString(await res.text(), 'text/html');
  // this page's chapter (its title's number), or every chapter on the notation page itself
  const h1 = document.querySelector('article h1');
  const num = h1 && (h1.querySelector('.section-number') || {}).textContent;
  const chapter = num ? parseInt(num) : null;
  const isNotation = here === 'notation.html';
  if (!isNotation && chapter === null) return out;
  const ALL = [1, 2, 3, 4, 5, 6, 7];
  const chaptersIn = (s) => {
    const found = new Set();
    const re = /chapters?\s+((?:\d+(?:\s*(?:,|and|to)\s*)?)+)/g;
    let m;
    while ((m = re.exec(s))) {
      const nums = m[1].match(/\d+/g).map(Number);
      if (/\bto\b/.test(m[1]) && nums.length === 2) for (let c = nums[0]; c <= nums[1]; c++) found.add(c);
      else nums.forEach(c => found.add(c));
    }
    return found;
  };
  // the TeX of an element's math (the raw page keeps it as \( ... \)) and its plain text
  const texOf = (el) => Array.from(el.querySelectorAll('.math')).map(m => m.textContent.replace(/^\\\(|\\\)$/g, '').trim());
  const token = (tex) => {
    // a symbol: an accent, a letter or a command, and a subscript that is not an index
    const m = tex.trim().match(/^((?:\\(?:hat|dot|ddot|bar|tilde|vec)\s*)?(?:\\[a-zA-Z]+|[A-Za-z]))(\s*_\s*(\{[^}]*\}|\\?[A-Za-z0-9]+))?/);
    if (!m) return null;
    let sub = m[3] ? m[3].replace(/[{}\s]/g, '') : '';
    if (/^(?:[0-9]+|[ijkn]|\d+[ijk]?|i,\d|i[+-]1)$/.test(sub)) sub = '•';
    return m[1].replace(/\s+/g, ' ') + (sub ? '_' + sub : '');
  };
  const tokensOf = (el) => {
    const t = new Set();
    texOf(el).forEach(tex => tex.split(/[,;]|=|\\dots|\\ldots|<|\\le/).forEach(part => {
      const k = token(part); if (k) t.add(k); }));
    return t;
  };
  const problems = [];   // [chapter, message]
  const second = /\b(?:is|are) also\b|\balso (?:the|a|an)\b|\balone is\b/;
  // the tables: each section's heading says which chapters it covers; the robot's covers all of them
  doc.querySelectorAll('section').forEach(sec => {
    const h = sec.querySelector(':scope > h2');
    if (!h) return;
    const head = h.textContent;
    const covers = /robot/i.test(head) ? new Set(ALL) : chaptersIn(head);
    if (/appendix|twice/i.test(head) || !covers.size) return;
    sec.querySelectorAll('table tbody tr').forEach(tr => {
      const cells = tr.querySelectorAll('td');
      if (!cells.length) return;
      const rowText = tr.textContent.replace(/\s+/g, ' ');
      const m = rowText.match(second);
      if (m) {
        const named = chaptersIn(rowText);
        (named.size ? named : covers).forEach(c => problems.push([c,
          `notation: in chapter ${c} a symbol of the row "${cells[0].textContent.trim().slice(0, 40)}" has a second meaning ("${m[0]}"): ${rowText.trim().slice(0, 120)}`]));
      }
    });
  });
  // the list of symbols used twice: one chapter in two clauses of an item, a second meaning, a scoped claim
  const twice = Array.from(doc.querySelectorAll('section')).find(s => /twice/i.test((s.querySelector(':scope > h2') || {}).textContent || ''));
  const pageTex = () => {
    // the TeX of this page's math, by the exercise or solution box that holds it
    const items = (window.MathJax && MathJax.startup && MathJax.startup.document) ? Array.from(MathJax.startup.document.math) : [];
    return items.map(it => ({tex: it.math, box: it.typesetRoot && it.typesetRoot.closest ? it.typesetRoot.closest('div.exercise, div.solution') : null}));
  };
  if (twice) twice.querySelectorAll(':scope li').forEach(li => {
    const texs = texOf(li);
    const head = texs.length ? token(texs[0]) : null;
    const plain = li.textContent.replace(/\s+/g, ' ').trim();
    // each clause (between ";") gives its symbols a meaning in the chapters it names; a clause without math
    // speaks of the item's symbol, and so does one whose math has no symbol of that letter
    const clauses = li.innerHTML.split(';').map(h => { const d = document.createElement('div'); d.innerHTML = h; return d; });
    const base = (k) => k.replace(/_.*$/, '');
    const byToken = new Map();   // token -> chapter -> number of clauses
    clauses.forEach(d => {
      const toks = new Set(texOf(d).map(token).filter(Boolean));
      if (head && !Array.from(toks).some(k => base(k) === base(head))) toks.add(head);
      chaptersIn(d.textContent).forEach(c => toks.forEach(k => {
        if (!byToken.has(k)) byToken.set(k, new Map());
        byToken.get(k).set(c, (byToken.get(k).get(c) || 0) + 1);
      }));
    });
    byToken.forEach((count, k) => count.forEach((n, c) => { if (n > 1) problems.push([c,
      `notation: ${k} has ${n} meanings in chapter ${c}: ${plain.slice(0, 140)}`]); }));
    clauses.forEach(d => { const cl = d.textContent, m = cl.match(second); if (m) chaptersIn(cl).forEach(c => problems.push([c,
      `notation: ${head} has a second meaning in chapter ${c} ("${m[0]}"): ${cl.trim().slice(0, 120)}`])); });
    const scoped = plain.match(/in one (?:solution|exercise) of chapter (\d+)/);
    if (scoped && head && Number(scoped[1]) === chapter && !isNotation) {
      const bare = head.replace(/_•$/, '');
      const re = new RegExp(bare.replace(/\\/g, '\\\\') + '(?![a-zA-Z])');
      const boxes = new Set(pageTex().filter(x => re.test(x.tex)).map(x => x.box ? x.box.id : 'the text'));
      if (boxes.size > 1) problems.push([chapter, `chapter ${chapter} uses ${bare} in ${boxes.size} places (${Array.from(boxes).join(', ')}), which the notation page declares for one solution only`]);
    }
  });
  const seen = new Set();
  problems.forEach(([c, msg]) => {
    if ((isNotation || c === chapter) && !seen.has(msg)) { seen.add(msg); out.push(msg); }
  });
  return out;
}"""

NUMBERING = r"""() => {
  const out = [];
  const article = document.querySelector('article') || document.body;
  const kinds = new Map();   // kind -> [[prefix, n, text]]
  const add = (kind, label) => {
    const m = label.match(/^(?:([A-Z0-9]+)\.)?(\d+)$/);
    if (!m) { out.push(`${kind} numbered "${label}"`); return; }
    if (!kinds.has(kind)) kinds.set(kind, []);
    kinds.get(kind).push([m[1] || '', Number(m[2]), label]);
  };
  article.querySelectorAll('.caption-number').forEach(el => {
    const m = el.textContent.trim().match(/^(\S+)\s+(\S+?)\.?$/);
    if (m) add(m[1], m[2]);
  });
  article.querySelectorAll('.eqno').forEach(el => {
    const m = el.textContent.trim().match(/^\(([^)]*)\)/);
    if (m) add('Equation', m[1]);
  });
  const h1 = article.querySelector('h1');
  const chapter = h1 && h1.querySelector('.section-number') ? h1.querySelector('.section-number').textContent.trim().replace(/\.$/, '') : null;
  kinds.forEach((list, kind) => {
    const prefixes = new Set(list.map(x => x[0]));
    if (prefixes.size > 1) out.push(`${kind}: numbers with different prefixes on one page: ${list.map(x => x[2]).join(', ')}`);
    if (chapter && list.some(x => x[0] !== chapter)) out.push(`${kind}: numbers without the chapter's ${chapter}: ${list.map(x => x[2]).join(', ')}`);
    const numbers = list.map(x => x[1]);
    const expected = numbers.map((_, i) => i + 1);
    if (numbers.join() !== expected.join())
      out.push(`${kind}: numbered ${list.map(x => x[2]).join(', ')} instead of from 1 without a gap`);
  });
  return out;
}"""

CHECKS = {"exercise answers": EXERCISE_ANSWERS, "raw labels": RAW_LABELS, "one meaning": ONE_MEANING,
          "numbering": NUMBERING}


def text_problems(pg) -> list[str]:
    """Every text problem of the page ``pg`` (loaded and settled, see ``page_checks.settle``), each prefixed with
    the check that found it."""
    problems = []
    for name, js in CHECKS.items():
        problems += [f"{name}: {p}" for p in pg.evaluate(js)]
    return problems


# --------------------------------------------------------------------------------------------------
# the same rules on the sources and the build, without a browser
# --------------------------------------------------------------------------------------------------
_EXERCISE = re.compile(r"```+\{exercise\}[^\n]*\n:label:\s*(\S+)")
_SOLUTION = re.compile(r"```+\{solution\}\s*(\S+)")


def _src(cell) -> str:
    return "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]


def exercise_output_problems(nb_path: Path) -> list[str]:
    """The cells of a notebook that would show an output between an exercise and its solution: a code cell there
    must hide its output (tag ``remove-cell`` or ``remove-output``), unless it publishes a figure the exercise
    refers to (the figure is then the question's data, shown by its caption's directive)."""
    cells = json.loads(nb_path.read_text())["cells"]
    out, open_ex, statement = [], None, ""
    for i, c in enumerate(cells):
        src = _src(c)
        if c["cell_type"] == "markdown":
            for m in re.finditer(r"```+\{(exercise|solution)\}[^\n]*\n(?::[\w-]+:[^\n]*\n)*(.*?)```", src, re.S):
                if m.group(1) == "exercise":
                    label = re.search(r":label:\s*(\S+)", m.group(0))
                    open_ex, statement = (label.group(1) if label else None), m.group(0)
                elif open_ex and re.search(rf"\{{solution\}}\s*{re.escape(open_ex)}\b", m.group(0)):
                    open_ex = None
            continue
        if open_ex is None:
            continue
        tags = set(c.get("metadata", {}).get("tags", []))
        if tags & {"remove-cell", "remove-output"}:
            continue
        published = re.findall(r"publish\([^\n]*?[\"'](fig-[\w-]+)[\"']", src)
        if published and all(name in statement for name in published):
            continue
        out.append(f"{nb_path.name}: cell {i} shows its output between the exercise {open_ex} and its solution")
    return out


NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))


def _table_rows(html: str, caption_words: str) -> dict:
    """The rows (header -> cell texts) of the first pandas table of ``html`` whose row headers include
    ``caption_words``."""
    from html.parser import HTMLParser  # noqa: PLC0415

    class Rows(HTMLParser):
        def __init__(self):
            super().__init__()
            self.tables, self.row, self.cell, self.in_cell = [], None, None, False

        def handle_starttag(self, tag, attrs):
            if tag == "table":
                self.tables.append({})
            elif tag == "tr":
                self.row = []
            elif tag in ("td", "th"):
                self.in_cell, self.cell = True, ""

        def handle_endtag(self, tag):
            if tag in ("td", "th") and self.row is not None:
                self.row.append(self.cell.strip())
                self.in_cell = False
            elif tag == "tr" and self.row and self.tables:
                self.tables[-1][self.row[0]] = self.row[1:]
                self.row = None

        def handle_data(self, data):
            if self.in_cell:
                self.cell += data

    p = Rows()
    p.feed(html)
    return next((t for t in p.tables if caption_words in t), {})


# --------------------------------------------------------------------------------------------------
# alone, on a build
# --------------------------------------------------------------------------------------------------
