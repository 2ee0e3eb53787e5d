"""Dynamic model of the SCARA arm with its motors and payload (chapter 5).

    B(q) qdd + C(q, qd) qd + F qd + g(q) = tau

``B`` is the inertia matrix of the links, the quill with its payload and the rotors (Siciliano et al. ch. 7
rotor model: motor i rides on link i-1 and spins at ``omega_{i-1} + k_ri qdot_i`` about the vertical);
``C`` comes from the Christoffel symbols of ``B``, so ``Bdot - 2C`` is skew-symmetric; ``F = diag(k_ri^2
F_mi)``; ``g = [0, 0, -m3 g0, 0]`` with ``m3 = m_l3 + m_L``. The model is linear in the parameter vector
``pi`` of :data:`PI_NAMES`: ``Y(q, qd, qd_r, qdd_r) pi = B qdd_r + C(q, qd) qd_r + F qd_r + g``.

Two layers
----------
*Compiled kernels* (``*_kernel``) take floats and float arrays only and write into arrays passed by the
caller; compiled loops (the simulation engine, controllers) call them with no Python objects. Every kernel
reads the robot from one flat float array ``dp = dynamic_array(p)`` that holds the robot's data (the table of
the introduction) in this order (index constants ``DP_*`` are exported)::

    0 d0   1 a1   2 a2   3 l1   4 l2   5 m_l1   6 m_l2   7 m_l3   8 I_l1   9 I_l2   10 I_l4
    11..14 k_r1..k_r4    15..18 I_m1..I_m4    19..22 F_m1..F_m4    23 m_L    24 g0

A controller that holds a wrong model (e.g. no payload) simply passes its own ``dynamic_array``.

*Public functions* (``inertia``, ``coriolis``, ...) check their inputs, take an optional
:class:`~scara.ScaraParams` (``None`` is the robot of the introduction, without payload) and return new arrays.
"""
from __future__ import annotations

import math

import numpy as np

from ._compile import kernel
from .errors import ScaraError, ShapeError, UnstableError, as_array
from .kinematics import _params
from .params import ScaraParams

__all__ = [
    # flat parameter array
    "DP_NAMES", "N_DP", "dynamic_array",
    # parameter vector pi
    "PI_NAMES", "PI_UNITS", "N_PI", "dynamic_parameters", "params_from_pi", "payload_from_pi",
    # public model
    "inertia", "coriolis", "gravity", "friction", "inverse_dynamics", "forward_dynamics", "regressor",
    "kinetic_energy", "potential_energy", "total_energy", "torque_breakdown", "TORQUE_TERMS",
    # kernels
    "inertia_kernel", "coriolis_kernel", "coriolis_vector_kernel", "gravity_kernel", "friction_kernel",
    "inverse_dynamics_kernel", "forward_dynamics_kernel", "forward_dynamics_scalar", "regressor_kernel", "pi_kernel",
    "kinetic_energy_kernel", "potential_energy_kernel", "cholesky_solve4", "gauss_solve4",
    "dynamics_workspace", "FD_WORK_ROWS",
]

# --------------------------------------------------------------------------------------------------
# the flat parameter array
# --------------------------------------------------------------------------------------------------
DP_D0, DP_A1, DP_A2, DP_L1, DP_L2 = 0, 1, 2, 3, 4
DP_ML1, DP_ML2, DP_ML3 = 5, 6, 7
DP_IL1, DP_IL2, DP_IL4 = 8, 9, 10
DP_KR, DP_IM, DP_FM = 11, 15, 19  # first of four entries each
DP_ML, DP_G0 = 23, 24
N_DP = 25
DP_NAMES = ("d0", "a1", "a2", "l1", "l2", "m_l1", "m_l2", "m_l3", "I_l1", "I_l2", "I_l4",
            "k_r1", "k_r2", "k_r3", "k_r4", "I_m1", "I_m2", "I_m3", "I_m4",
            "F_m1", "F_m2", "F_m3", "F_m4", "m_L", "g0")


def dynamic_array(p: ScaraParams | None = None) -> np.ndarray:
    """The robot's data in ``p`` (the table of the introduction) as one flat float array of shape ``(25,)``, in
    the order of :data:`DP_NAMES`: the form every compiled dynamics kernel takes.

    >>> dynamic_array()[[1, 7, 23, 24]]
    array([ 0.5 , 10.  ,  0.  ,  9.81])
    """
    p = _params(p)
    return np.array([p.d0, p.a1, p.a2, p.l1, p.l2, p.m_l1, p.m_l2, p.m_l3, p.I_l1, p.I_l2, p.I_l4,
                     *p.k_r, *p.I_m, *p.F_m, p.m_L, p.g0], dtype=float)


# --------------------------------------------------------------------------------------------------
# the parameter vector pi of the linear-in-parameters model
# --------------------------------------------------------------------------------------------------
#: Names of the 13 dynamic parameters in ``pi``, in order, for the regressor form ``Y pi`` of chapter 5.
#: ``beta_ij`` is the constant part of ``B_ij`` (everything in ``B_ij`` that does not multiply ``m3`` or
#: ``m_l2 l2``); ``F1`` to ``F4`` are the joints' viscous friction. Units: :data:`PI_UNITS`.
PI_NAMES = ("m3", "m_l2 l2", "beta11", "beta12", "beta22", "beta13", "beta33", "beta14", "beta44",
            "F1", "F2", "F3", "F4")
