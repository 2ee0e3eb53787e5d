"""The Jupyter front end of the live panels: ipywidgets controls built from a panel's declaration, a message
line, figures that redraw in place, a table.

A panel is declared once, as data, in :mod:`scara.plots.panels` (:class:`~scara.plots.panels.Panel`): its
controls, ``compute(settings) -> state`` (the robotics, in compiled code; it raises
:class:`~scara.errors.ScaraError` for a setting the package refuses), its figures as builder/update pairs and
its summary table. :class:`LivePanel` builds the ipywidgets from the controls table (:func:`build_control`). A
slider is a :class:`NumberSlider`, a slider with a number box beside it (the page panel's range and number
inputs): a number typed outside the slider's range is refused with the page panel's message, like any refused
setting, never clamped. A panel built with ``keep=True`` starts from the last accepted settings of the previous
panel of its kind (a re-run cell keeps what was set in it).

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
import traitlets
from plotly.basedatatypes import Undefined

from ..errors import ScaraError, check_flag
from ..plots.layout import without_template
from ..plots.panels import Control, Panel, apply_update, start_value

__all__ = ["LivePanel", "NumberSlider", "build_control", "table", "readable", "start_value", "trajectory_arg",
           "LABEL_STYLE", "STALE_TITLE", "REFUSED", "SLIDER_DIGITS"]

#: the style of every control: its description shown in full, not cut to a fixed width
LABEL_STYLE = {"description_width": "initial"}

#: the title a figure shows while the controls describe a setting that was refused
STALE_TITLE = "Not current: this setting was refused (see the message above)"
#: the words before a refusal's message
REFUSED = "Cannot show this setting:"

#: the last panel of each kind built in this process (``declaration.widget`` or ``name`` -> LivePanel), whose
#: accepted settings a panel built with ``keep=True`` starts from
_LATEST: dict = {}

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


#: the significant digits of a slider's position as a value (:class:`NumberSlider`): a log slider's steps of 0.01
#: decade stay distinct, and the number fits the box beside it
SLIDER_DIGITS = 6


def _digits(v: float) -> float:
    """``v`` to :data:`SLIDER_DIGITS` significant digits (a value that is not finite as it is)."""
    return float(f"{v:.{SLIDER_DIGITS}g}") if math.isfinite(v) else v


class NumberSlider(ipw.HBox):
    """A slider with a number box beside it, which never clamps: the Jupyter form of a ``"slider"``
    :class:`~scara.plots.panels.Control` (as the page panel's range input beside its number input).

    ``value`` is the control's value (a float), what the panel reads. Moving the slider sets it and writes the
    box; a number typed in the box sets it as typed and, when it lies in the control's range ``[low, high]``,
    moves the slider there; outside the range the slider stays where it was, and the panel, seeing a value
    outside the range, refuses it with :func:`~scara.plots.panels.range_template`'s message. Setting ``value``
    from Python does the same (the box shows it, the slider follows when it is in range): nothing is clamped.
    (An ipywidgets slider's own readout clamps what is typed into it in the browser, before the kernel sees it:
    it is not shown.)

    A position of the slider gives its value to :data:`SLIDER_DIGITS` significant digits (a log slider's
    ``10 ** 1.96`` is 91.2011), so that the box shows the very number the panel computes with; a typed value or
    one set from Python is taken as it is (the box shows it to those digits).

    ``slider`` (a ``FloatSlider``, or a ``FloatLogSlider`` on a log scale, without its readout) and ``box`` (a
    ``FloatText``) are the two parts; ``disabled`` disables both; ``description`` is the slider's label, ``min``,
    ``max`` and ``step`` the control's range (in its unit, on a log scale too) and step.
    """

    value = traitlets.CFloat()
    disabled = traitlets.Bool(False)

    def __init__(self, c: Control):
        common = dict(continuous_update=False, readout=False, description=c.label, style=LABEL_STYLE,
                      layout=ipw.Layout(width="auto", flex="1 1 auto", min_width="0"))
        if c.scale == "log":
            slider = ipw.FloatLogSlider(value=c.default, base=10, min=math.log10(c.low), max=math.log10(c.high),
                                        step=c.step, **common)
        else:
            slider = ipw.FloatSlider(value=c.default, min=c.low, max=c.high, step=c.step, **common)
        box = ipw.FloatText(value=_digits(c.default), step=c.step if c.scale == "linear" else None,
                            continuous_update=False, layout=ipw.Layout(width="8.5em", flex="0 0 auto"))
        super().__init__([slider, box], value=c.default, layout=ipw.Layout(width="100%", align_items="center"))
        self.add_class("scara-slider")
        self.control = c
        self.slider, self.box = slider, box
        self._source = None  # the part whose change is being passed on (the others do not echo it)
        slider.observe(self._slid, names="value")
        box.observe(self._typed, names="value")
        self.observe(self._follow, names="value")
        self.observe(self._disable, names="disabled")

    @property
    def description(self) -> str:
        """The slider's label (the control's ``label``)."""
        return self.slider.description

    @property
    def min(self) -> float:
        """The lower end of the control's range (``low``, in its unit; on a log scale too)."""
        return self.control.low

    @property
    def max(self) -> float:
        """The upper end of the control's range (``high``, in its unit; on a log scale too)."""
        return self.control.high

    @property
    def step(self) -> float:
        """The slider's step (in the control's unit, in decades on a log scale)."""
        return self.control.step

    def in_range(self, v) -> bool:
        """Whether ``v`` lies in the control's range ``[low, high]``."""
        return self.control.low <= v <= self.control.high

    @contextmanager
    def _from(self, source: str):
        self._source = source
        try:
            yield
        finally:
            self._source = None

    def _slid(self, change):
        if self._source is None:
            v = _digits(change["new"])
            if not self.in_range(v):
                # a position at an end of the range: the end itself (a log slider's 10 ** log10(high) may differ
                # from high by its last bit, and the slider cannot leave its range)
                v = min(max(change["new"], self.control.low), self.control.high)
            with self._from("slider"):
                self.value = v

    def _typed(self, change):
        if self._source is None:
            with self._from("box"):
                self.value = change["new"]

    def _follow(self, change):
        """The value changed (by a part, or from Python): the other parts show it; the slider only in range."""
        v = change["new"]
        source = self._source
        with self._from(source or "value"):
            if source != "box":
                self.box.value = _digits(v)
            if source != "slider" and self.in_range(v):
                self.slider.value = v

    def _disable(self, change):
        self.slider.disabled = self.box.disabled = change["new"]


