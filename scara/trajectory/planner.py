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
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import (ScaraError, ShapeError, UnreachableError, as_array, check_flag, check_index, check_number,
                      check_positive)
from ..kinematics import check_reachable, ikine, is_reachable
from ..params import ScaraParams
from .._manipulability import manipulability
from .paths import GEOMETRY_TOL, Arc, Line, _fmt
from .timing import DEFAULT_BLEND_FRACTION, Trapezoidal, in_time_order, times

__all__ = ["Waypoint", "Trajectory", "plan_path", "start_orientation", "MAX_SAMPLES"]

#: largest number of samples of a planned trajectory (``total / dt + 1``), checked before any work: each sample
#: holds ``t``, ``x``, ``xd``, ``xdd`` (104 bytes), so the limit caps a plan at about 200 MB; the reference
#: scenario has 70 001 samples at 1 ms
MAX_SAMPLES = 2_000_000


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
    with np.errstate(over="ignore"):
        periods = float(value) / float(dt)
    if not periods <= MAX_SAMPLES:
        raise ScaraError(f"{what} = {value:g} s is {periods:.4g} sampling periods dt = {dt:g} s, more than a plan "
                         f"may hold (MAX_SAMPLES = {MAX_SAMPLES:g} samples); use a longer dt or a shorter plan")
    n = round(periods)
    if abs(value / dt - n) > 1e-6:
        raise ScaraError(f"{what} = {value:g} s is not a whole number of sampling periods dt = {dt:g} s "
                         f"({value / dt:.6g} periods); use a multiple of dt so that stop points fall on samples")
    return int(n)


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
        self.t = np.arange(n_samples) * self.dt
        self.x, self.xd, self.xdd = self.evaluate(self.t)
        for arr in (self.t, self.x, self.xd, self.xdd):
            arr.flags.writeable = False
        self._cache = {}

    # -- evaluation ----------------------------------------------------------------------------------
    def evaluate(self, t):
        """``x, xd, xdd`` (each (n, 4)) at arbitrary times ``t`` (n,) in s, by eq. 4.56 of the module docstring.

        Before 0 the arm is at the first waypoint; after the last segment it rests at the last one. A NaN or
        infinite time raises :class:`~scara.NonFiniteError`.
        """
        t = times(t, "t").reshape(-1)
        unsorted = in_time_order(self.evaluate, t)
        if unsorted is not None:
            return unsorted
        n = t.size
        x = np.empty((n, 4))
        xd = np.zeros((n, 4))
        xdd = np.zeros((n, 4))
        # component views (4, n) of the row-major outputs: every update below works on one component
        X, Xd, Xdd = x.T, xd.T, xdd.T
        # the displacement of every segment completed by time t: piecewise constant, built by np.repeat
        done = np.zeros((len(self.segments) + 1, 4))
        ends = np.searchsorted(t, self.segment_end, side="left")
        order = np.argsort(ends, kind="stable")
        for r, j in enumerate(order, start=1):
            seg = self.segments[j]
            done[r, :3] = done[r - 1, :3] + (seg.end - seg.start)
            done[r, 3] = done[r - 1, 3] + (self.phi_waypoints[j + 1] - self.phi_waypoints[j])
        counts = np.diff(np.r_[0, ends[order], n])
        start = np.r_[self.waypoints[0], self.phi_waypoints[0]]
        for c in range(4):
            X[c] = np.repeat(start[c] + done[:, c], counts)
        for j, (seg, law) in enumerate(zip(self.segments, self.laws)):
            t0 = self.segment_start[j]
            i0 = int(np.searchsorted(t, t0, side="left"))
            i1 = int(ends[j])
            if i1 <= i0:
                continue
            s, sd, sdd = law.evaluate_sorted(t[i0:i1] - t0)
            seg.accumulate(s, sd, sdd, X[:3, i0:i1], Xd[:3, i0:i1], Xdd[:3, i0:i1])
            dphi = self.phi_waypoints[j + 1] - self.phi_waypoints[j]
            if dphi != 0.0:
                g = dphi / seg.length
                X[3, i0:i1] += g * s
                Xd[3, i0:i1] += g * sd
                Xdd[3, i0:i1] += g * sdd
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
        Zero for a via point lying on a straight continuation (only the speed blends there).
        """
        out = {}
        for i in np.flatnonzero(self.via):
            pv = self.waypoints[i]
            before, after = self.segments[i - 1], self.segments[i]
            straight = (before.kind == after.kind == "line"
                        and np.linalg.norm(np.cross(before.tangent, after.tangent)) < 1e-12
                        and before.tangent @ after.tangent > 0)
            a, b = self.segment_start[i], self.segment_end[i - 1]
            k0, k1 = int(round(a / self.dt)), int(round(b / self.dt))
            d = np.linalg.norm(self.x[k0:k1 + 1, :3] - pv, axis=1)
            k = k0 + int(np.argmin(d))
            lo, hi = max(a, self.t[k] - self.dt), min(b, self.t[k] + self.dt)
            fun, arg = float(d[k - k0]), float(self.t[k])
            for _ in range(4):  # each pass narrows the bracket around the best of 65 exact samples 32-fold
                s = np.linspace(lo, hi, 65)
                dd = np.linalg.norm(self.evaluate(s)[0][:, :3] - pv, axis=1)
                j = int(np.argmin(dd))
                if dd[j] < fun:
                    fun, arg = float(dd[j]), float(s[j])
                step = (hi - lo) / 64
                lo, hi = max(lo, s[j] - step), min(hi, s[j] + step)
            best = (fun, arg)
            if straight:  # a straight continuation runs through the via point: the distance is exactly 0
                best = (0.0, best[1])
            out[self.labels[i]] = (float(best[0]), float(best[1]))
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
        sp = self.speed()
        acc = np.linalg.norm(self.xdd[:, :3], axis=1)
        ks, ka = int(np.argmax(sp)), int(np.argmax(acc))
        w = self.manipulability()
        kw = int(np.argmin(w))
        q = self.joints()
        qd = np.gradient(q, self.dt, axis=0)
        out = dict(
            duration=float(self.total), samples=int(self.t.size), dt=float(self.dt),
            motion_end=float(self.motion_end), rest=float(self.rest),
            waypoints=len(self.labels), segments=len(self.segments),
            via_points=[self.labels[i] for i in np.flatnonzero(self.via)],
            path_length=float(sum(s.length for s in self.segments)),
            max_speed=float(sp[ks]), max_speed_time=float(self.t[ks]),
            max_acceleration=float(acc[ka]), max_acceleration_time=float(self.t[ka]),
            max_phi_rate=float(np.max(np.abs(self.xd[:, 3]))),
            max_joint_speed=np.max(np.abs(qd), axis=0).tolist(),
            min_manipulability=float(w[kw]), min_manipulability_time=float(self.t[kw]),
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
    dt = check_positive(dt, "dt")
    check = check_flag(check, "check")
    wps, labels, seg_labels, pos = _waypoints(waypoints)
    nT = _segment_samples(durations, seg_labels, dt)
    T = nT * dt  # the durations the samples realise (equal to the inputs up to rounding)
    blends, tc = _blend_times(blends, T)
    ant, nA = _anticipation_samples(wps, seg_labels, T, dt)
    arcs, segments = _segments(pos, arcs, labels, seg_labels)
    laws = _timing_laws(segments, T, tc, seg_labels)
    phis = _orientations(wps, pos, phi, p, elbow)
    k0, k1, k_end, k_total = _schedule(nT, nA, total, dt)

    p_checked = ScaraParams.resolve(p)
    q0 = ikine(np.r_[pos[0], phis[0]], p_checked, elbow=elbow)
    built = dict(
        dt=dt, params=p_checked, elbow=elbow, q0=q0,
        waypoints=pos, labels=labels, via=ant > 0, anticipations=nA * dt, phi_waypoints=np.array(phis),
        segments=segments, segment_kinds=[s.kind for s in segments], segment_labels=seg_labels, laws=laws,
        durations=nT * dt, blends=np.array([law.blend for law in laws]),
        segment_start=k0 * dt, segment_end=k1 * dt, motion_end=k_end * dt,
        total=k_total * dt, rest=(k_total - k_end) * dt, _total_samples=k_total,
    )
    traj = Trajectory(waypoints=wps, durations=list(T), blends=blends, arcs=arcs, phi=phi, total=total, dt=dt,
                      p=p, elbow=elbow, check=check, _built=built)
    if check:
        _check_in_reach(traj, p_checked)
    return traj


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


def _segment_samples(durations, seg_labels, dt):
    """Each segment's duration as a whole number of samples (checked positive)."""
    m = len(seg_labels)
    if np.ndim(durations) != 1 or len(durations) != m:
        raise ShapeError(f"durations must have one entry per segment ({m} for {m + 1} waypoints), got {durations!r}")
    T = as_array(durations, "durations", (m,))
    nT = np.empty(m, dtype=np.int64)
    for j in range(m):
        check_positive(T[j], f"duration of segment {seg_labels[j]}")
        nT[j] = _samples(T[j], dt, f"duration of segment {seg_labels[j]}")
    return nT


