"""Shared machinery for live panels: controls, a message line, figures that redraw in place, a table.

A panel is built from two functions of the control values:

* ``compute(**values)`` does the robotics (the compiled code) and returns whatever ``draw`` needs; it raises
  :class:`~scara.errors.ScaraError` for a setting the package refuses;
* ``draw(state)`` turns that into :class:`PanelView`: the figures (``plotly.graph_objects.Figure``, built by the
  same :mod:`scara.plots` builders as the book's static figures) and an HTML table.

The figures are shown as plotly ``FigureWidget`` objects created once, when the panel is built. On every change
the new figures are compared with the previous ones and only what differs (a trace's ``x``/``y``/``z``, a
title, an axis, the annotations) is sent to the browser in one update message per figure (the message
``batch_update`` sends, built directly), so that one move redraws each figure once and nothing is ever
displayed outside the panel. A refused setting shows its message and marks every figure *stale* (its traces
hidden, its title saying why) until a valid setting is made again.
"""
from __future__ import annotations

import base64
import html
import json
import math
import numbers
import re
import time
from contextlib import contextmanager
from dataclasses import dataclass, field

import ipywidgets as ipw
import numpy as np
import plotly.graph_objects as go
from plotly.basedatatypes import Undefined
from IPython.display import display

from ..errors import NonFiniteError, ScaraError
from ..plots.layout import without_template

__all__ = ["LivePanel", "PanelView", "table", "readable", "number", "start_value", "angle_slider", "stroke_slider",
           "trajectory_arg", "LABEL_STYLE", "STALE_TITLE"]

#: the style of every control: its description shown in full, not cut to a fixed width
LABEL_STYLE = {"description_width": "initial"}

#: the title a figure shows while the controls describe a setting that was refused
STALE_TITLE = "Not current: this setting was refused (see the message above)"

#: style shared by every panel: a stale figure is greyed out as well as emptied
_STYLE = """<style>
.scara-panel .scara-stale {opacity: 0.35; filter: grayscale(1);}
.scara-panel .scara-panel-message {color: #B00020; padding: 4px 0;}
.scara-panel .scara-panel-note {color: #8a5a00; padding: 4px 0;}
.scara-panel table.scara-panel-table td {padding: 2px 10px;}
</style>"""


@dataclass
class PanelView:
    """What a panel shows for one valid setting: its figures, an HTML table below them, and notes (plain
    text) that flag a boundary case the numbers alone would hide.

    A figure is a ``go.Figure`` or, when only its data and title changed since the last one the panel drew
    (the same method or controller, other numbers), a partial update that skips rebuilding the layout:
    ``{"data": [dict of trace properties, or None for an unchanged trace, ...], "title": str,
    "layout": {top-level layout properties}}``.
    """

    figures: list
    table: str = ""
    notes: list = field(default_factory=list)


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


def _merge(old: dict, part: dict) -> dict:
    """The figure ``old`` (plotly JSON) with a partial update applied (see :class:`PanelView`)."""
    data = [dict(t) for t in old["data"]]
    for i, d in enumerate(part.get("data") or ()):
        if d:
            data[i].update(_widget_safe(d))
    layout = dict(old["layout"])
    layout.update(_widget_safe(part.get("layout") or {}))
    if "title" in part:
        layout["title"] = dict(layout.get("title") or {}, text=part["title"])
    return {"data": data, "layout": layout}


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


