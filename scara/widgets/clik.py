"""Live panel of chapter 4 (CLIK): choose a method, set the gain of each operational component, the damping,
the null-space gain and the relaxed component; the whole 70 s reference is re-run and redrawn on every move.

The move is one compiled kernel, the page program :func:`scara.programs.clik.clik_program`, so that the same
panel runs in JupyterLab (here) and, translated, in the book's page."""
from __future__ import annotations

from .._clik import COMPONENTS, SEED_K
from ..errors import check_count
from ..params import ScaraParams
from ..plots._common import FIGURE_BUDGET, MAX_POINTS
from ..plots.clik import (CLIK_PANEL_ROLES, CLIK_PANEL_TITLE, METHOD_CHOICES, clik_panel_bindings,
                          clik_panel_figure)
from ..plots.panels import Control, Flag, PageProgram, Panel, Text, program_panel
from ..programs.clik import (INPUTS, PANEL_METHODS, clik_compact, clik_data, clik_outputs, clik_prepare, clik_program,
                             clik_start,
                             refusal_templates)
from ..book import ahead
from ._common import LivePanel, trajectory_arg

__all__ = ["clik_panel", "clik_declaration", "clik_controls", "clik_page_program"]

#: the method dropdown's labels and the method each runs (:data:`scara.plots.clik.METHOD_CHOICES`), in the
#: order of the program's methods (:data:`scara.programs.clik.PANEL_METHODS`)
_METHODS = METHOD_CHOICES
assert tuple(_METHODS.values()) == PANEL_METHODS
#: the gain sliders: control name, the gain's name in a message, its label
_GAINS = (("Kx", "K_x", "K_x (1/s)"), ("Ky", "K_y", "K_y (1/s)"), ("Kz", "K_z", "K_z (1/s)"),
          ("Kphi", "K_φ", "K_φ (1/s)"))
#: what a refusal starts with: the method and the gains, in the panel's units
_REFUSAL_HEAD = "{method} with " + ", ".join(f"{name} = {{{key}:.4g}} 1/s" for key, name, _ in _GAINS) + ": "
#: the summary's rows and notes (fields of the program's outputs)
_ROWS = (("max / RMS position error (mm)", Text("{max_ep_mm:.4g} / {rms_ep_mm:.4g}")),
         ("max orientation error (mrad)", Text("{max_eo_mrad:.4g}")),
         ("min / mean manipulability (m²)", Text("{min_manipulability:.4f} / {mean_manipulability:.4f}")))
_NOTES = ((Flag("strays"), Text("The tip strays up to {max_ep_mm:.3g} mm from the path: raise the gains (within "
                                "the stability limit) to follow it more closely.")),
          (Flag("pseudo"), Text("drift of the relaxed {relaxed} (max): {drift:.4g}")))


def clik_controls() -> tuple:
    """The panel's controls: the method (the selector), the relaxed component, the four gains (log sliders), the
    damping and the null-space gain."""
    pseudo = tuple(label for label, m in METHOD_CHOICES.items() if m == "pseudoinverse")
    damped = tuple(label for label, m in METHOD_CHOICES.items() if m != "transpose")  # the transpose solves nothing
    gains = tuple(Control(name, "slider", label, float(k), 1.0, 2500.0, 0.01, scale="log", unit="1/s", readout=".0f")
                  for (name, _, label), k in zip(_GAINS, SEED_K))
    return (Control("method", "dropdown", "method", "Jacobian inverse", options=tuple(METHOD_CHOICES)),
            Control("relaxed", "dropdown", "relaxed (pseudo-inverse)", "x", options=tuple(COMPONENTS),
                    applies_to=pseudo),
            *gains,
            Control("damping", "slider", "damping λ (m)", 0.0, 0.0, 0.2, 0.005, unit="m", readout=".3f",
                    applies_to=damped),
            Control("k0", "slider", "null-space gain k0 (1/s)", 1.0, 0.0, 20.0, 0.5, unit="1/s", applies_to=pseudo))


def clik_page_program(traj, p=None, points: int = 800) -> PageProgram:
    """The panel's :class:`~scara.plots.panels.PageProgram` on ``traj`` (any trajectory :func:`scara.clik2` takes;
    robot ``p``, default ``traj.params``), drawn with ``points`` points per curve: the kernel
    :func:`~scara.programs.clik.clik_program`, its data (:func:`~scara.programs.clik.clik_data`) and outputs
    (:func:`~scara.programs.clik.clik_outputs`), its refusals (the package's messages after the method and the
    gains), the figure's bindings (:func:`~scara.plots.clik.clik_panel_bindings`), the summary's rows and notes."""
    refusals = {code: Text(_REFUSAL_HEAD + text) for code, text in refusal_templates(clik_start(traj, p)[2]).items()}
    compact = clik_compact(traj, p, points)  # a planned path travels as its plan, sampled by clik_prepare
    data = dict(data=clik_data(traj, p, points)) if compact is None else \
        dict(data=compact[1], prepare=clik_prepare, compact=compact[0])
    return PageProgram(clik_program, INPUTS, outputs=clik_outputs(len(traj.t), points), refusals=refusals,
                       traces=clik_panel_bindings(), titles={"clik": CLIK_PANEL_TITLE}, rows=_ROWS, notes=_NOTES,
                       **data)


def clik_declaration(traj=None, p=None, points: int = 800) -> Panel:
    """The CLIK panel as data (:class:`~scara.plots.panels.Panel`, with its
    :class:`~scara.plots.panels.PageProgram`, :func:`clik_page_program`); see :func:`clik_panel`."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    p = ScaraParams.resolve(p)
    traj = trajectory_arg(traj, p)
    return program_panel("CLIK", "CLIK on the 70 s reference: tune and watch", clik_controls(),
                         clik_page_program(traj, p, points), {"clik": clik_panel_figure}, widget="clik_panel",
                         explain=lambda exc, values: str(exc), selector="method", roles={"clik": CLIK_PANEL_ROLES})


@ahead(clik_program, clik_prepare)
def clik_panel(traj=None, p=None, points: int = 800, keep: bool = False) -> LivePanel:
    """Method dropdown; a log slider for each gain ``K_x, K_y, K_z, K_phi`` (1/s; the second-order CLIK uses
    ``K_P = K^2``, ``K_D = 2 K``); damping ``lambda`` (m) of the damped least-squares inverse; null-space gain
    ``k0`` and relaxed component of the pseudo-inverse (greyed out for the other methods). Each change re-runs
    the CLIK on ``traj`` (default: the 70 s reference of chapter 3) in one compiled kernel,
    :func:`scara.programs.clik.clik_program` (the loops of :func:`scara.clik` and :func:`scara.clik2`, behind
    the same checks), and redraws the position error (log), the orientation error and the manipulability, with
    the summary figures listed (and the drift of the relaxed component for the pseudo-inverse). Settings the
    package refuses (a gain past a stability limit, a run that diverges) are reported in the panel.

    ``points`` (samples per curve) runs from 2 to 10 000 (``scara.plots._common.MAX_POINTS``); outside, or not a
    whole number, or ``traj`` not a Trajectory (or a waypoint editor: its last accepted plan), raises
    :class:`ScaraError` before any run. ``keep=True`` starts from the last accepted settings of the previous CLIK
    panel built in this Python process (see :class:`~scara.widgets._common.LivePanel`). Its ``declaration`` is
    :func:`clik_declaration`."""
    return LivePanel(clik_declaration(traj, p, points), keep=keep)
