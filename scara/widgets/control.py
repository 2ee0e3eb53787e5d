"""Live tuning panel of chapter 6: choose a controller, move its gains, the independent-joint pole ``omega``,
the robust term's ``rho`` and ``epsilon``, the adaptation weight ``K_pi``, the integral gain ``K_I`` and the true
payload; the whole 70 s run is re-simulated (about 0.1 s) and redrawn at once. Jupyter only."""
from __future__ import annotations

import re

import ipywidgets as ipw
import numpy as np

from ..control import (
    AdaptiveController, IndependentJointController, OperationalSpaceController, RobustController, control_summary,
)
from ..plots._common import MAX_POINTS, check_count, run_colour, run_label
from ..plots.control import tuning_figure, tuning_series, tuning_signal, tuning_title
from ._common import LABEL_STYLE, LivePanel, PanelView, readable, start_value, trajectory_arg
from ..params import ScaraParams

__all__ = ["control_panel"]

_CONTROLLERS = ("robust", "adaptive (Slotine-Li)", "operational ID + integral", "operational ID, no integral",
                "independent joint PID")
#: which controls each controller reads (the others are greyed out)
_USES = {
    "robust": {"K_P", "K_D", "Lambda", "rho", "epsilon"},
    "adaptive (Slotine-Li)": {"Lambda", "K_D_scale", "K_pi"},
    "operational ID + integral": {"K_P", "K_D", "K_I"},
    "operational ID, no integral": {"K_P", "K_D"},
    "independent joint PID": {"omega"},
}


def _log(value, lo, hi, desc, fmt=".3g"):
    return ipw.FloatLogSlider(value=value, base=10, min=np.log10(lo), max=np.log10(hi), step=0.01,
                              description=desc, readout_format=fmt, continuous_update=False, style=LABEL_STYLE)


def make_controller(controller: str, K_P, K_D, Lambda, rho, epsilon, K_D_scale, K_pi, K_I, omega=30.0):
    """The controller the panel's settings describe (the panel's own mapping, exposed for tests)."""
    if controller.startswith("independent"):
        return IndependentJointController(omega=omega)
    if controller == "robust":
        return RobustController(K_P=K_P, K_D=K_D, rho=rho, epsilon=epsilon, Lambda=Lambda)
    if controller.startswith("adaptive"):
        return AdaptiveController(Lambda=Lambda, K_D=K_D_scale * np.array([600.0, 300.0, 1000.0, 60.0]),
                                  K_pi={"m3": K_pi})
    return OperationalSpaceController(integral=controller == "operational ID + integral", K_P=K_P, K_D=K_D, K_I=K_I)


