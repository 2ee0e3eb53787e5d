"""The public functions of the CLIK: :func:`clik` (the first-order methods (4.4), (4.8), (4.13), with the damped
least squares (4.15)), :func:`clik2` (the second-order law (4.16)), :func:`transpose_stability` (the margin
(4.12)), :func:`second_order_gains`, :func:`start_configuration` and :func:`dexterity`, and the steps of a run:
check the inputs, find the start, check the stability limits, run the compiled loop, build the result."""
from __future__ import annotations

import math
import time

import numpy as np

from ..errors import ScaraError, ShapeError, as_array, check_angles, check_finite_result, check_flag
from ..gains import gain_vector
from ..kinematics import _elbow_sign, check_regular, geometry, ikine, jacobian_kernel
from ..params import ScaraParams
from .checks import (_check_initial_error, _check_q0, _elbow, _first_order_options, _damping, _max_error,
                     _objective, _params, _trajectory)
from .kernels import _clik1_kernel, _clik2_kernel
from .records import (COMPONENTS, SEED_K, STATUS_DONE, _first_order_law, _reference, _second_order_law,
                      _series)
from .result import ClikResult, TransposeStability, _fail
from .stability import _check_first_order_stability, _check_second_order_stability, _transpose_margin

__all__ = ["clik", "clik2", "start_configuration", "transpose_stability", "second_order_gains", "dexterity"]


# --------------------------------------------------------------------------------------------------
# the steps of a run
# --------------------------------------------------------------------------------------------------
def _start(traj, q0, p):
    """The start configuration: ``q0`` if given (checked by :func:`~.checks._check_q0`), else
    :func:`start_configuration`."""
    return start_configuration(traj, p) if q0 is None else _check_q0(q0, p)


def _reference_and_start(traj, need_acc, q0, p, kept, max_err):
    """Check the trajectory and find the start configuration (refusing one whose initial error on a kept
    component is above ``max_err``); return ``(t, x_d, xd_d, xdd_d or None, dt, q_start)``."""
    t, x_d, xd_d, xdd_d, dt = _trajectory(traj, need_acc, p)
    q_start = _start(traj, q0, p)
    _check_initial_error(x_d[0], q_start, p, kept, max_err)
    return t, x_d, xd_d, xdd_d, dt, q_start


def _start_velocity(q_start, xd0, qd0, p):
    """A copy of ``qd0`` if given, else ``J_A^-1 xd_d(0)`` at the start configuration (a singular start is
    refused by :func:`~scara.kinematics.check_regular`)."""
    if qd0 is not None:
        return as_array(qd0, "qd0", (4,)).copy()
    check_regular(q_start, p, what="the start configuration")
    J = np.empty((4, 4))
    jacobian_kernel(q_start, p.a1, p.a2, J)
    return np.linalg.solve(J, xd0)


def _run_loop(loop, ref, law, p, out):
    """Run a compiled loop; return its ``info = [status, step]`` and the seconds it took."""
    info = np.zeros(2, np.int64)
    t0 = time.perf_counter()
    loop(ref, law, geometry(p), out, info)
    return info, time.perf_counter() - t0


def _build_result(t, out, x_d, method, kept, dt, gains, info, elapsed) -> ClikResult:
    """The :class:`ClikResult` of a run; raises the :class:`UnstableError` of :func:`~.result._fail` if it
    stopped."""
    second_order = method == "second_order"
    res = ClikResult(t, out.q, out.qd, out.qdd if second_order else None, out.x, out.e, out.w, x_d, method,
                     kept.astype(bool), dt, gains, elapsed)
    if info[0] != STATUS_DONE:
        raise _fail(info, res, "the second-order CLIK" if second_order else f"the {method} CLIK")
    return res


# --------------------------------------------------------------------------------------------------
# public functions
# --------------------------------------------------------------------------------------------------
def start_configuration(traj, p: ScaraParams | None = None) -> np.ndarray:
    """The start of chapter 4: the inverse kinematics of the first reference sample with ``theta2 < 0``.

    (``theta4`` follows from the reference's ``phi``, which the scenario sets to ``theta1 + theta2``, so it is 0.)
    A trajectory planned with ``elbow=+1`` (attribute ``traj.elbow``, checked to be +1 or -1) starts on that elbow
    instead, and the inverse kinematics (1.9), (1.10) use the trajectory's own parameters ``traj.params`` unless
    ``p`` is given (a ``p`` that disagrees with them is refused).

    >>> from scara import reference_trajectory                   # doctest: +SKIP
    >>> start_configuration(reference_trajectory()).round(4)     # doctest: +SKIP
    """
    p = _params(traj, p)
    if not hasattr(traj, "x"):
        raise ScaraError(f"traj must have an attribute x (N, 4); {type(traj).__name__} has none")
    x = as_array(traj.x, "traj.x", (4,), allow_batch=True)
    if x.ndim != 2 or len(x) == 0:
        raise ShapeError(f"traj.x must have shape (N, 4) with N >= 1, got {x.shape}")
    return ikine(x[0], p, elbow=_elbow(traj))


