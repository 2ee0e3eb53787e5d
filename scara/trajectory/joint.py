"""Joint-space trajectories (chapter 3, section Joint-space trajectories): every joint follows a polynomial in
time from one configuration to the next (Siciliano et al. 2009, section 4.2).

One segment of duration ``t_f`` from ``q_i`` to ``q_f``, with ``tau`` the time since it started and
``Delta = q_f - q_i`` (each joint on its own), meets the boundary conditions eq-traj-joint-bc:

* the **cubic** (the book's eq-traj-cubic) meets ``q(0) = q_i``, ``q(t_f) = q_f``, ``qd(0) = v_i``,
  ``qd(t_f) = v_f``::

      q = b0 + b1 tau + b2 tau^2 + b3 tau^3,   b0 = q_i,  b1 = v_i,
      b2 = (3 Delta - (2 v_i + v_f) t_f) / t_f^2,   b3 = (-2 Delta + (v_i + v_f) t_f) / t_f^3

* the **quintic** (eq-traj-quintic) also meets ``qdd(0) = alpha_i``, ``qdd(t_f) = alpha_f``::

      q = b0 + ... + b5 tau^5,   b0 = q_i,  b1 = v_i,  b2 = alpha_i / 2,
      b3 = (20 delta_0 - 8 delta_1 + delta_2) / (2 t_f^3)
      b4 = (-30 delta_0 + 14 delta_1 - 2 delta_2) / (2 t_f^4)
      b5 = (12 delta_0 - 6 delta_1 + delta_2) / (2 t_f^5)

  with what the start's motion, kept up for ``t_f``, would miss: ``delta_0 = Delta - v_i t_f - alpha_i t_f^2 / 2``,
  ``delta_1 = (v_f - v_i - alpha_i t_f) t_f``, ``delta_2 = (alpha_f - alpha_i) t_f^2``.

A sequence through points ``q_0 ... q_{n-1}`` at times ``t_0 < ... < t_{n-1}`` chains one segment per pair; each
segment starts with the velocity (and, for the quintic, the acceleration) the previous one ended with, so these
are continuous at the via points. The values at the inner points follow a stated rule (eq-traj-via-rule):

* velocities ``"mean"`` (the default; Siciliano et al., section 4.2.2): with the slopes
  ``vbar_k = (q_k - q_{k-1}) / (t_k - t_{k-1})``, ``qd_k = (vbar_k + vbar_{k+1}) / 2`` where the two slopes have
  the same sign, and ``qd_k = 0`` where the sign changes (the joint turns back there) or a slope is zero;
* velocities ``"spline"``: the inner velocities that also make the cubic's acceleration continuous (the cubic
  spline through the points with the given end velocities, a tridiagonal system);
* accelerations of the quintic ``"difference"``: ``qdd_k = (qd_{k+1} - qd_{k-1}) / (t_{k+1} - t_{k-1})``, the slope
  of the chosen velocities across the point;
* at a **stop** (an inner point listed in ``stops``) the velocity is zero, and the quintic's acceleration too.

Either rule may be replaced by explicit values at every point. The result, :class:`JointTrajectory`, is sampled
every ``dt`` like the operational :class:`~scara.trajectory.Trajectory` (``t``, ``q``, ``qd``, ``qdd``), so it can
drive :func:`scara.simulate` as a joint reference: ``simulate(controller, joint_reference=jt, dt=jt.dt)``.

:func:`joint_counterpart` builds the joint-space trajectory through the waypoints of an operational plan,
:func:`path_deviation` measures how far its tool strays from the operational path, and
:func:`compare_joint_space` sets the two side by side (joint speeds, torques, deviation).
"""
from __future__ import annotations

import numpy as np

from ..errors import (
    ScaraError, ShapeError, UnreachableError, as_array, check_angles, check_count, check_flag, check_index,
    check_number, check_positive,
)
from ..kinematics import ikine, tool_motion_kernel
from ..params import ScaraParams
from .planner import MAX_SAMPLES, Trajectory, _samples
from .timing import in_time_order, times as _times

__all__ = [
    "JointTrajectory", "cubic", "quintic", "joint_trajectory", "joint_counterpart", "passage_times", "path_deviation",
    "segment_deviations", "compare_joint_space", "KINDS", "MAX_JOINT_POINTS",
]

#: the polynomial laws and their degrees
KINDS = {"cubic": 3, "quintic": 5}
#: largest number of points of a joint-space trajectory (the spline rule solves a system of this size)
MAX_JOINT_POINTS = 100_000
#: the rules for the inner velocities and (quintic) accelerations
VELOCITY_RULES = ("mean", "spline")
ACCELERATION_RULES = ("difference",)
#: tolerance (m) of the check that the quill stays in its stroke between the points
_STROKE_TOL = 1e-12


# --------------------------------------------------------------------------------------------------
# one segment: the coefficients
# --------------------------------------------------------------------------------------------------
def _cubic_coefficients(q_i, q_f, T, v_i, v_f) -> np.ndarray:
    """The coefficients ``[b0, b1, b2, b3]`` (ascending powers of tau) of eq-traj-cubic for every joint, from the
    end positions ``q_i``, ``q_f`` and velocities ``v_i``, ``v_f``, ``T`` the duration ``t_f``: arrays (..., 4) in,
    (..., 4, 4) out (the last axis holds the powers)."""
    D = q_f - q_i
    b2 = (3.0 * D - (2.0 * v_i + v_f) * T) / T**2
    b3 = (-2.0 * D + (v_i + v_f) * T) / T**3
    return np.stack([q_i, v_i, b2, b3], axis=-1)


