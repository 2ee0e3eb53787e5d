"""Chapter 1's exercise answers (scara.course.answers.ch1) against independent computations: the DH product written
out here, finite differences of the pose, the law of cosines, a brute-force reach; for a few drawn parameter sets."""
import math

import numpy as np
import pytest

from scara import ScaraParams, pose
from scara.course.exercises import draw, exercise, solve
from scara.errors import ScaraError

P = ScaraParams()
STUDENTS = [f"student{i}" for i in range(6)]


def drawn(label):
    ex = exercise(label)
    return [draw(ex, b"tests-ch1", s) for s in STUDENTS]


def dh(a, d, theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0, a * c], [s, c, 0, a * s], [0, 0, 1, d], [0, 0, 0, 1.0]])




@pytest.mark.parametrize("params,res", drawn("ex-kin-direct"))
def test_direct_is_the_dh_product(params, res):
    t1, t2, t4 = (math.radians(params[k]) for k in ("t1", "t2", "t4"))
    base = np.array([[1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, P.d0], [0, 0, 0, 1.0]])
    T = base @ dh(P.a1, 0, t1) @ dh(P.a2, 0, t2) @ dh(0, params["d3"], 0) @ dh(0, 0, t4)
    assert np.allclose([res["px"], res["py"], res["pz"]], T[:3, 3], atol=1e-12)
    phi = math.degrees(math.atan2(-T[1, 0], T[0, 0]))
    assert abs((res["phi"] - phi + 180) % 360 - 180) < 1e-9


@pytest.mark.parametrize("params,res", drawn("ex-kin-elbows"))
def test_elbows_reach_the_target(params, res):
    target = np.array([params["px"], params["py"], params["pz"], math.radians(params["phi"])])
    r2 = params["px"] ** 2 + params["py"] ** 2
    assert math.isclose(res["t2_up"], math.degrees(math.acos((r2 - P.a1**2 - P.a2**2) / (2 * P.a1 * P.a2))),
                        abs_tol=1e-9)
    for t1, t2 in ((res["t1_up"], res["t2_up"]), (res["t1_down"], -res["t2_up"])):
        q = np.array([math.radians(t1), math.radians(t2), res["d3"], 0.0])
        q[3] = target[3] - q[0] - q[1]
        assert np.allclose(pose(q, P), target, atol=1e-12)


@pytest.mark.parametrize("params,res", drawn("ex-kin-straight"))
def test_straight_by_finite_differences(params, res):
    q = np.array([0.0, math.radians(params["t2"]), 0.5, 0.0])
    qd = np.array([res["w1"], res["w2"], 0.0, res["w4"]])
    h = 1e-6
    xd = (pose(q + h * qd, P) - pose(q - h * qd, P)) / (2 * h)
    assert np.allclose(xd, [params["v"], 0, 0, 0], atol=1e-8)


@pytest.mark.parametrize("params,res", drawn("ex-kin-singular"))
def test_singular_null_motion(params, res):
    a1, a2 = params["a1"], params["a2"]
    assert math.isclose(res["null2"], -(a1 + a2) / a2, rel_tol=1e-12)
    arm = P.replace(a1=a1, a2=a2)
    q = np.array([0.7, 0.0, 0.5, 0.0])
    h = 1e-5
    dq = h * np.array([1.0, res["null2"], 0.0, 0.0])
    # first order still: the position moves by O(h^2) only, radially
    assert np.linalg.norm(pose(q + dq, arm)[:2] - pose(q, arm)[:2]) < 10 * h**2


@pytest.mark.parametrize("params,res", drawn("ex-kin-unequal"))
def test_unequal_by_brute_force(params, res):
    a1, a2 = params["a1"], params["a2"]
    r = np.sqrt(a1**2 + a2**2 + 2 * a1 * a2 * np.cos(np.linspace(0, np.pi, 200001)))  # every reach of the arm
    assert math.isclose(res["rmin"], r.min(), abs_tol=1e-9)
    assert res["reachable"] == float(r.min() <= params["px"] <= r.max())


def test_unequal_draws_both_answers():
    outcomes = {draw(exercise("ex-kin-unequal"), b"tests-ch1", f"s{i}")[1]["reachable"] for i in range(30)}
    assert outcomes == {0.0, 1.0}


def test_predict_by_finite_differences():
    res = solve("ex-kin-predict")
    h = 1e-6
    for t2, expected in ((60, res["det_start"]), (-60, res["det_mirror"]), (0, res["det_zero"])):
        q = np.array([0.0, math.radians(t2), 0.5, 0.0])
        J = np.column_stack([(pose(q + h * e, P) - pose(q - h * e, P)) / (2 * h) for e in np.eye(4)])
        assert math.isclose(np.linalg.det(J), expected, abs_tol=1e-8)
    assert math.isclose(res["det_start"], P.a1 * P.a2 * math.sin(math.radians(60)), rel_tol=1e-12)


@pytest.mark.parametrize("px", exercise("ex-kin-edge").param("px").values())
def test_edge_elbow_reaches_the_distance(px):
    res = solve("ex-kin-edge", {"px": px})
    t2 = math.radians(res["t2"])
    assert math.isclose(math.sqrt(P.a1**2 + P.a2**2 + 2 * P.a1 * P.a2 * math.cos(t2)), px, rel_tol=1e-12)
    assert res["t2_rim"] < 1e-5


def test_meaningless_sets_are_refused():
    with pytest.raises(ScaraError):
        solve("ex-kin-elbows", {"px": 0.7, "py": -0.7})  # 0.99 m from the axis: the elbows nearly merge
    with pytest.raises(ScaraError):
        solve("ex-kin-unequal", {"a1": 0.6, "a2": 0.4, "px": 0.2})  # on the inner rim