PI_UNITS = ("kg", "kg m", "kg m^2", "kg m^2", "kg m^2", "kg m", "kg", "kg m^2", "kg m^2",
            "N m s/rad", "N m s/rad", "N s/m", "N m s/rad")
N_PI = 13
PI_M3 = 0


@kernel
def pi_kernel(dp, out):
    """The parameter vector ``pi`` (13,) of :data:`PI_NAMES` from the flat array ``dp``, into ``out``.

    ``pi = [m3, m_l2 l2, beta11, beta12, beta22, beta13, beta33, beta14, beta44, F1, F2, F3, F4]`` with
    ``m3 = m_l3 + m_L`` and

    * ``beta11 = I_l1 + m_l1 l1^2 + k_r1^2 I_m1 + I_l2 + m_l2 (a1^2 + l2^2) + I_l4 + I_m2 + I_m3 + I_m4``
    * ``beta12 = I_l2 + m_l2 l2^2 + I_l4 + k_r2 I_m2 + I_m3 + I_m4``
    * ``beta22 = I_l2 + m_l2 l2^2 + I_l4 + k_r2^2 I_m2 + I_m3 + I_m4``
    * ``beta13 = k_r3 I_m3``, ``beta33 = k_r3^2 I_m3``, ``beta14 = I_l4 + k_r4 I_m4``,
      ``beta44 = I_l4 + k_r4^2 I_m4``, ``F_i = k_ri^2 F_mi``.
    """
    a1 = dp[DP_A1]
    l1 = dp[DP_L1]
    l2 = dp[DP_L2]
    kr1 = dp[DP_KR]
    kr2 = dp[DP_KR + 1]
    kr3 = dp[DP_KR + 2]
    kr4 = dp[DP_KR + 3]
    im1 = dp[DP_IM]
    im2 = dp[DP_IM + 1]
    im3 = dp[DP_IM + 2]
    im4 = dp[DP_IM + 3]
    il4 = dp[DP_IL4]
    j2 = dp[DP_IL2] + dp[DP_ML2] * l2 * l2
    out[0] = dp[DP_ML3] + dp[DP_ML]
    out[1] = dp[DP_ML2] * l2
    out[2] = dp[DP_IL1] + dp[DP_ML1] * l1 * l1 + kr1 * kr1 * im1 + j2 + dp[DP_ML2] * a1 * a1 + il4 + im2 + im3 + im4
    out[3] = j2 + il4 + kr2 * im2 + im3 + im4
    out[4] = j2 + il4 + kr2 * kr2 * im2 + im3 + im4
    out[5] = kr3 * im3
    out[6] = kr3 * kr3 * im3
    out[7] = il4 + kr4 * im4
    out[8] = il4 + kr4 * kr4 * im4
    for i in range(4):
        out[9 + i] = dp[DP_KR + i] * dp[DP_KR + i] * dp[DP_FM + i]


# --------------------------------------------------------------------------------------------------
# compiled kernels
# --------------------------------------------------------------------------------------------------
@kernel
def inertia_kernel(q, dp, out):
    """Inertia matrix ``B(q)`` (chapter 5) written into ``out`` (4, 4).

    With ``b = a1 (m_l2 l2 + m3 a2)``: ``B11 = beta11 + m3 (a1^2 + a2^2) + 2 b c2``,
    ``B12 = beta12 + m3 a2^2 + b c2``, ``B22 = beta22 + m3 a2^2``, ``B13 = B23 = beta13``,
    ``B33 = m3 + beta33``, ``B14 = B24 = beta14``, ``B44 = beta44``, ``B34 = 0`` (``beta`` of :func:`pi_kernel`).
    """
    a1 = dp[DP_A1]
    a2 = dp[DP_A2]
    l1 = dp[DP_L1]
    l2 = dp[DP_L2]
    m3 = dp[DP_ML3] + dp[DP_ML]
    ml2 = dp[DP_ML2]
    kr1 = dp[DP_KR]
    kr2 = dp[DP_KR + 1]
    kr3 = dp[DP_KR + 2]
    kr4 = dp[DP_KR + 3]
    im1 = dp[DP_IM]
    im2 = dp[DP_IM + 1]
    im3 = dp[DP_IM + 2]
    im4 = dp[DP_IM + 3]
    il4 = dp[DP_IL4]
    c2 = math.cos(q[1])
    j2 = dp[DP_IL2] + ml2 * l2 * l2
    b = a1 * (ml2 * l2 + m3 * a2)
    b14 = il4 + kr4 * im4
    b13 = kr3 * im3
    out[0, 0] = (dp[DP_IL1] + dp[DP_ML1] * l1 * l1 + kr1 * kr1 * im1 + j2 + ml2 * a1 * a1 + il4 + im2 + im3 + im4
                 + m3 * (a1 * a1 + a2 * a2) + 2.0 * b * c2)
    out[0, 1] = j2 + il4 + kr2 * im2 + im3 + im4 + m3 * a2 * a2 + b * c2
    out[1, 1] = j2 + il4 + kr2 * kr2 * im2 + im3 + im4 + m3 * a2 * a2
    out[0, 2] = b13
    out[1, 2] = b13
    out[2, 2] = m3 + kr3 * kr3 * im3
    out[0, 3] = b14
    out[1, 3] = b14
    out[2, 3] = 0.0
    out[3, 3] = il4 + kr4 * kr4 * im4
    for i in range(4):
        for j in range(i):
            out[i, j] = out[j, i]


