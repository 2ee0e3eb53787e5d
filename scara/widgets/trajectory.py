"""Live panel of chapter 3 (trajectory planning): a waypoint editor.

Pick a waypoint and move it with the x/y/z sliders, make it a via point or a stop, change a segment's
duration or a via point's anticipation: the path is re-planned and redrawn in place at once. Every move is one
run of the page program :func:`~scara.programs.trajectory.editor_program`, which plans with the kernels of
:func:`~scara.trajectory.plan_path` (so the path drawn is the one the planner gives) and runs the same in the
book's pages. An invalid or unreachable edit shows the planner's message and marks the figures stale; in Jupyter
the plan keeps its last valid state, so picking another waypoint or undoing the edit goes on from there (the
program's ``data`` holds that plan and is updated after every accepted move).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..errors import ScaraError, check_flag, check_number
from ..plots.panels import Control, Flag, PageProgram, Pick, Text, program_panel
from ..plots.trajectory import editor_bindings, editor_labels, editor_pairs
from ..programs import trajectory as program
from ..programs.path import plan_spec
from ..trajectory import Waypoint, plan_path, reference_plan
from ..trajectory import _plan as K
from ..trajectory._plan import G_DURATION, MAX_SAMPLES, SPEC_HEAD, SPEC_SEGMENT, SPEC_WAYPOINT, W_ANT, W_X, W_Y, W_Z
from ..book import ahead
from ._common import LivePanel

__all__ = ["WaypointEditor", "waypoint_editor", "waypoint_editor_declaration"]

#: samples drawn per curve: enough for the eye, few enough for the browser to redraw at once
TOP_POINTS, PROFILE_POINTS = 600, 500


#: the arguments of :func:`~scara.trajectory.plan_path` a plan may hold
_PLAN_KEYS = ("waypoints", "durations", "blends", "arcs", "phi", "total", "dt", "p", "elbow", "check")


def _listed(value, name: str, what: str) -> list:
    """``value`` (a list, tuple or 1-D array) as a list, or :class:`ScaraError` naming it."""
    if isinstance(value, np.ndarray) and value.ndim >= 1:
        return list(value)
    if not isinstance(value, (list, tuple)):
        raise ScaraError(f"{name} must be a list of {what}, got {type(value).__name__} {value!r:.80}")
    return list(value)


def _checked_plan(plan) -> dict:
    """``plan`` (keyword arguments of :func:`plan_path`, default the reference of chapter 3 with ``total=None``)
    with its waypoints made :class:`Waypoint` objects labelled ``p0, p1, ...`` and its durations floats."""
    if plan is not None and not isinstance(plan, dict):
        raise ScaraError(f"plan must be a dict of the arguments of plan_path (as reference_plan() returns), "
                         f"got {type(plan).__name__} {plan!r:.80}")
    plan = dict(reference_plan(), total=None) if plan is None else dict(plan)
    if "waypoints" not in plan or "durations" not in plan:
        raise ScaraError("a plan needs 'waypoints' and 'durations' (the arguments of plan_path)")
    unknown = sorted(set(plan) - set(_PLAN_KEYS))
    if unknown:
        raise ScaraError(f"plan has unknown keys {unknown}: plan_path takes {', '.join(_PLAN_KEYS)}")
    plan["waypoints"] = _listed(plan["waypoints"], "plan['waypoints']", "waypoints")
    plan["durations"] = _listed(plan["durations"], "plan['durations']", "durations (s)")
    wps = []
    for i, w in enumerate(plan["waypoints"]):
        try:
            wps.append(w if isinstance(w, Waypoint) else Waypoint(w))
        except ScaraError:
            raise
        except (TypeError, ValueError) as exc:
            raise ScaraError(f"waypoint {i} = {w!r} is not a waypoint: give (x, y, z) in m or a Waypoint") from exc
    plan["waypoints"] = [w if w.label else w.replace(label=f"p{i}") for i, w in enumerate(wps)]
    plan["durations"] = [check_number(d, f"the duration of segment {j}", unit="s")
                         for j, d in enumerate(plan["durations"])]
    return plan


class EditorState:
    """The editor's state (``plan``: keyword arguments of :func:`plan_path`) and its declaration (the panel as
    data, without widgets: :class:`WaypointEditor` adds its :class:`LivePanel`).

    ``plan`` defaults to the reference scenario of chapter 3 with ``total=None`` (the series ends when the
    motion does, so a longer edit is never refused for overrunning 70 s); any valid plan of two waypoints or
    more opens. ``editor.trajectory`` is the last valid plan (planned on demand); ``editor.panel.last_error``
    the message shown, or None; ``editor.declaration`` the panel as data, its page program
    ``editor.declaration.page``. The sliders' ranges cover the plan's own values (positions within the arm's
    reach, durations and anticipations from 0.1 s), so loading a waypoint never clamps it.
    """

    def __init__(self, plan: dict | None = None, profiles: bool = True):
        profiles = check_flag(profiles, "profiles")
        plan = _checked_plan(plan)
        traj = plan_path(**plan)  # an invalid plan raises here, with the planner's message
        self.plan = plan
        self._trajectory = traj
        self.profiles = profiles
        self.declaration = self._declaration(traj)

    @property
    def trajectory(self):
        """The last valid plan, a :class:`~scara.trajectory.Trajectory` (planned by :func:`plan_path`)."""
        if self._trajectory is None:
            self._trajectory = plan_path(**self.plan)
        return self._trajectory

    def _declaration(self, traj):
        """The editor as data: its controls, set for the plan's first via point (or first waypoint), and its
        page program."""
        wps, durations = self.plan["waypoints"], self.plan["durations"]
        labels = [w.label for w in wps]
        segs = [f"{labels[j]}->{labels[j + 1]}" for j in range(len(wps) - 1)]
        first = next((i for i, w in enumerate(wps) if w.via), 0)
        w0, seg0 = wps[first], min(first, len(segs) - 1)
        ants = [w.anticipation for w in wps if w.via]
        reach = max(1.0, *(abs(v) for w in wps for v in w.position[:2]))
        z = [w.position[2] for w in wps]
        controls = (
            Control("point", "dropdown", "waypoint", first, options=tuple((lab, i) for i, lab in enumerate(labels))),
            Control("via", "toggle", "via point (do not stop)", w0.via),
            Control("x", "slider", "x (m)", w0.position[0], -reach, reach, 0.005, unit="m", readout=".3f"),
            Control("anticipation", "slider", "anticipation (s)", w0.anticipation or 1.0, 0.1, max(5.0, *ants, 0.1),
                    0.1, unit="s"),
            Control("y", "slider", "y (m)", w0.position[1], -reach, reach, 0.005, unit="m", readout=".3f"),
            Control("segment", "dropdown", "segment", seg0, options=tuple((sg, j) for j, sg in enumerate(segs))),
            Control("z", "slider", "z (m)", w0.position[2], min(0.0, *z), max(1.0, *z), 0.005, unit="m",
                    readout=".3f"),
            Control("duration", "slider", "duration (s)", durations[seg0], min(0.1, *durations),
                    max(20.0, *durations), 0.1, unit="s"),
        )
        n = len(wps)
        # the accepted edit is the plan the next move starts from (carry), and picking a waypoint or a segment
        # loads its values from that plan (react): declared here, done alike by both front ends
        w_at = lambda field: program.D_SPEC + SPEC_HEAD + field  # noqa: E731 - waypoint i at + 6 i
        g_at = program.D_SPEC + SPEC_HEAD + SPEC_WAYPOINT * n + G_DURATION
        react = {"point": {"x": Pick(w_at(W_X), SPEC_WAYPOINT, "point"), "y": Pick(w_at(W_Y), SPEC_WAYPOINT, "point"),
                           "z": Pick(w_at(W_Z), SPEC_WAYPOINT, "point"),
                           "via": Pick(w_at(W_ANT), SPEC_WAYPOINT, "point", "flag"),
                           "anticipation": Pick(w_at(W_ANT), SPEC_WAYPOINT, "point", "positive")},
                 "segment": {"duration": Pick(g_at, SPEC_SEGMENT, "segment")}}
        prog = PageProgram(
            kernel=program.editor_program, inputs=program.EDITOR_INPUTS,
            data=program.editor_data(plan_spec(self.plan), TOP_POINTS, PROFILE_POINTS),
            outputs=program.editor_outputs(n, TOP_POINTS, PROFILE_POINTS), refusals=editor_refusals(),
            **editor_bindings(n, self.profiles), rows=_rows(labels), notes=_NOTES,
            carry=("spec_out", program.D_SPEC), react=react,
            drag={"figure": "top view", "pick": "point", "x": "x", "y": "y"})  # the page's reader drags a waypoint
        builders, roles = editor_pairs(editor_labels(traj), n, self.profiles)
        panel = program_panel("waypoint editor", "Waypoint editor: edit the path, watch it re-planned", controls,
                              prog, builders, widget="waypoint_editor", roles=roles)
        self._run = panel.compute
        return dataclasses.replace(panel, compute=self._compute)

    # ------------------------------------------------------------------------------------------------------
    def _compute(self, v):
        """Run the program for the sliders (the picked waypoint and segment edited; an accepted edit is carried
        into the program's ``data``) and keep :attr:`plan` the plan the next moves start from."""
        values = self._run(v)
        plan = dict(self.plan, waypoints=list(self.plan["waypoints"]), durations=list(self.plan["durations"]))
        w = plan["waypoints"][v["point"]]
        plan["waypoints"][v["point"]] = w.replace(position=(v["x"], v["y"], v["z"]),
                                                  anticipation=v["anticipation"] if v["via"] else 0.0)
        plan["durations"][v["segment"]] = v["duration"]
        if plan["waypoints"] != self.plan["waypoints"] or plan["durations"] != self.plan["durations"]:
            self.plan, self._trajectory = plan, None
        return values



#: the last waypoint editor built in this process, whose plan an editor built with ``keep=True`` starts from
_LATEST: list = []


class WaypointEditor(EditorState):
    """The editor's state (:class:`EditorState`: ``plan``, ``trajectory``, ``declaration``) and its
    :class:`LivePanel` (``panel``); displayed as a cell's last expression, it shows the panel. ``keep=True``
    starts from the last accepted plan of the previous editor built in this process, and from its controls'
    last accepted settings (see :func:`waypoint_editor`)."""

    def __init__(self, plan: dict | None = None, profiles: bool = True, keep: bool = False):
        keep = check_flag(keep, "keep")
        if keep and _LATEST:
            plan = _LATEST[0].plan
        super().__init__(plan, profiles)
        self.panel = LivePanel(self.declaration, keep=keep)
        _LATEST[:] = [self]

    def _repr_mimebundle_(self, include=None, exclude=None):
        return self.panel._repr_mimebundle_(include=include, exclude=exclude)


def waypoint_editor_declaration(plan: dict | None = None, profiles: bool = True):
    """The waypoint editor's panel as data (a :class:`~scara.plots.panels.Panel` with its page program) on
    ``plan`` (default: the reference scenario of chapter 3 with ``total=None``), without widgets. Its
    ``compute`` keeps the last accepted plan, as the Jupyter panel does."""
    return EditorState(plan, profiles).declaration


# --------------------------------------------------------------------------------------------------
# the summary and the refusals, as texts of the program's outputs
# --------------------------------------------------------------------------------------------------
def _rows(labels) -> tuple:
    """The editor's table: when the motion ends, its peaks, its closest approach to a singularity and to each
    inner waypoint (0 at a stop point, which the path passes through)."""
    inner = range(1, len(labels) - 1)
    safe = [lab.replace("{", "{{").replace("}", "}}") for lab in labels]
    corners = ", ".join(f"{safe[i]}: {{corner_{i}:.1f}} mm" for i in inner) or "none"
    return (("motion ends at (s)", Text("{motion_end:.1f}")),
            ("peak speed (cm/s)", Text("{peak_speed_cm:.2f}")),
            ("peak acceleration (cm/s²)", Text("{peak_acc_cm:.2f}")),
            ("min manipulability (m²)", Text("{w_min:.4f} at {w_min_time:.1f} s")),
            ("corner distances (0 at a stop point)", Text(corners)))


_NOTES = ((Flag("near_singular"),
           Text("The path passes close to a singular configuration (w = {w_min:.2g} m² at {w_min_time:.1f} s): "
                "the joints must move fast there.")),)

_SEG = "p{s_a:.0f}->p{s_a1:.0f}"
_A, _B, _C = ("[{%sx:.4g}, {%sy:.4g}, {%sz:.4g}]" % (c, c, c) for c in "abc")
_POINT3 = "(x, y, z) = ({px:.4g}, {py:.4g}, {pz:.4g}) m"
_POINT4 = _POINT3 + ", φ = {phi_deg:.4g}°"
_ANNULUS = ("its distance from the joint-1 axis r = {r:.10g} m is outside the annulus |a1 - a2| = {r_min:g} m "
            "<= r <= a1 + a2 = {r_max:g} m")
_STROKE = ("p_z = {z_exact:.10g} m needs d3 = d0 - p_z = {d3:.10g} m, outside the stroke d3_min = {d3_min:g} m "
           "<= d3 <= d3_max = {d3_max:g} m")
_MAX = f"{MAX_SAMPLES:g}"
_WHERE = (_SEG, _SEG + " and p{s_b:.0f}->p{s_b1:.0f}",
          _SEG + " and p{s_b:.0f}->p{s_b1:.0f} and p{s_c:.0f}->p{s_c1:.0f}",
          _SEG + " and p{s_b:.0f}->p{s_b1:.0f} and p{s_c:.0f}->p{s_c1:.0f} and p{s_d:.0f}->p{s_d1:.0f}",
          _SEG + " and p{s_b:.0f}->p{s_b1:.0f} and … and p{s_d:.0f}->p{s_d1:.0f}", "at rest after " + _SEG)


def _samples_texts(what):
    return (f"{what} = {{value:g}} s is {{periods:.4g}} sampling periods dt = {{dt:g}} s, more than a plan may hold "
            f"(MAX_SAMPLES = {_MAX} samples); use a longer dt or a shorter plan",
            f"{what} = {{value:g}} s is not a whole number of sampling periods dt = {{dt:g}} s ({{periods:.6g}} "
            "periods); use a multiple of dt so that stop points fall on samples")


def editor_refusals() -> dict:
    """The text of every code the editor's program may return: the planner's messages (those of
    :func:`~scara.trajectory.plan_path`, shown with points in the panel's units as JupyterLab shows them),
    waypoints and segments named by index (``p3``, ``p3->p4``)."""
    t = {}
    t[K.DURATION_TOO_MANY], t[K.DURATION_NOT_WHOLE] = _samples_texts("duration of segment " + _SEG)
    for code, which in ((K.VIA_FIRST, "first"), (K.VIA_LAST, "last")):
        t[code] = (f"p{{w_a:.0f}} is the {which} waypoint and cannot be a via point (anticipation = {{ant:g}} s): "
                   "the arm starts and ends at rest")
    t[K.ANTICIPATION_TOO_LONG] = ("anticipation at via point p{w_a:.0f} = {ant:g} s must be shorter than both "
                                  "segments it joins: " + _SEG + " lasts {dur_a:g} s and p{s_b:.0f}->p{s_b1:.0f} "
                                  "lasts {dur_b:g} s")
    t[K.ANTICIPATION_TOO_MANY], t[K.ANTICIPATION_NOT_WHOLE] = _samples_texts("anticipation at p{w_a:.0f}")
    t[K.REPEATED_POINT] = ("repeated point: p{w_b:.0f} = p{w_a:.0f} = " + _A + "; consecutive waypoints must "
                           "differ (segment p{w_a:.0f}->p{w_b:.0f} would have zero length)")
    seg = "segment " + _SEG + ": "
    t[K.LINE_OVERFLOW] = seg + "the line has a length that overflows; the points must be finite and reasonably sized (m)"
    t[K.ARC_OVERFLOW] = (seg + "the circle through start " + _A + ", via " + _B + " and end " + _C + " cannot be computed: the "
             "points are too far apart and the arithmetic overflows")
    t[K.ARC_COLLINEAR] = (seg + "no circle passes through start " + _A + ", via " + _B + " and end " + _C + ": the points are "
             "collinear or two of them coincide")
    t[K.ARC_NORMAL_ZERO] = seg + "the normal of an arc's plane must be a non-zero vector, got [0, 0, 0]"
    t[K.ARC_START_OFF_PLANE] = seg + "the arc's start " + _A + " is not on its circle: it lies off the plane through its centre"
    t[K.ARC_END_OFF_PLANE] = seg + "the arc's end " + _C + " is not on its circle: it lies off the plane through its centre"
    t[K.ARC_RADIUS_OVERFLOW] = (seg + "the arc from start " + _A + " to end " + _C + " has a radius that overflows; the points must be "
             "reasonably sized (m)")
    t[K.ARC_RADIUS_TOO_SMALL] = seg + "an arc needs a positive radius (start " + _A + ", via " + _B + ", end " + _C + ")"
    t[K.ARC_START_OFF_CIRCLE] = seg + "the arc's start " + _A + " is not on its circle (tolerance 1e-09 m)"
    t[K.ARC_END_OFF_CIRCLE] = seg + "the arc's end " + _C + " is not on its circle (tolerance 1e-09 m)"
    t[K.ARC_SAME_ENDS] = seg + "an arc needs distinct ends, but start = end = " + _A + " (a repeated point)"
    t[K.LAW_BLEND] = (seg + "blend = {blend:g} s is longer than half the duration T/2 = {half:g} s; a trapezoidal "
                      "profile needs 0 < blend <= T/2")
    t[K.LAW_NOT_FINITE] = (seg + "length = {value:g} m over duration = {dur_a:g} s with blend = {blend:g} s needs a "
                           "speed {speed:g} m/s and an acceleration {acc:g} m/s^2 that are not finite: the length "
                           "is too large for the duration")
    t[K.GIVEN_ARC_START] = seg + "its start " + _A + " is not the waypoint " + _B
    t[K.GIVEN_ARC_END] = seg + "its end " + _A + " is not the waypoint " + _B
    t[K.START_OUTSIDE_ANNULUS] = "point " + _POINT4 + " is unreachable: " + _ANNULUS
    t[K.START_OUTSIDE_STROKE] = "point " + _POINT4 + " is unreachable: " + _STROKE
    t[K.MOTION_TOO_MANY] = ("the motion lasts {motion_end_at:g} s, {samples:.0f} samples at dt = {dt:g} s, more "
                            f"than a plan may hold (MAX_SAMPLES = {_MAX}); use a longer dt or a shorter plan")
    t[K.TOTAL_TOO_MANY], t[K.TOTAL_NOT_WHOLE] = _samples_texts("total")
    t[K.TOTAL_SAMPLES_TOO_MANY] = ("total = {total:g} s is {samples:.0f} samples at dt = {dt:g} s, more than a plan "
                                   f"may hold (MAX_SAMPLES = {_MAX}); use a longer dt or a shorter total")
    t[K.TOTAL_TOO_SHORT] = "total = {total:g} s is shorter than the motion, which ends at {motion_end_at:g} s"
    for where, text in enumerate(_WHERE):
        for why, reason in enumerate((_ANNULUS, _STROKE)):
            t[K.SAMPLE_OUT + 2 * where + why] = ("the path leaves the workspace at t = {t_out:.3f} s (sample "
                                                 "{sample:.0f}) on segment " + text + ": its point " + _POINT4 +
                                                 " is unreachable: " + reason)
    t[K.SAMPLE_NOT_FINITE] = ("the path leaves the workspace at t = {t_out:.3f} s (sample {sample:.0f}): its point "
                              "is not finite")
    t[K.WAYPOINT_OUTSIDE_ANNULUS] = "waypoint p{w_a:.0f} " + _POINT3 + " is unreachable: " + _ANNULUS
    t[K.WAYPOINT_OUTSIDE_STROKE] = "waypoint p{w_a:.0f} " + _POINT3 + " is unreachable: " + _STROKE
    t[program.SUMMARY_OUTSIDE_ANNULUS] = "sample {sample:.0f}: point " + _POINT4 + " is unreachable: " + _ANNULUS
    t[program.SUMMARY_OUTSIDE_STROKE] = "sample {sample:.0f}: point " + _POINT4 + " is unreachable: " + _STROKE
    return {code: Text(text) for code, text in t.items()}


@ahead(program.editor_program)
def waypoint_editor(plan: dict | None = None, profiles: bool = True, keep: bool = False) -> WaypointEditor:
    """A live waypoint editor on ``plan`` (default: the reference scenario of chapter 3).

    Controls: the waypoint to edit and its x/y/z (m), via or stop and the anticipation (s), the segment to
    edit and its duration (s). Every change re-plans the path and redraws the top view (and, with
    ``profiles``, the time profiles) in place; an invalid edit shows the planner's message instead and marks
    the figures stale; so does a number typed beside a slider outside its range (never clamped). Display the
    returned object as a cell's last expression.

    ``editor.trajectory`` is the last accepted plan (a :class:`~scara.trajectory.Trajectory`) and ``editor.plan``
    its arguments of :func:`~scara.trajectory.plan_path`: hand the editor, or its trajectory, to
    :func:`~scara.widgets.control_panel` or :func:`~scara.widgets.clik_panel` (``control_panel(editor)``) to run
    the controllers or the CLIK on the path edited.

    ``keep=True`` starts, when this Python process has built an editor before, from that editor's last accepted
    plan (all its edits; ``plan`` is then used only when there was none) and its picked waypoint and segment:
    re-running the cell keeps the path edited. Raises :class:`ScaraError` for an invalid ``plan`` or a
    ``profiles`` or ``keep`` that is not a bool.
    """
    return WaypointEditor(plan, profiles, keep)
