"""Kinematics (chapter 1) checked against independent computations: the product of DH matrices built
here from the DH convention, finite differences, round trips over random configurations."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from scara import (
    NonFiniteError, ScaraError, ScaraParams, ShapeError, UnreachableError, check_reachable, dh_table, fkine,
    ikine, is_reachable, jacobian, jacobian_dot, link_frames, pose,
)
from scara.kinematics import (
    elbow_cosine, geometry, planar_det, planar_jacobian, planar_jacobian_at, planar_jacobian_dot, planar_position,
    planar_trig,
)

from _largest import record

P = ScaraParams()
angle = st.floats(-math.pi, math.pi, allow_nan=False)
stroke = st.floats(0.0, 1.0, allow_nan=False)
configs = st.tuples(angle, angle, stroke, angle).map(np.array)
rates = st.tuples(*[st.floats(-3, 3, allow_nan=False)] * 4).map(np.array)


def dh(a, alpha, d, theta):
    """Standard DH transform Rot_z(theta) Trans_z(d) Trans_x(a) Rot_x(alpha), written out independently."""
    def rotz(t):
        return np.array([[math.cos(t), -math.sin(t), 0, 0], [math.sin(t), math.cos(t), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])

    def rotx(t):
        return np.array([[1, 0, 0, 0], [0, math.cos(t), -math.sin(t), 0], [0, math.sin(t), math.cos(t), 0], [0, 0, 0, 1]])

    def trans(x, y, z):
        T = np.eye(4)
        T[:3, 3] = [x, y, z]
        return T

    return rotz(theta) @ trans(0, 0, d) @ trans(a, 0, 0) @ rotx(alpha)


def dh_product(q, p=P):
    A0b = np.diag([1.0, -1.0, -1.0, 1.0])
    A0b[2, 3] = p.d0
    T = A0b
    for a, alpha, d, theta in [(p.a1, 0, 0, q[0]), (p.a2, 0, 0, q[1]), (0, 0, q[2], 0), (0, 0, 0, q[3])]:
        T = T @ dh(a, alpha, d, theta)
    return T



@given(configs)
def test_fkine_equals_dh_product(q):
    T = fkine(q)
    err = np.abs(T - dh_product(q)).max()
    record("fk", err)
    assert err < 1e-14
    # the frames used for drawing end at the same pose
    assert np.abs(link_frames(q)[-1] - T).max() < 1e-14
    # a proper rotation: right-handed frames
    R = T[:3, :3]
    assert np.allclose(R @ R.T, np.eye(3), atol=1e-14) and math.isclose(np.linalg.det(R), 1.0, abs_tol=1e-14)


@given(configs)
def test_pose_matches_fkine(q):
    T = fkine(q)
    x = pose(q)
    assert np.allclose(x[:3], T[:3, 3], atol=1e-15)
    # phi is the rotation about the downward axis: R = Rot_x(pi) Rot_z(phi) as (1.4) writes it
    c, s = math.cos(x[3]), math.sin(x[3])
    assert np.allclose(T[:3, :3], [[c, -s, 0], [-s, -c, 0], [0, 0, -1]], atol=1e-15)


def test_pose_batch_equals_single():
    rng = np.random.default_rng(1)
    qs = rng.uniform([-3, -3, 0, -3], [3, 3, 1, 3], size=(50, 4))
    assert np.allclose(pose(qs), np.array([pose(q) for q in qs]), atol=1e-15)


@given(configs)
def test_jacobian_equals_central_differences(q):
    h = 1e-6
    Jfd = np.column_stack([(pose(q + h * e) - pose(q - h * e)) / (2 * h) for e in np.eye(4)])
    err = np.abs(jacobian(q) - Jfd).max()
    record("jacobian", err)
    assert err < 1e-9  # central difference truncation ~ h^2 |x'''| / 6 ~ 1e-13, rounding ~ eps/h ~ 1e-10


@given(configs, rates)
def test_jacobian_dot_equals_derivative_along_motion(q, qd):
    h = 1e-6
    Jdot_fd = (jacobian(q + h * qd) - jacobian(q - h * qd)) / (2 * h)
    err = np.abs(jacobian_dot(q, qd) - Jdot_fd).max()
    record("jacobian_dot", err)
    assert err < 1e-8


def test_determinant_of_jacobian():
    rng = np.random.default_rng(2)
    for q in rng.uniform([-3, -3, 0, -3], [3, 3, 1, 3], size=(200, 4)):
        assert math.isclose(np.linalg.det(jacobian(q)), P.a1 * P.a2 * math.sin(q[1]), abs_tol=1e-14)



@given(configs, rates)
def test_planar_building_blocks_are_the_array_kernels(q, qd):
    """The scalar building blocks give exactly the entries of ``pose``, ``jacobian`` and ``jacobian_dot``
    (the array kernels are made of them), ``det J_A`` (1.7) and the elbow cosine of (1.9)."""
    sc = planar_trig(q[0], q[1])
    np.testing.assert_array_equal(planar_position(sc, P.a1, P.a2), pose(q, P)[:2])
    J = planar_jacobian(sc, P.a1, P.a2)
    np.testing.assert_array_equal(J, jacobian(q, P)[:2, :2].ravel())
    np.testing.assert_array_equal(planar_jacobian_at(*planar_position(sc, P.a1, P.a2), sc[2], sc[3], P.a2), J)
    Jd = planar_jacobian_dot(sc, P.a1, P.a2, qd[0], qd[0] + qd[1])
    np.testing.assert_array_equal(Jd, jacobian_dot(q, qd, P)[:2, :2].ravel())
    assert math.isclose(-planar_det(J), np.linalg.det(jacobian(q, P)), abs_tol=1e-14)
    assert math.isclose(elbow_cosine(*pose(q, P)[:2], P.a1, P.a2), math.cos(q[1]), abs_tol=1e-12)
    assert geometry(P) == (P.a1, P.a2, P.d0) and geometry(P).d0 == P.d0

@given(configs.filter(lambda q: abs(math.sin(q[1])) > 1e-6), st.sampled_from([1, -1]))
def test_ikine_round_trip_both_elbows(q, elbow):
    # the elbow that matches the sign of sin(theta2) gives back q itself
    el = 1 if math.sin(q[1]) > 0 else -1
    back = ikine(pose(q), elbow=el)
    dq = back - q
    dq[0] = (dq[0] + math.pi) % (2 * math.pi) - math.pi  # theta1 comes back in (-pi, pi]
    dq[3] = pose(back)[3] - pose(q)[3]
    assert np.abs(dq).max() < 1e-8
    # and either elbow reaches the same pose exactly
    other = ikine(pose(q), elbow=elbow)
    assert np.abs(pose(other) - pose(q)).max() < 1e-12
    assert np.sign(math.sin(other[1])) in (elbow, 0)


def test_ikine_batch_and_singular_boundary():
    x = np.array([[1.0, 0.0, 0.5, 0.2], [0.3, -0.4, 0.2, 0.0]])
    qs = ikine(x, elbow=-1)
    assert qs.shape == (2, 4)
    assert np.abs(pose(qs) - x).max() < 1e-12
    assert math.isclose(qs[0, 1], 0.0, abs_tol=1e-12)  # stretched: theta2 = 0 on the outer circle


def test_dh_table():
    t = dh_table([0.1, 0.2, 0.3, 0.4])
    assert np.allclose(t, [[0.5, 0, 0, 0.1], [0.5, 0, 0, 0.2], [0, 0, 0.3, 0], [0, 0, 0, 0.4]])


# --- errors --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("bad", [[0.0, 0.0, 0.5], np.zeros((2, 3)), np.zeros((2, 4, 4)), "abc"])
def test_wrong_shapes_raise(bad):
    with pytest.raises(ShapeError, match=r"q must have shape \(4,\) or \(N, 4\), got|array of numbers"):
        pose(bad)
    with pytest.raises(ShapeError):
        jacobian(bad)
    with pytest.raises(ShapeError):
        ikine(bad)


def test_single_configuration_functions_refuse_a_batch():
    with pytest.raises(ShapeError, match=r"q must have shape \(4,\), got \(4, 4\)"):
        jacobian(np.zeros((4, 4)))
    with pytest.raises(ShapeError, match=r"qd must have shape"):
        jacobian_dot(np.zeros(4), np.zeros(3))


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf])
def test_non_finite_raises_and_names_the_entry(value):
    q = [0.1, value, 0.3, 0.0]
    for fn in (pose, fkine, jacobian):
        with pytest.raises(NonFiniteError, match=r"q\[1\] = .* is not finite"):
            fn(q)
    with pytest.raises(NonFiniteError, match=r"qd\[1\]"):
        jacobian_dot([0, 0, 0, 0], q[:1] + [value, 0, 0])
    with pytest.raises(NonFiniteError, match=r"x\[1\]"):
        ikine(q)


def test_unreachable_outside_annulus_names_point_and_limit():
    with pytest.raises(UnreachableError, match=r"r = 1\.1 m is outside the annulus .*a1 \+ a2 = 1 m"):
        ikine([1.1, 0.0, 0.5, 0.0])
    long_inner = ScaraParams(a1=0.6, a2=0.4)
    with pytest.raises(UnreachableError, match=r"r = 0\.1 m .*\|a1 - a2\| = 0\.2 m"):
        ikine([0.1, 0.0, 0.5, 0.0], p=long_inner)


@pytest.mark.parametrize("pz, d3", [(1.2, "-0.2"), (-0.1, "1.1")])
def test_unreachable_outside_stroke(pz, d3):
    with pytest.raises(UnreachableError, match=rf"d3 = d0 - p_z = {d3} m, outside the stroke d3_min = 0 m <= d3 <= d3_max = 1 m"):
        ikine([0.5, 0.2, pz, 0.0])
    with pytest.raises(UnreachableError, match="stroke"):
        check_reachable([0.5, 0.2, pz])


def test_unreachable_in_a_batch_names_the_sample():
    with pytest.raises(UnreachableError, match=r"sample 1: point"):
        ikine([[0.5, 0.2, 0.5, 0.0], [2.0, 0.0, 0.5, 0.0]])


def test_is_reachable_mask():
    pts = np.array([[0.5, 0.2, 0.5], [1.5, 0, 0.5], [0.5, 0.2, 1.5], [0.0, 0.0, 0.0]])
    assert is_reachable(pts).tolist() == [True, False, False, True]


@pytest.mark.parametrize("elbow", [0, 2, "up", True, None, 1.5])
def test_unknown_elbow_raises(elbow):
    with pytest.raises(ScaraError, match=r"elbow = .* is not allowed: use \+1 .* or -1"):
        ikine([0.5, 0.2, 0.5, 0.0], elbow=elbow)


def test_plain_python_path_gives_the_same_numbers():
    """The kernels run as plain Python where numba is missing (SCARA_NO_NUMBA=1) with the same results."""
    code = ("import numpy as np, scara, scara._compile as c; q=np.array([0.3,-1.1,0.4,0.2]);"
            "assert not c.COMPILED; print(repr(np.r_[scara.pose(q), scara.jacobian(q).ravel(), scara.ikine(scara.pose(q), elbow=-1)].tolist()))")
    env = dict(os.environ, SCARA_NO_NUMBA="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    q = np.array([0.3, -1.1, 0.4, 0.2])
    ref = np.r_[pose(q), jacobian(q).ravel(), ikine(pose(q), elbow=-1)]
    assert np.array_equal(np.array(eval(out)), ref)


# -- the stroke in ScaraParams, huge angles and overflowing results --------------------------------------------
def test_ikine_and_reachability_use_the_stroke_of_the_params():
    short = ScaraParams(d3_min=0.2, d3_max=0.6)
    x = [0.5, 0.2, 0.9, 0.0]  # d3 = 0.1 m: inside 0..1 m, above a stroke starting at 0.2 m
    assert ikine(x)[2] == pytest.approx(0.1)
    with pytest.raises(UnreachableError, match=r"d3 = d0 - p_z = 0\.1 m, outside the stroke d3_min = 0\.2 m <= d3 <= "
                                               r"d3_max = 0\.6 m"):
        ikine(x, short)
    with pytest.raises(UnreachableError, match=r"d3_min = 0\.2 m <= d3 <= d3_max = 0\.6 m"):
        check_reachable(x, short)
    assert is_reachable([[0.5, 0.2, 0.9], [0.5, 0.2, 0.5]], short).tolist() == [False, True]


def test_angles_beyond_max_angle_are_refused():
    with pytest.raises(ScaraError, match=r"q\[0\] = 1e\+308 rad .* \|theta\| <= MAX_ANGLE = 1e\+06 rad"):
        pose([1e308, 1e308, 0.5, 1e308])
    with pytest.raises(ScaraError, match=r"x\[3\] = 1e\+07 rad .* MAX_ANGLE = 1e\+06 rad"):
        ikine([0.5, 0.2, 0.5, 1e7])
    with pytest.raises(ScaraError, match=r"q\[1\] = -2e\+06 rad .* MAX_ANGLE"):
        jacobian([0.0, -2e6, 0.5, 0.0])


def test_jacobian_dot_with_overflowing_speeds_names_qd():
    with pytest.raises(NonFiniteError, match=r"qd = \[1\.e\+308 1\.e\+308 0\.e\+000 0\.e\+000\] gives a non-finite "
                                             r"Jdot_A\(q, qd\): qd is too large \(an entry of magnitude 1e\+308\)"):
        jacobian_dot([0.0, 1.0, 0.5, 0.0], [1e308, 1e308, 0.0, 0.0])


def test_wrong_types_raise_scara_errors():
    with pytest.raises(ShapeError, match=r"q must be an array of numbers, got \[True, False, True, True\]"):
        pose([True, False, True, True])
    with pytest.raises(ScaraError, match=r"elbow = array\(\[1\]\) is not allowed: use \+1"):
        ikine([0.5, 0.2, 0.5, 0.0], elbow=np.array([1]))
    with pytest.raises(ScaraError, match=r"points must be an array of numbers, got 'abc'"):
        is_reachable("abc")


def test_base_transform_is_frame_0_at_height_d0_pointing_down():
    from scara.kinematics import base_transform

    A = base_transform(P.replace(d0=1.2))
    assert np.array_equal(A, np.array([[1.0, 0, 0, 0], [0, -1.0, 0, 0], [0, 0, -1.0, 1.2], [0, 0, 0, 1.0]]))
    assert np.array_equal(link_frames(np.zeros(4))[0], base_transform())


@pytest.mark.parametrize("r_over_rim", [-1e-9, -1e-13, 0.0, 1e-13, 4e-13, 6e-13, 1e-12, 1e-9])
@pytest.mark.parametrize("rim", ["outer", "inner"])
def test_is_reachable_and_ikine_apply_one_rule_at_the_rim(r_over_rim, rim):
    """At the rim of the annulus a point is reachable exactly when ikine solves it (one tolerance)."""
    p = P.replace(a2=0.3) if rim == "inner" else P
    r = p.r_max + r_over_rim if rim == "outer" else p.r_min - r_over_rim
    x = np.array([r * math.cos(0.4), r * math.sin(0.4), 0.5, 0.0])
    try:
        ikine(x, p)
        solved = True
    except UnreachableError:
        solved = False
    assert bool(is_reachable(x, p)) == solved
    try:
        check_reachable(x, p)
        checked = True
    except UnreachableError:
        checked = False
    assert checked == solved


def test_is_reachable_batches_and_refuses_nan():
    pts = np.array([[0.5, 0.2, 0.5], [np.nan, 0.2, 0.5], [2.0, 0.0, 0.5], [0.5, 0.2, np.inf]])
    assert is_reachable(pts).tolist() == [True, False, False, False]
    assert is_reachable(pts[0]).shape == ()


def test_tool_motion_kernel_is_the_direct_kinematics_and_its_derivatives():
    from scara.kinematics import tool_motion_kernel

    rng = np.random.default_rng(3)
    q, qd, qdd = (rng.uniform(-1, 1, (5, 4)) for _ in range(3))
    q[:, 2] = 0.5
    out = np.empty((5, 12))
    tool_motion_kernel(q, qd, qdd, P.a1, P.a2, P.d0, out)
    for k in range(5):
        assert np.allclose(out[k, :4], pose(q[k]), rtol=0, atol=1e-15)
        assert np.allclose(out[k, 4:8], jacobian(q[k]) @ qd[k], rtol=0, atol=1e-15)
        assert np.allclose(out[k, 8:12], jacobian(q[k]) @ qdd[k] + jacobian_dot(q[k], qd[k]) @ qd[k], rtol=0,
                           atol=1e-15)


def test_check_regular_takes_a_series():
    from scara import UnstableError
    from scara.kinematics import check_regular

    q = np.array([[0.0, 1.0, 0.5, 0.0], [0.0, 0.0, 0.5, 0.0]])
    with pytest.raises(UnstableError, match=r"the path at sample 1: q = \[0\.0, 0\.0, 0\.5, 0\.0\] is singular"):
        check_regular(q, what="the path")
    assert check_regular(q[:1]).shape == (1, 4)
