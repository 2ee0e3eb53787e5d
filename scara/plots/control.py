"""Figures of chapter 6 (control with an unknown payload): joint motion, operational errors and torques of each
controller, the independent-joint controller's saturation and anti-windup, the adaptive payload estimate, the
robust term and its boundary layer (with a static slider over ``epsilon``), the steady-state error with and
without integral action, the error against the payload mass, a static slider over any set of figures, and the
live panel's summary figure.

Builders take :class:`scara._simulate.SimulationResult` objects (a dict ``{label: result}`` where several are
compared) and compute nothing but what they draw. Long runs are thinned to about ``points`` samples per trace;
error curves on log axes keep the largest value of each thinned interval (an envelope), so no peak is lost.
Every controller keeps its colour (``PALETTE``) and its dash style (``CONTROLLER_DASHES``) across the chapter,
so that the curves stay apart in greyscale; figures are one column wide, with short titles and a legend that
is given room as it wraps, so that they read on a phone-width page.
"""
from __future__ import annotations

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..errors import ScaraError, check_count
from ._common import (
    AXIS_COLOURS, CONTROLLER_DASHES, CONTROLLER_LABELS, DASHES, JOINT_COLOURS, JOINT_NAMES, JOINT_UNITS, LOG_FLOOR,
    PALETTE, f32,
    envelope, run_colour, run_dash, run_label, slider, thin,
)
from ._common import MAX_POINTS, MAX_SLIDER_SAMPLES, MAX_STEPS, FIGURE_BUDGET
from .layout import finish_layout, stacked_axes
from .panels import Flag, Text
from ..programs.control import LAWS


__all__ = [
    "CONTROLLER_LABELS", "CONTROLLER_DASHES", "joint_motion_figure", "operational_error_figure",
    "error_norm_figure", "joint_error_figure", "torque_figure", "payload_estimate_figure", "robust_term_figure",
    "boundary_layer_slider_figure", "steady_state_figure", "payload_sweep_figure", "saturation_figure",
    "figure_slider", "tuning_figure", "tuning_build", "tuning_values", "tuning_title", "tuning_bindings",
    "TUNING_CONTROLLERS", "TUNING_ROLES", "TUNING_TRACES", "TUNING_PATHS", "TUNING_TITLE", "own_roles",
    "tuning_own_build", "tuning_own_update",
]

#: the live panel's controllers (keys of ``CONTROLLER_LABELS``), in the order of its dropdown (its program's laws)
TUNING_CONTROLLERS = LAWS
#: the layout key of :func:`tuning_build`'s signal axis (the third row; the second has a secondary axis)
_SIGNAL_AXIS = "yaxis4"

_COMPONENTS = ("x", "y", "z", "φ")


def _as_dict(results) -> dict:
    if hasattr(results, "tau") and hasattr(results, "e"):
        return {run_label(results): results}
    if isinstance(results, dict):
        out = dict(results)
    else:
        out = {run_label(r): r for r in results}
    if not out or not all(hasattr(r, "tau") and hasattr(r, "e") for r in out.values()):
        raise ScaraError("expected a SimulationResult or a list/dict of SimulationResult objects")
    return out


def _line(x, y, name, colour, width=1.5, dash=None, showlegend=True, legendgroup=None, **kw):
    return go.Scatter(x=f32(x), y=f32(y), mode="lines", name=name, showlegend=showlegend, legendgroup=legendgroup,
                      line=dict(color=colour, width=width, dash=dash), **kw)


