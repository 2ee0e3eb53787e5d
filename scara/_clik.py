"""Closed-loop inverse kinematics (CLIK): turn an operational-space trajectory into joint trajectories.

Four algorithms (chapter 4; Siciliano et al. 2009, section 3.7), all discretised with
Euler's rule at the trajectory's sampling period ``dt``:

* **Jacobian inverse** (4.4): ``qd = J_A^-1 (xd_d + K e)``. The error obeys ``ed = -K e``. Near a
  singularity the inverse can be replaced by the damped least-squares inverse
  ``J^* = J^T (J J^T + lambda^2 I)^-1`` (damped least squares (4.15); Siciliano et al. 2009, section 3.5), with
  a constant damping or one that grows only when the manipulability falls below a threshold.
* **Jacobian transpose** (4.8): ``qd = J_A^T K e``. No inversion; the error converges for a constant
  reference and lags a moving one.
* **Pseudo-inverse** with one operational component relaxed (x by default): the arm becomes functionally
  redundant, ``qd = J_r^+ (xd_r + K_r e_r) + (I - J_r^+ J_r) qd_0`` (4.13) with ``qd_0 = k_0 grad w_0(q)`` (4.14)
  climbing a dexterity measure (``w_0 = sin^2 theta2`` by default, or the manipulability ``w``).
* **Second order** (4.16; Siciliano et al. 2009, section 3.7.4, with the analytic Jacobian):
  ``qdd = J_A^-1 (xdd_d + K_D ed + K_P e - Jd_A qd)``, giving the joint positions, velocities and
  accelerations the control chapter tracks.

The loops run in compiled kernels (see :mod:`scara._compile`) with the closed-form kinematics of
:mod:`scara.kinematics` inside (its planar building blocks, inlined); nothing is allocated per step. A loop
takes its data as named records, each declared once with one packer: the reference (:class:`Reference`), the
law's settings (:class:`FirstOrderLaw`, :class:`SecondOrderLaw`), the arm's lengths
(:class:`~scara.kinematics.Geometry`) and the arrays it fills (:class:`Series`); it reports how it ended with
the ``STATUS_*`` codes. Every run checks its settings first
(positive, finite gains; the discrete-time stability limits derived below; a reachable reference) and stops
with an :class:`~scara.errors.UnstableError` giving the time and the cause if it diverges anyway.

Discrete-time stability (Euler, sampling period ``dt``). Linearising one step,
``e_{k+1} = e_k + (x_d,k+1 - x_d,k) - J_A (q_{k+1} - q_k)``:

* inverse (4.6): ``e_{k+1} = (I - dt K) e_k + O(dt^2)``, stable iff ``0 < dt K_i < 2`` for every component;
* transpose: ``e_{k+1} = (I - dt J_A J_A^T K) e_k + ...``. ``J_A J_A^T K`` is similar to the symmetric
  ``K^1/2 J_A J_A^T K^1/2`` (and to ``J_A^T K J_A``, the matrix of the joint-space iteration), so its
  eigenvalues ``mu_i(q)`` are real and positive and the step is stable iff ``dt mu_max(q) < 2`` at every
  configuration met (4.12). :func:`transpose_stability` evaluates ``mu_max`` along the reference;
* second order, per component with ``a = dt K_D``, ``b = dt^2 K_P``: the characteristic polynomial (4.19)
  ``z^2 - (2 - a) z + (1 - a + b)`` has both roots inside the unit circle iff ``b < a`` and ``2 a - b < 4``
  (Jury's test); with ``K_D = 2 omega``, ``K_P = omega^2`` both poles sit at ``z = 1 - omega dt``.
"""
from __future__ import annotations

import math
import time
from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from ._compile import kernel
from .errors import (ScaraError, ShapeError, UnreachableError, UnstableError, as_array, check_angles,
                     check_finite_result, check_flag)
from .gains import gain_vector
from .kinematics import (_elbow_sign, check_reachable, elbow_cosine, geometry, ikine, is_reachable, jacobian_kernel,
                         planar_det, planar_jacobian, planar_jacobian_at, planar_jacobian_dot, planar_position,
                         planar_trig, pose_kernel)
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
    "MAX_DAMPING_REACH",
]

#: the largest damping ``lambda`` of (4.15), as a multiple of the reach ``a1 + a2``: ``damping <= 10 (a1 + a2)``
#: (10 m for the arm of the course). The entries of ``J_A J_A^T`` are at most about ``(a1 + a2)^2``, so a larger
#: ``lambda^2`` only freezes the arm (and ``lambda`` of 1e300 overflows ``lambda^2`` to inf)
MAX_DAMPING_REACH = 10.0

#: the first-order methods of :func:`clik`
METHODS = ("inverse", "transpose", "pseudoinverse")
#: names of the operational components, in the order of ``x_e``
COMPONENTS = ("x", "y", "z", "phi")
#: the seed gains of chapter 4 for the inverse and transpose methods (1/s for the inverse)
SEED_K = (400.0, 400.0, 400.0, 100.0)
#: dexterity measures the pseudo-inverse's null-space term can climb
OBJECTIVES = ("sin2", "manipulability")

#: codes of the methods and objectives inside the compiled loops
METHOD_INVERSE = 0
METHOD_TRANSPOSE = 1
METHOD_PSEUDOINVERSE = 2
OBJECTIVE_SIN2 = 0
OBJECTIVE_MANIPULABILITY = 1
_METHOD_CODE = {"inverse": METHOD_INVERSE, "transpose": METHOD_TRANSPOSE, "pseudoinverse": METHOD_PSEUDOINVERSE}
_OBJECTIVE_CODE = {"sin2": OBJECTIVE_SIN2, "manipulability": OBJECTIVE_MANIPULABILITY}

