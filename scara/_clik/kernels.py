"""The compiled loops and solves of the CLIK (see :mod:`scara._compile`): the first-order loop (4.4), (4.8),
(4.13), (4.15), the second-order loop (4.16), the structured solves of ``J_A s = v`` they call each step, the
largest eigenvalue of ``J_A J_A^T K`` along a reference (4.12) and the one-pass reachability test of a reference;
then the checks made before a run (the stability limits (4.6), (4.12), (4.14), (4.19), the initial error, the
damping's ceiling) and the diagnosis of a run that stopped. Those return codes and numbers: :func:`scara.clik`
and :func:`scara.clik2` word them into their refusals, and the CLIK panel's page program
(:mod:`scara.programs.clik`) calls the same kernels.

The closed-form kinematics of :mod:`scara.kinematics` run inside (its planar building blocks, inlined); the joint
values, the Jacobian's entries and the step's vectors live in scalars and 4-tuples, so nothing is allocated per
step and no 4x4 matrix is formed.
"""
from __future__ import annotations

import math

from .._compile import kernel
from ..kinematics import (elbow_cosine, planar_det, planar_jacobian, planar_jacobian_at, planar_jacobian_dot,
                          planar_position, planar_trig)
from .records import (MAX_DAMPING_REACH, METHOD_INVERSE, METHOD_PSEUDOINVERSE, METHOD_TRANSPOSE, OBJECTIVE_SIN2,
                      STATUS_DONE, STATUS_ERROR_BOUND, STATUS_NONFINITE, STATUS_SINGULAR, _SINGULAR_TOL)


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


# --------------------------------------------------------------------------------------------------
# the checks run before a loop, and the diagnosis of a loop that stopped: one definition each, called by
# :func:`~scara.clik` / :func:`~scara.clik2` (which word the refusals) and by the chapter's page program
# --------------------------------------------------------------------------------------------------
#: codes of :func:`_first_order_check`
CHECK_STABLE = 0
CHECK_GAIN = 1
CHECK_K0 = 2
CHECK_TRANSPOSE = 3
CHECK_TRANSPOSE_NONFINITE = 4
#: entries of the ``res`` vector the check kernels fill (the numbers their refusals name)
RES_COMPONENT = 0
RES_LIMIT = 1
RES_K0_LIMIT = 2
RES_MU_MAX = 3
RES_WORST = 4
RES_SCALE = 5
RES_KP = 6
RES_KD = 7
RES_RHO = 8
RES_LOW = 9
RES_HIGH = 10
RES_ERROR = 11
#: the length of ``res``
RES_SIZE = 12


@kernel
def _gain_limit_component(K, keep, dt):
    """The first kept component ``i`` whose gain breaks ``dt K_i < 2``, the limit (4.6) of Euler's step
    ``e_(k+1) = (1 - dt K) e_k`` of the inverse and the pseudo-inverse, or -1."""
    for i in range(4):
        if K[i] * dt >= 2.0 and keep[i] > 0.0:
            return i
    return -1


@kernel
def _null_space_limit(objective, dt, a1, a2):
    """The largest null-space gain (4.14): ``k0 < 2 / (dt max |d^2 w_0 / d theta2^2|)``, the curvature being 2
    for ``w_0 = sin^2 theta2`` and ``a1 a2`` for the manipulability."""
    curv = 2.0 if objective == OBJECTIVE_SIN2 else a1 * a2
    return 2.0 / (dt * curv)


@kernel
def _transpose_worst(xr, K, a1, a2, elbow):
    """``(k, mu_max)``: the first sample where ``mu_max(J_A J_A^T K)`` (4.12) peaks along the reference ``xr``
    (N, 4) and its value, as :func:`_transpose_rate_kernel` computes it at each sample, with nothing
    allocated; ``mu_max`` is the first non-finite value met, if any (and ``k`` its sample)."""
    kd = (K[0], K[1], K[3])
    sk = (math.sqrt(K[0]), math.sqrt(K[1]), math.sqrt(K[3]))
    best = -math.inf
    kb = 0
    for k in range(xr.shape[0]):
        mu = max(_sym3_max_eig(_transpose_block(xr[k, 0], xr[k, 1], a1, a2, elbow, kd, sk)), K[2])
        if not math.isfinite(mu):
            return k, mu
        if mu > best:
            best = mu
            kb = k
    return kb, best