def _quintic_coefficients(q_i, q_f, T, v_i, v_f, alpha_i, alpha_f) -> np.ndarray:
    """The coefficients ``[b0 ... b5]`` of eq-traj-quintic for every joint, ``T`` the duration ``t_f``, from the end
    positions, velocities and accelerations (``alpha_i``, ``alpha_f``), in the book's form with the misses
    ``delta_0 = Delta - v_i T - alpha_i T^2 / 2``, ``delta_1 = (v_f - v_i - alpha_i T) T``,
    ``delta_2 = (alpha_f - alpha_i) T^2``: arrays (..., 4) in, (..., 4, 6) out."""
    delta0 = (q_f - q_i) - v_i * T - 0.5 * alpha_i * T**2
    delta1 = (v_f - v_i - alpha_i * T) * T
    delta2 = (alpha_f - alpha_i) * T**2
    c3 = (20.0 * delta0 - 8.0 * delta1 + delta2) / (2.0 * T**3)
    c4 = (-30.0 * delta0 + 14.0 * delta1 - 2.0 * delta2) / (2.0 * T**4)
    c5 = (12.0 * delta0 - 6.0 * delta1 + delta2) / (2.0 * T**5)
    return np.stack([q_i, v_i, 0.5 * alpha_i, c3, c4, c5], axis=-1)


# --------------------------------------------------------------------------------------------------
# the rules for the values at the inner points
# --------------------------------------------------------------------------------------------------
def _mean_velocities(q, t, v_first, v_last, stop):
    """eq-traj-via-rule: the mean of the adjacent slopes where they have the same sign, else zero; zero at the
    stops; the given velocities at the ends. ``q`` (n, 4), ``t`` (n,), ``stop`` (n,) bool."""
    slope = np.diff(q, axis=0) / np.diff(t)[:, None]
    v = np.zeros_like(q)
    same = np.sign(slope[:-1]) == np.sign(slope[1:])
    v[1:-1] = np.where(same, 0.5 * (slope[:-1] + slope[1:]), 0.0)
    v[stop] = 0.0
    v[0], v[-1] = v_first, v_last
    return v


def _spline_velocities(q, t, v_first, v_last, stop):
    """The inner velocities that make the cubic's acceleration continuous at every inner point that is not a
    stop: for each run of points between two anchors (the ends and the stops, where the velocity is given), the
    tridiagonal system ``h_k v_{k-1} + 2 (h_{k-1} + h_k) v_k + h_{k-1} v_{k+1} = 3 (h_k m_k + h_{k-1} m_{k+1})``
    with ``h`` the durations and ``m`` the slopes (Siciliano et al., section 4.2.2)."""
    from scipy.linalg import solve_banded  # noqa: PLC0415 - not at import: scipy.linalg is slow to load

    n = len(t)
    h = np.diff(t)
    m = np.diff(q, axis=0) / h[:, None]
    v = np.zeros_like(q)
    v[0], v[-1] = v_first, v_last
    anchors = [0] + [k for k in range(1, n - 1) if stop[k]] + [n - 1]
    for a, b in zip(anchors[:-1], anchors[1:]):
        inner = np.arange(a + 1, b)
        if inner.size == 0:
            continue
        hl, hr = h[inner - 1], h[inner]          # h_{k-1}, h_k
        rhs = 3.0 * (hr[:, None] * m[inner - 1] + hl[:, None] * m[inner])
        rhs[0] -= hr[0] * v[a]
        rhs[-1] -= hl[-1] * v[b]
        ab = np.zeros((3, inner.size))
        ab[0, 1:] = hl[:-1]                      # super-diagonal: h_{k-1} v_{k+1}
        ab[1] = 2.0 * (hl + hr)
        ab[2, :-1] = hr[1:]                      # sub-diagonal: h_k v_{k-1}
        v[inner] = solve_banded((1, 1), ab, rhs)
    return v


def _difference_accelerations(v, t, a_first, a_last, stop):
    """The quintic's inner accelerations: ``(qd_{k+1} - qd_{k-1}) / (t_{k+1} - t_{k-1})``, zero at the stops,
    the given ones at the ends."""
    a = np.zeros_like(v)
    a[1:-1] = (v[2:] - v[:-2]) / (t[2:] - t[:-2])[:, None]
    a[stop] = 0.0
    a[0], a[-1] = a_first, a_last
    return a