def joint_motion_figure(results, points: int = 350, title: str | None = None, height: int = 760) -> go.Figure:
    """Joint motion of each run, one run at a time (dropdown), in four stacked panels sharing the time axis:
    the revolute joints ``θ1, θ2, θ4`` (rad), the quill ``d3`` (m), the joint velocities (rad/s and m/s) and
    accelerations (rad/s² and m/s²). Each joint keeps its colour and dash style. The acceleration axis is
    scaled to the motion after the first 50 ms; the start transient of ``d̈3`` (the unknown payload pulling
    the quill down before the controller reacts) runs off that scale, and a note gives its peak.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    runs = _as_dict(results)
    fig = make_subplots(rows=4, cols=1, shared_xaxes=True, vertical_spacing=0.04, row_heights=[0.3, 0.2, 0.25, 0.25])
    groups, menu, ranges, notes = [], [], [], []
    head = title or "Joint motion"
    for label, r in runs.items():
        idx = thin(len(r.t), points)
        # keep the first samples whole: the start transient is a few milliseconds long
        idx = np.unique(np.concatenate([np.arange(min(len(r.t), 40)), idx]))
        start = len(fig.data)
        for j in range(4):
            style = dict(colour=JOINT_COLOURS[j], dash=DASHES[j], width=1.6, legendgroup=JOINT_NAMES[j])
            fig.add_trace(_line(r.t[idx], r.q[idx, j], f"{JOINT_NAMES[j]} · {label}", showlegend=True, **style),
                          row=2 if j == 2 else 1, col=1)
            fig.add_trace(_line(r.t[idx], r.qd[idx, j], f"{JOINT_NAMES[j]} rate · {label}", showlegend=False, **style),
                          row=3, col=1)
            fig.add_trace(_line(r.t[idx], r.qdd[idx, j], f"{JOINT_NAMES[j]} acceleration · {label}", showlegend=False,
                                **style), row=4, col=1)
        groups.append(list(range(start, len(fig.data))))
        menu.append((label, f"{head}<br>{label}"))
        late = r.t >= min(0.05, r.t[-1])
        lo, hi = float(r.qdd[late].min()), float(r.qdd[late].max())
        pad = 0.1 * max(hi - lo, 1e-9)
        ranges.append([lo - pad, hi + pad])
        k = int(np.argmax(np.abs(r.qdd[:, 2])))
        peak = float(r.qdd[k, 2])
        notes.append(f"d̈3 peaks at {peak:.3g} m/s² (t = {r.t[k]:.3f} s)" if not lo - pad <= peak <= hi + pad else "")
    finish_layout(fig, menu[0][1], height, groups=groups, menu=menu)
    fig.update_layout(annotations=[dict(text=notes[0], xref="x4 domain", yref="y4 domain", x=1.0, y=1.0,
                                        xanchor="right", yanchor="bottom", showarrow=False, font=dict(size=11))])
    fig.update_yaxes(range=ranges[0], row=4, col=1)
    for b, rg, note in zip(fig.layout.updatemenus[0].buttons, ranges, notes):
        b.args[1].update({"yaxis4.range": rg, "annotations[0].text": note})
    return stacked_axes(fig, ("θ1, θ2, θ4 (rad)", "d3 (m)", "velocity<br>(rad/s, m/s)",
                              "acceleration<br>(rad/s², m/s²)"))


def operational_error_figure(results, points: int = 600, title: str | None = None, height: int = 600) -> go.Figure:
    """Operational error ``x_d - x_e`` of each run, one run at a time (dropdown): the components x, y, z (mm)
    and phi (mrad) on top, the norm of the position error (m, log scale, envelope, in the controller's colour)
    below.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    runs = _as_dict(results)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08, row_heights=[0.55, 0.45])
    groups, menu = [], []
    head = title or "Operational error x_d − x_e"
    for label, r in runs.items():
        idx = thin(len(r.t), points)
        start = len(fig.data)
        for i in range(4):
            fig.add_trace(_line(r.t[idx], 1e3 * r.e[idx, i], f"e_{_COMPONENTS[i]}", AXIS_COLOURS[i],
                                dash=DASHES[i]), row=1, col=1)
        tt, yy = envelope(r.t, np.linalg.norm(r.e[:, :3], axis=1), points)
        fig.add_trace(_line(tt, yy, "‖e_p‖", run_colour(r), width=2, dash=run_dash(r)), row=2, col=1)
        groups.append(list(range(start, len(fig.data))))
        menu.append((label, f"{head}<br>{label}"))
    finish_layout(fig, menu[0][1], height, groups=groups, menu=menu)
    return stacked_axes(fig, ("e_x, e_y, e_z (mm)<br>e_φ (mrad)", "‖e_p‖ (m)"), log=(2,))


