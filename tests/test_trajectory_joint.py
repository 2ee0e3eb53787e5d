"""Tests of scara.trajectory.joint (chapter 3, section Joint-space trajectories).

Each property is checked by a route independent of the package's code: the coefficients against a symbolic solve
of the boundary-condition system (sympy), the boundary conditions and the continuity at the via points on the
polynomials themselves, the velocities and accelerations against finite differences with their error bounds,
the textbook's velocity rule and the cubic spline written out again (and against scipy's spline), the tool's
motion against the kinematics of chapter 1 sample by sample, and hypothesis-generated points and times; every
bad input is refused with a message naming it."""
from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.polynomial import polynomial as P

from scara import (
    NonFiniteError, ScaraError, ScaraParams, ShapeError, UnreachableError, ikine, jacobian, jacobian_dot, pose,
)
from scara.trajectory import (
    compare_joint_space, cubic, joint_counterpart, joint_trajectory, passage_times, path_deviation,
    plan_path, quintic, segment_deviations,
)

import _largest
from _trajectory_shared import SCENARIO_POINTS, SCENARIO_VIA


# --------------------------------------------------------------------------------------------------
# the boundary-condition systems, solved symbolically once
# --------------------------------------------------------------------------------------------------
def _symbolic_solution(degree):
    """The coefficients a_0..a_degree of q(tau) = sum a_k tau^k meeting q, qd (and qdd for degree 5) at tau = 0 and
    tau = T, as functions of (q_i, q_f, T, v_i, v_f[, al_i, al_f])."""
    tau, T, qi, qf, vi, vf, ai, af = sp.symbols("tau T q_i q_f v_i v_f al_i al_f")
    a = sp.symbols(f"a0:{degree + 1}")
    q = sum(a[k] * tau**k for k in range(degree + 1))
    qd, qdd = sp.diff(q, tau), sp.diff(q, tau, 2)
    eqs = [q.subs(tau, 0) - qi, q.subs(tau, T) - qf, qd.subs(tau, 0) - vi, qd.subs(tau, T) - vf]
    args = [qi, qf, T, vi, vf]
    if degree == 5:
        eqs += [qdd.subs(tau, 0) - ai, qdd.subs(tau, T) - af]
        args += [ai, af]
    sol = sp.solve(eqs, a, dict=True)[0]
    return sp.lambdify(args, [sol[k] for k in a], "numpy")


CUBIC_SYM = _symbolic_solution(3)
QUINTIC_SYM = _symbolic_solution(5)

ANGLE = st.floats(-3.0, 3.0, allow_nan=False)
STROKE = st.floats(0.05, 0.95, allow_nan=False)
RATE = st.floats(-2.0, 2.0, allow_nan=False)
CONFIG = st.tuples(ANGLE, ANGLE, STROKE, ANGLE)
VEC = st.tuples(RATE, RATE, RATE, RATE)


def _scale(c, T):
    """The size of the terms |a_k| T^k of a polynomial on [0, T]: the scale of its rounding errors."""
    return float(np.sum(np.abs(c) * T ** np.arange(len(c)))) + 1e-300


# --------------------------------------------------------------------------------------------------
# one segment: the coefficients against the symbolic solve, the boundary conditions
# --------------------------------------------------------------------------------------------------
@given(CONFIG, CONFIG, st.integers(1, 500), VEC, VEC)
def test_cubic_coefficients_solve_the_boundary_system(q0, q1, n10ms, v0, v1):
    T = n10ms * 0.01
    jt = cubic(q0, q1, T, v0, v1, dt=0.01, check=False)
    assert jt.coefficients.shape == (1, 4, 4) and jt.kind == "cubic" and jt.degree == 3
    for i in range(4):
        want = np.array(CUBIC_SYM(q0[i], q1[i], T, v0[i], v1[i]), float)
        c = jt.coefficients[0, i]
        err = np.max(np.abs(c - want) * T ** np.arange(4)) / _scale(want, T)
        assert _largest.record("cubic coefficients vs sympy (relative)", err) < 1e-12


@given(CONFIG, CONFIG, st.integers(1, 500), VEC, VEC, VEC, VEC)
def test_quintic_coefficients_solve_the_boundary_system(q0, q1, n10ms, v0, v1, a0, a1):
    T = n10ms * 0.01
    jt = quintic(q0, q1, T, v0, v1, a0, a1, dt=0.01, check=False)
    assert jt.coefficients.shape == (1, 4, 6) and jt.degree == 5
    for i in range(4):
        want = np.array(QUINTIC_SYM(q0[i], q1[i], T, v0[i], v1[i], a0[i], a1[i]), float)
        c = jt.coefficients[0, i]
        err = np.max(np.abs(c - want) * T ** np.arange(6)) / _scale(want, T)
        assert _largest.record("quintic coefficients vs sympy (relative)", err) < 1e-12