@kernel
def coriolis_kernel(q, qd, dp, out):
    """Coriolis and centrifugal matrix ``C(q, qd)`` from the Christoffel symbols, into ``out`` (4, 4).

    Only ``B11`` and ``B12`` depend on ``q`` (through ``c2``), so with ``h = a1 (m_l2 l2 + m3 a2) sin(theta2)``:
    ``C11 = -h qd2``, ``C12 = -h (qd1 + qd2)``, ``C21 = h qd1``, every other entry 0.
    """
    a1 = dp[DP_A1]
    a2 = dp[DP_A2]
    m3 = dp[DP_ML3] + dp[DP_ML]
    h = a1 * (dp[DP_ML2] * dp[DP_L2] + m3 * a2) * math.sin(q[1])
    for i in range(4):
        for j in range(4):
            out[i, j] = 0.0
    out[0, 0] = -h * qd[1]
    out[0, 1] = -h * (qd[0] + qd[1])
    out[1, 0] = h * qd[0]


@kernel
def coriolis_vector_kernel(q, qd, v, dp, out):
    """``C(q, qd) v`` written into ``out`` (4,) without forming ``C`` (``v = qd`` gives the usual term)."""
    a1 = dp[DP_A1]
    a2 = dp[DP_A2]
    m3 = dp[DP_ML3] + dp[DP_ML]
    h = a1 * (dp[DP_ML2] * dp[DP_L2] + m3 * a2) * math.sin(q[1])
    out[0] = -h * (qd[1] * v[0] + (qd[0] + qd[1]) * v[1])
    out[1] = h * qd[0] * v[0]
    out[2] = 0.0
    out[3] = 0.0


@kernel
def gravity_kernel(q, dp, out):
    """Gravity torques ``g(q) = [0, 0, -m3 g0, 0]`` (chapter 5) written into ``out`` (4,)."""
    out[0] = 0.0
    out[1] = 0.0
    out[2] = -(dp[DP_ML3] + dp[DP_ML]) * dp[DP_G0]
    out[3] = 0.0


@kernel
def friction_kernel(qd, dp, out):
    """Viscous friction torques ``F qd`` with ``F = diag(k_ri^2 F_mi)`` written into ``out`` (4,)."""
    for i in range(4):
        out[i] = dp[DP_KR + i] * dp[DP_KR + i] * dp[DP_FM + i] * qd[i]


@kernel
def inverse_dynamics_kernel(q, qd, qdd, dp, work, out):
    """``tau = B(q) qdd + C(q, qd) qd + F qd + g(q)`` into ``out`` (4,); ``work`` is scratch of shape (5, 4)."""
    B = work[0:4]
    inertia_kernel(q, dp, B)
    v = work[4]
    coriolis_vector_kernel(q, qd, qd, dp, v)
    m3g = (dp[DP_ML3] + dp[DP_ML]) * dp[DP_G0]
    for i in range(4):
        s = v[i] + dp[DP_KR + i] * dp[DP_KR + i] * dp[DP_FM + i] * qd[i]
        for j in range(4):
            s += B[i, j] * qdd[j]
        out[i] = s
    out[2] -= m3g


@kernel
def cholesky_solve4(A, b, out):
    """Solve ``A x = b`` for a symmetric positive definite 4x4 ``A`` by Cholesky, into ``out`` (4,).

    ``A`` is overwritten by its Cholesky factor (lower triangle). Returns 0, or 1 when ``A`` is not
    positive definite (``out`` is then left unchanged). ``out`` may be ``b`` itself.
    """
    n = 4
    for j in range(n):
        s = A[j, j]
        for k in range(j):
            s -= A[j, k] * A[j, k]
        if not s > 0.0:
            return 1
        d = math.sqrt(s)
        A[j, j] = d
        for i in range(j + 1, n):
            s = A[i, j]
            for k in range(j):
                s -= A[i, k] * A[j, k]
            A[i, j] = s / d
    # forward substitution L y = b (y kept in out)
    y0 = b[0] / A[0, 0]
    y1 = (b[1] - A[1, 0] * y0) / A[1, 1]
    y2 = (b[2] - A[2, 0] * y0 - A[2, 1] * y1) / A[2,2]
    y3 = (b[3] - A[3, 0] * y0 - A[3, 1] * y1 - A[3, 2] * y2) / A[3, 3]
    # back substitution L^T x = y
    x3 = y3 / A[3, 3]
    x2 = (y2 - A[3, 2] * x3) / A[2, 2]
    x1 = (y1 - A[2, 1] * x2 - A[3, 1] * x3) / A[1, 1]
    x0 = (y0 - A[1, 0] * x1 - A[2, 0] * x2 - A[3, 0] * x3) / A[0, 0]
    out[0] = x0
    out[1] = x1
    out[2] = x2
    out[3] = x3
    return 0