def error_norm_figure(results, points: int = 1000, title: str | None = None, height: int | None = None,
                      settle: float | None = 1.0, groups: dict | None = None) -> go.Figure:
    """The norm of the position error ``||p_d - p_e||`` (m, log scale, envelope) of several runs together, each
    in its controller's colour and dash style; a dotted line marks the end of the first ``settle`` seconds that
    the comparison table leaves out.

    ``groups`` (``{menu label: [labels of results]}``, optional): a dropdown shows one group of runs at a time
    (a run may belong to several groups), for more runs than one legend can name on a phone-width page.
    ``height`` (px) defaults to 460, or 560 with a dropdown (which takes room above the plot).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    runs = _as_dict(results)
    if groups is not None:
        if not isinstance(groups, dict) or not groups:
            raise ScaraError(f"groups must be a non-empty dict {{menu label: [run labels]}}, got {groups!r:.80}")
        for name, members in groups.items():
            unknown = [m for m in members if m not in runs] if isinstance(members, (list, tuple)) else members
            if unknown or not members:
                raise ScaraError(f"groups[{name!r}] must list labels of the runs {list(runs)}; unknown: {unknown}")
    head = title or "Position error of each controller<br>(5 kg payload, unknown to them)"
    height = (560 if groups else 460) if height is None else height
    fig = go.Figure()
    members = groups or {"": list(runs)}
    trace_groups, menu = [], []
    for name, labels in members.items():
        start = len(fig.data)
        for label in labels:
            r = runs[label]
            tt, yy = envelope(r.t, np.linalg.norm(r.e[:, :3], axis=1), points)
            fig.add_trace(_line(tt, yy, label, run_colour(r), width=2, dash=run_dash(r)))
        trace_groups.append(list(range(start, len(fig.data))))
        menu.append((name, f"{head}<br>{name}"))
    if settle:
        fig.add_vline(x=settle, line=dict(color="#777777", dash="dot", width=1))
    if groups:
        finish_layout(fig, menu[0][1], height, groups=trace_groups, menu=menu)
    else:
        finish_layout(fig, head, height)
    fig.update_yaxes(type="log", exponentformat="power", title_text="‖p_d − p_e‖ (m)")
    fig.update_xaxes(title_text="t (s)")
    return fig


def torque_figure(results, points: int = 500, title: str | None = None, height: int = 760, reference=None,
                  window=None) -> go.Figure:
    """The torques and the quill's force of several runs, one panel per joint stacked on a shared time axis
    (N m, N m, N, N m); each controller in its colour and dash style.

    ``reference`` (N, 4), optional: a torque sampled like the runs (the torque the true arm needs along the
    reference, say); each panel then shows the difference ``tau - reference``, which magnifies how the controllers
    differ where their torques would lie on top of each other. ``window = (t0, t1)`` (s), optional: only that
    interval, at full sampling (at most ``MAX_POINTS`` samples), e.g. around a corner of the path where the
    reference acceleration jumps; without it the whole run, thinned to ``points`` samples.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``), and as many samples in the window; a
    value outside, or not a whole number, raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    runs = _as_dict(results)
    ref = None
    if reference is not None:
        ref = np.asarray(reference, dtype=float)
        for label, r in runs.items():
            if ref.shape != r.tau.shape:
                raise ScaraError(f"reference has shape {ref.shape}, the run {label!r} has {r.tau.shape}: one torque "
                                 f"row per sample of the runs")
    units = ("N m", "N m", "N", "N m")
    sym = ("τ1", "τ2", "f3", "τ4")
    names = tuple(f"{s} − {s}_d ({u})" if ref is not None else f"{s} ({u})" for s, u in zip(sym, units))
    fig = make_subplots(rows=4, cols=1, shared_xaxes=True, vertical_spacing=0.04)
    for label, r in runs.items():
        if window is None:
            idx = thin(len(r.t), points)
        else:
            idx = np.flatnonzero((r.t >= window[0] - 1e-12) & (r.t <= window[1] + 1e-12))
            check_count(len(idx), f"the window {tuple(window)} s", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
        tau = r.tau[idx] - (ref[idx] if ref is not None else 0.0)
        for j in range(4):
            fig.add_trace(_line(r.t[idx], tau[:, j], label, run_colour(r), width=1.8, legendgroup=label,
                                showlegend=j == 0, dash=run_dash(r)), row=j + 1, col=1)
    head = title or ("Torque minus the torque the arm needs" if ref is not None
                     else "Joint torques and the quill's force")
    finish_layout(fig, head, height)
    return stacked_axes(fig, names)


def payload_estimate_figure(result, true_mass: float, horizon: float = 2.5, points: int = 1000,
                            title: str | None = None, height: int = 540) -> go.Figure:
    """The adaptive payload estimate: its first ``horizon`` seconds against the true mass (top, kg), and the
    estimation error ``|m_hat - m_L|`` over the whole run (bottom, kg, log scale).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    if "payload_estimate" not in getattr(result, "signals", {}):
        raise ScaraError("this run carries no payload_estimate: it is not an adaptive run")
    est = result.payload_estimate
    t = result.t
    fig = make_subplots(rows=2, cols=1, vertical_spacing=0.16, row_heights=[0.55, 0.45])
    first = t <= horizon + 1e-12
    idx = np.flatnonzero(first)[thin(int(first.sum()), points)]
    fig.add_trace(_line(t[idx], est[idx], f"m̂_L · {run_label(result)}", run_colour(result), width=2.2, dash=run_dash(result)),
                  row=1, col=1)
    fig.add_trace(_line([0, horizon], [true_mass, true_mass], f"true payload {true_mass:g} kg",
                        PALETTE["reference"], dash="dot", width=1.4), row=1, col=1)
    tt, yy = envelope(t, est - true_mass, points)
    fig.add_trace(_line(tt, yy, "|m̂_L − m_L|", AXIS_COLOURS[0], width=1.6), row=2, col=1)
    finish_layout(fig, title or "Adaptive control: the payload estimate", height)
    fig.update_yaxes(title_text="m̂_L (kg)", row=1, col=1)
    fig.update_yaxes(type="log", exponentformat="power", title_text="|m̂_L − m_L|<br>(kg)", row=2, col=1)
    fig.update_xaxes(title_text="t (s)", row=1, col=1)
    fig.update_xaxes(title_text="t (s)", row=2, col=1)
    return fig


def robust_term_figure(result, epsilon: float, window: tuple | None = None, points: int = 1500,
                       title: str | None = None, height: int = 580) -> go.Figure:
    """The robust term: ``||z||`` (rad/s and m/s mixed, log scale) against the boundary layer ``epsilon``
    (top) and the components of ``w`` (bottom, rad/s^2 and m/s^2), over ``window = (t0, t1)`` (s; default the
    whole run).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    t = result.t
    sel = np.ones(len(t), bool) if window is None else (t >= window[0]) & (t <= window[1])
    idx = np.flatnonzero(sel)
    z = result.z_norm[idx]
    w = np.column_stack([result.signals[f"w_{i}"] for i in range(1, 5)])[idx]
    tt, zz = envelope(t[idx], z, points)
    sub = idx[thin(len(idx), points)]
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08)
    fig.add_trace(_line(tt, zz, "‖z‖", run_colour(result), width=2, dash=run_dash(result)),
                  row=1, col=1)
    fig.add_trace(_line([t[idx[0]], t[idx[-1]]], [epsilon, epsilon], f"ε = {epsilon:g}", PALETTE["reference"],
                        dash="dot", width=1.4), row=1, col=1)
    for j in range(4):
        fig.add_trace(_line(t[sub], w[np.searchsorted(idx, sub), j], f"w_{j + 1}", JOINT_COLOURS[j], width=1.5,
                            dash=DASHES[j]), row=2, col=1)
    finish_layout(fig, title or "Robust control: ‖z‖ and the term w", height)
    # at least two decades on the log axis, so that it is labelled in powers of ten
    lo = np.log10(max(min(float(zz.min()), epsilon), LOG_FLOOR))
    hi = np.log10(max(float(zz.max()), epsilon))
    mid, half = 0.5 * (lo + hi), max(0.5 * (hi - lo) + 0.2, 1.0)
    fig.update_yaxes(type="log", exponentformat="power", title_text="‖z‖ (rad/s, m/s)", range=[mid - half, mid + half],
                     row=1, col=1)
    fig.update_yaxes(title_text="w (rad/s², m/s²)", row=2, col=1)
    fig.update_xaxes(title_text="t (s)", row=2, col=1)
    return fig