def test_the_books_forms_of_the_coefficients_solve_the_boundary_systems():
    """eq-traj-cubic and eq-traj-quintic as the book writes them (the quintic with the misses delta_0, delta_1,
    delta_2) equal the symbolic solution of the boundary-condition system."""
    T, qi, qf, vi, vf, ai, af = sp.symbols("T q_i q_f v_i v_f al_i al_f")
    D = qf - qi
    cubic_book = [qi, vi, (3 * D - (2 * vi + vf) * T) / T**2, (-2 * D + (vi + vf) * T) / T**3]
    d0, d1, d2 = D - vi * T - ai * T**2 / 2, (vf - vi - ai * T) * T, (af - ai) * T**2
    quintic_book = [qi, vi, ai / 2, (20 * d0 - 8 * d1 + d2) / (2 * T**3), (-30 * d0 + 14 * d1 - 2 * d2) / (2 * T**4),
                    (12 * d0 - 6 * d1 + d2) / (2 * T**5)]
    for book, sym, args in ((cubic_book, CUBIC_SYM, (qi, qf, T, vi, vf)),
                            (quintic_book, QUINTIC_SYM, (qi, qf, T, vi, vf, ai, af))):
        for mine, theirs in zip(book, sym(*args)):
            assert sp.simplify(mine - theirs) == 0


def test_rest_to_rest_laws_are_the_textbook_ones():
    """Hand-computed: from rest to rest, q = q_i + Delta (3 s^2 - 2 s^3) (cubic) and
    q_i + Delta (10 s^3 - 15 s^4 + 6 s^5) (quintic) with s = tau / T; peak speeds 3 Delta / (2 T) and
    15 Delta / (8 T) at mid-time, peak accelerations 6 Delta / T^2 (cubic, at the ends) and
    10 Delta / (sqrt(3) T^2) (quintic, at s = 1/2 -+ sqrt(3)/6)."""
    q0, q1, T = np.array([0.2, -1.0, 0.3, 0.5]), np.array([1.4, -0.4, 0.7, -0.5]), 2.0
    D = q1 - q0
    c, qn = cubic(q0, q1, T, dt=1e-3), quintic(q0, q1, T, dt=1e-3)
    s = c.t / T
    np.testing.assert_allclose(c.q, q0 + D * (3 * s**2 - 2 * s**3)[:, None], rtol=0, atol=1e-14)
    np.testing.assert_allclose(qn.q, q0 + D * (10 * s**3 - 15 * s**4 + 6 * s**5)[:, None], rtol=0, atol=1e-14)
    mid = len(c.t) // 2
    np.testing.assert_allclose(c.qd[mid], 1.5 * D / T, rtol=1e-14)
    np.testing.assert_allclose(np.abs(c.qd).max(0), 1.5 * np.abs(D) / T, rtol=1e-14)
    np.testing.assert_allclose(np.abs(c.qdd).max(0), 6 * np.abs(D) / T**2, rtol=1e-14)
    np.testing.assert_allclose(np.abs(qn.qd).max(0), 15 / 8 * np.abs(D) / T, rtol=1e-14)
    # the quintic's peak acceleration falls between samples: the exact value at s = 1/2 - sqrt(3)/6
    t_peak = T * (0.5 - math.sqrt(3) / 6)
    np.testing.assert_allclose(np.abs(qn.evaluate(t_peak)[2][0]), 10 / math.sqrt(3) * np.abs(D) / T**2, rtol=1e-13)
    assert np.all(np.abs(qn.qdd).max(0) <= 10 / math.sqrt(3) * np.abs(D) / T**2 * (1 + 1e-14))


def test_docstring_examples_of_one_segment():
    jt = cubic([0, 0, 0.5, 0], [1, 0, 0.5, 0], 2.0)
    assert jt.coefficients[0, 0].tolist() == [0.0, 0.0, 0.75, -0.25]
    jt = quintic([0, 0, 0.5, 0], [1, 0, 0.5, 0], 1.0)
    assert jt.coefficients[0, 0].tolist() == [0.0, 0.0, 0.0, 10.0, -15.0, 6.0]


# --------------------------------------------------------------------------------------------------
# sequences through via points
# --------------------------------------------------------------------------------------------------
@st.composite
def sequences(draw, min_points=2, max_points=6):
    n = draw(st.integers(min_points, max_points))
    q = np.array(draw(st.lists(CONFIG, min_size=n, max_size=n)), float)
    steps = draw(st.lists(st.integers(1, 300), min_size=n - 1, max_size=n - 1))   # durations in 10 ms
    start = draw(st.integers(0, 50))
    t = 0.01 * np.cumsum([start] + steps)
    return q, t


