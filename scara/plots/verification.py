"""Figures of the verification appendix: speed side by side with other libraries, and the rotor coupling
that those libraries leave out. Data in (the stored ``benchmarks/results.json``, time series), figures out."""
from __future__ import annotations

import numpy as np
import plotly.graph_objects as go

from ..errors import check_count
from ._common import DASHES, JOINT_COLOURS, JOINT_UNITS, slider, thin
from ._common import MAX_POINTS, FIGURE_BUDGET
from .layout import finish_layout

__all__ = ["IMPLEMENTATION_COLOURS", "PER_CALL_TASKS", "RUN_TASKS", "speed_figure", "rotor_coupling_figure"]

#: one colour per implementation compared in the appendix (Okabe-Ito, as the rest of the book)
IMPLEMENTATION_COLOURS = {
    "ours": "#0072B2",
    "ours (kernel)": "#56B4E9",
    "numpy": "#999999",
    "pinocchio": "#E69F00",
    "toolbox": "#D55E00",
    "mujoco": "#009E73",
}
#: (key in results["per_call"], label, slider label)
PER_CALL_TASKS = (
    ("fkine", "forward kinematics", "FK"),
    ("jacobian", "Jacobian", "J"),
    ("inertia", "inertia matrix B(q)", "B"),
    ("inverse_dynamics", "inverse dynamics", "ID"),
    ("forward_dynamics", "forward dynamics", "FD"),
)
#: (key in results, label, slider label)
RUN_TASKS = (
    ("clik", "70 s CLIK (Jacobian inverse)", "CLIK"),
    ("closed_loop", "70 s closed loop (PD + gravity, RK4)", "loop"),
)


def _fmt(seconds: float) -> str:
    if seconds < 1e-3:
        return f"{seconds * 1e6:.2g} µs"
    if seconds < 1.0:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds:.3g} s"


def _ratio(r: float) -> str:
    """A ratio to ours: three significant digits, whole numbers from 100 up (1701, not 1.7e+03)."""
    return f"{r:.0f}" if r >= 100 else f"{r:.3g}"


def speed_figure(results: dict, height: int = 460) -> go.Figure:
    """Bar chart of the stored timings, one slider step per task (five per-call costs, two 70 s runs).

    Each bar is a median time (log scale) and carries the ratio to our public function or our whole run;
    extrapolated library runs are marked ≈ (and say so on hover); an implementation has a bar where ``results``
    holds it (MuJoCo: the closed loop only). Slider labels: FK, J, B, ID, FD (one call each), CLIK and loop (the 70 s runs).
    ``results`` is the dict of ``benchmarks/results.json``.
    """
    fig = go.Figure()
    tasks = []
    for key, label, short in PER_CALL_TASKS:
        e = results["per_call"][key]
        names = [n for n in IMPLEMENTATION_COLOURS if n in e]
        secs = [e[n]["us"] * 1e-6 for n in names]
        text = [f"{_fmt(s)}<br>{e[n]['ratio_to_ours']:.2g}× ours" for n, s in zip(names, secs)]
        hover = [f"{n}: {e[n]['call']}" for n in names]
        tasks.append((label + ", one call", short, names, secs, text, hover, "time per call (s, log)"))
    for key, label, short in RUN_TASKS:
        e = results[key]
        names = [n for n in ("ours", "numpy", "pinocchio", "toolbox", "mujoco") if n in e]
        secs = [e[n]["seconds"] for n in names]
        text = []
        for n, s in zip(names, secs):   # ≈: extrapolated (a third line would shrink the label at 390 px)
            text.append(f"{'≈' if e[n].get('extrapolated') else ''}{_fmt(s)}<br>{_ratio(e[n]['ratio_to_ours'])}× ours")
        hover = [f"{n}: {e[n]['call']}" + (" (extrapolated)" if e[n].get("extrapolated") else "") for n in names]
        tasks.append((label, short, names, secs, text, hover, "time for the run (s, log)"))

    for i, (label, _, names, secs, text, hover, _) in enumerate(tasks):
        fig.add_trace(go.Bar(
            x=names, y=secs, text=text, textposition="outside", hovertext=hover, hoverinfo="text",
            marker_color=[IMPLEMENTATION_COLOURS[n] for n in names], name=label, visible=(i == 0),
            showlegend=False, cliponaxis=False, constraintext="none",   # full-size labels at 390 px too
        ))
    def yrange(secs):
        return [float(np.log10(min(secs))) - 0.6, float(np.log10(max(secs))) + 0.9]

    steps = []
    for i, (label, short, _, secs, _, _, ytitle) in enumerate(tasks):
        vis = [j == i for j in range(len(tasks))]
        steps.append(dict(label=short, method="update",
                          args=[{"visible": vis}, {"yaxis.title.text": ytitle, "yaxis.range": yrange(secs),
                                                   "title.text": f"Speed: {label}"}]))
    finish_layout(fig, f"Speed: {tasks[0][0]}", height, sliders=[slider(steps, "task: ", pad_top=95)])
    fig.update_layout(margin=dict(l=70, r=20, b=40), showlegend=False)
    fig.update_yaxes(type="log", range=yrange(tasks[0][3]), title_text=tasks[0][6])
    fig.update_xaxes(title_text="implementation (median)", title_standoff=8)   # fits its axis at 390 px
    fig.for_each_trace(lambda tr: tr.update(x=[n.replace(" (", "<br>(") for n in tr.x]))
    return fig


def rotor_coupling_figure(t, coupling_torque, torque, max_points: int = 2000, height: int = 460) -> go.Figure:
    """The torque ``Delta_B qdd`` that the libraries' diagonal rotor model leaves out, along a motion.

    ``t`` (N,) s; ``coupling_torque`` and ``torque`` (N, 4) (N m, N for the quill). One trace per joint,
    decimated to about ``max_points`` samples; the legend gives each joint's largest share of its torque.

    Limits: ``max_points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole
    number, raises :class:`ScaraError` before any work.
    """
    max_points = check_count(max_points, "max_points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    t = np.asarray(t)
    d = np.asarray(coupling_torque)
    tau = np.asarray(torque)
    idx = thin(len(t), max_points)
    fig = go.Figure()
    for j in range(4):
        share = np.max(np.abs(d[:, j])) / max(np.max(np.abs(tau[:, j])), 1e-300)
        fig.add_trace(go.Scatter(x=t[idx], y=d[idx, j], mode="lines",
                                 line=dict(color=JOINT_COLOURS[j], width=1.8, dash=DASHES[j]),
                                 name=f"joint {j + 1} ({JOINT_UNITS[j]}): up to {100 * share:.2f} % of |τ|"))
    finish_layout(fig, "Rotor coupling torque ΔB q̈ (5 kg payload)", height)
    fig.update_xaxes(title_text="time t (s)")
    fig.update_yaxes(title_text="ΔB q̈ (N m; N for joint 3)")
    return fig