#: status codes a compiled loop writes into ``info[0]``
STATUS_DONE = 0
STATUS_NONFINITE = 1
STATUS_ERROR_BOUND = 2
STATUS_SINGULAR = 3
_CAUSES = {
    STATUS_NONFINITE: "a value became NaN or infinite",
    STATUS_ERROR_BOUND: "the tracking error exceeded max_error",
    STATUS_SINGULAR: "the Jacobian became singular",
}
_SINGULAR_TOL = 1e-12  # |det J_A| (m^2) or Cholesky pivot below which the solve is refused


# --------------------------------------------------------------------------------------------------
# named data of the compiled loops: each record is declared once and built by one packer (see "packers")
# --------------------------------------------------------------------------------------------------
#: the reference the loop tracks: ``x``, ``xd`` (N, 4) and, for the second-order law, ``xdd`` (N, 4)
Reference = namedtuple("Reference", "x xd xdd")
#: the settings of the first-order laws (4.4), (4.8), (4.13), (4.15)
FirstOrderLaw = namedtuple("FirstOrderLaw", "dt method K keep lam0sq w_thr k0 objective max_err")
#: the settings of the second-order law (4.16)
SecondOrderLaw = namedtuple("SecondOrderLaw", "dt K_P K_D lam0sq w_thr max_err")
#: the arrays a loop fills: ``q, qd, qdd, x, e`` (N, 4) and ``w`` (N,); ``qdd`` is empty for a first-order run
Series = namedtuple("Series", "q qd qdd x e w")


# --------------------------------------------------------------------------------------------------
# compiled kernels
# --------------------------------------------------------------------------------------------------
@kernel
def _solve_kept(J, keep, lam2, v, g2):
    """``(ok, u)`` with ``u = g + J_r^T (J_r J_r^T + lam2 I)^-1 (v - J_r g)`` and ``g = [0, g2, 0, 0]``;
    ``ok`` is False if the system is singular.

    ``J = (J_11, J_12, J_21, J_22)`` are the non-constant entries of ``J_A`` (1.6); ``keep`` and ``v`` are
    4-tuples (tuples, not arrays, so that a call counts no references). ``J_r`` holds the rows of ``J_A``
    with ``keep[i] = 1`` (a dropped row acts as a zero row, its multiplier
    is 0). With ``lam2 = 0`` this is the pseudo-inverse solution plus the null-space projection of ``g``,
    ``J_r^+ v + (I - J_r^+ J_r) g`` (4.13) (all rows kept and ``g = 0``: ``J^-1 v``); with ``lam2 > 0`` the
    damped least-squares solution (4.15). Row z of ``J_A`` is ``[0, 0, -1, 0]`` and row phi ``[1, 1, 0, 1]``,
    so z decouples and the x, y, phi block is a 3x3 symmetric positive definite system, solved here by an
    unrolled Cholesky factorisation.
    """
    j11, j12, j21, j22 = J
    kx, ky, kz, kp = keep
    v0, v1, v2, v3 = v
    fail = (False, (0.0, 0.0, 0.0, 0.0))
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
        return fail
    l00 = math.sqrt(a00)
    l10 = a01 / l00
    l20 = a02 / l00
    d11 = a11 - l10 * l10
    if not d11 > _SINGULAR_TOL:
        return fail
    l11 = math.sqrt(d11)
    l21 = (a12 - l20 * l10) / l11
    d22 = a22 - l20 * l20 - l21 * l21
    if not d22 > _SINGULAR_TOL:
        return fail
    l22 = math.sqrt(d22)
    z0 = b0 / l00
    z1 = (b1 - l10 * z0) / l11
    z2 = (b2 - l20 * z0 - l21 * z1) / l22
    y2 = z2 / l22
    y1 = (z1 - l21 * y2) / l11
    y0 = (z0 - l10 * y1 - l20 * y2) / l00
    return True, (j11 * y0 + j21 * y1 + y2, g2 + j12 * y0 + j22 * y1 + y2, -kz * v2 / (1.0 + lam2), y2)


@kernel
def _solve_exact(J, v):
    """``(ok, J_A^-1 v)`` in closed form from the entries ``J`` of (1.6); ``ok`` is False if singular.

    The x, y rows give a 2x2 system in ``theta1, theta2`` with determinant ``-a1 a2 sin theta2`` (1.7); then
    ``d3_dot = -v_z`` and ``theta4_dot = v_phi - theta1_dot - theta2_dot``.
    """
    j11, j12, j21, j22 = J
    v0, v1, v2, v3 = v
    det = planar_det(J)
    if not abs(det) > _SINGULAR_TOL:
        return False, (0.0, 0.0, 0.0, 0.0)
    u1 = (j22 * v0 - j12 * v1) / det
    u2 = (j11 * v1 - j21 * v0) / det
    return True, (u1, u2, -v2, v3 - u1 - u2)


