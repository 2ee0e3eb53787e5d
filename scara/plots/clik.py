"""Figures of chapter 4 (closed-loop inverse kinematics): joint motion, tracking errors on a log scale,
manipulability along the path, the drift of a relaxed component, the transpose's stability limit, the damped
inverse near a singularity, the second-order CLIK's joint reference, and a gain sweep with slider steps.

Every builder takes :class:`scara._clik.ClikResult` objects (and computes nothing but what it draws, except
:func:`gain_slider_figure`, which runs :func:`scara._clik.clik` for each slider step), but the live panel's
:func:`clik_panel_figure`, which draws the outputs of its page program (:mod:`scara.programs.clik`), already
thinned, through the bindings of :func:`clik_panel_bindings`. Long runs are thinned to
about ``points`` samples per trace; error curves keep the largest value of every thinned interval (an
envelope), so no peak is lost on a log scale.
"""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from .._clik import COMPONENTS, SEED_K, ClikResult, TransposeStability, clik, clik2, second_order_gains
from ..errors import ScaraError, UnstableError, as_array, check_count
from ._common import (
    AXIS_COLOURS, DASHES, JOINT_COLOURS, JOINT_NAMES, LOG_FLOOR, METHOD_DASHES, METHOD_LABELS, PALETTE, f32,
    envelope, run_colour, run_dash, run_label, slider, thin,
)
from ._common import MAX_POINTS, MAX_SLIDER_SAMPLES, FIGURE_BUDGET
from ..programs.clik import PANEL_METHODS
from .layout import finish_layout, stacked_axes
from .panels import Flag, Text

__all__ = [
    "METHOD_LABELS",
    "METHOD_DASHES",
    "GAIN_SCALES",
    "envelope",
    "thin",
    "clik_joints_figure",
    "clik_error_figure",
    "error_components_figure",
    "manipulability_figure",
    "drift_figure",
    "transpose_stability_figure",
    "damping_figure",
    "second_order_figure",
    "convergence_figure",
    "gain_slider_figure",
    "gain_steps_figure",
    "relaxed_figure",
    "comparison_rows",
    "METHOD_CHOICES",
    "run_method",
    "CLIK_PANEL_SERIES",
    "CLIK_PANEL_ROLES",
    "CLIK_PANEL_TITLE",
    "clik_panel_bindings",
    "clik_panel_figure",
]

#: the live panel's choices of method: its dropdown labels (the legend names, ``METHOD_LABELS``; the
#: pseudo-inverse's also names its null-space term) and the method each runs (:func:`run_method`)
METHOD_CHOICES = {METHOD_LABELS[m] + (" + null space" if m == "pseudoinverse" else ""): m for m in METHOD_LABELS}
#: the rows of :func:`clik_panel_figure`: the role of their traces, the outputs they draw (``ep_m``, ``eo_m``,
#: ``w_m`` for each method ``m`` of the program) and the axis title
CLIK_PANEL_SERIES = (("position error", "ep", "‖e_p‖ (m)"), ("orientation error", "eo", "|e_φ| (rad)"),
                     ("manipulability", "w", "w (m²)"))
#: the roles of :func:`clik_panel_figure`'s traces, in order: each row's trace of each method
CLIK_PANEL_ROLES = tuple(f"{row} · {m}" for row, _, _ in CLIK_PANEL_SERIES for m in PANEL_METHODS)
#: the title of :func:`clik_panel_figure`: the method and the largest position error after 0.1 s (mm)
CLIK_PANEL_TITLE = Text("{method}: max ‖e_p‖ after 0.1 s = {max_ep_mm:.4g} mm")
#: the pseudo-inverse's legend name (:func:`~scara.plots._common.run_label` of its run)
CLIK_PSEUDO_NAME = Text(METHOD_LABELS["pseudoinverse"] + " ({relaxed} relaxed)")


#: default gain scales of :func:`gain_slider_figure`: the seed (1), up to and past the transpose's limit (~3.92
#: on the reference) and close to the inverse's (2 / (dt K) = 5 for the seed's x, y, z gains)
GAIN_SCALES = (0.25, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 3.5, 3.9, 4.5, 4.9)