def _mean_rule(q, t, stops=()):
    """eq-traj-via-rule written out, joint by joint, point by point."""
    n = len(t)
    v = np.zeros((n, 4))
    for k in range(1, n - 1):
        for i in range(4):
            s1 = (q[k, i] - q[k - 1, i]) / (t[k] - t[k - 1])
            s2 = (q[k + 1, i] - q[k, i]) / (t[k + 1] - t[k])
            if k in stops or np.sign(s1) != np.sign(s2):
                v[k, i] = 0.0
            else:
                v[k, i] = (s1 + s2) / 2
    return v


def _check_boundaries(jt):
    """Every segment starts and ends with the values at its two points: q, qd, and qdd for the quintic."""
    for j in range(len(jt.durations)):
        T = jt.durations[j]
        for i in range(4):
            c = jt.coefficients[j, i]
            dc, ddc = P.polyder(c), P.polyder(c, 2)
            sc = _scale(c, T)
            for tau, k in ((0.0, j), (T, j + 1)):
                assert abs(P.polyval(tau, c) - jt.points[k, i]) <= 1e-12 * sc
                assert abs(P.polyval(tau, dc) - jt.velocities[k, i]) <= 1e-11 * sc / T
                if jt.kind == "quintic":
                    err = abs(P.polyval(tau, ddc) - jt.accelerations[k, i])
                    assert _largest.record("quintic end accelerations (relative)", err * T**2 / sc) <= 1e-10


@given(sequences(), st.sampled_from(["cubic", "quintic"]))
def test_sequences_meet_their_boundary_conditions_and_the_velocity_rule(seq, kind):
    q, t = seq
    jt = joint_trajectory(q, t, kind, dt=0.01, check=False)
    np.testing.assert_allclose(jt.velocities, _mean_rule(q, t), rtol=1e-12, atol=1e-12)
    _check_boundaries(jt)
    # the quintic's inner accelerations: the slope of the velocities across the point, zero at the ends
    if kind == "quintic":
        want = np.zeros((len(t), 4))
        for k in range(1, len(t) - 1):
            want[k] = (jt.velocities[k + 1] - jt.velocities[k - 1]) / (t[k + 1] - t[k - 1])
        np.testing.assert_allclose(jt.accelerations, want, rtol=1e-12, atol=1e-12)
    else:
        assert jt.accelerations is None


@given(sequences(min_points=3), st.sampled_from(["cubic", "quintic"]))
def test_velocity_is_continuous_at_via_points_and_acceleration_for_the_quintic(seq, kind):
    q, t = seq
    jt = joint_trajectory(q, t, kind, dt=0.01, check=False)
    for k in range(1, len(t) - 1):
        left, right = jt.coefficients[k - 1], jt.coefficients[k]
        T = jt.durations[k - 1]
        for i in range(4):
            sc = max(_scale(left[i], T), _scale(right[i], jt.durations[k]))
            assert abs(P.polyval(T, left[i]) - P.polyval(0.0, right[i])) <= 1e-12 * sc
            jump_v = abs(P.polyval(T, P.polyder(left[i])) - P.polyval(0.0, P.polyder(right[i])))
            assert _largest.record("velocity jump at a via point (relative)", jump_v * T / sc) <= 1e-11
            if kind == "quintic":
                jump_a = abs(P.polyval(T, P.polyder(left[i], 2)) - P.polyval(0.0, P.polyder(right[i], 2)))
                assert _largest.record("quintic acceleration jump (relative)", jump_a * T**2 / sc) <= 1e-10


def test_the_cubic_acceleration_jumps_at_a_via_point_unless_the_spline_rule_is_used():
    q = np.array([[0.0, 0, 0.5, 0], [1.0, 0, 0.5, 0], [3.0, 0, 0.5, 0], [3.5, 0, 0.5, 0]])
    t = [0.0, 1.0, 2.0, 4.0]
    mean = joint_trajectory(q, t, "cubic")
    left = P.polyval(1.0, P.polyder(mean.coefficients[0, 0], 2))
    right = P.polyval(0.0, P.polyder(mean.coefficients[1, 0], 2))
    assert abs(left - right) > 1.0                      # the mean rule: velocity continuous, acceleration not
    spline = joint_trajectory(q, t, "cubic", velocities="spline")
    for k in (1, 2):
        T = spline.durations[k - 1]
        a_l = P.polyval(T, P.polyder(spline.coefficients[k - 1, 0], 2))
        a_r = P.polyval(0.0, P.polyder(spline.coefficients[k, 0], 2))
        assert abs(a_l - a_r) < 1e-12