@kernel
def _track_step(k, qk, xr, arm, bounds, x, e, w):
    """Pose ``x_e`` (1.5), error ``e = x_d - x_e`` (4.3) and manipulability ``w = |det J_A|`` (1.7), (2.4) at step
    ``k`` from the joint values ``qk`` (a 4-tuple), written into row ``k`` of ``x``, ``e``, ``w``.

    Returns ``(status, sc, J, ek)``: the :func:`_error_status` of the error against ``bounds``, the step's
    trigonometric values ``sc = planar_trig(theta1, theta2)``, the entries ``J`` of ``J_A`` (1.6) and the error
    as a 4-tuple.
    """
    sc = planar_trig(qk[0], qk[1])
    J = planar_jacobian(sc, arm.a1, arm.a2)
    x0, x1 = planar_position(sc, arm.a1, arm.a2)
    x2 = arm.d0 - qk[2]
    x3 = qk[0] + qk[1] + qk[3]
    _set_row(x, k, (x0, x1, x2, x3))
    w[k] = abs(planar_det(J))
    ek = (xr[k, 0] - x0, xr[k, 1] - x1, xr[k, 2] - x2, xr[k, 3] - x3)
    _set_row(e, k, ek)
    return _error_status(ek, bounds), sc, J, ek


@kernel
def _error_bounds(keep, max_err):
    """The bound on each error component: ``max_err`` where ``keep[i] > 0``, infinite on a relaxed one."""
    return (max_err if keep[0] > 0.0 else math.inf, max_err if keep[1] > 0.0 else math.inf,
            max_err if keep[2] > 0.0 else math.inf, max_err if keep[3] > 0.0 else math.inf)


@kernel
def _error_status(ek, bounds):
    """:data:`STATUS_NONFINITE` if the error ``ek`` holds a NaN or an infinity, :data:`STATUS_ERROR_BOUND` if a
    component is above its bound (:func:`_error_bounds`), else :data:`STATUS_DONE`."""
    e0, e1, e2, e3 = ek
    if not (math.isfinite(e0) and math.isfinite(e1) and math.isfinite(e2) and math.isfinite(e3)):
        return STATUS_NONFINITE
    if abs(e0) > bounds[0] or abs(e1) > bounds[1] or abs(e2) > bounds[2] or abs(e3) > bounds[3]:
        return STATUS_ERROR_BOUND
    return STATUS_DONE


@kernel
def _set_row(a, k, s):
    """``a[k] = s`` for a 4-tuple ``s``."""
    a[k, 0] = s[0]
    a[k, 1] = s[1]
    a[k, 2] = s[2]
    a[k, 3] = s[3]


@kernel
def _euler(qk, dt, s):
    """Euler's rule (4.2): ``qk + dt s`` for 4-tuples."""
    return qk[0] + dt * s[0], qk[1] + dt * s[1], qk[2] + dt * s[2], qk[3] + dt * s[3]


@kernel
def _solution_status(ok, s):
    """:data:`STATUS_SINGULAR` if the solve refused, :data:`STATUS_NONFINITE` if ``s`` holds a NaN or an
    infinity, else :data:`STATUS_DONE`."""
    if not ok:
        return STATUS_SINGULAR
    if not (math.isfinite(s[0]) and math.isfinite(s[1]) and math.isfinite(s[2]) and math.isfinite(s[3])):
        return STATUS_NONFINITE
    return STATUS_DONE


@kernel
def _solve_step(J, keep, lam2, v, g2, exact):
    """``(status, s)``: the rates ``s`` solving ``J_A s = v`` for one step, by the closed-form inverse where
    ``exact`` is set and there is no damping (``lam2 = 0``), else by :func:`_solve_kept` (pseudo-inverse or
    damped least squares, null-space rate ``g2``); ``status`` from :func:`_solution_status`."""
    if exact and lam2 == 0.0:
        ok, s = _solve_exact(J, v)
    else:
        ok, s = _solve_kept(J, keep, lam2, v, g2)
    return _solution_status(ok, s), s


@kernel
def _stop(info, status, k):
    """Record why and where the loop stopped: ``info = [status, k]``."""
    info[0] = status
    info[1] = k


@kernel
def _damping_at(lam0sq, w_thr, wk):
    """The damping ``lambda^2`` of (4.15) at manipulability ``wk``: ``lam0sq``, or with a threshold
    ``lam0sq (1 - (w / w_thr)^2)`` below it and 0 above."""
    if w_thr > 0.0:
        return lam0sq * (1.0 - (wk / w_thr) ** 2) if wk < w_thr else 0.0
    return lam0sq


@kernel
def _null_space_rate(objective, k0, t2, a1, a2):
    """``k0 dw_0/dtheta2``, the only non-zero entry of ``qd_0 = k0 grad w_0`` (4.14): ``w_0 = sin^2 theta2``
    or the manipulability ``a1 a2 |sin theta2|``."""
    if objective == OBJECTIVE_SIN2:
        return k0 * math.sin(2.0 * t2)
    return k0 * a1 * a2 * math.cos(t2) * (1.0 if math.sin(t2) >= 0.0 else -1.0)