def _results(results) -> list:
    if isinstance(results, ClikResult):
        return [results]
    if isinstance(results, dict):
        results = list(results.values())
    out = list(results)
    if not out or not all(isinstance(r, ClikResult) for r in out):
        raise ScaraError("expected a ClikResult or a list/dict of ClikResult objects")
    return out


def clik_joints_figure(results, points: int = 800, title: str | None = None, height: int = 560) -> go.Figure:
    """Joint motion in three stacked panels sharing the time axis: the revolute joints ``θ1, θ2, θ4`` (rad),
    the quill ``d3`` (m), and the revolute joint rates (rad/s). One column, so that it reads at phone width;
    each joint keeps its colour and dash style. With several results a dropdown picks the method shown.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    rs = _results(results)
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.05, row_heights=[0.4, 0.25, 0.35])
    groups, titles = [], []
    for r in rs:
        idx = thin(len(r.t), points)
        t = f32(r.t[idx])
        first = len(fig.data)
        for j, name in enumerate(JOINT_NAMES):
            style = dict(color=JOINT_COLOURS[j], width=1.8, dash=DASHES[j])
            if j == 2:
                fig.add_trace(go.Scatter(x=t, y=f32(r.q[idx, j]), mode="lines", name=f"{name} · {run_label(r)}",
                                         legendgroup=f"{r.method}{name}", line=style), row=2, col=1)
                continue
            fig.add_trace(go.Scatter(x=t, y=f32(r.q[idx, j]), mode="lines", name=f"{name} · {run_label(r)}",
                                     legendgroup=f"{r.method}{name}", line=style), row=1, col=1)
            fig.add_trace(go.Scatter(x=t, y=f32(r.qd[idx, j]), mode="lines", name=f"{name} rate · {run_label(r)}",
                                     legendgroup=f"{r.method}{name}", showlegend=False, line=style), row=3, col=1)
        groups.append(list(range(first, len(fig.data))))
        titles.append(f"Joint motion, {run_label(r)}")
    heads = titles if title is None else [title] * len(rs)
    menu = [(run_label(r), h) for r, h in zip(rs, heads)] if len(rs) > 1 else None
    finish_layout(fig, heads[0], height, groups=groups if menu else None, menu=menu)
    return stacked_axes(fig, ("θ1, θ2, θ4 (rad)", "d3 (m)", "rates (rad/s)"))


def clik_error_figure(results, points: int = 1000, title: str | None = None, height: int = 520,
                      settle: float = 0.0) -> go.Figure:
    """Norm of the position error (top, m) and orientation error ``|e_phi|`` (bottom, rad) on log axes, one
    curve per method (upper envelope; method colour and dash). For the pseudo-inverse only the kept
    components count.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    rs = _results(results)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08)
    for r in rs:
        keep = r.t >= r.t[0] + settle
        for row, series in ((1, r.position_error), (2, r.orientation_error)):
            tt, yy = envelope(r.t[keep], series[keep], points)
            fig.add_trace(go.Scatter(x=f32(tt), y=f32(yy), mode="lines", name=run_label(r), legendgroup=r.method,
                                     showlegend=row == 1, line=dict(color=run_colour(r), width=1.8, dash=run_dash(r))),
                          row=row, col=1)
    finish_layout(fig, title or "Tracking error along the reference", height)
    return stacked_axes(fig, ("‖e_p‖ (m)", "|e_φ| (rad)"), log=(1, 2))


