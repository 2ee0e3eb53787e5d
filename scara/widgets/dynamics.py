"""Live panel of chapter 5 (dynamics): choose the payload and the configuration and watch ``B(q)``, its
eigenvalues and the gravity load change; optionally hold the arm with PD plus gravity and see the quill sag
that the unknown payload causes. Jupyter only."""
from __future__ import annotations

import math

import numpy as np

from ..dynamics import gravity, inertia
from ..errors import ScaraError, as_vector, check_positive
from ..plots.dynamics import inertia_pair
from ..plots.panels import Control, Panel, angle_control, stroke_control
from .._simulate import PDGravityController
from ._common import LivePanel
from ..params import ScaraParams

__all__ = ["dynamics_panel", "dynamics_declaration"]

#: a quill sag above this (m) is flagged in the panel
_SAG_NOTE = 0.003


def dynamics_declaration(payload: float = 5.0, q=(0.0, -math.pi / 2, 0.5, 0.0), K_P3: float = 10000.0,
                         p=None) -> Panel:
    """The inertia panel as data (:class:`~scara.plots.panels.Panel`); see :func:`dynamics_panel`."""
    p = ScaraParams.resolve(p)
    q = as_vector(q, "q")
    controls = (Control("payload", "slider", "payload m_L (kg)", payload, 0.0, 20.0, 0.5, unit="kg"),
                angle_control(q[0], "theta1", "θ1 (°)"), angle_control(q[1], "theta2", "θ2 (°)"),
                stroke_control(q[2], p), angle_control(q[3], "theta4", "θ4 (°)"),
                Control("K_P3", "slider", "K_P3 (N/m)", K_P3, 100.0, 1e6, 0.1, scale="log", unit="N/m"))

    def compute(v):
        payload, theta2, d3, K_P3 = v["payload"], v["theta2"], v["d3"], v["K_P3"]
        robot = p.with_payload(check_positive(payload, "payload", strict=False))
        qq = np.array([math.radians(v["theta1"]), math.radians(theta2), d3, math.radians(v["theta4"])])
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

    def summary(s):
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
        return rows, notes

    return Panel("inertia matrix", "The inertia matrix: payload and configuration", controls, compute,
                 (inertia_pair(),), summary, columns=3)


def dynamics_panel(payload: float = 5.0, q=(0.0, -math.pi / 2, 0.5, 0.0), K_P3: float = 10000.0,
                   p=None) -> LivePanel:
    """Sliders for the payload mass (kg), theta1, theta2, theta4 (degrees), d3 (m) and the PD gain ``K_P3``
    (N/m); redraws ``B(q)`` with the make-up of its diagonal and lists its eigenvalues, ``g(q)`` and the
    quill's steady-state sag ``m_L g0 / K_P3`` under PD plus gravity with a payload-free model.
    Only theta2 and the payload change ``B``: moving the other sliders shows it. Its ``declaration`` is
    :func:`dynamics_declaration`."""
    return LivePanel(dynamics_declaration(payload, q, K_P3, p))
