"""Independent checks of chapter 4's exercise answers (scara.course.answers.ch4) for a few drawn parameter sets:
closed forms of the discrete loops, the reference's own numbers, monotonic trends of the damping table."""
import math

import numpy as np
import pytest

from scara import ikine, jacobian, reference_trajectory
from scara.course.exercises import draw_params, exercise, solve

STUDENTS = [f"s{i}" for i in range(4)]


def drawn(label):
    return [draw_params(exercise(label), b"test-ch4", s) for s in STUDENTS]


@pytest.fixture(scope="module")
def traj():
    return reference_trajectory()


@pytest.mark.parametrize("params", drawn("ex-clik-deadbeat"))
def test_deadbeat_gain_is_one_over_T(params):
    r = solve("ex-clik-deadbeat", params)
    T = params["T_ms"] * 1e-3
    # the Euler factor 1 - T K vanishes at the deadbeat gain and reaches -1 at the limit
    assert abs(1 - T * r["K_deadbeat"]) < 1e-12 and abs(1 - T * r["K_limit"] + 1) < 1e-12
    assert r["ratio"] < 1e-3 and r["ringing_flips"]


def test_fragile_limit_from_the_largest_singular_value(traj):
    r = solve("ex-clik-fragile")
    # kappa T sigma_max^2 = 2, with sigma_max from an SVD of the Jacobian at the worst sample
    k = int(round(r["t_worst"] / traj.dt))
    sigma = np.linalg.svd(jacobian(ikine(traj.x[k], elbow=-1)), compute_uv=False).max()
    assert math.isclose(r["kappa_max"] * traj.dt * sigma**2, 2.0, rel_tol=1e-9)
    # no configuration of the reference (every 50th sample) has a larger singular value
    coarse = max(np.linalg.svd(jacobian(ikine(x, elbow=-1)), compute_uv=False).max() for x in traj.x[::50])
    assert coarse <= sigma * (1 + 1e-12)
    assert r["k_below"] < r["kappa_max"] < r["k_above"]
    assert math.isclose(math.log10(r["k_above"]) - math.log10(r["k_below"]), 0.01, rel_tol=1e-6)


def test_relaxing_z_leaves_the_quill_still(traj):
    r = solve("ex-clik-relax")
    assert math.isclose(r["w_z"], r["w_inv"], rel_tol=1e-9) and r["w_y"] > r["w_inv"]
    assert math.isclose(r["drift_z"], np.ptp(traj.x[:, 2]), rel_tol=1e-9)


@pytest.mark.parametrize("params", drawn("ex-clik-damping"))
def test_damping_trades_rate_for_accuracy(params):
    r = solve("ex-clik-damping", params)
    rates = [r[f"rate_{k}"] for k in (10, 20, 50, 100)]
    away = [r[f"away_{k}"] for k in (10, 20, 50, 100)]
    assert rates[-1] < rates[0] and all(np.diff(away) > 0)
    # far from the axis the damped step stays accurate: micrometres against the millimetres near it
    assert all(a * 1e-3 < r[f"err_{k}"] for a, k in zip(away, (10, 20, 50, 100)))


@pytest.mark.parametrize("params", drawn("ex-clik-lag"))
def test_lag_closed_form(params):
    r = solve("ex-clik-lag", params)
    assert math.isclose(r["lag_um"], 1e-3 * params["A"] / params["K"] * 1e6, rel_tol=1e-4)


def test_second_order_limit_and_lag(traj):
    r = solve("ex-clik-second-limit")
    # the double root 1 - K T of eq-clik-second-poly leaves the unit circle at K = 2 / T
    assert abs(1 - r["k_limit"] * traj.dt) == pytest.approx(1.0)
    A = np.abs(np.diff(traj.xd[:, 2])).max() / traj.dt       # the largest vertical acceleration, by differences
    assert math.isclose(r["pred_400_nm"], traj.dt * A / 400 * 1e9, rel_tol=1e-3)
    assert abs(r["ez_400_nm"] / r["pred_400_nm"] - 1) < 0.02
    assert r["ep_ok_nm"] > 5 * r["ep_400_nm"]