def error_components_figure(results, points: int = 1000, title: str | None = None, height: int = 520) -> go.Figure:
    """The four components of ``e = x_d - x_e``, signed: position (m, top) and phi (rad, bottom), each component
    with its colour and dash style. With several results a dropdown picks the method shown (the axes rescale
    to it).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    rs = _results(results)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08, row_heights=[0.65, 0.35])
    groups, titles = [], []
    for r in rs:
        idx = thin(len(r.t), points)
        first = len(fig.data)
        for i, name in enumerate(COMPONENTS):
            fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(r.e[idx, i]), mode="lines",
                                     name=f"e_{name} · {run_label(r)}",
                                     line=dict(color=AXIS_COLOURS[i], width=1.6, dash=DASHES[i])),
                          row=1 if i < 3 else 2, col=1)
        groups.append(list(range(first, len(fig.data))))
        titles.append(f"Error components, {run_label(r)}")
    heads = titles if title is None else [title] * len(rs)
    menu = [(run_label(r), h) for r, h in zip(rs, heads)] if len(rs) > 1 else None
    finish_layout(fig, heads[0], height, groups=groups if menu else None, menu=menu)
    fig.update_yaxes(title_text="e_x, e_y, e_z (m)", exponentformat="power", row=1, col=1)
    fig.update_yaxes(title_text="e_φ (rad)", exponentformat="power", row=2, col=1)
    fig.update_xaxes(title_text="t (s)", row=2, col=1)
    return fig


def manipulability_figure(results, points: int = 1000, title: str | None = None, height: int = 400) -> go.Figure:
    """Manipulability ``w(t) = a1 a2 |sin theta2|`` along each run (method colour and dash); the axis reaches the
    largest possible value ``a1 a2``.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    rs = _results(results)
    fig = go.Figure()
    for r in rs:
        idx = thin(len(r.t), points)
        fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(r.w[idx]), mode="lines", name=run_label(r),
                                 line=dict(color=run_colour(r), width=2.2, dash=run_dash(r))))
    wmax = max(float(np.max(r.w)) for r in rs)
    finish_layout(fig, title or "Manipulability along the path", height)
    fig.update_xaxes(title_text="t (s)")
    fig.update_yaxes(title_text="w (m²)", rangemode="tozero", range=[0, max(0.26, 1.05 * wmax)])
    return fig


def drift_figure(relaxed: ClikResult, reference: ClikResult | None = None, points: int = 1000,
                 title: str | None = None, height: int = 520) -> go.Figure:
    """What the free component does: top, the relaxed coordinate reached by the pseudo-inverse against the
    planned one (and the run ``reference``, e.g. the inverse CLIK, which follows the plan); bottom, the elbow
    angle ``theta2`` of both runs, with ``±90°`` (best dexterity) marked.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    r = _results(relaxed)[0]
    if r.method != "pseudoinverse":
        raise ScaraError(f"drift_figure needs a pseudo-inverse run, got method {r.method!r}")
    i = COMPONENTS.index(r.gains.get("relaxed", "x"))
    unit = "rad" if i == 3 else "m"
    idx = thin(len(r.t), points)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08)
    fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(r.x_d[idx, i]), mode="lines", name=f"planned {COMPONENTS[i]}",
                             line=dict(color=PALETTE["reference"], width=1.4, dash="dash")), row=1, col=1)
    fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(r.x[idx, i]), mode="lines", name=f"{COMPONENTS[i]} · {run_label(r)}",
                             line=dict(color=run_colour(r), width=2.0)), row=1, col=1)
    runs = [r] + ([_results(reference)[0]] if reference is not None else [])
    for rr in runs:
        ii = thin(len(rr.t), points)
        fig.add_trace(go.Scatter(x=f32(rr.t[ii]), y=f32(rr.q[ii, 1]), mode="lines", name=f"θ2 · {run_label(rr)}",
                                 line=dict(color=run_colour(rr), width=1.8, dash="solid" if rr is r else "dash")),
                      row=2, col=1)
    for s in (-1, 1):
        fig.add_hline(y=s * math.pi / 2, line=dict(color="#999999", width=1, dash="dot"), row=2, col=1)
    finish_layout(fig, title or f"The relaxed {COMPONENTS[i]} drifts while θ2 climbs to ±90°", height)
    return stacked_axes(fig, (f"{COMPONENTS[i]} ({unit})", "θ2 (rad)"))


def transpose_stability_figure(stability: TransposeStability, runs: dict, points: int = 1000,
                               title: str | None = None, height: int = 540) -> go.Figure:
    """Top: the largest gain scale Euler's rule tolerates at each instant, ``2 / (dt mu_max(t))`` for the seed
    direction of ``K``, with the scales of ``runs`` as horizontal lines. Bottom: the position error of each run
    (``{label: ClikResult}``, e.g. the partial result of a diverged run) on a log axis. The runs are drawn in
    the transpose's colour, told apart by their dash style.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    st = stability
    dt = 2.0 / st.limit
    idx = thin(len(st.t), points)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08)
    fig.add_trace(go.Scatter(x=f32(st.t[idx]), y=f32(2.0 / (dt * st.mu[idx])), mode="lines",
                             name="largest stable gain scale", line=dict(color=PALETTE["reference"], width=1.6)),
                  row=1, col=1)
    for n, (label, r) in enumerate(runs.items()):
        r = _results(r)[0]
        scale = float(np.median(r.gains["K"] / np.asarray(SEED_K)))
        line = dict(color=run_colour(r), dash=DASHES[n % 4], width=2.0)
        fig.add_trace(go.Scatter(x=[st.t[0], st.t[-1]], y=[scale, scale], mode="lines", legendgroup=label,
                                 name=f"{r.method}, K = {scale:.3f} × seed ({label})", line=line), row=1, col=1)
        tt, yy = envelope(r.t, r.position_error, points)
        fig.add_trace(go.Scatter(x=f32(tt), y=f32(yy), mode="lines", name=f"‖e_p‖, {label}", showlegend=False,
                                 legendgroup=label, line=line), row=2, col=1)
    finish_layout(fig, title or "Transpose: Euler's limit on the gain", height)
    return stacked_axes(fig, ("gain scale (× seed K)", "‖e_p‖ (m)"), log=(2,))