@kernel
def _first_order_check(method, K, keep, dt, k0, objective, xr, a1, a2, theta2_start, res):
    """The discrete-time stability limits of a first-order run, checked before it: ``dt K_i < 2`` on every
    kept component for the inverse and the pseudo-inverse (4.6), ``k0`` below :func:`_null_space_limit` for a
    pseudo-inverse with a null-space term (4.14), and ``dt mu_max < 2`` along the reference ``xr`` for the
    transpose (4.12), on the elbow of the start (``theta2_start < 0``: elbow -1).

    ``method`` and ``objective`` are the loop's codes, ``K`` and ``keep`` (4,) arrays. Returns
    :data:`CHECK_STABLE`, or the limit broken (:data:`CHECK_GAIN`, :data:`CHECK_K0`, :data:`CHECK_TRANSPOSE`,
    :data:`CHECK_TRANSPOSE_NONFINITE`) with the numbers its refusal names written into ``res``
    (:data:`RES_SIZE`): the component, ``2 / dt``, the ``k0`` limit, ``mu_max``, the sample where it peaks and
    the scale ``2 / (dt mu_max)`` by which ``K`` may be multiplied.
    """
    limit = 2.0 / dt
    res[RES_LIMIT] = limit
    if method != METHOD_TRANSPOSE:
        i = _gain_limit_component(K, keep, dt)
        if i >= 0:
            res[RES_COMPONENT] = i
            return CHECK_GAIN
        if method == METHOD_PSEUDOINVERSE and k0 > 0.0:
            k0_lim = _null_space_limit(objective, dt, a1, a2)
            res[RES_K0_LIMIT] = k0_lim
            if k0 >= k0_lim:
                return CHECK_K0
        return CHECK_STABLE
    elbow = -1.0 if theta2_start < 0.0 else 1.0
    if _transpose_check_kernel(xr, K, a1, a2, elbow, limit) < 0:
        return CHECK_STABLE
    kw, mu = _transpose_worst(xr, K, a1, a2, elbow)
    res[RES_MU_MAX] = mu
    res[RES_WORST] = kw
    if not math.isfinite(mu):
        return CHECK_TRANSPOSE_NONFINITE
    res[RES_SCALE] = limit / mu
    return CHECK_TRANSPOSE


@kernel
def _quadratic_pole_radius(a, b):
    """The largest modulus of the roots of ``z^2 - (2 - a) z + (1 - a + b)``, the characteristic polynomial
    (4.19) of one component of the second-order law with ``a = dt K_D``, ``b = dt^2 K_P``: ``(|2 - a| +
    sqrt(disc)) / 2`` for real roots (``disc = a^2 - 4 b >= 0``), else ``sqrt(1 - a + b)``."""
    c1 = 2.0 - a
    c0 = 1.0 - a + b
    disc = c1 * c1 - 4.0 * c0
    if disc >= 0.0:
        return 0.5 * (abs(c1) + math.sqrt(disc))
    return math.sqrt(c0)


@kernel(light=True)
def _second_order_check(K_P, K_D, dt, res):
    """Jury's test of (4.19) on each component: with ``a = dt K_D``, ``b = dt^2 K_P`` both poles lie inside the
    unit circle iff ``b < a`` and ``2 a - b < 4``. Returns the first component that fails, or -1; for it
    ``res`` receives ``K_P``, ``K_D``, the largest pole modulus (:func:`_quadratic_pole_radius`) and the bounds
    ``dt K_P`` and ``2 / dt + dt K_P / 2`` of ``K_D``."""
    for i in range(4):
        a = dt * K_D[i]
        b = dt * dt * K_P[i]
        if not (b < a and 2 * a - b < 4):
            res[RES_COMPONENT] = i
            res[RES_KP] = K_P[i]
            res[RES_KD] = K_D[i]
            res[RES_RHO] = _quadratic_pole_radius(a, b)
            res[RES_LOW] = b / dt
            res[RES_HIGH] = (4 + b) / (2 * dt)
            return i
    return -1


@kernel(light=True)
def _initial_error_check(x0_ref, q0, a1, a2, d0, keep, max_err, res):
    """The kept component ``i`` with the largest initial error ``|x_d(0) - x_e(q0)|`` (1.5) when that error is
    above ``max_err`` (the error is written into ``res[RES_ERROR]``), or -1: a start the loop would stop at
    at once."""
    sc = planar_trig(q0[0], q0[1])
    x0, x1 = planar_position(sc, a1, a2)
    x = (x0, x1, d0 - q0[2], q0[0] + q0[1] + q0[3])
    worst = -1.0
    iw = 0
    for i in range(4):
        ei = abs(x0_ref[i] - x[i]) * keep[i]
        if ei > worst:
            worst = ei
            iw = i
    if worst > max_err:
        res[RES_ERROR] = worst
        return iw
    return -1


@kernel(light=True)
def _damping_ceiling(r_max):
    """The largest damping ``lambda`` (m) of (4.15): :data:`MAX_DAMPING_REACH` times the reach ``r_max``."""
    return MAX_DAMPING_REACH * r_max


@kernel
def _bound_component(e, k, keep):
    """The kept component with the largest error ``|e[k, i]|`` at the step ``k`` where a loop stopped on its
    error bound (the first one on a tie)."""
    best = -1.0
    ib = 0
    for i in range(4):
        v = abs(e[k, i]) * keep[i]
        if v > best:
            best = v
            ib = i
    return ib