# --------------------------------------------------------------------------------------------------
# the trajectory
# --------------------------------------------------------------------------------------------------
class JointTrajectory:
    """A joint-space trajectory: a cubic or quintic polynomial per segment and joint, sampled every ``dt``.

    Sampled series (as in the operational :class:`~scara.trajectory.Trajectory`): ``t`` (N,) in s; ``q``, ``qd``,
    ``qdd`` (N, 4): the joint values ``[theta1, theta2, d3, theta4]`` (rad, rad, m, rad), their velocities and
    accelerations. Before the first point's time the arm rests there, after the last it rests at the last point.

    Metadata: ``kind`` (``"cubic"``/``"quintic"``), ``degree``, ``points`` (n, 4), ``times`` (n,) s, ``labels``
    (n,), ``velocities`` (n, 4) and ``accelerations`` (n, 4; the quintic's, None for the cubic) at the points,
    ``stops`` (the inner points where the arm stops), ``rule`` (how the inner values were chosen),
    ``coefficients`` (m, 4, degree + 1): ``coefficients[j, i, k]`` multiplies ``tau^k`` for joint ``i`` on segment
    ``j``, with ``tau`` the time since the segment started; ``durations``, ``segment_start``, ``segment_end``
    (m,) s, ``segment_labels`` (m,), ``motion_end`` (s), ``total`` (s), ``rest`` (s at rest at the end), ``dt``,
    ``params``.

    Build one with :func:`cubic`, :func:`quintic`, :func:`joint_trajectory` or :func:`joint_counterpart`;
    :meth:`evaluate` gives ``q, qd, qdd`` at any times, :meth:`tool` the motion of the tool.
    """

    def __init__(self, *, kind, points, times, velocities, accelerations, coefficients, labels, stops, rule, total,
                 dt, params):
        self.kind, self.degree = kind, KINDS[kind]
        self.points, self.times, self.labels = points, times, list(labels)
        self.velocities, self.accelerations = velocities, accelerations
        self.stops, self.rule = tuple(stops), rule
        self.coefficients = coefficients
        k = np.arange(1, self.degree + 1)
        self._d1 = coefficients[..., 1:] * k                       # coefficients of qd, (m, 4, degree)
        self._d2 = self._d1[..., 1:] * k[:-1]                      # coefficients of qdd, (m, 4, degree - 1)
        self.durations = np.diff(times)
        self.segment_start, self.segment_end = times[:-1].copy(), times[1:].copy()
        self.segment_labels = [f"{labels[j]}->{labels[j + 1]}" for j in range(len(times) - 1)]
        self.dt, self.total, self.params = dt, total, params
        self.motion_end = float(times[-1])
        self.rest = float(total - times[-1])
        n = int(round(total / dt)) + 1
        self.t = np.arange(n) * dt
        self.q, self.qd, self.qdd = self._sample()
        for arr in (self.t, self.q, self.qd, self.qdd, self.points, self.times, self.velocities, self.coefficients,
                    self.durations, self.segment_start, self.segment_end):
            arr.flags.writeable = False
        if self.accelerations is not None:
            self.accelerations.flags.writeable = False
        self._cache = {}

    # -- evaluation ----------------------------------------------------------------------------------
    def _segment_values(self, j, tau):
        """``q, qd, qdd`` (n, 4) of segment ``j`` at times ``tau`` (n,) since its start."""
        c, d1, d2 = self.coefficients[j], self._d1[j], self._d2[j]
        tt = tau[:, None]
        out = []
        for cc in (c, d1, d2):
            v = np.broadcast_to(cc[:, -1], (tau.size, 4)).copy()
            for k in range(cc.shape[-1] - 2, -1, -1):
                v = v * tt + cc[:, k]
            out.append(v)
        return tuple(out)

    def _sample(self):
        return self.evaluate(self.t)

    def evaluate(self, t):
        """``q, qd, qdd`` (each (n, 4)) at times ``t`` (n,) in s (eq-traj-cubic or eq-traj-quintic on each
        segment).

        Segment ``j`` covers ``t_j <= t < t_{j+1}`` (the last one includes its end), so at an inner point the
        acceleration of the cubic is the one of the segment that starts there; at a point's time the position
        and velocity are exactly the point's. Before the first point's time the
        arm is at the first point, after the last at the last one, both at rest. A NaN or infinite time raises
        :class:`~scara.NonFiniteError`.
        """
        t = _times(t, "t").reshape(-1)
        unsorted = in_time_order(self.evaluate, t)
        if unsorted is not None:
            return unsorted
        n = t.size
        q = np.empty((n, 4))
        qd = np.zeros((n, 4))
        qdd = np.zeros((n, 4))
        tk = self.times
        first = int(np.searchsorted(t, tk[0], side="left"))     # the first time on the motion
        end = int(np.searchsorted(t, tk[-1], side="right"))     # the first time after it
        q[:first] = self.points[0]
        q[end:] = self.points[-1]
        starts = np.searchsorted(t, tk, side="left")
        m = len(tk) - 1
        for j in range(m):
            a, b = int(starts[j]), (int(starts[j + 1]) if j < m - 1 else end)
            if b > a:
                q[a:b], qd[a:b], qdd[a:b] = self._segment_values(j, t[a:b] - tk[j])
        # at the last point's time, its values exactly (the polynomial gives them to rounding)
        last = t == tk[-1]
        q[last], qd[last] = self.points[-1], self.velocities[-1]
        if self.accelerations is not None:
            qdd[last] = self.accelerations[-1]
        return q, qd, qdd

    # -- the tool ------------------------------------------------------------------------------------
    def tool(self, p=None):
        """The motion of the tool the joints produce, at the samples: ``x, xd, xdd`` (each (N, 4), ``[p_x, p_y,
        p_z, phi]`` in m and rad) by the direct kinematics ``x = k(q)``, ``xd = J_A qd``,
        ``xdd = J_A qdd + Jdot_A qd`` (chapter 1), for the arm ``p`` (default the one the trajectory was checked
        against)."""
        pp = self.params if p is None else ScaraParams.resolve(p)
        key = ("tool", pp)
        if key not in self._cache:
            out = np.empty((self.t.size, 12))
            tool_motion_kernel(np.ascontiguousarray(self.q), np.ascontiguousarray(self.qd),
                               np.ascontiguousarray(self.qdd), pp.a1, pp.a2, pp.d0, out)
            res = (out[:, 0:4], out[:, 4:8], out[:, 8:12])
            for a in res:
                a.flags.writeable = False
            self._cache[key] = res
        return self._cache[key]

    def tool_speed(self, p=None) -> np.ndarray:
        """Linear speed of the tool ``|pdot|`` (N,) in m/s."""
        return np.linalg.norm(self.tool(p)[1][:, :3], axis=1)

    def summary(self) -> dict:
        """The figures the chapter reports: timing, peak joint speeds and accelerations (per joint, in rad/s,
        m/s, rad/s^2, m/s^2), and the peak speed of the tool."""
        return dict(
            kind=self.kind, duration=float(self.total), motion_end=self.motion_end, rest=self.rest,
            samples=int(self.t.size), dt=float(self.dt), points=len(self.times),
            max_joint_speed=np.max(np.abs(self.qd), axis=0).tolist(),
            max_joint_acceleration=np.max(np.abs(self.qdd), axis=0).tolist(),
            max_tool_speed=float(self.tool_speed().max()),
        )

    def __repr__(self):
        return (f"JointTrajectory({self.kind}, {len(self.times)} points, {len(self.durations)} segments, velocities "
                f"{self.rule}, {self.total:g} s at dt = {self.dt:g} s, {self.t.size} samples)")