def damping_figure(runs: dict, points: int = 1500, title: str | None = None, height: int = 560) -> go.Figure:
    """Runs on a near-singular path (``{label: ClikResult}``): joint-1 rate (top), position error (middle,
    log) and manipulability (bottom). Each run takes its method's colour; runs of the same method are told
    apart by their dash style (the first solid).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.06)
    seen: dict = {}
    for label, r in runs.items():
        r = _results(r)[0]
        k = seen.get(r.method, 0)
        seen[r.method] = k + 1
        line = dict(color=run_colour(r), width=2.0, dash=DASHES[k % 4])
        idx = thin(len(r.t), points)
        fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(r.qd[idx, 0]), mode="lines", name=label, legendgroup=label,
                                 line=line), row=1, col=1)
        tt, yy = envelope(r.t, r.position_error, points)
        fig.add_trace(go.Scatter(x=f32(tt), y=f32(yy), mode="lines", name=label, legendgroup=label, showlegend=False,
                                 line=line), row=2, col=1)
        fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(r.w[idx]), mode="lines", name=label, legendgroup=label,
                                 showlegend=False, line=line), row=3, col=1)
    finish_layout(fig, title or "Near a singularity: exact and damped inverse", height)
    return stacked_axes(fig, ("θ1 rate (rad/s)", "‖e_p‖ (m)", "w (m²)"), log=(2,))


def second_order_figure(result: ClikResult, points: int = 1000, title: str | None = None,
                        height: int = 560) -> go.Figure:
    """The joint reference a second-order CLIK hands to the controllers: ``q``, ``qd`` and ``qdd`` per joint
    (revolute joints in rad, rad/s, rad/s²; ``d3`` in m, m/s, m/s²), each joint with its colour and dash.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    r = _results(result)[0]
    if r.qdd is None:
        raise ScaraError("second_order_figure needs a clik2 result (with qdd)")
    idx = thin(len(r.t), points)
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.05)
    for row, data in ((1, r.q), (2, r.qd), (3, r.qdd)):
        for j, name in enumerate(JOINT_NAMES):
            fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(data[idx, j]), mode="lines", name=f"{name} · second order",
                                     legendgroup=name, showlegend=row == 1,
                                     line=dict(color=JOINT_COLOURS[j], width=1.6, dash=DASHES[j])), row=row, col=1)
    finish_layout(fig, title or "Joint reference from the second-order CLIK", height)
    return stacked_axes(fig, ("q (rad; m)", "q̇ (rad/s; m/s)", "q̈ (rad/s²; m/s²)"))