@kernel
def _clik1_kernel(ref, law, arm, out, info):
    """First-order CLIK loop (inverse (4.4), transpose (4.8), pseudo-inverse (4.13)), Euler's rule
    ``q_{k+1} = q_k + dt qd_k`` (4.2).

    ``ref`` a :class:`Reference`, ``law`` a :class:`FirstOrderLaw`, ``arm`` a :class:`Geometry`, ``out`` a
    :class:`Series` whose ``q[0]`` holds the start configuration. The damping ``law.lam0sq`` (lambda^2)
    applies in full, or scaled by ``1 - (w / w_thr)^2`` below ``law.w_thr`` when that is > 0. ``info`` (2,)
    receives ``[status, step]`` (the ``STATUS_*`` constants). The joint values, the Jacobian's entries and the
    step's vectors live in scalars: nothing is allocated and no 4x4 matrix is formed.
    """
    # the records' arrays are read once here: reading them inside the loop would count references every step
    xr, vr = ref.x, ref.xd
    q, qd, x, e, w = out.q, out.qd, out.x, out.e, out.w
    K0, K1, K2, K3 = law.K[0], law.K[1], law.K[2], law.K[3]
    keep = (law.keep[0], law.keep[1], law.keep[2], law.keep[3])
    bounds = _error_bounds(keep, law.max_err)
    method = law.method
    n = xr.shape[0]
    qk = (q[0, 0], q[0, 1], q[0, 2], q[0, 3])
    _stop(info, STATUS_DONE, n - 1)
    for k in range(n):
        _set_row(q, k, qk)
        status, sc, J, ek = _track_step(k, qk, xr, arm, bounds, x, e, w)
        if status != STATUS_DONE:
            _stop(info, status, k)
            return
        j11, j12, j21, j22 = J
        e0, e1, e2, e3 = ek
        if method == METHOD_TRANSPOSE:  # qd = J^T K e (the zero entries of J_A dropped)
            s = (j11 * K0 * e0 + j21 * K1 * e1 + K3 * e3, j12 * K0 * e0 + j22 * K1 * e1 + K3 * e3, -K2 * e2, K3 * e3)
            status = _solution_status(True, s)
        else:
            v = (vr[k, 0] + K0 * e0, vr[k, 1] + K1 * e1, vr[k, 2] + K2 * e2, vr[k, 3] + K3 * e3)
            g2 = 0.0
            if method == METHOD_PSEUDOINVERSE and law.k0 != 0.0:
                g2 = _null_space_rate(law.objective, law.k0, qk[1], arm.a1, arm.a2)
            status, s = _solve_step(J, keep, _damping_at(law.lam0sq, law.w_thr, w[k]), v, g2,
                                    method == METHOD_INVERSE)
        if status != STATUS_DONE:
            _stop(info, status, k)
            return
        _set_row(qd, k, s)
        qk = _euler(qk, law.dt, s)


@kernel
def _clik2_kernel(ref, law, arm, out, info):
    """Second-order CLIK loop (4.16), ``Jd qd`` as in (4.18):
    ``qdd_k = J^-1 (xdd_d + K_D ed + K_P e - Jd qd)`` (or its damped form),
    then Euler ``q_{k+1} = q_k + dt qd_k``, ``qd_{k+1} = qd_k + dt qdd_k``.

    Arguments as for :func:`_clik1_kernel` with a :class:`SecondOrderLaw`; ``out.q[0]`` and ``out.qd[0]``
    hold the start. ``Jd qd`` comes from :func:`~scara.kinematics.planar_jacobian_dot` with the step's
    trigonometric values, no more trigonometric calls.
    """
    # the records' arrays are read once here (see _clik1_kernel)
    xr, vr, ar = ref.x, ref.xd, ref.xdd
    q, qd, qdd, x, e, w = out.q, out.qd, out.qdd, out.x, out.e, out.w
    KP, KD = law.K_P, law.K_D
    n = xr.shape[0]
    keep = (1.0, 1.0, 1.0, 1.0)
    bounds = _error_bounds(keep, law.max_err)
    qk = (q[0, 0], q[0, 1], q[0, 2], q[0, 3])
    uk = (qd[0, 0], qd[0, 1], qd[0, 2], qd[0, 3])
    _stop(info, STATUS_DONE, n - 1)
    for k in range(n):
        _set_row(q, k, qk)
        _set_row(qd, k, uk)
        u1, u2, u3, u4 = uk
        status, sc, J, ek = _track_step(k, qk, xr, arm, bounds, x, e, w)
        if status != STATUS_DONE:
            _stop(info, status, k)
            return
        j11, j12, j21, j22 = J
        jd11, jd12, jd21, jd22 = planar_jacobian_dot(sc, arm.a1, arm.a2, u1, u1 + u2)
        # x_e velocity J_A qd (4.1) and the term Jd_A qd
        xd = (j11 * u1 + j12 * u2, j21 * u1 + j22 * u2, -u3, u1 + u2 + u4)
        jdq_x = jd11 * u1 + jd12 * u2
        jdq_y = jd21 * u1 + jd22 * u2
        v = (ar[k, 0] + KD[0] * (vr[k, 0] - xd[0]) + KP[0] * ek[0] - jdq_x,
             ar[k, 1] + KD[1] * (vr[k, 1] - xd[1]) + KP[1] * ek[1] - jdq_y,
             ar[k, 2] + KD[2] * (vr[k, 2] - xd[2]) + KP[2] * ek[2],
             ar[k, 3] + KD[3] * (vr[k, 3] - xd[3]) + KP[3] * ek[3])
        status, s = _solve_step(J, keep, _damping_at(law.lam0sq, law.w_thr, w[k]), v, 0.0, True)
        if status != STATUS_DONE:
            _stop(info, status, k)
            return
        _set_row(qdd, k, s)
        qk = _euler(qk, law.dt, uk)
        uk = _euler(uk, law.dt, s)


@kernel
def _sym3_max_eig(S):
    """Largest eigenvalue of the symmetric 3x3 matrix ``S = (s00, s01, s02, s11, s12, s22)``, in closed form
    (trigonometric solution of the cubic)."""
    s00, s01, s02, s11, s12, s22 = S
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
def _ik_sc12(px, py, a1, a2, elbow):
    """``(s12, c12)``, the sine and cosine of ``theta1 + theta2`` at the inverse-kinematics configuration
    (1.9), (1.10) of the horizontal position ``(px, py)``, computed without any angle.

    ``cos theta2`` from (1.9), ``sin theta2 = elbow sqrt(1 - cos^2)``; with ``alpha = a1 c2 + a2`` and
    ``beta = a1 s2`` (``alpha^2 + beta^2 = r^2``), ``c12 = (alpha p_x + beta p_y) / r^2`` and
    ``s12 = (beta p_x - alpha p_y) / r^2``.
    """
    r2 = px * px + py * py
    c2 = min(1.0, max(-1.0, elbow_cosine(px, py, a1, a2)))
    s2 = elbow * math.sqrt(1.0 - c2 * c2)
    if r2 > 1e-24:
        al = a1 * c2 + a2
        be = a1 * s2
        return (be * px - al * py) / r2, (al * px + be * py) / r2
    return 0.0, 1.0  # folded arm on the joint-1 axis: theta1 is free, any direction will do


