"""Live tuning panel of chapter 6: choose a controller, move its gains, the independent-joint pole ``omega``,
the robust term's ``rho`` and ``epsilon``, the adaptation weight ``K_pi``, the integral gain ``K_I`` and the true
payload; the whole 70 s run is re-simulated and redrawn at once, by the panel's page program (the same compiled
kernel in Jupyter and, translated, in the book's page).

The reader's own controllers (``control_panel(controllers={label: class or factory})``) join the dropdown in
Jupyter: a move of one of them builds it from the panel's gains (:data:`OWN_GAINS`), runs it with
:func:`scara.simulate` and draws the run with the kernel that draws the program's own runs
(:func:`scara.programs.control.run_outputs`)."""
from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Mapping

import numpy as np

from ..control import (AdaptiveController, ComputedTorqueController, IndependentJointController,
                       OperationalSpaceController, PDPlusGravityController, RobustController)
from ..errors import ScaraError, check_count
from ..params import ScaraParams
from ..plots._common import CONTROLLER_LABELS, FIGURE_BUDGET, MAX_POINTS
from ..plots.control import (TUNING_CONTROLLERS, TUNING_ROLES, own_roles, tuning_bindings, tuning_build,
                             tuning_own_build, tuning_own_update)
from ..plots.panels import Control, FigurePair, Flag, PageProgram, Panel, Text, program_panel, start_value
from ..programs.control import (ADAPTIVE_K_D, INPUTS, control_compact, control_data, control_outputs, control_prepare,
                                control_program, control_refusals, control_scratch, joint_reference_refusal,
                                fill_joint_reference, joint_reference_rows, own_run_outputs)
from ..book import ahead
from ._common import LivePanel, trajectory_arg

__all__ = ["control_panel", "control_declaration", "make_controller", "own_gains", "OWN_GAINS", "PER_JOINT"]

#: the controller dropdown's choices: the controllers' legend names
_CONTROLLERS = tuple(CONTROLLER_LABELS[k] for k in TUNING_CONTROLLERS)
_KEYS = dict(zip(_CONTROLLERS, TUNING_CONTROLLERS))

#: the panel's gains a controller of the reader's own may take, by the names of their sliders (and of the
#: keyword arguments it is called with), in the sliders' order
OWN_GAINS = ("K_P", "K_D", "Lambda", "rho", "epsilon", "K_D_scale", "K_pi", "K_I", "omega")
#: the gains the package's controllers take per joint (``scara.gains.gain_vector``): given as a (4,) array,
#: every joint the slider's value; the others (``rho``, ``epsilon``, ``K_D_scale``, ``K_pi``) as floats
PER_JOINT = ("K_P", "K_D", "Lambda", "K_I", "omega")


def _gain(name, label, default, low, high, readout, *uses, unit="", own=()):
    """A log slider (step 0.01 decade) read by the controllers ``uses`` (keys of ``CONTROLLER_LABELS``) and by
    the reader's own controllers ``own`` (their dropdown labels)."""
    return Control(name, "slider", label, default, low, high, 0.01, scale="log", unit=unit, readout=readout,
                   applies_to=tuple(CONTROLLER_LABELS[k] for k in uses) + tuple(own))


def _callable_name(factory) -> str:
    return getattr(factory, "__qualname__", None) or getattr(factory, "__name__", None) or type(factory).__name__


def own_gains(factory, label: str = "controller", gains: tuple = OWN_GAINS) -> tuple:
    """The panel's gains (``gains``, default :data:`OWN_GAINS`) that ``factory`` (a controller class or a function
    returning a controller) takes: the keyword parameters of its signature (a class's ``__init__``) named after a
    gain, in the sliders' order; all of them when it takes ``**kwargs``; none when its signature cannot be read.
    Raises :class:`ScaraError` naming ``label`` for a parameter without a default that is not a gain (the panel
    could not call it)."""
    try:
        params = inspect.signature(factory).parameters.values()
    except (TypeError, ValueError):
        return ()
    reads = set()
    for prm in params:
        if prm.kind is prm.VAR_KEYWORD:
            return tuple(gains)
        if prm.kind is prm.VAR_POSITIONAL:
            continue
        if prm.name in gains and prm.kind is not prm.POSITIONAL_ONLY:
            reads.add(prm.name)
        elif prm.default is prm.empty:
            name = _callable_name(factory)
            a, b = gains[0], gains[1]
            raise ScaraError(f"controllers[{label!r}]: {name} needs the argument {prm.name!r}, which the panel does "
                             f"not give: it calls it with the keyword arguments it names among the panel's gains "
                             f"{', '.join(gains)}; give {prm.name!r} a default, or pass a function that sets it, "
                             f"e.g. lambda {a}, {b}: {name}({a}={a}, {b}={b}, {prm.name}=...)")
    return tuple(g for g in gains if g in reads)