# --------------------------------------------------------------------------------------------------
# the builders
# --------------------------------------------------------------------------------------------------
def _per_joint(value, name) -> np.ndarray:
    """A number (the same for every joint) or a vector (4,), as a finite float vector (4,)."""
    if np.ndim(value) == 0:
        return np.full(4, check_number(value, name))
    return as_array(value, name, (4,)).astype(float)


def _kind(kind) -> str:
    if not isinstance(kind, str) or kind not in KINDS:
        raise ScaraError(f"kind = {kind!r} must be one of {sorted(KINDS)}")
    return kind


def _points_and_times(points, times, dt):
    """The points (n, 4) and their times (n,), checked: shapes, finite values, at least two points, times that
    increase from a start >= 0, each a whole number of samples."""
    q = np.array(as_array(points, "points", (4,), allow_batch=True), dtype=float)  # the trajectory's own copy
    if q.ndim != 2:
        raise ShapeError(f"points must have shape (n, 4), one joint configuration per row, got {q.shape}")
    n = len(q)
    check_count(n, "the number of points", 2, MAX_JOINT_POINTS, "points")
    check_angles(q, "points")
    if isinstance(times, (str, bytes)) or np.ndim(times) != 1:
        raise ShapeError(f"times must be a sequence of {n} times (s), one per point, got {times!r}")
    t = _times(times, "times")
    if t.shape != (n,):
        raise ShapeError(f"times must have one entry per point ({n}), got {t.shape[0]}")
    if t[0] < 0:
        raise ScaraError(f"times[0] = {t[0]:g} s must be >= 0 (the samples start at t = 0)")
    for k in range(1, n):
        if not t[k] > t[k - 1]:
            raise ScaraError(f"times[{k}] = {t[k]:g} s is not after times[{k - 1}] = {t[k - 1]:g} s: the times must "
                             f"increase (every segment needs a duration > 0)")
    ks = np.array([_samples(t[k], dt, f"times[{k}]") for k in range(n)], dtype=np.int64)
    return q, ks * dt, ks


def _inner_flags(stops, n):
    """A boolean mask (n,) of the inner points where the arm stops."""
    mask = np.zeros(n, dtype=bool)
    if stops is None:
        return mask
    if isinstance(stops, (str, bytes, dict)) or np.ndim(stops) != 1:
        raise ScaraError(f"stops must be a sequence of inner point indices (1 to {n - 2}), got {stops!r}")
    for s in stops:
        i = check_index(s, "a stop", n)
        if i in (0, n - 1):
            raise ScaraError(f"stop {i} is an end point: the ends take the velocities qd_start and qd_end (zero by "
                             f"default); "
                             f"stops lists inner points, 1 to {n - 2}")
        mask[i] = True
    return mask


def _values_at_points(values, name, n):
    arr = as_array(values, name, (4,), allow_batch=True)
    if arr.ndim != 2 or len(arr) != n:
        raise ShapeError(f"{name} must have shape ({n}, 4), one row per point, got {arr.shape}")
    return arr.astype(float)