def convergence_figure(result: ClikResult, horizon: float = 0.05, title: str | None = None,
                       height: int = 440) -> go.Figure:
    """Decay of an initial error: ``|e_i(t)|`` of each component over the first ``horizon`` seconds on a log
    axis, against the continuous law ``|e_i(0)| exp(-K_i t)`` (dashed) and Euler's ``|e_i(0)| (1 - dt K_i)^k``
    (open markers, one symbol per component)."""
    r = _results(result)[0]
    if "K" not in r.gains:
        raise ScaraError("convergence_figure needs a first-order CLIK result (with gains K)")
    K = np.asarray(r.gains["K"])
    n = min(len(r.t), int(round(horizon / r.dt)) + 1)
    t = r.t[:n]
    symbols = ("circle-open", "square-open", "diamond-open", "triangle-up-open")
    fig = go.Figure()
    for i, name in enumerate(COMPONENTS):
        e0 = abs(r.e[0, i])
        if e0 == 0 or not r.kept[i]:
            continue
        c = AXIS_COLOURS[i]
        fig.add_trace(go.Scatter(x=f32(t), y=f32(np.maximum(np.abs(r.e[:n, i]), LOG_FLOOR)), mode="lines",
                                 name=f"|e_{name}|", legendgroup=name,
                                 line=dict(color=c, width=2)))
        fig.add_trace(go.Scatter(x=f32(t), y=f32(e0 * np.exp(-K[i] * t)), mode="lines", legendgroup=name,
                                 name="continuous law", showlegend=False, line=dict(color=c, width=1.2, dash="dash")))
        fig.add_trace(go.Scatter(x=f32(t), y=f32(e0 * (1 - r.dt * K[i]) ** np.arange(n)), mode="markers",
                                 legendgroup=name, name="Euler", showlegend=False,
                                 marker=dict(color=c, size=6, symbol=symbols[i])))
    # legend keys for the two predictions, drawn once in neutral grey
    fig.add_trace(go.Scatter(x=[None], y=[None], mode="lines", name="exp(−K t)",
                             line=dict(color="#777777", width=1.2, dash="dash")))
    fig.add_trace(go.Scatter(x=[None], y=[None], mode="markers", name="(1 − dt K)^k",
                             marker=dict(color="#777777", size=6, symbol="circle-open")))
    gains = ", ".join(f"{g:g}" for g in K)
    finish_layout(fig, title or f"Decay of an initial error, {run_label(r)}<br>K = diag({gains})", height)
    fig.update_xaxes(title_text="t (s)")
    fig.update_yaxes(type="log", exponentformat="power", title_text="|e_i| (m; rad for φ)")
    return fig


def gain_slider_figure(traj, scales=None, methods=("inverse", "transpose"), points: int = 600,
                       title: str | None = None, height: int = 500) -> go.Figure:
    """Static slider over the gain: for each scale ``c`` (``K = c`` × the seed ``diag(400, 400, 400, 100)``) the
    position-error envelope of each method on ``traj``. Works with no kernel (slider steps toggle visibility).
    Each step's title gives the scale on its first line and each method's largest position error after the
    first 0.1 s (:meth:`ClikResult.summary`) below, two methods a line.

    Scales past a method's discrete-time stability limit are skipped for that method (the curve is absent and
    the title says ``unstable``). At most 25 scales.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work.
    """
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    scales = np.asarray(GAIN_SCALES if scales is None else scales, dtype=float)
    if not 1 <= len(scales) <= 25:
        raise ScaraError(f"gain_slider_figure takes 1 to 25 scales, got {len(scales)}")
    fig = go.Figure()
    notes = []
    for s in scales:
        note = []
        for m in methods:
            try:
                r = clik(traj, m, s * np.asarray(SEED_K))
                tt, yy = envelope(r.t, r.position_error, points)
                note.append(f"{m}: {length_text(r.summary()['max_position_error'])}")
            except UnstableError:
                tt, yy = np.array([]), np.array([])
                note.append(f"{m}: unstable")
            fig.add_trace(go.Scatter(x=f32(tt), y=f32(yy), mode="lines", name=run_label(m),
                                     visible=False, line=dict(color=run_colour(m), width=1.8, dash=run_dash(m))))
        # two methods per line: with the first line the title keeps to two lines (a taller title would run
        # into the legend) and each line to the 45 characters of a phone-width page
        notes.append("<br>".join(", ".join(note[k:k + 2]) for k in range(0, len(note), 2)))
    nm = len(methods)
    active = int(np.argmin(np.abs(scales - 1.0)))
    for k in range(nm):
        fig.data[active * nm + k].visible = True
    steps = []
    for i, s in enumerate(scales):
        vis = [False] * len(fig.data)
        for k in range(nm):
            vis[i * nm + k] = True
        steps.append({"label": f"{s:.2f}", "method": "update",
                      "args": [{"visible": vis}, {"title.text": f"K = {s:.2f} × seed, largest ‖e_p‖<br>{notes[i]}"}]})
    finish_layout(fig, f"K = {scales[active]:.2f} × seed, largest ‖e_p‖<br>{notes[active]}", height,
                  sliders=[slider(steps, "gain scale × seed K: ", active=active)])
    fig.update_xaxes(title_text="t (s)")
    fig.update_yaxes(type="log", exponentformat="power", title_text="‖e_p‖ (m)", range=[-10.5, -1.5])
    return fig