def _own_controllers(controllers, choices: tuple = _CONTROLLERS, gains: tuple = OWN_GAINS) -> dict:
    """``controllers`` (label -> class or factory) checked against the panel's own ``choices`` and ``gains``:
    ``{label: (factory, gains it takes)}``."""
    if controllers is None:
        return {}
    if not isinstance(controllers, Mapping):
        raise ScaraError(f"controllers must be a dict of dropdown label -> controller class or factory, got "
                         f"{type(controllers).__name__} {controllers!r:.80}")
    own = {}
    for label, factory in controllers.items():
        if not isinstance(label, str) or not label.strip():
            raise ScaraError(f"controllers: a label must be a non-empty str (the dropdown's text), got {label!r:.80}")
        if label in choices:
            raise ScaraError(f"controllers: the label {label!r} is one of the panel's own controllers "
                             f"{choices}; give yours another name")
        if not callable(factory):
            raise ScaraError(f"controllers[{label!r}] must be a controller class or a function returning a controller "
                             f"(called with the panel's gains), got {type(factory).__name__} {factory!r:.80}")
        own[label] = (factory, own_gains(factory, label, gains))
    return own


def _failure(exc: BaseException) -> str:
    """An exception of the reader's code in a line or three: its type and the start of its message."""
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    text = " ".join(lines[:3])
    if len(text) > 300:
        text = text[:299] + "…"
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def _own_move(label, factory, reads, settings, traj, plant, program):
    """The program's outputs (:meth:`PageProgram.values`) for a move of the reader's controller ``label``: built by
    ``factory`` from the gains ``reads``, run by :func:`scara.simulate` on ``traj`` and ``plant`` carrying the
    payload (a joint controller tracks the joint reference of the program's data), drawn by
    :func:`~scara.programs.control.own_run_outputs`. Anything that goes wrong is a :class:`ScaraError` whose
    message starts with ``label``: the package's own message, or the reader's exception in a line."""
    from .. import simulate  # noqa: PLC0415 - the engine, on demand

    gains = {k: (np.full(4, float(settings[k])) if k in PER_JOINT else float(settings[k])) for k in reads}
    given = ", ".join(f"{k} = {settings[k]:g}" for k in reads) or "no gain"
    try:
        controller = factory(**gains)
    except ScaraError as exc:
        raise ScaraError(f"{label} with {given}: {exc}") from None
    except Exception as exc:  # noqa: BLE001 - the reader's code: any failure is refused, never raised
        raise ScaraError(f"{label} with {given}: building it failed: {_failure(exc)}") from None
    jref = None
    if getattr(controller, "reference_kind", None) == "joint":
        jref = joint_reference_rows(program.data)
        if jref is None:
            code, out = joint_reference_refusal(program.data, program.outputs.size)
            raise ScaraError(program.refusals[code].format(program.values(out, settings)))
    try:
        with np.errstate(all="ignore"):
            result = simulate(controller, traj, plant.with_payload(settings["payload"]), joint_reference=jref)
    except ScaraError as exc:
        raise ScaraError(f"{label} with {given}: {exc}") from None
    except Exception as exc:  # noqa: BLE001 - the reader's law: any failure is refused, never raised
        raise ScaraError(f"{label} with {given}: its run failed: {_failure(exc)}") from None
    code, out = own_run_outputs(result, program.data, program.outputs.size)
    values = program.values(out, settings)
    if code != 0:
        raise ScaraError(program.refusals[code].format(values))
    return values


def make_controller(controller: str, K_P, K_D, Lambda, rho, epsilon, K_D_scale, K_pi, K_I, omega=30.0):
    """The controller the panel's settings describe: ``controller`` is a choice of its dropdown (a legend name
    of ``CONTROLLER_LABELS``), the other arguments its sliders' values (the panel's own mapping, exposed for
    tests)."""
    key = _KEYS.get(controller)
    if key is None:
        raise ScaraError(f"controller = {controller!r} is not one of the panel's controllers {_CONTROLLERS}")
    if key == "independent":
        return IndependentJointController(omega=omega)
    if key == "pd_plus_gravity":
        return PDPlusGravityController(omega=omega)
    if key == "computed_torque":
        return ComputedTorqueController(omega=omega)
    if key == "robust":
        return RobustController(K_P=K_P, K_D=K_D, rho=rho, epsilon=epsilon, Lambda=Lambda)
    if key == "adaptive":
        return AdaptiveController(Lambda=Lambda, K_D=K_D_scale * np.array(ADAPTIVE_K_D),
                                  K_pi={"m3": K_pi})
    return OperationalSpaceController(integral=key == "operational", K_P=K_P, K_D=K_D, K_I=K_I)


