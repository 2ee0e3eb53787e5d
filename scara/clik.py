"""Closed-loop inverse kinematics (CLIK): turn an operational-space trajectory into joint trajectories.

Four algorithms (SPEC sections 4 and 5; Siciliano et al., *Robotics*, section 3.7), all discretised with
Euler's rule at the trajectory's sampling period ``dt``:

* **Jacobian inverse**: ``qd = J_A^-1 (xd_d + K e)``. The error obeys ``ed = -K e``. Near a
  singularity the inverse can be replaced by the damped least-squares inverse
  ``J^* = J^T (J J^T + lambda^2 I)^-1`` (damped least squares, Siciliano et al., section 3.5), with a constant damping or one that grows only when the
  manipulability falls below a threshold.
* **Jacobian transpose**: ``qd = J_A^T K e``. No inversion; the error converges for a constant
  reference and lags a moving one.
* **Pseudo-inverse** with one operational component relaxed (x by default): the arm becomes functionally
  redundant, ``qd = J_r^+ (xd_r + K_r e_r) + (I - J_r^+ J_r) qd_0`` with ``qd_0 = k_0 grad w_0(q)``
  climbing a dexterity measure (``w_0 = sin^2 theta2`` by default, or the manipulability ``w``).
* **Second order** (section 3.7.4, with the analytic Jacobian): ``qdd = J_A^-1 (xdd_d + K_D ed + K_P e - Jd_A qd)``,
  giving the joint positions, velocities and accelerations the control chapter tracks.

The loops run in compiled kernels (see :mod:`scara._compile`) with the closed-form kinematics of
:mod:`scara.kinematics` inside; nothing is allocated per step. Every run checks its settings first
(positive, finite gains; the discrete-time stability limits derived below; a reachable reference) and stops
with an :class:`~scara.errors.UnstableError` giving the time and the cause if it diverges anyway.

Discrete-time stability (Euler, sampling period ``dt``). Linearising one step,
``e_{k+1} = e_k + (x_d,k+1 - x_d,k) - J_A (q_{k+1} - q_k)``:

* inverse: ``e_{k+1} = (I - dt K) e_k + O(dt^2)``, stable iff ``0 < dt K_i < 2`` for every component;
* transpose: ``e_{k+1} = (I - dt J_A J_A^T K) e_k + ...``. ``J_A J_A^T K`` is similar to the symmetric
  ``K^1/2 J_A J_A^T K^1/2`` (and to ``J_A^T K J_A``, the matrix of the joint-space iteration), so its
  eigenvalues ``mu_i(q)`` are real and positive and the step is stable iff ``dt mu_max(q) < 2`` at every
  configuration met. :func:`transpose_stability` evaluates ``mu_max`` along the reference;
* second order, per component with ``a = dt K_D``, ``b = dt^2 K_P``: the characteristic polynomial
  ``z^2 - (2 - a) z + (1 - a + b)`` has both roots inside the unit circle iff ``b < a`` and ``2 a - b < 4``
  (Jury's test); with ``K_D = 2 omega``, ``K_P = omega^2`` both poles sit at ``z = 1 - omega dt``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ._compile import kernel
from .errors import ScaraError, ShapeError, UnreachableError, UnstableError, as_array
from .kinematics import _params, check_reachable, ikine, is_reachable, jacobian_kernel, pose_kernel
from .params import ScaraParams

__all__ = [
    "METHODS",
    "COMPONENTS",
    "SEED_K",
    "ClikResult",
    "TransposeStability",
    "clik",
    "clik2",
    "start_configuration",
    "transpose_stability",
    "second_order_gains",
    "dexterity",
]

#: the first-order methods of :func:`clik`
METHODS = ("inverse", "transpose", "pseudoinverse")
#: names of the operational components, in the order of ``x_e``
COMPONENTS = ("x", "y", "z", "phi")
#: the SPEC's seed gains for the inverse and transpose methods (1/s for the inverse)
SEED_K = (400.0, 400.0, 400.0, 100.0)
#: dexterity measures the pseudo-inverse's null-space term can climb
OBJECTIVES = ("sin2", "manipulability")

_METHOD_CODE = {"inverse": 0, "transpose": 1, "pseudoinverse": 2}
_OBJECTIVE_CODE = {"sin2": 0, "manipulability": 1}
_CAUSES = {
    1: "a value became NaN or infinite",
    2: "the tracking error exceeded max_error",
    3: "the Jacobian became singular",
}
_SINGULAR_TOL = 1e-12  # |det J_A| (m^2) or Cholesky pivot below which the solve is refused


# --------------------------------------------------------------------------------------------------
# compiled kernels
# --------------------------------------------------------------------------------------------------
@kernel
def _solve_kept_s(j11, j12, j21, j22, kx, ky, kz, kp, lam2, v0, v1, v2, v3, g2):
    """Scalar core of :func:`_solve_kept`: ``(ok, out0, out1, out2, out3)`` from the four non-constant entries
    of ``J_A`` (``j11 = J[0, 0]``, ``j12 = J[0, 1]``, ``j21 = J[1, 0]``, ``j22 = J[1, 1]``), the kept flags, the
    damping ``lam2``, the right-hand side ``v`` and the null-space gradient ``g2``."""
    a00 = kx * (j11 * j11 + j12 * j12 + lam2) + (1.0 - kx)
    a01 = kx * ky * (j11 * j21 + j12 * j22)
    a02 = kx * kp * (j11 + j12)
    a11 = ky * (j21 * j21 + j22 * j22 + lam2) + (1.0 - ky)
    a12 = ky * kp * (j21 + j22)
    a22 = kp * (3.0 + lam2) + (1.0 - kp)
    b0 = kx * (v0 - j12 * g2)
    b1 = ky * (v1 - j22 * g2)
    b2 = kp * (v3 - g2)
    if not a00 > _SINGULAR_TOL:
        return False, 0.0, 0.0, 0.0, 0.0
    l00 = math.sqrt(a00)
    l10 = a01 / l00
    l20 = a02 / l00
    d11 = a11 - l10 * l10
    if not d11 > _SINGULAR_TOL:
        return False, 0.0, 0.0, 0.0, 0.0
    l11 = math.sqrt(d11)
    l21 = (a12 - l20 * l10) / l11
    d22 = a22 - l20 * l20 - l21 * l21
    if not d22 > _SINGULAR_TOL:
        return False, 0.0, 0.0, 0.0, 0.0
    l22 = math.sqrt(d22)
    z0 = b0 / l00
    z1 = (b1 - l10 * z0) / l11
    z2 = (b2 - l20 * z0 - l21 * z1) / l22
    y2 = z2 / l22
    y1 = (z1 - l21 * y2) / l11
    y0 = (z0 - l10 * y1 - l20 * y2) / l00
    return (True, j11 * y0 + j21 * y1 + y2, g2 + j12 * y0 + j22 * y1 + y2, -kz * v2 / (1.0 + lam2), y2)


@kernel
def _solve_kept(J, keep, lam2, v, g2, out):
    """``out = g + J_r^T (J_r J_r^T + lam2 I)^-1 (v - J_r g)`` with ``g = [0, g2, 0, 0]``; returns False if singular.

    ``J_r`` holds the rows of ``J`` (4, 4) with ``keep[i] = 1`` (a dropped row acts as a zero row, its
    multiplier is 0). With ``lam2 = 0`` this is the pseudo-inverse solution plus the null-space projection of
    ``g``, ``J_r^+ v + (I - J_r^+ J_r) g`` (all rows kept and ``g = 0``: ``J^-1 v``); with ``lam2 > 0`` the
    damped least-squares solution. It uses the structure of ``J_A`` (SPEC section 2): rows x and y only
    involve ``theta1, theta2``, row z is ``[0, 0, -1, 0]`` and row phi is ``[1, 1, 0, 1]``; so z decouples and
    the x, y, phi block is a 3x3 symmetric positive definite system solved by an unrolled Cholesky factorisation
    (:func:`_solve_kept_s`, which the loops call with the entries in scalars).
    """
    ok, o0, o1, o2, o3 = _solve_kept_s(J[0, 0], J[0, 1], J[1, 0], J[1, 1], keep[0], keep[1], keep[2], keep[3],
                                       lam2, v[0], v[1], v[2], v[3], g2)
    if ok:
        out[0] = o0
        out[1] = o1
        out[2] = o2
        out[3] = o3
    return ok


@kernel
def _solve_exact_s(j11, j12, j21, j22, v0, v1, v2, v3):
    """``J^-1 v`` in closed form for the analytic Jacobian of SPEC section 2: ``(ok, u1, u2, u3, u4)``.

    The x, y rows give a 2x2 system in ``theta1, theta2`` with determinant ``-a1 a2 sin theta2``;
    then ``d3_dot = -v_z`` and ``theta4_dot = v_phi - theta1_dot - theta2_dot``. ``ok`` is False if singular.
    """
    det = j11 * j22 - j12 * j21
    if not abs(det) > _SINGULAR_TOL:
        return False, 0.0, 0.0, 0.0, 0.0
    u1 = (j22 * v0 - j12 * v1) / det
    u2 = (j11 * v1 - j21 * v0) / det
    return True, u1, u2, -v2, v3 - u1 - u2


@kernel
def _track_step(k, xr, q1, q2, q3, q4, a1, a2, d0, keep, max_err, x, e, w):
    """Pose, error and manipulability at step ``k`` from the joint values in scalars.

    Returns ``(status, j11, j12, j21, j22)``: status 0, 1 (non-finite) or 2 (error above ``max_err`` on a
    kept component), and the four non-constant entries of ``J_A`` (SPEC section 2), from the step's only four
    trigonometric calls: ``p_x = -J_21``, ``p_y = J_11``, ``p_z = d0 - d3``, ``phi = theta1 + theta2 + theta4``,
    and ``w = |det J_A| = |J_11 J_22 - J_12 J_21|``.
    """
    t12 = q1 + q2
    s1 = math.sin(q1)
    c1 = math.cos(q1)
    s12 = math.sin(t12)
    c12 = math.cos(t12)
    j11 = -(a1 * s1 + a2 * s12)
    j12 = -a2 * s12
    j21 = -(a1 * c1 + a2 * c12)
    j22 = -a2 * c12
    x0 = -j21
    x1 = j11
    x2 = d0 - q3
    x3 = t12 + q4
    x[k, 0] = x0
    x[k, 1] = x1
    x[k, 2] = x2
    x[k, 3] = x3
    w[k] = abs(j11 * j22 - j12 * j21)
    e0 = xr[k, 0] - x0
    e1 = xr[k, 1] - x1
    e2 = xr[k, 2] - x2
    e3 = xr[k, 3] - x3
    e[k, 0] = e0
    e[k, 1] = e1
    e[k, 2] = e2
    e[k, 3] = e3
    if not (math.isfinite(e0) and math.isfinite(e1) and math.isfinite(e2) and math.isfinite(e3)):
        return 1, j11, j12, j21, j22
    if ((keep[0] > 0.0 and abs(e0) > max_err) or (keep[1] > 0.0 and abs(e1) > max_err)
            or (keep[2] > 0.0 and abs(e2) > max_err) or (keep[3] > 0.0 and abs(e3) > max_err)):
        return 2, j11, j12, j21, j22
    return 0, j11, j12, j21, j22


@kernel
def _damping_at(lam0sq, w_thr, wk):
    """The damping ``lambda^2`` at manipulability ``wk``: ``lam0sq``, or with a threshold
    ``lam0sq (1 - (w / w_thr)^2)`` below it and 0 above."""
    if w_thr > 0.0:
        return lam0sq * (1.0 - (wk / w_thr) ** 2) if wk < w_thr else 0.0
    return lam0sq


@kernel
def _clik1_kernel(xr, vr, dt, method, K, keep, lam0sq, w_thr, k0, objective, a1, a2, d0, max_err,
                  q, qd, x, e, w, info):
    """First-order CLIK loop (inverse, transpose, pseudo-inverse), Euler rule ``q_{k+1} = q_k + dt qd_k``.

    Inputs: reference ``xr``, ``vr`` (N, 4); ``method`` 0/1/2; ``K`` (4,) diagonal gains; ``keep`` (4,) 1.0
    for controlled components; damping ``lam0sq`` (lambda^2) applied in full, or scaled by
    ``1 - (w / w_thr)^2`` below ``w_thr`` when ``w_thr > 0``; null-space gain ``k0`` and ``objective`` (0:
    sin^2 theta2, 1: manipulability). ``q[0]`` holds the start configuration. Outputs ``q, qd, x, e`` (N, 4)
    and ``w`` (N,). ``info`` (2,) receives ``[status, step]``: 0 done, 1 non-finite, 2 error above
    ``max_err`` on a kept component, 3 singular Jacobian. The joint values, the Jacobian's entries and the
    step's vectors live in scalars: nothing is allocated and no 4x4 matrix is formed.
    """
    n = xr.shape[0]
    K0 = K[0]
    K1 = K[1]
    K2 = K[2]
    K3 = K[3]
    q1 = q[0, 0]
    q2 = q[0, 1]
    q3 = q[0, 2]
    q4 = q[0, 3]
    info[0] = 0
    info[1] = n - 1
    for k in range(n):
        q[k, 0] = q1
        q[k, 1] = q2
        q[k, 2] = q3
        q[k, 3] = q4
        status, j11, j12, j21, j22 = _track_step(k, xr, q1, q2, q3, q4, a1, a2, d0, keep, max_err, x, e, w)
        if status != 0:
            info[0] = status
            info[1] = k
            return
        e0 = e[k, 0]
        e1 = e[k, 1]
        e2 = e[k, 2]
        e3 = e[k, 3]
        ok = True
        if method == 1:  # transpose: qd = J^T K e (the zero entries of J_A dropped)
            s0 = j11 * K0 * e0 + j21 * K1 * e1 + K3 * e3
            s1 = j12 * K0 * e0 + j22 * K1 * e1 + K3 * e3
            s2 = -K2 * e2
            s3 = K3 * e3
        else:
            v0 = vr[k, 0] + K0 * e0
            v1 = vr[k, 1] + K1 * e1
            v2 = vr[k, 2] + K2 * e2
            v3 = vr[k, 3] + K3 * e3
            lam2 = _damping_at(lam0sq, w_thr, w[k])
            if method == 0 and lam2 == 0.0:
                ok, s0, s1, s2, s3 = _solve_exact_s(j11, j12, j21, j22, v0, v1, v2, v3)
            else:
                g2 = 0.0
                if method == 2 and k0 != 0.0:
                    if objective == 0:  # grad of sin^2 theta2
                        g2 = k0 * math.sin(2.0 * q2)
                    else:  # grad of a1 a2 |sin theta2|
                        g2 = k0 * a1 * a2 * math.cos(q2) * (1.0 if math.sin(q2) >= 0.0 else -1.0)
                ok, s0, s1, s2, s3 = _solve_kept_s(j11, j12, j21, j22, keep[0], keep[1], keep[2], keep[3], lam2,
                                                   v0, v1, v2, v3, g2)
        if not ok:
            info[0] = 3
            info[1] = k
            return
        if not (math.isfinite(s0) and math.isfinite(s1) and math.isfinite(s2) and math.isfinite(s3)):
            info[0] = 1
            info[1] = k
            return
        qd[k, 0] = s0
        qd[k, 1] = s1
        qd[k, 2] = s2
        qd[k, 3] = s3
        q1 += dt * s0
        q2 += dt * s1
        q3 += dt * s2
        q4 += dt * s3


@kernel
def _clik2_kernel(xr, vr, ar, dt, KP, KD, lam0sq, w_thr, a1, a2, d0, max_err, q, qd, qdd, x, e, w, info):
    """Second-order CLIK loop: ``qdd_k = J^-1 (xdd_d + K_D ed + K_P e - Jd qd)`` (or its damped form), then
    Euler ``q_{k+1} = q_k + dt qd_k``, ``qd_{k+1} = qd_k + dt qdd_k``. ``q[0]``, ``qd[0]`` hold the start.
    Same ``info`` codes as :func:`_clik1_kernel`.

    ``Jd qd`` comes from the entries of ``J`` with no more trigonometry: differentiating SPEC section 2 gives
    ``Jd_11 = J_21 w1 + J_22 qd2``, ``Jd_12 = J_22 w12``, ``Jd_21 = -J_11 w1 - J_12 qd2``, ``Jd_22 = -J_12 w12``
    (``w1 = qd1``, ``w12 = qd1 + qd2``), the only non-zero entries (as in ``jacobian_dot_kernel``).
    """
    n = xr.shape[0]
    keep = np.ones(4)
    q1 = q[0, 0]
    q2 = q[0, 1]
    q3 = q[0, 2]
    q4 = q[0, 3]
    u1 = qd[0, 0]
    u2 = qd[0, 1]
    u3 = qd[0, 2]
    u4 = qd[0, 3]
    info[0] = 0
    info[1] = n - 1
    for k in range(n):
        q[k, 0] = q1
        q[k, 1] = q2
        q[k, 2] = q3
        q[k, 3] = q4
        qd[k, 0] = u1
        qd[k, 1] = u2
        qd[k, 2] = u3
        qd[k, 3] = u4
        status, j11, j12, j21, j22 = _track_step(k, xr, q1, q2, q3, q4, a1, a2, d0, keep, max_err, x, e, w)
        if status != 0:
            info[0] = status
            info[1] = k
            return
        w1 = u1
        w12 = u1 + u2
        jdq_x = (j21 * w1 + j22 * u2) * u1 + j22 * w12 * u2
        jdq_y = -(j11 * w1 + j12 * u2) * u1 - j12 * w12 * u2
        xd_x = j11 * u1 + j12 * u2
        xd_y = j21 * u1 + j22 * u2
        xd_z = -u3
        xd_p = u1 + u2 + u4
        v0 = ar[k, 0] + KD[0] * (vr[k, 0] - xd_x) + KP[0] * e[k, 0] - jdq_x
        v1 = ar[k, 1] + KD[1] * (vr[k, 1] - xd_y) + KP[1] * e[k, 1] - jdq_y
        v2 = ar[k, 2] + KD[2] * (vr[k, 2] - xd_z) + KP[2] * e[k, 2]
        v3 = ar[k, 3] + KD[3] * (vr[k, 3] - xd_p) + KP[3] * e[k, 3]
        lam2 = _damping_at(lam0sq, w_thr, w[k])
        if lam2 == 0.0:
            ok, s0, s1, s2, s3 = _solve_exact_s(j11, j12, j21, j22, v0, v1, v2, v3)
        else:
            ok, s0, s1, s2, s3 = _solve_kept_s(j11, j12, j21, j22, 1.0, 1.0, 1.0, 1.0, lam2, v0, v1, v2, v3, 0.0)
        if not ok:
            info[0] = 3
            info[1] = k
            return
        if not (math.isfinite(s0) and math.isfinite(s1) and math.isfinite(s2) and math.isfinite(s3)):
            info[0] = 1
            info[1] = k
            return
        qdd[k, 0] = s0
        qdd[k, 1] = s1
        qdd[k, 2] = s2
        qdd[k, 3] = s3
        q1 += dt * u1
        q2 += dt * u2
        q3 += dt * u3
        q4 += dt * u4
        u1 += dt * s0
        u2 += dt * s1
        u3 += dt * s2
        u4 += dt * s3


@kernel
def _sym3_max_eig(s00, s01, s02, s11, s12, s22):
    """Largest eigenvalue of a symmetric 3x3 matrix, closed form (trigonometric solution of the cubic)."""
    p1 = s01 * s01 + s02 * s02 + s12 * s12
    qm = (s00 + s11 + s22) / 3.0
    d0 = s00 - qm
    d1 = s11 - qm
    d2 = s22 - qm
    p2 = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * p1
    if p2 <= 1e-300:
        return qm
    pp = math.sqrt(p2 / 6.0)
    b00 = d0 / pp
    b11 = d1 / pp
    b22 = d2 / pp
    b01 = s01 / pp
    b02 = s02 / pp
    b12 = s12 / pp
    r = 0.5 * (b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02))
    if r <= -1.0:
        phi = math.pi / 3.0
    elif r >= 1.0:
        phi = 0.0
    else:
        phi = math.acos(r) / 3.0
    return qm + 2.0 * pp * math.cos(phi)


@kernel
def _position_gram(px, py, a1, a2, elbow):
    """Entries ``(g_xx, g_yy, g_xy, g_xphi, g_yphi)`` of ``J_3 J_3^T`` (rows x, y, phi of ``J_A``) at the
    inverse-kinematics configuration of the horizontal position ``(px, py)``, computed without any angle.

    ``cos theta2 = (r^2 - a1^2 - a2^2) / (2 a1 a2)``, ``sin theta2 = elbow sqrt(1 - cos^2)``; with
    ``alpha = a1 c2 + a2`` and ``beta = a1 s2`` (``alpha^2 + beta^2 = r^2``), ``c12 = (alpha p_x + beta p_y) / r^2``
    and ``s12 = (beta p_x - alpha p_y) / r^2``; then ``J_11 = p_y``, ``J_21 = -p_x``, ``J_12 = -a2 s12``,
    ``J_22 = -a2 c12`` (SPEC section 2) and the phi row is ``[1, 1, 1]`` over ``theta1, theta2, theta4``.
    """
    r2 = px * px + py * py
    c2 = (r2 - a1 * a1 - a2 * a2) / (2.0 * a1 * a2)
    c2 = min(1.0, max(-1.0, c2))
    s2 = elbow * math.sqrt(1.0 - c2 * c2)
    if r2 > 1e-24:
        al = a1 * c2 + a2
        be = a1 * s2
        c12 = (al * px + be * py) / r2
        s12 = (be * px - al * py) / r2
    else:  # folded arm on the joint-1 axis: theta1 is free, any direction will do
        c12 = 1.0
        s12 = 0.0
    j11 = py
    j12 = -a2 * s12
    j21 = -px
    j22 = -a2 * c12
    return (j11 * j11 + j12 * j12, j21 * j21 + j22 * j22, j11 * j21 + j12 * j22, j11 + j12, j21 + j22)


@kernel
def _transpose_rate_kernel(xr, K, a1, a2, elbow, out):
    """``out[k] = mu_max(J_A J_A^T K)`` at the inverse-kinematics configuration of every reference sample.

    The z row of ``J_A`` only involves ``d3`` and gives the eigenvalue ``K_z``; the x, y, phi rows give the
    symmetric block ``S = K^1/2 J_3 J_3^T K^1/2`` (see :func:`_position_gram`), whose largest eigenvalue is
    found in closed form. The caller has checked that every sample is reachable.
    """
    sk0 = math.sqrt(K[0])
    sk1 = math.sqrt(K[1])
    sk3 = math.sqrt(K[3])
    for k in range(xr.shape[0]):
        gxx, gyy, gxy, gxp, gyp = _position_gram(xr[k, 0], xr[k, 1], a1, a2, elbow)
        mu = _sym3_max_eig(K[0] * gxx, sk0 * sk1 * gxy, sk0 * sk3 * gxp, K[1] * gyy, sk1 * sk3 * gyp, 3.0 * K[3])
        out[k] = max(mu, K[2])


@kernel
def _transpose_check_kernel(xr, K, a1, a2, elbow, limit):
    """First sample where ``mu_max(J_A J_A^T K) >= limit``, or -1: the fast test run before every transpose CLIK.

    The trace of ``S`` bounds its largest eigenvalue (all are >= 0), so the closed-form eigenvalue is only
    computed where the trace reaches the limit.
    """
    if K[2] >= limit:
        return 0
    sk0 = math.sqrt(K[0])
    sk1 = math.sqrt(K[1])
    sk3 = math.sqrt(K[3])
    for k in range(xr.shape[0]):
        gxx, gyy, gxy, gxp, gyp = _position_gram(xr[k, 0], xr[k, 1], a1, a2, elbow)
        if K[0] * gxx + K[1] * gyy + 3.0 * K[3] < limit:
            continue
        if _sym3_max_eig(K[0] * gxx, sk0 * sk1 * gxy, sk0 * sk3 * gxp, K[1] * gyy, sk1 * sk3 * gyp,
                         3.0 * K[3]) >= limit:
            return k
    return -1


# --------------------------------------------------------------------------------------------------
# results
# --------------------------------------------------------------------------------------------------
@dataclass
class ClikResult:
    """The joint trajectory a CLIK run produced, with its pose and error.

    Attributes
    ----------
    t : (N,) s
    q, qd : (N, 4)
        Joint positions (rad, rad, m, rad) and velocities; ``q[k+1] = q[k] + dt qd[k]``.
    qdd : (N, 4) or None
        Joint accelerations (second-order CLIK only).
    x : (N, 4)
        End-effector pose ``x_e = k(q)`` reached, ``[px, py, pz, phi]``.
    e : (N, 4)
        ``x_d - x_e``. For the pseudo-inverse the relaxed component is uncontrolled: its entry is the drift.
    w : (N,)
        Manipulability ``a1 a2 |sin theta2|`` (m^2).
    x_d : (N, 4)
        The reference that was tracked.
    method : str
        ``"inverse"``, ``"transpose"``, ``"pseudoinverse"`` or ``"second_order"``.
    kept : (4,) bool
        Components under control (all but the relaxed one for the pseudo-inverse).
    dt : float
        Sampling period (s).
    gains : dict
        The gains and options used (``K`` or ``K_P``/``K_D``, damping, null-space gain, ...).
    run_time : float
        Seconds spent in the compiled loop.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray | None
    x: np.ndarray
    e: np.ndarray
    w: np.ndarray
    x_d: np.ndarray
    method: str
    kept: np.ndarray
    dt: float
    gains: dict = field(default_factory=dict)
    run_time: float = 0.0

    @property
    def position_error(self) -> np.ndarray:
        """Norm of the position error over the kept position components, (N,) in m."""
        cols = [i for i in range(3) if self.kept[i]]
        return np.sqrt(np.sum(self.e[:, cols] ** 2, axis=1)) if cols else np.zeros(len(self.t))

    @property
    def orientation_error(self) -> np.ndarray:
        """``|phi_d - phi_e|`` (N,) in rad (zeros if phi is the relaxed component)."""
        return np.abs(self.e[:, 3]) if self.kept[3] else np.zeros(len(self.t))

    def summary(self, settle: float = 0.1) -> dict:
        """The figures of the chapter's comparison table, in SI units.

        Error figures skip the first ``settle`` seconds (the start-up transient, where a given ``q0`` may
        leave a large initial error); position figures use the kept position components only. Manipulability
        figures cover the whole run.

        Returns a dict with ``method``, ``max_position_error`` and ``rms_position_error`` (m),
        ``max_orientation_error`` (rad), ``min_manipulability`` and ``mean_manipulability`` (m^2), ``run_time``
        (s). Raises :class:`ScaraError` if ``settle`` is negative or not shorter than the run.
        """
        settle = float(settle)
        if not (0.0 <= settle < self.t[-1] - self.t[0]):
            raise ScaraError(f"settle = {settle} s must lie in [0, {self.t[-1] - self.t[0]:g}) s, the run's length")
        after = self.t >= self.t[0] + settle - 1e-12
        ep = self.position_error[after]
        return {
            "method": self.method,
            "max_position_error": float(ep.max()),
            "rms_position_error": float(np.sqrt(np.mean(ep**2))),
            "max_orientation_error": float(self.orientation_error[after].max()),
            "min_manipulability": float(self.w.min()),
            "mean_manipulability": float(self.w.mean()),
            "run_time": float(self.run_time),
        }

    def __repr__(self):
        return (f"ClikResult(method={self.method!r}, N={len(self.t)}, dt={self.dt:g} s, "
                f"max |e_p| = {self.position_error.max():.3g} m, run_time = {self.run_time * 1e3:.2f} ms)")