@kernel
def _transpose_block(px, py, a1, a2, elbow, kd, sk):
    """``S = K^1/2 J_3 J_3^T K^1/2`` as ``(s00, s01, s02, s11, s12, s22)``, with ``J_3`` the rows x, y, phi of
    ``J_A`` (1.6) over ``theta1, theta2, theta4`` at the inverse-kinematics configuration of ``(px, py)``;
    ``kd = (K_x, K_y, K_phi)`` and ``sk = (sqrt K_x, sqrt K_y, sqrt K_phi)`` (tuples, so that a call counts no
    references)."""
    s12, c12 = _ik_sc12(px, py, a1, a2, elbow)
    j11, j12, j21, j22 = planar_jacobian_at(px, py, s12, c12, a2)
    return (kd[0] * (j11 * j11 + j12 * j12), sk[0] * sk[1] * (j11 * j21 + j12 * j22), sk[0] * sk[2] * (j11 + j12),
            kd[1] * (j21 * j21 + j22 * j22), sk[1] * sk[2] * (j21 + j22), 3.0 * kd[2])


@kernel
def _transpose_rate_kernel(xr, K, a1, a2, elbow, out):
    """``out[k] = mu_max(J_A J_A^T K)`` at the inverse-kinematics configuration of every reference sample.

    The z row of ``J_A`` only involves ``d3`` and gives the eigenvalue ``K_z``; the x, y, phi rows give the
    symmetric block ``S`` of :func:`_transpose_block`, whose largest eigenvalue is found in closed form. The
    caller has checked that every sample is reachable.
    """
    kd = (K[0], K[1], K[3])
    sk = (math.sqrt(K[0]), math.sqrt(K[1]), math.sqrt(K[3]))
    for k in range(xr.shape[0]):
        out[k] = max(_sym3_max_eig(_transpose_block(xr[k, 0], xr[k, 1], a1, a2, elbow, kd, sk)), K[2])


@kernel
def _transpose_check_kernel(xr, K, a1, a2, elbow, limit):
    """First sample where ``mu_max(J_A J_A^T K) >= limit``, or -1: the fast test run before every transpose CLIK.

    The trace of ``S`` bounds its largest eigenvalue (all are >= 0), so the closed-form eigenvalue is only
    computed where the trace reaches the limit.
    """
    if K[2] >= limit:
        return 0
    kd = (K[0], K[1], K[3])
    sk = (math.sqrt(K[0]), math.sqrt(K[1]), math.sqrt(K[3]))
    for k in range(xr.shape[0]):
        S = _transpose_block(xr[k, 0], xr[k, 1], a1, a2, elbow, kd, sk)
        if S[0] + S[3] + S[5] >= limit and _sym3_max_eig(S) >= limit:
            return k
    return -1


# --------------------------------------------------------------------------------------------------
# packers: the one place each record of the compiled loops is built
# --------------------------------------------------------------------------------------------------
_NO_ROWS = np.empty((0, 4))


def _reference(x_d, xd_d, xdd_d=None) -> Reference:
    """The :class:`Reference` record (``xdd`` empty for a first-order run)."""
    return Reference(x_d, xd_d, _NO_ROWS if xdd_d is None else xdd_d)


def _first_order_law(dt, method, K, kept, lam2, w_thr, k0, objective, max_err) -> FirstOrderLaw:
    """The :class:`FirstOrderLaw` record from checked settings (``method`` and ``objective`` by name)."""
    return FirstOrderLaw(float(dt), _METHOD_CODE[method], np.ascontiguousarray(K, float),
                         np.ascontiguousarray(kept, float), float(lam2), float(w_thr), float(k0),
                         _OBJECTIVE_CODE[objective], float(max_err))


def _second_order_law(dt, K_P, K_D, lam2, w_thr, max_err) -> SecondOrderLaw:
    """The :class:`SecondOrderLaw` record from checked settings."""
    return SecondOrderLaw(float(dt), np.ascontiguousarray(K_P, float), np.ascontiguousarray(K_D, float),
                          float(lam2), float(w_thr), float(max_err))


def _series(n: int, second_order: bool) -> Series:
    """The :class:`Series` a run fills, as C-contiguous slices of one allocation: a block this large is backed
    by huge pages where the system allows it, which saves thousands of page faults per run."""
    count = 5 if second_order else 4
    buf = np.empty(n * (4 * count + 1))
    q, qd, *rest = [buf[4 * n * i:4 * n * (i + 1)].reshape(n, 4) for i in range(count)]
    qdd = rest.pop(0) if second_order else _NO_ROWS
    x, e = rest
    return Series(q, qd, qdd, x, e, buf[4 * n * count:])


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
        given, settle = settle, _number(settle)
        if not (0.0 <= settle < self.t[-1] - self.t[0]):
            raise ScaraError(f"settle = {given!r} s must be a number and lie in [0, {self.t[-1] - self.t[0]:g}) s, the run's length")
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
def _first_unclear_sample(x, r2_lo, r2_hi, d0, d3_lo, d3_hi):
    """First sample of ``x`` (N, >=3) whose reachability is not clear from squared radii and the stroke
    ``d3_lo <= d0 - p_z <= d3_hi``, or -1."""
    for k in range(x.shape[0]):
        r2 = x[k, 0] * x[k, 0] + x[k, 1] * x[k, 1]
        d3 = d0 - x[k, 2]
        if not (r2 >= r2_lo and r2 <= r2_hi and d3 >= d3_lo and d3 <= d3_hi):
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
    return _first_unclear_sample(x, r2_lo, r2_hi, p.d0, p.d3_min - tol, p.d3_max + tol) < 0


