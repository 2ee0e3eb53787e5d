"""What the chapters' notebooks use to put computed numbers and figures into their prose, in the built book and
in JupyterLab alike.

* :func:`glue` records a value under a name. In the book's build (where ``myst_nb`` is installed) it also hands
  the value to myst-nb's ``glue``, whose ``{glue:text}`` roles and ``{glue:figure}`` directives place it in the
  page. Without myst-nb (the course's own install) it only records it.
* The take-home copy of a chapter (written by the book's build for JupyterLab) shows each such number through
  an inline expression ``{eval}`glued("name", ".2f")``` that JupyterLab's MyST extension evaluates in the kernel
  when the text's cell runs: :func:`glued` formats the value as the book's ``{glue:text}`name:.2f``` does
  (:func:`format_plain_text`), so that both show the same characters, and a learner who edits an input and runs
  the chapter again reads the new numbers. Each captioned figure is shown by :func:`show` in a cell of its own
  above its caption.
* The checks the book runs on its own numbers (hidden cells) carry the cell magic ``%%book_check`` in the
  take-home copy (:func:`book_check`): a check that fails, as a check of the book's values does once the learner
  changed an input, prints one line that says so and the chapter goes on; every other statement of the cell runs.
* The take-home chapter's first cell also names the live panels the chapter builds: :func:`compile_ahead` compiles
  their page programs in a background process (on a second core, at low priority) while the chapter's first cells
  run, into numba's on-disk cache, and a panel's first move waits for that work (:func:`wait_compiled`) instead
  of compiling the same program again. On an empty compile cache a panel's program takes up to 13 s to compile
  (chapter 6's controllers); the chapter no longer waits for most of it.
"""
from __future__ import annotations

import ast
import atexit
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["GLUED", "UNDEFINED", "UNDEFINED_TEXT", "glue", "glued", "show", "format_plain_text", "plain_text", "fixed",
           "equation_numbers", "equation_links", "book_check", "load_ipython_extension",
           "compile_ahead", "ahead", "wait_compiled", "kernel_name", "AHEAD_BUILDERS"]

#: every value glued in this kernel, by name (the latest one of a name)
GLUED: dict = {}
#: the names a hidden check could not glue for the inputs of this run (its statement failed), as regular
#: expressions, with the note
UNDEFINED: dict = {}
#: what the text shows for such a number
UNDEFINED_TEXT = "n/a (not defined for your inputs: see the note of the hidden check above)"


def glue(name: str, value, display: bool = True):
    """Record ``value`` under ``name`` (:data:`GLUED`) and, where myst-nb is installed (the book's build), glue it
    for the page (``myst_nb.glue(name, value, display)``); without myst-nb, ``display=True`` shows the value. A
    numpy scalar is glued as the Python number it holds, so the page reads its text as a number."""
    if not isinstance(name, str) or not name:
        raise ValueError(f"a glued value needs a name (a non-empty string), got {name!r}")
    if type(value).__module__ == "numpy" and hasattr(value, "item") and getattr(value, "ndim", None) == 0:
        value = value.item()  # a numpy scalar as a plain number: its text is '2.87', never 'np.float64(2.87)'
    GLUED[name] = value
    try:
        from myst_nb import glue as myst_glue  # noqa: PLC0415 - the book's toolchain, absent from the course's install
    except ImportError:
        myst_glue = None
    if myst_glue is not None:
        return myst_glue(name, value, display)
    if display:
        from IPython.display import display as show_value  # noqa: PLC0415

        show_value(value)
    return None


def plain_text(value) -> str:
    """The ``text/plain`` form of ``value`` a Jupyter kernel sends (IPython's plain-text formatter): what the
    book's build reads a glued value from."""
    from IPython import get_ipython  # noqa: PLC0415
    from IPython.core.formatters import PlainTextFormatter  # noqa: PLC0415

    ip = get_ipython()
    # the kernel's own formatter: the book's figures module teaches it to print numpy scalars as plain numbers
    formatter = ip.display_formatter.formatters["text/plain"] if ip is not None else PlainTextFormatter()
    return formatter(value)


def format_plain_text(text: str, spec: str) -> str:
    """A glued value's ``text/plain`` as the book prints it with the format spec ``spec`` (``{glue:text}`name:spec```):
    the text read as a Python literal where it is one (a string loses its quotes), then converted by the spec's
    type letter (``s`` to a string; ``b c d o x X`` to an integer; ``e E f F g G n %`` to a float) and formatted.

    >>> format_plain_text("0.05625", ".4f")
    '0.0563'
    >>> format_plain_text("'p1'", "")
    'p1'
    """
    try:
        value = ast.literal_eval(text)
    except (SyntaxError, ValueError):
        value = text
    if spec == "":
        return str(value)
    kind = spec[-1]
    if kind == "s":
        value = str(value)
    elif kind in "bcdoxX":
        value = int(value)
    elif kind in "eEfFgGn%":
        value = float(value)
    return format(value, spec)