@dataclass(frozen=True)
class TransposeStability:
    """Discrete-time stability of the Jacobian-transpose CLIK along a reference (see the module notes).

    ``mu`` (N,) is the largest eigenvalue of ``J_A J_A^T K`` (1/s) at the reference's configurations, ``limit``
    is ``2 / dt``; ``scale_limit = limit / mu_max`` is the factor by which ``K`` may be multiplied before Euler's
    rule goes unstable (> 1: stable). ``t_worst`` is where ``mu`` peaks.
    """

    t: np.ndarray
    mu: np.ndarray
    mu_max: float
    t_worst: float
    limit: float
    scale_limit: float

    @property
    def stable(self) -> bool:
        return self.scale_limit > 1.0


# --------------------------------------------------------------------------------------------------
# input checks
# --------------------------------------------------------------------------------------------------
def _trajectory(traj, need_acc: bool, p: ScaraParams):
    """Validate a trajectory-like object; return ``(t, x, xd, xdd or None, dt)``."""
    missing = [a for a in ("t", "x", "xd") + (("xdd",) if need_acc else ()) if not hasattr(traj, a)]
    if missing:
        raise ScaraError(f"traj must have attributes t, x, xd{', xdd' if need_acc else ''} "
                         f"(and dt); {type(traj).__name__} lacks {', '.join(missing)}")
    if np.ndim(traj.t) != 1:
        raise ShapeError(f"traj.t must have shape (N,), got {np.shape(traj.t)}")
    n = len(traj.t)
    t = as_array(traj.t, "traj.t", (n,))
    if n < 2:
        raise ShapeError(f"traj.t must hold at least 2 samples, got {n}")
    x = np.ascontiguousarray(as_array(traj.x, "traj.x", (n, 4)))
    xd = np.ascontiguousarray(as_array(traj.xd, "traj.xd", (n, 4)))
    xdd = np.ascontiguousarray(as_array(traj.xdd, "traj.xdd", (n, 4))) if need_acc else None
    dt = getattr(traj, "dt", None)
    dt = float(t[1] - t[0]) if dt is None else dt
    try:
        dt = float(dt)
    except (TypeError, ValueError) as exc:
        raise ScaraError(f"traj.dt must be a number, got {dt!r}") from exc
    if not math.isfinite(dt) or dt <= 0:
        raise ScaraError(f"traj.dt = {dt} s must be finite and > 0 (the sampling period)")
    steps = np.diff(t)
    if np.max(np.abs(steps - dt)) > 1e-6 * dt + 1e-12:
        k = int(np.argmax(np.abs(steps - dt)))
        raise ScaraError(f"traj.t must be sampled every dt = {dt:g} s; t[{k + 1}] - t[{k}] = {steps[k]:g} s")
    if not _clearly_reachable(x, p):
        ok = is_reachable(x, p)
        if not ok.all():
            k = int(np.argmin(ok))
            check_reachable(x[k], p, label=f"reference sample {k} (t = {t[k]:.4g} s)")
            raise UnreachableError(f"reference sample {k} (t = {t[k]:.4g} s) is unreachable")  # pragma: no cover
    return t, x, xd, xdd, dt