@given(sequences(min_points=3), VEC, VEC)
def test_spline_rule_is_scipys_clamped_cubic_spline(seq, v0, v1):
    from scipy.interpolate import CubicSpline

    q, t = seq
    t = t - t[0]  # a start velocity needs the motion to start at 0 (the arm rests before its first point)
    jt = joint_trajectory(q, t, "cubic", velocities="spline", qd_start=v0, qd_end=v1, dt=0.01, check=False)
    for i in range(4):
        cs = CubicSpline(t, q[:, i], bc_type=((1, v0[i]), (1, v1[i])))
        scale = np.max(np.abs(q[:, i])) + np.max(np.abs(cs(t, 1))) * np.max(np.diff(t)) + 1.0
        err = np.max(np.abs(jt.velocities[:, i] - cs(t, 1))) * np.max(np.diff(t)) / scale
        assert _largest.record("spline velocities vs scipy (relative)", err) < 1e-9
        tt = np.linspace(t[0], t[-1], 301)
        err = np.max(np.abs(jt.evaluate(tt)[0][:, i] - cs(tt))) / scale
        assert _largest.record("spline positions vs scipy (relative)", err) < 1e-9


def test_stops_hold_the_arm_still_with_either_rule():
    q = np.array([[0.0, 0, 0.5, 0], [1.0, 0.5, 0.6, 0], [2.0, 1.0, 0.7, 0], [3.0, 1.5, 0.8, 0]])
    t = [0.0, 1.0, 2.0, 3.0]
    for kind, rule in (("cubic", "mean"), ("cubic", "spline"), ("quintic", "mean")):
        jt = joint_trajectory(q, t, kind, velocities=rule, stops=[2])
        assert jt.stops == (2,) and np.all(jt.velocities[2] == 0) and np.all(jt.velocities[1, :3] != 0)
        k = round(2.0 / jt.dt)
        assert np.all(jt.qd[k] == 0)
        if kind == "quintic":
            assert np.all(jt.accelerations[2] == 0) and np.all(jt.qdd[k] == 0)
    np.testing.assert_allclose(joint_trajectory(q, t, stops=[2]).velocities, _mean_rule(q, np.array(t), stops=(2,)))


def test_explicit_values_at_every_point():
    q = np.array([[0.0, 0, 0.5, 0], [1.0, 0.5, 0.6, 0], [2.0, 1.0, 0.7, 0]])
    v = np.array([[0.1, 0, 0, 0], [0.5, 0.2, 0.1, 0], [0, 0, 0, 0]])
    a = np.array([[0, 0, 0, 0], [0.3, -0.1, 0, 0.2], [0, 0, 0, 0]])
    jt = joint_trajectory(q, [0, 2, 4], "quintic", velocities=v, accelerations=a)
    assert jt.rule == "given, accelerations given"
    _check_boundaries(jt)
    np.testing.assert_array_equal(jt.velocities, v)
    np.testing.assert_array_equal(jt.accelerations, a)


# --------------------------------------------------------------------------------------------------
# evaluation and sampling: finite differences, rest before and after, the sampled series
# --------------------------------------------------------------------------------------------------
@settings(max_examples=60)
@given(sequences(), st.sampled_from(["cubic", "quintic"]), st.floats(0.05, 0.95))
def test_velocity_and_acceleration_are_the_derivatives(seq, kind, frac):
    q, t = seq
    jt = joint_trajectory(q, t, kind, dt=0.01, check=False)
    for j in range(len(jt.durations)):
        T = jt.durations[j]
        tau = frac * T
        h = 1e-3 * T
        tt = t[j] + tau + np.array([-h, 0.0, h])
        qs, qds, qdds = jt.evaluate(tt)
        for i in range(4):
            c = jt.coefficients[j, i]
            # bounds on the segment of |q|, |q'|, |q''|, |q'''|, |q''''| (as sums |c_k| T^k of each derivative)
            m0, m1, m2, m3, m4 = (_scale(P.polyder(c, r), T) if len(c) > r else 0.0 for r in range(5))
            fd1 = (qs[2, i] - qs[0, i]) / (2 * h)
            fd2 = (qds[2, i] - qds[0, i]) / (2 * h)
            # truncation h^2/6 max|f'''| plus rounding: Horner's error (eps times the sum of the terms) and the
            # time rounded to eps |t| (times the derivative), divided by h
            eps = np.finfo(float).eps
            tmax = float(np.max(np.abs(tt)))
            bound1 = h**2 / 6 * m3 + 4 * eps * (m0 + m1 * tmax) / h
            bound2 = h**2 / 6 * m4 + 4 * eps * (m1 + m2 * tmax) / h
            assert _largest.record("qd vs finite differences / bound", abs(fd1 - qds[1, i]) / bound1) <= 1.0
            assert _largest.record("qdd vs finite differences / bound", abs(fd2 - qdds[1, i]) / bound2) <= 1.0