def boundary_layer_slider_figure(runs: dict, bound: float, window: tuple = (40.0, 40.15), title: str | None = None,
                                 height: int = 640, notes: dict | None = None) -> go.Figure:
    """Static slider over the boundary-layer width: for each ``{epsilon: result}`` of a robust run, the torques
    of the revolute joints (top, N m; the quill's force hardly chatters) and ``||z||`` against ``epsilon``
    (bottom, log) over ``window`` at full sampling, so that the sample-to-sample switching below ``bound`` (the
    sampled layer's stability limit) is visible. The title (two lines) says whether the step chatters; ``notes``
    (``{epsilon: text}``, optional, at most 45 characters each) adds a third line to the steps it names, so that a
    static page carries the run's figures (its sag at rest, say).

    Limits: at most 121 runs (``MAX_STEPS``) and 100 000 samples in the window over all of them
    (``MAX_SLIDER_SAMPLES``); more raises :class:`ScaraError` before any work."""
    if not isinstance(runs, dict) or not runs:
        raise ScaraError(f"runs must be a non-empty dict {{epsilon: result}}, got {runs!r:.80}")
    check_count(len(runs), "len(runs)", 1, MAX_STEPS, "runs (slider steps)", FIGURE_BUDGET)
    notes = dict(notes or {})
    unknown = [e for e in notes if e not in runs]
    if unknown:
        raise ScaraError(f"notes name widths without a run: {unknown}; the runs have {sorted(runs)}")
    in_window = sum(int(np.count_nonzero((r.t >= window[0]) & (r.t <= window[1]))) for r in runs.values())
    check_count(in_window, f"the window {tuple(window)} s", 0, MAX_SLIDER_SAMPLES, "samples over all the runs", FIGURE_BUDGET)
    eps_list = sorted(runs)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.1)
    joints = (0, 1, 3)
    per = len(joints) + 2
    for n, eps in enumerate(eps_list):
        r = runs[eps]
        sel = (r.t >= window[0]) & (r.t <= window[1])
        t = r.t[sel]
        for j in joints:
            # solid lines: a dash pattern on a torque that switches every sample would only add noise
            fig.add_trace(_line(t, r.tau[sel, j], f"τ{j + 1}", JOINT_COLOURS[j], width=1.3,
                                visible=n == 0, legendgroup=f"tau{j}"), row=1, col=1)
        fig.add_trace(_line(t, np.maximum(r.z_norm[sel], LOG_FLOOR), "‖z‖ · robust", PALETTE["robust"], width=1.8,
                            visible=n == 0), row=2, col=1)
        fig.add_trace(_line([t[0], t[-1]], [eps, eps], "layer ε", PALETTE["reference"], dash="dot", width=1.4,
                            visible=n == 0), row=2, col=1)


    def head(eps):
        tag = "chatters" if eps <= bound else "smooth"
        note = f"<br>{notes[eps]}" if eps in notes else ""
        return f"{title or 'Robust control, boundary layer'}<br>ε = {eps:.3g}: {tag} (limit {bound:.3g}){note}"

    steps = [dict(label=f"{eps:.3g}", method="update",
                  args=[{"visible": [per * n <= i < per * (n + 1) for i in range(per * len(eps_list))]},
                        {"title.text": head(eps)}])
             for n, eps in enumerate(eps_list)]
    finish_layout(fig, head(eps_list[0]), height, groups=[list(range(per))], bottom=120)
    fig.update_layout(sliders=[slider(steps, "ε = ")])
    return stacked_axes(fig, ("τ (N m)", "‖z‖ (rad/s, m/s)"), log=(2,))


