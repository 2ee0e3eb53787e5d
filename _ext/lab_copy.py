"""The chapters as JupyterLab reads them: the take-home copy of each notebook, written from the source notebook and
the numbers the book's build gave every label.

JupyterLab's MyST extension (jupyterlab-myst) renders a notebook's markdown but knows neither myst-nb's glue
(``{glue:text}`` roles, ``{glue:figure}`` directives) nor labels defined in another notebook, nor the book's
bibliography, and it numbers equations and exercises on its own, from 1 in every notebook. The copy says the same
as the built page, in forms it renders:

* a glued number ``{glue:text}`key:.2f``` becomes the inline expression ``{eval}`glued("key", ".2f")``` that the
  extension evaluates in the kernel when its cell runs (:func:`scara.book.glued` formats it as the book does); the
  cell's metadata carries the book's own result, so the number shows before the first run too;
* a figure's caption (``{glue:figure}``) becomes a markdown cell under the figure: its label as a target, "Fig.
  3.2." in bold and the caption (the figure itself is drawn by the cell above, ``scara.plots.publish``);
* every reference (``{numref}``, ``{eq}``, ``{ref}``, ``{doc}``, a markdown link to a label) becomes a link whose text is the one the book
  prints ("Fig. 1.2", "(4.17)", "Exercise 3.4", a section's or page's title), to ``#label`` in the same notebook or
  ``file.ipynb#label`` in another; a citation becomes "[Siciliano et al. 2009]" (where the book prints its key, "[SSVO09]"), linked to the
  references page;
* a labelled display equation carries its book number as ``\\tag{3.6}`` after a ``(label)=`` target, and the first
  cell's front matter turns the extension's own equation numbering off and numbers exercises as the book does
  (``3.1``, ``3.2``, ...);
* a link to a file the build writes for download (``<a ... href="../_downloads/scara.urdf" download>``) becomes
  a markdown link to the file of that name beside the chapter, where the take-home copy puts it
  (``take_home.py``): JupyterLab opens it in a tab, from which the learner can save it;
* a hidden check cell (tag ``remove-cell``) is collapsed and runs under ``%%book_check``
  (:func:`scara.book.book_check`): a check of the book's own numbers that no longer holds after a learner's edit
  prints one line instead of stopping the chapter; cells whose code the book hides are collapsed too.

:func:`lab_notebook` is pure: it takes the source notebook, a :class:`Resolver` (what each label reads as) and the
book's glued values, so a test can run it without Sphinx.
"""
from __future__ import annotations

import copy
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

#: a role with its backtick content: {name}`content`
ROLE = re.compile(r"\{(glue:text|glue:md|glue|numref|eq|ref|doc|cite(?::[a-z]+)?)\}`([^`]*)`")
#: a fenced glue:figure directive (backticks or colons) with its options and caption
FIGURE = re.compile(r"^(?P<fence>`{3,}|:{3,})\{glue:figure\}[ \t]+(?P<key>\S+)[ \t]*\n(?P<body>.*?)^(?P=fence)[ \t]*$",
                    re.M | re.S)
#: a labelled display equation: $$ ... $$ (label)
EQUATION = re.compile(r"^\$\$[ \t]*\n(?P<math>.*?)\n\$\$[ \t]*\((?P<label>[^)\s]+)\)[ \t]*$", re.M | re.S)
#: a markdown link to a label of the book: [text](label) (no scheme, no file, no anchor sign)
LABEL_LINK = re.compile(r"\]\((?P<url>[A-Za-z][\w\-]*)\)")
#: a raw HTML link to a file the build writes for download (``../_downloads/NAME`` from a chapter's page)
DOWNLOAD = re.compile(r'<a class="reference download" href="\.\./_downloads/(?P<name>[^"/]+)" download>(?P<text>[^<]*)</a>')
#: "text <target>" in a role's content
EXPLICIT = re.compile(r"^(?P<text>.*?)\s*<(?P<target>[^<>]+)>$", re.S)