def _number(value):
    """``float(value)`` for a real scalar, else NaN (so that the caller's range check reports it)."""
    try:
        return float(value) if np.ndim(value) == 0 and not isinstance(value, (str, bool)) else math.nan
    except (TypeError, ValueError):
        return math.nan


def _damping(damping, damping_threshold, p):
    lam = _number(damping)
    if not math.isfinite(lam) or lam < 0:
        raise ScaraError(f"damping = {damping!r} must be a finite number >= 0 (m)")
    lam_max = MAX_DAMPING_REACH * p.r_max
    if lam > lam_max:
        raise ScaraError(f"damping = {lam:g} m is above the largest damping accepted, {MAX_DAMPING_REACH:g} times the "
                         f"reach a1 + a2: {lam_max:g} m (a larger lambda only freezes the arm)")
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
    """The trajectory's elbow if it carries one (``scara.trajectory`` does), else -1, the elbow of the
    reference scenario (chapter 3)."""
    elbow = getattr(traj, "elbow", -1)
    return 1 if np.ndim(elbow) == 0 and not isinstance(elbow, (str, bytes)) and elbow == 1 else -1


def start_configuration(traj, p: ScaraParams | None = None) -> np.ndarray:
    """The start of chapter 4: the inverse kinematics of the first reference sample with ``theta2 < 0``.

    (``theta4`` follows from the reference's ``phi``, which the scenario sets to ``theta1 + theta2``, so it is 0.)
    A trajectory planned with ``elbow=+1`` (attribute ``traj.elbow``) starts on that elbow instead.

    >>> from scara import reference_trajectory                   # doctest: +SKIP
    >>> start_configuration(reference_trajectory()).round(4)     # doctest: +SKIP
    """
    p = ScaraParams.resolve(p)
    if not hasattr(traj, "x"):
        raise ScaraError(f"traj must have an attribute x (N, 4); {type(traj).__name__} has none")
    x = as_array(traj.x, "traj.x", (4,), allow_batch=True)
    if x.ndim != 2 or len(x) == 0:
        raise ShapeError(f"traj.x must have shape (N, 4) with N >= 1, got {x.shape}")
    x0 = x[0]
    return ikine(x0, p, elbow=_elbow(traj))


