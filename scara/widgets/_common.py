"""The Jupyter front end of the live panels: ipywidgets controls built from a panel's declaration, a message
line, figures that redraw in place, a table.

A panel is declared once, as data, in :mod:`scara.plots.panels` (:class:`~scara.plots.panels.Panel`): its
controls, ``compute(settings) -> state`` (the robotics, in compiled code; it raises
:class:`~scara.errors.ScaraError` for a setting the package refuses), its figures as builder/update pairs and
its summary table. :class:`LivePanel` builds the ipywidgets from the controls table (:func:`build_control`).

The figures are shown as plotly ``FigureWidget`` objects created once, from the builders, when the panel is
built. On every change each pair's update (trace data and titles keyed by role or name) is applied to the figure
shown, and only what differs (a trace's ``x``/``y``/``z``, a title, an axis, the annotations) is sent to the
browser in one update message per figure (the message ``batch_update`` sends, built directly), so that one move
redraws each figure once and nothing is ever displayed outside the panel. A refused setting shows its message
and marks every figure *stale* (its traces hidden, its title saying why) until a valid setting is made again.
"""
from __future__ import annotations

import base64
import html
import json
import math
import re
import time
from contextlib import contextmanager

import ipywidgets as ipw
import numpy as np
import plotly.graph_objects as go
from plotly.basedatatypes import Undefined

from ..errors import ScaraError
from ..plots.layout import without_template
from ..plots.panels import Control, Panel, apply_update, start_value

__all__ = ["LivePanel", "build_control", "table", "readable", "start_value", "trajectory_arg", "LABEL_STYLE",
           "STALE_TITLE", "REFUSED"]

#: the style of every control: its description shown in full, not cut to a fixed width
LABEL_STYLE = {"description_width": "initial"}

#: the title a figure shows while the controls describe a setting that was refused
STALE_TITLE = "Not current: this setting was refused (see the message above)"
#: the words before a refusal's message
REFUSED = "Cannot show this setting:"

#: style shared by every panel: a stale figure is greyed out as well as emptied
_STYLE = """<style>
.scara-panel .scara-stale {opacity: 0.35; filter: grayscale(1);}
.scara-panel .scara-panel-message {color: #B00020; padding: 4px 0;}
.scara-panel .scara-panel-note {color: #8a5a00; padding: 4px 0;}
.scara-panel table.scara-panel-table td {padding: 2px 10px;}
</style>"""


def table(rows) -> str:
    """An HTML table of ``(label, value)`` pairs of plain text (escaped here)."""
    body = "".join(f"<tr><td>{html.escape(str(a))}</td><td><b>{html.escape(str(b))}</b></td></tr>"
                   for a, b in rows)
    return f"<table class='scara-panel-table' style='font-family:monospace'>{body}</table>"


_POINT = re.compile(r"\bx = \[\s*([^\]]*?)\s*\]")


def readable(message: str) -> str:
    """A package message in a panel's units: a point printed as an array, ``x = [px py pz phi]`` (m and rad),
    becomes ``(x, y, z) = (px, py, pz) m, φ = ...°``."""

    def point(match):
        try:
            v = [float(t) for t in match.group(1).replace(",", " ").split()]
        except ValueError:
            return match.group(0)
        if len(v) not in (3, 4):
            return match.group(0)
        text = f"(x, y, z) = ({v[0]:.4g}, {v[1]:.4g}, {v[2]:.4g}) m"
        return text + (f", φ = {math.degrees(v[3]):.4g}°" if len(v) == 4 else "")

    return _POINT.sub(point, message)