def fixed(value, digits: int = 2) -> str:
    """``value`` with ``digits`` decimals, rounded half up after it is read to 9 significant digits: two results
    that are equal in exact arithmetic but differ in their last bits (5.624999999999999 and 5.625000000000001,
    one speed computed two ways) print the same, where ``format(v, ".2f")`` gives 5.62 and 5.63. A value that
    rounds to zero prints without a sign.

    >>> fixed(5.624999999999999), fixed(5.625000000000001), fixed(-0.0001), fixed(7.03125, 3)
    ('5.63', '5.63', '0.00', '7.031')
    """
    from decimal import ROUND_HALF_UP, Decimal  # noqa: PLC0415

    out = Decimal(f"{float(value):.9g}").quantize(Decimal(1).scaleb(-digits), rounding=ROUND_HALF_UP)
    return str(abs(out) if out == 0 else out)


#: a labelled display equation of a chapter as the book writes it (``$$ ... $$ (label)``) and as its take-home copy
#: does (``(label)=`` then ``$$ ... \tag{3.6} $$``)
_BOOK_EQUATION = re.compile(r"^\$\$[ \t]*\n.*?\n\$\$[ \t]*\((?P<label>[^)\s]+)\)[ \t]*$", re.M | re.S)
_COPY_EQUATION = re.compile(r"^\((?P<label>[^)\s]+)\)=[ \t]*\n\$\$.*?\\tag\{(?P<number>[^}]+)\}\s*\n\$\$", re.M | re.S)


def equation_numbers(folder=None) -> dict:
    """label -> (notebook file, number, anchor) for every labelled equation of the chapters ``NN_*.ipynb`` in
    ``folder`` (default: the working directory, the chapters' own folder when a notebook runs), as the book numbers
    them: chapter ``NN``, then the equation's rank in its chapter ("3.6"). In the book's sources the anchor is the
    built page's (``03_trajectory.html``, ``equation-LABEL``); in the take-home copy, whose equations carry their
    number as ``\tag{3.6}``, it is the notebook's (``03_trajectory.ipynb``, ``LABEL``)."""
    import json  # noqa: PLC0415

    out = {}
    for path in sorted(Path(folder or Path.cwd()).glob("[0-9][0-9]_*.ipynb")):
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        text = "\n".join("".join(c["source"]) if isinstance(c["source"], list) else c["source"]
                         for c in cells if c["cell_type"] == "markdown")
        copied = list(_COPY_EQUATION.finditer(text))
        if copied:
            out.update({m.group("label"): (path.name, m.group("number"), m.group("label")) for m in copied})
            continue
        chapter = int(path.name[:2])
        for k, m in enumerate(_BOOK_EQUATION.finditer(text), 1):
            out[m.group("label")] = (path.with_suffix(".html").name, f"{chapter}.{k}", f"equation-{m.group('label')}")
    return out


def equation_links(html_text: str, numbers: dict) -> str:
    """``html_text`` with every "(eq-label)" of a known label as a link that reads as the book's number, "(3.6)"
    (``numbers`` from :func:`equation_numbers`); an unknown label raises ``KeyError`` naming it.

    >>> equation_links("cubic (eq-a)", {"eq-a": ("03_trajectory.html", "3.6", "equation-eq-a")})
    'cubic <a href="03_trajectory.html#equation-eq-a">(3.6)</a>'
    """
    def link(m):
        if m.group(1) not in numbers:
            raise KeyError(f"the equation label {m.group(1)!r} is not in the book's chapters")
        page, number, anchor = numbers[m.group(1)]
        return f'<a href="{page}#{anchor}">({number})</a>'

    return re.sub(r"\((eq-[\w-]+)\)", link, html_text)


def glued(name: str, spec: str = ""):
    """The value glued as ``name`` in this kernel, as the book shows it: formatted with ``spec`` (see
    :func:`format_plain_text`); a value with a Markdown form (``IPython.display.Markdown``: a version, a date) as
    its text;
    :data:`UNDEFINED_TEXT` when a hidden check could not compute it for this run's inputs (:func:`book_check`
    printed why). Raises ``KeyError`` naming the value when nothing was glued under ``name`` yet (run the cells
    above first)."""
    if name not in GLUED and any(re.fullmatch(pattern, name) for pattern in UNDEFINED):
        return UNDEFINED_TEXT
    if name not in GLUED:
        raise KeyError(f"no value is glued as {name!r} yet: run the chapter's cells above this text first")
    value = GLUED[name]
    if hasattr(value, "_repr_markdown_"):  # a Markdown object (a version, a date): its text, shown as text
        return str(value._repr_markdown_())
    return format_plain_text(plain_text(value), spec)