@kernel
def _first_unclear_sample(x, r2_lo, r2_hi, d0, tol):
    """First sample of ``x`` (N, >=3) whose reachability is not clear from squared radii, or -1."""
    for k in range(x.shape[0]):
        r2 = x[k, 0] * x[k, 0] + x[k, 1] * x[k, 1]
        d3 = d0 - x[k, 2]
        if not (r2 >= r2_lo and r2 <= r2_hi and d3 >= -tol and d3 <= d0 + tol):
            return k
    return -1


def _clearly_reachable(x, p) -> bool:
    """One compiled pass over a finite reference ``x`` (N, 4): True if every sample is inside the workspace
    with a margin of 1e-9 m on the radius (squared radii, no square root). False means "look closer": the
    caller then runs :func:`~scara.kinematics.is_reachable`, which decides (and names the first bad sample).
    The stroke test is the same arithmetic as ``is_reachable``'s."""
    tol = 1e-12
    r2_lo = (p.r_min + 1e-9) ** 2 if p.r_min - tol > 0.0 else -1.0
    r2_hi = (p.r_max - 1e-9) ** 2
    return _first_unclear_sample(x, r2_lo, r2_hi, p.d0, tol) < 0


def _series(n: int, count: int):
    """``count`` (n, 4) arrays and one (n,) array, C-contiguous slices of one allocation: a block this large
    is backed by huge pages where the system allows it, which saves thousands of page faults per run."""
    buf = np.empty(n * (4 * count + 1))
    return [buf[4 * n * i:4 * n * (i + 1)].reshape(n, 4) for i in range(count)] + [buf[4 * n * count:]]