def joint_trajectory(points, times, kind: str = "cubic", *, velocities="mean", accelerations="difference",
                     stops=(), qd_start=0.0, qd_end=0.0, qdd_start=0.0, qdd_end=0.0, total=None, dt: float = 1e-3,
                     labels=None, p=None, check: bool = True) -> JointTrajectory:
    """A joint-space trajectory through the configurations ``points`` at ``times``: one cubic (eq-traj-cubic) or
    quintic (eq-traj-quintic) per segment and joint, with continuous velocity (both) and acceleration (quintic)
    at the via points (module docstring; Siciliano et al. 2009, section 4.2.2).

    Parameters
    ----------
    points : array (n, 4)
        The configurations ``[theta1, theta2, d3, theta4]`` (rad, rad, m, rad) to pass through, n >= 2.
    times : sequence (n,)
        When the arm is at each point (s): increasing from ``times[0] >= 0``, each a whole number of samples.
    kind : ``"cubic"`` or ``"quintic"``
    velocities : ``"mean"`` (default), ``"spline"`` or array (n, 4)
        The rule for the inner velocities (eq-traj-via-rule: the mean of the adjacent slopes, zero where the
        sign changes; or the cubic spline's, which makes the cubic's acceleration continuous too), or the
        velocity at every point, ends included.
    accelerations : ``"difference"`` (default) or array (n, 4)
        Quintic only: the inner accelerations ``(qd_{k+1} - qd_{k-1}) / (t_{k+1} - t_{k-1})``, or the
        acceleration at every point, ends included.
    stops : sequence of int
        Inner points where the arm stops: velocity zero there (and acceleration, for the quintic). Only with a
        rule, not with explicit values.
    qd_start, qd_end, qdd_start, qdd_end : number or array (4,)
        Velocity and (quintic) acceleration at the first and last point, with a rule (default 0: from rest, to
        rest). They must be 0 where the arm rests: before ``times[0] > 0`` or after ``times[-1] < total``.
    total : float, optional
        Length of the sampled series (s, a whole number of samples, at least ``times[-1]``); default
        ``times[-1]``. The arm rests at the last point after ``times[-1]``.
    dt : float
        Sampling period (s), default 1 ms.
    labels : sequence of str, optional
        Names of the points (default ``p0``, ``p1``...), used in messages and plots.
    p : ScaraParams, optional
        The arm whose joint limits are checked (default ``ScaraParams()``): the quill's stroke
        ``d3_min <= d3 <= d3_max``, at the points and everywhere between them.
    check : bool
        Check the stroke (default True).

    Raises
    ------
    ShapeError
        ``points`` not (n, 4), ``times`` not one per point, values at the points not (n, 4).
    NonFiniteError
        A NaN or infinite point, time or value.
    ScaraError
        Fewer than two points; times that do not increase, start before 0 or are not whole numbers of samples; an
        unknown kind or rule; a stop at an end; a start or end velocity where the arm rests.
    UnreachableError
        ``d3`` leaves the quill's stroke at a point or between two (the message names the segment, the time and
        the value).

    >>> jt = joint_trajectory([[0, 0, 0.5, 0], [1, -1, 0.5, 0], [2, -1, 0.5, 0]], [0.0, 1.0, 3.0])
    >>> jt.velocities[1].round(3).tolist()       # theta1: mean of 1 and 0.5 rad/s; theta2: its slope turns to 0
    [0.75, 0.0, 0.0, 0.0]
    >>> [float(v) for v in jt.evaluate(1.0)[0][0]]
    [1.0, -1.0, 0.5, 0.0]
    """
    kind = _kind(kind)
    dt = check_positive(dt, "dt")
    check = check_flag(check, "check")
    q, t, ks = _points_and_times(points, times, dt)
    n = len(q)
    labels = _point_labels(labels, n)
    stop = _inner_flags(stops, n)
    ends = {name: _per_joint(value, name) for name, value in (("qd_start", qd_start), ("qd_end", qd_end),
                                                               ("qdd_start", qdd_start), ("qdd_end", qdd_end))}
    v, acc, rule = _values_at_the_points(kind, velocities, accelerations, q, t, ends, stop)
    k_total = _total_samples(total, ks, t, dt)
    _check_rests(t, k_total * dt, v, acc)

    T = np.diff(t)[:, None]
    if kind == "cubic":
        coef = _cubic_coefficients(q[:-1], q[1:], T, v[:-1], v[1:])
    else:
        coef = _quintic_coefficients(q[:-1], q[1:], T, v[:-1], v[1:], acc[:-1], acc[1:])
    if not np.all(np.isfinite(coef)):
        raise ScaraError("the polynomial coefficients overflow: the points, velocities or accelerations are too large "
                         "for the durations between the points")
    pp = ScaraParams.resolve(p)
    jt = JointTrajectory(kind=kind, points=q, times=t, velocities=v, accelerations=acc, coefficients=coef,
                         labels=labels, stops=np.flatnonzero(stop).tolist(), rule=rule, total=k_total * dt, dt=dt,
                         params=pp)
    if check:
        _check_stroke(jt, pp)
    return jt


def _point_labels(labels, n) -> list:
    """The names of the ``n`` points: ``p0``, ``p1``... by default, else ``labels`` (n names)."""
    if labels is None:
        return [f"p{i}" for i in range(n)]
    if isinstance(labels, (str, bytes)) or np.ndim(labels) != 1 or len(labels) != n:
        raise ShapeError(f"labels must be {n} names, one per point, got {labels!r}")
    return [str(s) for s in labels]


def _values_at_the_points(kind, velocities, accelerations, q, t, ends, stop):
    """``(v, acc, rule)``: the velocities (n, 4) and (quintic) accelerations (n, 4, else None) at the points, by
    their rules (eq-traj-via-rule) or as given, and the name of the rule."""
    n = len(q)
    takes_accelerations = (np.any(ends["qdd_start"] != 0) or np.any(ends["qdd_end"] != 0)
                           or not _is_rule(accelerations, "difference"))
    if kind == "cubic" and takes_accelerations:
        raise ScaraError("a cubic cannot take accelerations (qdd_start, qdd_end, accelerations): it meets four "
                         "conditions per segment, the positions and velocities at both ends; use kind='quintic'")
    if _is_rule(velocities, *VELOCITY_RULES):
        rule = velocities
        fn = _mean_velocities if rule == "mean" else _spline_velocities
        v = fn(q, t, ends["qd_start"], ends["qd_end"], stop)
    elif isinstance(velocities, str):
        raise ScaraError(f"velocities = {velocities!r} must be one of {list(VELOCITY_RULES)} or an array (n, 4)")
    else:
        rule = "given"
        _no_rule_options(stop, ends, ("qd_start", "qd_end"), "velocities")
        v = _values_at_points(velocities, "velocities", n)
    acc = None
    if kind == "quintic":
        if _is_rule(accelerations, *ACCELERATION_RULES):
            acc = _difference_accelerations(v, t, ends["qdd_start"], ends["qdd_end"], stop)
        elif isinstance(accelerations, str):
            raise ScaraError(f"accelerations = {accelerations!r} must be one of {list(ACCELERATION_RULES)} or an "
                             f"array (n, 4)")
        else:
            _no_rule_options(stop, ends, ("qdd_start", "qdd_end"), "accelerations")
            acc = _values_at_points(accelerations, "accelerations", n)
            rule = f"{rule}, accelerations given"
    return v, acc, rule


