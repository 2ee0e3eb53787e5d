"""Figures of chapter 7 (interaction with the environment): the normal force and the penetration of the laws
during the approach and the pressing, the steady force of compliance control against the surface's stiffness
(a static slider over the gain: formula and simulation on one figure), and the peg-in-hole animation.

Data in (runs of :func:`scara.interaction.simulate_contact`, the dicts of :func:`scara.interaction.stiffness_sweep`
and :func:`scara.interaction.peg_frames`), ``go.Figure`` out; nothing is computed here beyond unit changes.
"""
from __future__ import annotations

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..errors import ScaraError, check_count
from ._common import FIGURE_BUDGET, MAX_POINTS, MAX_STEPS, PALETTE, as_list, f32, slider, thin
from .animation import FRAME_MS, _BOTTOM, _frames, _moved, play_controls
from .layout import finish_layout, stacked_axes

__all__ = ["INTERACTION_LABELS", "INTERACTION_COLOURS", "INTERACTION_DASHES", "contact_force_figure",
           "stiffness_slider_figure", "peg_animation"]

#: legend names of the interaction laws (keys: the controllers' ``name``)
INTERACTION_LABELS = {"compliance": "compliance", "impedance": "impedance", "admittance": "admittance",
                      "force": "force (inner position loop)", "parallel": "parallel force/position"}
#: one Okabe-Ito colour per law, the same in every figure of the chapter
INTERACTION_COLOURS = {"compliance": "#0072B2", "impedance": "#E69F00", "admittance": "#009E73",
                       "force": "#D55E00", "parallel": "#CC79A7"}
#: one dash style per law, so that the curves stay apart in greyscale
INTERACTION_DASHES = {"compliance": "solid", "impedance": "dash", "admittance": "dot", "force": "dashdot",
                      "parallel": "longdash"}


def _law(run) -> str:
    name = getattr(run, "controller", None)
    if getattr(run, "force", None) is None or not isinstance(name, str):
        raise ScaraError(f"a figure of chapter 7 needs runs of simulate_contact, got {type(run).__name__}")
    return name