def build_control(c: Control):
    """The ipywidget of the control ``c``: a :class:`NumberSlider` (a slider and a number box, never clamping), a
    ``Dropdown``, a ``FloatText`` or a ``Checkbox``, labelled ``c.label``, starting at ``c.default``; each has a
    ``value`` and ``disabled``."""
    common = dict(description=c.label, style=LABEL_STYLE)
    if c.kind == "dropdown":
        return ipw.Dropdown(options=list(c.options), value=c.default, **common)
    if c.kind == "toggle":
        return ipw.Checkbox(value=c.default, **common)
    if c.kind == "number":
        return ipw.FloatText(value=c.default, step=c.step, layout=ipw.Layout(width="180px"), continuous_update=False,
                             **common)
    return NumberSlider(c)


class LivePanel:
    """Controls, a message line, figures redrawn in place and a table (see the module's docstring).

    Parameters
    ----------
    declaration : Panel
        The panel (:class:`~scara.plots.panels.Panel`): its controls become ipywidgets (:func:`build_control`),
        ``declaration.compute`` is called with the controls' values by name, each figure pair draws one figure.

    keep : bool
        Start from the last accepted settings of the previous panel of the same kind (the same
        ``declaration.widget``, else ``declaration.name``) built in this Python process: re-running a panel's
        cell keeps what was set in it. Only the settings this panel can take are kept (a dropdown's choice it
        does not offer is not); kept settings it refuses (a value outside a slider's range, a setting its
        computation refuses) are shown refused, with their message, over a panel built on its own start values.
        Without a previous panel, or with ``keep=False`` (the default), the panel starts from its declaration.

    Every slider control's value must lie in its range (``low`` to ``high``): a value outside it, typed in its
    number box or set from Python, is refused with :func:`~scara.plots.panels.range_template`'s message (the
    page panel's), like any refused setting; nothing is clamped. The initial values must be valid: a panel
    built on a refused setting raises that :class:`ScaraError`.
    Attributes a test or a notebook may read: ``declaration``, ``controls`` (name -> ipywidget: a
    :class:`NumberSlider`, a ``Dropdown``, a ``FloatText`` or a ``Checkbox``, each with a ``value``),
    ``figures`` (the ``FigureWidget`` objects), ``last_error`` (the message shown, or None), ``state`` (the
    last valid computation), ``accepted`` (the settings it was made for), ``timings`` (seconds spent in
    ``compute``, ``draw`` and sending the update, for the last change), ``redraws`` (figure updates sent so
    far). ``compute`` may be replaced (a test counts its calls).
    """

    def __init__(self, declaration: Panel, keep: bool = False):
        keep = check_flag(keep, "keep")
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

        kind = declaration.widget or declaration.name
        kept = self._keepable(_LATEST.get(kind)) if keep else {}
        self._set_quietly(kept)
        try:
            state = self._start(self.values())  # raises for an invalid start: nothing silently clamped
            kept = {}  # taken as they are
        except ScaraError:
            if not kept:
                raise
            self._set_quietly(declaration.defaults())  # kept settings refused: shown refused, below
            state = self._start(self.values())
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
        _LATEST[kind] = self
        if kept:
            with self.hold():
                for name, value in kept.items():
                    self.controls[name].value = value

    # ------------------------------------------------------------------------------------------------------
    def _keepable(self, previous) -> dict:
        """The accepted settings of the ``previous`` panel of this kind that this panel can take."""
        if previous is None:
            return {}
        out = {}
        for c in self.declaration.controls:
            if c.name not in previous.accepted:
                continue
            v = previous.accepted[c.name]
            if c.kind == "dropdown":
                ok = any(v == x and type(v) is type(x) for x in c.values)
            elif c.kind == "toggle":
                ok = isinstance(v, bool)
            else:
                ok = isinstance(v, (int, float)) and not isinstance(v, bool)
            if ok:
                out[c.name] = v
        return out

    def _set_quietly(self, settings: dict) -> None:
        """Set controls before the panel observes them (no computation)."""
        for name, value in settings.items():
            self.controls[name].value = value

    def _outside(self, values: dict) -> str | None:
        """The message of the first slider whose value lies outside its range (:func:`start_value`'s, the
        page panel's :func:`~scara.plots.panels.range_template`), or None."""
        for c in self.declaration.controls:
            if c.kind == "slider":
                try:
                    start_value(values[c.name], c.low, c.high, c.name, c.unit, c.limit)
                except ScaraError as exc:
                    return str(exc)
        return None

    def _start(self, values: dict):
        """The computation of the start ``values``: :class:`ScaraError` for a refused one."""
        outside = self._outside(values)
        if outside is not None:
            raise ScaraError(outside)
        state = self._compute(values)
        self.accepted = dict(values)
        return state

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
        """Recompute for the controls' values and redraw in place, or show why the setting is refused (a slider's
        value outside its range, or a setting the computation refuses)."""
        values = self.values()
        outside = self._outside(values)
        if outside is not None:
            self._refuse(outside)
            return
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
        self.accepted = dict(values)
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
    """``traj`` (a :class:`~scara.trajectory.Trajectory`); the last accepted plan of a waypoint editor
    (:func:`~scara.widgets.waypoint_editor`: its ``trajectory``); or the 70 s reference of chapter 3 when it is
    None; anything else raises :class:`ScaraError`."""
    from ..trajectory import Trajectory, reference_trajectory  # noqa: PLC0415 - built on demand
    from .trajectory import EditorState  # noqa: PLC0415 - it builds on this module

    if traj is None:
        return reference_trajectory(p=p)
    if isinstance(traj, EditorState):
        return traj.trajectory
    if not isinstance(traj, Trajectory):
        raise ScaraError(f"traj must be a Trajectory (from plan_path or reference_trajectory), a waypoint editor or "
                         f"None, got {type(traj).__name__} {traj!r:.80}")
    return traj