def steady_state_figure(with_integral, without_integral, predicted: float, integral_target: float,
                        points: int = 1000, title: str | None = None, height: int = 580) -> go.Figure:
    """Vertical error ``e_z`` (mm) of the operational controller without and with integral action, against the
    predicted ``m_L g0 / (B33_hat K_P,z)`` (top); the integral action ``K_I s_z`` (m/s^2) approaching the
    acceleration ``m_L g0 / B33_hat`` it must supply (bottom).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08)
    for r in (without_integral, with_integral):
        idx = thin(len(r.t), points)
        fig.add_trace(_line(r.t[idx], 1e3 * r.e[idx, 2], run_label(r), run_colour(r), width=2.2, dash=run_dash(r)),
                      row=1, col=1)
    t_end = with_integral.t[-1]
    fig.add_trace(_line([0, t_end], [1e3 * predicted] * 2, "theory", PALETTE["reference"],
                        dash="dot", width=1.2), row=1, col=1)
    idx = thin(len(with_integral.t), points)
    fig.add_trace(_line(with_integral.t[idx], with_integral.integral_action_z[idx],
                        f"K_I s_z · {run_label(with_integral)}", run_colour(with_integral), width=2.2,
                        dash=run_dash(with_integral), showlegend=False), row=2, col=1)
    fig.add_trace(_line([0, t_end], [integral_target] * 2, "m_L g0 / B̂33", PALETTE["reference"], dash="dot",
                        width=1.2), row=2, col=1)
    finish_layout(fig, title or "Steady-state error and integral action", height)
    return stacked_axes(fig, ("e_z (mm)", "K_I s_z (m/s²)"))


def joint_error_figure(results, predicted: dict | None = None, points: int = 1000, title: str | None = None,
                       height: int = 780) -> go.Figure:
    """The joint errors ``q_d - q`` of several runs together, one panel per joint (mrad for the revolute joints, mm
    for the quill), each run in its controller's colour and dash style; ``predicted`` (``{label: (4,) error at
    rest}``, optional) draws each run's predicted steady-state error of the quill as a dotted line in its colour
    (e.g. a law's ``steady_state_error(plant)``).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    runs = _as_dict(results)
    predicted = {} if predicted is None else predicted
    unknown = [k for k in predicted if k not in runs] if isinstance(predicted, dict) else predicted
    if unknown:
        raise ScaraError(f"predicted must map labels of the runs {list(runs)} to errors at rest; unknown: {unknown}")
    fig = make_subplots(rows=4, cols=1, shared_xaxes=True, vertical_spacing=0.035)  # room for each axis's title
    for label, r in runs.items():
        idx = thin(len(r.t), points)
        for j in range(4):
            fig.add_trace(_line(r.t[idx], 1e3 * (r.q_d[idx, j] - r.q[idx, j]), label if j == 0 else
                                f"{label} · {JOINT_NAMES[j]}", run_colour(r), width=2, dash=run_dash(r),
                                showlegend=j == 0, legendgroup=label), row=j + 1, col=1)
        if label in predicted:
            e = np.asarray(predicted[label], dtype=float)
            if e.shape != (4,) or not np.all(np.isfinite(e)):
                raise ScaraError(f"predicted[{label!r}] must be 4 finite joint errors, got {predicted[label]!r:.80}")
            fig.add_trace(_line([r.t[0], r.t[-1]], [1e3 * e[2]] * 2, f"predicted at rest · {label}",
                                run_colour(r), dash="dot", width=1.2, showlegend=False, legendgroup=label),
                          row=3, col=1)
    finish_layout(fig, title or "Joint errors<br>(5 kg payload, unknown to the controllers)", height)
    return stacked_axes(fig, tuple(f"{n}_d − {n} ({'mm' if j == 2 else 'mrad'})" for j, n in enumerate(JOINT_NAMES)))


def saturation_figure(runs: dict, joint: int = 2, horizon: float = 1.5, limit: float | None = None,
                      title: str | None = None, height: int = 700) -> go.Figure:
    """Actuator saturation and anti-windup on one joint (default the quill) during the first ``horizon`` seconds
    of several runs ``{label: result}`` of :class:`~scara.control.IndependentJointController`, at full sampling:
    the joint's torque (force) against the bound ``limit`` (top, dotted), its error ``q_d - q`` (middle, mm or
    mrad) and the integral action ``K_I chi`` (bottom, N m or N). Runs of one controller share its colour in the
    other figures; here each run has its own colour and dash, in the order given.

    Limits: at most 8 runs and 10 000 samples per curve in the horizon (``MAX_POINTS``); more raises
    :class:`ScaraError` before any work."""
    from ..errors import check_index, check_positive  # noqa: PLC0415

    if not isinstance(runs, dict) or not runs:
        raise ScaraError(f"runs must be a non-empty dict {{label: result}}, got {runs!r:.80}")
    check_count(len(runs), "len(runs)", 1, 8, "runs")
    joint = check_index(joint, "joint", 4)
    horizon = check_positive(horizon, "horizon")
    signal = f"integral_action_{joint + 1}"
    for label, r in runs.items():
        if signal not in getattr(r, "signals", {}):
            raise ScaraError(f"the run {label!r} carries no {signal}: it is not a run of the independent-joint "
                             f"controller")
        n = int(np.count_nonzero(r.t <= horizon + 1e-12))
        check_count(n, f"horizon = {horizon:g} s", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    unit = JOINT_UNITS[joint]
    err_unit = "mm" if joint == 2 else "mrad"
    sym = JOINT_NAMES[joint]
    force = "f3" if joint == 2 else f"τ{joint + 1}"
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.06)
    for n, (label, r) in enumerate(runs.items()):
        sel = r.t <= horizon + 1e-12
        t = r.t[sel]
        style = dict(colour=AXIS_COLOURS[n % 4], dash=DASHES[n % 4], width=2.0, legendgroup=label)
        fig.add_trace(_line(t, r.tau[sel, joint], label, **style), row=1, col=1)
        fig.add_trace(_line(t, 1e3 * (r.q_d[sel, joint] - r.q[sel, joint]), f"error · {label}", showlegend=False,
                            **style), row=2, col=1)
        fig.add_trace(_line(t, r.signals[signal][sel], f"integral · {label}", showlegend=False, **style),
                      row=3, col=1)
    if limit is not None:
        # the bound on the side(s) the torques come near (within 5 % of it)
        limit = check_positive(limit, "limit")
        lo = float(min(r.tau[r.t <= horizon + 1e-12, joint].min() for r in runs.values()))
        hi = float(max(r.tau[r.t <= horizon + 1e-12, joint].max() for r in runs.values()))
        for sign in (1.0, -1.0):
            if lo - 0.05 * limit <= sign * limit <= hi + 0.05 * limit:
                fig.add_trace(_line([0.0, horizon], [sign * limit] * 2, f"bound ±{limit:g} {unit}",
                                    PALETTE["reference"], dash="dot", width=1.3, showlegend=True), row=1, col=1)
    finish_layout(fig, title or f"Saturation and anti-windup, {sym}", height)
    return stacked_axes(fig, (f"{force} ({unit})", f"{sym}_d − {sym} ({err_unit})", f"K_I χ ({unit})"))


def figure_slider(figures: dict, prefix: str, active: int = 0) -> go.Figure:
    """One figure with a static slider over several figures of the same build (``{label: figure}``, e.g. one
    :func:`payload_estimate_figure` per adaptation weight): the traces of every figure, one figure's shown at a
    time with its own title. Works on a static page (plotly slider steps, no kernel). The figures must share
    their subplot grid and axes (the first one's layout is kept); axes keep autoranging on the visible traces.

    Limits: at most 121 figures (``MAX_STEPS``) and 100 000 samples over all their traces
    (``MAX_SLIDER_SAMPLES``); more raises :class:`ScaraError` before any work."""
    if not isinstance(figures, dict) or not figures:
        raise ScaraError(f"figures must be a non-empty dict {{label: figure}}, got {figures!r:.80}")
    check_count(len(figures), "len(figures)", 1, MAX_STEPS, "figures (slider steps)", FIGURE_BUDGET)
    figs = list(figures.values())
    if not all(isinstance(f, go.Figure) for f in figs):
        raise ScaraError("every value of figures must be a plotly Figure")
    samples = sum(len(tr.x) if tr.x is not None else 0 for f in figs for tr in f.data)
    check_count(samples, "the samples of all the figures", 0, MAX_SLIDER_SAMPLES, "samples", FIGURE_BUDGET)
    out = go.Figure(layout=figs[0].layout)
    counts = []
    for n, f in enumerate(figs):
        counts.append(len(f.data))
        for tr in f.data:
            tr = go.Figure(data=[tr]).data[0]
            tr.visible = n == active
            out.add_trace(tr)
    starts = np.cumsum([0] + counts)
    total = int(starts[-1])
    steps = [dict(label=str(label), method="update",
                  args=[{"visible": [int(starts[n]) <= i < int(starts[n + 1]) for i in range(total)]},
                        {"title.text": f.layout.title.text}])
             for n, (label, f) in enumerate(figures.items())]
    out.update_layout(title_text=figs[active].layout.title.text, sliders=[slider(steps, prefix, active=active)],
                      margin=dict(b=max(int(figs[0].layout.margin.b or 0), 120)))
    return out


def payload_sweep_figure(masses, errors: dict, title: str | None = None, height: int | None = None,
                         ylabel: str = "max ‖p_d − p_e‖ after 1 s (m)", groups: dict | None = None) -> go.Figure:
    """An error measure (log scale) against the payload mass (kg) for each controller: ``errors`` maps a
    controller name (a key of ``PALETTE``) to one value per mass; colour, dash and marker name the controller.

    ``groups`` (``{menu label: [controller names]}``, optional): a dropdown shows one group at a time, for more
    controllers than one legend can name on a phone-width page; ``height`` (px) defaults to 480, or 560 with it."""
    masses = np.asarray(masses, dtype=float)
    if groups is not None:
        if not isinstance(groups, dict) or not groups:
            raise ScaraError(f"groups must be a non-empty dict {{menu label: [controller names]}}, "
                             f"got {groups!r:.80}")
        for name, members in groups.items():
            unknown = [m for m in members if m not in errors] if isinstance(members, (list, tuple)) else members
            if unknown or not members:
                raise ScaraError(f"groups[{name!r}] must list names of errors {list(errors)}; unknown: {unknown}")
    for name, vals in errors.items():
        if np.asarray(vals, dtype=float).shape != masses.shape:
            raise ScaraError(f"errors[{name!r}] has {np.size(vals)} values for {masses.size} masses")
    symbols = ("circle", "square", "diamond", "triangle-up", "x", "star")
    marker = {name: symbols[n % len(symbols)] for n, name in enumerate(errors)}
    head = title or "Tracking error against the payload"
    height = (560 if groups else 480) if height is None else height
    fig = go.Figure()
    trace_groups, menu = [], []
    for label, names in (groups or {"": list(errors)}).items():
        start = len(fig.data)
        for name in names:
            vals = np.asarray(errors[name], dtype=float)
            fig.add_trace(go.Scatter(x=masses, y=np.maximum(vals, LOG_FLOOR), mode="lines+markers",
                                     name=run_label(name), marker=dict(size=8, symbol=marker[name]),
                                     line=dict(color=run_colour(name), width=2, dash=run_dash(name))))
        trace_groups.append(list(range(start, len(fig.data))))
        menu.append((label, f"{head}<br>{label}"))
    if groups:
        finish_layout(fig, menu[0][1], height, groups=trace_groups, menu=menu)
    else:
        finish_layout(fig, head, height)
    fig.update_yaxes(type="log", exponentformat="power", title_text=ylabel)
    fig.update_xaxes(title_text="payload m_L (kg)")
    return fig


def _value(binding, values):
    """The value of a panel's binding (:class:`~scara.plots.panels.PageProgram`) for ``values``: an output field
    (a float array as float64), a :class:`~scara.plots.panels.Text` formatted, a :class:`~scara.plots.panels.Flag`
    as a bool."""
    if isinstance(binding, Text):
        return binding.format(values)
    if isinstance(binding, Flag):
        return bool(values[binding.field] != 0)
    v = values[binding]
    return np.asarray(v, dtype=float) if np.ndim(v) else v


def _bound_trace(values, role, name, colour, width, **kw):
    """The trace ``role`` of :func:`tuning_build`, its bound properties (:data:`TUNING_TRACES`) from ``values``."""
    props = {prop: _value(b, values) for prop, b in TUNING_TRACES[role].items()}
    return go.Scatter(mode="lines", name=name, line=dict(color=colour, width=width), **props, **kw)


def tuning_build(values, height: int = 640, title: str | None = None) -> go.Figure:
    """The live panel's figure drawn from its program's ``values`` (the outputs of
    :func:`scara.programs.control.control_program` by field, with the settings): the position error norm (log, upper
    envelope; one trace per controller, in its colour, the run's shown), the quill's force and the other torques,
    and the run's own signal: the payload estimate (adaptive), ``||z||`` (robust, log) or ``e_z`` (mm), each on its
    own axis of the third panel (the run's shown), with the controller's own figures in a note above it. Every
    property that changes with the settings is a binding of :data:`TUNING_TRACES`, :data:`TUNING_PATHS` and
    :data:`TUNING_TITLE` (``title`` replaces the title's text)."""
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.07,
                        specs=[[{}], [{"secondary_y": True}], [{}]])
    for name in TUNING_CONTROLLERS:
        fig.add_trace(_bound_trace(values, f"error {name}", CONTROLLER_LABELS[name], PALETTE[name], 1.8), row=1, col=1)
    fig.add_trace(_bound_trace(values, "f3", "f3 (N)", JOINT_COLOURS[2], 1.3), row=2, col=1)
    for j in (0, 1, 3):
        fig.add_trace(_bound_trace(values, f"τ{j + 1}", f"τ{j + 1} (N m)", JOINT_COLOURS[j], 1.1), row=2, col=1,
                      secondary_y=True)
    for role, (name, colour, axis) in _SIGNALS.items():
        fig.add_trace(_bound_trace(values, role, name, colour, 1.5, xaxis="x3", yaxis=axis.replace("axis", "")))
    fig.update_layout(annotations=[
        dict(text=_value(TUNING_PATHS[f"annotations.{i}.text"], values), xref="x3 domain", yref="y4 domain", x=1.0,
             y=1.0, xanchor="right", yanchor="bottom", showarrow=False, font=dict(size=11),
             visible=_value(TUNING_PATHS[f"annotations.{i}.visible"], values)) for i in range(len(_NOTED))])
    finish_layout(fig, _value(TUNING_TITLE, values) if title is None else title, height)
    fig.update_yaxes(type="log", exponentformat="power", title_text="‖e_p‖ (m)", row=1, col=1)
    fig.update_yaxes(title_text="f3 (N)", row=2, col=1, secondary_y=False)
    fig.update_yaxes(title_text="τ (N m)", row=2, col=1, secondary_y=True)
    fig.update_xaxes(title_text="t (s)", row=3, col=1)
    for role, (name, colour, axis) in _SIGNALS.items():
        extra = dict(type="log", exponentformat="power") if role == "z" else {}
        if axis != _SIGNAL_AXIS:
            extra.update(overlaying=_SIGNAL_AXIS.replace("axis", ""), anchor="x3")
        fig.update_layout({axis: dict(title=dict(text=name), visible=_value(TUNING_PATHS[f"{axis}.visible"], values),
                                      **extra)})
    return fig