def _diag_gain(value, name: str, default) -> np.ndarray:
    """A diagonal gain given as a scalar, a (4,) vector or a diagonal (4, 4) matrix; checked positive."""
    if value is None:
        value = default
    arr = np.asarray(value, dtype=float) if not isinstance(value, str) else None
    if arr is None or arr.shape not in ((), (4,), (4, 4)):
        raise ShapeError(f"{name} must be a number, a (4,) vector or a diagonal (4, 4) matrix, got {value!r}")
    if arr.shape == (4, 4):
        off = arr - np.diag(np.diag(arr))
        if np.any(off != 0):
            raise ScaraError(f"{name} must be diagonal (one gain per operational component); its largest "
                             f"off-diagonal entry is {np.max(np.abs(off)):g}")
        arr = np.diag(arr)
    arr = np.broadcast_to(arr, (4,)).astype(float).copy()
    if not np.all(np.isfinite(arr)):
        raise ScaraError(f"{name} = {arr.tolist()} must be finite")
    if np.any(arr <= 0):
        i = int(np.argmin(arr))
        raise ScaraError(f"{name} must be positive definite: its {COMPONENTS[i]} entry is {arr[i]:g} (must be > 0)")
    return arr


def _number(value):
    """``float(value)`` for a real scalar, else NaN (so that the caller's range check reports it)."""
    try:
        return float(value) if np.ndim(value) == 0 and not isinstance(value, (str, bool)) else math.nan
    except (TypeError, ValueError):
        return math.nan