def _blend_times(blends, T):
    """The blend time ``t_c`` of each segment's trapezoid (default a third of its duration)."""
    m = len(T)
    if blends is not None and (isinstance(blends, (str, bytes, dict)) or np.ndim(blends) != 1):
        raise ShapeError(f"blends must be a sequence with one blend time (s, or None) per segment ({m}), "
                         f"got {blends!r}")
    blends = [None] * m if blends is None else list(blends)
    if len(blends) != m:
        raise ShapeError(f"blends must have one entry per segment ({m}), got {len(blends)}")
    tc = np.array([DEFAULT_BLEND_FRACTION * T[j] if b is None else check_positive(b, f"blends[{j}]")
                   for j, b in enumerate(blends)])
    return blends, tc


def _anticipation_samples(wps, seg_labels, T, dt):
    """The anticipation (s) of every waypoint and its number of samples; only inner waypoints may be via
    points, and an anticipation must be shorter than both segments it joins."""
    n = len(wps)
    ant = np.array([w.anticipation for w in wps])
    for i in (0, n - 1):
        if ant[i] > 0:
            raise ScaraError(f"{wps[i].label} is the {'first' if i == 0 else 'last'} waypoint and cannot be a via "
                             f"point (anticipation = {ant[i]:g} s): the arm starts and ends at rest")
    nA = np.zeros(n, dtype=np.int64)
    for i in range(1, n - 1):
        if ant[i] > 0:
            if ant[i] >= T[i - 1] or ant[i] >= T[i]:
                raise ScaraError(f"anticipation at via point {wps[i].label} = {ant[i]:g} s must be shorter than "
                                 f"both segments it joins: {seg_labels[i - 1]} lasts {T[i - 1]:g} s and "
                                 f"{seg_labels[i]} lasts {T[i]:g} s")
            nA[i] = _samples(ant[i], dt, f"anticipation at {wps[i].label}")
    return ant, nA


