"""Live panel of chapter 5 (dynamics): choose the payload and the configuration and watch ``B(q)``, its
eigenvalues and the gravity load change; optionally hold the arm with PD plus gravity and see the quill sag
that the unknown payload causes. Jupyter only."""
from __future__ import annotations

import math

import ipywidgets as ipw
import numpy as np

from ..dynamics import gravity, inertia
from ..errors import ScaraError, as_vector, check_positive
from ..plots.dynamics import inertia_figure
from .._simulate import PDGravityController
from ._common import LABEL_STYLE, LivePanel, PanelView, angle_slider, start_value, stroke_slider, table
from ..params import ScaraParams

__all__ = ["dynamics_panel"]

#: a quill sag above this (m) is flagged in the panel
_SAG_NOTE = 0.003


def dynamics_panel(payload: float = 5.0, q=(0.0, -math.pi / 2, 0.5, 0.0), K_P3: float = 10000.0,
                   p=None) -> LivePanel:
    """Sliders for the payload mass (kg), theta1, theta2, theta4 (degrees), d3 (m) and the PD gain ``K_P3``
    (N/m); redraws ``B(q)`` with the make-up of its diagonal and lists its eigenvalues, ``g(q)`` and the
    quill's steady-state sag ``m_L g0 / K_P3`` under PD plus gravity with a payload-free model.
    Only theta2 and the payload change ``B``: moving the other sliders shows it."""
    p = ScaraParams.resolve(p)
    q = as_vector(q, "q")
    controls = {
        "payload": ipw.FloatSlider(value=start_value(payload, 0.0, 20.0, "payload", "kg"), min=0.0, max=20.0,
                                   step=0.5, description="payload m_L (kg)", continuous_update=False, style=LABEL_STYLE),
        "theta1": angle_slider(q[0], "theta1", "θ1 (°)"),
        "theta2": angle_slider(q[1], "theta2", "θ2 (°)"),
        "d3": stroke_slider(q[2], p),
        "theta4": angle_slider(q[3], "theta4", "θ4 (°)"),
        "K_P3": ipw.FloatLogSlider(value=start_value(K_P3, 100.0, 1e6, "K_P3", "N/m"), base=10, min=2, max=6,
                                   step=0.1, description="K_P3 (N/m)", continuous_update=False, style=LABEL_STYLE),
    }

    def compute(payload, theta1, theta2, d3, theta4, K_P3):
        robot = p.with_payload(check_positive(payload, "payload", strict=False))
        qq = np.array([math.radians(theta1), math.radians(theta2), d3, math.radians(theta4)])
        ctrl = PDGravityController(K_P=(1.0, 1.0, check_positive(K_P3, "K_P3"), 1.0), model=p.with_payload(0.0))
        sag = -ctrl.steady_state_error(robot)[2]
        if d3 + sag > p.d3_max:
            raise ScaraError(f"with K_P3 = {K_P3:.3g} N/m the {payload:g} kg payload would sag {sag * 1e3:.1f} mm "
                             f"under PD + gravity: the quill, at d3 = {d3:.2f} m, would need d3 = {d3 + sag:.3f} m, "
                             f"past the end of its stroke (d3_min to d3_max = {p.d3_min:g} to {p.d3_max:g} m). "
                             "Raise K_P3 or lighten the payload.")
        B = inertia(qq, robot)
        return dict(q=qq, robot=robot, payload=payload, theta2=theta2, K_P3=K_P3, B=B,
                    eig=np.linalg.eigvalsh(B), g=gravity(qq, robot), sag=sag)

    def draw(s):
        fig = inertia_figure(s["q"], s["robot"], f"B(q) with a {s['payload']:g} kg payload at θ2 = {s['theta2']:.0f}°")
        eig, sag = s["eig"], s["sag"]
        rows = [("eigenvalues of B", ", ".join(f"{v:.4g}" for v in eig)),
                ("condition number of B", f"{eig[-1] / eig[0]:.1f}"),
                ("gravity torques g(q) (N m, N m, N, N m)", ", ".join(f"{v:.4g}" for v in s["g"])),
                ("quill sag under PD + gravity (payload-free model)", f"{sag * 1e3:.3f} mm = m_L g0 / K_P3")]
        notes = []
        if sag > _SAG_NOTE:
            notes.append(f"The quill sags {sag * 1e3:.1f} mm with K_P3 = {s['K_P3']:.3g} N/m: more than "
                         f"{_SAG_NOTE * 1e3:.0f} mm, visible at the tool. A stiffer K_P3, integral action or a model "
                         "that knows the payload (chapter 6) removes it.")
        return PanelView([fig], table(rows), notes)

    return LivePanel(controls, compute, draw, title="The inertia matrix: payload and configuration", columns=3)