def _total_samples(total, ks, t, dt) -> int:
    """The sample index of the series' end: ``total`` (s, at least the motion's end ``times[-1]``), default the
    motion's end; at most ``MAX_SAMPLES`` samples."""
    k_total = ks[-1] if total is None else _samples(check_positive(total, "total"), dt, "total")
    if k_total < ks[-1]:
        raise ScaraError(f"total = {total:g} s is shorter than the motion, which ends at times[-1] = {t[-1]:g} s")
    if k_total + 1 > MAX_SAMPLES:
        raise ScaraError(f"the series lasts {k_total * dt:g} s, {k_total + 1} samples at dt = {dt:g} s, more than a "
                         f"trajectory may hold (MAX_SAMPLES = {MAX_SAMPLES:g}); use a longer dt or a shorter motion")
    return k_total


def _is_rule(value, *names) -> bool:
    return isinstance(value, str) and value in names


def _no_rule_options(stop, ends, keys, what):
    if stop.any():
        raise ScaraError(f"stops apply to the rule for the inner values; with explicit {what}, give 0 at those "
                         f"points instead")
    for key in keys:
        if np.any(ends[key] != 0):
            raise ScaraError(f"{key} is taken from the explicit {what} (their first or last row); leave {key} at 0")


def _check_rests(t, total, v, acc):
    """A start or end velocity (acceleration) other than zero where the arm rests would be a jump."""
    for where, k, rests in (("first", 0, t[0] > 0), ("last", -1, total > t[-1])):
        if not rests:
            continue
        for name, arr in (("velocity", v), ("acceleration", acc)):
            if arr is not None and np.any(arr[k] != 0):
                side = "before times[0]" if k == 0 else "after times[-1] until total"
                raise ScaraError(f"the arm rests at the {where} point {side}, so its {name} there must be 0, got "
                                 f"{np.asarray(arr[k]).tolist()}")


def _check_stroke(jt, p):
    """``d3`` within the quill's stroke at the points and between them: the extremes of each segment's
    polynomial are at its ends or where its velocity (a polynomial of degree 2 or 4) vanishes."""
    lo, hi = p.d3_min, p.d3_max
    for i, d3 in enumerate(jt.points[:, 2]):
        if not lo - _STROKE_TOL <= d3 <= hi + _STROKE_TOL:
            raise UnreachableError(f"point {jt.labels[i]}: d3 = {d3:.6g} m is outside the quill's stroke "
                                   f"d3_min = {lo:g} m <= d3 <= d3_max = {hi:g} m")
    for j in range(len(jt.durations)):
        T = float(jt.durations[j])
        roots = np.polynomial.polynomial.polyroots(jt._d1[j, 2]) if np.any(jt._d1[j, 2, 1:] != 0) else np.array([])
        tau = [r.real for r in np.atleast_1d(roots) if abs(r.imag) <= 1e-9 * max(1.0, abs(r)) and 0 < r.real < T]
        if not tau:
            continue
        tau = np.array(tau)
        d3 = np.polynomial.polynomial.polyval(tau, jt.coefficients[j, 2])
        for tk, val in zip(tau, d3):
            if not lo - _STROKE_TOL <= val <= hi + _STROKE_TOL:
                raise UnreachableError(
                    f"between the points, d3 reaches {val:.6g} m at t = {jt.segment_start[j] + tk:.4f} s on segment "
                    f"{jt.segment_labels[j]}, outside the quill's stroke d3_min = {lo:g} m <= d3 <= d3_max = {hi:g} m "
                    f"(the polynomial overshoots): move the points, slow the segment or stop at its ends")


def cubic(q0, q1, duration, qd_start=0.0, qd_end=0.0, *, dt: float = 1e-3, p=None,
          check: bool = True) -> JointTrajectory:
    """One cubic segment per joint (eq-traj-cubic) from the configuration ``q0`` to ``q1`` (4,) in ``duration``
    seconds (a whole number of samples ``dt``), leaving with the joint velocity ``qd_start`` and arriving with
    ``qd_end`` (a number for every joint or a vector (4,); default 0, from rest to rest).

    The coefficients are ``jt.coefficients[0]`` (4 joints x 4 powers of tau). See :func:`joint_trajectory` for
    the errors.

    >>> jt = cubic([0, 0, 0.5, 0], [1, 0, 0.5, 0], 2.0)
    >>> jt.coefficients[0, 0].tolist()              # q = 0.75 tau^2 - 0.25 tau^3 for theta1
    [0.0, 0.0, 0.75, -0.25]
    >>> round(float(jt.qd[:, 0].max()), 6)           # 1.5 Delta / T at mid-time
    0.75
    """
    T = check_positive(duration, "duration")
    return joint_trajectory([as_array(q0, "q0", (4,)), as_array(q1, "q1", (4,))], [0.0, T], "cubic",
                            velocities=[_per_joint(qd_start, "qd_start"), _per_joint(qd_end, "qd_end")], dt=dt, p=p,
                            check=check)


