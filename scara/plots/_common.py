"""Shared figure conventions: the book renderer, one colour, dash style and legend name per method or
controller, the joints' names and units, slider steps, and the little converters every builder uses to hand
its data to plotly. The page layout of the figures is :mod:`scara.plots.layout`."""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
import plotly.io as pio
from plotly.io._base_renderers import MimetypeRenderer

from ..errors import check_count

__all__ = [
    "PALETTE", "AXIS_COLOURS", "JOINT_COLOURS", "DASHES", "JOINT_NAMES", "JOINT_UNITS", "LOG_FLOOR", "METHOD_LABELS",
    "METHOD_DASHES", "CONTROLLER_LABELS", "CONTROLLER_DASHES", "run_name", "run_label", "run_colour", "run_dash",
    "thin", "envelope", "f32", "as_list", "slider", "use_book_renderer", "publish",
    "MAX_POINTS", "MAX_STEPS", "MAX_SWEEP", "MAX_GRID", "MAX_SLIDER_SAMPLES", "MAX_TARGETS", "FIGURE_BUDGET",
]

# Okabe-Ito colours: distinguishable with the common colour-vision deficiencies and, with the dash styles
# below, in greyscale. One colour per method or signal, the same across the whole book.
PALETTE = {
    "reference": "#000000",
    "inverse": "#0072B2",
    "transpose": "#D55E00",
    "pseudoinverse": "#009E73",
    "second_order": "#CC79A7",
    "robust": "#E69F00",
    "adaptive": "#56B4E9",
    "operational": "#009E73",
    "operational_noint": "#D55E00",
    "pd_gravity": "#999999",
    "independent": "#0072B2",
    "independent_pd": "#CC79A7",
    "pd_plus_gravity": "#999999",
    "computed_torque": "#8C510A",
    "velocity": "#0072B2",
    "force": "#D55E00",
    "arm": "#4D4D4D",
}
#: colours of the x, y, z, phi components (and of joints 1..4)
AXIS_COLOURS = ("#0072B2", "#D55E00", "#009E73", "#CC79A7")
JOINT_COLOURS = AXIS_COLOURS
DASHES = ("solid", "dash", "dot", "dashdot")
#: names of the joint variables, in the order of ``q``
JOINT_NAMES = ("θ1", "θ2", "d3", "θ4")
#: generalised-force unit of each joint
JOINT_UNITS = ("N m", "N m", "N", "N m")
#: log axes: values below this (exact zeros) are drawn at the floor (the page programs' own, one number)
from ..programs.thinning import LOG_FLOOR  # noqa: E402

#: legend names of the CLIK methods of chapter 4 (keys: ``ClikResult.method``, also keys of ``PALETTE``)
METHOD_LABELS = {
    "inverse": "Jacobian inverse",
    "transpose": "Jacobian transpose",
    "pseudoinverse": "pseudo-inverse",
    "second_order": "second order",
}
#: one dash style per method, so that the curves stay apart in greyscale (colours: ``PALETTE``)
METHOD_DASHES = {"inverse": "solid", "transpose": "dash", "pseudoinverse": "dot", "second_order": "dashdot"}
#: legend names of the controllers of chapter 6 (keys: ``SimulationResult.controller``, also keys of ``PALETTE``)
CONTROLLER_LABELS = {
    "robust": "robust",
    "adaptive": "adaptive (Slotine-Li)",
    "operational": "operational ID + integral",
    "operational_noint": "operational ID, no integral",
    "pd_gravity": "PD + gravity",
    "independent": "independent joint PID",
    "independent_pd": "independent joint PD",
    "pd_plus_gravity": "PD + gravity compensation",
    "computed_torque": "computed torque",
}
#: one dash style per controller (colours: ``PALETTE``), so that the curves stay apart in greyscale
CONTROLLER_DASHES = {"robust": "solid", "adaptive": "dash", "operational": "dot", "operational_noint": "dashdot",
                     "pd_gravity": "longdash", "independent": "longdashdot",
                     "independent_pd": "8px,3px,2px,3px,2px,3px", "pd_plus_gravity": "longdash",
                     "computed_torque": "12px,3px,3px,3px"}


def run_name(r) -> str:
    """The method of a CLIK run (``ClikResult.method``) or the controller of a simulation
    (``SimulationResult.controller``): the key of its colour, dash style and legend name. ``r`` may also be
    that name itself, for a curve drawn without its run."""
    if isinstance(r, str):
        return r
    method = getattr(r, "method", None)
    if isinstance(method, str):
        return method
    return getattr(r, "controller", "") or "controller"


def run_label(r) -> str:
    """The legend name of a run; a pseudo-inverse run also names its relaxed component."""
    name = run_name(r)
    if name == "pseudoinverse" and not isinstance(r, str):
        return f"pseudo-inverse ({r.gains.get('relaxed', 'x')} relaxed)"
    return METHOD_LABELS.get(name) or CONTROLLER_LABELS.get(name, name)


def run_colour(r) -> str:
    """The colour of a run's method or controller (black for one the palette does not know)."""
    return PALETTE.get(run_name(r), PALETTE["reference"])


def run_dash(r) -> str:
    """The dash style of a run's method or controller (solid for one without its own)."""
    name = run_name(r)
    return METHOD_DASHES.get(name) or CONTROLLER_DASHES.get(name, "solid")


