"""Independent checks of chapter 5's exercise answers (scara.course.answers.ch5) for a few drawn parameter sets:
closed forms (sag, B33, the cos(theta2) law of B11), the payload used to make the torques, conservation laws."""
import math

import numpy as np
import pytest

from scara import ScaraParams, clik2, inertia, reference_trajectory
from scara.course.exercises import draw_params, exercise, solve

STUDENTS = [f"s{i}" for i in range(4)]
G0 = ScaraParams().g0


def drawn(label):
    return [draw_params(exercise(label), b"test-ch5", s) for s in STUDENTS]


@pytest.fixture(scope="module")
def q_start():
    return clik2(reference_trajectory()).q[0]


@pytest.mark.parametrize("params", drawn("ex-dyn-rotor"))
def test_rotor_share(params):
    r = solve("ex-dyn-rotor", params)
    rotor = 50.0**2 * 0.005                        # k_r3^2 I_m3 of the course's table
    assert math.isclose(r["share_pct"], 100 * rotor / (10.0 + params["m_L"] + rotor), rel_tol=1e-9)


@pytest.mark.parametrize("params", drawn("ex-dyn-stiff"))
def test_stiff_gain(params):
    r = solve("ex-dyn-stiff", params)
    assert math.isclose(r["kp"], params["m_L"] * G0 / (params["sag_mm"] * 1e-3), rel_tol=1e-12)
    assert math.isclose(r["sag_sim_mm"], params["sag_mm"], rel_tol=1e-3)


@pytest.mark.parametrize("params", drawn("ex-dyn-fall"))
def test_fall_first_order(params):
    r = solve("ex-dyn-fall", params)
    p = ScaraParams().with_payload(params["m_L"])
    # v(t) solves B33 v' + F33 v = m3 g0: its finite-difference residual vanishes
    t, h = params["t"], 1e-6
    v = lambda s: r["v_inf"] * (1 - math.exp(-s / r["tau_3"]))  # noqa: E731
    B33, F33 = r["tau_3"] * r["F33"], r["F33"]
    assert abs(B33 * (v(t + h) - v(t - h)) / (2 * h) + F33 * v(t) - p.m3 * G0) < 1e-6 * p.m3 * G0
    assert math.isclose(r["v_pred"], v(t), rel_tol=1e-12)
    assert abs(r["v_sim"] / r["v_pred"] - 1) < 0.01          # the arm's rotation changes little


@pytest.mark.parametrize("params", drawn("ex-dyn-weigh"))
def test_weigh_finds_the_payload(params):
    assert abs(solve("ex-dyn-weigh", params)["mL_hat"] - params["m_L"]) < 1e-8


@pytest.mark.parametrize("params", drawn("ex-dyn-energy"))
def test_energy_momentum_kept(params, q_start):
    r = solve("ex-dyn-energy", params)
    p = ScaraParams().with_payload(params["m_L"])
    qd0 = np.array([params["w1"], params["w2"], 0.0, params["w4"]])
    assert math.isclose(r["T0"], 0.5 * qd0 @ inertia(q_start, p) @ qd0, rel_tol=1e-9)
    assert r["T1"] < r["T0"] and r["share4_pct"] > 99
    assert abs(r["L1"] - r["L0"]) < 1e-3 * abs(r["L0"])


@pytest.mark.parametrize("params", drawn("ex-dyn-fold"))
def test_fold_cosine_law(params):
    r = solve("ex-dyn-fold", params)
    p = ScaraParams().with_payload(params["m_L"])
    amp = 2 * p.a1 * (p.m_l2 * p.l2 + p.m3 * p.a2)
    assert math.isclose(r["B11_0"] - r["B11_90"], amp, rel_tol=1e-9)
    assert math.isclose(r["B11_90"] - r["B11_180"], amp, rel_tol=1e-9)
    # theta1, d3, theta4 change nothing
    assert math.isclose(inertia([2.0, 0.0, 0.9, 1.0], p)[0, 0], r["B11_0"], rel_tol=1e-12)
    assert math.isclose(inertia([-1.0, 1.0, 0.1, -2.0], p)[1, 1], r["B22"], rel_tol=1e-12)


@pytest.mark.parametrize("params", drawn("ex-dyn-heavy"))
def test_heavy_sag_and_slider_gain(params):
    r = solve("ex-dyn-heavy", params)
    m, s = params["m_L"], params["sag_max_mm"] * 1e-3
    assert math.isclose(r["sag_mm"], 1e3 * m * G0 / 1e4, rel_tol=1e-12)
    k = round(10 * r["k_step"])
    assert m * G0 / 10 ** (k / 10) <= s < m * G0 / 10 ** ((k - 1) / 10)