@kernel
def gauss_solve4(A, b, out):
    """Solve ``A x = b`` for a general 4x4 ``A`` by Gauss elimination with partial pivoting, into ``out``.

    ``A`` and ``b`` are overwritten. Returns 0, or 1 when a pivot is below ``1e-14`` times the largest entry
    of ``A`` (numerically singular; ``out`` is then left unchanged). ``out`` may be ``b`` itself.
    """
    n = 4
    amax = 0.0
    for i in range(n):
        for j in range(n):
            if abs(A[i, j]) > amax:
                amax = abs(A[i, j])
    tol = 1e-14 * amax
    if amax == 0.0:
        return 1
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(A[i, k]) > abs(A[p, k]):
                p = i
        if abs(A[p, k]) <= tol:
            return 1
        if p != k:
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[p, j]
                A[p, j] = tmp
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
        for i in range(k + 1, n):
            f = A[i, k] / A[k, k]
            for j in range(k, n):
                A[i, j] -= f * A[k, j]
            b[i] -= f * b[k]
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= A[i, j] * b[j]
        b[i] = s / A[i, i]
    for i in range(n):
        out[i] = b[i]
    return 0


#: rows of the ``(rows, 4)`` scratch array that :func:`forward_dynamics_kernel` needs
FD_WORK_ROWS = 5


def dynamics_workspace() -> np.ndarray:
    """A scratch array of shape ``(FD_WORK_ROWS, 4)`` for :func:`forward_dynamics_kernel` and friends."""
    return np.zeros((FD_WORK_ROWS, 4))


@kernel
def forward_dynamics_scalar(q2, v1, v2, v3, v4, t1, t2, t3, t4, dp):
    """Scalar core of :func:`forward_dynamics_kernel`: ``(qdd1, qdd2, qdd3, qdd4, code)`` from ``theta2``, the
    joint velocities and torques as floats (``B`` depends on ``q`` through ``theta2`` only). ``code`` is 0, or
    1 if ``B`` is not positive definite. Used by the engine's RK4 stages to keep everything in registers."""
    a1 = dp[DP_A1]
    a2 = dp[DP_A2]
    l1 = dp[DP_L1]
    l2 = dp[DP_L2]
    m3 = dp[DP_ML3] + dp[DP_ML]
    ml2 = dp[DP_ML2]
    kr1 = dp[DP_KR]
    kr2 = dp[DP_KR + 1]
    kr3 = dp[DP_KR + 2]
    kr4 = dp[DP_KR + 3]
    im1 = dp[DP_IM]
    im2 = dp[DP_IM + 1]
    im3 = dp[DP_IM + 2]
    im4 = dp[DP_IM + 3]
    il4 = dp[DP_IL4]
    c2 = math.cos(q2)
    s2 = math.sin(q2)
    j2 = dp[DP_IL2] + ml2 * l2 * l2
    b = a1 * (ml2 * l2 + m3 * a2)
    # B (chapter 5)
    B11 = (dp[DP_IL1] + dp[DP_ML1] * l1 * l1 + kr1 * kr1 * im1 + j2 + ml2 * a1 * a1 + il4 + im2 + im3 + im4
           + m3 * (a1 * a1 + a2 * a2) + 2.0 * b * c2)
    B12 = j2 + il4 + kr2 * im2 + im3 + im4 + m3 * a2 * a2 + b * c2
    B22 = j2 + il4 + kr2 * kr2 * im2 + im3 + im4 + m3 * a2 * a2
    B13 = kr3 * im3
    B33 = m3 + kr3 * kr3 * im3
    B14 = il4 + kr4 * im4
    B44 = il4 + kr4 * kr4 * im4
    # right-hand side tau - C qd - F qd - g
    h = b * s2
    r1 = t1 + h * (v2 * v1 + (v1 + v2) * v2) - kr1 * kr1 * dp[DP_FM] * v1
    r2 = t2 - h * v1 * v1 - kr2 * kr2 * dp[DP_FM + 1] * v2
    r3 = t3 - kr3 * kr3 * dp[DP_FM + 2] * v3 + m3 * dp[DP_G0]
    r4 = t4 - kr4 * kr4 * dp[DP_FM + 3] * v4
    # Cholesky B = L L^T (B23 = B13, B24 = B14, B34 = 0)
    if not B11 > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 1
    L11 = math.sqrt(B11)
    L21 = B12 / L11
    L31 = B13 / L11
    L41 = B14 / L11
    d = B22 - L21 * L21
    if not d > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 1
    L22 = math.sqrt(d)
    L32 = (B13 - L31 * L21) / L22
    L42 = (B14 - L41 * L21) / L22
    d = B33 - L31 * L31 - L32 * L32
    if not d > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 1
    L33 = math.sqrt(d)
    L43 = (0.0 - L41 * L31 - L42 * L32) / L33
    d = B44 - L41 * L41 - L42 * L42 - L43 * L43
    if not d > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 1
    L44 = math.sqrt(d)
    y1 = r1 / L11
    y2 = (r2 - L21 * y1) / L22
    y3 = (r3 - L31 * y1 - L32 * y2) / L33
    y4 = (r4 - L41 * y1 - L42 * y2 - L43 * y3) / L44
    x4 = y4 / L44
    x3 = (y3 - L43 * x4) / L33
    x2 = (y2 - L32 * x3 - L42 * x4) / L22
    x1 = (y1 - L21 * x2 - L31 * x3 - L41 * x4) / L11
    return x1, x2, x3, x4, 0