def _damping(damping, damping_threshold):
    lam = _number(damping)
    if not math.isfinite(lam) or lam < 0:
        raise ScaraError(f"damping = {damping!r} must be a finite number >= 0 (m)")
    if damping_threshold is None:
        return lam * lam, 0.0
    thr = _number(damping_threshold)
    if not math.isfinite(thr) or thr <= 0:
        raise ScaraError(f"damping_threshold = {damping_threshold!r} must be a finite manipulability > 0 (m^2)")
    return lam * lam, thr


def _max_error(max_error):
    v = _number(max_error)
    if not math.isfinite(v) or v <= 0:
        raise ScaraError(f"max_error = {max_error!r} must be a finite number > 0 (m or rad)")
    return v


def _elbow(traj) -> int:
    """The trajectory's elbow if it carries one (``scara.trajectory`` does), else the SPEC's -1."""
    elbow = getattr(traj, "elbow", -1)
    return 1 if elbow == 1 else -1


def start_configuration(traj, p: ScaraParams | None = None) -> np.ndarray:
    """SPEC section 4 start: the inverse kinematics of the first reference sample with ``theta2 < 0``.

    (``theta4`` follows from the reference's ``phi``, which the scenario sets to ``theta1 + theta2``, so it is 0.)
    A trajectory planned with ``elbow=+1`` (attribute ``traj.elbow``) starts on that elbow instead.

    >>> from scara import reference_trajectory                   # doctest: +SKIP
    >>> start_configuration(reference_trajectory()).round(4)     # doctest: +SKIP
    """
    p = _params(p)
    if not hasattr(traj, "x"):
        raise ScaraError(f"traj must have an attribute x (N, 4); {type(traj).__name__} has none")
    x0 = as_array(np.asarray(traj.x, dtype=float)[0], "traj.x[0]", (4,))
    return ikine(x0, p, elbow=_elbow(traj))