def control_panel(traj=None, p=None, payload: float = 5.0, points: int = 600) -> LivePanel:
    """Controller dropdown and sliders: the pole ``omega`` (rad/s) of the independent-joint PID (the triple pole of
    every joint's nominal loop), ``K_P`` (1/s^2) and ``K_D`` (1/s) of the robust and operational laws,
    ``Lambda`` (1/s) of the robust and adaptive laws, ``rho`` (m/s^2) and ``epsilon`` of the robust term, a scale of
    the adaptive ``K_D`` (times the book's ``(600, 300, 1000, 60)``), the adaptation weight ``K_pi`` of the
    lumped mass ``m3``, ``K_I`` (1/s^3), and the true payload (kg) of the plant (the controllers never know it).
    Each change re-runs the 70 s reference (``traj``, default the reference of chapter 3; the joint reference of
    ``clik2`` is computed once) and redraws the error, the torques and the controller's own signal. Settings the
    package refuses (non-positive gains, ``Lambda >= K_D``, an unstable integral, a run that diverges or breaks a
    bound) are reported in the panel with the time and cause.

    ``payload`` must lie in the slider's range 0 to 10 kg and ``points`` (samples per curve) from 2 to 10 000
    (``scara.plots._common.MAX_POINTS``); outside, or not a number, or ``traj`` not a Trajectory, raises
    :class:`ScaraError` before any run."""
    payload = start_value(payload, 0.0, 10.0, "payload", "kg")
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
    p = ScaraParams.resolve(p)
    traj = trajectory_arg(traj, p)
    from .._clik import clik2  # noqa: PLC0415

    jref = clik2(traj, p=p)
    controls = {
        "controller": ipw.Dropdown(options=_CONTROLLERS, value="robust", description="controller", style=LABEL_STYLE),
        "payload": ipw.FloatSlider(value=payload, min=0.0, max=10.0,
                                   step=0.5, description="true payload m_L (kg)", continuous_update=False,
                                   style=LABEL_STYLE),
        "K_P": _log(900.0, 10.0, 1e5, "K_P (1/s²)", ".0f"),
        "K_D": _log(60.0, 2.0, 3000.0, "K_D (1/s)", ".1f"),
        "Lambda": _log(30.0, 1.0, 300.0, "Λ (1/s)", ".1f"),
        "rho": _log(20.0, 0.1, 200.0, "ρ (m/s²)", ".3g"),
        "epsilon": _log(0.05, 1e-3, 1.0, "ε (boundary layer)", ".3g"),
        "K_D_scale": _log(1.0, 0.05, 20.0, "adaptive K_D (× book)", ".2f"),
        "K_pi": _log(0.01, 1e-5, 10.0, "K_π (weight of m3)", ".2e"),
        "K_I": _log(8000.0, 10.0, 1e6, "K_I (1/s³)", ".0f"),
        "omega": _log(30.0, 1.0, 300.0, "ω, independent joint (rad/s)", ".3g"),
    }

    def grey(change=None):
        used = _USES[controls["controller"].value]
        for key, w in controls.items():
            if key not in ("controller", "payload"):
                w.disabled = key not in used

    controls["controller"].observe(grey, names="value")
    grey()

    def compute(controller, payload, K_P, K_D, Lambda, rho, epsilon, K_D_scale, K_pi, K_I, omega):
        c = make_controller(controller, K_P, K_D, Lambda, rho, epsilon, K_D_scale, K_pi, K_I, omega)
        plant = p.with_payload(float(payload))
        res = c.run(traj, plant, joint_reference=jref if c.reference_kind == "joint" else None)
        return dict(controller=c, plant=plant, payload=payload, result=res, summary=control_summary(res))

    drawn = {}  # the first figure's signal axis: later runs only need new data, names, colours and title

    def draw(st):
        c, res, s, payload = st["controller"], st["result"], st["summary"], st["payload"]
        extra = f"70 s simulated in {1e3 * res.elapsed:.0f} ms (compiled loop)"
        if c.name == "robust":
            extra += f"; ε = {c.epsilon:.3g}, ρ/ε = {c.rho / c.epsilon:.3g} 1/s"
        elif c.name == "adaptive":
            extra += f"; final payload estimate {res.payload_estimate[-1]:.4g} kg (true {payload:g})"
        elif c.name == "independent":
            extra += f"; ω = {c.omega[0]:.3g} rad/s, largest K_P = {c.K_P.max():.3g}"
        elif c.name == "operational_noint":
            theory = c.steady_state_error(st["plant"], res.q[-1])[2]
            extra += f"; e_z at rest {1e3 * s['final_error_z']:.4g} mm, theory {1e3 * theory:.4g} mm"
        notes = []
        if s["final_error"] > 1e-3:
            notes.append(f"At rest the tool stays {1e3 * s['final_error']:.3g} mm from its target: "
                         "the payload's weight is not fully compensated.")
        if drawn:  # the figure's layout is built: send data, names, colours, the signal's axis and the title
            data = [dict(x=x, y=y) for x, y in tuning_series(res, points)]
            name, colour, log = tuning_signal(res)
            data[0].update(name=run_label(res), line=dict(color=run_colour(res), width=1.8))
            data[5].update(name=name, line=dict(color=colour, width=1.5))
            axis = dict(drawn["signal_axis"], type="log" if log else "linear", title=dict(text=name))
            fig = dict(data=data, title=tuning_title(res, s, extra), layout={drawn["signal_axis_key"]: axis})
        else:
            fig = tuning_figure(res, s, extra, points=points)
            key = fig.data[5].yaxis.replace("y", "yaxis")
            drawn.update(signal_axis_key=key, signal_axis=fig.layout[key].to_plotly_json())
        return PanelView([fig], "", notes)

    def explain(exc, values):
        # the panel gives every joint or component the same gain: name the gain, not its first entry
        return readable(re.sub(r"\[0\]", "", str(exc)))

    return LivePanel(controls, compute, draw, explain=explain, title="Chapter 6: tune a controller on the 70 s run", columns=2)
