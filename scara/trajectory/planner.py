"""Multi-segment operational-space trajectories through stop points and via points.

A path is a list of waypoints joined by segments (straight lines, or circular arcs where asked). Each segment
``j`` (from waypoint ``j`` to ``j+1``) runs its own trapezoidal timing law ``s_j(t)`` over its duration ``T_j``.
At a stop point the next segment starts when the current one ends, so the arm is at rest there for an instant.
At a via point with anticipation ``dT`` the next segment starts ``dT`` before the current one ends and the two
displacements add up (Siciliano et al., eq. 4.56):

    p_e(t) = p_0 + sum_j [ p_j(s_j(t)) - p_j(0) ]
    pdot_e = sum_j t_j sdot_j,          pddot_e = sum_j ( t_j sddot_j + k_j sdot_j^2 )

so the corner is rounded and the speed never drops to zero there. The orientation ``phi`` rides on the same
timing laws: segment ``j`` adds ``(phi_{j+1} - phi_j) s_j / L_j``.

All segment boundaries are whole numbers of samples, so every stop point falls exactly on a sample.

The planning itself is compiled (:mod:`scara.trajectory._plan`): :func:`plan_path` checks the types and shapes of
its inputs, packs them as a float vector, and runs the kernels that check and resolve the plan, sample it and
check it against the workspace, the very kernels the live waypoint editor runs on every move (in Jupyter and,
translated, in the book's pages). :class:`Trajectory` keeps the planned path as that vector (``plan_vector``).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import (ScaraError, ShapeError, UnreachableError, as_array, check_flag, check_index, check_number,
                      check_positive)
from ..kinematics import _elbow_sign, check_reachable, ikine
from ..params import ScaraParams
from .._manipulability import manipulability
from . import _plan as K
from ._plan import MAX_SAMPLES
from .paths import Arc, Line, _fmt
from .timing import DEFAULT_BLEND_FRACTION, Trapezoidal, times

__all__ = ["Waypoint", "Trajectory", "plan_path", "plan_spec", "start_orientation", "MAX_SAMPLES"]


@dataclass(frozen=True)
class Waypoint:
    """A point of the path (base frame, m).

    ``anticipation`` (s) > 0 makes it a via point: the next segment starts that long before the arm arrives,
    and the arm rounds the corner without stopping. ``anticipation = 0`` (default) makes it a stop point.
    ``phi`` (rad), if given, is the orientation to reach there; otherwise the previous waypoint's is kept.
    ``label`` names it in messages and plots (default ``p<index>``).

    >>> Waypoint([0.10, 0.10, 0.5], anticipation=2.0).via
    True
    """

    position: tuple
    anticipation: float = 0.0
    phi: float | None = None
    label: str | None = None

    def __post_init__(self):
        pos = as_array(self.position, "waypoint position", (3,))
        object.__setattr__(self, "position", tuple(float(v) for v in pos))
        a = check_number(self.anticipation, "anticipation", "a number of seconds")
        if a < 0:
            raise ScaraError(f"anticipation = {a} s must be >= 0 (0 makes a stop point)")
        object.__setattr__(self, "anticipation", a)
        if self.phi is not None:
            object.__setattr__(self, "phi", check_number(self.phi, "phi at a waypoint", "a number of radians"))

    @property
    def via(self) -> bool:
        """True for a via point (positive anticipation)."""
        return self.anticipation > 0

    def replace(self, **changes) -> "Waypoint":
        """A copy with fields replaced, e.g. ``w.replace(anticipation=0)`` turns a via point into a stop."""
        return dataclasses.replace(self, **changes)


def start_orientation(point, p=None, elbow: int = -1) -> float:
    """The orientation ``phi = theta1 + theta2`` of the configuration reaching ``point`` (3,) with the given
    elbow and ``theta4 = 0`` (chapter 3: phi is held at the start configuration's value).

    >>> round(start_orientation([0.18, 0.20, 0.5]), 6)
    -2.136348
    """
    q = ikine(np.r_[as_array(point, "point", (3,)), 0.0], p, elbow=elbow)
    return float(q[0] + q[1])


def _samples(value: float, dt: float, what: str) -> int:
    """``value`` (s) as a whole number of sampling periods ``dt`` (:func:`~scara.trajectory._plan.whole_samples`),
    or :class:`ScaraError` naming ``what``."""
    code, n = K.whole_samples(float(value), float(dt))
    if code != 0:
        raise ScaraError(_samples_message(what, value, dt, code))
    return int(n)


def _samples_message(what: str, value: float, dt: float, code: int) -> str:
    """The message of :func:`~scara.trajectory._plan.whole_samples`'s ``code`` for ``value`` (s) named ``what``."""
    if code == 1:
        with np.errstate(over="ignore"):
            periods = float(value) / float(dt)
        return (f"{what} = {value:g} s is {periods:.4g} sampling periods dt = {dt:g} s, more than a plan "
                f"may hold (MAX_SAMPLES = {MAX_SAMPLES:g} samples); use a longer dt or a shorter plan")
    return (f"{what} = {value:g} s is not a whole number of sampling periods dt = {dt:g} s "
            f"({value / dt:.6g} periods); use a multiple of dt so that stop points fall on samples")


class Trajectory:
    """A planned operational-space trajectory, sampled every ``dt``.

    Sampled series (the interface every later chapter uses): ``t`` (N,) in s; ``x``, ``xd``, ``xdd`` (N, 4):
    ``[p_x, p_y, p_z, phi]`` in m and rad, its velocity and its acceleration.

    Metadata: ``waypoints`` (n, 3), ``labels`` (n,), ``via`` (n,) bool, ``anticipations`` (n,) s,
    ``phi_waypoints`` (n,) rad, ``segments`` (m,) path primitives, ``segment_kinds`` (m,) ``"line"``/``"arc"``,
    ``segment_labels`` (m,) like ``"p3->p4"``, ``laws`` (m,) :class:`Trapezoidal`, ``durations``, ``blends``,
    ``segment_start``, ``segment_end`` (m,) s, ``motion_end`` (s, when the last segment ends), ``total`` (s),
    ``rest`` (s at rest at the end), ``elbow`` and ``q0`` (the start configuration).

    Build one with :func:`plan_path` or :func:`~scara.trajectory.reference_trajectory`; :meth:`evaluate`
    gives the same quantities at any times, :meth:`replan` a modified copy.
    """

    def __init__(self, *, waypoints, durations, blends, arcs, phi, total, dt, p, elbow, check, _built):
        self.inputs = dict(waypoints=list(waypoints), durations=list(durations), blends=blends, arcs=arcs,
                           phi=phi, total=total, dt=dt, p=p, elbow=elbow, check=check)
        for k, v in _built.items():
            setattr(self, k, v)
        n_samples = self._total_samples + 1
        self.t = np.empty(n_samples)
        self.x, self.xd, self.xdd = np.empty((n_samples, 4)), np.empty((n_samples, 4)), np.empty((n_samples, 4))
        K.sample_plan(self._plan, self.t, self.x, self.xd, self.xdd)
        for arr in (self.t, self.x, self.xd, self.xdd, self._plan):
            arr.flags.writeable = False
        self._cache = {}

    @property
    def plan_vector(self) -> np.ndarray:
        """The planned path packed as a float vector (read-only), the layout of :mod:`scara.programs.path`:
        what :func:`~scara.programs.path.sample_plan` samples."""
        return self._plan

    # -- evaluation ----------------------------------------------------------------------------------
    def evaluate(self, t):
        """``x, xd, xdd`` (each (n, 4)) at arbitrary times ``t`` (n,) in s, by eq. 4.56 of the module docstring
        (:func:`~scara.trajectory._plan.plan_at`, the kernel that samples the trajectory).

        Before 0 the arm is at the first waypoint; after the last segment it rests at the last one. A NaN or
        infinite time raises :class:`~scara.NonFiniteError`.
        """
        t = np.ascontiguousarray(times(t, "t").reshape(-1), dtype=float)
        n = t.size
        x, xd, xdd = np.empty((n, 4)), np.empty((n, 4)), np.empty((n, 4))
        K.evaluate_plan(self._plan, t, x, xd, xdd)
        return x, xd, xdd

    def replan(self, **changes) -> "Trajectory":
        """A new trajectory from the same inputs with some replaced (any keyword of :func:`plan_path`)."""
        unknown = set(changes) - set(self.inputs)
        if unknown:
            raise ScaraError(f"unknown planning input(s) {sorted(unknown)}; known: {sorted(self.inputs)}")
        kw = {**self.inputs, **changes}
        return plan_path(**kw)

    # -- queries -------------------------------------------------------------------------------------
    def segments_at(self, time: float) -> list[int]:
        """Indices of the segments moving at ``time`` (two during a via point's overlap, none at rest)."""
        time = float(times(time, "time"))
        return [j for j in range(len(self.segments)) if self.segment_start[j] <= time < self.segment_end[j]]

    def _segment_names(self, time: float) -> str:
        idx = self.segments_at(time)
        if not idx:
            return "at rest after " + (self.segment_labels[-1] if time >= self.motion_end else "the start")
        return " and ".join(self.segment_labels[j] for j in idx)

    def speed(self) -> np.ndarray:
        """Linear speed ``|pdot|`` (N,) in m/s."""
        return np.linalg.norm(self.xd[:, :3], axis=1)

    def joints(self, p=None) -> np.ndarray:
        """Joint path ``q(t)`` (N, 4) by closed-form inverse kinematics with this trajectory's elbow (for the
        arm ``p``; default the one the plan was checked against). Raises :class:`UnreachableError` if ``p``
        cannot reach some sample."""
        if p is not None and p != self.params:
            return ikine(self.x, p, elbow=self.elbow)
        if "q" not in self._cache:
            q = ikine(self.x, self.params, elbow=self.elbow)
            q.flags.writeable = False
            self._cache["q"] = q
        return self._cache["q"]

    def manipulability(self, p=None) -> np.ndarray:
        """Manipulability ``w(q(t)) = a1 a2 |sin theta2|`` (N,) along the path."""
        pp = p if p is not None else self.params
        return manipulability(self.joints(p), pp)

    def corner_distances(self) -> dict:
        """Closest approach to every via point: ``{label: (distance m, time s)}``.

        The minimum of ``|p_e(t) - p_via|`` over the overlap of the two segments (outside it the arm is on
        one of the straight lines, farther away), found on the samples and refined between the neighbouring
        samples with :meth:`evaluate` (four passes of 65 samples each, which fix the time to about 1e-9 s).
        Zero for a via point lying on a straight continuation (only the speed blends there). Computed by
        :func:`~scara.trajectory._plan.corner_distance`.
        """
        out = {}
        for i in np.flatnonzero(self.via):
            d, when = K.corner_distance(self._plan, self.x, int(i))
            out[self.labels[i]] = (float(d), float(when))
        return out

    def segment_table(self) -> list[dict]:
        """One row per segment: what the chapter's table shows (lengths in m, times in s, speeds in m/s,
        accelerations in m/s^2; ``peak_acceleration`` adds the centripetal part on an arc)."""
        rows = []
        for j, (seg, law) in enumerate(zip(self.segments, self.laws)):
            v = law.cruise_speed
            centripetal = v * v / seg.radius if seg.kind == "arc" else 0.0
            rows.append(dict(
                segment=self.segment_labels[j], kind=seg.kind, length=seg.length, duration=law.duration,
                blend=law.blend, start=float(self.segment_start[j]), end=float(self.segment_end[j]),
                anticipation=float(self.anticipations[j + 1]), cruise_speed=v, acceleration=law.acceleration,
                peak_acceleration=math.hypot(law.acceleration, centripetal) if seg.kind == "arc" else law.acceleration,
            ))
        return rows

    def summary(self) -> dict:
        """The figures the chapter reports: timing, path length, peak speed and acceleration, manipulability
        minimum (value, time, segment, point), corner distances at the via points."""
        if "summary" in self._cache:
            return dict(self._cache["summary"])
        q = self.joints()  # raises for a sample out of reach of this trajectory's arm
        ext = np.empty(K.EXTREMES)
        K.plan_extremes(self._plan, self.x, self.xd, self.xdd, ext)
        ks, ka, kw = int(ext[K.X_SPEED_K]), int(ext[K.X_ACC_K]), int(ext[K.X_W_K])
        qd = np.gradient(q, self.dt, axis=0)
        out = dict(
            duration=float(self.total), samples=int(self.t.size), dt=float(self.dt),
            motion_end=float(self.motion_end), rest=float(self.rest),
            waypoints=len(self.labels), segments=len(self.segments),
            via_points=[self.labels[i] for i in np.flatnonzero(self.via)],
            path_length=float(sum(s.length for s in self.segments)),
            max_speed=float(ext[K.X_SPEED]), max_speed_time=float(self.t[ks]),
            max_acceleration=float(ext[K.X_ACC]), max_acceleration_time=float(self.t[ka]),
            max_phi_rate=float(np.max(np.abs(self.xd[:, 3]))),
            max_joint_speed=np.max(np.abs(qd), axis=0).tolist(),
            min_manipulability=float(ext[K.X_W]), min_manipulability_time=float(self.t[kw]),
            min_manipulability_segment=self._segment_names(float(self.t[kw])),
            min_manipulability_point=self.x[kw, :3].tolist(),
            corner_distances={k: v[0] for k, v in self.corner_distances().items()},
        )
        self._cache["summary"] = out
        return dict(out)

    def __repr__(self):
        return (f"Trajectory({len(self.labels)} waypoints, {len(self.segments)} segments, "
                f"via {[self.labels[i] for i in np.flatnonzero(self.via)]}, {self.total:g} s at dt = {self.dt:g} s, "
                f"{self.t.size} samples)")


def _as_waypoint(w, i) -> Waypoint:
    if isinstance(w, Waypoint):
        return w if w.label is not None else w.replace(label=f"p{i}")
    return Waypoint(as_array(w, f"waypoint p{i}", (3,)), label=f"p{i}")


def plan_path(waypoints, durations, *, blends=None, arcs=None, phi=None, total=None, dt: float = 1e-3,
              p=None, elbow: int = -1, check: bool = True) -> Trajectory:
    """Plan and sample a trajectory through ``waypoints`` (module docstring: eq. 4.56 of Siciliano et al.).

    Parameters
    ----------
    waypoints : sequence of :class:`Waypoint` or of positions (3,)
        At least two; a bare position is a stop point.
    durations : sequence (n - 1,)
        Duration ``T_j`` (s) of each segment's timing law, a whole number of samples.
    blends : sequence (n - 1,) of float or None, optional
        Blend time of each segment's trapezoid (s); None (default) is a third of the duration.
    arcs : dict {segment index: point (3,) or Arc}, optional
        Segments that are circular arcs: either the arc through that point, or a ready :class:`Arc`
        whose ends must be the segment's waypoints. Others are straight lines.
    phi : float, optional
        Constant orientation (rad). Default: the start configuration's ``theta1 + theta2`` (see
        :func:`start_orientation`). Waypoints with their own ``phi`` plan it along the path.
    total : float, optional
        Length of the sampled series (s); the arm rests at the last waypoint after the last segment.
        Default: the end of the last segment.
    dt : float
        Sampling period (s), default 1 ms.
    p : ScaraParams, optional
        The arm whose workspace is checked (default ``ScaraParams()``).
    elbow : +1 or -1
        Elbow of the start configuration (and of :meth:`Trajectory.joints`); default -1 (``theta2 < 0``).
    check : bool
        Check that every sample is reachable (default True).

    Returns
    -------
    Trajectory

    Raises
    ------
    ScaraError
        Fewer than two waypoints; a repeated point; a blend longer than half its segment; an anticipation at
        the first or last waypoint, or not shorter than both segments it joins; durations, anticipations or
        ``total`` that are not whole numbers of samples; ``total`` shorter than the motion; an arc whose ends
        are not on its circle or are not the segment's waypoints.
    UnreachableError
        A sample leaves the workspace: the message names the first such time, point and segment; or a via
        point lies out of reach although its rounded corner does not (the message names the waypoint).

    >>> traj = plan_path([[0.3, 0.2, 0.5], [0.5, 0.2, 0.5]], durations=[2.0], total=3.0)
    >>> traj.t.shape, traj.x.shape, float(traj.x[-1, 0])
    ((3001,), (3001, 4), 0.5)
    """
    v = _inputs(waypoints, durations, blends, arcs, phi, total, dt, p, elbow, check)
    wps, labels, seg_labels, pos, arcs, arc_in = v.wps, v.labels, v.seg_labels, v.pos, v.arcs, v.arc_in
    T_in, tc_in, blends, phi, total_f, p_checked, dt, check = v.T, v.tc, v.blends, v.phi, v.total, v.p, v.dt, v.check
    spec = v.spec
    plan = np.empty(K.plan_size(len(wps)))
    info = np.zeros(K.INFO_SIZE)
    code = K.build_plan(spec, plan, info)
    if code != K.PLAN_OK:
        _raise_plan_error(code, info, wps, labels, seg_labels, pos, arcs, arc_in, T_in, tc_in, dt, phi, total_f,
                          p_checked, elbow)

    n, m = len(wps), len(seg_labels)
    seg = [K.plan_segment(n, j) for j in range(m)]
    way = [K.plan_waypoint(n, i) for i in range(n)]
    nT = np.array([plan[q + K.Q_K1] - plan[q + K.Q_K0] for q in seg]).astype(np.int64)
    nA = np.array([plan[v + K.V_NA] for v in way]).astype(np.int64)
    k0 = np.array([plan[q + K.Q_K0] for q in seg]).astype(np.int64)
    k1 = np.array([plan[q + K.Q_K1] for q in seg]).astype(np.int64)
    k_end, k_total = int(plan[K.P_K_END]), int(plan[K.P_K])
    T = nT * dt  # the durations the samples realise (equal to the inputs up to rounding)
    phis = [float(plan[v + K.V_PHI]) for v in way]
    segments = [_segment(pos[j], pos[j + 1], arcs.get(j), j) for j in range(m)]
    laws = [Trapezoidal(sg.length, T[j], DEFAULT_BLEND_FRACTION * T[j] if np.isnan(tc_in[j]) else tc_in[j])
            for j, sg in enumerate(segments)]
    q0 = ikine(np.r_[pos[0], phis[0]], p_checked, elbow=elbow)
    ant = np.array([w.anticipation for w in wps])
    built = dict(
        dt=dt, params=p_checked, elbow=elbow, q0=q0,
        waypoints=pos, labels=labels, via=ant > 0, anticipations=nA * dt, phi_waypoints=np.array(phis),
        segments=segments, segment_kinds=[s.kind for s in segments], segment_labels=seg_labels, laws=laws,
        durations=nT * dt, blends=np.array([law.blend for law in laws]),
        segment_start=k0 * dt, segment_end=k1 * dt, motion_end=k_end * dt,
        total=k_total * dt, rest=(k_total - k_end) * dt, _total_samples=k_total, _plan=plan,
    )
    traj = Trajectory(waypoints=wps, durations=list(T), blends=blends, arcs=arcs, phi=phi, total=total, dt=dt,
                      p=p, elbow=elbow, check=check, _built=built)
    if check:
        _check_in_reach(traj, p_checked)
    return traj


def _inputs(waypoints, durations, blends, arcs, phi, total, dt, p, elbow, check):
    """The inputs of :func:`plan_path` checked (types, shapes, signs) and packed as the spec of
    :mod:`scara.programs.path` (``.spec``), with the objects the planner keeps."""
    from types import SimpleNamespace  # noqa: PLC0415

    dt = check_positive(dt, "dt")
    check = check_flag(check, "check")
    wps, labels, seg_labels, pos = _waypoints(waypoints)
    T_in = _durations(durations, seg_labels)
    blends, tc_in = _blend_inputs(blends, len(seg_labels))
    arcs, arc_in = _arc_inputs(arcs, pos, seg_labels)
    if phi is not None:
        phi = check_number(phi, "phi", "a number of radians")
    total_f = None if total is None else check_positive(total, "total")
    p_checked = ScaraParams.resolve(p)
    elbow_sign = _elbow_sign(elbow)
    spec = _spec(wps, T_in, tc_in, arc_in, phi, total_f, dt, p_checked, elbow_sign, check)
    return SimpleNamespace(wps=wps, labels=labels, seg_labels=seg_labels, pos=pos, T=T_in, tc=tc_in, blends=blends,
                           arcs=arcs, arc_in=arc_in, phi=phi, total=total_f, p=p_checked, elbow=elbow, dt=dt,
                           check=check, spec=spec)


def plan_spec(waypoints, durations, *, blends=None, arcs=None, phi=None, total=None, dt: float = 1e-3, p=None,
              elbow: int = -1, check: bool = True) -> np.ndarray:
    """The inputs of :func:`plan_path` (the same arguments) checked for their types, shapes and signs and packed
    as the spec of :mod:`scara.programs.path`, the vector :func:`~scara.trajectory._plan.build_plan` plans from."""
    return _inputs(waypoints, durations, blends, arcs, phi, total, dt, p, elbow, check).spec


def _waypoints(waypoints):
    """The waypoints as :class:`Waypoint` objects, their labels, the segments' labels and the positions (n, 3)."""
    try:
        wps = list(waypoints)
    except TypeError as exc:
        raise ScaraError(f"waypoints must be a sequence of points, got {waypoints!r}") from exc
    if len(wps) < 2:
        raise ScaraError(f"a path needs at least two waypoints, got {len(wps)}")
    wps = [_as_waypoint(w, i) for i, w in enumerate(wps)]
    labels = [w.label for w in wps]
    seg_labels = [f"{labels[j]}->{labels[j + 1]}" for j in range(len(wps) - 1)]
    return wps, labels, seg_labels, np.array([w.position for w in wps])


def _durations(durations, seg_labels):
    """Each segment's duration (s), checked positive (the kernel checks it is a whole number of samples)."""
    m = len(seg_labels)
    if np.ndim(durations) != 1 or len(durations) != m:
        raise ShapeError(f"durations must have one entry per segment ({m} for {m + 1} waypoints), got {durations!r}")
    T = as_array(durations, "durations", (m,))
    for j in range(m):
        check_positive(T[j], f"duration of segment {seg_labels[j]}")
    return np.array(T, dtype=float)


def _blend_inputs(blends, m):
    """The blends as given (a list, None for the default) and as numbers (NaN for the default: a third of the
    duration), each checked positive."""
    if blends is not None and (isinstance(blends, (str, bytes, dict)) or np.ndim(blends) != 1):
        raise ShapeError(f"blends must be a sequence with one blend time (s, or None) per segment ({m}), "
                         f"got {blends!r}")
    blends = [None] * m if blends is None else list(blends)
    if len(blends) != m:
        raise ShapeError(f"blends must have one entry per segment ({m}), got {len(blends)}")
    tc = np.array([math.nan if b is None else check_positive(b, f"blends[{j}]") for j, b in enumerate(blends)])
    return blends, tc


def _arc_inputs(arcs, pos, seg_labels):
    """The ``arcs`` dict checked (keys are segment indices) and, per segment, None (a line), the point an arc
    passes through (3,), or a ready :class:`Arc`."""
    m = len(seg_labels)
    if arcs is not None and not isinstance(arcs, dict):
        raise ScaraError(f"arcs must be a dict {{segment index: point (3,) or Arc}}, got {arcs!r}")
    arcs = dict(arcs or {})
    for key in arcs:
        try:
            check_index(key, "an arcs key", m)
        except ScaraError as exc:
            raise ScaraError(f"arcs keys are segment indices 0..{m - 1} (segment j joins waypoints j and j+1), "
                             f"got {key!r}") from exc
    out = []
    for j in range(m):
        arc = arcs.get(j)
        if arc is not None and not isinstance(arc, Arc):
            try:
                arc = as_array(arc, f"arcs[{j}] (a point the arc passes through)", (3,))
            except ScaraError as exc:
                raise type(exc)(f"segment {seg_labels[j]}: {exc}") from exc
        out.append(arc)
    return arcs, out


def _spec(wps, T, tc, arcs, phi, total, dt, p, elbow, check):
    """The plan's inputs packed as the spec of :mod:`scara.programs.path`."""
    n = len(wps)
    spec = np.zeros(K.spec_size(n))
    spec[[K.S_N, K.S_DT, K.S_TOTAL, K.S_PHI, K.S_ELBOW, K.S_CHECK]] = (
        n, dt, math.nan if total is None else total, math.nan if phi is None else phi, elbow, float(check))
    spec[[K.S_A1, K.S_A2, K.S_D0, K.S_D3_MIN, K.S_D3_MAX]] = p.a1, p.a2, p.d0, p.d3_min, p.d3_max
    for i, w in enumerate(wps):
        o = K.spec_waypoint(n, i)
        spec[o:o + 3] = w.position
        spec[o + K.W_ANT] = w.anticipation
        spec[o + K.W_HAS_PHI] = 0.0 if w.phi is None else 1.0
        spec[o + K.W_PHI] = 0.0 if w.phi is None else w.phi
    for j, arc in enumerate(arcs):
        o = K.spec_segment(n, j)
        spec[o + K.G_DURATION] = T[j]
        spec[o + K.G_BLEND] = tc[j]
        if arc is None:
            spec[o + K.G_ARC] = K.ARC_NONE
        elif isinstance(arc, Arc):
            spec[o + K.G_ARC] = K.ARC_GIVEN
            d = o + K.G_DATA
            for off, v in ((K.GA_START, arc.start), (K.GA_END, arc.end), (K.GA_CENTRE, arc.centre), (K.GA_U, arc._u),
                           (K.GA_V, arc._v)):
                spec[d + off:d + off + 3] = v
            spec[d + K.GA_RADIUS], spec[d + K.GA_ANGLE], spec[d + K.GA_LENGTH] = arc.radius, arc.angle, arc.length
        else:
            spec[o + K.G_ARC] = K.ARC_THROUGH
            spec[o + K.G_DATA:o + K.G_DATA + 3] = arc
    return spec


def _segment(a, b, arc, j):
    """The path primitive of a segment the kernels accepted: a line, the arc through a point, or the given arc."""
    if arc is None:
        return Line(a, b)
    if isinstance(arc, Arc):
        return arc
    return Arc.through(a, as_array(arc, f"arcs[{j}] (a point the arc passes through)", (3,)), b)


def _raise_plan_error(code, info, wps, labels, seg_labels, pos, arcs, arc_in, T_in, tc_in, dt, phi, total, p, elbow):
    """Raise the error of :func:`~scara.trajectory._plan.build_plan`'s ``code`` (the numbers in ``info``)."""
    F = dict(zip(K.INFO.names, info))
    i, j = int(F["w_a"]), int(F["s_a"])
    if code in (K.DURATION_TOO_MANY, K.DURATION_NOT_WHOLE):
        raise ScaraError(_samples_message(f"duration of segment {seg_labels[j]}", F["value"], dt,
                                          1 if code == K.DURATION_TOO_MANY else 2))
    if code in (K.VIA_FIRST, K.VIA_LAST):
        raise ScaraError(f"{wps[i].label} is the {'first' if i == 0 else 'last'} waypoint and cannot be a via "
                         f"point (anticipation = {F['ant']:g} s): the arm starts and ends at rest")
    if code == K.ANTICIPATION_TOO_LONG:
        raise ScaraError(f"anticipation at via point {wps[i].label} = {F['ant']:g} s must be shorter than "
                         f"both segments it joins: {seg_labels[i - 1]} lasts {F['dur_a']:g} s and "
                         f"{seg_labels[i]} lasts {F['dur_b']:g} s")
    if code in (K.ANTICIPATION_TOO_MANY, K.ANTICIPATION_NOT_WHOLE):
        raise ScaraError(_samples_message(f"anticipation at {wps[i].label}", F["value"], dt,
                                          1 if code == K.ANTICIPATION_TOO_MANY else 2))
    if code == K.REPEATED_POINT:
        raise ScaraError(f"repeated point: {labels[j + 1]} = {labels[j]} = {_fmt(pos[j])}; consecutive waypoints "
                         f"must differ (segment {seg_labels[j]} would have zero length)")
    if code in (K.GIVEN_ARC_START, K.GIVEN_ARC_END):
        name, got, want = (("start", arcs[j].start, pos[j]) if code == K.GIVEN_ARC_START
                           else ("end", arcs[j].end, pos[j + 1]))
        raise ScaraError(f"segment {seg_labels[j]}: its {name} {_fmt(got)} is not the waypoint {_fmt(want)}")
    if 8 <= code <= 19:  # the geometry kernels' codes: the primitive raises its own message
        try:
            _segment(pos[j], pos[j + 1], arc_in[j], j)
        except ScaraError as exc:
            raise type(exc)(f"segment {seg_labels[j]}: {exc}") from exc
    if code in (K.LAW_BLEND, K.LAW_NOT_FINITE):
        T = round(T_in[j] / dt) * dt
        try:
            Trapezoidal(_segment(pos[j], pos[j + 1], arc_in[j], j).length, T,
                        DEFAULT_BLEND_FRACTION * T if np.isnan(tc_in[j]) else tc_in[j])
        except ScaraError as exc:
            raise ScaraError(f"segment {seg_labels[j]}: {exc}") from exc
    if code in (K.START_OUTSIDE_ANNULUS, K.START_OUTSIDE_STROKE):
        if wps[0].phi is None and phi is None:
            start_orientation(pos[0], p, elbow)
        ikine(np.r_[pos[0], wps[0].phi if wps[0].phi is not None else phi], p, elbow=elbow)
    if code == K.MOTION_TOO_MANY:
        raise ScaraError(f"the motion lasts {F['motion_end_at']:g} s, {int(F['samples'])} samples at dt = {dt:g} s, "
                         f"more than a plan may hold (MAX_SAMPLES = {MAX_SAMPLES:g}); use a longer dt or a shorter "
                         f"plan")
    if code in (K.TOTAL_TOO_MANY, K.TOTAL_NOT_WHOLE):
        raise ScaraError(_samples_message("total", total, dt, 1 if code == K.TOTAL_TOO_MANY else 2))
    if code == K.TOTAL_SAMPLES_TOO_MANY:
        raise ScaraError(f"total = {total:g} s is {int(F['samples'])} samples at dt = {dt:g} s, more than a plan may "
                         f"hold (MAX_SAMPLES = {MAX_SAMPLES:g}); use a longer dt or a shorter total")
    if code == K.TOTAL_TOO_SHORT:
        raise ScaraError(f"total = {total:g} s is shorter than the motion, which ends at {F['motion_end_at']:g} s")
    raise ScaraError(f"the planner refused the plan with code {code}")  # pragma: no cover - every code is above


def _check_in_reach(traj, p):
    """Every sample in the workspace (the message names the first one out and its segment), and every waypoint
    too: a via point's corner is rounded, so the path may stay in reach while the point itself is not, and the
    arm would be asked to pass near a point it could never reach (:func:`~scara.trajectory._plan.plan_reach`)."""
    info = np.zeros(K.INFO_SIZE)
    code = K.plan_reach(traj._plan, traj.x, info)
    if code == 0:
        return
    if code < K.WAYPOINT_OUTSIDE_ANNULUS:
        k = int(info[K.I_SAMPLE])
        tk = float(traj.t[k])
        try:
            check_reachable(traj.x[k], p, label="its point")
            why = ""
        except UnreachableError as exc:
            why = f": {exc}"
        raise UnreachableError(f"the path leaves the workspace at t = {tk:.3f} s (sample {k}) on segment "
                               f"{traj._segment_names(tk)}{why}")
    i = int(info[K.I_W_A])
    check_reachable(traj.waypoints[i], p, label=f"waypoint {traj.labels[i]}")