def transpose_stability(traj, K=None, p: ScaraParams | None = None, elbow: int | None = None) -> TransposeStability:
    """Discrete-time stability margin of the Jacobian-transpose CLIK along ``traj`` (Euler, ``dt = traj.dt``).

    One Euler step maps the error as ``e_{k+1} = (I - dt J_A J_A^T K) e_k + (reference terms)``; with ``K``
    diagonal positive, ``J_A J_A^T K`` has real positive eigenvalues ``mu_i(q)`` (it is similar to
    ``K^1/2 J_A J_A^T K^1/2``), so the step is stable iff ``dt mu_max(q) < 2`` at every configuration met.
    The configurations are those of the reference (inverse kinematics with the given ``elbow``, by default the
    trajectory's own, ``traj.elbow``, or -1 as in the reference scenario of chapter 3) (4.12). ``K`` as in
    :func:`clik` (default the seed); ``p`` as in :func:`clik` (default ``traj.params``).

    Returns a :class:`TransposeStability`; raises :class:`UnreachableError` for an unreachable reference.

    >>> from scara import reference_trajectory                     # doctest: +SKIP
    >>> transpose_stability(reference_trajectory()).scale_limit    # doctest: +SKIP
    """
    p = _params(traj, p)
    t, x, _, _, dt = _trajectory(traj, False, p)
    K = gain_vector(K, "K", default=SEED_K, labels=COMPONENTS)
    return _transpose_margin(t, x, dt, K, p, _elbow(traj) if elbow is None else _elbow_sign(elbow))


