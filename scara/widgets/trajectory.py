"""Live panel of chapter 3 (trajectory planning): a waypoint editor. Jupyter only.

Pick a waypoint and move it with the x/y/z sliders, make it a via point or a stop, change a segment's
duration or a via point's anticipation: the path is re-planned with :func:`~scara.trajectory.plan_path` and
redrawn in place at once. An invalid or unreachable edit shows the planner's message and marks the figures
stale; the plan keeps its last valid state, so picking another waypoint or undoing the edit goes on from there.
"""
from __future__ import annotations

import numpy as np

from ..errors import ScaraError, check_flag, check_number
from ..plots.panels import Control, Panel
from ..plots.trajectory import editor_pairs
from ..trajectory import Waypoint, plan_path, reference_plan
from ._common import LivePanel

__all__ = ["WaypointEditor", "waypoint_editor"]

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


class WaypointEditor:
    """The editor's state (``plan``: keyword arguments of :func:`plan_path`) and its :class:`LivePanel`.

    ``plan`` defaults to the reference scenario of chapter 3 with ``total=None`` (the series ends when the
    motion does, so a longer edit is never refused for overrunning 70 s); any valid plan of two waypoints or
    more opens. ``editor.trajectory`` is the last valid plan; ``editor.panel.last_error`` the message shown, or
    None; ``editor.declaration`` the panel as data. The sliders' ranges cover the plan's own values (positions
    within the arm's reach, durations and anticipations from 0.1 s), so loading a waypoint never clamps it.
    """

    def __init__(self, plan: dict | None = None, profiles: bool = True):
        profiles = check_flag(profiles, "profiles")
        plan = _checked_plan(plan)
        self.trajectory = plan_path(**plan)  # an invalid plan raises here, with the planner's message
        self.plan = plan
        self.profiles = profiles
        self.declaration = self._declaration()
        self.panel = LivePanel(self.declaration)

    def _declaration(self) -> Panel:
        """The editor as data: its controls, set for the plan's first via point (or first waypoint)."""
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
        return Panel("waypoint editor", "Waypoint editor: edit the path, watch it re-planned", controls,
                     self._compute, editor_pairs(self.profiles, TOP_POINTS, PROFILE_POINTS), _summary,
                     react=self._react)

    # ------------------------------------------------------------------------------------------------------
    def _react(self, name: str, settings: dict) -> dict:
        """A waypoint or segment picked: its current values, for the sliders (one redraw follows)."""
        if name == "point":
            w = self.plan["waypoints"][settings["point"]]
            out = dict(zip("xyz", w.position), via=w.via)
            if w.via:
                out["anticipation"] = w.anticipation
            return out
        if name == "segment":
            return {"duration": self.plan["durations"][settings["segment"]]}
        return {}

    def _compute(self, v):
        """Apply the sliders to the picked waypoint and segment and re-plan; the plan changes only if the
        planner accepts the edit."""
        plan = dict(self.plan, waypoints=list(self.plan["waypoints"]), durations=list(self.plan["durations"]))
        w = plan["waypoints"][v["point"]]
        plan["waypoints"][v["point"]] = w.replace(position=(v["x"], v["y"], v["z"]),
                                                  anticipation=v["anticipation"] if v["via"] else 0.0)
        plan["durations"][v["segment"]] = v["duration"]
        traj = plan_path(**plan)
        self.plan, self.trajectory = plan, traj
        return dict(traj=traj, point=v["point"], summary=traj.summary())

    def _ipython_display_(self):
        self.panel._ipython_display_()


def _summary(s):
    """The editor's table and notes: when the motion ends, its peaks, its closest approach to a singularity."""
    summ = s["summary"]
    corner = ", ".join(f"{name}: {1000 * v:.1f} mm" for name, v in summ["corner_distances"].items()) or "none"
    rows = [("motion ends at (s)", f"{summ['motion_end']:.1f}"),
            ("peak speed (cm/s)", f"{100 * summ['max_speed']:.2f}"),
            ("peak acceleration (cm/s²)", f"{100 * summ['max_acceleration']:.2f}"),
            ("min manipulability (m²)",
             f"{summ['min_manipulability']:.4f} at {summ['min_manipulability_time']:.1f} s"),
            ("corner distances at the via points", corner)]
    notes = []
    if summ["min_manipulability"] < 0.01:
        notes.append(f"The path passes close to a singular configuration (w = {summ['min_manipulability']:.2g} m² "
                     f"at {summ['min_manipulability_time']:.1f} s): the joints must move fast there.")
    return rows, notes


def waypoint_editor(plan: dict | None = None, profiles: bool = True) -> WaypointEditor:
    """A live waypoint editor on ``plan`` (default: the reference scenario of chapter 3).

    Controls: the waypoint to edit and its x/y/z (m), via or stop and the anticipation (s), the segment to
    edit and its duration (s). Every change re-plans the path and redraws the top view (and, with
    ``profiles``, the time profiles) in place; an invalid edit shows the planner's message instead and marks
    the figures stale. Display the returned object as a cell's last expression.
    """
    return WaypointEditor(plan, profiles)