@kernel
def forward_dynamics_kernel(q, qd, tau, dp, work, out):
    """``qdd = B(q)^-1 (tau - C(q, qd) qd - F qd - g(q))`` into ``out`` (4,), with no allocation.

    ``B`` and the right-hand side are formed in closed form (as :func:`inertia_kernel`,
    :func:`coriolis_vector_kernel`) in local scalars and solved by an unrolled 4x4 Cholesky factorisation
    (:func:`forward_dynamics_scalar`). The simulation engine uses a cheaper reduced solve of its own (``scara.simulate._plant_acceleration``), tested against this one.
    ``work`` (shape (5, 4), :func:`dynamics_workspace`) is accepted for a uniform kernel signature and is
    not touched. Returns 0, or 1 if ``B`` is not positive definite (``out`` then unchanged).
    """
    x1, x2, x3, x4, code = forward_dynamics_scalar(q[1], qd[0], qd[1], qd[2], qd[3],
                                                   tau[0], tau[1], tau[2], tau[3], dp)
    if code == 0:
        out[0] = x1
        out[1] = x2
        out[2] = x3
        out[3] = x4
    return code


@kernel
def regressor_kernel(q, qd, qd_r, qdd_r, dp, out):
    """Regressor ``Y(q, qd, qd_r, qdd_r)`` (4, 13) into ``out``: ``Y pi = B qdd_r + C(q, qd) qd_r + F qd_r + g``.

    Only ``a1``, ``a2`` and ``g0`` are read from ``dp`` (geometry and gravity are known); the columns follow
    :data:`PI_NAMES`.
    """
    a1 = dp[DP_A1]
    a2 = dp[DP_A2]
    g0 = dp[DP_G0]
    c2 = math.cos(q[1])
    s2 = math.sin(q[1])
    v1 = qd[0]
    v2 = qd[1]
    r1 = qd_r[0]
    r2 = qd_r[1]
    u1 = qdd_r[0]
    u2 = qdd_r[1]
    u3 = qdd_r[2]
    u4 = qdd_r[3]
    for i in range(4):
        for j in range(13):
            out[i, j] = 0.0
    cor1 = -s2 * (v2 * r1 + (v1 + v2) * r2)   # (C qd_r)_1 / b,  b = a1 (m_l2 l2 + m3 a2)
    cor2 = s2 * v1 * r1                        # (C qd_r)_2 / b
    # row 1
    out[0, 0] = (a1 * a1 + a2 * a2 + 2.0 * a1 * a2 * c2) * u1 + (a2 * a2 + a1 * a2 * c2) * u2 + a1 * a2 * cor1
    out[0, 1] = a1 * c2 * (2.0 * u1 + u2) + a1 * cor1
    out[0, 2] = u1
    out[0, 3] = u2
    out[0, 5] = u3
    out[0, 7] = u4
    out[0, 9] = r1
    # row 2
    out[1, 0] = (a2 * a2 + a1 * a2 * c2) * u1 + a2 * a2 * u2 + a1 * a2 * cor2
    out[1, 1] = a1 * c2 * u1 + a1 * cor2
    out[1, 3] = u1
    out[1, 4] = u2
    out[1, 5] = u3
    out[1, 7] = u4
    out[1, 10] = r2
    # row 3
    out[2, 0] = u3 - g0
    out[2, 5] = u1 + u2
    out[2, 6] = u3
    out[2, 11] = qd_r[2]
    # row 4
    out[3, 7] = u1 + u2
    out[3, 8] = u4
    out[3, 12] = qd_r[3]


@kernel
def kinetic_energy_kernel(q, qd, dp, work):
    """Kinetic energy ``T = qd^T B(q) qd / 2`` (J); ``work`` is scratch of shape (>= 4, 4)."""
    B = work[0:4]
    inertia_kernel(q, dp, B)
    s = 0.0
    for i in range(4):
        for j in range(4):
            s += qd[i] * B[i, j] * qd[j]
    return 0.5 * s


@kernel
def potential_energy_kernel(q, dp):
    """Potential energy ``U = g0 [(m_l1 + m_l2) d0 + m3 (d0 - d3)]`` (J), zero at the base-frame floor.

    Links 1 and 2 move in the horizontal plane at height ``d0``; the quill and payload sit at ``p_z = d0 - d3``;
    link 4 and the rotors have no mass.
    """
    d0 = dp[DP_D0]
    return dp[DP_G0] * ((dp[DP_ML1] + dp[DP_ML2]) * d0 + (dp[DP_ML3] + dp[DP_ML]) * (d0 - q[2]))


# --------------------------------------------------------------------------------------------------
# public functions
# --------------------------------------------------------------------------------------------------
def _vec(value, name):
    return np.ascontiguousarray(as_array(value, name, (4,)))


