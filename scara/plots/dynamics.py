"""Figures of chapter 5 (dynamics): where the joint torques go along the reference motion, the torque needed
with and without payload (static slider over the payload mass), the energy of the free arm with its balance,
and the inertia matrix at a configuration. Data in, figure out: the numbers come from :mod:`scara.dynamics`
and :mod:`scara.simulate`."""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..dynamics import TORQUE_TERMS, inertia
from ..errors import ScaraError, as_vector, check_count
from ._common import DASHES, JOINT_COLOURS, JOINT_UNITS, LOG_FLOOR, f32, slider, thin
from ._common import MAX_POINTS, MAX_SLIDER_SAMPLES, MAX_STEPS, MAX_SWEEP, FIGURE_BUDGET
from .panels import Text
from .layout import finish_layout, stacked_axes
from ..params import ScaraParams
from ..programs.dynamics import B_FIELDS, inertia_values

__all__ = [
    "TERM_COLOURS", "TERM_LABELS", "TERM_DASHES", "TERM_PATTERNS", "JOINT_UNITS", "torque_share_figure",
    "torque_terms_figure", "payload_torque_figure", "payload_slider_figure", "energy_figure", "window_max",
    "inertia_figure", "inertia_slider_figure", "inertia_panel_figure", "INERTIA_TRACES", "INERTIA_TITLE",
]

#: one colour per torque term (Okabe-Ito), the same in every figure of the chapter
TERM_COLOURS = {"links": "#0072B2", "rotors": "#E69F00", "payload": "#D55E00", "coriolis": "#CC79A7",
                "friction": "#009E73", "gravity": "#000000"}
#: legend names of the terms, short enough for a phone-width legend (the captions say what each one holds: link
#: and quill inertia, rotor inertia with its coupling, the payload's share, Coriolis and centrifugal terms, viscous
#: friction, the quill's weight)
TERM_LABELS = {"links": "link inertia", "rotors": "rotors", "payload": "payload", "coriolis": "Coriolis",
               "friction": "friction", "gravity": "gravity"}
_JOINT_NAMES = ("joint 1 (θ1)", "joint 2 (θ2)", "joint 3 (d3)", "joint 4 (θ4)")
_JOINT_SHORT = ("joint 1", "joint 2", "joint 3", "joint 4")
#: a dash style and a bar hatch per term, so that the terms stay apart in greyscale
TERM_DASHES = {"links": "solid", "rotors": "dash", "payload": "dot", "coriolis": "dashdot", "friction": "longdash",
               "gravity": "solid"}
TERM_PATTERNS = {"links": "", "rotors": "/", "payload": ".", "coriolis": "x", "friction": "-", "gravity": ""}


def _rms(a):
    return np.sqrt(np.mean(np.asarray(a) ** 2, axis=0))


def torque_share_figure(breakdown: dict, title: str = "Where the joint torque goes",
                        payload_label: str | None = None, height: int = 480) -> go.Figure:
    """Stacked bars, one per joint: the share of each term's RMS value in the sum of the terms' RMS values (%),
    with the RMS itself (N m or N) in the hover. ``breakdown`` is :func:`scara.dynamics.torque_breakdown`.
    Each term has its colour and a hatch pattern, so the stack also reads in greyscale."""
    rms = {k: _rms(breakdown[k]) for k in TORQUE_TERMS}
    total = sum(rms.values())
    total = np.where(total > 0, total, 1.0)
    fig = go.Figure()
    for k in TORQUE_TERMS:
        label = TERM_LABELS[k] if k != "payload" or payload_label is None else payload_label
        fig.add_bar(x=list(_JOINT_SHORT), y=100 * rms[k] / total, name=label, marker_color=TERM_COLOURS[k],
                    marker_pattern_shape=TERM_PATTERNS[k], marker_pattern_fgcolor="#FFFFFF",
                    customdata=np.column_stack([rms[k], list(JOINT_UNITS)]),
                    hovertemplate="%{x}<br>" + label + ": %{y:.2f} % (RMS %{customdata[0]:.3g} %{customdata[1]})"
                                  "<extra></extra>")
    finish_layout(fig, title, height, barmode="stack")
    fig.update_yaxes(title_text="share of summed RMS torques (%)", range=[0, 100])
    fig.update_xaxes(title_text="joint")
    return fig