# Upper limits on the work a figure builder may be asked for, checked before any work
# (:func:`scara.errors.check_count`).
# They keep a figure under a few MB of page and about a second of work; each builder's docstring names its own.
#: samples per curve (a float32 curve of 10 000 points weighs about 0.2 MB in the page)
MAX_POINTS = 10_000
#: slider steps or animation frames of one figure (each step carries its own copy of the data it changes)
MAX_STEPS = 121
#: samples of a sweep that computes at each sample (ellipses, for instance)
MAX_SWEEP = 2001
#: grid points per side of a map (301 x 301 = 90 601 cells, about 0.6 MB)
MAX_GRID = 301
#: samples per curve times slider steps, for a slider whose every step carries its own curves (about 2 MB)
MAX_SLIDER_SAMPLES = 100_000
#: arms, targets or configurations drawn at once in one figure
MAX_TARGETS = 200
#: why the limits above exist (the ``why`` of :func:`~scara.errors.check_count` for a figure's counts)
FIGURE_BUDGET = "a figure stays under a few MB and about a second of work"


def thin(n: int, points: int = 1000) -> np.ndarray:
    """Indices of about ``points`` evenly spaced samples out of ``n`` (first and last included). ``points`` is a
    whole number from 1 to ``MAX_POINTS`` (:func:`~scara.errors.check_count`)."""
    points = check_count(points, "points", 1, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    if n <= points:
        return np.arange(n)
    return np.unique(np.linspace(0, n - 1, points).round().astype(int))


def envelope(t, y, points: int = 1000):
    """``(t_k, max |y|)`` over about ``points`` consecutive blocks of the series ``y`` (N,): an upper envelope
    that keeps every peak when a long run is thinned for plotting. Values are floored at 1e-12 for log axes.
    ``points`` is a whole number from 1 to ``MAX_POINTS`` (:func:`~scara.errors.check_count`)."""
    points = check_count(points, "points", 1, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    t = np.asarray(t)
    y = np.abs(np.asarray(y, dtype=float))
    n = len(t)
    if n <= points:
        return t, np.maximum(y, LOG_FLOOR)
    size = int(math.ceil(n / points))
    m = n // size
    head = y[: m * size].reshape(m, size).max(axis=1)
    tt = t[: m * size : size] + 0.5 * size * (t[1] - t[0])
    if m * size < n:
        head = np.append(head, y[m * size:].max())
        tt = np.append(tt, t[-1])
    return tt, np.maximum(head, LOG_FLOOR)


def f32(a) -> np.ndarray:
    """Plot data as float32: half the page weight, 7 significant digits (ample for a curve on screen)."""
    return np.asarray(a, dtype=np.float32)


def as_list(values, digits: int = 4) -> list:
    """A plain list for plotly (NaN becomes ``None``, a gap in a line), rounded to keep pages light."""
    return [None if not np.isfinite(v) else round(float(v), digits) for v in np.ravel(values)]


class _BookHtmlRenderer(MimetypeRenderer):
    """Returns ``text/html`` that needs ``plotly.min.js`` already loaded by the page (offline book)."""

    def to_mimebundle(self, fig_dict):
        html = pio.to_html(fig_dict, include_plotlyjs=False, include_mathjax=False, full_html=False,
                           auto_play=False, validate=False, config={"displaylogo": False, "responsive": True})
        return {"text/html": html}


def use_book_renderer() -> None:
    """Register the ``scara_book`` renderer and make ``plotly_mimetype+scara_book`` the default.

    JupyterLab keeps its native plotly view (the JSON bundle); the static book uses the HTML bundle, whose
    ``plotly.min.js`` the book serves itself (see ``_ext/offline_assets.py``).
    """
    pio.renderers["scara_book"] = _BookHtmlRenderer()
    pio.renderers.default = "plotly_mimetype+scara_book"
    _plain_numpy_scalars()


def _plain_numpy_scalars() -> None:
    """Show numpy scalars as plain numbers (``22.5``, not ``np.float64(22.5)``) in IPython, so that numbers
    glued into the text with :func:`scara.book.glue` can be formatted (``{glue:text}`name:.3f```)."""
    try:
        from IPython import get_ipython
    except ImportError:  # pragma: no cover
        return
    ip = get_ipython()
    if ip is None:
        return
    import numpy as np

    fmt = ip.display_formatter.formatters["text/plain"]
    fmt.for_type(np.floating, lambda obj, pp, cycle: pp.text(repr(float(obj))))
    fmt.for_type(np.integer, lambda obj, pp, cycle: pp.text(repr(int(obj))))
    fmt.for_type(np.bool_, lambda obj, pp, cycle: pp.text(repr(bool(obj))))


def slider(steps: list[dict], prefix: str, active: int = 0, pad_top: int = 40) -> dict:
    """A plotly slider from a list of ``{"label": str, "method": ..., "args": [...]}`` steps."""
    return dict(
        active=active,
        currentvalue=dict(prefix=prefix, font=dict(size=13)),
        pad=dict(t=pad_top, b=10),
        steps=[dict(label=s["label"], method=s.get("method", "update"), args=s["args"]) for s in steps],
    )


class _FigureBundle:
    """Wraps a figure so that myst-nb's ``glue`` stores its mime bundle (a plotly figure displays itself
    through ``_ipython_display_``, which glue cannot capture)."""

    def __init__(self, fig: go.Figure):
        self.fig = fig

    def _repr_mimebundle_(self, include=None, exclude=None):
        return pio.renderers._build_mime_bundle(self.fig.to_dict(), renderers_string=pio.renderers.default)


def publish(fig: go.Figure, name: str) -> None:
    """Show ``fig`` under its cell and glue it as ``name`` for a numbered, captioned figure in the book.

    In the notebook the figure appears under the cell as usual (JupyterLab). In the book the cell carries
    the tag ``remove-output`` and a markdown cell places the figure with its caption and label::

        ```{glue:figure} fig-arm
        :name: fig-arm

        The arm at q = 0, with its DH frames.
        ```

    so that ``{numref}`fig-arm``` refers to it from any chapter.
    """
    from ..book import glue

    glue(name, _FigureBundle(fig), display=True)
