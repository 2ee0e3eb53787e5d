"""The book's live panels declared as plain data, for any front end (ipywidgets in Jupyter, or a page that
recomputes the figures in the browser).

A panel (:class:`Panel`) is

* a table of controls (:class:`Control`): name, kind, range, step, scale, unit, default, label, and the
  choices of the panel's selector it applies to;
* one computation: ``compute(settings) -> state``, where ``settings`` is a dict keyed by the control names
  and ``state`` the plain data the figures and the table are drawn from; it raises
  :class:`~scara.errors.ScaraError` for a setting the package refuses;
* its figures as pairs (:class:`FigurePair`): a builder ``state -> go.Figure`` and an update
  ``state -> {"traces": {key: properties}, "title": str, "layout": {...}}`` whose trace keys are the traces'
  declared roles (or names), never their positions; :func:`apply_update` applies one to a figure's JSON;
* a summary ``state -> (rows, notes)``: the ``(label, value)`` rows of the table under the figures and the
  notes that flag a boundary case.

Nothing here imports ipywidgets: :mod:`scara.widgets` builds the Jupyter controls from these declarations.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

from ..errors import ScaraError, check_number

__all__ = ["Control", "FigurePair", "Panel", "KINDS", "SCALES", "start_value", "angle_control", "stroke_control",
           "apply_update", "rebuilt_update"]

#: the kinds of control: a slider, a dropdown of choices, a typed number, an on/off toggle
KINDS = ("slider", "dropdown", "number", "toggle")
#: the scales of a slider: ``step`` is in the control's unit on a linear slider, in decades on a log one
SCALES = ("linear", "log")


def start_value(value, lo: float, hi: float, name: str, unit: str = "", limit: str = "the panel's range") -> float:
    """A control's starting value, checked against the control's range ``[lo, hi]``: a value outside it, or
    one that is not a number (:func:`~scara.errors.check_number`), raises :class:`ScaraError` naming the value
    and the range (``limit`` says what the range is; a panel never silently clamps what it was given).

    >>> start_value(0.5, 0.0, 1.0, "d3", "m")
    0.5
    """
    v = check_number(value, name, unit=unit)
    if not (lo <= v <= hi):
        u = unit if unit == "°" else (f" {unit}" if unit else "")
        raise ScaraError(f"{name} = {v:g}{u} is outside {limit} {lo:g} to {hi:g}{u}")
    return v


@dataclass(frozen=True)
class Control:
    """One control of a panel.

    ``kind`` is one of :data:`KINDS`. A slider or a typed number has ``low``, ``high`` and ``step`` (a log
    slider's ``step`` is in decades); ``default`` must lie in ``[low, high]`` (``limit`` names that range in
    the message) or :class:`ScaraError` is raised: nothing is clamped. A dropdown has ``options``: values, or
    ``(label, value)`` pairs, and its ``default`` is one of the values. ``label`` is the text shown beside the
    control, ``unit`` the unit of its value, ``readout`` the format of a slider's readout. ``applies_to`` lists
    the values of the panel's selector (:attr:`Panel.selector`) the control is read for (None: always).
    """

    name: str
    kind: str
    label: str
    default: Any
    low: float | None = None
    high: float | None = None
    step: float | None = None
    scale: str = "linear"
    unit: str = ""
    options: tuple = ()
    readout: str | None = None
    applies_to: tuple | None = None
    limit: str = "the panel's range"

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ScaraError(f"control {self.name!r}: kind = {self.kind!r} must be one of {KINDS}")
        if self.scale not in SCALES:
            raise ScaraError(f"control {self.name!r}: scale = {self.scale!r} must be one of {SCALES}")
        if self.kind == "slider":
            object.__setattr__(self, "default", start_value(self.default, self.low, self.high, self.name, self.unit,
                                                            self.limit))
        elif self.kind == "dropdown" and self.default not in self.values:
            raise ScaraError(f"control {self.name!r}: default = {self.default!r} is not one of {self.values}")

    @property
    def values(self) -> tuple:
        """The values a dropdown offers (its options without their labels)."""
        return tuple(o[1] if isinstance(o, tuple) else o for o in self.options)


def angle_control(value_rad, name: str, label: str, applies_to=None) -> Control:
    """A slider in degrees over [-180°, 180°] (step 1°) starting at ``value_rad`` (rad), checked by
    :func:`start_value`."""
    deg = math.degrees(check_number(value_rad, name, unit="rad"))
    return Control(name, "slider", label, deg, -180.0, 180.0, 1.0, unit="°", applies_to=applies_to)


def stroke_control(d3, p) -> Control:
    """A slider over the quill's stroke ``p.d3_min`` to ``p.d3_max`` (m, step 0.01 m) starting at ``d3``."""
    return Control("d3", "slider", "d3 (m)", d3, p.d3_min, p.d3_max, 0.01, unit="m",
                   limit="the quill's stroke d3_min to d3_max =")