def _start(traj, x0, q0, p):
    if q0 is None:
        return ikine(x0, p, elbow=_elbow(traj))
    return as_array(q0, "q0", (4,)).copy()


def _check_initial_error(x0_ref, q0, p, kept, max_err):
    x0 = np.empty(4)
    pose_kernel(q0, p.a1, p.a2, p.d0, x0)
    e0 = np.abs(x0_ref - x0) * kept
    if e0.max() > max_err:
        i = int(np.argmax(e0))
        raise ScaraError(f"the start configuration q0 leaves an initial {COMPONENTS[i]} error of {e0[i]:.4g}, "
                         f"above max_error = {max_err:g}; pass a larger max_error to allow it")


def _fail(info, t, result, what):
    status, k = int(info[0]), int(info[1])
    cause = _CAUSES[status]
    extra = ""
    if status == 2:
        i = int(np.argmax(np.abs(result.e[k]) * result.kept))
        extra = f" ({COMPONENTS[i]} error {result.e[k, i]:.4g})"
    elif status == 3:
        extra = f" (theta2 = {result.q[k, 1]:.6g} rad, manipulability {result.w[k]:.3g} m^2)"
    exc = UnstableError(f"{what} diverged at t = {t[k]:.4f} s (step {k}): {cause}{extra}")
    cut = slice(0, k + 1)
    exc.result = ClikResult(result.t[cut], result.q[cut], result.qd[cut],
                            None if result.qdd is None else result.qdd[cut], result.x[cut], result.e[cut],
                            result.w[cut], result.x_d[cut], result.method, result.kept, result.dt, result.gains,
                            result.run_time)
    exc.time = float(t[k])
    exc.cause = cause
    return exc


# --------------------------------------------------------------------------------------------------
# public functions
# --------------------------------------------------------------------------------------------------
def transpose_stability(traj, K=None, p: ScaraParams | None = None, elbow: int | None = None) -> TransposeStability:
    """Discrete-time stability margin of the Jacobian-transpose CLIK along ``traj`` (Euler, ``dt = traj.dt``).

    One Euler step maps the error as ``e_{k+1} = (I - dt J_A J_A^T K) e_k + (reference terms)``; with ``K``
    diagonal positive, ``J_A J_A^T K`` has real positive eigenvalues ``mu_i(q)`` (it is similar to
    ``K^1/2 J_A J_A^T K^1/2``), so the step is stable iff ``dt mu_max(q) < 2`` at every configuration met.
    The configurations are those of the reference (inverse kinematics with the given ``elbow``, by default the
    trajectory's own, ``traj.elbow``, or -1 as in SPEC section 4). ``K`` as in :func:`clik` (default the seed).

    Returns a :class:`TransposeStability`; raises :class:`UnreachableError` for an unreachable reference.

    >>> from scara import reference_trajectory                     # doctest: +SKIP
    >>> transpose_stability(reference_trajectory()).scale_limit    # doctest: +SKIP
    """
    p = _params(p)
    t, x, _, _, dt = _trajectory(traj, False, p)
    K = _diag_gain(K, "K", SEED_K)
    mu = np.empty(len(t))
    elbow = _elbow(traj) if elbow is None else elbow
    if isinstance(elbow, bool) or elbow not in (1, -1):
        raise ScaraError(f"elbow = {elbow!r} is not allowed: use +1 (sin theta2 >= 0) or -1 (sin theta2 <= 0)")
    _transpose_rate_kernel(x, K, p.a1, p.a2, float(elbow), mu)
    k = int(np.argmax(mu))
    limit = 2.0 / dt
    return TransposeStability(t, mu, float(mu[k]), float(t[k]), limit, float(limit / mu[k]))


