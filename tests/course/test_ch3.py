"""Chapter 3's exercise answers against closed forms, for a few drawn parameter sets (not the solver against
itself)."""
import math

import numpy as np
import pytest

from scara import ScaraParams, ikine
from scara.course.exercises import draw, exercise, solve
from scara.errors import ScaraError
from scara.trajectory import REFERENCE_ANTICIPATIONS, REFERENCE_DURATIONS, REFERENCE_POINTS

STUDENTS = [f"s{i}" for i in range(4)]


def drawn(label):
    return [draw(exercise(label), b"test-ch3", s) for s in STUDENTS]


def test_corner_closed_form():
    for params, r in drawn("ex-traj-corner"):
        a = 4.5 * params["L"] / params["tf"] ** 2
        assert r["a"] == pytest.approx(a, rel=1e-12)
        assert r["d_mm"] == pytest.approx(1000 * a * params["dt"] ** 2 / (4 * math.sqrt(2)), rel=1e-7)
        assert r["t_into"] == pytest.approx(params["dt"] / 2, abs=1e-6)


def test_corner_refuses_an_anticipation_longer_than_the_blend():
    with pytest.raises(ScaraError):
        solve("ex-traj-corner", {"tf": 2.0, "dt": 1.0})


def test_fast_closed_form():
    L = float(np.linalg.norm(REFERENCE_POINTS[7] - REFERENCE_POINTS[6]))
    for params, r in drawn("ex-traj-fast") + [(exercise("ex-traj-fast").defaults, solve("ex-traj-fast"))]:
        v, a = params["v"], params["acc"]
        exact = L / v + v / a if L >= v * v / a else 2 * math.sqrt(L / a)
        assert exact <= r["T"] < exact + 1e-3 + 1e-12
        assert abs(r["T"] * 1000 - round(r["T"] * 1000)) < 1e-9
    assert solve("ex-traj-fast")["T"] == pytest.approx(2.125)


def test_half_circle_scaling():
    rho = 0.05
    for params, r in drawn("ex-traj-half-circle"):
        T = params["T_arc"]
        assert r["growth"] == pytest.approx((9.6 / T) ** 2, rel=1e-9)
        v_c = 1.5 * math.pi * rho / T
        assert r["cent_quick"] == pytest.approx(v_c**2 / rho, rel=1e-9)
        # the reference rests 4 s; every second taken off the arc is added to the rest
        assert r["quick_rest"] == pytest.approx(4.0 + 9.6 - T, abs=1e-9)


def test_turn_closed_form():
    for params, r in drawn("ex-traj-turn"):
        assert r["phidot_max_deg"] == pytest.approx(1.5 * params["turn"] / REFERENCE_DURATIONS[0], rel=1e-9)
        assert r["position_change"] == 0.0


def _trapezoid_time(s, L, T):
    """Time at which the trapezoid (blend T/3) over L in T reaches arc length s."""
    tc = T / 3
    vc = L / (T - tc)
    a = vc / tc
    if s <= 0.5 * a * tc**2:
        return math.sqrt(2 * s / a)
    if s <= L - 0.5 * a * tc**2:
        return s / vc + tc / 2
    return T - math.sqrt(2 * (L - s) / a)


def test_reach_crossing_time():
    """The first sample beyond r = 1 m on the straight line p6 -> p7, from the quadratic |p6 + s u|_xy = 1 and
    the trapezoid inverted."""
    start = sum(REFERENCE_DURATIONS[:6]) - sum(v for k, v in REFERENCE_ANTICIPATIONS.items() if k <= 6)
    for params, r in drawn("ex-traj-reach"):
        p7 = np.array([params["x7"], params["y7"], params["z7"]])
        assert r["r7"] == pytest.approx(math.hypot(p7[0], p7[1]), rel=1e-12)
        p6 = REFERENCE_POINTS[6]
        L = float(np.linalg.norm(p7 - p6))
        u = (p7 - p6) / L
        A, B, C = u[0] ** 2 + u[1] ** 2, 2 * (p6[0] * u[0] + p6[1] * u[1]), p6[0] ** 2 + p6[1] ** 2 - 1.0
        s_star = (-B + math.sqrt(B * B - 4 * A * C)) / (2 * A)
        tau = _trapezoid_time(s_star, L, REFERENCE_DURATIONS[6])
        expected = start + math.ceil(tau / 1e-3 - 1e-9) * 1e-3
        assert r["t_out"] == pytest.approx(expected, abs=1.5e-3)


def test_reach_refuses_a_reachable_point():
    with pytest.raises(ScaraError):
        solve("ex-traj-reach", {"x7": 0.8, "y7": 0.35})


def test_stop_at_p4():
    r = solve("ex-traj-stop")
    assert r["end_stop"] == pytest.approx(r["end_ref"] + REFERENCE_ANTICIPATIONS[4], abs=1e-9)
    p = ScaraParams()
    theta2 = ikine(np.r_[REFERENCE_POINTS[4], 0.0], p, elbow=-1)[1]
    assert r["w_stop"] == pytest.approx(p.a1 * p.a2 * abs(math.sin(theta2)), rel=1e-9)


def test_half_anticipation_square_law():
    solve("ex-traj-stop")  # warms the reference
    for params, r in drawn("ex-traj-half-anticipation"):
        dt = params["antic"]
        assert r["d_mm"] == pytest.approx(r["d_ref_mm"] * (dt / 2.0) ** 2, rel=1e-6)
        assert r["end"] == pytest.approx(r["end_ref"] + 2.0 - dt, abs=1e-9)


def test_rest_to_rest_from_the_knots():
    """theta2 at p6 and p7 by the inverse kinematics, then the peaks 3 dq / (2 T) and 15 dq / (8 T)."""
    p = ScaraParams()
    r = solve("ex-traj-rest-to-rest")
    q6 = ikine(np.r_[REFERENCE_POINTS[6], 0.0], p, elbow=-1)
    q7 = ikine(np.r_[REFERENCE_POINTS[7], 0.0], p, elbow=-1)
    dq = math.degrees(abs(q7[1] - q6[1]))
    T = REFERENCE_DURATIONS[6]
    assert r["cubic_peak"] == pytest.approx(1.5 * dq / T, rel=1e-9)
    assert r["quintic_peak"] == pytest.approx(15 / 8 * dq / T, rel=1e-9)


def test_knots_monotone_in_the_tolerance():
    """A looser tolerance never needs more knots; the book's millimetre needs 8."""
    values = exercise("ex-traj-knots").param("tol_mm").values()
    ns = [solve("ex-traj-knots", {"tol_mm": t})["n"] for t in values]
    assert all(a >= b for a, b in zip(ns, ns[1:]))
    assert solve("ex-traj-knots")["n"] == 8
    assert all(solve("ex-traj-knots", {"tol_mm": t})["dev_mm"] <= t for t in values)
