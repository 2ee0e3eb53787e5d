"""Live panel of chapter 4 (CLIK): choose a method, set the gain of each operational component, the damping,
the null-space gain and the relaxed component; the whole 70 s reference is re-run and redrawn on every move.
Jupyter only."""
from __future__ import annotations

import math

import ipywidgets as ipw
import numpy as np
from plotly.subplots import make_subplots

from .._clik import COMPONENTS, SEED_K, clik, clik2, second_order_gains
from ..plots._common import MAX_POINTS, check_count, envelope, run_colour, run_label, thin
from ..plots.layout import finish_layout, stacked_axes
from ._common import LABEL_STYLE, LivePanel, PanelView, readable, table, trajectory_arg
from ..params import ScaraParams

__all__ = ["clik_panel"]

_METHODS = {"Jacobian inverse": "inverse", "Jacobian transpose": "transpose",
            "pseudo-inverse + null space": "pseudoinverse", "second order": "second_order"}


def clik_panel(traj=None, p=None, points: int = 800) -> LivePanel:
    """Method dropdown; a log slider for each gain ``K_x, K_y, K_z, K_phi`` (1/s; the second-order CLIK uses
    ``K_P = K^2``, ``K_D = 2 K``); damping ``lambda`` (m) of the damped least-squares inverse; null-space gain
    ``k0`` and relaxed component of the pseudo-inverse. Each change re-runs :func:`scara._clik.clik` (or
    ``clik2``) on ``traj`` (default: the 70 s reference of chapter 3) and redraws the position error (log),
    the orientation error and the manipulability, with the summary figures and the run time listed. Settings
    the package refuses (a gain past a stability limit, a run that diverges) are reported in the panel.

    ``points`` (samples per curve) runs from 2 to 10 000 (``scara.plots._common.MAX_POINTS``); outside, or not a
    whole number, or ``traj`` not a Trajectory, raises :class:`ScaraError` before any run."""
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
    p = ScaraParams.resolve(p)
    traj = trajectory_arg(traj, p)
    gain = dict(base=10, min=0.0, max=math.log10(2500.0), step=0.01, continuous_update=False, readout_format=".0f",
                style=LABEL_STYLE)
    controls = {
        "method": ipw.Dropdown(options=list(_METHODS), value="Jacobian inverse", description="method", style=LABEL_STYLE),
        "relaxed": ipw.Dropdown(options=list(COMPONENTS), value="x", description="relaxed (pseudo-inverse)",
                                style=LABEL_STYLE),
        "Kx": ipw.FloatLogSlider(value=SEED_K[0], description="K_x (1/s)", **gain),
        "Ky": ipw.FloatLogSlider(value=SEED_K[1], description="K_y (1/s)", **gain),
        "Kz": ipw.FloatLogSlider(value=SEED_K[2], description="K_z (1/s)", **gain),
        "Kphi": ipw.FloatLogSlider(value=SEED_K[3], description="K_φ (1/s)", **gain),
        "damping": ipw.FloatSlider(value=0.0, min=0.0, max=0.2, step=0.005, readout_format=".3f",
                                   description="damping λ (m)", continuous_update=False, style=LABEL_STYLE),
        "k0": ipw.FloatSlider(value=1.0, min=0.0, max=20.0, step=0.5, description="null-space gain k0 (1/s)",
                              continuous_update=False, style=LABEL_STYLE),
    }

    def compute(method, relaxed, Kx, Ky, Kz, Kphi, damping, k0):
        m = _METHODS[method]
        K = np.array([Kx, Ky, Kz, Kphi])
        if m == "second_order":
            KP, KD = second_order_gains(K)
            r = clik2(traj, KP, KD, p=p, damping=damping)
        elif m == "pseudoinverse":
            r = clik(traj, m, K, p=p, damping=damping, relaxed=relaxed, k0=k0)
        else:
            r = clik(traj, m, K, p=p, damping=damping)
        return dict(method=m, relaxed=relaxed, result=r, summary=r.summary())

    drawn = {}  # set once the figure is built: later runs only need new data, names, colours and title

    def draw(st):
        m, r, s = st["method"], st["result"], st["summary"]
        series = [envelope(r.t, r.position_error, points), envelope(r.t, r.orientation_error, points)]
        idx = thin(len(r.t), points)
        series.append((r.t[idx], r.w[idx]))
        title = f"{run_label(m)}: max ‖e_p‖ after 0.1 s = {s['max_position_error'] * 1e3:.4g} mm"
        colour = run_colour(m)
        if drawn:  # the figure's layout is built: send data, names, colours and the title
            fig = dict(data=[dict(x=x, y=y, name=run_label(r) if k < 2 else "w", line=dict(color=colour, width=1.5))
                             for k, (x, y) in enumerate(series)], title=title)
        else:
            fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.07)
            for k, (x, y) in enumerate(series):
                fig.add_trace(dict(type="scatter", x=x, y=y, mode="lines", name=run_label(r) if k < 2 else "w",
                                   showlegend=k == 0, line=dict(color=colour, width=1.5)), row=k + 1, col=1)
            finish_layout(fig, title, 620)
            stacked_axes(fig, ("‖e_p‖ (m)", "|e_φ| (rad)", "w (m²)"), log=(1, 2))
            drawn["method"] = m
        rows = [("max / RMS position error (mm)",
                 f"{s['max_position_error'] * 1e3:.4g} / {s['rms_position_error'] * 1e3:.4g}"),
                ("max orientation error (mrad)", f"{s['max_orientation_error'] * 1e3:.4g}"),
                ("min / mean manipulability (m²)", f"{s['min_manipulability']:.4f} / {s['mean_manipulability']:.4f}"),
                ("compiled loop (ms)", f"{s['run_time'] * 1e3:.1f}")]
        if m == "pseudoinverse":
            drift = np.abs(r.e[:, COMPONENTS.index(st["relaxed"])]).max()
            rows.append((f"drift of the relaxed {st['relaxed']} (max)", f"{drift:.4g}"))
        notes = []
        if s["max_position_error"] > 1e-3:
            notes.append(f"The tip strays up to {s['max_position_error'] * 1e3:.3g} mm from the path: "
                         "raise the gains (within the stability limit) to follow it more closely.")
        return PanelView([fig], table(rows), notes)

    def explain(exc, values):
        gains = ", ".join(f"{name} = {values[key]:.4g} 1/s" for key, name in
                          (("Kx", "K_x"), ("Ky", "K_y"), ("Kz", "K_z"), ("Kphi", "K_φ")))
        return f"{values['method']} with {gains}: {readable(str(exc))}"

    return LivePanel(controls, compute, draw, explain=explain, title="CLIK on the 70 s reference: tune and watch", columns=2)