def quintic(q0, q1, duration, qd_start=0.0, qd_end=0.0, qdd_start=0.0, qdd_end=0.0, *, dt: float = 1e-3,
            p=None, check: bool = True) -> JointTrajectory:
    """One quintic segment per joint (eq-traj-quintic) from ``q0`` to ``q1`` (4,) in ``duration`` seconds (a whole
    number of samples ``dt``), with the joint velocities ``qd_start``, ``qd_end`` and accelerations ``qdd_start``,
    ``qdd_end`` at the two ends (a number for every joint or a vector (4,); default 0).

    The coefficients are ``jt.coefficients[0]`` (4 joints x 6 powers of tau). See :func:`joint_trajectory` for
    the errors.

    >>> jt = quintic([0, 0, 0.5, 0], [1, 0, 0.5, 0], 1.0)
    >>> jt.coefficients[0, 0].tolist()              # 10 tau^3 - 15 tau^4 + 6 tau^5 for theta1
    [0.0, 0.0, 0.0, 10.0, -15.0, 6.0]
    """
    T = check_positive(duration, "duration")
    return joint_trajectory([as_array(q0, "q0", (4,)), as_array(q1, "q1", (4,))], [0.0, T], "quintic",
                            velocities=[_per_joint(qd_start, "qd_start"), _per_joint(qd_end, "qd_end")],
                            accelerations=[_per_joint(qdd_start, "qdd_start"), _per_joint(qdd_end, "qdd_end")], dt=dt,
                            p=p, check=check)


# --------------------------------------------------------------------------------------------------
# the joint-space counterpart of an operational plan
# --------------------------------------------------------------------------------------------------
def _check_plan(traj) -> None:
    if not isinstance(traj, Trajectory):
        raise ScaraError(f"traj must be a Trajectory (from plan_path or reference_trajectory), got "
                         f"{type(traj).__name__}")


def passage_times(traj: Trajectory) -> np.ndarray:
    """When the operational trajectory ``traj`` is at (or nearest in time to) each waypoint (n,) s: the arrival
    at a stop point, the middle of the overlap at a via point (rounded to a sample)."""
    _check_plan(traj)
    out = np.empty(len(traj.labels))
    out[0] = traj.segment_start[0]
    for i in range(1, len(out)):
        if traj.via[i]:
            k = round(0.5 * (traj.segment_start[i] + traj.segment_end[i - 1]) / traj.dt)
            out[i] = k * traj.dt
        else:
            out[i] = traj.segment_end[i - 1]
    return out


def joint_counterpart(traj: Trajectory, kind: str = "cubic", extra: int = 0, velocities: str = "mean",
                      check: bool = True) -> JointTrajectory:
    """The joint-space trajectory through the waypoints of the operational trajectory ``traj`` (chapter 3,
    section Joint-space trajectories).

    The knots are the waypoints at :func:`passage_times`: a stop point at the arrival, where the arm stops; a
    via point at the middle of its overlap, where the knot is the point ``traj`` is at then (the operational
    trajectory passes near a via point, not through it), passed by ``velocities``' rule
    (:func:`joint_trajectory`). ``extra`` (0 to 1000) more knots per segment are samples of ``traj`` at evenly
    spaced times between two waypoints (rounded to samples), so that with more of them the joint motion follows
    ``traj`` more closely. Every knot becomes a configuration by the closed-form inverse kinematics with the
    trajectory's elbow (``theta1`` unwrapped, ``theta4 = phi - theta1 - theta2``). Same ``dt``, ``total`` and arm
    as ``traj``.

    >>> from scara import reference_trajectory
    >>> jt = joint_counterpart(reference_trajectory(dt=0.01))
    >>> jt.motion_end, len(jt.times), jt.stops
    (66.0, 12, (1, 2, 6, 7, 9, 10))
    """
    _check_plan(traj)
    kind = _kind(kind)
    extra = check_count(extra, "extra", 0, 1000, "points per segment")
    tw = passage_times(traj)
    kw = np.round(tw / traj.dt).astype(np.int64)
    ks, labels, anchor = [], [], []
    for i in range(len(kw)):
        ks.append(kw[i])
        labels.append(traj.labels[i])
        anchor.append(i)
        if i + 1 < len(kw):
            inner = np.round(kw[i] + (kw[i + 1] - kw[i]) * np.arange(1, extra + 1) / (extra + 1)).astype(np.int64)
            inner = np.unique(inner[(inner > kw[i]) & (inner < kw[i + 1])])
            ks.extend(inner.tolist())
            labels.extend(f"{traj.labels[i]}+{m}" for m in range(1, inner.size + 1))
            anchor.extend([-1] * inner.size)
    ks = np.array(ks)
    x = np.array(traj.x[ks])
    for row, i in enumerate(anchor):       # a stop point exactly (the samples there hold it to rounding)
        if i >= 0 and not traj.via[i]:
            x[row] = np.r_[traj.waypoints[i], traj.phi_waypoints[i]]
    q = ikine(x, traj.params, elbow=traj.elbow)
    q[:, 0] = np.unwrap(q[:, 0])
    q[:, 3] = x[:, 3] - q[:, 0] - q[:, 1]
    stops = [row for row, i in enumerate(anchor) if 0 < row < len(anchor) - 1 and i >= 0 and not traj.via[i]]
    return joint_trajectory(q, ks * traj.dt, kind, velocities=velocities, stops=stops, total=traj.total, dt=traj.dt,
                            labels=labels, p=traj.params, check=check)