def _segments(pos, arcs, labels, seg_labels):
    """The geometric path of each segment: a :class:`Line`, or an :class:`Arc` where ``arcs`` asks for one."""
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
    segments = []
    for j in range(m):
        a, b = pos[j], pos[j + 1]
        if np.linalg.norm(b - a) <= GEOMETRY_TOL:
            raise ScaraError(f"repeated point: {labels[j + 1]} = {labels[j]} = {_fmt(a)}; consecutive waypoints must "
                             f"differ (segment {seg_labels[j]} would have zero length)")
        try:
            segments.append(_segment(a, b, arcs.get(j), j))
        except ScaraError as exc:
            raise type(exc)(f"segment {seg_labels[j]}: {exc}") from exc
    return arcs, segments


def _segment(a, b, arc, j):
    if arc is None:
        return Line(a, b)
    if isinstance(arc, Arc):
        for name, got, want in (("start", arc.start, a), ("end", arc.end, b)):
            if np.linalg.norm(got - want) > GEOMETRY_TOL:
                raise ScaraError(f"its {name} {_fmt(got)} is not the waypoint {_fmt(want)}")
        return arc
    return Arc.through(a, as_array(arc, f"arcs[{j}] (a point the arc passes through)", (3,)), b)


def _timing_laws(segments, T, tc, seg_labels):
    """The trapezoidal timing law of every segment (Siciliano et al. 2009, (4.8)-(4.9); chapter 3)."""
    laws = []
    for j, seg in enumerate(segments):
        try:
            laws.append(Trapezoidal(seg.length, T[j], tc[j]))
        except ScaraError as exc:
            raise ScaraError(f"segment {seg_labels[j]}: {exc}") from exc
    return laws