def inertia(q, p: ScaraParams | None = None) -> np.ndarray:
    """Inertia matrix ``B(q)`` of the arm with rotors and payload (chapter 5), shape (4, 4).

    Units: kg m^2 for the revolute entries, kg for ``B33``, kg m for ``B13``/``B23``. Raises
    :class:`~scara.ShapeError` / :class:`~scara.NonFiniteError` for a bad ``q``.

    >>> round(inertia([0, 0, 0.5, 0])[2, 2], 6)   # m3 + k_r3^2 I_m3 = 10 + 2500 * 0.005
    22.5
    """
    out = np.empty((4, 4))
    inertia_kernel(_vec(q, "q"), dynamic_array(p), out)
    return out


def coriolis(q, qd, p: ScaraParams | None = None) -> np.ndarray:
    """Coriolis and centrifugal matrix ``C(q, qd)`` from the Christoffel symbols of ``B``, shape (4, 4).

    ``c_ij = sum_k (dB_ij/dq_k + dB_ik/dq_j - dB_jk/dq_i) qd_k / 2``, which makes ``Bdot - 2C`` skew-symmetric.

    >>> coriolis([0, 1.0, 0.5, 0], [0, 0, 0, 0])[0, 0]
    -0.0
    """
    out = np.empty((4, 4))
    coriolis_kernel(_vec(q, "q"), _vec(qd, "qd"), dynamic_array(p), out)
    return out


def gravity(q, p: ScaraParams | None = None) -> np.ndarray:
    """Gravity torques ``g(q) = dU/dq = [0, 0, -m3 g0, 0]`` (N m, N m, N, N m), shape (4,).

    >>> gravity([0, 0, 0.5, 0], ScaraParams().with_payload(5.0))
    array([   0.  ,    0.  , -147.15,    0.  ])
    """
    out = np.empty(4)
    gravity_kernel(_vec(q, "q"), dynamic_array(p), out)
    return out


def friction(p: ScaraParams | None = None) -> np.ndarray:
    """Viscous friction matrix ``F = diag(k_ri^2 F_mi)`` at the joints (chapter 5), shape (4, 4).

    >>> np.diag(friction())
    array([5.e-05, 5.e-05, 2.5e+01, 2.e+00])
    """
    return np.diag(_params(p).F)


def inverse_dynamics(q, qd, qdd, p: ScaraParams | None = None) -> np.ndarray:
    """Joint torques ``tau = B(q) qdd + C(q, qd) qd + F qd + g(q)``: the model of chapter 5.

    ``q``, ``qd``, ``qdd`` have shape (4,) or all (N, 4) (a time series; the result then has shape (N, 4)).
    """
    dp = dynamic_array(p)
    q = as_array(q, "q", (4,), allow_batch=True)
    qd = as_array(qd, "qd", (4,), allow_batch=True)
    qdd = as_array(qdd, "qdd", (4,), allow_batch=True)
    if not (q.shape == qd.shape == qdd.shape):
        raise ShapeError(f"q, qd and qdd must have the same shape, got {q.shape}, {qd.shape}, {qdd.shape}")
    work = dynamics_workspace()
    if q.ndim == 1:
        out = np.empty(4)
        inverse_dynamics_kernel(np.ascontiguousarray(q), np.ascontiguousarray(qd), np.ascontiguousarray(qdd),
                                dp, work, out)
        return out
    q, qd, qdd = (np.ascontiguousarray(a) for a in (q, qd, qdd))
    out = np.empty_like(q)
    _inverse_dynamics_batch(q, qd, qdd, dp, work, out)
    return out


@kernel
def _inverse_dynamics_batch(q, qd, qdd, dp, work, out):
    for k in range(q.shape[0]):
        inverse_dynamics_kernel(q[k], qd[k], qdd[k], dp, work, out[k])


def forward_dynamics(q, qd, tau, p: ScaraParams | None = None) -> np.ndarray:
    """Joint accelerations ``qdd = B(q)^-1 (tau - C(q, qd) qd - F qd - g(q))``, shape (4,).

    Solved with a 4x4 Cholesky factorisation of ``B``. Raises :class:`~scara.ShapeError` /
    :class:`~scara.NonFiniteError` for bad inputs and :class:`~scara.UnstableError` if ``B`` is not
    positive definite (only possible with non-physical parameters).

    >>> forward_dynamics([0, 1.0, 0.5, 0], [0, 0, 0, 0], [0, 0, -98.1, 0]).round(12)   # quill held
    array([ 0.,  0., -0.,  0.])
    """
    out = np.empty(4)
    code = forward_dynamics_kernel(_vec(q, "q"), _vec(qd, "qd"), _vec(tau, "tau"), dynamic_array(p),
                                   dynamics_workspace(), out)
    if code:
        raise UnstableError("B(q) is not positive definite for these parameters; check the inertias and masses")
    return out


