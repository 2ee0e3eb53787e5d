"""The dynamic model (chapter 5) checked against an independent derivation and its structural properties.

* ``B``, ``C`` and ``g`` are derived here from scratch with sympy: positions of every mass from the product of
  DH matrices, their velocities by differentiation, the angular velocities from ``Rdot R^T``, the rotors spinning
  at ``omega_{i-1} + k_ri qdot_i z_{i-1}``; ``B`` is the Hessian of the kinetic energy in ``qd``, ``C`` the
  Christoffel matrix of that ``B``, ``g`` the gradient of the potential energy.
* The ``B`` printed in chapter 5 is transcribed as a third, literal, version.
* ``Bdot - 2C`` is skew-symmetric, with ``Bdot`` from finite differences along a motion.
* ``Y pi`` reproduces the model's torque; ``pi`` can be identified by least squares from ``Y`` and the payload
  read back from it; ``forward_dynamics`` inverts the model; the power balance ``dE/dt = qd^T (tau - F qd)`` holds.
"""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from scara import (
    NonFiniteError, ScaraError, ScaraParams, ShapeError, coriolis, dynamic_array, dynamic_parameters,
    forward_dynamics, friction, gravity, inertia, inverse_dynamics, kinetic_energy, params_from_pi,
    payload_from_pi, potential_energy, regressor, total_energy,
)
from scara import dynamics as dyn

from _largest import record

P0 = ScaraParams()
P5 = ScaraParams().with_payload(5.0)