def length_text(metres: float) -> str:
    """A length for a title, to three significant digits in the unit that suits it: ``"30.3 nm"``,
    ``"4.70 µm"``, ``"2.24 mm"``, ``"0.638 m"`` (metres from 0.1 m up, nanometres below 1 µm)."""
    metres = float(metres)
    if metres == 0.0:
        return "0 m"
    rounded = abs(float(f"{metres:.3g}"))
    unit, size = next(((u, s) for u, s, least in (("m", 1.0, 0.1), ("mm", 1e-3, 1e-3), ("µm", 1e-6, 1e-6))
                       if rounded >= least), ("nm", 1e-9))
    return f"{f'{metres / size:#.3g}'.rstrip('.')} {unit}"


def run_method(traj, method: str, K, p=None, damping: float = 0.0, relaxed=None, k0=None) -> ClikResult:
    """One CLIK run of ``method`` (a key of ``METHOD_LABELS``) with the gains ``K`` (4,) in 1/s: the inverse
    (4.4), the transpose (4.8) or the pseudo-inverse with its ``relaxed`` component and null-space gain ``k0``
    by :func:`scara._clik.clik`, or the second-order law (4.16) by :func:`scara._clik.clik2` with ``K_P = K²``,
    ``K_D = 2K`` (:func:`scara._clik.second_order_gains`); ``damping`` (m) of the damped least-squares inverse.
    The one place that maps a method and one gain vector to a run (the chapter's live panel and
    :func:`gain_steps_figure`)."""
    K = np.asarray(K, dtype=float)
    if method == "second_order":
        return clik2(traj, *second_order_gains(K), p=p, damping=damping)
    if method == "pseudoinverse":
        return clik(traj, method, K, p=p, damping=damping, relaxed=relaxed, k0=k0)
    return clik(traj, method, K, p=p, damping=damping)