CHECK_MAGIC = "%%book_check"
#: what the first code cell runs first: scara.book's extension (%%book_check, glued), loaded again on a re-run
#: without IPython's "already loaded" message
LOAD_MAGIC = "import scara.book; scara.book.load_ipython_extension(get_ipython())"


def load_line(nb: dict) -> str:
    """:data:`LOAD_MAGIC`, naming the live panels the notebook's code builds (``panels=("control_panel",)``), whose
    programs the kernel then compiles ahead in the background (:func:`scara.book.compile_ahead`)."""
    import scara.widgets  # noqa: F401, PLC0415 - its builders register themselves in AHEAD_BUILDERS
    from scara.book import AHEAD_BUILDERS  # noqa: PLC0415

    code = "\n".join("".join(c["source"]) if isinstance(c["source"], list) else c["source"]
                     for c in nb.get("cells", []) if c["cell_type"] == "code")
    panels = [name for name in AHEAD_BUILDERS if re.search(rf"\b{name}\(", code)]
    return LOAD_MAGIC if not panels else LOAD_MAGIC[:-1] + f", panels={tuple(panels)!r})"


@dataclass
class Resolver:
    """What each reference of one chapter (``docname``) reads as in the book. ``lookup(kind, label)`` gives
    ``(docname, text)`` for a label: ``kind`` is ``"numref"`` (text as the book prints a ``{numref}`` to it: "Fig.
    3.2", "Exercise 3.4"), ``"eq"`` ("(3.6)") or ``"ref"`` (a section's title). ``titles`` maps a docname to its
    page title, ``files`` a docname to its file name in the take-home copy (``01_kinematics.ipynb``,
    ``notation.md``), ``citations`` a bibliography key to its short form ("Siciliano et al. 2009"); ``chapter`` is
    the chapter's prefix for exercises ("3", "A"; None: none given). An unknown name raises ``KeyError`` naming
    it and the chapter."""

    docname: str
    lookup: object = None
    titles: dict = field(default_factory=dict)
    files: dict = field(default_factory=dict)
    citations: dict = field(default_factory=dict)
    chapter: str | None = None
    references_doc: str = "book/references"

    def _href(self, docname: str, anchor: str | None = None) -> str:
        if docname == self.docname:
            return f"#{anchor}" if anchor else "#"
        target = self.files[docname]
        return f"{target}#{anchor}" if anchor else target

    def _known(self, table: dict, key: str, what: str):
        if key not in table:
            raise KeyError(f"{self.docname}: the {what} {key!r} is not known to the book's build")
        return table[key]

    def label(self, kind: str, label: str) -> tuple[str, str]:
        found = self.lookup(kind, label)
        if found is None:
            raise KeyError(f"{self.docname}: the label {label!r} ({kind}) is not known to the book's build")
        docname, text = found
        return text, self._href(docname, label)

    def doc(self, target: str) -> tuple[str, str]:
        base = self.docname.rsplit("/", 1)[0]
        docname = target.lstrip("/") if target.startswith("/") else f"{base}/{target}"
        return self._known(self.titles, docname, "page"), self._href(docname)

    def cite(self, keys: str) -> tuple[str, str]:
        names = [self._known(self.citations, k.strip(), "citation") for k in keys.split(",") if k.strip()]
        return "; ".join(names), self._href(self.references_doc)


def _link(text: str, href: str) -> str:
    text = text.replace("[", "\\[").replace("]", "\\]")
    return f"[{text}]({href})"


def _role(match: re.Match, res: Resolver, glued: dict, found: list) -> str:
    name, content = match.group(1), match.group(2)
    if name.startswith("glue"):
        key, spec = (content.rsplit(":", 1) + [""])[:2] if name == "glue:text" else (content, "")
        if name == "glue:md":
            key, spec = content.split(":", 1)[0], ""
        expr = f'glued("{key}", "{spec}")' if spec else f'glued("{key}")'
        found.append((expr, key, spec, name))
        return f"{{eval}}`{expr}`"
    explicit = EXPLICIT.match(content)
    text, target = (explicit.group("text"), explicit.group("target")) if explicit else (None, content)
    if name in ("numref", "eq", "ref"):
        shown, href = res.label(name, target)
        if text is not None:
            shown = text.replace("%s", shown.split(" ")[-1]) if "%s" in text else text
        return _link(shown, href)
    if name == "doc":
        shown, href = res.doc(target)
        return _link(text if text is not None else shown, href)
    shown, href = res.cite(target)  # cite, cite:p, cite:t: in brackets, where the book prints [SSVO09]
    return _link(f"[{shown}]", href)