def show(name: str):
    """The figure (or any value) glued as ``name``, returned so that a cell ending with ``show(name)`` displays it."""
    if name not in GLUED:
        raise KeyError(f"no figure is glued as {name!r} yet: run the chapter's cells above this one first")
    return GLUED[name]


def _glued_names(stmt) -> list[str]:
    """The names a statement glues (``glue("name", ...)``), as regular expressions: a literal name exactly, an
    f-string name (``glue(f"w_{k}", ...)``) with any text where its fields go."""
    names = []
    for n in ast.walk(stmt):
        if not (isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "glue" and n.args):
            continue
        first = n.args[0]
        if isinstance(first, ast.Constant) and isinstance(first.value, str):
            names.append(re.escape(first.value))
        elif isinstance(first, ast.JoinedStr):
            names.append("".join(re.escape(v.value) if isinstance(v, ast.Constant) else ".+" for v in first.values))
    return names


def book_check(line: str, cell: str, namespace: dict | None = None) -> list[str]:
    """Run ``cell``, one of the chapter's hidden checks of its own numbers, statement by statement in
    ``namespace`` (the kernel's own, for the cell magic ``%%book_check``). A statement that fails (a check that
    does not hold, or a step of one that no longer applies) is noted and the next statement runs, so that the
    numbers the cell also computes for the text are computed where they can be. Prints one line for the cell when
    anything failed, and returns the notes (one per failed statement). The checks hold for the book's own inputs;
    after a learner's edit some may not, and the chapter must go on."""
    if namespace is None:
        from IPython import get_ipython  # noqa: PLC0415

        namespace = get_ipython().user_ns
    notes = []
    for stmt in ast.parse(cell).body:
        code = compile(ast.Module(body=[stmt], type_ignores=[]), "<book check>", "exec")
        try:
            exec(code, namespace)  # noqa: S102 - the chapter's own hidden check
        except Exception as exc:  # noqa: BLE001 - every failure of a check is reported in one line, never raised
            what = "does not hold" if isinstance(exc, AssertionError) else f"failed ({type(exc).__name__}: {exc})"
            notes.append(f"line {stmt.lineno}: {what}"[:200])
            for pattern in _glued_names(stmt):  # the numbers this statement would have given the text
                UNDEFINED[pattern] = notes[-1]
    if notes:
        more = f" and {len(notes) - 1} more" if len(notes) > 1 else ""
        print(f"A hidden check of the book's own numbers did not pass here ({notes[0]}{more}): expected after a "
              "change of the chapter's inputs; the text shows the numbers of your run where it can.")
    return notes


def load_ipython_extension(ipython, panels=()):
    """``%load_ext scara.book`` (or this function called again, as the take-home chapters' first cell does: a
    second call changes nothing): registers the cell magic ``%%book_check`` (:func:`book_check`) and gives the
    notebook :func:`glued` and :func:`show`, which the text's inline expressions call. ``panels`` names the
    :mod:`scara.widgets` builders the chapter calls, whose programs :func:`compile_ahead` compiles meanwhile."""
    ipython.push({"glued": glued, "show": show})
    ipython.register_magic_function(lambda line, cell: book_check(line, cell, ipython.user_ns) and None,
                                    magic_kind="cell", magic_name="book_check")
    if panels:
        compile_ahead(panels)


# --------------------------------------------------------------------------------------------------
# compiling the chapter's panels ahead, in a background process
# --------------------------------------------------------------------------------------------------
#: set in the background process's environment (it starts no process of its own)
AHEAD_CHILD = "SCARA_COMPILE_AHEAD_CHILD"
#: the longest a panel waits for the background process to compile its program (s); then it compiles it itself
AHEAD_TIMEOUT = 300.0
#: the running background process, its marker folder (one file per kernel compiled) and its kernels' names
_AHEAD: dict = {}
#: the :mod:`scara.widgets` builders (decorated by :func:`ahead`): the compiled kernels of their panels, by name
AHEAD_BUILDERS: dict = {}


def kernel_name(kernel) -> str:
    """A kernel's name in the marker folder of :func:`compile_ahead`: its module and qualified name."""
    fn = getattr(kernel, "py_func", kernel)
    return f"{fn.__module__}.{fn.__qualname__}"