def contact_force_figure(runs: dict, target: float | None = None, points: int = 1000, title: str | None = None,
                         height: int = 560) -> go.Figure:
    """The normal force ``-h_z`` (N, top) and the penetration ``z_s - p_z`` (mm, bottom: negative above the
    surface) over time for each run of ``runs`` (``{label: ContactResult}``), each law in its colour and dash
    style; ``target`` (N, optional) draws the force the runs aim at as a dotted line.

    Limits: at most 8 runs; ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); more, or not a
    whole number, raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    if not isinstance(runs, dict) or not runs:
        raise ScaraError(f"runs must be a non-empty dict {{label: run of simulate_contact}}, got {runs!r:.80}")
    check_count(len(runs), "len(runs)", 1, 8, "runs", "one legend a phone-width page can read")
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08, row_heights=[0.55, 0.45])
    for label, r in runs.items():
        law = _law(r)
        idx = thin(len(r.t), points)
        style = dict(color=INTERACTION_COLOURS.get(law, PALETTE["reference"]), width=2,
                     dash=INTERACTION_DASHES.get(law, "solid"))
        fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(r.normal_force[idx]), mode="lines", name=str(label),
                                 legendgroup=str(label), line=style), row=1, col=1)
        fig.add_trace(go.Scatter(x=f32(r.t[idx]), y=f32(1e3 * (r.surface.height - r.x[idx, 2])), mode="lines",
                                 name=f"{label} · penetration", legendgroup=str(label), showlegend=False,
                                 line=style), row=2, col=1)
    if target is not None:
        t_end = max(float(r.t[-1]) for r in runs.values())
        fig.add_trace(go.Scatter(x=[0.0, t_end], y=[float(target)] * 2, mode="lines", name=f"{float(target):g} N",
                                 line=dict(color=PALETTE["reference"], width=1.2, dash="dot")), row=1, col=1)
    finish_layout(fig, title or "Approach and pressing", height)
    return stacked_axes(fig, ("−h_z (N)", "z_s − p_z (mm)"))


def stiffness_slider_figure(sweep: dict, depth: float, title: str = "Steady force of compliance control",
                            height: int = 560) -> go.Figure:
    """The steady normal force (N) against the surface's stiffness ``k_e`` (N/m, log axis) of compliance control
    held ``depth`` m below the surface: the formula's curve and the simulated runs (markers) of
    :func:`scara.interaction.stiffness_sweep`, one gain ``K_P,z`` at a time (a static slider, plotly steps), with
    the two limits of the formula, ``K_P,z depth`` (a stiff surface, dotted) and ``k_e depth`` (a stiff tool,
    dashed); each step scales the force axis to its gain (up to 1.15 ``K_P,z depth``).

    Limits: at most 121 gains (``MAX_STEPS``); a sweep without its keys raises :class:`ScaraError`."""
    keys = ("gains", "stiffness", "simulated", "dense", "dense_formula")
    if not isinstance(sweep, dict) or any(k not in sweep for k in keys):
        raise ScaraError(f"sweep must be the dict of stiffness_sweep, with the keys {keys}")
    gains = np.asarray(sweep["gains"], dtype=float)
    check_count(gains.size, "the sweep's gains", 1, MAX_STEPS, "slider steps", FIGURE_BUDGET)
    fig = go.Figure()
    dense = np.asarray(sweep["dense"])
    per = 4
    for i, kp in enumerate(gains):
        shown = i == 0
        fig.add_trace(go.Scatter(x=as_list(dense, 1), y=as_list(sweep["dense_formula"][i]), mode="lines",
                                 name="formula", visible=shown, line=dict(color="#0072B2", width=2)))
        fig.add_trace(go.Scatter(x=as_list(sweep["stiffness"], 1), y=as_list(sweep["simulated"][i]),
                                 mode="markers", name="simulation", visible=shown,
                                 marker=dict(color="#D55E00", size=9, symbol="circle-open", line=dict(width=2))))
        fig.add_trace(go.Scatter(x=as_list(dense[[0, -1]], 1), y=[round(kp * depth, 4)] * 2, mode="lines",
                                 name="K_P,z · depth", visible=shown,
                                 line=dict(color=PALETTE["reference"], width=1.2, dash="dot")))
        fig.add_trace(go.Scatter(x=as_list(dense, 1), y=as_list(dense * depth), mode="lines", name="k_e · depth",
                                 visible=shown, line=dict(color="#999999", width=1.2, dash="dash")))
    n = len(fig.data)
    titles = [f"{title}<br>K_P,z = {kp:g} N/m, {1e3 * depth:g} mm deep" for kp in gains]
    # each gain on its own scale: up to a little above its stiff-surface limit K_P,z depth
    tops = [round(1.15 * float(kp) * depth, 4) for kp in gains]
    steps = [dict(label=f"{kp:g}", method="update",
                  args=[{"visible": [per * i <= j < per * (i + 1) for j in range(n)]},
                        {"title.text": titles[i], "yaxis.range": [0.0, tops[i]]}])
             for i, kp in enumerate(gains)]
    finish_layout(fig, titles[0], height, bottom=130)
    # the slider's readout clear of the axis title under the log ticks (10^4 stands taller than a tick)
    fig.update_layout(sliders=[slider(steps, "K_P,z (N/m) = ", pad_top=56)])
    fig.update_xaxes(type="log", exponentformat="power", title_text="k_e (N/m)")
    fig.update_yaxes(title_text="−h_z at rest (N)", range=[0.0, tops[0]])
    return fig


def peg_animation(frames: dict, scale: float = 0.5, title: str = "Peg in hole (side view)",
                  height: int = 640) -> go.Figure:
    """The peg-in-hole run of :func:`scara.interaction.peg_frames`, seen from the side in the vertical plane
    through the hole's axis and the peg's start (mm from the hole's axis, mm above the surface; the two axes at
    different scales): the surface, the hole's walls and bottom, the peg, and the force the environment exerts
    on the peg, ``-h_e``, as an arrow from its end (``scale`` mm per N); under it the normal force ``-h_z`` (N)
    over time with a marker at the frame's time. Play/Pause buttons and a time slider (a static page).

    Limits: 2 to 1000 frames; frames without their keys raise :class:`ScaraError`."""
    keys = ("t", "tip", "top", "force", "centre", "hole_radius", "peg_radius", "height", "bottom")
    if not isinstance(frames, dict) or any(k not in frames for k in keys):
        raise ScaraError(f"frames must be the dict of peg_frames, with the keys {keys}")
    t = np.asarray(frames["t"], dtype=float)
    check_count(t.size, "the frames", 2, 1000, "animation frames", FIGURE_BUDGET)
    if not (isinstance(scale, (int, float)) and np.isfinite(scale) and scale > 0):
        raise ScaraError(f"scale = {scale!r} mm per N must be a positive number")
    tip = np.asarray(frames["tip"], dtype=float)
    force = np.asarray(frames["force"], dtype=float)
    centre = np.asarray(frames["centre"], dtype=float)
    off = tip[0, :2] - centre
    u = off / np.linalg.norm(off) if np.linalg.norm(off) > 0 else np.array([1.0, 0.0])
    s = 1e3 * (tip[:, :2] - centre) @ u                       # mm along the plane, from the hole's axis
    z = 1e3 * (tip[:, 2] - frames["height"])                  # mm above the surface
    length = 1e3 * float(np.asarray(frames["top"])[0, 2] - tip[0, 2])
    fs = -force[:, :2] @ u                                    # the environment's push on the peg, in the plane
    fz = -force[:, 2]
    R, r, depth = 1e3 * frames["hole_radius"], 1e3 * frames["peg_radius"], 1e3 * (frames["height"] - frames["bottom"])
    width = R + 3 * r
    fig = make_subplots(rows=2, cols=1, vertical_spacing=0.14, row_heights=[0.68, 0.32])
    solid = dict(color=PALETTE["arm"], width=3)
    fig.add_trace(go.Scatter(x=as_list([-width, -R, -R, R, R, width]), y=as_list([0, 0, -depth, -depth, 0, 0]),
                             mode="lines",
                             name="surface and hole", line=solid), row=1, col=1)

    def peg(k):
        x0, x1, z0 = s[k] - r, s[k] + r, z[k]
        return [round(v, 4) for v in (x0, x1, x1, x0, x0)], [round(v, 4) for v in (z0, z0, z0 + length,
                                                                                   z0 + length, z0)]

    def arrow(k):
        return [round(s[k], 4), round(s[k] + scale * fs[k], 4)], [round(z[k], 4), round(z[k] + scale * fz[k], 4)]

    px, pz = peg(0)
    fig.add_trace(go.Scatter(x=px, y=pz, mode="lines", fill="toself", name="peg",
                             line=dict(color="#0072B2", width=2), fillcolor="rgba(0,114,178,0.25)"), row=1, col=1)
    ax, az = arrow(0)
    fig.add_trace(go.Scatter(x=ax, y=az, mode="lines+markers", name=f"−h_e ({scale:g} mm/N)",
                             line=dict(color="#D55E00", width=3),
                             marker=dict(symbol="arrow", angleref="previous", size=[0, 12], color="#D55E00")),
                  row=1, col=1)
    fig.add_trace(go.Scatter(x=f32(t), y=f32(fz), mode="lines", name="−h_z (N)", showlegend=False,
                             line=dict(color="#D55E00", width=1.5)), row=2, col=1)
    fig.add_trace(go.Scatter(x=[round(t[0], 3)], y=[round(fz[0], 3)], mode="markers", name="now",
                             showlegend=False, marker=dict(color="#D55E00", size=9)), row=2, col=1)
    data = []
    for k in range(t.size):
        data.append([_moved(*peg(k)), _moved(*arrow(k)), _moved([round(t[k], 3)], [round(fz[k], 3)])])
    fig.frames = _frames(data, [1, 2, 4])
    low = min(-depth - 3.0, float(np.min(z + scale * np.minimum(fz, 0.0))) - 2.0)
    high = float(np.max(z)) + length + 2.0
    fig.update_xaxes(range=[-width, width], title_text="across the hole (mm)", row=1, col=1)
    fig.update_yaxes(range=[low, high], title_text="height (mm)", row=1, col=1)
    fig.update_xaxes(title_text="t (s)", row=2, col=1)
    fig.update_yaxes(title_text="−h_z (N)", row=2, col=1)
    finish_layout(fig, title, height, bottom=_BOTTOM)
    # the peg is a filled shape, which plotly redraws only on a full redraw
    fig.update_layout(**play_controls(t, redraw=True, duration=FRAME_MS))
    return fig
