"""Live tuning panel of chapter 6: choose a controller, move its gains, the independent-joint pole ``omega``,
the robust term's ``rho`` and ``epsilon``, the adaptation weight ``K_pi``, the integral gain ``K_I`` and the true
payload; the whole 70 s run is re-simulated and redrawn at once, by the panel's page program (the same compiled
kernel in Jupyter and, translated, in the book's page)."""
from __future__ import annotations

import numpy as np

from ..control import AdaptiveController, IndependentJointController, OperationalSpaceController, RobustController
from ..errors import ScaraError, check_count
from ..params import ScaraParams
from ..plots._common import CONTROLLER_LABELS, FIGURE_BUDGET, MAX_POINTS
from ..plots.control import TUNING_CONTROLLERS, TUNING_ROLES, tuning_bindings, tuning_build
from ..plots.panels import Control, Flag, PageProgram, Panel, Text, program_panel, start_value
from ..programs.control import (ADAPTIVE_K_D, INPUTS, control_compact, control_data, control_outputs, control_prepare,
                                control_program, control_refusals, control_scratch)
from ._common import LivePanel, trajectory_arg

__all__ = ["control_panel", "control_declaration", "make_controller"]

#: the controller dropdown's choices: the controllers' legend names
_CONTROLLERS = tuple(CONTROLLER_LABELS[k] for k in TUNING_CONTROLLERS)
_KEYS = dict(zip(_CONTROLLERS, TUNING_CONTROLLERS))


def _gain(name, label, default, low, high, readout, *uses, unit=""):
    """A log slider (step 0.01 decade) read by the controllers ``uses`` (keys of ``CONTROLLER_LABELS``)."""
    return Control(name, "slider", label, default, low, high, 0.01, scale="log", unit=unit, readout=readout,
                   applies_to=tuple(CONTROLLER_LABELS[k] for k in uses))


def make_controller(controller: str, K_P, K_D, Lambda, rho, epsilon, K_D_scale, K_pi, K_I, omega=30.0):
    """The controller the panel's settings describe: ``controller`` is a choice of its dropdown (a legend name
    of ``CONTROLLER_LABELS``), the other arguments its sliders' values (the panel's own mapping, exposed for
    tests)."""
    key = _KEYS.get(controller)
    if key is None:
        raise ScaraError(f"controller = {controller!r} is not one of the panel's controllers {_CONTROLLERS}")
    if key == "independent":
        return IndependentJointController(omega=omega)
    if key == "robust":
        return RobustController(K_P=K_P, K_D=K_D, rho=rho, epsilon=epsilon, Lambda=Lambda)
    if key == "adaptive":
        return AdaptiveController(Lambda=Lambda, K_D=K_D_scale * np.array(ADAPTIVE_K_D),
                                  K_pi={"m3": K_pi})
    return OperationalSpaceController(integral=key == "operational", K_P=K_P, K_D=K_D, K_I=K_I)


def control_declaration(traj=None, p=None, payload: float = 5.0, points: int = 600) -> Panel:
    """The controllers panel as data (:class:`~scara.plots.panels.Panel`, made by
    :func:`~scara.plots.panels.program_panel`); see :func:`control_panel`. Every move is one run of its page
    program (:func:`scara.programs.control.control_program`) on the data of
    :func:`~scara.programs.control.control_data`, drawn by the bindings of :func:`scara.plots.control.tuning_bindings`
    into :func:`~scara.plots.control.tuning_build`."""
    payload = start_value(payload, 0.0, 10.0, "payload", "kg")
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    p = ScaraParams.resolve(p)
    traj = trajectory_arg(traj, p)
    controls = (
        Control("controller", "dropdown", "controller", "robust", options=_CONTROLLERS),
        Control("payload", "slider", "true payload m_L (kg)", payload, 0.0, 10.0, 0.5, unit="kg"),
        _gain("K_P", "K_P (1/s²)", 900.0, 10.0, 1e5, ".0f", "robust", "operational", "operational_noint",
              unit="1/s²"),
        _gain("K_D", "K_D (1/s)", 60.0, 2.0, 3000.0, ".1f", "robust", "operational", "operational_noint", unit="1/s"),
        _gain("Lambda", "Λ (1/s)", 30.0, 1.0, 300.0, ".1f", "robust", "adaptive", unit="1/s"),
        _gain("rho", "ρ (m/s²)", 20.0, 0.1, 200.0, ".3g", "robust", unit="m/s²"),
        _gain("epsilon", "ε (boundary layer)", 0.05, 1e-3, 1.0, ".3g", "robust"),
        _gain("K_D_scale", "adaptive K_D (× book)", 1.0, 0.05, 20.0, ".2f", "adaptive"),
        _gain("K_pi", "K_π (weight of m3)", 0.01, 1e-5, 10.0, ".2e", "adaptive"),
        _gain("K_I", "K_I (1/s³)", 8000.0, 10.0, 1e6, ".0f", "operational", unit="1/s³"),
        _gain("omega", "ω, independent joint (rad/s)", 30.0, 1.0, 300.0, ".3g", "independent", unit="rad/s"),
    )
    compact = control_compact(traj, p, points)  # a planned path travels as its plan, sampled by control_prepare
    data = dict(data=control_data(traj, p, points)) if compact is None else \
        dict(data=compact[1], prepare=control_prepare, compact=compact[0])
    outputs = control_outputs(len(traj.t), points)
    note = Text("At rest the tool stays {final_position_error_mm:.3g} mm from its target: the payload's weight is not "
                "fully compensated.")
    program = PageProgram(control_program, INPUTS, outputs=outputs, refusals=control_refusals(p), **tuning_bindings(),
                          notes=((Flag("not_compensated"), note),), scratch=control_scratch(len(traj.t)), **data)
    return program_panel("controllers", "Chapter 6: tune a controller on the 70 s run", controls, program,
                         {"tuning": tuning_build}, widget="control_panel", selector="controller",
                         roles={"tuning": TUNING_ROLES})


def control_panel(traj=None, p=None, payload: float = 5.0, points: int = 600) -> LivePanel:
    """Controller dropdown and sliders: the pole ``omega`` (rad/s) of the independent-joint PID (the triple pole of
    every joint's nominal loop), ``K_P`` (1/s^2) and ``K_D`` (1/s) of the robust and operational laws,
    ``Lambda`` (1/s) of the robust and adaptive laws, ``rho`` (m/s^2) and ``epsilon`` of the robust term, a scale of
    the adaptive ``K_D`` (times the book's ``(600, 300, 1000, 60)``), the adaptation weight ``K_pi`` of the
    lumped mass ``m3``, ``K_I`` (1/s^3), and the true payload (kg) of the plant (the controllers never know it).
    The sliders a controller does not read are greyed out. Each change re-runs the 70 s reference (``traj``,
    default the reference of chapter 3; the joint controllers track its ``clik2`` joint reference) in one compiled
    program and redraws the error, the torques and the controller's own signal (with its own figures in a note
    above it). Settings the package refuses (non-positive gains,
    ``Lambda >= K_D``, an unstable integral, a run that diverges or breaks a bound) are reported in the panel
    with the time and cause.

    ``payload`` must lie in the slider's range 0 to 10 kg and ``points`` (samples per curve) from 2 to 10 000
    (``scara.plots._common.MAX_POINTS``); outside, or not a number, or ``traj`` not a Trajectory, raises
    :class:`ScaraError` before any run. Its ``declaration`` is :func:`control_declaration`."""
    return LivePanel(control_declaration(traj, p, payload, points))