def regressor(q, qd, qd_r, qdd_r, p: ScaraParams | None = None) -> np.ndarray:
    """Regressor ``Y(q, qd, qd_r, qdd_r)``, shape (4, 13), with ``Y pi = B qdd_r + C(q, qd) qd_r + F qd_r + g``.

    ``pi = dynamic_parameters(p)``; the columns follow :data:`PI_NAMES`; column 0 multiplies the lumped mass
    ``m3 = m_l3 + m_L`` on the joint-3/4 axis. Only the geometry ``a1, a2`` and ``g0`` of ``p`` are used
    (they are known to a controller; the masses and inertias are in ``pi``).

    >>> Y = regressor([0, 1, 0.5, 0], [0.1, 0.2, 0, 0], [0.1, 0.2, 0, 0], [1, 2, 3, 4])
    >>> bool(np.allclose(Y @ dynamic_parameters(), inverse_dynamics([0, 1, 0.5, 0], [0.1, 0.2, 0, 0], [1, 2, 3, 4])))
    True
    """
    out = np.empty((4, N_PI))
    regressor_kernel(_vec(q, "q"), _vec(qd, "qd"), _vec(qd_r, "qd_r"), _vec(qdd_r, "qdd_r"), dynamic_array(p), out)
    return out


def dynamic_parameters(p: ScaraParams | None = None) -> np.ndarray:
    """The parameter vector ``pi`` (13,) of :data:`PI_NAMES` for ``p`` (units :data:`PI_UNITS`).

    ``pi[0] = m3 = m_l3 + m_L`` so that a payload estimate is ``pi_hat[0] - m_l3``
    (:func:`payload_from_pi`).

    >>> dynamic_parameters(ScaraParams().with_payload(5.0))[0]
    15.0
    """
    out = np.empty(N_PI)
    pi_kernel(dynamic_array(p), out)
    return out


def payload_from_pi(pi, base: ScaraParams | None = None) -> float | np.ndarray:
    """Payload mass ``m_L = pi[0] - m_l3`` (kg) read from a parameter vector (13,) or a series (N, 13)."""
    base = _params(base)
    pi = as_array(pi, "pi", (N_PI,), allow_batch=True)
    m = pi[..., PI_M3] - base.m_l3
    return float(m) if np.ndim(m) == 0 else m


def params_from_pi(pi, base: ScaraParams | None = None, rtol: float = 1e-9) -> ScaraParams:
    """The parameter object whose ``dynamic_parameters`` is ``pi``, filling in what ``pi`` cannot tell from
    ``base`` (default :class:`ScaraParams()`).

    ``pi`` fixes the lumped combinations of :data:`PI_NAMES`; the physical entries recovered are
    ``m_L = m3 - m_l3``, ``m_l2 = (m_l2 l2) / l2``, ``F_m = F / k_r^2``, ``I_m3 = beta13 / k_r3``,
    ``I_m4`` and ``I_l4`` from ``beta14, beta44`` (needs ``k_r4 != 1``), ``I_m2`` from ``beta22 - beta12``
    (needs ``k_r2 != 1``; otherwise ``base.I_m2`` is kept), ``I_l2`` from ``beta22`` and ``I_l1`` from
    ``beta11``. The geometry, ``m_l1``, ``m_l3``, ``I_m1``, ``k_r`` and ``g0`` come from ``base``.

    Raises :class:`~scara.ScaraError` when ``pi`` is inconsistent with ``base`` (e.g. ``beta33 != k_r3
    beta13``, or ``beta12 != beta22`` while ``k_r2 = 1``) beyond ``rtol``, or gives a negative physical value.

    >>> p = ScaraParams().with_payload(2.5)
    >>> params_from_pi(dynamic_parameters(p)).m_L
    2.5
    """
    base = _params(base)
    pi = as_array(pi, "pi", (N_PI,))
    m3, m2l2, b11, b12, b22, b13, b33, b14, b44 = (float(v) for v in pi[:9])
    kr = np.asarray(base.k_r)

    def close(a, b, what):
        if abs(a - b) > rtol * max(1.0, abs(a), abs(b)):
            raise ScaraError(f"pi is inconsistent with the base parameters: {what} ({a:.12g} != {b:.12g})")

    I_m3 = b13 / kr[2]
    close(b33, kr[2] ** 2 * I_m3, "beta33 must equal k_r3 * beta13")
    if abs(kr[3] ** 2 - kr[3]) > 1e-12:
        I_m4 = (b44 - b14) / (kr[3] ** 2 - kr[3])
        I_l4 = b14 - kr[3] * I_m4
    else:
        I_m4 = base.I_m[3]
        I_l4 = b14 - kr[3] * I_m4
        close(b44, b14, "beta44 must equal beta14 when k_r4 = 1")
    if abs(kr[1] ** 2 - kr[1]) > 1e-12:
        I_m2 = (b22 - b12) / (kr[1] ** 2 - kr[1])
    else:
        I_m2 = base.I_m[1]
        close(b22, b12, "beta22 must equal beta12 when k_r2 = 1")
    m_l2 = m2l2 / base.l2
    j2 = b22 - I_l4 - kr[1] ** 2 * I_m2 - I_m3 - I_m4
    I_l2 = j2 - m_l2 * base.l2 ** 2
    I_l1 = (b11 - j2 - m_l2 * base.a1 ** 2 - I_l4 - I_m2 - I_m3 - I_m4
            - base.m_l1 * base.l1 ** 2 - kr[0] ** 2 * base.I_m[0])
    F_m = np.asarray(pi[9:13], dtype=float) / kr ** 2
    I_m = (base.I_m[0], I_m2, I_m3, I_m4)
    # tiny negative round-off (e.g. -1e-17) is clipped; real negatives are refused by ScaraParams
    fix = lambda v: 0.0 if -1e-12 < v < 0 else v  # noqa: E731
    try:
        return base.replace(m_L=fix(m3 - base.m_l3), m_l2=fix(m_l2), I_l1=fix(I_l1), I_l2=fix(I_l2),
                            I_l4=fix(I_l4), I_m=tuple(fix(v) for v in I_m), F_m=tuple(fix(v) for v in F_m))
    except ScaraError as exc:
        raise ScaraError(f"pi does not correspond to a physical robot with these base parameters: {exc}") from exc


