"""Chapter 2's exercise answers (scara.course.answers.ch2) against independent computations: sweeps of the elbow
with the package's manipulability, the force for unit torque in every direction, closed forms of the semi-axes;
for a few drawn parameter sets."""
import math

import numpy as np
import pytest

from scara import ScaraParams, jacobian, manipulability, pose
from scara.course.exercises import draw, exercise, solve
from scara.errors import ScaraError

P = ScaraParams()
STUDENTS = [f"student{i}" for i in range(6)]


def drawn(label):
    ex = exercise(label)
    return [draw(ex, b"tests-ch2", s) for s in STUDENTS]


def sweep(arm, n=36001):
    """w and the distance r from the axis over a sweep of the elbow from 0 to 180°."""
    t = np.linspace(0.0, math.pi, n)
    qs = np.column_stack([np.zeros(n), t, np.full(n, 0.5), np.zeros(n)])
    return np.asarray(manipulability(qs, arm)), np.hypot(*pose(qs, arm)[:, :2].T)




def test_best_by_sweep():
    res = solve("ex-manip-best")
    w, r = sweep(P)
    assert math.isclose(res["w_max"], w.max(), rel_tol=1e-6)
    assert math.isclose(res["r_best"], r[np.argmax(w)], abs_tol=1e-4)


@pytest.mark.parametrize("params,res", drawn("ex-manip-share"))
def test_share_closed_form(params, res):
    k = params["pct"] / 100
    assert math.isclose(res["share"], math.sqrt(1 - k**2), rel_tol=1e-12)
    assert abs(res["share_grid"] - res["share"]) < 0.01


@pytest.mark.parametrize("params,res", drawn("ex-manip-push"))
def test_push_is_the_largest_force_for_unit_torque(params, res):
    q = np.array([0.0, math.radians(params["t2"]), 0.5, 0.0])
    H = jacobian(q, P)[:2, :2]
    angles = np.radians(np.linspace(-90, 90, 180001))
    d = np.stack([np.cos(angles), np.sin(angles)])
    force = 1.0 / np.linalg.norm(H.T @ d, axis=0)  # |gamma| along d that takes a torque of unit norm
    assert math.isclose(res["push"], force.max(), rel_tol=1e-6)
    assert abs(res["angle"] - math.degrees(angles[np.argmax(force)])) < 0.01


@pytest.mark.parametrize("t1", exercise("ex-manip-turn").param("t1").values())
def test_turn_is_rigid(t1):
    res = solve("ex-manip-turn", {"t1": t1})
    s2 = math.sin(math.radians(45))
    assert math.isclose(res["w"], P.a1 * P.a2 * s2, rel_tol=1e-12)
    assert math.isclose(res["s1"] * res["s2"], res["w"], rel_tol=1e-12)
    assert abs((res["axis_b"] - (res["axis_a"] - t1) + 90) % 180 - 90) < 1e-9


@pytest.mark.parametrize("params,res", drawn("ex-manip-unequal"))
def test_unequal_by_sweep(params, res):
    arm = P.replace(a1=params["a1"], a2=params["a2"])
    w, r = sweep(arm)
    assert math.isclose(res["w_max"], w.max(), rel_tol=1e-6)
    assert math.isclose(res["r_best"], r[np.argmax(w)], abs_tol=1e-4)
    assert math.isclose(res["r_min"], r.min(), abs_tol=1e-9)


@pytest.mark.parametrize("t2", exercise("ex-manip-stretched").param("t2").values())
def test_stretched_semi_axes_closed_form(t2):
    res = solve("ex-manip-stretched", {"t2": t2})
    t = math.radians(t2)
    w = P.a1 * P.a2 * math.sin(t)
    S = P.a1**2 + 2 * P.a2**2 + 2 * P.a1 * P.a2 * math.cos(t)
    assert math.isclose(res["s1"], math.sqrt((S + math.sqrt(S**2 - 4 * w**2)) / 2), rel_tol=1e-9)
    assert math.isclose(res["s2"], math.sqrt((S - math.sqrt(S**2 - 4 * w**2)) / 2), rel_tol=1e-6)
    assert math.isclose(res["f2"] * res["s2"], 1.0, rel_tol=1e-12)


def test_meaningless_sets_are_refused():
    with pytest.raises(ScaraError):
        solve("ex-manip-push", {"t2": 120.0})  # the strongest push along y_b: ±90° cannot be marked
    with pytest.raises(ScaraError):
        solve("ex-manip-unequal", {"a1": 0.5, "a2": 0.5})