def rel(a, b):
    """Largest entry of |a - b| relative to max(1, |b|): a relative error for big entries, absolute for small."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))))


# --------------------------------------------------------------------------------------------------
# the independent symbolic derivation
# --------------------------------------------------------------------------------------------------
def _symbolic_model():
    q = sp.symbols("q1:5", real=True)
    qd = sp.symbols("qd1:5", real=True)
    (d0, a1, a2, l1, l2, ml1, ml2, ml3, Il1, Il2, Il4, kr1, kr2, kr3, kr4, Im1, Im2, Im3, Im4, mL, g0) = sp.symbols(
        "d0 a1 a2 l1 l2 m_l1 m_l2 m_l3 I_l1 I_l2 I_l4 k_r1 k_r2 k_r3 k_r4 I_m1 I_m2 I_m3 I_m4 m_L g0", real=True)
    params = (d0, a1, a2, l1, l2, ml1, ml2, ml3, Il1, Il2, Il4, kr1, kr2, kr3, kr4, Im1, Im2, Im3, Im4, mL, g0)

    def dh(a, d, theta):  # standard DH with alpha = 0: Rot_z(theta) Trans_z(d) Trans_x(a)
        c, s = sp.cos(theta), sp.sin(theta)
        return sp.Matrix([[c, -s, 0, a * c], [s, c, 0, a * s], [0, 0, 1, d], [0, 0, 0, 1]])

    A0b = sp.Matrix([[1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, d0], [0, 0, 0, 1]])
    T = [A0b]
    for a, d, th in [(a1, 0, q[0]), (a2, 0, q[1]), (0, q[2], 0), (0, 0, q[3])]:
        T.append(sp.simplify(T[-1] * dh(a, d, th)))
    R = [Ti[:3, :3] for Ti in T]
    o = [Ti[:3, 3] for Ti in T]
    z = [Ri[:, 2] for Ri in R]  # z_{i} in the base frame

    def vel(pos):
        return pos.jacobian(q) * sp.Matrix(qd)

    def omega(Rm):
        Rdot = sum((Rm.diff(q[j]) * qd[j] for j in range(4)), sp.zeros(3, 3))
        S = sp.simplify(Rdot * Rm.T)
        return sp.Matrix([S[2, 1], S[0, 2], S[1, 0]])

    def rot_energy(w, Rm, Izz):
        I_link = sp.diag(0, 0, Izz)  # only the moment about the link's (vertical) axis is given
        return sp.Rational(1, 2) * (w.T * Rm * I_link * Rm.T * w)[0]

    # centres of mass: link i's is l_i from joint axis i along x_i, i.e. o_{i-1} + l_i x_i
    pc1 = o[0] + l1 * R[1][:, 0]
    pc2 = o[1] + l2 * R[2][:, 0]
    pq = o[3]  # quill and payload on the joint-3/4 axis
    w = [omega(Ri) for Ri in R]
    Tk = (sp.Rational(1, 2) * ml1 * (vel(pc1).T * vel(pc1))[0] + rot_energy(w[1], R[1], Il1)
          + sp.Rational(1, 2) * ml2 * (vel(pc2).T * vel(pc2))[0] + rot_energy(w[2], R[2], Il2)
          + sp.Rational(1, 2) * (ml3 + mL) * (vel(pq).T * vel(pq))[0]            # link 3 has no rotational inertia
          + rot_energy(w[4], R[4], Il4))                                         # link 4: inertia only
    # rotors: motor i on link i-1, spinning at omega_{i-1} + k_ri qdot_i z_{i-1} (massless, inertia about spin axis)
    kr = (kr1, kr2, kr3, kr4)
    Im = (Im1, Im2, Im3, Im4)
    for i in range(4):
        wm = w[i] + kr[i] * qd[i] * z[i]
        Tk += sp.Rational(1, 2) * Im[i] * (z[i].T * wm)[0] ** 2
    Bs = sp.hessian(Tk, qd).applyfunc(sp.simplify)
    # potential energy: links 1, 2 at the heights of their frames' origins (COM in the link plane), quill, payload
    U = g0 * (ml1 * pc1[2] + ml2 * pc2[2] + (ml3 + mL) * pq[2])
    gs = sp.Matrix([U.diff(qi) for qi in q])
    Cs = sp.zeros(4, 4)
    for i in range(4):
        for j in range(4):
            Cs[i, j] = sum(sp.Rational(1, 2) * (Bs[i, j].diff(q[k]) + Bs[i, k].diff(q[j]) - Bs[j, k].diff(q[i])) * qd[k]
                           for k in range(4))
    args = (q, qd, params)
    return (sp.lambdify(args, Bs, "numpy"), sp.lambdify(args, Cs, "numpy"), sp.lambdify(args, gs, "numpy"),
            sp.lambdify(args, Tk, "numpy"))


@pytest.fixture(scope="module")
def symbolic():
    return _symbolic_model()


def _pvals(p):
    return (p.d0, p.a1, p.a2, p.l1, p.l2, p.m_l1, p.m_l2, p.m_l3, p.I_l1, p.I_l2, p.I_l4, *p.k_r, *p.I_m, p.m_L, p.g0)


def chapter5_B(q, p):
    """Chapter 5's B, transcribed literally."""
    c2 = math.cos(q[1])
    kr, Im = p.k_r, p.I_m
    m3 = p.m_l3 + p.m_L
    B = np.zeros((4, 4))
    B[0, 0] = (p.I_l1 + p.m_l1 * p.l1 ** 2 + kr[0] ** 2 * Im[0] + p.I_l2 + p.m_l2 * (p.a1 ** 2 + p.l2 ** 2 + 2 * p.a1 * p.l2 * c2)
               + m3 * (p.a1 ** 2 + p.a2 ** 2 + 2 * p.a1 * p.a2 * c2) + p.I_l4 + Im[1] + Im[2] + Im[3])
    B[0, 1] = p.I_l2 + p.m_l2 * (p.l2 ** 2 + p.a1 * p.l2 * c2) + m3 * (p.a2 ** 2 + p.a1 * p.a2 * c2) + p.I_l4 + kr[1] * Im[1] + Im[2] + Im[3]
    B[1, 1] = p.I_l2 + p.m_l2 * p.l2 ** 2 + m3 * p.a2 ** 2 + p.I_l4 + kr[1] ** 2 * Im[1] + Im[2] + Im[3]
    B[0, 2] = B[1, 2] = kr[2] * Im[2]
    B[2, 2] = m3 + kr[2] ** 2 * Im[2]
    B[0, 3] = B[1, 3] = p.I_l4 + kr[3] * Im[3]
    B[3, 3] = p.I_l4 + kr[3] ** 2 * Im[3]
    return np.triu(B) + np.triu(B, 1).T