def test_sampling_rests_before_and_after_and_matches_evaluate():
    q = np.array([[0.0, -1.0, 0.5, 0.2], [0.5, -0.5, 0.4, 0.0], [1.0, -0.2, 0.3, -0.2]])
    jt = joint_trajectory(q, [0.5, 1.5, 3.0], "quintic", total=4.0)
    assert jt.t.shape == (4001,) and jt.t[-1] == 4.0 and jt.motion_end == 3.0 and jt.rest == 1.0
    before, after = jt.t < 0.5, jt.t > 3.0
    assert np.all(jt.q[before] == q[0]) and np.all(jt.q[after] == q[-1])
    assert np.all(jt.qd[before | after] == 0) and np.all(jt.qdd[before | after] == 0)
    k = round(1.5 / 1e-3)
    np.testing.assert_allclose(jt.q[k], q[1], atol=1e-15)
    qq, qqd, qqdd = jt.evaluate(jt.t[::-7])                 # any order of times
    np.testing.assert_array_equal(qq, jt.q[::-7])
    np.testing.assert_array_equal(qqdd, jt.qdd[::-7])
    assert not jt.q.flags.writeable and not jt.coefficients.flags.writeable
    with pytest.raises(NonFiniteError, match="not a finite time"):
        jt.evaluate([0.0, float("nan")])
    assert "quintic, 3 points" in repr(jt)


def test_tool_motion_is_the_kinematics_of_chapter_one():
    q = np.array([[0.3, -1.2, 0.4, 0.0], [0.8, -0.9, 0.6, 0.5], [1.2, -1.5, 0.5, 0.2]])
    jt = joint_trajectory(q, [0.0, 1.0, 2.5], "quintic")
    x, xd, xdd = jt.tool()
    for k in range(0, len(jt.t), 97):
        np.testing.assert_allclose(x[k], pose(jt.q[k]), atol=1e-15)
        J = jacobian(jt.q[k])
        np.testing.assert_allclose(xd[k], J @ jt.qd[k], atol=1e-14)
        np.testing.assert_allclose(xdd[k], J @ jt.qdd[k] + jacobian_dot(jt.q[k], jt.qd[k]) @ jt.qd[k], atol=1e-14)
    np.testing.assert_allclose(jt.tool_speed(), np.linalg.norm(xd[:, :3], axis=1))
    summ = jt.summary()
    assert summ["points"] == 3 and summ["kind"] == "quintic"
    np.testing.assert_allclose(summ["max_joint_speed"], np.abs(jt.qd).max(0))


# --------------------------------------------------------------------------------------------------
# the joint limits
# --------------------------------------------------------------------------------------------------
def test_the_quill_stroke_is_checked_at_the_points_and_between_them():
    p = ScaraParams()
    with pytest.raises(UnreachableError, match=r"point p1: d3 = 1.2 m is outside the quill's stroke"):
        joint_trajectory([[0, 0, 0.5, 0], [0, 0, 1.2, 0]], [0, 1])
    # from d3 = 0.95 m at 0.5 m/s towards 0.99 m in 1 s: the cubic overshoots the bottom of the stroke
    with pytest.raises(UnreachableError) as info:
        cubic([0, 0, 0.95, 0], [0, 0, 0.99, 0], 1.0, qd_start=[0, 0, 0.5, 0])
    msg = str(info.value)
    assert "between the points" in msg and "segment p0->p1" in msg and "d3_max = 1 m" in msg
    # the extreme, found independently: the root of qd of joint 3 in (0, 1)
    jt = cubic([0, 0, 0.95, 0], [0, 0, 0.99, 0], 1.0, qd_start=[0, 0, 0.5, 0], check=False)
    c = jt.coefficients[0, 2]
    roots = [r.real for r in np.roots(P.polyder(c)[::-1]) if 0 < r.real < 1]
    peak = max(P.polyval(r, c) for r in roots)
    assert peak > p.d3_max and f"reaches {peak:.6g} m" in msg
    assert jt.q[:, 2].max() <= peak + 1e-12
    # a stroke that allows it
    cubic([0, 0, 0.95, 0], [0, 0, 0.99, 0], 1.0, qd_start=[0, 0, 0.5, 0], p=p.replace(d3_max=1.5))


# --------------------------------------------------------------------------------------------------
# bad input
# --------------------------------------------------------------------------------------------------
Q2 = [[0, 0, 0.5, 0], [1, 0, 0.5, 0]]