def gain_steps_figure(traj, gains: dict, method: str = "transpose", points: int = 600, title: str | None = None,
                      prefix: str = "", suffix: str = "", height: int = 460) -> go.Figure:
    """Static slider over chosen gain vectors: for each step ``label: K`` of ``gains`` (``K`` the four gains
    ``K_x, K_y, K_z, K_φ`` in 1/s) the position-error envelope of one ``method`` on ``traj``: the inverse
    (4.4) or the transpose (4.8) run by :func:`scara._clik.clik`, or the second-order law (4.16) run by
    :func:`scara._clik.clik2` with ``K_P = K²``, ``K_D = 2K``. It is what the chapter's live panel shows when
    its gain sliders are set to each ``K``, and works with no kernel (slider steps toggle visibility).

    Each step's title names the method (or ``title``) and the step (``prefix + label + suffix``, also shown
    above the slider) and, below, the largest position error after the first 0.1 s
    (:meth:`ClikResult.summary`), or ``refused: past the stability limit`` where the discrete-time limits
    (4.6), (4.12) or (4.19) fail and :func:`scara._clik.clik` or :func:`scara._clik.clik2` refuses the gains
    (:class:`UnstableError`; the step then draws no curve). The log axis spans eight decades below the largest
    error of all steps.

    Limits: 1 to 25 steps; ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``), and at most 100 000
    samples in all (``MAX_SLIDER_SAMPLES``); a value outside, or not a whole number, raises
    :class:`ScaraError` before any work.
    """
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    if not isinstance(gains, dict) or not 1 <= len(gains) <= 25:
        raise ScaraError("gain_steps_figure takes a dict {label: K} of 1 to 25 gain vectors")
    check_count(points * len(gains), "points × steps", 2, MAX_SLIDER_SAMPLES, "samples in all", FIGURE_BUDGET)
    if method not in METHOD_LABELS or method == "pseudoinverse":
        raise ScaraError(f"method {method!r}: use 'inverse', 'transpose' or 'second_order'")
    Ks = {str(label): as_array(K, f"gains[{label!r}]", (4,)) for label, K in gains.items()}
    head = title or run_label(method)
    fig = go.Figure()
    heads, top = [], 0.0
    for label, K in Ks.items():
        try:
            r = run_method(traj, method, K)
            tt, yy = envelope(r.t, r.position_error, points)
            note = f"largest ‖e_p‖: {length_text(r.summary()['max_position_error'])}"
            top = max(top, float(yy.max()))
        except UnstableError:
            tt, yy = np.array([]), np.array([])
            note = "refused: past the stability limit"
        fig.add_trace(go.Scatter(x=f32(tt), y=f32(yy), mode="lines", name=run_label(method), visible=False,
                                 line=dict(color=run_colour(method), width=1.8, dash=run_dash(method))))
        heads.append(f"{head}, {prefix}{label}{suffix}<br>{note}")
    fig.data[0].visible = True
    steps = []
    for i, label in enumerate(Ks):
        vis = [k == i for k in range(len(Ks))]
        steps.append({"label": label, "args": [{"visible": vis}, {"title.text": heads[i]}]})
    bar = slider(steps, prefix)
    bar["currentvalue"]["suffix"] = suffix
    finish_layout(fig, heads[0], height, sliders=[bar])
    fig.update_xaxes(title_text="t (s)")
    upper = math.log10(top) + 0.5 if top > 0 else -1.0
    fig.update_yaxes(type="log", exponentformat="power", title_text="‖e_p‖ (m)", range=[upper - 8.5, upper])
    return fig