# --------------------------------------------------------------------------------------------------
# strategies
# --------------------------------------------------------------------------------------------------
angle = st.floats(-math.pi, math.pi, allow_nan=False)
stroke = st.floats(0.0, 1.0, allow_nan=False)
rate = st.floats(-3.0, 3.0, allow_nan=False)
configs = st.tuples(angle, angle, stroke, angle).map(np.array)
vectors = st.tuples(rate, rate, rate, rate).map(np.array)
payloads = st.floats(0.0, 20.0, allow_nan=False)
positive = st.floats(0.01, 5.0, allow_nan=False)


@st.composite
def robots(draw):
    """Random physical parameter sets around the robot of book/intro.md (gear ratios != 1 included)."""
    return ScaraParams(
        l1=draw(st.floats(0.05, 0.5)), l2=draw(st.floats(0.05, 0.5)), m_l1=draw(st.floats(1, 40)),
        m_l2=draw(st.floats(1, 40)), m_l3=draw(st.floats(1, 20)), I_l1=draw(positive), I_l2=draw(positive),
        I_l4=draw(positive), k_r=tuple(draw(st.floats(1.5, 100)) for _ in range(4)),
        I_m=tuple(draw(st.floats(1e-4, 0.05)) for _ in range(4)), F_m=tuple(draw(st.floats(0, 0.05)) for _ in range(4)),
        m_L=draw(payloads))


# --------------------------------------------------------------------------------------------------
# B, C, g against the symbolic derivation and chapter 5's printed B
# --------------------------------------------------------------------------------------------------
@given(configs, vectors, st.sampled_from([P0, P5]))
def test_inertia_equals_symbolic_derivation(symbolic, q, qd, p):
    Bs, Cs, gs, _ = symbolic
    B = inertia(q, p)
    err = rel(B, np.array(Bs(q, qd, _pvals(p)), float))
    record("B vs sympy", err)
    assert err < 1e-12
    err = rel(B, chapter5_B(q, p))
    record("B vs chapter 5", err)
    assert err < 1e-12


@given(configs, vectors, robots())
def test_model_equals_symbolic_derivation_random_robots(symbolic, q, qd, p):
    Bs, Cs, gs, Ts = symbolic
    vals = _pvals(p)
    assert rel(inertia(q, p), np.array(Bs(q, qd, vals), float)) < 1e-12
    errC = rel(coriolis(q, qd, p), np.array(Cs(q, qd, vals), float))
    record("C vs sympy Christoffel", errC)
    assert errC < 1e-12
    errg = rel(gravity(q, p), np.array(gs(q, qd, vals), float).ravel())
    record("g vs sympy dU/dq", errg)
    assert errg < 1e-12
    errT = abs(kinetic_energy(q, qd, p) - float(Ts(q, qd, vals))) / max(1.0, abs(kinetic_energy(q, qd, p)))
    record("T vs sympy", errT)
    assert errT < 1e-12
    assert rel(inertia(q, p), chapter5_B(q, p)) < 1e-12


@given(configs, st.sampled_from([P0, P5]))
def test_inertia_symmetric_positive_definite(q, p):
    B = inertia(q, p)
    assert np.array_equal(B, B.T)
    assert np.linalg.eigvalsh(B).min() > 0.1  # the smallest eigenvalue is ~1 kg m^2 (B44 with the rotor)


