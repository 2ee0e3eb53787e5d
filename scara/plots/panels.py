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
           "apply_update", "rebuilt_update", "range_template", "set_path", "PageProgram", "Pick", "Text", "Flag",
           "program_panel"]

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
        raise ScaraError(range_template(name, lo, hi, unit, limit).format(value=v))
    return v


def range_template(name: str, lo: float, hi: float, unit: str = "", limit: str = "the panel's range") -> str:
    """The message of a value outside ``[lo, hi]``, with ``{value:g}`` where the value goes: the one wording of
    :func:`start_value` and of the page panel's check of a typed value."""
    u = unit if unit == "°" else (f" {unit}" if unit else "")
    return f"{name} = {{value:g}}{u} is outside {limit} {lo:g} to {hi:g}{u}"


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
    # 12 significant digits: the degrees of radians(60) read 60, not 59.99999999999999 (radians(60.0) is the same
    # float as pi / 3, so the configuration drawn does not change)
    deg = float(f"{math.degrees(check_number(value_rad, name, unit='rad')):.12g}")
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
    for path, value in (update.get("paths") or {}).items():
        layout = set_path(layout, path, value)
    return {"data": data, "layout": layout}


def set_path(tree: dict, path: str, value):
    """``tree`` with the entry at the dotted ``path`` (``"xaxis.range"``, ``"annotations.2.text"``: a number
    indexes a list) set to ``value``: a new dict, copying the dicts and lists on the path and sharing the rest.
    A missing dict on the path is created; a missing list entry raises ``KeyError`` naming the path."""
    head, _, rest = path.partition(".")
    if isinstance(tree, list):
        i = int(head)
        if not 0 <= i < len(tree):
            raise KeyError(f"layout path {path!r}: no entry {i} in a list of {len(tree)}")
        out = list(tree)
        out[i] = set_path(out[i], rest, value) if rest else value
        return out
    out = dict(tree or {})
    out[head] = set_path(out.get(head) if out.get(head) is not None else {}, rest, value) if rest else value
    return out


@dataclass(frozen=True)
class Panel:
    """A live panel: its controls, its computation, its figures and its summary (see the module's docstring).

    ``explain(exc, settings) -> str`` words a refusal in the panel's units (default: the exception's text);
    ``react(name, settings) -> dict`` gives the controls a change of ``name`` sets in turn (e.g. the values of
    the waypoint a dropdown picked), the panel then computes once; ``selector`` is the control whose value the
    controls' ``applies_to`` refer to; ``columns`` is the number of controls per row. ``widget`` names the
    :mod:`scara.widgets` function that builds the panel, and ``page`` is its :class:`PageProgram` when the
    panel also runs in the book's pages (:func:`program_panel` makes such a panel).
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
    widget: str | None = None
    page: PageProgram | None = None

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


# --------------------------------------------------------------------------------------------------
# the page program: one compiled computation of a panel's move, run by numba here and, translated, in the page
# --------------------------------------------------------------------------------------------------
import re as _re  # noqa: E402

import numpy as _np  # noqa: E402

#: a template's field: ``{name:spec}`` with a format spec of Python's mini-language limited to what the page's
#: formatter implements the same way (sign, width, precision and one of ``f g e %``); ``{name}`` is a setting
#: given as text (a dropdown's value)
_FIELD = _re.compile(r"\{([A-Za-z_][A-Za-z0-9_]*)(?::([^{}]*))?\}")
_SPEC = _re.compile(r"^([+ ])?(\d+)?(?:\.(\d+))?([fge%])$")


@dataclass(frozen=True)
class Text:
    """A string made from a panel's values: ``template`` in Python's ``str.format`` syntax, every field named
    (an output of the program or a control) and, for a number, a format spec of sign, width, precision and one
    of ``f g e %`` (``{w:.4f}``). The page formats it the same way (its formatter implements exactly these)."""

    template: str

    def __post_init__(self):
        for name, spec in _FIELD.findall(self.template):
            if spec and not _SPEC.match(spec):
                raise ScaraError(f"template {self.template!r}: the format spec {spec!r} of {name!r} is not one the "
                                 "page formats (sign, width, precision and one of f g e %)")

    @property
    def names(self) -> tuple:
        return tuple(n for n, _ in _FIELD.findall(self.template))

    def format(self, values: dict) -> str:
        for name, spec in _FIELD.findall(self.template):
            if not spec and not isinstance(values[name], str):
                raise ScaraError(f"template {self.template!r}: the number {name!r} needs a format spec")
        return self.template.format(**values)


@dataclass(frozen=True)
class Flag:
    """A boolean made from a program's output: true when ``field`` (one number) is not 0."""

    field: str