@pytest.mark.parametrize("call, error, words", [
    (lambda: joint_trajectory([[0, 0, 0.5]], [0]), ShapeError, ["points must have shape", "(1, 3)"]),
    (lambda: joint_trajectory([[0, 0, 0.5, 0]], [0]), ScaraError, ["number of points = 1", "2 <="]),
    (lambda: joint_trajectory(Q2, [0, 1, 2]), ShapeError, ["one entry per point (2)", "got 3"]),
    (lambda: joint_trajectory(Q2, [[0, 1]]), ShapeError, ["times must be a sequence of 2 times"]),
    (lambda: joint_trajectory(Q2, [0, float("nan")]), NonFiniteError, ["times[1] = nan"]),
    (lambda: joint_trajectory([[0, 0, 0.5, 0], [1, np.inf, 0.5, 0]], [0, 1]), NonFiniteError, ["points[(1, 1)]"]),
    (lambda: joint_trajectory(Q2, [1.0, 1.0]), ScaraError, ["times[1] = 1 s is not after times[0] = 1 s"]),
    (lambda: joint_trajectory(Q2, [2.0, 1.0]), ScaraError, ["times[1] = 1 s is not after times[0] = 2 s"]),
    (lambda: joint_trajectory(Q2, [-1.0, 1.0]), ScaraError, ["times[0] = -1 s must be >= 0"]),
    (lambda: joint_trajectory(Q2, [0.0, 1.0005]), ScaraError, ["times[1] = 1.0005 s is not a whole number"]),
    (lambda: joint_trajectory(Q2, [0, 1], "linear"), ScaraError, ["kind = 'linear'", "cubic", "quintic"]),
    (lambda: joint_trajectory(Q2, [0, 1], velocities="fast"), ScaraError, ["velocities = 'fast'", "mean"]),
    (lambda: joint_trajectory(Q2, [0, 1], "quintic", accelerations="zero"), ScaraError, ["accelerations = 'zero'"]),
    (lambda: joint_trajectory(Q2, [0, 1], velocities=np.zeros((3, 4))), ShapeError, ["(2, 4)", "(3, 4)"]),
    (lambda: joint_trajectory(Q2, [0, 1], qdd_start=1.0), ScaraError, ["a cubic cannot take accelerations"]),
    (lambda: joint_trajectory(Q2, [0, 1], stops=[0]), ScaraError, ["stop 0 is an end point"]),
    (lambda: joint_trajectory(Q2 + [[2, 0, 0.5, 0]], [0, 1, 2], stops=[1.0]), ScaraError, ["a stop = 1.0",
                                                                                          "integer index"]),
    (lambda: joint_trajectory(Q2 + [[2, 0, 0.5, 0]], [0, 1, 2], stops=[1], velocities=np.zeros((3, 4))),
     ScaraError, ["with explicit velocities, give 0"]),
    (lambda: joint_trajectory(Q2, [0, 1], velocities=np.zeros((2, 4)), qd_start=1.0), ScaraError, ["leave qd_start at 0"]),
    (lambda: joint_trajectory(Q2, [0.5, 1.5], qd_start=0.2), ScaraError, ["rests at the first point", "velocity"]),
    (lambda: joint_trajectory(Q2, [0, 1], qd_end=0.2, total=2.0), ScaraError, ["rests at the last point"]),
    (lambda: joint_trajectory(Q2, [0, 2], total=1.0), ScaraError, ["total = 1 s is shorter than the motion"]),
    (lambda: joint_trajectory(Q2, [0, 1], dt=0.0), ScaraError, ["dt = 0.0 must be > 0"]),
    (lambda: joint_trajectory(Q2, [0, 1e4], dt=1e-3), ScaraError, ["MAX_SAMPLES"]),
    (lambda: joint_trajectory(Q2, [0, 1], labels=["a"]), ShapeError, ["labels must be 2 names"]),
    (lambda: joint_trajectory(Q2, [0, 1], check="yes"), ScaraError, ["check = 'yes' must be True or False"]),
    (lambda: joint_trajectory([[0, 0, 0.5, 0], [2e6, 0, 0.5, 0]], [0, 1]), ScaraError, ["MAX_ANGLE"]),
    (lambda: cubic([0, 0, 0.5], [1, 0, 0.5, 0], 1.0), ShapeError, ["q0 must have shape (4,)"]),
    (lambda: cubic(Q2[0], Q2[1], -1.0), ScaraError, ["duration = -1.0 must be > 0"]),
    (lambda: cubic(Q2[0], Q2[1], 1.0, qd_start=[1, 2]), ShapeError, ["qd_start must have shape (4,)"]),
    (lambda: quintic(Q2[0], Q2[1], 1.0, qdd_end=float("nan")), NonFiniteError, ["qdd_end = nan is not finite"]),
    (lambda: quintic(Q2[0], Q2[1], 1.0, qdd_end="big"), ScaraError, ["qdd_end must be a number, got 'big'"]),
])
def test_bad_input_is_refused_with_a_clear_message(call, error, words):
    with pytest.raises(error) as info:
        call()
    for w in words:
        assert w in str(info.value), (w, str(info.value))


