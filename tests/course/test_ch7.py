"""Independent checks of chapter 7's exercise answers (scara.course.answers.ch7) for a few drawn parameter sets:
the series springs, the bias, the force loop's time constant and Routh bound written out here, the clearance; and
the solver's runs against those closed forms."""
import math

import numpy as np
import pytest

from scara.course.exercises import draw_params, exercise, solve

STUDENTS = [f"s{i}" for i in range(3)]
K_E = 2e4        # the book's surface (N/m)
D_E = 50.0       # its damping (N s/m)


def drawn(label):
    return [draw_params(exercise(label), b"test-ch7", s) for s in STUDENTS]


@pytest.mark.parametrize("params", drawn("ex-int-series"))
def test_series_springs(params):
    r = solve("ex-int-series", params)
    kp, depth = params["K_P"], params["depth_mm"]
    force = depth * 1e-3 / (1 / kp + 1 / K_E)                    # two springs in series
    assert math.isclose(r["force_N"], force, rel_tol=1e-12)
    assert math.isclose(r["penetration_mm"], 1e3 * force / K_E, rel_tol=1e-9)
    assert abs(r["sim_N"] - force) < 1e-4                       # the run comes to rest there


@pytest.mark.parametrize("params", drawn("ex-int-bias"))
def test_bias_adds_to_the_force(params):
    r = solve("ex-int-bias", params)
    force = params["f_d"] + params["bias"]
    assert math.isclose(r["force_N"], force, rel_tol=1e-12)
    assert math.isclose(r["penetration_mm"], 1e3 * force / K_E, rel_tol=1e-9)
    assert abs(r["sim_N"] - force) < 1e-6 and abs(r["measured_N"] - params["f_d"]) < 1e-6


@pytest.mark.parametrize("params", drawn("ex-int-force-loop"))
def test_force_loop_time_constant_and_bounds(params):
    r = solve("ex-int-force-loop", params)
    ki, kp, kd, kf = params["K_I"], 2500.0, 70.0, 2e-5
    assert math.isclose(r["tau_ms"], 1e3 * (1 + kf * K_E) / (ki * K_E), rel_tol=1e-12)
    a2 = kd + kp * kf * D_E

    def unstable(k_i):   # a root of the cubic in the right half-plane
        return np.roots([1.0, a2, kp * (1 + kf * K_E + k_i * D_E), kp * k_i * K_E]).real.max() > 0

    assert not unstable(0.999 * r["routh"]) and unstable(1.001 * r["routh"])
    assert r["sampled"] < r["routh"] and r["radius"] < 1.0 and ki < r["sampled"]
    # the slowest root of the cubic is slower than the first-order estimate (the inner loop is not much faster)
    assert r["slowest_ms"] > r["tau_ms"]


@pytest.mark.parametrize("params", drawn("ex-int-peg"))
def test_peg_drops_in_within_the_clearance(params):
    r = solve("ex-int-peg", params)
    assert r["offset_mm"] == params["clearance_mm"]
    assert r["within_landed"] == 0.0 and r["beyond_landed"] == 1.0
    assert r["within_entered"] < r["beyond_entered"] and r["beyond_depth_mm"] > 30.0