@given(st.lists(configs, min_size=1, max_size=6), st.sampled_from([P0, P5]))
def test_inertia_of_a_series_is_the_matrix_of_each_row(qs, p):
    q = np.array(qs)
    B = inertia(q, p)
    assert B.shape == (len(qs), 4, 4)
    for k, qk in enumerate(qs):
        assert np.array_equal(B[k], inertia(qk, p))


def test_inertia_of_a_series_refuses_bad_rows():
    with pytest.raises(ShapeError):
        inertia(np.zeros((3, 5)))
    q = np.zeros((3, 4))
    q[1, 2] = np.nan
    with pytest.raises(NonFiniteError):
        inertia(q)


def test_reference_values():
    """Hand-computed entries at theta2 = 0 (c2 = 1) and theta2 = pi/2 (c2 = 0), without payload."""
    B = inertia([0.0, 0.0, 0.5, 0.0])
    # B11 = 4 + 20 * 0.0625 + 0.01 + 4 + 20 (0.25 + 0.0625 + 0.25) + 10 (0.25 + 0.25 + 0.5) + 1 + 0.01 + 0.005 + 0.001
    assert B[0, 0] == pytest.approx(31.526, abs=1e-12)
    assert B[2, 2] == pytest.approx(22.5, abs=1e-12)
    assert B[3, 3] == pytest.approx(1.4, abs=1e-12)
    assert B[0, 3] == pytest.approx(1.02, abs=1e-12)
    assert B[0, 2] == pytest.approx(0.25, abs=1e-12)
    assert inertia([0.0, math.pi / 2, 0.5, 0.0])[0, 0] == pytest.approx(31.526 - 2 * 0.5 * (20 * 0.25 + 10 * 0.5), abs=1e-12)
    assert np.allclose(np.diag(friction()), [5e-5, 5e-5, 25.0, 2.0], rtol=0, atol=1e-15)
    assert gravity([0, 0, 0.3, 0], P5)[2] == pytest.approx(-15.0 * 9.81, abs=1e-12)


# --------------------------------------------------------------------------------------------------
# structure: skew symmetry, power balance
# --------------------------------------------------------------------------------------------------
@given(configs, vectors, st.sampled_from([P0, P5]))
def test_Bdot_minus_2C_is_skew(q, qd, p):
    # Bdot along the motion q(t) = q + t qd by the five-point central difference (h = 1e-3): truncation
    # ~h^4 |d^5B/dt^5| / 30 <= 1e-12 * 2b * |qd2|^5 / 30 ~ 1e-10 (b = a1 (m_l2 l2 + m3 a2) <= 7.5, |qd2| <= 3)
    # and round-off ~1e-16 |B| / h ~ 1e-11: 1e-9 is a safe bound.
    h = 1e-3
    Bdot = (8 * (inertia(q + h * qd, p) - inertia(q - h * qd, p))
            - (inertia(q + 2 * h * qd, p) - inertia(q - 2 * h * qd, p))) / (12 * h)
    N = Bdot - 2 * coriolis(q, qd, p)
    err = np.abs(N + N.T).max()
    record("Bdot - 2C skew", err)
    assert err < 1e-9
    # and x^T N x = 0 for any x (the form used in the passivity argument)
    x = np.array([1.0, -2.0, 0.5, 3.0])
    assert abs(x @ N @ x) < 1e-8


@given(configs, vectors, vectors, st.sampled_from([P0, P5]))
def test_power_balance(q, qd, tau, p):
    """Along the free motion of the model, d(T + U)/dt = qd^T tau - qd^T F qd (a consequence of N being skew).

    dE/dt = dE/dq qd + dE/dqd qdd, by central differences of the energy (h = 1e-6: error ~1e-7 for E ~ 1e3)."""
    tau = 30 * tau
    qdd = forward_dynamics(q, qd, tau, p)
    h = 1e-6
    dE = (total_energy(q + h * qd, qd + h * qdd, p) - total_energy(q - h * qd, qd - h * qdd, p)) / (2 * h)
    expected = qd @ tau - qd @ friction(p) @ qd
    err = abs(dE - expected) / max(1.0, abs(expected))
    record("power balance", err)
    assert err < 1e-6


