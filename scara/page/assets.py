"""What a static page needs to run the live panels with no kernel: the engine (the page programs' kernels
translated to JavaScript by :mod:`scara.page.translate`, with a Web Worker's message loop), the panels' script
(``static/scara-panels.js``: building the controls, scheduling the work, handing arrays to plotly.js) and, for
each panel, the HTML that declares it (:func:`panel_html`).

The page panel's contract, for graders, tests and a teacher's scripts:

* the panel is the element ``[data-scara-panel=NAME]``, NAME being the :mod:`scara.widgets` function that builds
  the same panel in Jupyter;
* each control is a native ``<input>`` or ``<select>`` with ``name`` = the control's key (as
  :attr:`scara.widgets.LivePanel.controls` names it); a slider is a range input beside a number input, and the
  number input (``input[type=number][name=KEY]``) holds the value (a log slider's range input moves in decades);
  a dropdown's ``<option>`` values are the indices of its choices; a toggle is a checkbox;
* after every redraw the hidden element ``.scara-panel-values`` holds JSON: ``values`` by control name, as
  :meth:`scara.widgets.LivePanel.values` gives them, an increasing ``seq`` and the timings (ms) of the move;
* a refused setting shows its message in ``.scara-panel-message`` and gives the panel the class ``scara-stale``
  (figures greyed and emptied) until a setting is valid again;
* its plotly figures are the ``.scara-panel-figure`` elements inside it, in the order and with the traces of the
  Jupyter panel's ``figures``;
* its settings are written in the page's address (``#NAME.KEY=VALUE&...``), so a link opens the panel at those
  settings and a reload keeps them; a panel whose edits build on each other (the waypoint editor) also keeps
  its earlier edits there (``NAME.edits=KEY:VALUE,...;KEY:VALUE,...``, one per stretch of moves at the same
  waypoint and segment), replayed in order on a reload; its reset button returns to the book's values;
* a panel with a ``drag`` (:class:`~scara.plots.panels.PageProgram`) lets the reader drag the points of one
  figure with the pointer: each pointer move sets the declared controls, as typing them would.
"""
from __future__ import annotations

import html
import importlib
import json
import pkgutil
from pathlib import Path

import numpy as np

from .translate import translate

__all__ = ["ENGINE_JS", "PANELS_JS", "STATIC", "program_kernels", "engine_source", "panel_spec", "panel_html",
           "WORKER"]

#: the folder of the hand-written page scripts (the mechanics), copied into the book's ``_static``
STATIC = Path(__file__).resolve().parent / "static"
#: the engine's file name in ``_static`` (generated at build time) and the panels' script
ENGINE_JS = "scara-engine.js"
PANELS_JS = "scara-panels.js"

#: the engine's message loop in the Web Worker: the panel sends its fixed data once, then one message per move
#: (the latest move only: the page drops the moves made while the engine was busy)
WORKER = r"""
if (typeof self !== 'undefined' && typeof module === 'undefined') {
  const store = {};
  self.onmessage = (ev) => {
    const m = ev.data;
    if (m.type === 'data') {
      // the data, then the program's scratch (PageProgram.scratch: work space it overwrites in every move)
      const given = Float64Array.from(m.data), scratch = m.scratch || 0;
      const size = m.prepare ? m.size : given.length;
      const full = new Float64Array(size + scratch);
      const data = full.subarray(0, size);  // the data alone, a view of the block the program gets
      if (m.prepare) {  // the data made from its compact form by the program's own kernel, once
        const status = SCARA_KERNELS[m.prepare](given, data);
        if (Number(status) !== 0) { store[m.panel] = new Error(m.prepare + ' refused the panel data (status ' + status + ')'); return; }
      } else data.set(given);
      store[m.panel] = {data, full};
      return;
    }
    if (m.type === 'dump') {  // the data as the engine holds it, prepared here (a test compares a run on it)
      const d = store[m.panel];
      self.postMessage({id: m.id, panel: m.panel, data: d instanceof Error ? null : d.data.slice()});
      return;
    }
    const t0 = performance.now();
    try {
      const fn = SCARA_KERNELS[m.kernel];
      if (!fn) throw new Error('the engine has no program ' + m.kernel);
      if (store[m.panel] instanceof Error) throw store[m.panel];
      const out = new Float64Array(m.size);
      const status = fn(Float64Array.from(m.inputs), store[m.panel].full, out);
      self.postMessage({id: m.id, panel: m.panel, status: Number(status), out: out, compute_ms: performance.now() - t0},
                       [out.buffer]);
    } catch (err) {
      self.postMessage({id: m.id, panel: m.panel, error: String(err && err.message || err),
                        compute_ms: performance.now() - t0});
    }
  };
}
"""


