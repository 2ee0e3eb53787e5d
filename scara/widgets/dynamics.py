"""Live panel of chapter 5 (dynamics): choose the payload and the configuration and watch ``B(q)``, its
eigenvalues and the gravity load change; optionally hold the arm with PD plus gravity and see the quill sag
that the unknown payload causes. Jupyter only."""
from __future__ import annotations

import math

import ipywidgets as ipw
import numpy as np

from ..dynamics import gravity, inertia
from ..errors import as_vector, check_positive
from ..kinematics import _params
from ..plots.dynamics import inertia_figure
from ..simulate import PDGravityController
from ._common import LivePanel

__all__ = ["dynamics_panel"]

_STYLE = {"description_width": "initial"}


def _table(rows):
    body = "".join(f"<tr><td style='padding:2px 10px'>{a}</td><td style='padding:2px 10px'><b>{b}</b></td></tr>"
                   for a, b in rows)
    return f"<table>{body}</table>"


def dynamics_panel(payload: float = 5.0, q=(0.0, -math.pi / 2, 0.5, 0.0), K_P3: float = 10000.0,
                   p=None) -> LivePanel:
    """Sliders for the payload mass (kg), theta1, theta2, theta4 (degrees), d3 (m) and the PD gain ``K_P3``
    (N/m); redraws ``B(q)`` with the make-up of its diagonal and lists its eigenvalues, ``g(q)`` and the
    quill's steady-state sag ``m_L g0 / K_P3`` under PD plus gravity with a payload-free model.
    Only theta2 and the payload change ``B``: moving the other sliders shows it."""
    p = _params(p)
    check_positive(payload, "payload", strict=False)
    q = as_vector(q, "q")
    deg = dict(min=-180.0, max=180.0, step=1.0, continuous_update=False, style=_STYLE)
    controls = {
        "payload": ipw.FloatSlider(value=payload, min=0.0, max=20.0, step=0.5, description="payload m_L (kg)",
                                   continuous_update=False, style=_STYLE),
        "theta1": ipw.FloatSlider(value=math.degrees(q[0]), description="θ1 (°)", **deg),
        "theta2": ipw.FloatSlider(value=math.degrees(q[1]), description="θ2 (°)", **deg),
        "d3": ipw.FloatSlider(value=q[2], min=0.0, max=p.d0, step=0.01, description="d3 (m)",
                              continuous_update=False, style=_STYLE),
        "theta4": ipw.FloatSlider(value=math.degrees(q[3]), description="θ4 (°)", **deg),
        "K_P3": ipw.FloatLogSlider(value=K_P3, base=10, min=2, max=6, step=0.1, description="K_P3 (N/m)",
                                   continuous_update=False, style=_STYLE),
    }

    def render(payload, theta1, theta2, d3, theta4, K_P3):
        robot = p.with_payload(check_positive(payload, "payload", strict=False))
        qq = np.array([math.radians(theta1), math.radians(theta2), d3, math.radians(theta4)])
        B = inertia(qq, robot)
        eig = np.linalg.eigvalsh(B)
        ctrl = PDGravityController(K_P=(1.0, 1.0, check_positive(K_P3, "K_P3"), 1.0), model=p.with_payload(0.0))
        sag = -ctrl.steady_state_error(robot)[2]
        fig = inertia_figure(qq, robot, f"B(q) with a {payload:g} kg payload at θ2 = {theta2:.0f}°")
        rows = [("eigenvalues of B", ", ".join(f"{v:.4g}" for v in eig)),
                ("condition number of B", f"{eig[-1] / eig[0]:.1f}"),
                ("gravity torques g(q) (N m, N m, N, N m)", ", ".join(f"{v:.4g}" for v in gravity(qq, robot))),
                ("quill sag under PD + gravity (payload-free model)", f"{sag * 1e3:.3f} mm = m_L g0 / K_P3")]
        return [fig, _table(rows)]

    return LivePanel(controls, render, title="The inertia matrix: payload and configuration", columns=3)