def kinetic_energy(q, qd, p: ScaraParams | None = None):
    """Kinetic energy ``qd^T B(q) qd / 2`` (J) of links, quill, payload and rotors.

    ``q``, ``qd`` of shape (4,) give a float; (N, 4) series give shape (N,).
    """
    dp = dynamic_array(p)
    q = as_array(q, "q", (4,), allow_batch=True)
    qd = as_array(qd, "qd", (4,), allow_batch=True)
    if q.shape != qd.shape:
        raise ShapeError(f"q and qd must have the same shape, got {q.shape} and {qd.shape}")
    work = dynamics_workspace()
    if q.ndim == 1:
        return float(kinetic_energy_kernel(np.ascontiguousarray(q), np.ascontiguousarray(qd), dp, work))
    out = np.empty(q.shape[0])
    _kinetic_batch(np.ascontiguousarray(q), np.ascontiguousarray(qd), dp, work, out)
    return out


@kernel
def _kinetic_batch(q, qd, dp, work, out):
    for k in range(q.shape[0]):
        out[k] = kinetic_energy_kernel(q[k], qd[k], dp, work)


def potential_energy(q, p: ScaraParams | None = None):
    """Gravitational potential energy ``U(q)`` (J) of chapter 5, zero at the base-frame floor; shape (4,) gives
    a float, (N, 4) gives (N,)."""
    p = _params(p)
    q = as_array(q, "q", (4,), allow_batch=True)
    u = p.g0 * ((p.m_l1 + p.m_l2) * p.d0 + p.m3 * (p.d0 - q[..., 2]))
    return float(u) if q.ndim == 1 else u


def total_energy(q, qd, p: ScaraParams | None = None):
    """Total energy (J), kinetic plus potential: :func:`kinetic_energy` plus :func:`potential_energy`."""
    return kinetic_energy(q, qd, p) + potential_energy(q, p)


#: the terms of :func:`torque_breakdown`, in display order
TORQUE_TERMS = ("links", "rotors", "payload", "coriolis", "friction", "gravity")


def torque_breakdown(q, qd, qdd, p: ScaraParams | None = None) -> dict:
    """Split the joint torque ``tau = B qdd + C qd + F qd + g`` along a motion into physical contributions.

    Returns a dict of (N, 4) arrays (or (4,) for a single state) whose sum is :func:`inverse_dynamics`:

    * ``links``: ``B_0 qdd`` with ``B_0`` the inertia of links and quill alone (rotors and payload removed);
    * ``rotors``: ``(B - B_no rotors) qdd``, the reflected rotor inertia ``k_r^2 I_m`` and the rotors' coupling
      with the links that carry them (a constant matrix);
    * ``payload``: every term ``m_L`` brings: its inertia, Coriolis and weight;
    * ``coriolis``: ``C qd`` of the robot without payload; ``friction``: ``F qd``; ``gravity``: ``g`` of the
      robot without payload (the quill's weight, on joint 3 only).
    """
    p = _params(p)
    bare = p.replace(m_L=0.0)
    no_rotor = bare.replace(I_m=(0.0, 0.0, 0.0, 0.0))
    q = as_array(q, "q", (4,), allow_batch=True)
    qd = as_array(qd, "qd", (4,), allow_batch=True)
    qdd = as_array(qdd, "qdd", (4,), allow_batch=True)
    if not (q.shape == qd.shape == qdd.shape):
        raise ShapeError(f"q, qd and qdd must have the same shape, got {q.shape}, {qd.shape}, {qdd.shape}")
    zero = np.zeros_like(q)
    links = inverse_dynamics(q, zero, qdd, no_rotor.replace(F_m=(0.0,) * 4, g0=0.0))
    with_rotors = inverse_dynamics(q, zero, qdd, bare.replace(F_m=(0.0,) * 4, g0=0.0))
    coriolis_only = inverse_dynamics(q, qd, zero, bare.replace(F_m=(0.0,) * 4, g0=0.0))
    total_bare = inverse_dynamics(q, qd, qdd, bare)
    total = inverse_dynamics(q, qd, qdd, p)
    fr = np.asarray(p.F) * qd
    grav = np.zeros_like(q)
    grav[..., 2] = -bare.m3 * bare.g0
    return {"links": links, "rotors": with_rotors - links, "payload": total - total_bare,
            "coriolis": coriolis_only, "friction": fr, "gravity": grav}