# --------------------------------------------------------------------------------------------------
# regressor and parameter vector
# --------------------------------------------------------------------------------------------------
@given(configs, vectors, vectors, vectors, robots())
def test_regressor_reproduces_model(q, qd, qd_r, qdd_r, p):
    tau = inertia(q, p) @ qdd_r + coriolis(q, qd, p) @ qd_r + friction(p) @ qd_r + gravity(q, p)
    Y = regressor(q, qd, qd_r, qdd_r, p)
    pi = dynamic_parameters(p)
    err = rel(Y @ pi, tau)
    record("Y pi vs model", err)
    assert err < 1e-12
    assert pi[0] == pytest.approx(p.m_l3 + p.m_L, abs=1e-12)
    assert payload_from_pi(pi, p) == pytest.approx(p.m_L, abs=1e-12)


def test_regressor_depends_only_on_geometry():
    """Y must not hide any dynamic parameter: the same Y for very different masses and inertias."""
    rng = np.random.default_rng(3)
    q, qd, a, b = rng.normal(size=(4, 4))
    other = P0.replace(m_l1=3.0, m_l2=7.0, m_l3=1.0, I_l1=0.2, I_m=(0.1, 0.2, 0.3, 0.4), m_L=9.0)
    assert np.array_equal(regressor(q, qd, a, b, P0), regressor(q, qd, a, b, other))


def test_payload_is_identifiable_by_least_squares():
    """Stacking Y over random samples gives a full-rank (13-column) matrix, so the torques of a robot carrying
    an unknown payload determine pi, and pi[0] - m_l3 gives the payload back."""
    rng = np.random.default_rng(11)
    p_true = P0.with_payload(3.7)
    rows, taus = [], []
    for _ in range(40):
        q = rng.uniform(-3, 3, 4)
        qd, qdd = rng.uniform(-2, 2, (2, 4))
        rows.append(regressor(q, qd, qd, qdd, P0))
        taus.append(inverse_dynamics(q, qd, qdd, p_true))
    Y = np.vstack(rows)
    assert np.linalg.matrix_rank(Y) == dyn.N_PI
    pi_hat = np.linalg.lstsq(Y, np.concatenate(taus), rcond=None)[0]
    err = rel(pi_hat, dynamic_parameters(p_true))
    record("least-squares pi", err)
    assert err < 1e-9
    assert payload_from_pi(pi_hat) == pytest.approx(3.7, abs=1e-9)


@given(robots())
def test_pi_round_trip(p):
    base = P0.replace(l1=p.l1, l2=p.l2, m_l1=p.m_l1, m_l3=p.m_l3, k_r=p.k_r, I_m=(p.I_m[0], 0, 0, 0))
    back = params_from_pi(dynamic_parameters(p), base)
    for name in ("m_L", "m_l2", "I_l1", "I_l2", "I_l4"):
        assert getattr(back, name) == pytest.approx(getattr(p, name), rel=1e-9, abs=1e-9), name
    assert np.allclose(back.I_m, p.I_m, rtol=1e-9, atol=1e-12)
    assert np.allclose(back.F_m, p.F_m, rtol=1e-9, atol=1e-15)
    assert rel(dynamic_parameters(back), dynamic_parameters(p)) < 1e-12