def clik(traj, method: str = "inverse", K=None, *, q0=None, p: ScaraParams | None = None,
         damping: float = 0.0, damping_threshold: float | None = None, relaxed=None, k0: float | None = None,
         objective: str = "sin2", max_error: float = 0.1, check_stability: bool = True) -> ClikResult:
    """First-order closed-loop inverse kinematics along ``traj`` with Euler's rule (SPEC sections 4-5).

    Parameters
    ----------
    traj : object with ``t`` (N,), ``x``, ``xd`` (N, 4) and ``dt``
        The operational reference ``x_d = [px, py, pz, phi]`` (m, rad) and its velocity, sampled every ``dt``
        (e.g. :func:`scara.reference_trajectory`).
    method : {"inverse", "transpose", "pseudoinverse"}
        ``qd = J^-1 (xd_d + K e)``; ``qd = J^T K e``; or ``qd = J_r^+ (xd_r + K_r e_r) + (I - J_r^+ J_r) qd_0``.
    K : number, (4,) or diagonal (4, 4), optional
        Positive gains on ``e = x_d - x_e``; default the seed ``diag(400, 400, 400, 100)``.
    q0 : (4,), optional
        Start configuration; default the SPEC's (inverse kinematics of ``x_d(0)`` with ``theta2 < 0``).
        Any other start leaves an initial error that the loop removes.
    p : ScaraParams, optional
    damping : float, default 0
        Damped least squares (inverse and pseudo-inverse): ``J^* = J^T (J J^T + lambda^2 I)^-1`` with
        ``lambda = damping``. Trades exactness for bounded joint velocities near a singularity.
    damping_threshold : float, optional
        If given, the damping is applied only where the manipulability ``w`` falls below it, growing as
        ``lambda^2 = damping^2 (1 - (w / threshold)^2)``; elsewhere the exact inverse is used.
    relaxed : {"x", "y", "z", "phi"} or 0..3, optional
        The component the pseudo-inverse leaves free (default ``"x"``). Only for ``method="pseudoinverse"``.
    k0 : float, optional
        Null-space gain of the pseudo-inverse, ``qd_0 = k0 grad w_0`` (1/s; default 1, 0 turns the term off).
    objective : {"sin2", "manipulability"}
        ``w_0 = sin^2 theta2`` (smooth, default) or ``w = a1 a2 |sin theta2|``.
    max_error : float, default 0.1
        A run whose error on a controlled component exceeds this (m or rad) is stopped as divergent.
    check_stability : bool, default True
        Refuse, before running, gains past the discrete-time stability limit (see the module notes).
        With ``False`` the run goes ahead and a divergence is caught while it happens.

    Returns
    -------
    ClikResult
        ``t, q, qd, x, e, w`` (``qdd`` is None) and :meth:`ClikResult.summary`.

    Raises
    ------
    ScaraError
        Unknown method, relaxed component or objective; non-positive or non-finite gains; bad damping;
        ``dt <= 0``; a start leaving an error above ``max_error``.
    ShapeError, NonFiniteError
        Malformed or non-finite trajectory arrays.
    UnreachableError
        A reference sample outside the workspace (the message names the first).
    UnstableError
        Gains past the stability limit (message gives the limit), or a run that diverged (message gives the
        time and the cause; the run up to that point is attached as ``exc.result``).

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> t = np.arange(0, 1.0, 1e-3)
    >>> x = np.tile([0.4, 0.2, 0.5, -1.0], (len(t), 1)); x[:, 0] += 0.05 * t
    >>> xd = np.zeros_like(x); xd[:, 0] = 0.05
    >>> r = clik(SimpleNamespace(t=t, x=x, xd=xd, dt=1e-3), "inverse")
    >>> bool(r.summary()["max_position_error"] < 1e-6)
    True
    """
    p = _params(p)
    if method not in _METHOD_CODE:
        raise ScaraError(f"method = {method!r} is unknown; choose one of {', '.join(METHODS)}")
    if objective not in _OBJECTIVE_CODE:
        raise ScaraError(f"objective = {objective!r} is unknown; choose one of {', '.join(OBJECTIVES)}")
    kept = np.ones(4)
    if method == "pseudoinverse":
        r = "x" if relaxed is None else relaxed
        idx = COMPONENTS.index(r) if r in COMPONENTS else (int(r) if isinstance(r, (int, np.integer))
                                                           and not isinstance(r, bool) and 0 <= r < 4 else None)
        if idx is None:
            raise ScaraError(f"relaxed = {relaxed!r} is not an operational component; use one of "
                             f"{', '.join(COMPONENTS)} (or 0..3)")
        kept[idx] = 0.0
        k0 = 1.0 if k0 is None else k0
    elif relaxed is not None:
        raise ScaraError(f"relaxed = {relaxed!r} only applies to method='pseudoinverse' (got {method!r})")
    k0v = 0.0 if k0 is None else _number(k0)
    if not math.isfinite(k0v) or k0v < 0:
        raise ScaraError(f"k0 = {k0!r} (null-space gain) must be a finite number >= 0")
    K = _diag_gain(K, "K", SEED_K)
    lam2, w_thr = _damping(damping, damping_threshold)
    max_err = _max_error(max_error)
    t, x_d, xd_d, _, dt = _trajectory(traj, False, p)
    q_start = _start(traj, x_d[0], q0, p)
    _check_initial_error(x_d[0], q_start, p, kept, max_err)

    if check_stability:
        if method in ("inverse", "pseudoinverse"):
            bad = (K * dt >= 2.0) & (kept > 0)
            if bad.any():
                i = int(np.argmax(bad))
                raise UnstableError(
                    f"K[{COMPONENTS[i]}] = {K[i]:g} is past the discrete-time stability limit of the {method} CLIK: "
                    f"Euler's step gives e_(k+1) = (1 - dt K) e_k, stable only for K < 2 / dt = {2.0 / dt:g} 1/s")
            if method == "pseudoinverse" and k0v > 0:
                curv = 2.0 if objective == "sin2" else p.a1 * p.a2  # max |d^2 w_0 / d theta2^2|
                k0_lim = 2.0 / (dt * curv)
                if k0v >= k0_lim:
                    raise UnstableError(
                        f"k0 = {k0v:g} is past the null-space stability limit: the gradient step on theta2 needs "
                        f"dt k0 |d^2 w_0/d theta2^2| < 2, i.e. k0 < {k0_lim:g} for objective {objective!r}")
        else:
            elbow = -1 if q_start[1] < 0 else 1
            if _transpose_check_kernel(x_d, K, p.a1, p.a2, float(elbow), 2.0 / dt) >= 0:
                st = transpose_stability(traj, K, p, elbow=elbow)
                raise UnstableError(
                    f"K = [{', '.join(f'{k:.5g}' for k in K)}] is past the discrete-time stability limit of the transpose CLIK: along the "
                    f"reference the largest eigenvalue of J J^T K reaches {st.mu_max:.5g} 1/s (t = {st.t_worst:.3f} s), "
                    f"but Euler's step needs it below 2 / dt = {st.limit:g} 1/s; scale K by less than "
                    f"{st.scale_limit:.5g}")

    n = len(t)
    q, qd, x, e, w = _series(n, 4)
    q[0] = q_start
    info = np.zeros(2, np.int64)
    t0 = time.perf_counter()
    _clik1_kernel(x_d, xd_d, dt, _METHOD_CODE[method], K, kept, lam2, w_thr, k0v, _OBJECTIVE_CODE[objective],
                  p.a1, p.a2, p.d0, max_err, q, qd, x, e, w, info)
    run_time = time.perf_counter() - t0
    gains = {"K": K, "damping": math.sqrt(lam2), "damping_threshold": w_thr or None}
    if method == "pseudoinverse":
        gains.update(k0=k0v, objective=objective, relaxed=COMPONENTS[int(np.argmin(kept))])
    res = ClikResult(t, q, qd, None, x, e, w, x_d, method, kept.astype(bool), dt, gains, run_time)
    if info[0] != 0:
        raise _fail(info, t, res, f"the {method} CLIK")
    return res


