"""Live panel of chapter 5 (dynamics): choose the payload and the configuration and watch ``B(q)``, its
eigenvalues and the gravity load change; optionally hold the arm with PD plus gravity and see the quill sag
that the unknown payload causes. Every move is one run of the page program
:func:`scara.programs.dynamics.dynamics_program`, drawn by the bindings of
:data:`scara.plots.dynamics.INERTIA_TRACES` (the same in JupyterLab and in the book's pages)."""
from __future__ import annotations

import math

from ..errors import as_vector
from ..plots.dynamics import INERTIA_TITLE, INERTIA_TRACES, inertia_panel_figure
from ..plots.panels import Control, Flag, PageProgram, Panel, Text, angle_control, program_panel, stroke_control
from ..programs.dynamics import (DYNAMICS_INPUTS, DYNAMICS_OUTPUTS, REFUSED_GAIN, REFUSED_PAYLOAD, REFUSED_SAG,
                                 SAG_NOTE, dynamics_data, dynamics_program)
from ..book import ahead
from ._common import LivePanel
from ..params import ScaraParams

__all__ = ["dynamics_panel", "dynamics_declaration"]


def dynamics_declaration(payload: float = 5.0, q=(0.0, -math.pi / 2, 0.5, 0.0), K_P3: float = 10000.0,
                         p=None) -> Panel:
    """The inertia panel as data (:class:`~scara.plots.panels.Panel`); see :func:`dynamics_panel`."""
    p = ScaraParams.resolve(p)
    q = as_vector(q, "q")
    controls = (Control("payload", "slider", "payload m_L (kg)", payload, 0.0, 20.0, 0.5, unit="kg"),
                angle_control(q[0], "theta1", "θ1 (°)"), angle_control(q[1], "theta2", "θ2 (°)"),
                stroke_control(q[2], p), angle_control(q[3], "theta4", "θ4 (°)"),
                Control("K_P3", "slider", "K_P3 (N/m)", K_P3, 100.0, 1e6, 0.1, scale="log", unit="N/m"))
    sag_refusal = ("with K_P3 = {K_P3:.3g} N/m the {payload:g} kg payload would sag {sag_mm:.1f} mm under PD + "
                   "gravity: the quill, at d3 = {d3:.2f} m, would need d3 = {d3_need:.3f} m, past the end of its "
                   f"stroke (d3_min to d3_max = {p.d3_min:g} to {p.d3_max:g} m). Raise K_P3 or lighten the payload.")
    program = PageProgram(
        dynamics_program, DYNAMICS_INPUTS, dynamics_data(p), DYNAMICS_OUTPUTS,
        refusals={REFUSED_SAG: Text(sag_refusal), REFUSED_PAYLOAD: Text("payload = {payload:g} must be >= 0"),
                  REFUSED_GAIN: Text("K_P3 = {K_P3:g} must be > 0")},
        traces=INERTIA_TRACES, titles={"inertia": INERTIA_TITLE},
        rows=(("eigenvalues of B", Text("{eig1:.4g}, {eig2:.4g}, {eig3:.4g}, {eig4:.4g}")),
              ("condition number of B", Text("{cond:.1f}")),
              ("gravity torques g(q) (N m, N m, N, N m)", Text("{g1:.4g}, {g2:.4g}, {g3:.4g}, {g4:.4g}")),
              ("quill sag under PD + gravity (payload-free model)", Text("{sag_mm:.3f} mm = m_L g0 / K_P3"))),
        notes=((Flag("sag_note"),
                Text("The quill sags {sag_mm:.1f} mm with K_P3 = {K_P3:.3g} N/m: more than "
                     f"{SAG_NOTE * 1e3:.0f} mm, visible at the tool. A stiffer K_P3, integral action or a model that "
                     "knows the payload (chapter 6) removes it.")),))
    return program_panel("inertia matrix", "The inertia matrix: payload and configuration", controls, program,
                         {"inertia": inertia_panel_figure}, widget="dynamics_panel", columns=3)


@ahead(dynamics_program)
def dynamics_panel(payload: float = 5.0, q=(0.0, -math.pi / 2, 0.5, 0.0), K_P3: float = 10000.0,
                   p=None, keep: bool = False) -> LivePanel:
    """Sliders for the payload mass (kg), theta1, theta2, theta4 (degrees), d3 (m) and the PD gain ``K_P3``
    (N/m); redraws ``B(q)`` with the make-up of its diagonal and lists its eigenvalues, ``g(q)`` and the
    quill's steady-state sag ``m_L g0 / K_P3`` under PD plus gravity with a payload-free model.
    Only theta2 and the payload change ``B``: moving the other sliders shows it. ``keep=True`` starts from the last
    accepted settings of the previous inertia panel built in this Python process (see
    :class:`~scara.widgets._common.LivePanel`). Its ``declaration`` is :func:`dynamics_declaration`."""
    return LivePanel(dynamics_declaration(payload, q, K_P3, p), keep=keep)