def test_pi_round_trip_of_the_books_robot_and_refusals():
    back = params_from_pi(dynamic_parameters(P5))  # k_r2 = 1: I_m2 taken from the base
    assert back.m_L == pytest.approx(5.0, abs=1e-12)
    assert rel(dynamic_parameters(back), dynamic_parameters(P5)) < 1e-13
    pi = dynamic_parameters(P5)
    bad = pi.copy()
    bad[3] += 0.5  # beta12 != beta22 while k_r2 = 1
    with pytest.raises(ScaraError, match="beta22 must equal beta12"):
        params_from_pi(bad)
    bad = pi.copy()
    bad[0] = 2.0  # m3 below m_l3: a negative payload
    with pytest.raises(ScaraError, match="m_L"):
        params_from_pi(bad)
    with pytest.raises(ShapeError):
        params_from_pi(pi[:5])


# --------------------------------------------------------------------------------------------------
# forward dynamics and the solvers
# --------------------------------------------------------------------------------------------------
@given(configs, vectors, vectors, st.sampled_from([P0, P5]))
def test_forward_dynamics_inverts_the_model(q, qd, qdd, p):
    tau = inverse_dynamics(q, qd, qdd, p)
    err = rel(forward_dynamics(q, qd, tau, p), qdd)
    record("forward(inverse(qdd)) - qdd", err)
    assert err < 1e-11
    # and against numpy's general solver on the model's terms
    ref = np.linalg.solve(inertia(q, p), tau - coriolis(q, qd, p) @ qd - friction(p) @ qd - gravity(q, p))
    assert rel(forward_dynamics(q, qd, tau, p), ref) < 1e-11


def test_inverse_dynamics_batch_matches_single():
    rng = np.random.default_rng(5)
    q, qd, qdd = rng.normal(size=(3, 50, 4))
    batch = inverse_dynamics(q, qd, qdd, P5)
    single = np.array([inverse_dynamics(a, b, c, P5) for a, b, c in zip(q, qd, qdd)])
    assert np.array_equal(batch, single)
    T = kinetic_energy(q, qd, P5)
    assert T.shape == (50,) and np.allclose(T, [0.5 * b @ inertia(a, P5) @ b for a, b in zip(q, qd)], rtol=1e-14)
    assert potential_energy(q, P5).shape == (50,)


def test_solvers():
    rng = np.random.default_rng(9)
    for _ in range(200):
        M = rng.normal(size=(4, 4))
        b = rng.normal(size=4)
        x = np.empty(4)
        S = M @ M.T + 0.1 * np.eye(4)
        assert dyn.cholesky_solve4(S.copy(), b.copy(), x) == 0
        assert np.allclose(x, np.linalg.solve(S, b), rtol=1e-9, atol=1e-9)
    assert dyn.cholesky_solve4(-np.eye(4), np.ones(4), x) == 1
    # the live path: forward dynamics solves B qdd = tau - n with it
    q, qd, tau = rng.normal(size=(3, 4))
    qdd = forward_dynamics(q, qd, tau, P5)
    assert np.allclose(inertia(q, P5) @ qdd, tau - inverse_dynamics(q, qd, np.zeros(4), P5), rtol=1e-10, atol=1e-10)


def test_kernels_write_what_the_functions_return():
    rng = np.random.default_rng(1)
    q, qd, v, a = rng.normal(size=(4, 4))
    dp = dynamic_array(P5)
    out = np.empty((4, 4))
    dyn.inertia_kernel(q, dp, out)
    assert np.array_equal(out, inertia(q, P5))
    dyn.coriolis_kernel(q, qd, dp, out)
    assert np.array_equal(out, coriolis(q, qd, P5))
    cv = np.empty(4)
    dyn.coriolis_vector_kernel(q, qd, v, dp, cv)
    assert np.allclose(cv, coriolis(q, qd, P5) @ v, rtol=1e-14, atol=1e-14)
    fq = np.empty(4)
    dyn.friction_kernel(qd, dp, fq)
    assert np.allclose(fq, friction(P5) @ qd, rtol=1e-15, atol=0)
    pi = np.empty(dyn.N_PI)
    dyn.pi_kernel(dp, pi)
    assert np.array_equal(pi, dynamic_parameters(P5))
    assert len(dyn.DP_NAMES) == dyn.N_DP == len(dp) and len(dyn.PI_NAMES) == dyn.N_PI == len(dyn.PI_UNITS)
    assert dp[dyn.DP_ML] == 5.0 and dp[dyn.DP_G0] == 9.81