def second_order_gains(K=SEED_K):
    """``(K_P, K_D) = (K^2, 2 K)``: the second-order CLIK with both discrete poles at ``z = 1 - K dt``.

    Euler's rule turns ``ed_dot + K_D ed + K_P e = 0`` into ``z^2 - (2 - dt K_D) z + (1 - dt K_D + dt^2 K_P)``,
    which with this choice is ``(z - (1 - K dt))^2``: critically damped in discrete time, at the same pole as
    the first-order inverse CLIK with gain ``K``.
    """
    K = _diag_gain(K, "K", SEED_K)
    return K**2, 2.0 * K


def clik2(traj, K_P=None, K_D=None, *, q0=None, qd0=None, p: ScaraParams | None = None, damping: float = 0.0,
          damping_threshold: float | None = None, max_error: float = 0.1,
          check_stability: bool = True) -> ClikResult:
    """Second-order CLIK: joint positions, velocities and accelerations that track ``traj`` (Euler's rule).

    ``qdd = J_A^-1 (xdd_d + K_D (xd_d - J_A qd) + K_P e - Jd_A qd)`` (Siciliano et al., section 3.7.4), so that
    ``e`` obeys ``ed_dot + K_D ed + K_P e = 0``; then ``q_{k+1} = q_k + dt qd_k`` and
    ``qd_{k+1} = qd_k + dt qdd_k``. Its output is the joint reference of the control chapter.

    Parameters
    ----------
    traj : object with ``t``, ``x``, ``xd``, ``xdd`` and ``dt`` (see :func:`clik`)
    K_P, K_D : number, (4,) or diagonal (4, 4), optional
        Default :func:`second_order_gains` of the seed ``K``: ``K_P = diag(1.6e5, 1.6e5, 1.6e5, 1e4)`` 1/s^2,
        ``K_D = diag(800, 800, 800, 200)`` 1/s, double discrete pole at ``1 - K dt`` (0.6 and 0.9). With Euler
        a constant reference acceleration ``A`` leaves a lag ``dt A / omega`` (``omega = K_D / 2``): about
        2.5 micrometres per m/s^2 with these gains.
    q0, qd0 : (4,), optional
        Start; default the SPEC configuration and ``qd0 = J_A^-1 xd_d(0)``.
    p, damping, damping_threshold, max_error, check_stability : see :func:`clik`

    Returns
    -------
    ClikResult
        with ``qdd`` filled and ``method = "second_order"``.

    Raises
    ------
    The errors of :func:`clik`; :class:`UnstableError` when a component's gains put a discrete pole on or
    outside the unit circle (``dt K_P < K_D`` and ``2 dt K_D - dt^2 K_P < 4`` are required).
    """
    p = _params(p)
    KP0, KD0 = second_order_gains()
    K_P = _diag_gain(K_P, "K_P", KP0)
    K_D = _diag_gain(K_D, "K_D", KD0)
    lam2, w_thr = _damping(damping, damping_threshold)
    max_err = _max_error(max_error)
    t, x_d, xd_d, xdd_d, dt = _trajectory(traj, True, p)
    q_start = _start(traj, x_d[0], q0, p)
    kept = np.ones(4)
    _check_initial_error(x_d[0], q_start, p, kept, max_err)
    if qd0 is None:
        J = np.empty((4, 4))
        jacobian_kernel(q_start, p.a1, p.a2, J)
        if abs(np.linalg.det(J)) <= _SINGULAR_TOL:
            raise UnstableError(f"the start configuration q0 = {q_start.tolist()} is singular; give qd0 explicitly")
        qd_start = np.linalg.solve(J, xd_d[0])
    else:
        qd_start = as_array(qd0, "qd0", (4,)).copy()
    if check_stability:
        a, b = dt * K_D, dt * dt * K_P
        bad = ~((b < a) & (2 * a - b < 4))
        if bad.any():
            i = int(np.argmax(bad))
            rho = max(abs(z) for z in np.roots([1.0, -(2.0 - a[i]), 1.0 - a[i] + b[i]]))
            raise UnstableError(
                f"K_P[{COMPONENTS[i]}] = {K_P[i]:g}, K_D[{COMPONENTS[i]}] = {K_D[i]:g} are past the discrete-time "
                f"stability limit of the second-order CLIK: Euler's step puts a pole at |z| = {rho:.4g} >= 1; it "
                f"needs dt K_P < K_D < 2 / dt + dt K_P / 2 (here {b[i] / dt:g} < {K_D[i]:g} < {(4 + b[i]) / (2 * dt):g} fails)")

    n = len(t)
    q, qd, qdd, x, e, w = _series(n, 5)
    q[0] = q_start
    qd[0] = qd_start
    info = np.zeros(2, np.int64)
    t0 = time.perf_counter()
    _clik2_kernel(x_d, xd_d, xdd_d, dt, K_P, K_D, lam2, w_thr, p.a1, p.a2, p.d0, max_err, q, qd, qdd, x, e, w, info)
    run_time = time.perf_counter() - t0
    gains = {"K_P": K_P, "K_D": K_D, "damping": math.sqrt(lam2), "damping_threshold": w_thr or None}
    res = ClikResult(t, q, qd, qdd, x, e, w, x_d, "second_order", kept.astype(bool), dt, gains, run_time)
    if info[0] != 0:
        raise _fail(info, t, res, "the second-order CLIK")
    return res


def dexterity(q, objective: str = "sin2", p: ScaraParams | None = None):
    """The dexterity measure the pseudo-inverse climbs: ``sin^2 theta2`` or ``w = a1 a2 |sin theta2|``.

    ``q`` (4,) or (N, 4); returns a float or (N,).
    """
    p = _params(p)
    if objective not in _OBJECTIVE_CODE:
        raise ScaraError(f"objective = {objective!r} is unknown; choose one of {', '.join(OBJECTIVES)}")
    q = as_array(q, "q", (4,), allow_batch=True)
    s2 = np.sin(q[..., 1])
    val = s2**2 if objective == "sin2" else p.a1 * p.a2 * np.abs(s2)
    return float(val) if np.ndim(val) == 0 else val