@dataclass(frozen=True)
class Pick:
    """A control's new value read from a program's data when another control changes (:attr:`PageProgram.react`):
    the number at ``offset + stride * settings[index]`` (``index`` names a dropdown whose values are indices),
    as it is (``as_="value"``), as whether it is above 0 (``"flag"``), or only when it is above 0
    (``"positive"``: the control is left alone otherwise)."""

    offset: int
    stride: int
    index: str
    as_: str = "value"


@dataclass(frozen=True)
class PageProgram:
    """The computation of a panel's move as one compiled kernel, with how its outputs are drawn.

    ``kernel(inputs, data, out) -> int`` is a :func:`~scara._compile.kernel` in the subset the page's
    translator takes (:mod:`scara.page`): ``inputs`` holds the controls named in :attr:`inputs`, in order (a
    slider or a typed number as its value, a dropdown as the index of its value in the control's ``values``, a
    toggle as 0 or 1); ``data`` the panel's fixed numbers (the robot, the path: :attr:`data`, made once in
    Python); ``out`` the fields of :attr:`outputs`. It returns 0 for a setting it draws, or the key of
    :attr:`refusals` whose message says why not (formatted with the outputs it wrote). ``out`` starts zeroed.

    The drawing is data: :attr:`traces` maps a figure's role to ``{trace key: {property: binding}}``,
    :attr:`paths` a figure's role to ``{dotted layout path: binding}`` (``"xaxis.range"``,
    ``"annotations.2.text"``), :attr:`titles` a figure's role to a :class:`Text`. A binding is the name of an
    output field (one number, or its numbers as an array), a :class:`Text`, a :class:`Flag` or a tuple of
    bindings (a list). :attr:`rows` are the summary's ``(label, Text)`` rows and :attr:`notes` its ``(Flag,
    Text)`` notes. Both front ends draw from these: the same properties set to the same numbers.

    Data too long for a page (a sampled 70 s path) is given in a compact form: ``prepare(compact, data) -> int``,
    a kernel, writes the data (``data`` is then its size) from ``compact`` (a planned path's vector), here once
    and in the page once, where only ``compact`` travels.

    A panel whose moves build on each other (the waypoint editor: each accepted edit is the plan the next one
    starts from) names in ``carry = (field, offset)`` an output written into ``data`` at ``offset`` after every
    accepted move, and in ``react`` the controls a change sets from the data: ``{control: {other control:
    Pick}}`` (pick a waypoint, its sliders show its values). Both front ends do both, from these declarations.

    A program that needs large work arrays on every move (a 70 s run's series) names their size in ``scratch``:
    both front ends append that many entries to the data, once, and the program finds them after its data (its
    own offsets), overwrites them in every move and reads none it has not written in that move. :attr:`data`
    stays the data alone, which is all that is sent to the page, and a move allocates nothing large.

    ``drag = {"figure": role, "pick": control, "x": control, "y": control}`` lets the page's reader drag, on
    the figure of that role, the points ``pick`` chooses among (their positions read from the data by the
    ``react`` picks of ``pick`` for ``x`` and ``y``): dragging one picks it and sets ``x`` and ``y`` to the
    pointer's place, rounded to the sliders' steps, one move per pointer move. Only the page does this.
    """

    kernel: Callable
    inputs: tuple
    data: Any
    outputs: Any
    refusals: dict
    traces: dict
    paths: dict = None
    titles: dict = None
    rows: tuple = ()
    notes: tuple = ()
    prepare: Callable | None = None
    compact: Any = None
    carry: tuple | None = None
    react: dict = None
    drag: dict | None = None
    scratch: int = 0

    def __post_init__(self):
        if self.drag is not None:
            if set(self.drag) != {"figure", "pick", "x", "y"}:
                raise ScaraError(f"drag must name figure, pick, x and y; got {sorted(self.drag)}")
            picks = (self.react or {}).get(self.drag["pick"], {})
            missing = [k for k in ("x", "y") if self.drag[k] not in picks]
            if missing:
                raise ScaraError(f"drag: the points picked by {self.drag['pick']!r} have no react pick for "
                                 f"{[self.drag[k] for k in missing]}, so their positions cannot be read")
            if self.drag["figure"] not in self.traces:
                raise ScaraError(f"drag: no figure {self.drag['figure']!r}; the program draws {sorted(self.traces)}")
        if self.carry is not None and self.prepare is not None:
            raise ScaraError("a program with a prepared data cannot carry an output into it")
        object.__setattr__(self, "react", dict(self.react or {}))
        if self.prepare is not None and _np.ndim(self.data) == 0:
            # the data made from a compact form by a kernel, which the page runs once on the same compact form
            compact = _np.array(self.compact, dtype=_np.float64).ravel()
            full = _np.zeros(int(self.data))
            status = int(self.prepare(compact, full))
            if status != 0:
                raise ScaraError(f"{getattr(self.prepare, '__name__', self.prepare)} refused its compact data "
                                 f"(status {status})")
            object.__setattr__(self, "compact", compact)
            object.__setattr__(self, "data", full)
        if not (isinstance(self.scratch, int) and not isinstance(self.scratch, bool) and self.scratch >= 0):
            raise ScaraError(f"scratch must be a count of entries (an int >= 0), got {self.scratch!r}")
        if self.scratch and self.carry is not None:
            raise ScaraError("a program that carries an output into its data cannot have a scratch (the page "
                             "sends its data again after every move)")
        object.__setattr__(self, "data", _np.array(self.data, dtype=_np.float64).ravel())
        # what the kernel is given: the data itself, or a copy followed by the scratch
        object.__setattr__(self, "_given", self.data if not self.scratch else
                           _np.concatenate([self.data, _np.zeros(self.scratch)]))
        object.__setattr__(self, "paths", dict(self.paths or {}))
        object.__setattr__(self, "titles", dict(self.titles or {}))
        fields = set(self.outputs.names) | set(self.inputs)
        for t in self._texts():
            unknown = [n for n in t.names if n not in fields]
            if unknown:
                raise ScaraError(f"template {t.template!r} names {unknown}, which are neither outputs "
                                 f"{self.outputs.names} nor controls {self.inputs}")
        for b in self._fields():
            if b not in self.outputs.names:
                raise ScaraError(f"binding {b!r} is not an output of the program; its outputs are {self.outputs.names}")

    def _bindings(self):
        for props in self.traces.values():
            for tr in props.values():
                yield from tr.values()
        for paths in self.paths.values():
            yield from paths.values()
        yield from self.titles.values()
        for _, t in self.rows:
            yield t
        for f, t in self.notes:
            yield f
            yield t
        yield from self.refusals.values()

    def _walk(self, b):
        if isinstance(b, tuple):
            for x in b:
                yield from self._walk(x)
        else:
            yield b

    def _texts(self):
        return [x for b in self._bindings() for x in self._walk(b) if isinstance(x, Text)]

    def _fields(self):
        out = []
        for b in self._bindings():
            for x in self._walk(b):
                if isinstance(x, str):
                    out.append(x)
                elif isinstance(x, Flag):
                    out.append(x.field)
        return out

    def pack(self, settings: dict, controls) -> "_np.ndarray":
        """The ``inputs`` vector of ``settings`` (see the class's docstring); ``controls`` maps a name to its
        :class:`Control`."""
        vec = _np.empty(len(self.inputs))
        for i, name in enumerate(self.inputs):
            c, v = controls[name], settings[name]
            if c.kind == "dropdown":
                vec[i] = c.values.index(v)
            elif c.kind == "toggle":
                vec[i] = 1.0 if v else 0.0
            else:
                vec[i] = check_number(v, name, unit=c.unit)
        return vec

    def run(self, settings: dict, controls) -> dict:
        """Run the kernel for ``settings``: the outputs by field (one number as a float, more as a new array) with
        the settings, or :class:`ScaraError` with the refusal's message."""
        from ..book import wait_compiled  # noqa: PLC0415

        wait_compiled(self.kernel)  # a take-home chapter may be compiling it in the background (compile_ahead)
        out = _np.zeros(self.outputs.size)
        status = int(self.kernel(self.pack(settings, controls), self._given, out))
        values = self.values(out, settings)
        if status != 0:
            if status not in self.refusals:
                raise ScaraError(f"the panel's program returned status {status}, which it does not declare")
            raise ScaraError(self.refusals[status].format(values))
        return values

    def carried(self, values: dict) -> None:
        """After an accepted move: the :attr:`carry` output written into :attr:`data`."""
        if self.carry is not None:
            field, offset = self.carry
            v = _np.atleast_1d(values[field])
            self.data[int(offset):int(offset) + v.size] = v

    def reacted(self, name: str, settings: dict) -> dict:
        """The controls a change of ``name`` sets (:attr:`react`), read from :attr:`data`."""
        out = {}
        for target, k in self.react.get(name, {}).items():
            v = float(self.data[k.offset + k.stride * int(settings[k.index])])
            if k.as_ == "flag":
                out[target] = v > 0
            elif k.as_ == "value" or v > 0:
                out[target] = v
        return out

    def values(self, out, settings: dict) -> dict:
        """The outputs of ``out`` by field (one number as a float, more as an array) with the settings."""
        values = dict(settings)
        for name, start in zip(self.outputs.names, self.outputs.offsets):
            n = self.outputs.sizes[name]
            values[name] = float(out[start]) if n == 1 else _np.array(out[start:start + n])
        return values

    def bound(self, b, values):
        """The value of the binding ``b`` for ``values`` (see the class's docstring)."""
        if isinstance(b, tuple):
            return [self.bound(x, values) for x in b]
        if isinstance(b, Text):
            return b.format(values)
        if isinstance(b, Flag):
            return bool(values[b.field] != 0)
        return values[b]

    def update(self, role: str, values: dict) -> dict:
        """The update (see :func:`apply_update`) of the figure ``role`` for ``values``."""
        traces = {key: {prop: self.bound(b, values) for prop, b in props.items()}
                  for key, props in self.traces.get(role, {}).items()}
        paths = {path: self.bound(b, values) for path, b in self.paths.get(role, {}).items()}
        title = self.titles.get(role)
        return dict(traces=traces, paths=paths, title=None if title is None else title.format(values))

    def summary(self, values: dict):
        """The summary's rows and notes for ``values``."""
        rows = [(label, t.format(values)) for label, t in self.rows]
        notes = [t.format(values) for f, t in self.notes if values[f.field] != 0]
        return rows, notes

    def describe(self, panel) -> dict:
        """The program as JSON-ready data for the page: everything but the kernel (named by the page's engine)."""

        def enc(b):
            if isinstance(b, tuple):
                return {"list": [enc(x) for x in b]}
            if isinstance(b, Text):
                return {"text": b.template}
            if isinstance(b, Flag):
                return {"flag": b.field}
            return {"field": b}

        controls = {c.name: c for c in panel.controls}
        return dict(
            kernel=getattr(self.kernel, "__name__", str(self.kernel)),
            inputs=[dict(name=n, kind=controls[n].kind, values=list(controls[n].values)) for n in self.inputs],
            # the data as the bytes of its float64s (base64): exact, NaN included, and short
            data=_b64((self.compact if self.prepare is not None else self.data)),
            prepare=None if self.prepare is None else getattr(self.prepare, "__name__", str(self.prepare)),
            data_size=int(self.data.size),
            scratch=int(self.scratch),
            carry=None if self.carry is None else dict(field=self.carry[0], offset=int(self.carry[1])),
            drag=None if self.drag is None else dict(self.drag),
            react={name: {target: dict(offset=int(k.offset), stride=int(k.stride), index=k.index, as_=k.as_)
                          for target, k in picks.items()} for name, picks in self.react.items()},
            outputs=[dict(name=n, offset=o, size=self.outputs.sizes[n])
                     for n, o in zip(self.outputs.names, self.outputs.offsets)],
            size=self.outputs.size,
            refusals={str(k): v.template for k, v in self.refusals.items()},
            traces={role: {key: {prop: enc(b) for prop, b in props.items()} for key, props in tr.items()}
                    for role, tr in self.traces.items()},
            paths={role: {path: enc(b) for path, b in ps.items()} for role, ps in self.paths.items()},
            titles={role: t.template for role, t in self.titles.items()},
            rows=[[label, t.template] for label, t in self.rows],
            notes=[[f.field, t.template] for f, t in self.notes])


