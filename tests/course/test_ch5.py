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


@pytest.mark.parametrize("params", drawn("ex-dyn-encoder"))
def test_encoder_steps_against_readings(params):
    """The RMS error of readings of uniformly spread positions, rounded by the package's quantiser: e^2 of a
    rounding error uniform over ± half a step has a relative standard deviation sqrt(4/5), so the RMS of n of
    them has a relative standard error sqrt(4/5) / (2 sqrt(n)); within 4 of those. The speed error is reached:
    two readings half a step off in opposite directions."""
    from scara.identification import quantise
    r = solve("ex-dyn-encoder", params)
    step = r["step_urad"] * 1e-6
    assert math.isclose(step * 2 ** params["bits"], 2 * math.pi, rel_tol=1e-12)
    x = np.random.default_rng(int(params["bits"])).uniform(-3.0, 3.0, (100_000, 4))
    rms = float(np.sqrt(np.mean((quantise(x, np.full(4, step)) - x) ** 2)))
    assert abs(rms / (r["rms_urad"] * 1e-6) - 1) < 4 * math.sqrt(0.8) / (2 * math.sqrt(x.size))
    # just below half a step (rounded down) and just above three and a half (rounded up): 3.0002 steps apart,
    # read 4 steps apart
    a, b = (np.array([[k, 0.0, 0.0, 0.0]]) * step for k in (0.4999, 3.5001))
    worst = abs((quantise(b, np.full(4, step)) - quantise(a, np.full(4, step)))[0, 0] - (b - a)[0, 0]) / 1e-3
    assert worst <= r["speed_err"] * (1 + 1e-9) and worst > 0.99 * r["speed_err"]


@pytest.mark.parametrize("params", drawn("ex-dyn-record"))
def test_record_length_gives_the_interval(params):
    """Identifying from the predicted number of whole periods gives a half-width of m3 no wider than asked, up to
    the scatter of the noise level's estimate (relative standard error about 1 / sqrt(2 N), N >= 380 samples:
    within 4 of those)."""
    from scara.identification import EXAMPLE_SEED, book_design, draw_arm, identify, measure
    r = solve("ex-dyn-record", params)
    assert math.isclose(r["duration_s"], 40.0 * (r["h40_g"] / params["target_g"]) ** 2, rel_tol=1e-12)
    exc = book_design().excitation
    est, _ = identify(measure(draw_arm(EXAMPLE_SEED), exc.reference(int(r["periods"])), seed=1))
    half_g = 1e3 * 0.5 * (est.interval[0, 1] - est.interval[0, 0])
    assert half_g <= params["target_g"] * (1 + 4 / math.sqrt(2 * 380))
    assert r["periods"] * exc.period >= r["duration_s"] > (r["periods"] - 1) * exc.period


@pytest.mark.parametrize("params", drawn("ex-dyn-weighing"))
def test_weighing_finds_the_payload(params):
    """The payload put on the arm lies within its interval (four half-widths, far beyond the 95 % level), and
    payload_from_pi misses it by the quill's own error, m_l3 - 10 kg."""
    from scara.identification import EXAMPLE_SEED, draw_arm
    r = solve("ex-dyn-weighing", params)
    assert abs(r["payload_kg"] - params["m_L"]) < 4 * r["half_g"] * 1e-3
    assert abs((r["nominal_kg"] - r["payload_kg"]) - (draw_arm(EXAMPLE_SEED).m_l3 - 10.0)) < 0.01