def rebuilt_update(fig) -> dict:
    """The update that turns any figure of the same builder into ``fig``: every trace's properties keyed by
    its name, the title and the layout (without the template, sent once with the first figure)."""
    js = fig.to_plotly_json()
    traces = {}
    for t in js["data"]:
        props = {k: v for k, v in t.items() if k != "type"}
        if t.get("name") in traces:
            raise ScaraError(f"two traces are named {t.get('name')!r}: declare the figure's roles")
        traces[t.get("name")] = props
    layout = {k: v for k, v in js["layout"].items() if k not in ("template", "title")}
    return dict(traces=traces, title=(js["layout"].get("title") or {}).get("text"), layout=layout)


@dataclass(frozen=True)
class FigurePair:
    """A panel's figure: ``build(state) -> go.Figure`` and ``update(state) -> dict`` (see
    :func:`apply_update`). ``roles`` names the builder's traces in order, for a figure whose trace names change
    with the state or repeat; without roles an update keys the traces by name. Without ``update`` the update
    is every trace of the rebuilt figure by name (:func:`rebuilt_update`)."""

    role: str
    build: Callable
    update: Callable | None = None
    roles: tuple = ()

    def updated(self, state) -> dict:
        """The update for ``state``."""
        return self.update(state) if self.update is not None else rebuilt_update(self.build(state))

    def index(self, fig_json: dict, key) -> int:
        """The position of the trace ``key`` (a role, or a name) in ``fig_json`` (plotly JSON of this builder)."""
        if self.roles:
            if key not in self.roles:
                raise KeyError(f"figure {self.role!r} has no trace role {key!r}; its roles are {self.roles}")
            return self.roles.index(key)
        for i, t in enumerate(fig_json["data"]):
            if t.get("name") == key:
                return i
        raise KeyError(f"figure {self.role!r} has no trace named {key!r}")


def _merged(old, new):
    """``new`` over ``old`` one level deep for dicts (a ``None`` value removes the property)."""
    if isinstance(old, dict) and isinstance(new, dict):
        out = dict(old)
        for k, v in new.items():
            if v is None:
                out.pop(k, None)
            else:
                out[k] = v
        return out
    return new


def apply_update(fig_json: dict, update: dict, pair: FigurePair) -> dict:
    """The figure ``fig_json`` (plotly JSON: ``{"data": [...], "layout": {...}}``) with ``update`` applied: a
    new dict, sharing no dict with ``fig_json``. ``update["traces"]`` maps a trace's role or name
    (:meth:`FigurePair.index`) to properties that replace its own; ``update["title"]`` is the title's text;
    ``update["layout"]`` maps layout properties to values (a dict value is merged into the property one level
    deep, ``None`` removes it)."""
    data = [dict(t) for t in fig_json["data"]]
    for key, props in (update.get("traces") or {}).items():
        i = pair.index(fig_json, key)
        data[i].update(props)
    layout = dict(fig_json["layout"])
    for k, v in (update.get("layout") or {}).items():
        if v is None:
            layout.pop(k, None)
        else:
            layout[k] = _merged(layout.get(k), v)
    if update.get("title") is not None:
        layout["title"] = dict(layout.get("title") or {}, text=update["title"])
    return {"data": data, "layout": layout}


@dataclass(frozen=True)
class Panel:
    """A live panel: its controls, its computation, its figures and its summary (see the module's docstring).

    ``explain(exc, settings) -> str`` words a refusal in the panel's units (default: the exception's text);
    ``react(name, settings) -> dict`` gives the controls a change of ``name`` sets in turn (e.g. the values of
    the waypoint a dropdown picked), the panel then computes once; ``selector`` is the control whose value the
    controls' ``applies_to`` refer to; ``columns`` is the number of controls per row.
    """

    name: str
    title: str
    controls: tuple
    compute: Callable
    figures: tuple
    summary: Callable | None = None
    explain: Callable | None = None
    react: Callable | None = None
    selector: str | None = None
    columns: int = 2

    def control(self, name: str) -> Control:
        """The control called ``name``."""
        for c in self.controls:
            if c.name == name:
                return c
        raise KeyError(f"panel {self.name!r} has no control {name!r}")

    def defaults(self) -> dict:
        """The settings the panel opens with."""
        return {c.name: c.default for c in self.controls}

    def applies(self, control: Control, settings: dict) -> bool:
        """Whether ``control`` is read for ``settings`` (its ``applies_to`` holds the selector's value)."""
        return control.applies_to is None or settings[self.selector] in control.applies_to