def control_declaration(traj=None, p=None, payload: float = 5.0, points: int = 600, controllers=None) -> Panel:
    """The controllers panel as data (:class:`~scara.plots.panels.Panel`, made by
    :func:`~scara.plots.panels.program_panel`); see :func:`control_panel`. Every move of the seven controllers is
    one run of its page program (:func:`scara.programs.control.control_program`) on the data of
    :func:`~scara.programs.control.control_data`, drawn by the bindings of :func:`scara.plots.control.tuning_bindings`
    into :func:`~scara.plots.control.tuning_build`. With ``controllers`` of the reader's own, a move of one of them
    is :func:`scara.simulate`'s run (see :func:`control_panel`), the figure has their error traces
    (:func:`~scara.plots.control.tuning_own_build`) and the panel has no page form (``page`` is None)."""
    payload = start_value(payload, 0.0, 10.0, "payload", "kg")
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    own = _own_controllers(controllers)
    p = ScaraParams.resolve(p)
    traj = trajectory_arg(traj, p)

    def reading(gain):
        return tuple(label for label, (_, reads) in own.items() if gain in reads)

    def gain(name, label, default, low, high, readout, *uses, unit=""):
        return _gain(name, label, default, low, high, readout, *uses, unit=unit, own=reading(name))

    controls = (
        Control("controller", "dropdown", "controller", "robust", options=_CONTROLLERS + tuple(own)),
        Control("payload", "slider", "true payload m_L (kg)", payload, 0.0, 10.0, 0.5, unit="kg"),
        gain("K_P", "K_P (1/s²)", 900.0, 10.0, 1e5, ".0f", "robust", "operational", "operational_noint",
             unit="1/s²"),
        gain("K_D", "K_D (1/s)", 60.0, 2.0, 3000.0, ".1f", "robust", "operational", "operational_noint", unit="1/s"),
        gain("Lambda", "Λ (1/s)", 30.0, 1.0, 300.0, ".1f", "robust", "adaptive", unit="1/s"),
        gain("rho", "ρ (m/s²)", 20.0, 0.1, 200.0, ".3g", "robust", unit="m/s²"),
        gain("epsilon", "ε (boundary layer)", 0.05, 1e-3, 1.0, ".3g", "robust"),
        gain("K_D_scale", "adaptive K_D (× book)", 1.0, 0.05, 20.0, ".2f", "adaptive"),
        gain("K_pi", "K_π (weight of m3)", 0.01, 1e-5, 10.0, ".2e", "adaptive"),
        gain("K_I", "K_I (1/s³)", 8000.0, 10.0, 1e6, ".0f", "operational", unit="1/s³"),
        gain("omega", "ω, independent joint, PD + g, computed torque (rad/s)", 30.0, 1.0, 300.0, ".3g", "independent",
             "pd_plus_gravity", "computed_torque", unit="rad/s"),
    )
    compact = control_compact(traj, p, points)  # a planned path travels as its plan, sampled by control_prepare
    data = dict(data=control_data(traj, p, points)) if compact is None else \
        dict(data=compact[1], prepare=control_prepare, compact=compact[0])
    outputs = control_outputs(len(traj.t), points)
    note = Text("At rest the tool stays {final_position_error_mm:.3g} mm from its target: the payload's weight is not "
                "fully compensated.")
    program = PageProgram(control_program, INPUTS, outputs=outputs, refusals=control_refusals(p), **tuning_bindings(),
                          notes=((Flag("not_compensated"), note),), scratch=control_scratch(len(traj.t)), **data)
    panel = program_panel("controllers", "Chapter 6: tune a controller on the 70 s run", controls, program,
                          {"tuning": tuning_build}, widget="control_panel", selector="controller",
                          roles={"tuning": TUNING_ROLES})
    if not own:
        return panel
    labels = tuple(own)
    plant = ScaraParams.for_trajectory(traj, p)
    run = panel.compute

    def compute(settings):
        choice = settings["controller"]
        if choice in own:
            factory, reads = own[choice]
            return _own_move(choice, factory, reads, settings, traj, plant, program)
        return run(settings)

    pair = FigurePair("tuning", lambda values: tuning_own_build(values, labels),
                      lambda values: tuning_own_update(program.update("tuning", values), values, labels),
                      TUNING_ROLES + own_roles(labels))
    return dataclasses.replace(panel, compute=compute, figures=(pair,), page=None)