def _b64(a) -> dict:
    import base64  # noqa: PLC0415

    a = _np.ascontiguousarray(a, dtype="<f8")
    return {"float64": base64.b64encode(a.tobytes()).decode("ascii")}


def program_panel(name: str, title: str, controls: tuple, program: PageProgram, builders: dict, widget: str,
                  explain: Callable | None = None, react: Callable | None = None, selector: str | None = None,
                  columns: int = 2, roles: dict | None = None) -> Panel:
    """A :class:`Panel` whose every move is ``program``: ``compute`` runs its kernel (:meth:`PageProgram.run`),
    each figure of ``builders`` (role -> ``values -> go.Figure``, in the panel's order) is updated by the
    program's bindings (:meth:`PageProgram.update`), the summary is the program's rows and notes. ``roles``
    gives a figure's trace roles (see :class:`FigurePair`) where the trace keys are not the traces' names."""
    by_name = {c.name: c for c in controls}
    roles = roles or {}
    figures = tuple(FigurePair(role, build, (lambda values, role=role: program.update(role, values)),
                               tuple(roles.get(role, ()))) for role, build in builders.items())

    def compute(settings):
        values = program.run(settings, by_name)
        program.carried(values)
        return values

    if react is None and program.react:
        react = program.reacted
    return Panel(name, title, controls, compute, figures, program.summary, explain, react, selector, columns, widget,
                 program)