def _label_link(match: re.Match, res: Resolver) -> str:
    """``](label)`` as a link the extension follows (``](#label)``, ``](file.ipynb#label)``); anything that is not
    a label of the book is left as it is."""
    if res.lookup("ref", match.group("url")) is None:
        return match.group(0)
    return f"]({res.label('ref', match.group('url'))[1]})"


def _equation(match: re.Match, res: Resolver) -> str:
    label = match.group("label")
    number = res.label("eq", label)[0].strip("()")
    return f"({label})=\n$$\n{match.group('math')}\n\\tag{{{number}}}\n$$"


def _caption(match: re.Match, res: Resolver) -> str:
    key = match.group("key")
    lines = [ln for ln in match.group("body").splitlines() if not re.match(r"^:[a-z\-]+:", ln.strip())]
    caption = "\n".join(lines).strip()
    text, _ = res.label("numref", key)
    return f"({key})=\n**{text}.** {caption}"


def _expression_results(found: list, glued: dict) -> list:
    """The extension's ``user_expressions`` metadata for the expressions ``found`` in a cell, from the book's own
    glued values (``glued[key]`` = the value's mime bundle), so that the numbers show before the first run."""
    from scara.book import format_plain_text  # noqa: PLC0415

    out, seen = [], set()
    for expr, key, spec, role in found:
        if expr in seen:
            continue
        seen.add(expr)
        bundle = glued.get(key)
        if bundle is None:
            continue
        # a Markdown value (a version, a date) shows as its text, as scara.book.glued gives it
        text = bundle["text/markdown"] if role == "glue:md" else format_plain_text(bundle["text/plain"], spec)
        data = {"text/plain": repr(text)}
        out.append({"expression": expr, "result": {"status": "ok", "data": data, "metadata": {}}})
    return out


def _front_matter(res: Resolver) -> str:
    lines = ["---", "numbering:", "  equation: false"]
    if res.chapter is not None:  # what the extension numbers itself (the exercises): 3.1, 3.2, ... as in the book
        lines += [f'  enumerator: "{res.chapter}.%s"']
    return "\n".join(lines + ["---", ""])


def lab_notebook(nb: dict, res: Resolver, glued: dict) -> dict:
    """The take-home copy of the notebook ``nb`` (a dict, not changed), outputs cleared (see the module's
    docstring). ``glued`` maps a glued key to the mime bundle the book's build read for it."""
    nb = copy.deepcopy(nb)
    first_md = True
    loaded = False
    cells = nb.get("cells", [])
    load = load_line(nb)
    first_code = next((c for c in cells if c["cell_type"] == "code"), None)
    if first_code is not None and "remove-cell" in first_code.get("metadata", {}).get("tags", []):
        # a check cell's magic must be its first line: the loading goes in a cell of its own before it
        cells.insert(cells.index(first_code), {"cell_type": "code", "id": "scara-book-load", "execution_count": None, "outputs": [],
                                               "metadata": {"tags": ["hide-input"]}, "source": load})
    for cell in cells:
        meta = cell.setdefault("metadata", {})
        tags = meta.get("tags", [])
        src = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
        if cell["cell_type"] == "markdown":
            src = FIGURE.sub(lambda m: _caption(m, res), src)
            src = EQUATION.sub(lambda m: _equation(m, res), src)
            found: list = []
            src = ROLE.sub(lambda m: _role(m, res, glued, found), src)
            src = LABEL_LINK.sub(lambda m: _label_link(m, res), src)
            src = DOWNLOAD.sub(lambda m: _link(m.group("text"), m.group("name")), src)
            results = _expression_results(found, glued)
            if results:
                meta["user_expressions"] = results
            if first_md:
                src = _front_matter(res) + src
                first_md = False
        elif cell["cell_type"] == "code":
            cell["outputs"], cell["execution_count"] = [], None
            if not loaded:  # the first code cell loads what the text and the checks call
                src = src if src == load else load + "\n" + src
                loaded = True
            if "remove-cell" in tags:
                src = CHECK_MAGIC + "\n" + src
            if {"remove-cell", "hide-input", "remove-input"} & set(tags):
                meta.setdefault("jupyter", {})["source_hidden"] = True
        cell["source"] = src
    return nb