def torque_terms_figure(t, breakdown: dict, target: int = 1500,
                        title: str = "Torque terms", height: int = 500) -> go.Figure:
    """Every term of :func:`~scara.dynamics.torque_breakdown` against time (decimated), for one joint at a
    time: a dropdown (works on a static page) picks the joint, joint 1 first. Each term keeps its colour and
    gets its own dash style.

    Limits: ``target`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    target = check_count(target, "target", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    t = np.asarray(t)
    idx = thin(len(t), target)
    fig = go.Figure()
    n_terms = len(TORQUE_TERMS)
    for j in range(4):
        for n, k in enumerate(TORQUE_TERMS):
            y = np.asarray(breakdown[k])[idx, j]
            fig.add_scatter(x=f32(t[idx]), y=f32(y), mode="lines", name=TERM_LABELS[k], legendgroup=k,
                            visible=(j == 0), line=dict(color=TERM_COLOURS[k], width=1.8, dash=TERM_DASHES[k]))
    groups = [list(range(j * n_terms, (j + 1) * n_terms)) for j in range(4)]
    # the title says which joint the dropdown shows
    menu = [(_JOINT_NAMES[j], f"{title}: {_JOINT_NAMES[j]}", {"yaxis.title.text": f"{_JOINT_SHORT[j]} ({JOINT_UNITS[j]})"})
            for j in range(4)]
    finish_layout(fig, menu[0][1], height, groups=groups, menu=menu)
    fig.update_xaxes(title_text="t (s)")
    fig.update_yaxes(title_text=f"{_JOINT_SHORT[0]} ({JOINT_UNITS[0]})")
    return fig


def payload_torque_figure(t, torques: dict, target: int = 1500,
                          title: str = "Torque to follow the reference",
                          height: int = 520) -> go.Figure:
    """Torques of several cases (``torques`` maps a label, e.g. ``"no payload"``, ``"5 kg"``, to an (N, 4)
    series): the revolute joints 1, 2, 4 on top (N m, colour per joint), the quill's force below (N); one dash
    style per case.

    Limits: ``target`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    target = check_count(target, "target", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    t = np.asarray(t)
    idx = thin(len(t), target)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08, row_heights=[0.55, 0.45])
    for c, (label, tau) in enumerate(torques.items()):
        tau = np.asarray(tau)
        for j in range(4):
            fig.add_scatter(x=f32(t[idx]), y=f32(tau[idx, j]), mode="lines", name=f"τ{j + 1}, {label}",
                            legendgroup=label, line=dict(color=JOINT_COLOURS[j], dash=DASHES[c % 4], width=1.6),
                            row=2 if j == 2 else 1, col=1)
    stacked_axes(fig, ("τ1, τ2, τ4 (N m)", "τ3 (N)"))
    return finish_layout(fig, title, height)


def payload_slider_figure(t, torques_by_mass: dict, target: int = 500,
                          title: str = "Joint torques (inverse dynamics)", height: int = 560,
                          baseline: float | None = None, active: int | None = None) -> go.Figure:
    """Static slider figure: ``torques_by_mass`` maps payload masses (kg) to (N, 4) torque series; one slider
    step per mass restyles the four torque traces (revolute joints 1, 2, 4 on top in N m, the quill's force
    below in N) and the title. The torques of the ``baseline`` mass (default: the first) stay drawn as thin
    grey lines for comparison. ``active`` is the index of the mass shown first (default 0). Works in the HTML
    with no kernel.

    Limits: ``target`` from 2 to 10 000 samples per curve (``MAX_POINTS``), at most 121 masses (``MAX_STEPS``)
    and at most 100 000 samples per curve in all the steps together (masses × ``target``,
    ``MAX_SLIDER_SAMPLES``); a value outside, or not a whole number, raises :class:`ScaraError` before any work."""
    target = check_count(target, "target", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    if not isinstance(torques_by_mass, dict) or not torques_by_mass:
        raise ScaraError("torques_by_mass must be a non-empty dict {payload mass (kg): (N, 4) torques}, "
                         f"got {torques_by_mass!r:.80}")
    check_count(len(torques_by_mass), "len(torques_by_mass)", 1, MAX_STEPS, "payload masses (slider steps)", FIGURE_BUDGET)
    check_count(len(torques_by_mass) * target, f"{len(torques_by_mass)} masses × target {target}", 1, MAX_SLIDER_SAMPLES, "samples per curve in all the slider steps", FIGURE_BUDGET)
    t = np.asarray(t)
    idx = thin(len(t), target)
    masses = list(torques_by_mass)
    active = 0 if active is None else int(active)
    if not 0 <= active < len(masses):
        raise ScaraError(f"active = {active} is not the index of one of the {len(masses)} payload masses")
    base_m = masses[0] if baseline is None else baseline
    if base_m not in torques_by_mass:
        raise ScaraError(f"baseline = {base_m!r} kg is not one of the payload masses {masses}")
    shown = np.asarray(torques_by_mass[masses[active]])
    base = np.asarray(torques_by_mass[base_m])
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08, row_heights=[0.55, 0.45])
    for j in range(4):
        fig.add_scatter(x=f32(t[idx]), y=f32(shown[idx, j]), mode="lines", name=f"τ{j + 1}",
                        line=dict(color=JOINT_COLOURS[j], width=2.0, dash=DASHES[j]), row=2 if j == 2 else 1, col=1)
    for j in range(4):
        fig.add_scatter(x=f32(t[idx]), y=f32(base[idx, j]), mode="lines", name=f"τ at {base_m:g} kg",
                        legendgroup="baseline", showlegend=(j == 0), hoverinfo="skip",
                        line=dict(color="#999999", width=1.0), row=2 if j == 2 else 1, col=1)
    for row, joints in ((1, (0, 1, 3)), (2, (2,))):
        lo = min(float(np.min(np.asarray(v)[:, joints])) for v in torques_by_mass.values())
        hi = max(float(np.max(np.asarray(v)[:, joints])) for v in torques_by_mass.values())
        pad = 0.05 * (hi - lo) + 1e-6
        fig.update_yaxes(range=[lo - pad, hi + pad], row=row, col=1)
    stacked_axes(fig, ("τ1, τ2, τ4 (N m)", "τ3 (N)"))

    def heading(m, tau):
        return f"{title}<br>payload {m:g} kg, largest |τ3| {np.abs(tau[:, 2]).max():.1f} N"

    steps = []
    for m in masses:
        tau = np.asarray(torques_by_mass[m])
        steps.append(dict(label=f"{m:g}", method="update",
                          args=[{"y": [[float(f"{v:.4g}") for v in tau[idx, j]] for j in range(4)]},
                                {"title.text": heading(m, tau)}, [0, 1, 2, 3]]))
    return finish_layout(fig, heading(masses[active], shown), height, bottom=130,
                         sliders=[slider(steps, "payload m_L (kg): ", active=active, pad_top=50)])


def window_max(t, y, size: int):
    """``(t_k, max |y|)`` over consecutive windows of ``size`` samples of the series ``y`` (N,); the last window
    also takes the samples left over (fewer than ``size``), so that no window is a lone sample, and a series of at
    most ``size`` samples is one window. ``t_k`` is the midpoint of the window's first and last times. Unlike a
    sample every ``size`` steps, the window maximum keeps every peak, and a series that alternates from one
    sample to the next (as a residual of Simpson's rule does) draws as one line, not as a band. Values are
    floored at ``LOG_FLOOR`` (1e-12) for a log axis. ``size`` is a whole number from 1 to ``MAX_POINTS``."""
    size = check_count(size, "size", 1, MAX_POINTS, "samples per window", FIGURE_BUDGET)
    t = np.asarray(t, dtype=float)
    y = np.abs(np.asarray(y, dtype=float))
    if t.shape != y.shape or t.ndim != 1 or not len(t):
        raise ScaraError(f"t and y must be series of the same length, got shapes {t.shape} and {y.shape}")
    starts = np.arange(0, max(len(t) - size, 0) + 1, size)
    ends = np.append(starts[1:] - 1, len(t) - 1)
    peaks = np.maximum.reduceat(y, starts)
    return 0.5 * (t[starts] + t[ends]), np.maximum(peaks, LOG_FLOOR)


def energy_figure(t, energy: dict, title: str = "Energy of the released arm", target: int = 1000,
                  height: int = 540, window: int = 10) -> go.Figure:
    """Top: kinetic energy, potential energy and total energy (relative to their start values), the work
    dissipated by friction and the work done by the torques; bottom, on a log axis: the largest absolute value of
    the balance residual ``E - E(0) - W_in + W_f`` (J) in each window of ``window`` consecutive samples
    (:func:`window_max`; more samples per window if the run has more than ``target`` windows).
    ``energy`` is :meth:`scara.SimulationResult.energy`.

    Limits: ``target`` from 2 to 10 000 samples per curve and ``window`` from 1 to 10 000 samples
    (``MAX_POINTS``); a value outside, or not a whole number, raises :class:`ScaraError` before any work."""
    target = check_count(target, "target", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    window = check_count(window, "window", 1, MAX_POINTS, "samples per residual window", FIGURE_BUDGET)
    t = np.asarray(t)
    idx = thin(len(t), target)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, row_heights=[0.64, 0.36], vertical_spacing=0.1)
    T, U, E = (np.asarray(energy[k]) for k in ("kinetic", "potential", "total"))
    series = [("kinetic T", T - T[0], "#0072B2", "solid"),
              ("potential U − U(0)", U - U[0], "#009E73", "dash"),
              ("total E − E(0)", E - E[0], "#000000", "solid"),
              ("friction work −W_f", -np.asarray(energy["friction_work"]), "#D55E00", "dot")]
    if np.abs(energy["input_work"]).max() > 0:
        series.append(("input W_in", np.asarray(energy["input_work"]), "#CC79A7", "dashdot"))
    for name, y, c, d in series:
        width = 3.2 if name.startswith("total") else 2
        fig.add_scatter(x=f32(t[idx]), y=f32(y[idx]), mode="lines", name=name, line=dict(color=c, dash=d, width=width),
                        row=1, col=1)
    size = max(window, -(-len(t) // target))
    tt, peak = window_max(t, energy["balance"], size)
    fig.add_scatter(x=f32(tt), y=f32(peak), mode="lines", name=f"largest |residual| per {size} samples",
                    showlegend=False, line=dict(color="#555555", width=1.8),
                    hovertemplate="t = %{x:.3f} s<br>largest |E − E(0) − W_in + W_f| = %{y:.2e} J<extra></extra>",
                    row=2, col=1)
    # whole decades around the residual, one tick each: a narrow log range would label odd fractions of a decade
    lo = math.floor(math.log10(float(peak.min())))
    hi = max(math.ceil(math.log10(float(peak.max()))), lo + 1)
    stacked_axes(fig, ("energy (J)", "|residual| (J)"), log=(2,))
    fig.update_yaxes(range=[lo, hi], dtick=1, row=2, col=1)
    return finish_layout(fig, title, height)


#: the text of each entry of ``B`` in the inertia figure, row by row (3 significant digits)
B_TEXTS = tuple(Text("{" + name + ":.3g}") for name in B_FIELDS)


def _bar_name(k: str) -> str:
    """The legend name of the bar of the term ``k`` in the inertia figure."""
    return TERM_LABELS[k].replace(" (5 kg)", "")


#: the terms of the bars of the diagonal's make-up, with the output of :mod:`scara.programs.dynamics` each draws
_DIAGONAL_BARS = (("links", "d_links"), ("rotors", "d_rotors"), ("payload", "d_payload"))
#: how the inertia panel draws its program's outputs (:mod:`scara.programs.dynamics`), keyed by trace name (a
#: :class:`~scara.plots.panels.PageProgram`'s ``traces``): the shades of ``B`` and the top of their colour
#: scale, the entries' texts, the three bars of the diagonal; :func:`inertia_figure` draws the same fields
INERTIA_TRACES = {"inertia": {
    "B(q) shade": {"z": "shade", "zmax": "cmax"},
    "B(q)": {"text": B_TEXTS},
    **{_bar_name(k): {"x": field} for k, field in _DIAGONAL_BARS},
}}
#: the inertia panel's title, from the payload and theta2 sliders
INERTIA_TITLE = Text("B(q) with a {payload:g} kg payload at θ2 = {theta2:.0f}°")


def text_colours(shade) -> list:
    """The colour of each entry's text over its square of shade ``shade`` (16,): white on the darkest 40 % of the
    range of shades, near-black elsewhere."""
    shade = np.asarray(shade)
    dark = shade > shade.min() + 0.6 * (shade.max() - shade.min())
    return np.where(dark, "white", "#222222").tolist()


def inertia_figure(q, p=None, title: str | None = None, values: dict | None = None) -> go.Figure:
    """Left: ``B(q)`` as a grid of shaded squares with its entries written in them; right: each diagonal entry
    split into links, rotors and payload (stacked horizontal bars). Drawn from the outputs of
    :func:`scara.programs.dynamics.inertia_core` (``values``; by default those of ``q`` and the robot ``p`` with its
    own payload, :func:`~scara.programs.dynamics.inertia_values`): the fields of :data:`INERTIA_TRACES`, so that
    the live panel, which draws the same fields, updates it in place.

    The shades are a heat map under a text trace named ``"B(q)"`` (its hover names each entry): a heat map's
    colours are its top-level ``z`` and ``zmax``, which a panel's bindings set."""
    if values is None:
        values = inertia_values(as_vector(q, "q"), ScaraParams.resolve(p))
    fig = make_subplots(rows=1, cols=2, column_widths=[0.5, 0.5], horizontal_spacing=0.14,
                        subplot_titles=["B(q) (kg m², kg m, kg)", "diagonal of B: what it is made of"])
    rows, cols = np.indices((4, 4))
    shade = values["shade"]
    fig.add_heatmap(x=(cols + 1).ravel(), y=(rows + 1).ravel(), z=shade, zmin=-3.0, zmax=values["cmax"],
                    colorscale="Blues", showscale=False, xgap=10, ygap=10, name="B(q) shade", hoverinfo="skip",
                    row=1, col=1)
    fig.add_scatter(x=(cols + 1).ravel(), y=(rows + 1).ravel(), mode="markers+text", name="B(q)", showlegend=False,
                    text=[t.format(values) for t in B_TEXTS],
                    textfont=dict(color=text_colours(shade), size=11),
                    marker=dict(symbol="square", size=44, color="rgba(0, 0, 0, 0)"),
                    customdata=[f"B[{i + 1},{j + 1}]" for i, j in zip(rows.ravel(), cols.ravel())],
                    hovertemplate="%{customdata} = %{text}<extra></extra>", row=1, col=1)
    fig.update_yaxes(autorange="reversed", title_text="row", tickvals=[1, 2, 3, 4], range=[4.6, 0.4],
                     showgrid=False, zeroline=False, row=1, col=1)
    fig.update_xaxes(title_text="column", tickvals=[1, 2, 3, 4], range=[0.4, 4.6], showgrid=False, zeroline=False,
                     row=1, col=1)
    names = [f"B{i}{i}" for i in range(1, 5)]
    for k, field in _DIAGONAL_BARS:
        fig.add_bar(y=names, x=values[field], orientation="h", name=_bar_name(k),
                    marker_color=TERM_COLOURS[k], row=1, col=2)
    fig.update_xaxes(title_text="kg m² (B33: kg)", row=1, col=2)
    fig.update_yaxes(autorange="reversed", row=1, col=2)
    finish_layout(fig, title, 460, subplot_titles=True, barmode="stack")
    return fig


def inertia_panel_figure(values) -> go.Figure:
    """The inertia panel's figure: :func:`inertia_figure` drawn from the outputs of
    :func:`scara.programs.dynamics.dynamics_program` (``values``), titled :data:`INERTIA_TITLE`."""
    return inertia_figure(None, values=values, title=INERTIA_TITLE.format(values))


#: the entries of B drawn by :func:`inertia_slider_figure`: (row, column), legend name, colour, dash
_INERTIA_CURVES = (((0, 0), "B11", "#0072B2", "solid"), ((0, 1), "B12", "#E69F00", "dash"),
                   ((1, 1), "B22", "#009E73", "dot"))


def inertia_slider_figure(theta2_deg, masses, p=None, q=(0.0, 0.0, 0.5, 0.0),
                          title: str = "Arm inertia against the elbow", height: int = 500,
                          active: int = 0) -> go.Figure:
    """Static slider figure: ``B11``, ``B12`` and ``B22`` of :func:`scara.dynamics.inertia` (kg m²) against the
    elbow angle ``theta2_deg`` (degrees), one slider step per payload mass in ``masses`` (kg) on the robot ``p``.
    ``q`` is a configuration (rad, rad, m, rad) whose theta1, d3 and theta4 are held; its theta2 is replaced by
    each angle of the sweep (``B`` depends on theta2 alone, so the others only label the figure). Each
    step restyles the three curves and the title; the y range is the same for every step, so that the curves of
    two payloads compare. ``active`` is the index of the mass shown first. Works in the HTML with no kernel.

    Limits: 2 to 2001 angles (``MAX_SWEEP``), at most 121 masses (``MAX_STEPS``) and at most 100 000 samples per
    curve in all the steps together (masses × angles, ``MAX_SLIDER_SAMPLES``); a count outside raises
    :class:`ScaraError` before any work."""
    theta2_deg = np.asarray(theta2_deg, dtype=float).ravel()
    masses = [float(m) for m in np.asarray(masses, dtype=float).ravel()]
    check_count(len(theta2_deg), "len(theta2_deg)", 2, MAX_SWEEP, "elbow angles", FIGURE_BUDGET)
    check_count(len(masses), "len(masses)", 1, MAX_STEPS, "payload masses (slider steps)", FIGURE_BUDGET)
    check_count(len(masses) * len(theta2_deg), f"{len(masses)} masses × {len(theta2_deg)} angles", 1, MAX_SLIDER_SAMPLES, "samples per curve in all the slider steps", FIGURE_BUDGET)
    if not 0 <= int(active) < len(masses):
        raise ScaraError(f"active = {active} is not the index of one of the {len(masses)} payload masses")
    active = int(active)
    p = ScaraParams.resolve(p)
    q = as_vector(q, "q")
    configs = np.repeat(q[None, :], len(theta2_deg), axis=0)
    configs[:, 1] = np.radians(theta2_deg)
    curves = {}     # mass -> (3, n) array of the entries drawn
    for m in masses:
        robot = p.with_payload(m)
        B = np.array([inertia(c, robot) for c in configs])
        curves[m] = np.array([B[:, i, j] for (i, j), *_ in _INERTIA_CURVES])
    fig = go.Figure()
    shown = curves[masses[active]]
    for k, (_, name, colour, dash) in enumerate(_INERTIA_CURVES):
        fig.add_scatter(x=f32(theta2_deg), y=f32(shown[k]), mode="lines", name=name,
                        line=dict(color=colour, dash=dash, width=2.2),
                        hovertemplate=name + " = %{y:.4g} kg m²<extra></extra>")
    lo = min(float(v.min()) for v in curves.values())
    hi = max(float(v.max()) for v in curves.values())
    pad = 0.05 * (hi - lo) + 1e-6

    def heading(m):
        return f"{title}<br>payload {m:g} kg"

    steps = [dict(label=f"{m:g}", method="update",
                  args=[{"y": [[float(f"{v:.5g}") for v in curves[m][k]] for k in range(len(_INERTIA_CURVES))]},
                        {"title.text": heading(m)}, list(range(len(_INERTIA_CURVES)))])
             for m in masses]
    finish_layout(fig, heading(masses[active]), height, bottom=130, hovermode="x unified",
                  sliders=[slider(steps, "payload m_L (kg): ", active=active, pad_top=50)])
    fig.update_xaxes(title_text="θ2 (°)", tickvals=[-180, -90, 0, 90, 180],
                     range=[float(theta2_deg.min()), float(theta2_deg.max())])
    fig.update_yaxes(title_text="entry of B (kg m²)", range=[lo - pad, hi + pad])
    return fig
