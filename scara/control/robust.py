"""Robust control in joint space (Siciliano et al., sec. 8.5.3), discrete-time at the sampling period.

    u = B_hat y + n_hat(q, qd),    y = qdd_d + K_D qt_dot + K_P qt + w,    qt = q_d - q

``B_hat`` is a constant diagonal estimate of the inertia matrix and ``n_hat = F qd + g_hat(q)`` leaves out the
Coriolis and centrifugal terms and the payload. With ``xi = [qt, qt_dot]`` the error obeys
``xi_dot = H xi + D (eta - w)``, ``H = [[0, I], [-K_P, -K_D]]``, ``D = [0, I]``, where
``eta = (I - B^-1 B_hat) y - B^-1 n_tilde`` gathers every modelling error. The robust term

    w = rho z / ||z||   if ||z|| >= epsilon,      w = rho z / epsilon   otherwise,      z = D^T Q xi,

with ``Q`` the solution of the Lyapunov equation ``H^T Q + Q H = -P``, makes ``V = xi^T Q xi`` decrease
whenever ``rho >= ||eta||`` (outside the boundary layer), which needs ``||I - B^-1 B_hat|| <= alpha < 1``.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from ..dynamics import dynamic_array, friction_kernel, gravity_kernel, inertia, inertia_rows
from ..errors import (
    ScaraError, ShapeError, UnstableError, as_array, check_angles, check_count, check_finite_result, check_positive,
    is_bool,
)
from ..params import ScaraParams
from .._simulate import control_law
from .._simulate.interface import REF_ACC, REF_POS, REF_VEL, WORK_WIDTH
from ._common import (
    BOUND_FIELDS, ERROR_BOUND, OK, TORQUE_BOUND, BoundedController, positive_gains, recorded_signals,
)

__all__ = ["RobustController", "sliding_weight", "lyapunov_matrix", "sliding_matrix", "inertia_uncertainty",
           "inertia_eigenvalues",
           "design_inertia_estimate", "B_HAT", "rho_bound"]

#: The book's constant diagonal inertia estimate (kg m^2, kg m^2, kg, kg m^2). Joints 1, 2 and 4: the entries
#: that keep ``alpha = max ||I - B(q)^-1 B_hat||`` smallest (about 0.80) over the configurations of the reference
#: path and payloads from 0 to 10 kg (:func:`design_inertia_estimate`), rounded; the plain diagonal of ``B`` would
#: give ``alpha`` about 1.6, joints 1 and 2 being strongly coupled. Joint 3 is almost decoupled and ``alpha`` does
#: not depend on its entry over a wide range, so it keeps the model's own payload-free ``B33 = 22.5 kg``.
B_HAT = (8.6, 6.0, 22.5, 1.4)


# --------------------------------------------------------------------------------------------------
# design: P, Q, z, alpha, rho
# --------------------------------------------------------------------------------------------------
def sliding_weight(K_P, K_D, Lambda) -> np.ndarray:
    """The weight ``P`` (8, 8) of the Lyapunov equation that makes ``z = D^T Q xi = qt_dot + Lambda qt``.

    For one joint with gains ``k_p``, ``k_d`` the equation ``H^T Q + Q H = -diag(p1, p2)`` gives
    ``Q12 = p1 / (2 k_p)`` and ``Q22 = (Q12 + p2 / 2) / k_d``; asking ``Q12 = lambda`` and ``Q22 = 1`` gives
    ``p1 = 2 k_p lambda`` and ``p2 = 2 (k_d - lambda)``, positive when ``0 < lambda < k_d``. So ``P`` decides
    what the robust term acts on: the combination of position and velocity error whose zero set is the
    sliding surface ``qt_dot = -Lambda qt``, on which each error decays as ``exp(-lambda t)``.

    Raises :class:`~scara.ScaraError` for non-positive gains and :class:`~scara.UnstableError` when some
    ``lambda >= k_d`` (``P`` would not be positive definite).
    """
    K_P = positive_gains(K_P, "K_P")
    K_D = positive_gains(K_D, "K_D")
    lam = positive_gains(Lambda, "Lambda")
    i = lambda_status(lam, K_D)
    if i >= 0:
        raise UnstableError(LAMBDA_MESSAGE.format(i=i, Lambda=lam[i], K_D=K_D[i]))
    with np.errstate(over="ignore", invalid="ignore"):
        P = np.diag(np.concatenate([2.0 * K_P * lam, 2.0 * (K_D - lam)]))
    return check_finite_result(P, "P = diag(2 K_P Lambda, 2 (K_D - Lambda))", K_P=K_P, K_D=K_D, Lambda=lam)


#: The refusal of a ``Lambda`` not below ``K_D`` (:func:`sliding_weight`), a template of the joint ``i`` and the two
#: gains: the one wording of the check, in :class:`RobustController` and in the controllers panel of chapter 6.
LAMBDA_MESSAGE = ("Lambda[{i}] = {Lambda:g} must be < K_D[{i}] = {K_D:g}: the weight P of the Lyapunov equation (its "
                  "velocity block 2 (K_D - Lambda)) would not be positive definite")


@kernel(light=True)
def lambda_status(Lambda, K_D):
    """The first joint ``i`` whose ``Lambda_i >= K_D_i`` (4,) each, or -1: the check of :func:`sliding_weight`, whose
    weight ``P`` has the velocity block ``2 (K_D - Lambda)``, positive definite only when every ``Lambda_i < K_D_i``."""
    for i in range(4):
        if Lambda[i] >= K_D[i]:
            return i
    return -1


@kernel
def sliding_rows(K_P, K_D, Lambda, out):
    """``Z = D^T Q`` (4, 8), row-major into ``out`` (32,), for the weight ``P = sliding_weight(K_P, K_D, Lambda)``
    (diagonal), in closed form: each joint's block of ``H^T Q + Q H = -P`` with ``H = [[0, 1], [-k_p, -k_d]]`` and
    ``P = diag(p1, p2)`` gives ``Q12 = p1 / (2 k_p)`` and ``Q22 = (Q12 + p2 / 2) / k_d`` (the equations of
    :func:`sliding_weight`; ``Q12 = lambda``, ``Q22 = 1`` up to round-off), so ``z_i = Q12 qt_i + Q22 qt_dot_i``.
    Equal to :func:`sliding_matrix` (scipy's Bartels-Stewart solve) to about 1e-12 relative; the entries off the two
    diagonals are exact zeros."""
    for j in range(32):
        out[j] = 0.0
    for i in range(4):
        p1 = 2.0 * K_P[i] * Lambda[i]
        p2 = 2.0 * (K_D[i] - Lambda[i])
        q12 = p1 / (2.0 * K_P[i])
        out[8 * i + i] = q12
        out[8 * i + 4 + i] = (q12 + 0.5 * p2) / K_D[i]


def lyapunov_matrix(K_P, K_D, P) -> np.ndarray:
    """``Q`` (8, 8) solving ``H^T Q + Q H = -P`` with ``H = [[0, I], [-K_P, -K_D]]`` (scipy's
    ``solve_continuous_lyapunov``). ``P`` (8, 8) must be symmetric positive definite."""
    K_P = positive_gains(K_P, "K_P")
    K_D = positive_gains(K_D, "K_D")
    P = as_array(P, "P", (8, 8))
    if not np.allclose(P, P.T, rtol=0, atol=1e-12 * max(1.0, np.abs(P).max())):
        raise ScaraError("P must be symmetric")
    if np.linalg.eigvalsh(P).min() <= 0:
        raise ScaraError(f"P must be positive definite; its smallest eigenvalue is {np.linalg.eigvalsh(P).min():.3g}")
    from scipy.linalg import solve_continuous_lyapunov  # noqa: PLC0415 - not at import: scipy.linalg is slow to load

    H = np.block([[np.zeros((4, 4)), np.eye(4)], [-np.diag(K_P), -np.diag(K_D)]])
    Q = solve_continuous_lyapunov(H.T, -P)
    return check_finite_result(0.5 * (Q + Q.T), "Lyapunov matrix Q", K_P=K_P, K_D=K_D, P=P)


def sliding_matrix(K_P, K_D, P) -> np.ndarray:
    """``D^T Q`` (4, 8): the map from ``xi = [qt, qt_dot]`` to the variable ``z`` of the robust term."""
    Q = lyapunov_matrix(K_P, K_D, P)
    return np.ascontiguousarray(Q[4:, :])


#: The most inertia matrices (configurations times payloads) one sweep computes: 1,000,000 of them take 128 MB,
#: and the book's sweeps need about 1,500.
MAX_SWEEP = 1_000_000
#: The most inertia matrices :func:`design_inertia_estimate` optimises over: Nelder-Mead evaluates ``alpha``
#: over all of them hundreds of times (10,000 matrices take about 40 s, 562 about 2 s); a path sampled every
#: few hundred samples (the book's 281 configurations) gives the same estimate to three digits.
MAX_DESIGN = 5_000


def _inertias(q, payloads, p, limit: int = MAX_SWEEP, why: str = "1,000,000 inertia matrices take 128 MB"):
    """The checked configurations (N, 4) and the inertia matrices ``B(q)`` (len(payloads) N, 4, 4), payload by
    payload (``payloads=None``: ``p``'s own); at most ``limit`` matrices (``why`` says where the limit comes
    from)."""
    p = ScaraParams.resolve(p)
    q = np.ascontiguousarray(check_angles(as_array(q, "q", (4,), allow_batch=True).reshape(-1, 4)))
    if len(q) == 0:
        raise ShapeError("q holds no configuration: the bounds over the configurations need at least one (N >= 1)")
    if payloads is None:  # the parameters' own payload
        return q, check_finite_result(_inertia_sweep(q, [dynamic_array(p)], limit, why), "inertia matrix B(q)",
                                      m_L=p.m_L)
    try:
        if isinstance(payloads, (str, bytes)) or is_bool(payloads):
            raise TypeError(payloads)
        pays = np.atleast_1d(np.asarray(payloads, dtype=float))
    except (TypeError, ValueError) as exc:
        raise ScaraError(f"payloads = {payloads!r} must be a number or a list of masses (kg)") from exc
    if pays.ndim != 1 or pays.size == 0:
        raise ShapeError(f"payloads must be a number or a list of masses (kg), got shape {pays.shape}")
    if np.any(pays < 0) or not np.all(np.isfinite(pays)):
        raise ScaraError(f"payloads = {pays.tolist()} must be finite masses >= 0 kg")
    Bs = _inertia_sweep(q, [dynamic_array(p.with_payload(float(m))) for m in pays], limit, why)
    return q, check_finite_result(Bs, "inertia matrix B(q)", payloads=pays)


def _inertia_sweep(q, dps, limit, why):
    """``B(q)`` (len(dps) N, 4, 4) for every parameter array of ``dps`` (one per payload) and every row of ``q``,
    after checking there are at most ``limit`` matrices."""
    check_count(len(q) * len(dps), "len(q) * len(payloads)", 1, limit, "inertia matrices", why)
    Bs = np.empty((len(dps), len(q), 4, 4))
    for i, dp in enumerate(dps):  # every configuration in one compiled loop
        inertia_rows(q, dp, Bs[i])
    return Bs.reshape(-1, 4, 4)


def inertia_eigenvalues(B_hat, q, payloads=(0.0, 10.0), p: ScaraParams | None = None) -> tuple[float, float]:
    """Smallest and largest eigenvalue of ``B(q)^-1 B_hat`` over the configurations ``q`` (N, 4) and the payloads.

    ``qdd = B^-1 B_hat y + ...``: these are the factors by which the true arm scales the acceleration ``y`` that
    the law asks for; the largest sets the sampling limit of the boundary layer (:meth:`RobustController.epsilon_bound`).
    """
    Bh = np.diag(positive_gains(B_hat, "B_hat"))
    _, Bs = _inertias(q, payloads, p)
    lam = np.linalg.eigvals(np.linalg.solve(Bs, np.broadcast_to(Bh, Bs.shape))).real
    check_finite_result(lam, "eigenvalues of B^-1 B_hat", B_hat=np.diag(Bh), payloads=payloads)
    return float(lam.min()), float(lam.max())


def inertia_uncertainty(B_hat, q, payloads=(0.0, 10.0), p: ScaraParams | None = None) -> float:
    """``alpha = max ||I - B(q)^-1 B_hat||_2`` over the configurations ``q`` (N, 4) and the payloads (kg).

    The robust design needs ``alpha < 1``: then the part of ``eta`` that the robust term itself causes
    (``(I - B^-1 B_hat) w``) is smaller than ``w``.
    """
    Bh = np.diag(positive_gains(B_hat, "B_hat"))
    _, Bs = _inertias(q, payloads, p)
    M = np.eye(4) - np.linalg.solve(Bs, np.broadcast_to(Bh, Bs.shape))
    check_finite_result(M, "I - B^-1 B_hat", B_hat=np.diag(Bh), payloads=payloads)
    return float(np.linalg.norm(M, 2, axis=(1, 2)).max())


def design_inertia_estimate(q, payloads=(0.0, 10.0), p: ScaraParams | None = None) -> tuple[np.ndarray, float]:
    """The constant diagonal ``B_hat`` that minimises :func:`inertia_uncertainty` (Nelder-Mead on the logs of
    its entries, started from half the diagonal of ``B`` at the configurations' mean). Returns
    ``(B_hat (4,), alpha)``."""
    from scipy.optimize import minimize  # noqa: PLC0415

    p = ScaraParams.resolve(p)
    q, Bs = _inertias(q, payloads, p, MAX_DESIGN, "Nelder-Mead evaluates alpha over every matrix up to 4000 times; "
                      "sample the path more sparsely (the book uses every 250th configuration)")
    Binv = np.linalg.inv(Bs)
    eye = np.eye(4)

    def alpha(x):
        return np.linalg.norm(eye - Binv * np.exp(x)[None, None, :], 2, axis=(1, 2)).max()

    x0 = np.log(0.5 * np.diag(inertia(q.mean(axis=0), p)))
    res = minimize(alpha, x0, method="Nelder-Mead", options=dict(xatol=1e-6, fatol=1e-9, maxiter=4000))
    return np.exp(res.x), float(res.fun)


def rho_bound(alpha: float, qdd_max: float, eta0_max: float) -> float:
    """The smallest constant ``rho`` of the robust term that the Lyapunov argument accepts at ``xi = 0``:
    ``rho >= (alpha qdd_max + eta0_max) / (1 - alpha)``, with ``qdd_max`` the largest ``||qdd_d||`` (rad/s^2) and
    ``eta0_max`` the largest ``||B^-1 n_tilde||`` (the model error the robust term must cover, rad/s^2).

    Raises :class:`~scara.ScaraError` when an argument is not a finite number (``qdd_max``, ``eta0_max`` must
    be ``>= 0``), :class:`~scara.UnstableError` when ``alpha`` is not in ``[0, 1)`` (no ``rho`` is enough), and
    :class:`~scara.NonFiniteError` when the bound overflows.
    """
    alpha = check_positive(alpha, "alpha", strict=False)
    qdd_max = check_positive(qdd_max, "qdd_max", strict=False)
    eta0_max = check_positive(eta0_max, "eta0_max", strict=False)
    if not alpha < 1:
        raise UnstableError(f"alpha = {alpha:.3g} must be < 1 for the robust term to dominate the uncertainty")
    rho = (alpha * qdd_max + eta0_max) / (1.0 - alpha)
    return check_finite_result(rho, "rho", alpha=alpha, qdd_max=qdd_max, eta0_max=eta0_max)


# --------------------------------------------------------------------------------------------------
# the law
# --------------------------------------------------------------------------------------------------
#: The law's arrays: gains (``Z = D^T Q``, 4x8 row-major), scratch rows and signals (it keeps no state).
GAINS = ArrayLayout(("K_P", 4), ("K_D", 4), ("Z", 32), ("rho", 1), ("epsilon", 1), ("B_hat", 4), *BOUND_FIELDS)
_G_KP, _G_KD, _G_Z, _G_RHO, _G_EPS, _G_BH, _G_TMAX, _G_EMAX = GAINS.offsets
WORK = ArrayLayout(("qt", 1), ("qt_dot", 1), ("z", 1), ("g_hat", 1), ("friction", 1), width=WORK_WIDTH)
_W_QT, _W_QTD, _W_Z, _W_G, _W_FR = WORK.offsets
SIGNALS = ArrayLayout(("z_norm", 1), ("w", 4))
_S_ZNORM, _S_W = SIGNALS.offsets


@kernel(light=True)
def pack_gains(K_P, K_D, Z, rho, epsilon, B_hat, tau_max, max_error, out):
    """The law's gain array (:data:`GAINS`, ``out`` of ``GAINS.size``) from ``K_P``, ``K_D``, ``B_hat``,
    ``tau_max`` (4,) each, ``Z = D^T Q`` (32,) row-major, ``rho``, ``epsilon`` and ``max_error``: the one packer of
    :meth:`RobustController.gains_array` and of the controllers panel's program."""
    for i in range(4):
        out[_G_KP + i] = K_P[i]
        out[_G_KD + i] = K_D[i]
        out[_G_BH + i] = B_hat[i]
        out[_G_TMAX + i] = tau_max[i]
    for j in range(32):
        out[_G_Z + j] = Z[j]
    out[_G_RHO] = rho
    out[_G_EPS] = epsilon
    out[_G_EMAX] = max_error


@control_law
def robust_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Robust control step (see the module docstring). ``ref = [q_d, qd_d, qdd_d]``; the twelve arguments are
    the engine's fixed :data:`~scara._compile.LAW_SIGNATURE`.

    ``signals = [||z||, w_1, w_2, w_3, w_4]``. Returns 0, 2 (torque beyond ``tau_max``) or 3 (a joint error
    beyond ``max_error``): :data:`OK`, :data:`TORQUE_BOUND`, :data:`ERROR_BOUND`.
    """
    qt = work[_W_QT]
    qtd = work[_W_QTD]
    z = work[_W_Z]
    g = work[_W_G]
    fr = work[_W_FR]
    emax = gains[_G_EMAX]
    for i in range(4):
        qt[i] = ref[REF_POS + i] - q[i]
        qtd[i] = ref[REF_VEL + i] - qd[i]
        if not abs(qt[i]) <= emax:
            return ERROR_BOUND
    nz2 = 0.0
    for i in range(4):
        s = 0.0
        for j in range(4):
            s += gains[_G_Z + 8 * i + j] * qt[j] + gains[_G_Z + 8 * i + 4 + j] * qtd[j]
        z[i] = s
        nz2 += s * s
    nz = math.sqrt(nz2)
    rho = gains[_G_RHO]
    eps = gains[_G_EPS]
    scale = rho / nz if nz >= eps else rho / eps
    gravity_kernel(q, model, g)
    friction_kernel(qd, model, fr)
    signals[_S_ZNORM] = nz
    for i in range(4):
        w = scale * z[i]
        signals[_S_W + i] = w
        y = ref[REF_ACC + i] + gains[_G_KD + i] * qtd[i] + gains[_G_KP + i] * qt[i] + w
        u = gains[_G_BH + i] * y + fr[i] + g[i]
        tau[i] = u
        if not abs(u) <= gains[_G_TMAX + i]:
            return TORQUE_BOUND
    return OK


class RobustController(BoundedController):
    """Robust joint-space controller ``u = B_hat y + n_hat`` with the boundary-layer robust term (module
    docstring; Siciliano et al. eqs. 8.56-8.72). Tracks the joint reference of the second-order CLIK.

    Parameters
    ----------
    K_P, K_D : 4 positive gains each (1/s^2, 1/s), default ``900`` and ``60``: double pole of the nominal
        error dynamics at 30 rad/s.
    rho : float > 0 (rad/s^2, m/s^2), default 20: the bound on ``||eta||``; :func:`rho_bound` with the path's
        ``alpha`` and a payload up to 10 kg asks for about 15.
    epsilon : float > 0 (1/s units of ``z``), default 0.05: half-width of the boundary layer. Inside it
        ``w = (rho / epsilon) z`` is a linear loop of gain ``rho / epsilon``; sampled at ``dt`` it chatters unless
        ``epsilon`` exceeds :meth:`epsilon_bound` (0.016 on the reference path). Inside the layer at rest the
        payload leaves ``qt_3 = -m_L g0 / (B33_hat (K_P3 + rho Lambda_3 / epsilon))``.
    Lambda : 4 positive gains (1/s), default 30, each below ``K_D``: ``P = sliding_weight(K_P, K_D, Lambda)``
        makes ``z = qt_dot + Lambda qt``. Ignored when ``P`` is given.
    P : (8, 8) symmetric positive definite, optional: the weight of the Lyapunov equation.
    B_hat : 4 positive numbers, default :data:`B_HAT`: the constant diagonal inertia estimate.
    model : ScaraParams, default ``ScaraParams()`` (no payload): gives ``n_hat = F qd + g_hat``.
    tau_max, max_error : the stated bounds (default :data:`~scara.control.TAU_MAX`, :data:`~scara.control.MAX_ERROR`).

    Raises :class:`~scara.ScaraError` for non-positive gains, ``rho`` or ``epsilon``, and
    :class:`~scara.UnstableError` for ``Lambda >= K_D``.

    >>> c = RobustController()
    >>> c.sliding[2, [2, 6]]          # z_3 = 30 qt_3 + qt_dot_3
    array([30.,  1.])
    """

    law = staticmethod(robust_law)
    name = "robust"
    reference_kind = "joint"
    gains_layout = GAINS
    state_layout = ArrayLayout()
    work_layout = WORK
    signals_layout = SIGNALS

    def __init__(self, K_P=900.0, K_D=60.0, rho: float = 20.0, epsilon: float = 0.05, Lambda=30.0, P=None,
                 B_hat=B_HAT, *, model: ScaraParams | None = None, tau_max=None, max_error=None):
        self.K_P = positive_gains(K_P, "K_P")
        self.K_D = positive_gains(K_D, "K_D")
        self.rho = check_positive(rho, "rho")
        self.epsilon = check_positive(epsilon, "epsilon")
        if P is None:
            self.Lambda = positive_gains(Lambda, "Lambda")
            P = sliding_weight(self.K_P, self.K_D, self.Lambda)
        else:
            self.Lambda = None
        self.P = as_array(P, "P", (8, 8)).copy()
        self.Q = lyapunov_matrix(self.K_P, self.K_D, self.P)
        self.sliding = np.ascontiguousarray(self.Q[4:, :])
        self.sliding[np.abs(self.sliding) < 1e-12 * np.abs(self.sliding).max()] = 0.0
        self.B_hat = positive_gains(B_hat, "B_hat")
        self.model = ScaraParams.resolve(model)
        self._set_bounds(tau_max, max_error)

    def gains_array(self) -> np.ndarray:
        out = np.empty(GAINS.size)
        pack_gains(self.K_P, self.K_D, np.ascontiguousarray(self.sliding, dtype=float).ravel(), self.rho, self.epsilon,
                   self.B_hat, np.ascontiguousarray(self.tau_max, dtype=float), self.max_error, out)
        return out

    def epsilon_bound(self, lam_max: float, dt: float = 1e-3) -> float:
        """The thinnest boundary layer whose sampled linear loop is still stable (below it, chattering).

        Inside the layer ``w = (rho / epsilon) z`` with ``z = qt_dot + Lambda qt``, and the arm turns ``y`` into
        ``qdd = B^-1 B_hat y + ...``: the velocity error sees the loop gain ``a = lam (K_D + rho / epsilon)`` for
        each eigenvalue ``lam`` of ``B^-1 B_hat``. Held over ``dt``, that loop multiplies the error by about
        ``1 - a dt`` per sample: it alternates in sign for ``a dt > 1`` and grows for ``a dt > 2``, until ``w``
        saturates at ``rho`` and switches every sample. So the layer works only for

            epsilon > lam_max rho dt / (2 - lam_max K_D dt)

        ``lam_max``: largest eigenvalue of ``B^-1 B_hat`` (:func:`inertia_eigenvalues`; at most ``1 + alpha``),
        with the largest ``K_D``. Raises :class:`~scara.UnstableError` if ``K_D`` alone breaks the limit.
        """
        lam_max = check_positive(lam_max, "lam_max")
        dt = check_positive(dt, "dt")
        kd = float(self.K_D.max())
        den = 2.0 - lam_max * kd * dt
        if den <= 0:
            raise UnstableError(f"K_D = {kd:g} alone is past the sampling limit 2 / (lam_max dt) = {2 / (lam_max * dt):g}")
        return check_finite_result(lam_max * self.rho * dt / den, "boundary-layer bound", lam_max=lam_max,
                                   rho=self.rho, dt=dt)

    def uncertainty(self, result) -> np.ndarray:
        """``eta = y - qdd`` (N, 4) along a run of this controller: the modelling error the robust term had to
        cover (``qdd = y - eta`` by construction), from the recorded state, reference and ``w``."""
        w = recorded_signals(result, SIGNALS.labels["w"], "RobustController.uncertainty")
        ref = result.reference
        qt = ref[:, REF_POS:REF_POS + 4] - result.q
        qtd = ref[:, REF_VEL:REF_VEL + 4] - result.qd
        y = ref[:, REF_ACC:REF_ACC + 4] + self.K_D * qtd + self.K_P * qt + w
        return y - result.qdd

    def __repr__(self):
        return (f"RobustController(K_P={self.K_P.tolist()}, K_D={self.K_D.tolist()}, rho={self.rho:g}, "
                f"epsilon={self.epsilon:g}, B_hat={self.B_hat.tolist()})")