BIBLIOGRAPHY = re.compile(r"^(?P<fence>`{3,}|:{3,})\{bibliography\}[ \t]*\n(?P<body>.*?)^(?P=fence)[ \t]*$", re.M | re.S)


def lab_markdown(text: str, res: Resolver, entries: dict | None = None) -> str:
    """A markdown page of the book (``notation.md``, ``references.md``) as JupyterLab's markdown preview reads
    it: its references as links (see :func:`lab_notebook`) and each ``{bibliography}`` directive as the list of
    its entries (``entries``: key -> (short form, type, the entry in markdown), filtered by ``type == "book"`` or
    ``type != "book"`` as the directive says)."""
    def bibliography(m):
        rule = re.search(r':filter:\s*type\s*(==|!=)\s*"([^"]+)"', m.group("body"))
        keep = [(short, md) for short, kind, md in (entries or {}).values()
                if rule is None or ((kind == rule.group(2)) == (rule.group(1) == "=="))]
        return "\n".join(f"- **[{short}]** {md}" for short, md in sorted(keep))

    text = BIBLIOGRAPHY.sub(bibliography, text)
    text = EQUATION.sub(lambda m: _equation(m, res), text)
    text = ROLE.sub(lambda m: _role(m, res, {}, []), text)
    return LABEL_LINK.sub(lambda m: _label_link(m, res), text)


def bibliography_entries(path) -> dict:
    """key -> (short form, entry type, the entry in markdown) for every entry of the BibTeX file ``path``."""
    from pybtex.database import parse_file  # noqa: PLC0415
    from pybtex.plugin import find_plugin  # noqa: PLC0415

    bib = parse_file(str(path))
    style, markdown = find_plugin("pybtex.style.formatting", "plain")(), find_plugin("pybtex.backends", "markdown")()
    return {e.key: (short_citation(bib.entries[e.key]), bib.entries[e.key].type,
                    " ".join(e.text.render(markdown).split()))
            for e in style.format_entries(bib.entries.values())}


def glued_bundles(store: dict) -> dict:
    """Every value a chapter glued, as the book's build stored them (myst-nb's ``NAME.glue.json`` beside the
    executed notebook: key -> its display output): key -> the value's mime bundle."""
    return {key: {k: ("".join(v) if isinstance(v, list) else v) for k, v in out.get("data", {}).items()}
            for key, out in store.items()}


def short_citation(entry) -> str:
    """"Siciliano et al. 2009" from a pybtex entry: one author's last name, two joined by "and", more "et al."."""
    people = entry.persons.get("author") or entry.persons.get("editor") or []
    last = [" ".join(p.last_names) for p in people]
    year = entry.fields.get("year", "n.d.")
    if not last:
        who = entry.fields.get("title", "?")
    elif len(last) == 1:
        who = last[0]
    elif len(last) == 2:
        who = f"{last[0]} and {last[1]}"
    else:
        who = f"{last[0]} et al."
    return f"{who} {year}".replace("{", "").replace("}", "")