@ahead(control_program, control_prepare, fill_joint_reference)
def control_panel(traj=None, p=None, payload: float = 5.0, points: int = 600, controllers=None,
                  keep: bool = False) -> LivePanel:
    """Controller dropdown and sliders: the pole ``omega`` (rad/s) of the independent-joint PID (the triple pole of
    every joint's nominal loop), of PD with gravity compensation (the double pole of the same nominal loop) and of
    computed torque (the critically damped error's natural frequency), ``K_P`` (1/s^2) and ``K_D`` (1/s) of the robust and operational laws,
    ``Lambda`` (1/s) of the robust and adaptive laws, ``rho`` (m/s^2) and ``epsilon`` of the robust term, a scale of
    the adaptive ``K_D`` (times the book's ``(600, 300, 1000, 60)``), the adaptation weight ``K_pi`` of the
    lumped mass ``m3``, ``K_I`` (1/s^3), and the true payload (kg) of the plant (the controllers never know it).
    The sliders a controller does not read are greyed out. Each change re-runs the 70 s reference (``traj``,
    default the reference of chapter 3; the joint controllers track its ``clik2`` joint reference) in one compiled
    program and redraws the error, the torques and the controller's own signal (with its own figures in a note
    above it). Settings the package refuses (non-positive gains,
    ``Lambda >= K_D``, an unstable integral, a run that diverges or breaks a bound) are reported in the panel
    with the time and cause; so is a number typed beside a slider outside its range (never clamped).

    ``traj`` may also be a waypoint editor (:func:`~scara.widgets.waypoint_editor`): its last accepted plan,
    ``editor.trajectory``, whose joint reference is computed for the joint controllers.

    ``controllers`` adds controllers of your own to the dropdown: a dict mapping the label shown to a controller
    class, or a function returning a controller (an object with the interface of :class:`scara.Controller`, as
    the package page's *Writing your own controller* builds one). On a move it is called with the panel's gains
    its signature names, as keyword arguments (:data:`OWN_GAINS`: ``K_P, K_D, Lambda, rho, epsilon, K_D_scale,
    K_pi, K_I, omega``, the sliders' names; ``**kwargs`` takes them all): the per-joint gains ``K_P``, ``K_D``,
    ``Lambda``, ``K_I`` and ``omega`` as (4,) float arrays holding the slider's value for every joint (the form
    :class:`~scara.PDGravityController` takes), ``rho``, ``epsilon``, ``K_D_scale`` and ``K_pi`` as floats, in
    the sliders' units. The sliders it does not name are greyed out while it is chosen; the true payload is the
    plant's, as for the others. The controller built is run by :func:`scara.simulate` on ``traj`` with the
    plant carrying the payload (a ``"joint"`` controller tracking the same joint reference as the panel's, an
    ``"operational"`` one the trajectory) -- compiled when its law is a :func:`~scara.control_law` kernel,
    as plain Python otherwise (about a second a move on the 70 s reference instead of a few hundredths) -- and drawn
    as the others are, by the same kernel (its own signal is ``e_z``). A controller that cannot be built, whose
    arrays do not match their layouts, whose law fails or reads or writes past its arrays, or whose run
    diverges or gives a NaN is refused in the panel with the reason (the package's message, or your exception's
    type and first line). A label must differ from the panel's seven; a parameter of the class or function that
    is not a gain must have a default (else :class:`ScaraError`). A panel with controllers of your own runs in
    Jupyter only: the book's page runs the seven.

    ``keep=True`` starts from the last accepted settings of the previous controllers panel built in this Python
    process (re-running the cell keeps the dropdown's choice and the sliders; a choice this panel does not
    offer is not kept): see :class:`~scara.widgets._common.LivePanel`.

    ``payload`` must lie in the slider's range 0 to 10 kg and ``points`` (samples per curve) from 2 to 10 000
    (``scara.plots._common.MAX_POINTS``); outside, or not a number, or ``traj`` not a Trajectory, raises
    :class:`ScaraError` before any run. Its ``declaration`` is :func:`control_declaration`."""
    return LivePanel(control_declaration(traj, p, payload, points, controllers), keep=keep)