def _path_tree(traj: Trajectory) -> tuple:
    """The distinct points of ``traj``'s path (M, 3) (the samples at rest repeat a point: one copy is enough) and
    their k-d tree (``scipy.spatial.cKDTree``), built once per trajectory (its samples are read-only)."""
    if "path_tree" not in traj._cache:
        from scipy.spatial import cKDTree  # noqa: PLC0415

        path = np.ascontiguousarray(traj.x[:, :3])
        keep = np.r_[True, np.any(np.diff(path, axis=0) != 0, axis=1)]
        path = path[keep]
        path.flags.writeable = False
        traj._cache["path_tree"] = (path, cKDTree(path))
    return traj._cache["path_tree"]


def path_deviation(jt: JointTrajectory, traj: Trajectory) -> np.ndarray:
    """How far the tool of the joint-space trajectory ``jt`` strays from the path of the operational trajectory
    ``traj``: at every sample of ``jt``, the distance (m) from the tool's position to the nearest point of the
    curve ``traj`` traces (its samples joined by straight pieces, which follow an arc within
    ``h^2 / (8 rho)``, about 1e-8 m at the reference's speeds), shape (N,).

    >>> from scara import reference_trajectory
    >>> traj = reference_trajectory(dt=0.01)
    >>> d = path_deviation(joint_counterpart(traj), traj)
    >>> bool(d[0] < 1e-12), bool(d.max() > 0.01)        # at the start on the path; between the points, not
    (True, True)
    """
    if not isinstance(jt, JointTrajectory):
        raise ScaraError(f"jt must be a JointTrajectory, got {type(jt).__name__}")
    _check_plan(traj)
    path, tree = _path_tree(traj)
    tool = np.ascontiguousarray(jt.tool()[0][:, :3])
    _, nearest = tree.query(tool, workers=-1)  # every core: the same nearest points, sooner
    best = np.full(len(tool), np.inf)
    for shift in (-1, 0):                   # the pieces either side of the nearest sample hold the nearest point
        a_idx = np.clip(nearest + shift, 0, len(path) - 2)
        a, b = path[a_idx], path[a_idx + 1]
        ab = b - a
        ll = np.einsum("ij,ij->i", ab, ab)
        s = np.clip(np.einsum("ij,ij->i", tool - a, ab) / np.where(ll > 0, ll, 1.0), 0.0, 1.0)
        d = np.linalg.norm(tool - (a + s[:, None] * ab), axis=1)
        best = np.minimum(best, d)
    return best


def segment_deviations(jt: JointTrajectory, traj: Trajectory) -> dict:
    """The largest :func:`path_deviation` (m) on each segment of ``jt`` (its samples from the segment's start to
    its end, both included): ``{segment label: distance}``."""
    d = path_deviation(jt, traj)
    out = {}
    for j, label in enumerate(jt.segment_labels):
        a = int(round(jt.segment_start[j] / jt.dt))
        b = int(round(jt.segment_end[j] / jt.dt))
        out[label] = float(d[a:b + 1].max())
    return out


def compare_joint_space(traj: Trajectory, kinds=("cubic", "quintic"), extra: int = 0, p=None) -> list[dict]:
    """The operational trajectory ``traj`` against its joint-space counterparts (:func:`joint_counterpart`, one
    per kind in ``kinds``, with ``extra`` knots per segment): one row per motion with ``name``, ``motion_end``
    (s), ``max_joint_speed`` (4,) (rad/s, rad/s, m/s, rad/s), ``max_joint_acceleration`` (4,),
    ``max_torque`` (4,) (N m, N m, N, N m; the inverse dynamics of chapter 5 for the arm ``p``, default the
    unloaded arm), ``max_tool_speed`` (m/s) and ``max_deviation`` (m, :func:`path_deviation`; 0 for ``traj``
    itself). The operational row's joint motion is the exact one of the closed-form inverse kinematics,
    ``qd = J_A^-1 xd`` and ``qdd = J_A^-1 (xdd - Jdot_A qd)``."""
    from ..dynamics import inverse_dynamics  # noqa: PLC0415 - chapter 5's model, loaded when asked for
    from .._simulate.setpoints import ikine_reference  # noqa: PLC0415

    _check_plan(traj)
    if isinstance(kinds, str) or not all(isinstance(k, str) for k in kinds):
        raise ScaraError(f"kinds must be a sequence of {sorted(KINDS)}, got {kinds!r}")
    pp = ScaraParams.resolve(p)
    ref = ikine_reference(traj, traj.params, elbow=traj.elbow)
    motions = [("operational", traj.motion_end, ref[:, :4], ref[:, 4:8], ref[:, 8:12], traj.speed(), 0.0)]
    for kind in kinds:
        jt = joint_counterpart(traj, _kind(kind), extra=extra)
        motions.append((f"joint space, {kind}", jt.motion_end, jt.q, jt.qd, jt.qdd, jt.tool_speed(),
                        float(path_deviation(jt, traj).max())))
    rows = []
    for name, end, q, qd, qdd, speed, dev in motions:
        tau = inverse_dynamics(q, qd, qdd, pp)
        rows.append(dict(name=name, motion_end=float(end), max_joint_speed=np.abs(qd).max(axis=0),
                         max_joint_acceleration=np.abs(qdd).max(axis=0), max_torque=np.abs(tau).max(axis=0),
                         max_tool_speed=float(speed.max()), max_deviation=dev))
    return rows