class LivePanel:
    """Controls, a message line, figures redrawn in place and a table (see the module's docstring).

    Parameters
    ----------
    controls : dict
        Name -> ipywidget; ``compute`` is called with the widgets' values under these names.
    compute, draw : callables
        ``compute(**values) -> state`` and ``draw(state) -> PanelView``.
    title : str
        A heading shown above the controls.
    columns : int
        Controls per row.
    explain : callable, optional
        ``explain(exc, values) -> str``: the message shown for a refused setting, in the panel's own units
        (default: the exception's text, points written as (x, y, z) in m and φ in degrees).
    react : callable, optional
        ``react(change)``, called on every change before the panel recomputes, while updates are held: it may
        set other controls (e.g. load the values of the item a dropdown picked) and the panel still
        recomputes and redraws once.

    The initial values must be valid: a panel built on a refused setting raises that :class:`ScaraError`.
    Attributes a test or a notebook may read: ``figures`` (the ``FigureWidget`` objects), ``last_error``
    (the message shown, or None), ``state`` (the last valid computation), ``timings`` (seconds spent in
    ``compute``, ``draw`` and sending the update, for the last change), ``redraws`` (figure updates sent so
    far).
    """

    def __init__(self, controls: dict, compute, draw, title: str = "", columns: int = 2, explain=None,
                 react=None):
        self.controls = controls
        self.react = react
        self.compute = compute
        self.draw = draw
        self.explain = explain or (lambda exc, values: readable(str(exc)))
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

        view = self._view(self.values(), first=True)  # raises for an invalid start: nothing silently clamped
        self._states = [_widget_safe(f.to_plotly_json()) for f in view.figures]
        self.figures = [go.FigureWidget(state) for state in self._states]
        # each figure in a box of its own: the box carries the classes (a FigureWidget's own are not applied)
        self._boxes = [ipw.Box([fw], layout=ipw.Layout(display="block")) for fw in self.figures]
        for box in self._boxes:
            box.add_class("scara-panel-figure")
        self._show_text(view)

        for w in controls.values():
            w.observe(self._changed, names="value")
        grid = ipw.GridBox(list(controls.values()),
                           layout=ipw.Layout(grid_template_columns=f"repeat({columns}, minmax(0, 1fr))"))
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

    def _changed(self, change):
        if self._holding:
            return
        if self.react is None:
            self.update()
            return
        with self.hold():
            self.react(change)

    def _view(self, values, first: bool = False) -> PanelView:
        t0 = time.perf_counter()
        state = self.compute(**values)
        t1 = time.perf_counter()
        if first:
            view = self.draw(state)
        else:  # the template went with the first figure; only what changes is sent from now on
            with without_template():
                view = self.draw(state)
        self.timings = {"compute": t1 - t0, "draw": time.perf_counter() - t1}
        self.state = state
        return view

    def update(self) -> None:
        """Recompute for the controls' values and redraw in place, or show why the setting is refused."""
        values = self.values()
        try:
            view = self._view(values)
        except ScaraError as exc:
            self._refuse(self.explain(exc, values))
            return
        if len(view.figures) != len(self.figures):  # a programming error, not a student's
            raise RuntimeError(f"the panel drew {len(view.figures)} figures, it shows {len(self.figures)}")
        t0 = time.perf_counter()
        for k, (fw, fig) in enumerate(zip(self.figures, view.figures)):
            new = _merge(self._states[k], fig) if isinstance(fig, dict) else _widget_safe(fig.to_plotly_json())
            self._sync(k, fw, new)
        self.timings["send"] = time.perf_counter() - t0
        self.last_error = None
        self._stale = False
        self.message.value = ""
        self._show_text(view)

    def _values_html(self) -> str:
        """The controls' values, as JSON in a hidden element, with the number of this update and its timings
        (ms): what the figure was computed for, readable by a browser test without parsing rounded readouts."""
        self._seq += 1
        values = {k: (v if isinstance(v, (bool, int, float, str)) else str(v)) for k, v in self.values().items()}
        state = dict(values=values, seq=self._seq, **{f"{k}_ms": 1e3 * v for k, v in self.timings.items()})
        return f"<span hidden class='scara-panel-values'>{html.escape(json.dumps(state))}</span>"

    def _show_text(self, view: PanelView) -> None:
        self.info.value = view.table + self._values_html()
        self.notes.value = "".join(f"<div>⚠ {html.escape(n)}</div>" for n in view.notes)

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
        self.message.value = f"<b>Cannot show this setting:</b> {html.escape(text)}"
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

    def _ipython_display_(self):
        display(self.widget)


def number(value, name: str, unit: str = "") -> float:
    """``value`` as a float, if it is a real number (an ``int``, a ``float``, a numpy scalar), else
    :class:`ScaraError` naming it: a string, a bool, a list or an array is refused, never converted."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        u = f" (in {unit})" if unit else ""
        raise ScaraError(f"{name} must be a number{u}, got {type(value).__name__} {value!r:.80}")
    v = float(value)
    if not math.isfinite(v):
        raise NonFiniteError(f"{name} = {v} is not finite")
    return v


def start_value(value, lo: float, hi: float, name: str, unit: str = "", limit: str = "the panel's range") -> float:
    """A control's starting value, checked against the control's range ``[lo, hi]``: a value outside it, or
    one that is not a number (:func:`number`), raises :class:`ScaraError` naming the value and the range
    (``limit`` says what the range is; a panel never silently clamps what it was given)."""
    v = number(value, name, unit)
    if not (lo <= v <= hi):
        u = unit if unit == "°" else (f" {unit}" if unit else "")
        raise ScaraError(f"{name} = {v:g}{u} is outside {limit} {lo:g} to {hi:g}{u}")
    return v


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


def stroke_slider(d3: float, p):
    """A slider over the quill's stroke ``p.d3_min`` to ``p.d3_max`` (m) starting at ``d3``, which must lie in it."""
    v = start_value(d3, p.d3_min, p.d3_max, "d3", "m", limit="the quill's stroke d3_min to d3_max =")
    return ipw.FloatSlider(value=v, min=p.d3_min, max=p.d3_max, step=0.01, description="d3 (m)",
                           continuous_update=False, style=LABEL_STYLE)


def angle_slider(value_rad: float, name: str, desc: str):
    """A slider in degrees over [-180°, 180°] starting at ``value_rad`` (rad), checked by :func:`start_value`."""
    v = start_value(math.degrees(number(value_rad, name, "rad")), -180.0, 180.0, name, "°")
    return ipw.FloatSlider(value=v, min=-180.0, max=180.0, step=1.0, description=desc, continuous_update=False,
                           style=LABEL_STYLE)