# --------------------------------------------------------------------------------------------------
# bad inputs
# --------------------------------------------------------------------------------------------------
def test_bad_inputs_are_refused():
    with pytest.raises(ShapeError, match="q must have shape"):
        inertia([1, 2, 3])
    with pytest.raises(NonFiniteError, match=r"qd\[1\]"):
        coriolis([0, 0, 0, 0], [0, np.nan, 0, 0])
    with pytest.raises(ShapeError):
        inverse_dynamics(np.zeros((3, 4)), np.zeros((3, 4)), np.zeros((2, 4)))
    with pytest.raises(ScaraError, match="ScaraParams"):
        gravity([0, 0, 0, 0], p={"m_L": 5})
    with pytest.raises(ScaraError, match="must be finite and >= 0"):
        P0.with_payload(-1.0)


# --------------------------------------------------------------------------------------------------
# the plain-Python path
# --------------------------------------------------------------------------------------------------
def test_plain_python_path_gives_the_same_numbers():
    code = ("import json, numpy as np, scara, scara._compile as c; from scara import *;"
            "assert not c.COMPILED; p=ScaraParams().with_payload(5.0); q=np.array([0.3,-1.1,0.4,0.2]);"
            "qd=np.array([0.5,-0.2,0.1,1.0]); a=np.array([1.0,2.0,-1.0,0.5]);"
            "print(json.dumps(np.r_[inertia(q,p).ravel(), coriolis(q,qd,p).ravel(), gravity(q,p),"
            "regressor(q,qd,qd,a,p).ravel(), forward_dynamics(q,qd,a,p), inverse_dynamics(q,qd,a,p),"
            "kinetic_energy(q,qd,p)].tolist()))")
    env = dict(os.environ, SCARA_NO_NUMBA="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    q = np.array([0.3, -1.1, 0.4, 0.2])
    qd = np.array([0.5, -0.2, 0.1, 1.0])
    a = np.array([1.0, 2.0, -1.0, 0.5])
    ref = np.r_[inertia(q, P5).ravel(), coriolis(q, qd, P5).ravel(), gravity(q, P5), regressor(q, qd, qd, a, P5).ravel(),
                forward_dynamics(q, qd, a, P5), inverse_dynamics(q, qd, a, P5), kinetic_energy(q, qd, P5)]
    err = np.abs(np.array(json.loads(out)) - ref).max()
    record("plain Python vs compiled", err)
    assert err < 1e-12  # compiled code may contract a*b+c into FMA: round-off only


# -- huge but finite inputs: a non-finite result names the input that overflowed ------------------------------
Q1 = [0.0, 1.0, 0.5, 0.0]
HUGE = [1e300, 1e300, 0.0, 0.0]


@pytest.mark.parametrize("call, what, name", [
    (lambda: inverse_dynamics(Q1, HUGE, np.zeros(4)), r"tau = B qdd \+ C qd \+ F qd \+ g", "qd"),
    (lambda: inverse_dynamics(Q1, np.zeros(4), [1e308, 0, 0, 0]), r"tau = B qdd \+ C qd \+ F qd \+ g", "qdd"),
    (lambda: forward_dynamics(Q1, HUGE, np.zeros(4)), r"qdd = B\^-1 \(tau - C qd - F qd - g\)", "qd"),
    (lambda: kinetic_energy(Q1, [1e200, 0, 0, 0]), r"kinetic energy qd\^T B qd / 2", "qd"),
    (lambda: total_energy(Q1, [1e200, 0, 0, 0]), r"kinetic energy qd\^T B qd / 2", "qd"),
    (lambda: regressor(Q1, HUGE, HUGE, np.zeros(4)), r"Y\(q, qd, qd_r, qdd_r\)", "qd"),
    (lambda: potential_energy([0, 0, 1e308, 0], P0.with_payload(1e3)), r"potential energy U\(q\)", "d3"),
])
def test_overflowing_inputs_raise_non_finite_error_naming_them(call, what, name):
    with pytest.raises(NonFiniteError, match=rf"{name} = .* gives a non-finite {what}: {name} is too large"):
        call()


def test_angles_beyond_max_angle_are_refused_by_the_dynamics():
    for call in (lambda: inertia([0.0, 1e308, 0.5, 0.0]), lambda: coriolis([0.0, 2e6, 0.5, 0.0], np.zeros(4)),
                 lambda: inverse_dynamics([[0.0, 1e7, 0.5, 0.0]], np.zeros((1, 4)), np.zeros((1, 4)))):
        with pytest.raises(ScaraError, match=r"q\[.*\] = .* rad is beyond the largest angle .* MAX_ANGLE = 1e\+06 rad"):
            call()


def test_params_from_pi_refuses_a_bad_rtol():
    with pytest.raises(ScaraError, match=r"rtol must be a number, got \{\}"):
        params_from_pi(dynamic_parameters(), rtol={})


def test_inertia_split_is_the_split_of_torque_breakdown():
    """One split of B into links, rotors and payload: its parts sum to B, and the inertial terms of
    torque_breakdown are those parts times qdd."""
    p = ScaraParams().with_payload(5.0)
    q = np.array([0.3, -1.1, 0.4, 0.2])
    qdd = np.array([1.0, 2.0, -1.0, 0.5])
    parts = dyn.inertia_split(q, p)
    assert sorted(parts) == ["links", "payload", "rotors"]
    assert np.allclose(parts["links"] + parts["rotors"] + parts["payload"], inertia(q, p), rtol=1e-15, atol=0)
    assert np.allclose(parts["payload"], inertia(q, p) - inertia(q, p.replace(m_L=0.0)), rtol=0, atol=0)
    br = dyn.torque_breakdown(q, np.zeros(4), qdd, p)
    assert np.allclose(br["links"], parts["links"] @ qdd, rtol=1e-14, atol=1e-12)
    assert np.allclose(br["rotors"], parts["rotors"] @ qdd, rtol=1e-14, atol=1e-12)
    assert np.array_equal(br["gravity"], gravity(q, p.replace(m_L=0.0)))


def test_gravity_and_potential_energy_are_written_once():
    """g(q) of the bias term, of torque_breakdown and of gravity() are the gravity kernel's; U(q) of a series
    is the kernel's at every sample."""
    p = ScaraParams().with_payload(2.0)
    q = np.array([[0.3, -1.1, 0.4, 0.2], [1.0, 0.5, 0.9, -0.3]])
    zero = np.zeros_like(q)
    at_rest = inverse_dynamics(q, zero, zero, p.replace(F_m=(0.0,) * 4))
    assert np.array_equal(at_rest, np.array([gravity(r, p) for r in q]))
    u = potential_energy(q, p)
    assert u.shape == (2,) and all(u[k] == dyn.potential_energy_kernel(q[k], dynamic_array(p)) for k in range(2))
    assert potential_energy(q[0], p) == u[0]


def test_a_zero_gear_ratio_never_reaches_params_from_pi():
    """Recovering I_m = beta / k_r needs every k_r > 0: the parameters refuse a zero where it is given."""
    with pytest.raises(ScaraError, match=r"k_r = \[1\.0, 1\.0, 0\.0, 20\.0\] must be > 0 for every joint"):
        params_from_pi(dynamic_parameters(ScaraParams()), ScaraParams(k_r=(1.0, 1.0, 0.0, 20.0)))
