"""Live panel of chapter 4 (CLIK): choose a method, set the gain of each operational component, the damping,
the null-space gain and the relaxed component; the whole 70 s reference is re-run and redrawn on every move.
Jupyter only."""
from __future__ import annotations

import numpy as np

from .._clik import COMPONENTS, SEED_K
from ..errors import check_count
from ..plots._common import FIGURE_BUDGET, MAX_POINTS
from ..plots.clik import METHOD_CHOICES, clik_pair, run_method
from ..plots.panels import Control, Panel
from ._common import LivePanel, readable, trajectory_arg
from ..params import ScaraParams

__all__ = ["clik_panel", "clik_declaration"]

#: the method dropdown's labels and the method each runs (:data:`scara.plots.clik.METHOD_CHOICES`)
_METHODS = METHOD_CHOICES
#: the gain sliders: control name, the gain's name in a message, its label
_GAINS = (("Kx", "K_x", "K_x (1/s)"), ("Ky", "K_y", "K_y (1/s)"), ("Kz", "K_z", "K_z (1/s)"),
          ("Kphi", "K_φ", "K_φ (1/s)"))


def clik_declaration(traj=None, p=None, points: int = 800) -> Panel:
    """The CLIK panel as data (:class:`~scara.plots.panels.Panel`); see :func:`clik_panel`."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    p = ScaraParams.resolve(p)
    traj = trajectory_arg(traj, p)
    pseudo = tuple(label for label, m in METHOD_CHOICES.items() if m == "pseudoinverse")
    damped = tuple(label for label, m in METHOD_CHOICES.items() if m != "transpose")  # the transpose solves nothing
    gains = tuple(Control(name, "slider", label, float(k), 1.0, 2500.0, 0.01, scale="log", unit="1/s", readout=".0f")
                  for (name, _, label), k in zip(_GAINS, SEED_K))
    controls = (Control("method", "dropdown", "method", "Jacobian inverse", options=tuple(METHOD_CHOICES)),
                Control("relaxed", "dropdown", "relaxed (pseudo-inverse)", "x", options=tuple(COMPONENTS),
                        applies_to=pseudo),
                *gains,
                Control("damping", "slider", "damping λ (m)", 0.0, 0.0, 0.2, 0.005, unit="m", readout=".3f",
                        applies_to=damped),
                Control("k0", "slider", "null-space gain k0 (1/s)", 1.0, 0.0, 20.0, 0.5, unit="1/s",
                        applies_to=pseudo))

    def compute(v):
        m = METHOD_CHOICES[v["method"]]
        K = np.array([v["Kx"], v["Ky"], v["Kz"], v["Kphi"]])
        damping = v["damping"] if v["method"] in damped else 0.0  # a greyed-out control is not read
        r = run_method(traj, m, K, p=p, damping=damping, relaxed=v["relaxed"], k0=v["k0"])
        return dict(method=m, relaxed=v["relaxed"], result=r, summary=r.summary())

    def summary(st):
        m, r, s = st["method"], st["result"], st["summary"]
        rows = [("max / RMS position error (mm)",
                 f"{s['max_position_error'] * 1e3:.4g} / {s['rms_position_error'] * 1e3:.4g}"),
                ("max orientation error (mrad)", f"{s['max_orientation_error'] * 1e3:.4g}"),
                ("min / mean manipulability (m²)", f"{s['min_manipulability']:.4f} / {s['mean_manipulability']:.4f}"),
                ("compiled loop (ms)", f"{s['elapsed'] * 1e3:.1f}")]
        if m == "pseudoinverse":
            drift = np.abs(r.e[:, COMPONENTS.index(st["relaxed"])]).max()
            rows.append((f"drift of the relaxed {st['relaxed']} (max)", f"{drift:.4g}"))
        notes = []
        if s["max_position_error"] > 1e-3:
            notes.append(f"The tip strays up to {s['max_position_error'] * 1e3:.3g} mm from the path: "
                         "raise the gains (within the stability limit) to follow it more closely.")
        return rows, notes

    def explain(exc, values):
        named = ", ".join(f"{name} = {values[key]:.4g} 1/s" for key, name, _ in _GAINS)
        return f"{values['method']} with {named}: {readable(str(exc))}"

    return Panel("CLIK", "CLIK on the 70 s reference: tune and watch", controls, compute, (clik_pair(points),),
                 summary, explain, selector="method")


def clik_panel(traj=None, p=None, points: int = 800) -> LivePanel:
    """Method dropdown; a log slider for each gain ``K_x, K_y, K_z, K_phi`` (1/s; the second-order CLIK uses
    ``K_P = K^2``, ``K_D = 2 K``); damping ``lambda`` (m) of the damped least-squares inverse; null-space gain
    ``k0`` and relaxed component of the pseudo-inverse (greyed out for the other methods). Each change re-runs
    :func:`scara._clik.clik` (or ``clik2``, :func:`scara.plots.clik.run_method`) on ``traj`` (default: the 70 s
    reference of chapter 3) and redraws the position error (log), the orientation error and the manipulability,
    with the summary figures and the run time listed. Settings the package refuses (a gain past a stability
    limit, a run that diverges) are reported in the panel.

    ``points`` (samples per curve) runs from 2 to 10 000 (``scara.plots._common.MAX_POINTS``); outside, or not a
    whole number, or ``traj`` not a Trajectory, raises :class:`ScaraError` before any run. Its ``declaration``
    is :func:`clik_declaration`."""
    return LivePanel(clik_declaration(traj, p, points))