def tuning_values(result, summary: dict, points: int = 1200) -> dict:
    """The values :func:`tuning_build` draws, for one run (a :class:`~scara._simulate.SimulationResult` of any
    controller) and its :func:`~scara.control.control_summary`: the same fields as the panel's program gives (its
    thinning and envelopes, :func:`scara.programs.control.thin_index` and :func:`~scara.plots._common.envelope`), the
    numbers the panel's notes name left at zero."""
    from ..programs.control import SCALARS, control_outputs  # noqa: PLC0415

    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    n = len(result.t)
    layout = control_outputs(n, points)
    values = {name: (0.0 if layout.sizes[name] == 1 else np.zeros(layout.sizes[name])) for name in layout.names}
    values.update(controller=run_label(result), payload=0.0, epsilon=0.0, omega=0.0)
    values["err_t"], values["err_y"] = envelope(result.t, np.linalg.norm(result.e[:, :3], axis=1), points)
    idx = thin(n, points)
    values["t"] = result.t[idx]
    values["f3"], values["tau1"], values["tau2"], values["tau4"] = (result.tau[idx, j] for j in (2, 0, 1, 3))
    sig = result.signals
    if "payload_estimate" in sig:
        values["estimate"], values["estimate_shown"] = sig["payload_estimate"][idx], 1.0
    elif "z_norm" in sig:
        values["z_norm"], values["z_shown"] = envelope(result.t, sig["z_norm"], points)[1], 1.0
    else:
        values["e_z"], values["e_z_shown"] = 1e3 * result.e[idx, 2], 1.0
    name = getattr(result, "controller", "")
    if name in TUNING_CONTROLLERS:
        values[f"{name}_shown"] = 1.0
    values.update({k: float(np.atleast_1d(summary[k])[0]) for k in SCALARS.names if np.size(summary.get(k, [])) == 1})
    return values