def _same(a, b) -> bool:
    """Deep equality of plotly JSON values (dicts, lists, tuples, numpy arrays, numbers, strings)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        try:
            a_arr, b_arr = np.asarray(a), np.asarray(b)
        except (TypeError, ValueError):
            return False
        if a_arr.shape != b_arr.shape or a_arr.dtype.kind != b_arr.dtype.kind:
            return False
        if a_arr.dtype.kind == "f":
            return bool(np.array_equal(a_arr, b_arr, equal_nan=True))
        return bool(np.array_equal(a_arr, b_arr))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        if len(a) != len(b):
            return False
        try:  # lists of numbers or strings: one comparison in C (NaN never appears: gaps are None)
            if (a == b) is True:
                return True
        except (TypeError, ValueError):  # numpy arrays inside: element by element
            pass
        return all(_same(x, y) for x, y in zip(a, b))
    if type(a) is not type(b) and not (isinstance(a, (int, float)) and isinstance(b, (int, float))):
        return False
    return a == b or (a != a and b != b)  # NaN equals NaN here


def _delta(old: dict, new: dict) -> dict:
    """The top-level properties of ``new`` that differ from ``old``; properties ``old`` had and ``new`` has
    not are reset (``None``)."""
    out = {k: v for k, v in new.items() if k not in old or not _same(old[k], v)}
    out.update({k: None for k in old if k not in new})
    return out


def _widget_safe(value):
    """``value`` with every numpy array made a plain list (NaN as ``None``, a gap in a line), and plotly's
    base64 arrays (``{"dtype", "bdata"}``, which ``to_plotly_json`` may return) decoded first.

    plotly's FigureWidget (7.1) keeps a numpy array as it is but stores the browser's echo of it (a typed
    array) as a dict, and then fails comparing the two (``ValueError: The truth value of an array ... is
    ambiguous`` in ``_remove_overlapping_props``, written to the Log Console on every update). Plain lists
    travel as plain arrays and come back as lists.
    """
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "f":
            return [None if v != v else v for v in value.astype(np.float64).tolist()]
        return value.tolist()
    if isinstance(value, dict):
        if "bdata" in value and "dtype" in value:
            arr = np.frombuffer(base64.b64decode(value["bdata"]), dtype=np.dtype(value["dtype"]))
            if value.get("shape"):
                arr = arr.reshape([int(n) for n in str(value["shape"]).split(",")])
            return _widget_safe(arr)
        return {k: _widget_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_widget_safe(v) for v in value)
    return value


def _detached(value):
    """``value`` with its dicts copied at every depth, lists of dicts (shapes, annotations) included; lists of
    numbers and arrays, never edited in place, are shared."""
    if isinstance(value, dict):
        return {k: _detached(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)) and value and isinstance(value[0], dict):
        return type(value)(_detached(v) for v in value)
    return value


def _structure(state: dict) -> list:
    return [t.get("type", "scatter") for t in state["data"]]


def build_control(c: Control):
    """The ipywidget of the control ``c``: a ``FloatSlider`` (or ``FloatLogSlider`` on a log scale), a
    ``Dropdown``, a ``FloatText`` or a ``Checkbox``, labelled ``c.label``, starting at ``c.default``."""
    common = dict(description=c.label, style=LABEL_STYLE)
    if c.kind == "dropdown":
        return ipw.Dropdown(options=list(c.options), value=c.default, **common)
    if c.kind == "toggle":
        return ipw.Checkbox(value=c.default, **common)
    common["continuous_update"] = False
    if c.kind == "number":
        return ipw.FloatText(value=c.default, step=c.step, layout=ipw.Layout(width="180px"), **common)
    if c.readout:
        common["readout_format"] = c.readout
    if c.scale == "log":
        return ipw.FloatLogSlider(value=c.default, base=10, min=math.log10(c.low), max=math.log10(c.high), step=c.step,
                                  **common)
    return ipw.FloatSlider(value=c.default, min=c.low, max=c.high, step=c.step, **common)


class LivePanel:
    """Controls, a message line, figures redrawn in place and a table (see the module's docstring).

    Parameters
    ----------
    declaration : Panel
        The panel (:class:`~scara.plots.panels.Panel`): its controls become ipywidgets (:func:`build_control`),
        ``declaration.compute`` is called with the controls' values by name, each figure pair draws one figure.

    The initial values must be valid: a panel built on a refused setting raises that :class:`ScaraError`.
    Attributes a test or a notebook may read: ``declaration``, ``controls`` (name -> ipywidget), ``figures``
    (the ``FigureWidget`` objects), ``last_error`` (the message shown, or None), ``state`` (the last valid
    computation), ``timings`` (seconds spent in ``compute``, ``draw`` and sending the update, for the last
    change), ``redraws`` (figure updates sent so far). ``compute`` may be replaced (a test counts its calls).
    """

    def __init__(self, declaration: Panel):
        self.declaration = declaration
        self.controls = {c.name: build_control(c) for c in declaration.controls}
        self.compute = declaration.compute
        self.explain = declaration.explain or (lambda exc, values: readable(str(exc)))
        self.message = ipw.HTML()
        self.message.add_class("scara-panel-message")
        self.notes = ipw.HTML()
        self.notes.add_class("scara-panel-note")
        self.info = ipw.HTML()
        self.last_error: str | None = None
        self.redraws = 0
        self.timings: dict = {}
        self._holding = 0
        self._stale = False
        self._seq = 0

        state = self._compute(self.values())  # raises for an invalid start: nothing silently clamped
        self._states = [_widget_safe(pair.build(state).to_plotly_json()) for pair in declaration.figures]
        self.timings["draw"] = time.perf_counter() - self._t
        self.figures = [go.FigureWidget(s) for s in self._states]
        # each figure in a box of its own: the box carries the classes (a FigureWidget's own are not applied)
        self._boxes = [ipw.Box([fw], layout=ipw.Layout(display="block")) for fw in self.figures]
        for box in self._boxes:
            box.add_class("scara-panel-figure")
        self._show_text(state)

        for w in self.controls.values():
            w.observe(self._changed, names="value")
        if declaration.selector is not None:
            self.controls[declaration.selector].observe(self._grey, names="value")
            self._grey()
        grid = ipw.GridBox(list(self.controls.values()),
                           layout=ipw.Layout(grid_template_columns=f"repeat({declaration.columns}, minmax(0, 1fr))"))
        title = declaration.title
        head = ipw.HTML(_STYLE + (f"<b>{html.escape(title)}</b>" if title else ""))
        self.widget = ipw.VBox([head, grid, self.message, *self._boxes, self.notes, self.info])
        self.widget.add_class("scara-panel")

    # ------------------------------------------------------------------------------------------------------
    def values(self) -> dict:
        """The controls' current values, by name."""
        return {k: w.value for k, w in self.controls.items()}

    @contextmanager
    def hold(self):
        """Change several controls at once: the panel recomputes once, when the block ends."""
        self._holding += 1
        try:
            yield self
        finally:
            self._holding -= 1
        if not self._holding:
            self.update()

    def _grey(self, change=None):
        """Grey out the controls the selector's choice does not read (their ``applies_to``)."""
        values = self.values()
        for c in self.declaration.controls:
            self.controls[c.name].disabled = not self.declaration.applies(c, values)

    def _changed(self, change):
        if self._holding:
            return
        react = self.declaration.react
        name = next(k for k, w in self.controls.items() if w is change["owner"])
        if react is None:
            self.update()
            return
        with self.hold():
            for key, value in react(name, self.values()).items():
                self.controls[key].value = value

    def _compute(self, values):
        t0 = time.perf_counter()
        state = self.compute(values)
        self._t = time.perf_counter()
        self.timings = {"compute": self._t - t0}
        return state

    def update(self) -> None:
        """Recompute for the controls' values and redraw in place, or show why the setting is refused."""
        values = self.values()
        try:
            state = self._compute(values)
            # the template went with the first figures; only what changes is sent from now on
            with without_template():
                news = [apply_update(old, _widget_safe(pair.updated(state)), pair)
                        for old, pair in zip(self._states, self.declaration.figures)]
        except ScaraError as exc:
            self._refuse(self.explain(exc, values))
            return
        self.timings["draw"] = time.perf_counter() - self._t
        t0 = time.perf_counter()
        for k, (fw, new) in enumerate(zip(self.figures, news)):
            self._sync(k, fw, new)
        self.timings["send"] = time.perf_counter() - t0
        self.last_error = None
        self._stale = False
        self.message.value = ""
        self._show_text(state)

    def _values_html(self) -> str:
        """The controls' values, as JSON in a hidden element, with the number of this update and its timings
        (ms): what the figure was computed for, readable by a browser test without parsing rounded readouts."""
        self._seq += 1
        values = {k: (v if isinstance(v, (bool, int, float, str)) else str(v)) for k, v in self.values().items()}
        state = dict(values=values, seq=self._seq, **{f"{k}_ms": 1e3 * v for k, v in self.timings.items()})
        return f"<span hidden class='scara-panel-values'>{html.escape(json.dumps(state))}</span>"

    def _show_text(self, state) -> None:
        self.state = state
        rows, notes = self.declaration.summary(state) if self.declaration.summary else ((), ())
        self.info.value = (table(rows) if rows else "") + self._values_html()
        self.notes.value = "".join(f"<div>⚠ {html.escape(n)}</div>" for n in notes)

    def _sync(self, k: int, fw, new: dict) -> None:
        """Send the differences between the figure shown and ``new`` (a plotly JSON dict) in one update."""
        old = self._states[k]
        if "template" in old["layout"]:
            new["layout"]["template"] = old["layout"]["template"]  # sent once, with the first figure
        layout = _delta(old["layout"], new["layout"])
        if self._stale:
            self._boxes[k].remove_class("scara-stale")
            layout.setdefault("title", new["layout"].get("title"))
        if _structure(old) != _structure(new):
            # a different set of traces: replace them (no panel changes its traces' kinds on a move)
            fw.data = ()
            fw.add_traces(new["data"])
            deltas = []
        else:
            deltas = [_delta(a, b) for a, b in zip(old["data"], new["data"])]
            if self._stale:
                for d, b in zip(deltas, new["data"]):
                    d["visible"] = b.get("visible", True)
        if layout or any(deltas):
            # the message ``batch_update`` builds (one Plotly.update in the browser), without re-validating
            # data that came from validated figures: plotly's validators walk every element of every list
            changed = [i for i, d in enumerate(deltas) if d]
            props = sorted({key for i in changed for key in deltas[i]})
            restyle = {key: [_detached(deltas[i].get(key, Undefined)) for i in changed] for key in props}
            # plotly keeps what it is sent and later edits it in place (a refusal sets ``layout.title.text``):
            # send copies of the nested dicts, so that the panel's record of the figure stays its own
            fw.plotly_update(restyle_data=restyle, relayout_data=_detached(layout), trace_indexes=changed)
            self.redraws += 1
        self._states[k] = new

    def _refuse(self, text: str) -> None:
        """Show ``text`` and mark every figure stale: traces hidden, title replaced, greyed out."""
        self.last_error = text
        self.message.value = f"<b>{REFUSED}</b> {html.escape(text)}"
        self.info.value = self._values_html()
        self.notes.value = ""
        if self._stale:
            return
        for fw, box in zip(self.figures, self._boxes):
            with fw.batch_update():
                for trace in fw.data:
                    trace.visible = False
                fw.layout.title.text = STALE_TITLE
            box.add_class("scara-stale")
            self.redraws += 1
        self._stale = True

    def _repr_mimebundle_(self, include=None, exclude=None):
        """The ipywidgets view (what Jupyter shows) and, when the declaration has a page program, the page
        panel as HTML (what the built book shows, computing in the page: :mod:`scara.page.assets`)."""
        bundle = self.widget._repr_mimebundle_(include=include, exclude=exclude)
        if self.declaration.page is not None:
            from ..page.assets import panel_html  # noqa: PLC0415

            bundle = dict(bundle)
            bundle["text/html"] = panel_html(self)
        return bundle


def trajectory_arg(traj, p):
    """``traj`` (a :class:`~scara.trajectory.Trajectory`), or the 70 s reference of chapter 3 when it is None;
    anything else raises :class:`ScaraError`."""
    from ..trajectory import Trajectory, reference_trajectory  # noqa: PLC0415 - built on demand

    if traj is None:
        return reference_trajectory(p=p)
    if not isinstance(traj, Trajectory):
        raise ScaraError(f"traj must be a Trajectory (from plan_path or reference_trajectory) or None, "
                         f"got {type(traj).__name__} {traj!r:.80}")
    return traj