def relaxed_figure(results, reference: ClikResult | None = None, points: int = 1000,
                   height: int = 520) -> go.Figure:
    """Pseudo-inverse runs (4.13) that climb ``w_0`` (4.14), each with another component relaxed, shown one at
    a time (a dropdown picks it): top, the manipulability ``w(t)`` of the run against that of ``reference``
    (e.g. the Jacobian inverse, dashed); bottom, the drift ``x_e - x_d`` of the relaxed component, the price of
    the freedom. Each entry's title gives the mean ``w`` over the run (:meth:`ClikResult.summary`) and the
    largest drift ``max |e_i|``.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole
    number, raises :class:`ScaraError` before any work; every result must be a pseudo-inverse run."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    rs = _results(results)
    if not all(r.method == "pseudoinverse" for r in rs):
        raise ScaraError("relaxed_figure needs pseudo-inverse runs (clik(traj, 'pseudoinverse', relaxed=...))")
    ref = _results(reference)[0] if reference is not None else None
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08)
    groups, menu = [], []
    for r in rs:
        c = r.gains.get("relaxed", "x")
        i = COMPONENTS.index(c)
        unit = "rad" if i == 3 else "m"
        first = len(fig.data)
        idx = thin(len(r.t), points)
        fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(r.w[idx]), mode="lines", name=f"w · {run_label(r)}",
                                 line=dict(color=run_colour(r), width=2.0)), row=1, col=1)
        if ref is not None:
            ii = thin(len(ref.t), points)
            fig.add_trace(go.Scatter(x=f32(ref.t[ii]), y=f32(ref.w[ii]), mode="lines", name=f"w · {run_label(ref)}",
                                     line=dict(color=run_colour(ref), width=1.6, dash="dash")), row=1, col=1)
        fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(-r.e[idx, i]), mode="lines", name=f"drift of {c}",
                                 line=dict(color=AXIS_COLOURS[i], width=1.8, dash=DASHES[i])), row=2, col=1)
        groups.append(list(range(first, len(fig.data))))
        drift = float(np.abs(r.e[:, i]).max())
        drift_text = f"{drift:.3g} rad" if i == 3 else length_text(drift)
        menu.append((f"{c} relaxed", f"{c} relaxed: mean w = {r.summary()['mean_manipulability']:.3f} m²<br>"
                     f"largest drift of {c}: {drift_text}",
                     {"yaxis2.title.text": f"{c}_e − {c}_d ({unit})"}))
    finish_layout(fig, menu[0][1], height, groups=groups, menu=menu)
    stacked_axes(fig, ("w (m²)", menu[0][2]["yaxis2.title.text"]))
    wmax = max(float(np.max(r.w)) for r in rs + ([ref] if ref is not None else []))
    fig.update_yaxes(range=[0, max(0.26, 1.05 * wmax)], row=1, col=1)
    return fig


def comparison_rows(results, settle: float = 0.1) -> list[dict]:
    """Rows of the chapter's comparison table (display units: mm, mrad, m², ms) from each result's summary."""
    rows = []
    for r in _results(results):
        s = r.summary(settle)
        rows.append({
            "method": run_label(r),
            "max ‖e_p‖ (mm)": s["max_position_error"] * 1e3,
            "RMS ‖e_p‖ (mm)": s["rms_position_error"] * 1e3,
            "max |e_φ| (mrad)": s["max_orientation_error"] * 1e3,
            "min w (m²)": s["min_manipulability"],
            "mean w (m²)": s["mean_manipulability"],
            "run time (ms)": s["elapsed"] * 1e3,
        })
    return rows


def clik_panel_bindings() -> dict:
    """The bindings of :func:`clik_panel_figure`'s traces to the outputs of the CLIK panel's program
    (:func:`scara.programs.clik.clik_program`), by role (:data:`CLIK_PANEL_ROLES`): each method's curves
    (``ep_m``, ``eo_m``, ``w_m``), shown only for the method run (``show_m``), and the pseudo-inverse's legend
    name, which names its relaxed component. The time axes do not change with the settings: not bound."""
    traces = {}
    for row, key, _ in CLIK_PANEL_SERIES:
        for m in PANEL_METHODS:
            props = {"y": f"{key}_{m}", "visible": Flag(f"show_{m}")}
            if m == "pseudoinverse" and key != "w":
                props["name"] = CLIK_PSEUDO_NAME
            traces[f"{row} · {m}"] = props
    return {"clik": traces}


def clik_panel_figure(values, height: int = 620) -> go.Figure:
    """The CLIK panel's figure for ``values`` (the outputs of :func:`scara.programs.clik.clik_program` with the
    settings, :meth:`~scara.plots.panels.PageProgram.run`): the position error (log), the orientation error
    (log) and the manipulability of the run against time, stacked, in the method's colour. Each row holds a
    trace per method (roles :data:`CLIK_PANEL_ROLES`), the method run shown; the title gives the method and
    the largest position error after 0.1 s (mm, :data:`CLIK_PANEL_TITLE`)."""
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.07)
    for k, (_, key, _) in enumerate(CLIK_PANEL_SERIES):
        x = values["t_thin" if key == "w" else "t_env"]
        for m in PANEL_METHODS:
            if key == "w":
                name = "w"
            else:
                name = CLIK_PSEUDO_NAME.format(values) if m == "pseudoinverse" else run_label(m)
            fig.add_trace(dict(type="scatter", mode="lines", x=x, y=values[f"{key}_{m}"], name=name,
                               showlegend=k == 0, visible=bool(values[f"show_{m}"] != 0),
                               line=dict(color=run_colour(m), width=1.5)), row=k + 1, col=1)
    finish_layout(fig, CLIK_PANEL_TITLE.format(values), height)
    stacked_axes(fig, tuple(axis for _, _, axis in CLIK_PANEL_SERIES), log=(1, 2))
    return fig