# --------------------------------------------------------------------------------------------------
# the joint-space counterpart of the reference, and its deviation from the operational path
# --------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def counterpart(ref):
    return joint_counterpart(ref, "cubic"), joint_counterpart(ref, "quintic")


def test_counterpart_passes_the_waypoints_when_the_reference_does(ref, counterpart):
    tp = passage_times(ref)
    # stops: the arrival; via points: the middle of the overlap (hand-computed from the chapter's table)
    assert tp[0] == 0.0 and tp[1] == 4.0 and tp[2] == 12.0
    assert math.isclose(tp[3], 20.0 - SCENARIO_VIA[3] / 2)
    assert math.isclose(tp[11], ref.motion_end)
    for jt in counterpart:
        assert jt.motion_end == ref.motion_end and jt.total == ref.total and jt.dt == ref.dt
        assert jt.stops == (1, 2, 6, 7, 9, 10)
        np.testing.assert_allclose(jt.times, tp, atol=1e-12)
        k = np.round(tp / ref.dt).astype(int)
        # at every knot the tool is where the operational trajectory is at that instant
        np.testing.assert_allclose(jt.tool()[0][k], ref.x[k], atol=1e-12)
        stops = [i for i in range(12) if not ref.via[i]]
        np.testing.assert_allclose(jt.tool()[0][k[stops], :3], SCENARIO_POINTS[stops], atol=1e-12)
        # the knots are the closed-form inverse kinematics with the elbow theta2 < 0
        q = ikine(ref.x[k], elbow=-1)
        np.testing.assert_allclose(np.cos(jt.points[:, [0, 3]]), np.cos(q[:, [0, 3]]), atol=1e-12)
        np.testing.assert_allclose(jt.points[:, 1:3], q[:, 1:3], atol=1e-12)
        assert np.all(jt.qd[k[stops]] == 0)


def test_path_deviation_against_a_brute_force_distance(ref, counterpart):
    jt = counterpart[0]
    d = path_deviation(jt, ref)
    assert d.shape == jt.t.shape and d[0] < 1e-12
    tool = jt.tool()[0][:, :3]
    path = ref.x[:, :3]
    for k in list(range(0, len(d), 2333)) + [int(np.argmax(d))]:
        brute = np.min(np.linalg.norm(path - tool[k], axis=1))   # the nearest sample: never nearer than the curve
        # between samples <= 0.07 mm apart, the curve is at most half a spacing nearer than its nearest sample
        assert d[k] <= brute + 1e-15 and brute - d[k] <= 4e-5
    # the half circle is replaced by a curve near its chord: the largest distance is on it, near its top
    k = int(np.argmax(d))
    assert ref.segments_at(ref.t[k]) == [10] or jt.segment_labels[np.searchsorted(jt.times, jt.t[k]) - 1] == "p10->p11"
    assert 0.040 < d[k] < 0.050


def test_segment_deviations_split_the_deviation_by_segment(ref, counterpart):
    jc, jq = counterpart
    dc, dq = segment_deviations(jc, ref), segment_deviations(jq, ref)
    assert list(dc) == jc.segment_labels and max(dc.values()) == path_deviation(jc, ref).max()
    # a segment from stop to stop: every joint follows q_i + Delta q sigma(tau) with the same sigma, so the
    # tool's path is the image of the same straight joint-space segment whatever the law (cubic or quintic)
    for lab in ("p0->p1", "p1->p2", "p6->p7", "p9->p10", "p10->p11"):
        j = jc.segment_labels.index(lab)
        for jt in (jc, jq):
            w = (jt.t >= jt.segment_start[j]) & (jt.t <= jt.segment_end[j])
            dq_ = jt.points[j + 1] - jt.points[j]
            moving = np.abs(dq_) > 1e-9
            sigma = (jt.q[w][:, moving] - jt.points[j, moving]) / dq_[moving]
            assert np.ptp(sigma, axis=1).max() < 1e-12, (lab, jt.kind)   # one sigma(tau) for every joint
        # the same path sampled at other instants: the largest distances agree to the sampling (<= 0.07 mm apart)
        assert abs(dc[lab] - dq[lab]) < 1e-6, lab
    # next to a via point the velocity there is not along Delta q, and the path depends on the law
    assert abs(dc["p3->p4"] - dq["p3->p4"]) > 1e-3


def test_more_knots_bring_the_tool_onto_the_path(ref):
    dev = [path_deviation(joint_counterpart(ref, extra=e), ref).max() for e in (0, 3, 15)]
    assert dev[0] > dev[1] > dev[2] and dev[2] < 2e-4