def compile_ahead(panels) -> bool:
    """Start one background process that compiles the page programs of the panels named in ``panels`` (builders of
    :mod:`scara.widgets`, such as ``"control_panel"``; then the kernels that prepare their data) into numba's
    on-disk cache, which this kernel then reads instead of compiling them: a panel's move waits for its program
    there (:func:`wait_compiled`). The process runs at a lower priority, with this kernel's environment (the same
    ``NUMBA_CACHE_DIR``), and is stopped when the kernel exits. Returns whether a process was started (not when
    one is running, when there is nothing to compile, when numba or the panels' own packages (ipywidgets) are
    missing, or inside such a process): the chapter runs the same without it."""
    from ._compile import COMPILED  # noqa: PLC0415

    try:
        from . import widgets  # noqa: F401, PLC0415 - its builders register their kernels in AHEAD_BUILDERS
    except ImportError:  # an install without the panels: the chapter's panel cells say what is missing
        return False

    names = tuple(dict.fromkeys(str(n) for n in panels))
    if not names:
        return False
    unknown = [n for n in names if n not in AHEAD_BUILDERS]
    if unknown:
        raise ValueError(f"panels {unknown} are not builders of scara.widgets; they are {sorted(AHEAD_BUILDERS)}")
    kernels = tuple(dict.fromkeys(kernel_name(k) for n in names for k in AHEAD_BUILDERS[n]))
    if not kernels or not COMPILED or os.environ.get(AHEAD_CHILD) or _AHEAD.get("process") is not None:
        return False
    folder = tempfile.mkdtemp(prefix="scara-ahead-")
    kw: dict = {}
    if sys.platform == "win32":
        kw["creationflags"] = subprocess.BELOW_NORMAL_PRIORITY_CLASS
    else:
        kw["preexec_fn"] = lambda: os.nice(10)
    process = subprocess.Popen([sys.executable, "-m", "scara.book", folder, *names], stdin=subprocess.DEVNULL,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               env={**os.environ, AHEAD_CHILD: "1"}, **kw)
    if not _AHEAD.get("registered"):
        atexit.register(_stop_ahead)
    _AHEAD.update(process=process, folder=Path(folder), kernels=kernels, registered=True)
    return True


def _stop_ahead():
    """Stop the background process of :func:`compile_ahead` if it still runs, and remove its marker folder."""
    process = _AHEAD.pop("process", None)
    if process is not None and process.poll() is None:
        process.kill()
    if process is not None:
        process.wait()
    folder = _AHEAD.pop("folder", None)
    if folder is not None:
        shutil.rmtree(folder, ignore_errors=True)
    _AHEAD.pop("kernels", None)


def wait_compiled(kernel, timeout: float = AHEAD_TIMEOUT) -> None:
    """Wait until the background process of :func:`compile_ahead` has compiled ``kernel`` (or has ended, or
    ``timeout`` s passed); at once when it was not asked to."""
    process = _AHEAD.get("process")
    if process is None:
        return
    name = kernel_name(kernel)
    if name not in _AHEAD["kernels"]:
        return
    marker = _AHEAD["folder"] / name
    end = time.monotonic() + timeout
    while not marker.exists() and process.poll() is None and time.monotonic() < end:
        time.sleep(0.02)


def ahead(*kernels):
    """Decorator of a :mod:`scara.widgets` panel builder: ``kernels`` are its panel's compiled kernels, its page
    program first (then those that prepare its data), each taking float arrays only, which :func:`compile_ahead`
    compiles for a chapter that calls the builder."""

    def register(builder):
        AHEAD_BUILDERS[builder.__name__] = kernels
        return builder

    return register


def _compile_kernels(folder: str, names) -> None:
    """The background process: the kernels of each panel named, compiled (or read from the cache) for arrays of
    floats, in order; a marker file for each kernel done, whatever the outcome (a kernel that cannot be compiled
    here is compiled, or refused with its message, by the panel in the kernel)."""
    import numba  # noqa: PLC0415

    import scara.widgets  # noqa: F401, PLC0415 - the builders register their kernels

    from scara.book import AHEAD_BUILDERS as builders  # noqa: PLC0415 - the module's, not __main__'s

    done = set()
    for name in names:
        for k in builders[name]:
            if kernel_name(k) in done:
                continue
            done.add(kernel_name(k))
            try:
                n = k.py_func.__code__.co_argcount
                k.compile((numba.types.float64[::1],) * n)
            except Exception:  # noqa: BLE001, S110 - the panel in the kernel compiles it and reports any problem
                pass
            Path(folder, kernel_name(k)).touch()


if __name__ == "__main__":  # python -m scara.book FOLDER BUILDER...: the process of compile_ahead
    _compile_kernels(sys.argv[1], sys.argv[2:])