#: the run's figures at the head of the tuning figure's title, two lines (the static figure's and the panel's)
TUNING_HEAD = ("{controller}: max ‖e_p‖ after 1 s {max_position_error_mm:.4g} mm, at rest {final_position_error_mm:.3g} mm"
               "<br>peak f3 {peak_f3:.0f} N, chattering {chattering:.3g}")


def tuning_title(result, summary: dict, extra: str = "") -> str:
    """The title of :func:`tuning_figure`: the run's figures (error after 1 s and at rest, peak quill force,
    chattering) and ``extra``."""
    s = summary
    head = TUNING_HEAD.format(controller=run_label(result), max_position_error_mm=1e3 * s["max_position_error"],
                              final_position_error_mm=1e3 * s["final_position_error"], peak_f3=s["peak_tau"][2],
                              chattering=s["chattering"])
    return head + (f"<br>{extra}" if extra else "")


def tuning_figure(result, summary: dict, extra: str = "", points: int = 1200, height: int = 640) -> go.Figure:
    """The live panel's figure (:func:`tuning_build`) for one run and its :func:`~scara.control.control_summary`: the
    position error norm (log), the quill's force and the other torques, and the run's own signal (payload estimate,
    ``||z||`` or ``e_z``); data from :func:`tuning_values`, title from :func:`tuning_title` (no note). A run of a
    controller the panel does not offer draws its error in its own colour.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    fig = tuning_build(tuning_values(result, summary, points), height, tuning_title(result, summary, extra))
    for a in fig.layout.annotations:
        a.visible = False
    if getattr(result, "controller", "") not in TUNING_CONTROLLERS:
        fig.data[0].update(visible=True, name=run_label(result), line=dict(color=run_colour(result), width=1.8))
    return fig


#: the roles of :func:`tuning_build`'s traces, in order: the position error of each controller of the panel (one
#: shown), the quill's force, the other torques, the run's own signal (one of three shown)
TUNING_ROLES = tuple(f"error {name}" for name in TUNING_CONTROLLERS) + ("f3", "τ1", "τ2", "τ4", "estimate", "z", "e_z")
#: the run's own signal: role -> (name, colour, axis of the third panel)
_SIGNALS = {"estimate": ("m̂_L (kg)", PALETTE["adaptive"], "yaxis4"), "z": ("‖z‖", PALETTE["robust"], "yaxis5"),
            "e_z": ("e_z (mm)", AXIS_COLOURS[2], "yaxis6")}
#: the controllers whose own figures a note above the signal panel gives, in the order of the annotations
_NOTED = ("robust", "adaptive", "operational_noint", "independent", "pd_plus_gravity", "computed_torque")
_NOTES = {
    "robust": Text("ε = {epsilon:.3g}, ρ/ε = {rho_over_epsilon:.3g} 1/s"),
    "adaptive": Text("final payload estimate {payload_estimate:.4g} kg (true {payload:g})"),
    "operational_noint": Text("e_z at rest {steady_z_error_mm:.4g} mm, theory {theory_mm:.4g} mm"),
    "independent": Text("ω = {omega:.3g} rad/s, largest K_P = {largest_K_P:.3g}"),
    "pd_plus_gravity": Text("ω = {omega:.3g} rad/s, e_z at rest {steady_z_error_mm:.4g} mm, theory {theory_mm:.4g} mm"),
    "computed_torque": Text("ω = {omega:.3g} rad/s, e_z at rest {steady_z_error_mm:.4g} mm, theory {theory_mm:.4g} mm"),
}
#: the bindings of :func:`tuning_build`'s traces (by role), of its layout (by dotted path) and of its title, to the
#: outputs of :func:`scara.programs.control.control_program` (the panel's :class:`~scara.plots.panels.PageProgram`)
TUNING_TRACES = {
    **{f"error {name}": {"x": "err_t", "y": "err_y", "visible": Flag(f"{name}_shown")} for name in TUNING_CONTROLLERS},
    "f3": {"x": "t", "y": "f3"}, "τ1": {"x": "t", "y": "tau1"}, "τ2": {"x": "t", "y": "tau2"},
    "τ4": {"x": "t", "y": "tau4"},
    "estimate": {"x": "t", "y": "estimate", "visible": Flag("estimate_shown")},
    "z": {"x": "err_t", "y": "z_norm", "visible": Flag("z_shown")},
    "e_z": {"x": "t", "y": "e_z", "visible": Flag("e_z_shown")},
}
TUNING_PATHS = {
    "yaxis4.visible": Flag("estimate_shown"), "yaxis5.visible": Flag("z_shown"), "yaxis6.visible": Flag("e_z_shown"),
    **{f"annotations.{i}.text": _NOTES[name] for i, name in enumerate(_NOTED)},
    **{f"annotations.{i}.visible": Flag(f"{name}_shown") for i, name in enumerate(_NOTED)},
}
TUNING_TITLE = Text(TUNING_HEAD + "; {duration:.0f} s simulated at {dt_ms:g} ms")


def own_roles(labels) -> tuple:
    """The roles of the error traces that :func:`tuning_own_build` adds for the reader's own controllers
    ``labels``, after :data:`TUNING_ROLES`."""
    return tuple(f"own error {k}" for k in range(len(labels)))


def _own_props(values, label: str) -> dict:
    """The changing properties of the error trace of the reader's controller ``label``: the run's error envelope
    (the outputs ``err_t``, ``err_y`` of the panel's program) when ``values`` are a run of it, else hidden."""
    if values["controller"] != label:
        return {"visible": False}
    return {"x": _value("err_t", values), "y": _value("err_y", values), "visible": True}


def tuning_own_build(values, labels) -> go.Figure:
    """:func:`tuning_build` with one more error trace per controller of the reader's own (``labels``: their names
    in the panel's dropdown, :func:`scara.widgets.control_panel`), after its other traces (roles
    :func:`own_roles`): in black, each with its own dash, the one of the run's controller shown (the seven of
    the panel are hidden for such a run, and its own signal is ``e_z``). :func:`tuning_own_update` updates it."""
    fig = tuning_build(values)
    for k, label in enumerate(labels):
        props = dict(x=_value("err_t", values), y=_value("err_y", values), **_own_props(values, label))
        fig.add_trace(go.Scatter(mode="lines", name=label, line=dict(color=PALETTE["reference"], width=1.8,
                                                                     dash=DASHES[k % len(DASHES)]), **props),
                      row=1, col=1)
    return fig


def tuning_own_update(update: dict, values, labels) -> dict:
    """``update`` (the update of :func:`tuning_build`'s traces for ``values``, by the panel's program) with the
    error traces of :func:`tuning_own_build` (by role, :func:`own_roles`)."""
    traces = dict(update.get("traces") or {})
    traces.update({role: _own_props(values, label) for role, label in zip(own_roles(labels), labels)})
    return dict(update, traces=traces)


def tuning_bindings() -> dict:
    """The bindings of the panel's figure ``"tuning"`` for its :class:`~scara.plots.panels.PageProgram`:
    ``traces``, ``paths`` and ``titles``."""
    return dict(traces={"tuning": TUNING_TRACES}, paths={"tuning": TUNING_PATHS}, titles={"tuning": TUNING_TITLE})
