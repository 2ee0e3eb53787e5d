"""Live interaction panel of chapter 7: choose an interaction law, move its gains along z, the pressing force and
the surface's stiffness; the approach from 2 cm above the surface and the press (3 s at 1 ms) is re-simulated and
redrawn at once, by the panel's page program (the same compiled kernel in Jupyter and, translated, in the book's
page)."""
from __future__ import annotations

import dataclasses
import math

from ..book import ahead
from ..errors import ScaraError
from ..params import ScaraParams
from ..plots.interaction_panel import PRESS_ROLES, press_bindings, press_build
from ..plots.panels import Control, PageProgram, Panel, program_panel
from ..programs.interaction import (INPUTS, LAWS, interaction_data, interaction_outputs, interaction_program,
                                   interaction_refusals, interaction_run, interaction_scratch, own_run_outputs)
from ._common import LivePanel
from .control import _failure, _own_controllers

__all__ = ["interaction_panel", "interaction_declaration", "OWN_GAINS"]

_STIFFNESS_LAWS = ("compliance", "impedance", "admittance")
_FORCE_LAWS = ("force", "parallel")
#: the panel's settings a controller of the reader's own may take, by the names of their sliders (and of the
#: keyword arguments it is called with, as floats in the sliders' units), in the sliders' order
OWN_GAINS = ("force", "K_z", "D_z", "M_z", "K_F", "K_I")


def _own_move(label, factory, reads, settings, program):
    """The program's outputs (:meth:`PageProgram.values`) for a move of the reader's controller ``label``: built by
    ``factory`` from the settings ``reads``, run by :func:`~scara.programs.interaction.interaction_run` (the
    panel's approach, :func:`~scara.interaction.simulate_contact`), reduced by
    :func:`~scara.programs.interaction.own_run_outputs`. Anything that goes wrong is a :class:`ScaraError` whose
    message starts with ``label``: the package's own message, or the reader's exception in a line."""
    given = ", ".join(f"{k} = {settings[k]:g}" for k in reads) or "no gain"
    try:
        controller = factory(**{k: float(settings[k]) for k in reads})
    except ScaraError as exc:
        raise ScaraError(f"{label} with {given}: {exc}") from None
    except Exception as exc:  # noqa: BLE001 - the reader's code: any failure is refused, never raised
        raise ScaraError(f"{label} with {given}: building it failed: {_failure(exc)}") from None
    try:
        result = interaction_run(controller, settings["k_e"], settings["force"])
    except ScaraError as exc:
        raise ScaraError(f"{label} with {given}: {exc}") from None
    except Exception as exc:  # noqa: BLE001 - the reader's law: any failure is refused, never raised
        raise ScaraError(f"{label} with {given}: its run failed: {_failure(exc)}") from None
    formula = settings["force"] if getattr(controller, "stiffness_field", None) is not None else math.nan
    return program.values(own_run_outputs(result, program.data, program.outputs.size, formula), settings)