def _orientations(wps, pos, phi, p, elbow):
    """The orientation at every waypoint: its own ``phi`` if it has one, else the one before it; the first is
    the waypoint's, or ``phi``, or the start configuration's."""
    if phi is not None:
        phi = check_number(phi, "phi", "a number of radians")
    if wps[0].phi is not None:
        phi0 = wps[0].phi
    else:
        phi0 = start_orientation(pos[0], p, elbow) if phi is None else phi
    phis = [phi0]
    for w in wps[1:]:
        phis.append(w.phi if w.phi is not None else phis[-1])
    return phis


def _schedule(nT, nA, total, dt):
    """Start and end sample of every segment (each starts its anticipation before the previous one ends), the
    last motion sample and the length of the series."""
    m = len(nT)
    k0 = np.zeros(m, dtype=np.int64)
    for j in range(1, m):
        k0[j] = k0[j - 1] + nT[j - 1] - nA[j]
    k1 = k0 + nT
    k_end = int(k1.max())
    if k_end + 1 > MAX_SAMPLES:
        raise ScaraError(f"the motion lasts {k_end * dt:g} s, {k_end + 1} samples at dt = {dt:g} s, more than a plan "
                         f"may hold (MAX_SAMPLES = {MAX_SAMPLES:g}); use a longer dt or a shorter plan")
    if total is None:
        return k0, k1, k_end, k_end
    total_f = check_positive(total, "total")
    k_total = _samples(total_f, dt, "total")
    if k_total + 1 > MAX_SAMPLES:
        raise ScaraError(f"total = {total_f:g} s is {k_total + 1} samples at dt = {dt:g} s, more than a plan may hold "
                         f"(MAX_SAMPLES = {MAX_SAMPLES:g}); use a longer dt or a shorter total")
    if k_total < k_end:
        raise ScaraError(f"total = {total_f:g} s is shorter than the motion, which ends at {k_end * dt:g} s")
    return k0, k1, k_end, k_total


def _check_in_reach(traj, p):
    """Every sample in the workspace (the message names the first one out and its segment), and every waypoint
    too: a via point's corner is rounded, so the path may stay in reach while the point itself is not, and the
    arm would be asked to pass near a point it could never reach."""
    ok = is_reachable(traj.x, p)
    if not ok.all():
        k = int(np.argmin(ok))
        tk = float(traj.t[k])
        try:
            check_reachable(traj.x[k], p, label="its point")
            why = ""
        except UnreachableError as exc:
            why = f": {exc}"
        raise UnreachableError(f"the path leaves the workspace at t = {tk:.3f} s (sample {k}) on segment "
                               f"{traj._segment_names(tk)}{why}")
    for label, point in zip(traj.labels, traj.waypoints):
        check_reachable(point, p, label=f"waypoint {label}")