def _start(traj, q0, p):
    """The start configuration: ``q0`` if given (checked inside the quill's stroke ``p.d3_min <= d3 <= p.d3_max``
    and within ``MAX_ANGLE`` rad), else :func:`start_configuration`."""
    if q0 is None:
        return start_configuration(traj, p)
    q = check_angles(as_array(q0, "q0", (4,)).copy(), "q0")
    if not p.d3_min <= q[2] <= p.d3_max:
        raise UnreachableError(f"q0[2] = d3 = {q[2]:.10g} m is outside the quill's stroke d3_min = {p.d3_min:g} m <= "
                               f"d3 <= d3_max = {p.d3_max:g} m: a motion cannot start there")
    return q


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
    if status == STATUS_ERROR_BOUND:
        i = int(np.argmax(np.abs(result.e[k]) * result.kept))
        extra = f" ({COMPONENTS[i]} error {result.e[k, i]:.4g})"
    elif status == STATUS_SINGULAR:
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
# the steps of a run
# --------------------------------------------------------------------------------------------------
def _first_order_options(method, relaxed, k0, objective):
    """Check the method, the relaxed component, the null-space gain and the objective of :func:`clik`;
    return the kept-component mask (4,) and the null-space gain ``k0`` as a float."""
    if not isinstance(method, str) or method not in _METHOD_CODE:
        raise ScaraError(f"method = {method!r} is unknown; choose one of {', '.join(METHODS)}")
    if not isinstance(objective, str) or objective not in _OBJECTIVE_CODE:
        raise ScaraError(f"objective = {objective!r} is unknown; choose one of {', '.join(OBJECTIVES)}")
    kept = np.ones(4)
    if method == "pseudoinverse":
        r = "x" if relaxed is None else relaxed
        idx = COMPONENTS.index(r) if isinstance(r, str) and r in COMPONENTS else (int(r) if isinstance(r, (int, np.integer))
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
    return kept, k0v


def _reference_and_start(traj, need_acc, q0, p, kept, max_err):
    """Check the trajectory and find the start configuration (refusing one whose initial error on a kept
    component is above ``max_err``); return ``(t, x_d, xd_d, xdd_d or None, dt, q_start)``."""
    t, x_d, xd_d, xdd_d, dt = _trajectory(traj, need_acc, p)
    q_start = _start(traj, q0, p)
    _check_initial_error(x_d[0], q_start, p, kept, max_err)
    return t, x_d, xd_d, xdd_d, dt, q_start


def _check_first_order_stability(traj, method, law, objective, x_d, q_start, p):
    """Refuse gains past the discrete-time stability limits of the module notes: ``dt K < 2`` for the inverse
    and pseudo-inverse (4.6), ``dt k0 |d^2 w_0 / d theta2^2| < 2`` for the null-space term, and (4.12) for the
    transpose."""
    K, kept, dt, k0v = law.K, law.keep, law.dt, law.k0
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
        return
    elbow = -1 if q_start[1] < 0 else 1
    if _transpose_check_kernel(x_d, K, p.a1, p.a2, float(elbow), 2.0 / dt) >= 0:
        st = transpose_stability(traj, K, p, elbow=elbow)
        raise UnstableError(
            f"K = [{', '.join(f'{k:.5g}' for k in K)}] is past the discrete-time stability limit of the transpose CLIK: along the "
            f"reference the largest eigenvalue of J J^T K reaches {st.mu_max:.5g} 1/s (t = {st.t_worst:.3f} s), "
            f"but Euler's step needs it below 2 / dt = {st.limit:g} 1/s; scale K by less than "
            f"{st.scale_limit:.5g}")


def _check_second_order_stability(K_P, K_D, dt):
    """Refuse gains that put a discrete pole of (4.19) on or outside the unit circle (Jury's test)."""
    a, b = dt * K_D, dt * dt * K_P
    bad = ~((b < a) & (2 * a - b < 4))
    if bad.any():
        i = int(np.argmax(bad))
        rho = max(abs(z) for z in np.roots([1.0, -(2.0 - a[i]), 1.0 - a[i] + b[i]]))
        raise UnstableError(
            f"K_P[{COMPONENTS[i]}] = {K_P[i]:g}, K_D[{COMPONENTS[i]}] = {K_D[i]:g} are past the discrete-time "
            f"stability limit of the second-order CLIK: Euler's step puts a pole at |z| = {rho:.4g} >= 1; it "
            f"needs dt K_P < K_D < 2 / dt + dt K_P / 2 (here {b[i] / dt:g} < {K_D[i]:g} < {(4 + b[i]) / (2 * dt):g} fails)")


def _start_velocity(q_start, xd0, qd0, p):
    """``qd0`` if given, else ``J_A^-1 xd_d(0)`` at the start configuration (refused if singular)."""
    if qd0 is not None:
        return as_array(qd0, "qd0", (4,)).copy()
    J = np.empty((4, 4))
    jacobian_kernel(q_start, p.a1, p.a2, J)
    if abs(np.linalg.det(J)) <= _SINGULAR_TOL:
        raise UnstableError(f"the start configuration q0 = {q_start.tolist()} is singular; give qd0 explicitly")
    return np.linalg.solve(J, xd0)


def _run_loop(loop, ref, law, p, out):
    """Run a compiled loop; return its ``info = [status, step]`` and the seconds it took."""
    info = np.zeros(2, np.int64)
    t0 = time.perf_counter()
    loop(ref, law, geometry(p), out, info)
    return info, time.perf_counter() - t0


def _build_result(t, out, x_d, method, kept, dt, gains, info, run_time, what) -> ClikResult:
    """The :class:`ClikResult` of a run; raises the :class:`UnstableError` of :func:`_fail` if it stopped."""
    qdd = out.qdd if method == "second_order" else None
    res = ClikResult(t, out.q, out.qd, qdd, out.x, out.e, out.w, x_d, method, kept.astype(bool), dt, gains,
                     run_time)
    if info[0] != STATUS_DONE:
        raise _fail(info, t, res, what)
    return res


# --------------------------------------------------------------------------------------------------
# public functions
# --------------------------------------------------------------------------------------------------
def transpose_stability(traj, K=None, p: ScaraParams | None = None, elbow: int | None = None) -> TransposeStability:
    """Discrete-time stability margin of the Jacobian-transpose CLIK along ``traj`` (Euler, ``dt = traj.dt``).

    One Euler step maps the error as ``e_{k+1} = (I - dt J_A J_A^T K) e_k + (reference terms)``; with ``K``
    diagonal positive, ``J_A J_A^T K`` has real positive eigenvalues ``mu_i(q)`` (it is similar to
    ``K^1/2 J_A J_A^T K^1/2``), so the step is stable iff ``dt mu_max(q) < 2`` at every configuration met.
    The configurations are those of the reference (inverse kinematics with the given ``elbow``, by default the
    trajectory's own, ``traj.elbow``, or -1 as in the reference scenario of chapter 3). ``K`` as in :func:`clik`
    (default the seed).

    Returns a :class:`TransposeStability`; raises :class:`UnreachableError` for an unreachable reference.

    >>> from scara import reference_trajectory                     # doctest: +SKIP
    >>> transpose_stability(reference_trajectory()).scale_limit    # doctest: +SKIP
    """
    p = ScaraParams.resolve(p)
    t, x, _, _, dt = _trajectory(traj, False, p)
    K = gain_vector(K, "K", default=SEED_K, labels=COMPONENTS)
    mu = np.empty(len(t))
    elbow = _elbow(traj) if elbow is None else _elbow_sign(elbow)
    _transpose_rate_kernel(x, K, p.a1, p.a2, float(elbow), mu)
    check_finite_result(mu, "largest eigenvalue mu of J_A J_A^T K", K=K)
    k = int(np.argmax(mu))
    limit = 2.0 / dt
    return TransposeStability(t, mu, float(mu[k]), float(t[k]), limit, float(limit / mu[k]))


def clik(traj, method: str = "inverse", K=None, *, q0=None, p: ScaraParams | None = None,
         damping: float = 0.0, damping_threshold: float | None = None, relaxed=None, k0: float | None = None,
         objective: str = "sin2", max_error: float = 0.1, check_stability: bool = True) -> ClikResult:
    """First-order closed-loop inverse kinematics along ``traj`` with Euler's rule (chapter 4).

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
        Start configuration; default :func:`start_configuration` (inverse kinematics of ``x_d(0)`` with ``theta2 < 0``).
        Any other start leaves an initial error that the loop removes. Its ``d3`` must lie in the quill's stroke
        ``p.d3_min <= d3 <= p.d3_max`` (:class:`UnreachableError` otherwise) and its angles within ``MAX_ANGLE``
        rad (:data:`scara.errors.MAX_ANGLE`).
    p : ScaraParams, optional
    damping : float, default 0
        Damped least squares (inverse and pseudo-inverse): ``J^* = J^T (J J^T + lambda^2 I)^-1`` with
        ``lambda = damping`` (m), ``0 <= damping <= MAX_DAMPING_REACH (a1 + a2)`` (10 m for the arm of the
        course). Trades exactness for bounded joint velocities near a singularity.
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
        Unknown method, relaxed component or objective; non-positive or non-finite gains; a damping that is
        negative, not finite or above ``MAX_DAMPING_REACH (a1 + a2)``; ``dt <= 0``; a start leaving an error above
        ``max_error``; ``check_stability`` not a bool.
    ShapeError, NonFiniteError
        Malformed or non-finite trajectory arrays.
    UnreachableError
        A reference sample outside the workspace (the message names the first), or a ``q0`` outside the stroke.
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
    p = ScaraParams.resolve(p)
    kept, k0v = _first_order_options(method, relaxed, k0, objective)
    K = gain_vector(K, "K", default=SEED_K, labels=COMPONENTS)
    lam2, w_thr = _damping(damping, damping_threshold, p)
    max_err = _max_error(max_error)
    check_stability = check_flag(check_stability, "check_stability")
    t, x_d, xd_d, _, dt, q_start = _reference_and_start(traj, False, q0, p, kept, max_err)
    law = _first_order_law(dt, method, K, kept, lam2, w_thr, k0v, objective, max_err)
    if check_stability:
        _check_first_order_stability(traj, method, law, objective, x_d, q_start, p)
    out = _series(len(t), second_order=False)
    out.q[0] = q_start
    info, run_time = _run_loop(_clik1_kernel, _reference(x_d, xd_d), law, p, out)
    gains = {"K": K, "damping": math.sqrt(lam2), "damping_threshold": w_thr or None}
    if method == "pseudoinverse":
        gains.update(k0=k0v, objective=objective, relaxed=COMPONENTS[int(np.argmin(kept))])
    return _build_result(t, out, x_d, method, kept, dt, gains, info, run_time, f"the {method} CLIK")


def second_order_gains(K=SEED_K):
    """``(K_P, K_D) = (K^2, 2 K)``: the second-order CLIK with both discrete poles at ``z = 1 - K dt``.

    Euler's rule turns ``ed_dot + K_D ed + K_P e = 0`` into ``z^2 - (2 - dt K_D) z + (1 - dt K_D + dt^2 K_P)``,
    which with this choice is ``(z - (1 - K dt))^2``: critically damped in discrete time, at the same pole as
    the first-order inverse CLIK with gain ``K``.
    """
    K = gain_vector(K, "K", default=SEED_K, labels=COMPONENTS)
    with np.errstate(over="ignore"):
        K_P = K**2
    check_finite_result(K_P, "K_P = K^2", K=K)
    return K_P, 2.0 * K


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
        Start; default :func:`start_configuration` and ``qd0 = J_A^-1 xd_d(0)``.
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
    p = ScaraParams.resolve(p)
    KP0, KD0 = second_order_gains()
    K_P = gain_vector(K_P, "K_P", default=KP0, labels=COMPONENTS)
    K_D = gain_vector(K_D, "K_D", default=KD0, labels=COMPONENTS)
    lam2, w_thr = _damping(damping, damping_threshold, p)
    max_err = _max_error(max_error)
    check_stability = check_flag(check_stability, "check_stability")
    kept = np.ones(4)
    t, x_d, xd_d, xdd_d, dt, q_start = _reference_and_start(traj, True, q0, p, kept, max_err)
    qd_start = _start_velocity(q_start, xd_d[0], qd0, p)
    if check_stability:
        _check_second_order_stability(K_P, K_D, dt)
    out = _series(len(t), second_order=True)
    out.q[0] = q_start
    out.qd[0] = qd_start
    law = _second_order_law(dt, K_P, K_D, lam2, w_thr, max_err)
    info, run_time = _run_loop(_clik2_kernel, _reference(x_d, xd_d, xdd_d), law, p, out)
    gains = {"K_P": K_P, "K_D": K_D, "damping": math.sqrt(lam2), "damping_threshold": w_thr or None}
    return _build_result(t, out, x_d, "second_order", kept, dt, gains, info, run_time, "the second-order CLIK")


def dexterity(q, objective: str = "sin2", p: ScaraParams | None = None):
    """The dexterity measure the pseudo-inverse climbs: ``sin^2 theta2`` or ``w = a1 a2 |sin theta2|``.

    ``q`` (4,) or (N, 4); returns a float or (N,).
    """
    p = ScaraParams.resolve(p)
    if not isinstance(objective, str) or objective not in _OBJECTIVE_CODE:
        raise ScaraError(f"objective = {objective!r} is unknown; choose one of {', '.join(OBJECTIVES)}")
    q = check_angles(as_array(q, "q", (4,), allow_batch=True))
    s2 = np.sin(q[..., 1])
    val = s2**2 if objective == "sin2" else p.a1 * p.a2 * np.abs(s2)
    return float(val) if np.ndim(val) == 0 else val