def resolvers(app) -> dict:
    """One :class:`Resolver` per notebook of the book, from the finished build's environment: a label reads as
    Sphinx's own resolution of a ``numref``, ``eq`` or ``ref`` to it prints it (asked only for the labels the
    chapters refer to, so that no label without a number is asked for one)."""
    from docutils import nodes  # noqa: PLC0415
    from pybtex.database import parse_file  # noqa: PLC0415
    from sphinx.addnodes import pending_xref  # noqa: PLC0415

    env, builder = app.env, app.builder
    std, math = env.get_domain("std"), env.get_domain("math")
    src = Path(app.srcdir)
    def copy_name(d):  # a MyST notebook (a .md page with a kernel) is a notebook in the copy
        path = Path(env.doc2path(d))
        is_notebook = path.suffix == ".md" and "kernelspec:" in path.read_text(encoding="utf-8").split("\n---", 1)[0]
        return path.with_suffix(".ipynb").name if is_notebook else path.name

    files = {d: copy_name(d) for d in env.found_docs}
    titles = {d: env.titles[d].astext() for d in env.found_docs if d in env.titles}
    citations = {}
    for bib in app.config.bibtex_bibfiles:
        for key, entry in parse_file(str(src / bib)).entries.items():
            citations[key] = short_citation(entry)

    def lookup_for(docname):
        def lookup(kind, label):
            if kind == "eq":
                if label not in math.equations:
                    return None
                domain, target_doc = math, math.equations[label][0]
            else:
                if label not in std.labels and label not in std.anonlabels:
                    return None
                domain = std
                target_doc = (std.labels.get(label) or std.anonlabels[label])[0]
                if kind == "ref":  # a section's title (a label of something else: the label itself)
                    return target_doc, (std.labels.get(label) or (None, None, ""))[2] or label
            node = pending_xref("", refdomain=domain.name, reftype=kind, reftarget=label, refexplicit=False,
                                refdoc=docname, refwarn=True)
            ref = domain.resolve_xref(env, docname, builder, kind, label, node, nodes.inline(label, label))
            return None if ref is None else (target_doc, ref.astext())
        return lookup

    out = {}
    for docname in sorted(env.found_docs):
        if not env.doc2path(docname).endswith((".ipynb", ".md")):
            continue
        nums = env.toc_fignumbers.get(docname, {})
        first = next((n for kind in nums.values() for n in kind.values() if n), None)
        out[docname] = Resolver(docname, lookup=lookup_for(docname), titles=titles, files=files,
                                citations=citations, chapter=str(first[0]) if first and len(first) > 1 else None)
    return out


def lab_copies(app) -> dict[str, bytes | None]:
    """The take-home copy of the book's folder: ``book/NAME.ipynb`` -> the bytes of its JupyterLab copy, for every
    notebook of the finished build and every MyST notebook (a ``.md`` page with a kernel, as the introduction:
    ``book/intro.md`` -> None, dropped, and ``book/intro.ipynb`` written); a plain markdown page -> its text as
    the markdown preview reads it (:func:`lab_markdown`)."""
    from myst_nb.core.read import read_myst_markdown_notebook  # noqa: PLC0415

    src = Path(app.srcdir)
    executed_dir = Path(app.outdir).parent / "jupyter_execute"
    entries = {}
    for bib in app.config.bibtex_bibfiles:
        entries.update(bibliography_entries(src / bib))
    out = {}
    for docname, res in resolvers(app).items():
        rel = Path(app.env.doc2path(docname, base=False))
        text = (src / rel).read_text(encoding="utf-8")
        if rel.suffix == ".md":
            if "kernelspec:" not in text.split("\n---", 1)[0]:
                out[rel.as_posix()] = (lab_markdown(text, res, entries)).encode()
                continue
            nb = read_myst_markdown_notebook(text)
            nb = json.loads(json.dumps(nb))
            out[rel.as_posix()] = None
            rel = rel.with_suffix(".ipynb")
        else:
            nb = json.loads(text)
        store = executed_dir / rel.with_suffix(".glue.json")
        glued = glued_bundles(json.loads(store.read_text(encoding="utf-8"))) if store.is_file() else {}
        out[rel.as_posix()] = (json.dumps(lab_notebook(nb, res, glued), indent=1, ensure_ascii=False) + "\n").encode()
    return out