def program_kernels() -> dict:
    """Every page program of the package, and the kernels that prepare their data: the kernels named
    ``*_program`` or ``*_prepare`` in the modules of :mod:`scara.programs`, by name."""
    import scara.programs as programs  # noqa: PLC0415

    found = {}
    for info in pkgutil.iter_modules(programs.__path__):
        mod = importlib.import_module(f"scara.programs.{info.name}")
        for name, value in vars(mod).items():
            fn = getattr(value, "py_func", value)
            if name.endswith(("_program", "_prepare")) and callable(value) and \
                    getattr(fn, "__module__", "") == mod.__name__:
                if name in found:
                    raise ValueError(f"two page programs are called {name!r}")
                found[name] = value
    return found


def engine_source() -> str:
    """The engine script: every page program translated (with the kernels they call) and the worker's loop."""
    from ..programs import PREPARE_ARGS, PROGRAM_ARGS  # noqa: PLC0415

    kernels = program_kernels()
    signatures = None if PROGRAM_ARGS is None else {
        name: PREPARE_ARGS if name.endswith("_prepare") else PROGRAM_ARGS for name in kernels}
    return "// Generated from the scara package's kernels by scara.page.translate: do not edit.\n" + \
        translate(list(kernels.values()), exports=kernels, signatures=signatures) + WORKER


def _plain(value):
    """``value`` made JSON-ready: arrays as lists (NaN as None, a gap in a plotly line), numpy numbers as numbers."""
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, (np.floating, float)):
        v = float(value)
        return None if v != v else v
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    return value


def panel_spec(panel) -> dict:
    """What the page needs of a :class:`~scara.widgets.LivePanel` whose declaration has a page program: its
    controls, its program (:meth:`~scara.plots.panels.PageProgram.describe`), its figures as the Jupyter panel
    first draws them with, for each, the position of every bound trace (:meth:`FigurePair.index`), and the
    texts the page shows around them."""
    from ..plots.panels import range_template  # noqa: PLC0415
    from ..widgets._common import STALE_TITLE, REFUSED  # noqa: PLC0415

    d = panel.declaration
    prog = d.page
    controls = []
    for c in d.controls:
        controls.append(dict(name=c.name, kind=c.kind, label=c.label, default=_plain(c.default), low=c.low,
                             high=c.high, step=c.step, scale=c.scale, unit=c.unit, readout=c.readout,
                             limit=c.limit,
                             options=[[str(o[0]), _plain(o[1])] if isinstance(o, tuple) else [str(o), _plain(o)]
                                      for o in c.options],
                             applies_to=None if c.applies_to is None else _plain(list(c.applies_to)),
                             outside=None if c.low is None else range_template(c.name, c.low, c.high, c.unit, c.limit),
                             not_number=f"{c.name} must be a number{f' (in {c.unit})' if c.unit else ''}, got '{{value}}'"))
    figures = []
    for pair, fig in zip(d.figures, panel._states):
        index = {key: pair.index(fig, key) for key in prog.traces.get(pair.role, {})}
        figures.append(dict(role=pair.role, figure=_plain(fig), index=index))
    return dict(name=d.widget, title=d.title, columns=d.columns, selector=d.selector, controls=controls,
                program=_plain(prog.describe(d)), figures=figures, stale_title=STALE_TITLE, refused=REFUSED,
                values=_plain(panel.values()))


def panel_html(panel) -> str:
    """The page panel of ``panel`` (a :class:`~scara.widgets.LivePanel` with a page program): an element
    ``data-scara-panel`` holding its declaration as JSON, which ``scara-panels.js`` builds into controls and
    figures; with JavaScript off, a note says what the panel needs."""
    spec = json.dumps(panel_spec(panel), separators=(",", ":"), allow_nan=False)
    spec = spec.replace("</", "<\\/")  # never close the script element early
    name = html.escape(panel.declaration.widget or "", quote=True)
    return (f'<div class="scara-page-panel" data-scara-panel="{name}">'
            f'<script type="application/json" class="scara-panel-spec">{spec}</script>'
            '<noscript><p class="scara-panel-noscript">This live panel computes in the page with the package\'s '
            'own code: it needs JavaScript. The figures around it are static and read without it.</p></noscript>'
            '</div>')