def clik(traj, method: str = "inverse", K=None, *, q0=None, p: ScaraParams | None = None,
         damping: float = 0.0, damping_threshold: float | None = None, relaxed=None, k0: float | None = None,
         objective: str = "sin2", max_error: float = 0.1, check_stability: bool = True) -> ClikResult:
    """First-order closed-loop inverse kinematics along ``traj`` with Euler's rule (chapter 4).

    Parameters
    ----------
    traj : object with ``t`` (N,), ``x``, ``xd`` (N, 4) and ``dt``
        The operational reference ``x_d = [px, py, pz, phi]`` (m, rad) and its velocity, sampled every ``dt``
        (e.g. :func:`scara.reference_trajectory`); a planned trajectory's ``params`` and ``elbow`` are used.
    method : {"inverse", "transpose", "pseudoinverse"}
        ``qd = J^-1 (xd_d + K e)``; ``qd = J^T K e``; or ``qd = J_r^+ (xd_r + K_r e_r) + (I - J_r^+ J_r) qd_0``.
    K : number, (4,) or diagonal (4, 4), optional
        Positive gains on ``e = x_d - x_e``; default the seed ``diag(400, 400, 400, 100)``.
    q0 : (4,), optional
        Start configuration; default :func:`start_configuration` (inverse kinematics of ``x_d(0)`` on the
        trajectory's elbow, ``theta2 < 0`` unless it was planned with ``elbow=+1``).
        Any other start leaves an initial error that the loop removes. Its ``d3`` must lie in the quill's stroke
        ``p.d3_min <= d3 <= p.d3_max`` (:class:`UnreachableError` otherwise) and its angles within ``MAX_ANGLE``
        rad (:data:`scara.errors.MAX_ANGLE`).
    p : ScaraParams, optional
        Default the trajectory's own ``traj.params`` (``ScaraParams()`` for a trajectory that carries none);
        a ``p`` that disagrees with ``traj.params`` is refused.
    damping : float, default 0
        Damped least squares (4.15), inverse and pseudo-inverse only: ``J^* = J^T (J J^T + lambda^2 I)^-1`` with
        ``lambda = damping`` (m), ``0 <= damping <= MAX_DAMPING_REACH (a1 + a2)`` (10 m for the arm of the
        course). Trades exactness for bounded joint velocities near a singularity.
    damping_threshold : float, optional
        If given, the damping is applied only where the manipulability ``w`` falls below it, growing as
        ``lambda^2 = damping^2 (1 - (w / threshold)^2)``; elsewhere the exact inverse is used (inverse and
        pseudo-inverse only).
    relaxed : {"x", "y", "z", "phi"} or 0..3, optional
        The component the pseudo-inverse leaves free (default ``"x"``). Only for ``method="pseudoinverse"``.
    k0 : float, optional
        Null-space gain of the pseudo-inverse, ``qd_0 = k0 grad w_0`` (4.14) (1/s; default 1, 0 turns the term
        off). Only for ``method="pseudoinverse"``.
    objective : {"sin2", "manipulability"}
        ``w_0 = sin^2 theta2`` (smooth, default) or ``w = a1 a2 |sin theta2|``; another than the default only for
        ``method="pseudoinverse"``.
    max_error : float, default 0.1
        A run whose error on a controlled component exceeds this (m or rad) is stopped as divergent.
    check_stability : bool, default True
        Refuse, before running, gains past the discrete-time stability limit (see the module notes).
        With ``False`` the run goes ahead and a divergence is caught while it happens.

    Returns
    -------
    ClikResult
        ``t, q, qd, x, e, w`` (``qdd`` is None) and :meth:`ClikResult.summary`; its arrays are its own (no
        memory shared with ``traj`` or the options).

    Raises
    ------
    ScaraError
        Unknown method, relaxed component or objective; an option the method does not use (``relaxed``, ``k0``
        or ``objective`` other than the inverse's or transpose's defaults, ``damping`` or ``damping_threshold``
        with the transpose); non-positive or non-finite gains; a damping that is negative, not finite or above
        ``MAX_DAMPING_REACH (a1 + a2)``; ``dt <= 0``; a start leaving an error above ``max_error``;
        ``check_stability`` not a bool; a ``p`` that disagrees with ``traj.params``.
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
    p = _params(traj, p)
    kept, k0v, lam2, w_thr = _first_order_options(method, relaxed, k0, objective, damping, damping_threshold, p)
    K = gain_vector(K, "K", default=SEED_K, labels=COMPONENTS)
    max_err = _max_error(max_error)
    check_stability = check_flag(check_stability, "check_stability")
    t, x_d, xd_d, _, dt, q_start = _reference_and_start(traj, False, q0, p, kept, max_err)
    law = _first_order_law(dt, method, K, kept, lam2, w_thr, k0v, objective, max_err)
    if check_stability:
        _check_first_order_stability(method, law, objective, t, x_d, q_start, p)
    out = _series(len(t), second_order=False)
    out.q[0] = q_start
    info, elapsed = _run_loop(_clik1_kernel, _reference(x_d, xd_d), law, p, out)
    gains = {"K": K, "damping": math.sqrt(lam2), "damping_threshold": w_thr or None}
    if method == "pseudoinverse":
        gains.update(k0=k0v, objective=objective, relaxed=COMPONENTS[int(np.argmin(kept))])
    return _build_result(t, out, x_d, method, kept, dt, gains, info, elapsed)


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
        Start; default :func:`start_configuration` and ``qd0 = J_A^-1 xd_d(0)`` (refused, with an
        :class:`UnstableError`, at a singular start: give ``qd0`` there).
    p, damping, damping_threshold, max_error, check_stability : see :func:`clik`

    Returns
    -------
    ClikResult
        with ``qdd`` filled and ``method = "second_order"``.

    Raises
    ------
    The errors of :func:`clik` (its option checks aside: every option applies here); :class:`UnstableError` when a component's gains put a discrete pole on or
    outside the unit circle (``dt K_P < K_D`` and ``2 dt K_D - dt^2 K_P < 4`` are required).
    """
    p = _params(traj, p)
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
    info, elapsed = _run_loop(_clik2_kernel, _reference(x_d, xd_d, xdd_d), law, p, out)
    gains = {"K_P": K_P, "K_D": K_D, "damping": math.sqrt(lam2), "damping_threshold": w_thr or None}
    return _build_result(t, out, x_d, "second_order", kept, dt, gains, info, elapsed)


def dexterity(q, objective: str = "sin2", p: ScaraParams | None = None):
    """The dexterity measure the pseudo-inverse climbs: ``sin^2 theta2`` or ``w = a1 a2 |sin theta2|``.

    ``q`` (4,) or (N, 4); returns a float or (N,).
    """
    p = ScaraParams.resolve(p)
    objective = _objective(objective)
    q = check_angles(as_array(q, "q", (4,), allow_batch=True))
    s2 = np.sin(q[..., 1])
    val = s2**2 if objective == "sin2" else p.a1 * p.a2 * np.abs(s2)
    return float(val) if np.ndim(val) == 0 else val