def interaction_declaration(p=None, points: int = 600, controllers=None) -> Panel:
    """The interaction panel as data (:class:`~scara.plots.panels.Panel`, made by
    :func:`~scara.plots.panels.program_panel`); see :func:`interaction_panel`. With ``controllers`` of the
    reader's own, a move of one of them is :func:`~scara.programs.interaction.interaction_run`'s and the panel has
    no page form (``page`` is None)."""
    p = ScaraParams.resolve(p)
    own = _own_controllers(controllers, LAWS, OWN_GAINS)

    def _log(name, label, default, low, high, readout, uses, unit=""):
        """A log slider (step 0.01 decade) read by the laws ``uses`` and by the reader's controllers that take it
        (every one reads the surface's stiffness)."""
        reading = tuple(lb for lb, (_, reads) in own.items() if name in reads or name == "k_e")
        return Control(name, "slider", label, default, low, high, 0.01, scale="log", unit=unit, readout=readout,
                       applies_to=tuple(uses) + reading)

    controls = (
        Control("law", "dropdown", "interaction law", "compliance", options=LAWS + tuple(own)),
        Control("force", "slider", "pressing force (N)", 10.0, 1.0, 50.0, 0.5, unit="N"),
        _log("K_z", "stiffness along z, K_P / K_Pd (N/m)", 5000.0, 500.0, 1e5, ".0f", _STIFFNESS_LAWS, unit="N/m"),
        _log("D_z", "damping along z, K_D / K_Dd (N s/m)", 650.0, 10.0, 1e5, ".0f", _STIFFNESS_LAWS, unit="N s/m"),
        _log("M_z", "mass along z, M_d (kg)", 10.0, 0.5, 500.0, ".3g", ("impedance", "admittance"), unit="kg"),
        _log("K_F", "force gain K_F (m/N)", 2e-5, 1e-7, 1e-3, ".2e", _FORCE_LAWS, unit="m/N"),
        _log("K_I", "force integral gain K_I (m/(N s))", 2e-3, 1e-5, 1.0, ".2e", _FORCE_LAWS, unit="m/(N s)"),
        _log("k_e", "surface stiffness k_e (N/m)", 2e4, 2e3, 2e5, ".3g", LAWS, unit="N/m"),
    )
    data = interaction_data(p, points)
    n = int(data[0])
    program = PageProgram(interaction_program, INPUTS, data=data, outputs=interaction_outputs(n, points),
                          refusals=interaction_refusals(), scratch=interaction_scratch(n), **press_bindings())
    panel = program_panel("interaction", "Chapter 7: approach a surface and press it", controls, program,
                          {"press": press_build}, widget="interaction_panel", selector="law",
                          roles={"press": PRESS_ROLES})
    if not own:
        return panel
    run = panel.compute

    def compute(settings):
        choice = settings["law"]
        if choice in own:
            factory, reads = own[choice]
            return _own_move(choice, factory, reads, settings, program)
        return run(settings)

    return dataclasses.replace(panel, compute=compute, page=None)


@ahead(interaction_program)
def interaction_panel(p=None, points: int = 600, controllers=None, keep: bool = False) -> LivePanel:
    """Interaction law dropdown (compliance, impedance, admittance, force, parallel) and sliders: the pressing
    force (N), the stiffness law's ``K_P`` (admittance: ``K_Pd``), damping ``K_D`` (``K_Dd``) and mass ``M_d``
    along z (N/m, N s/m, kg), the force laws' ``K_F`` (m/N) and ``K_I`` (m/(N s)), and the surface's stiffness
    ``k_e`` (N/m, log). The sliders a law does not read are greyed out; the other entries of its gains are its
    controller's defaults. Each change re-runs the approach of
    :func:`scara.interaction.steady.approach_run` (2 cm above the default surface at (0.4, 0.1) m, a 1 s quintic
    to the set point of :func:`~scara.interaction.steady.pressing_target` for the pressing force, 2 s held; the
    package's default wrist sensor: 0.2 N noise, 0.5 N bias on ``f_z``) in one compiled program and redraws the
    normal force ``-h_z`` against the steady force of the formulas, and the tool's height against its set
    point, with the transition's figures (:func:`~scara.interaction.steady.contact_transition`). A run the engine
    stops (a torque or error bound, a divergence, the quill leaving its stroke) is reported in the panel with the
    time and cause, as :func:`scara.interaction.simulate_contact` words it; so is a number typed beside a slider
    outside its range (never clamped). ``keep=True`` starts from the last accepted settings of the previous
    interaction panel built in this Python process. ``points`` (samples per curve) from 2 to 10 000.

    ``controllers`` adds interaction controllers of your own to the dropdown, as
    :func:`~scara.widgets.control_panel` does: a dict mapping the label shown to a controller class or a function
    returning a controller (an object with the interface of :class:`scara.Controller`; it reads the wrist
    sensor in a scratch row named ``measured_force`` if its ``work_layout`` declares one). On a move it is called
    with the panel's settings its signature names, as keyword floats (:data:`OWN_GAINS`: ``force, K_z, D_z, M_z,
    K_F, K_I``, the sliders' names and units; ``**kwargs`` takes them all); the sliders it does not name are greyed
    out. Its run is :func:`~scara.programs.interaction.interaction_run` (the same approach, surface and sensor;
    a controller with a ``stiffness()`` gets the set point of
    :func:`~scara.interaction.steady.pressing_target`, others the surface's height; one with
    ``check_contact`` is checked first), drawn by the kernel that draws the program's runs (the steady force of
    the formulas is the pressing force for a law with a ``stiffness_field``, NaN otherwise; the spectral radii
    NaN). A controller that cannot be built or whose run fails is refused in the panel with the reason. A panel
    with controllers of your own runs in Jupyter only: the book's page runs the five."""
    return LivePanel(interaction_declaration(p, points, controllers), keep=keep)