def test_compare_joint_space_rows(ref):
    rows = compare_joint_space(ref)
    assert [r["name"] for r in rows] == ["operational", "joint space, cubic", "joint space, quintic"]
    assert rows[0]["max_deviation"] == 0.0 and all(r["motion_end"] == ref.motion_end for r in rows)
    # the operational joint speeds: finite differences of the closed-form inverse kinematics
    q = np.array(ref.joints())
    q[:, 0] = np.unwrap(q[:, 0])
    fd = np.abs(np.diff(q, axis=0) / ref.dt).max(axis=0)
    np.testing.assert_allclose(rows[0]["max_joint_speed"], fd, rtol=2e-3)
    with pytest.raises(ScaraError, match="kinds must be a sequence"):
        compare_joint_space(ref, kinds="cubic")
    with pytest.raises(ScaraError, match="kind = 'linear'"):
        compare_joint_space(ref, kinds=("linear",))


def test_counterpart_and_deviation_refuse_other_objects(ref):
    with pytest.raises(ScaraError, match="traj must be a Trajectory"):
        joint_counterpart("p0 to p11")
    with pytest.raises(ScaraError, match="extra = 5000"):
        joint_counterpart(ref, extra=5000)
    with pytest.raises(ScaraError, match="jt must be a JointTrajectory"):
        path_deviation(ref, ref)
    with pytest.raises(ScaraError, match="traj must be a Trajectory"):
        path_deviation(joint_counterpart(ref), np.zeros((3, 4)))


def test_a_via_point_off_the_sample_grid_is_rounded_to_a_sample():
    from scara import Waypoint

    traj = plan_path([Waypoint([0.3, 0.2, 0.5]), Waypoint([0.4, 0.2, 0.5], anticipation=0.003),
                      Waypoint([0.4, 0.3, 0.5])], durations=[1.0, 1.0])
    tp = passage_times(traj)
    assert tp[1] == round((traj.segment_start[1] + traj.segment_end[0]) / 2 / traj.dt) * traj.dt
    assert abs(tp[1] - 0.9985) <= traj.dt / 2 + 1e-12


# --------------------------------------------------------------------------------------------------
# a joint-space trajectory drives the simulation as a joint reference
# --------------------------------------------------------------------------------------------------
def test_a_joint_trajectory_is_a_joint_reference_for_simulate():
    from scara import PDGravityController, simulate

    q = np.array([[0.3, -1.2, 0.4, 0.0], [0.5, -1.0, 0.45, 0.2], [0.6, -1.1, 0.5, 0.1]])
    jt = joint_trajectory(q, [0.0, 1.0, 2.0], "quintic", total=2.5)
    r = simulate(PDGravityController(), joint_reference=jt, dt=jt.dt)
    # the controller receives the trajectory's rows [q, qd, qdd] sample by sample, and starts on it
    np.testing.assert_array_equal(r.reference, np.hstack([jt.q, jt.qd, jt.qdd]))
    np.testing.assert_array_equal(r.q_d, jt.q)
    np.testing.assert_array_equal(r.q[0], jt.q[0])
    # PD with exact gravity compensation lags during the motion and closes the gap once the reference rests
    err = np.max(np.abs(r.q - jt.q), axis=1)
    assert err[-1] < 0.1 * err[jt.t <= jt.motion_end].max()
    with pytest.raises(ScaraError, match="sampled every 0.001 s but the run's dt = 0.002 s"):
        simulate(PDGravityController(), joint_reference=jt, dt=2e-3)


def test_the_trajectory_owns_its_arrays():
    """joint_trajectory neither freezes nor keeps the caller's arrays: the result's are its own copies."""
    points = np.array([[0.0, 0.0, 0.5, 0.0], [1.0, -1.0, 0.5, 0.0], [2.0, -1.0, 0.5, 0.0]])
    times = np.array([0.0, 1.0, 3.0])
    vel = np.zeros((3, 4))
    keep = points.copy()
    jt = joint_trajectory(points, times, velocities=vel)
    assert points.flags.writeable and times.flags.writeable and vel.flags.writeable
    for mine, theirs in ((jt.points, points), (jt.times, times), (jt.velocities, vel)):
        assert not np.shares_memory(mine, theirs)
    points[1, 0] = 5.0
    assert np.array_equal(jt.points, keep)


def test_renamed_end_conditions_say_what_they_are():
    """The end velocities and accelerations are qd_start, qd_end, qdd_start, qdd_end (a1 is a link length)."""
    jt = quintic([0, 0, 0.5, 0], [1, 0, 0.5, 0], 1.0, qd_start=0.5, qdd_end=-1.0)
    assert jt.velocities[0].tolist() == [0.5] * 4 and jt.accelerations[-1].tolist() == [-1.0] * 4
    with pytest.raises(TypeError):
        quintic([0, 0, 0.5, 0], [1, 0, 0.5, 0], 1.0, a1=1.0)
