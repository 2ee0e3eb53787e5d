"""Adaptive control in joint space: the Slotine-Li law (Siciliano et al., sec. 8.5.4), discrete-time.

    qd_r = qd_d + Lambda qt,   qdd_r = qdd_d + Lambda qt_dot,   sigma = qd_r - qd = qt_dot + Lambda qt
    u = Y(q, qd, qd_r, qdd_r) pi_hat + K_D sigma
    pi_hat_dot = K_pi^-1 Y^T sigma           (discretised: pi_hat_{k+1} = pi_hat_k + dt K_pi^-1 Y_k^T sigma_k)

``Y`` and ``pi`` are the linear parametrisation of :mod:`scara.dynamics` (``pi[0] = m3 = m_l3 + m_L``, the
lumped mass on the joint-3/4 axis). ``K_pi`` is diagonal; an infinite entry freezes its parameter at the
initial estimate, so ``K_pi`` chooses which parameters adapt. The initial estimate is the controller's own
model (no payload), and the payload estimate ``pi_hat[0] - m_l3`` is recorded at every sample.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from ..dynamics import DP_ML3, N_PI, PI_NAMES, dynamic_parameters, regressor_kernel
from ..errors import ScaraError, ShapeError, is_bool
from ..params import ScaraParams
from .._simulate import control_law
from .._simulate.interface import REF_ACC, REF_POS, REF_VEL, WORK_WIDTH
from ._common import BOUND_FIELDS, ERROR_BOUND, BoundedController, final_state, positive_gains, torque_code

__all__ = ["AdaptiveController", "adaptation_gains"]


def adaptation_gains(K_pi) -> np.ndarray:
    """``K_pi^-1`` (13,) from ``K_pi`` given as a number (only ``m3`` adapts), a dict ``{name: value}`` over
    :data:`~scara.dynamics.PI_NAMES` (the others frozen), or 13 entries where ``inf`` freezes a parameter.

    Raises :class:`~scara.ScaraError` for a non-positive entry or an unknown name, and when nothing adapts.
    """
    if isinstance(K_pi, dict):
        full = np.full(N_PI, np.inf)
        for key, val in K_pi.items():
            if key not in PI_NAMES:
                raise ScaraError(f"K_pi names {key!r}, which is not a parameter; choose from {PI_NAMES}")
            full[PI_NAMES.index(key)] = float(positive_gains(val, f"K_pi[{key!r}]", 1)[0])
        K_pi = full
    if isinstance(K_pi, (str, bytes)) or is_bool(K_pi):
        raise ShapeError(f"K_pi must be a number, a dict over {PI_NAMES} or {N_PI} entries, got {K_pi!r}")
    try:
        shape = np.shape(K_pi)
    except ValueError as exc:  # a ragged sequence
        raise ShapeError(f"K_pi must be a number, a dict over {PI_NAMES} or {N_PI} entries, got {K_pi!r}") from exc
    if shape == ():
        full = np.full(N_PI, np.inf)
        full[0] = positive_gains(K_pi, "K_pi", 1)[0]
        K_pi = full
    elif shape != (N_PI,):
        raise ShapeError(f"K_pi must be a number, a dict over {PI_NAMES} or {N_PI} entries, got shape {shape}")
    arr = positive_gains(K_pi, "K_pi", N_PI, allow_inf=True)
    inv = np.empty(N_PI)
    with np.errstate(over="ignore"):
        i = adaptation_rates(arr, inv)
    if i == FROZEN:
        raise ScaraError(FROZEN_MESSAGE)
    if i >= 0:
        raise ScaraError(SMALL_WEIGHT_MESSAGE.format(i=i, K_pi=arr[i], name=PI_NAMES[i]))
    return inv


#: What :func:`adaptation_rates` returns when every parameter is frozen, and the refusals of
#: :func:`adaptation_gains` (templates: the one wording, in the controller and in the controllers panel).
FROZEN = -2
FROZEN_MESSAGE = "K_pi freezes every parameter (all entries infinite): nothing would adapt"
SMALL_WEIGHT_MESSAGE = "K_pi[{i}] = {K_pi:g} ({name}) is too small: its inverse, the adaptation rate, is not finite"


@kernel(light=True)
def adaptation_rates(K_pi, out):
    """``out = K_pi^-1`` (13,) for positive weights ``K_pi`` (13,; ``inf`` freezes a parameter, rate 0). Returns
    -1, :data:`FROZEN` when every entry is infinite (nothing adapts), or the first ``i`` whose rate ``1 / K_pi_i``
    is not finite (a weight so small that its inverse overflows): the checks of :func:`adaptation_gains`."""
    frozen = True
    for i in range(N_PI):
        if K_pi[i] != math.inf:
            frozen = False
    if frozen:
        return FROZEN
    for i in range(N_PI):
        out[i] = 1.0 / K_pi[i]
    for i in range(N_PI):
        if not math.isfinite(out[i]):
            return i
    return -1


#: The law's arrays: gains (``K_pi_inv = K_pi^-1``), state (the estimate ``pi_hat``), scratch rows (``Y`` is
#: 4x13, row-major over 13 rows of 4) and signals.
GAINS = ArrayLayout(("Lambda", 4), ("K_D", 4), ("K_pi_inv", N_PI), *BOUND_FIELDS)
_G_LAMBDA, _G_KD, _G_KPI, _G_TMAX, _G_EMAX = GAINS.offsets
STATE = ArrayLayout(("pi_hat", N_PI))
(_X_PI,) = STATE.offsets
WORK = ArrayLayout(("Y", N_PI), ("qd_r", 1), ("qdd_r", 1), ("sigma", 1), width=WORK_WIDTH)
_W_Y, _W_QDR, _W_QDDR, _W_SIGMA = WORK.offsets
SIGNALS = ArrayLayout(("payload_estimate", 1), ("sigma_norm", 1))
_S_PAYLOAD, _S_SIGMA = SIGNALS.offsets


@kernel(light=True)
def pack_gains(Lambda, K_D, K_pi_inv, tau_max, max_error, out):
    """The law's gain array (:data:`GAINS`, ``out`` of ``GAINS.size``) from ``Lambda``, ``K_D``, ``tau_max`` (4,),
    the rates ``K_pi_inv`` (13,) and ``max_error``: the one packer of :meth:`AdaptiveController.gains_array` and of
    the controllers panel's program."""
    for i in range(4):
        out[_G_LAMBDA + i] = Lambda[i]
        out[_G_KD + i] = K_D[i]
        out[_G_TMAX + i] = tau_max[i]
    for j in range(N_PI):
        out[_G_KPI + j] = K_pi_inv[j]
    out[_G_EMAX] = max_error


@control_law
def adaptive_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Slotine-Li step (module docstring; the twelve arguments are the engine's fixed
    :data:`~scara._compile.LAW_SIGNATURE`). ``state = pi_hat`` (13,), updated in place after ``u`` is formed.

    ``signals = [payload_estimate, ||sigma||]`` (kg, mixed units), the estimate being the one used at ``t``.
    Returns :data:`OK`, :data:`TORQUE_BOUND` or :data:`ERROR_BOUND`.
    """
    Y = work[_W_Y:_W_Y + N_PI].reshape((4, N_PI))
    qd_r = work[_W_QDR]
    qdd_r = work[_W_QDDR]
    sigma = work[_W_SIGMA]
    emax = gains[_G_EMAX]
    ns = 0.0
    for i in range(4):
        qt = ref[REF_POS + i] - q[i]
        if not abs(qt) <= emax:
            return ERROR_BOUND
        lam = gains[_G_LAMBDA + i]
        qd_r[i] = ref[REF_VEL + i] + lam * qt
        qdd_r[i] = ref[REF_ACC + i] + lam * (ref[REF_VEL + i] - qd[i])
        sigma[i] = qd_r[i] - qd[i]
        ns += sigma[i] * sigma[i]
    regressor_kernel(q, qd, qd_r, qdd_r, model, Y)
    signals[_S_PAYLOAD] = state[_X_PI] - model[DP_ML3]
    signals[_S_SIGMA] = np.sqrt(ns)
    for i in range(4):
        u = gains[_G_KD + i] * sigma[i]
        for j in range(N_PI):
            u += Y[i, j] * state[_X_PI + j]
        tau[i] = u
    code = torque_code(tau, gains, _G_TMAX)
    for j in range(N_PI):
        gj = gains[_G_KPI + j]
        if gj != 0.0:
            s = 0.0
            for i in range(4):
                s += Y[i, j] * sigma[i]
            state[_X_PI + j] += dt * gj * s
    return code


class AdaptiveController(BoundedController):
    """Slotine-Li adaptive joint-space controller (module docstring). Tracks the joint reference of the
    second-order CLIK; the payload estimate is ``result.payload_estimate`` (kg, one per sample).

    Parameters
    ----------
    Lambda : 4 positive gains (1/s), default 30: ``sigma = qt_dot + Lambda qt``, so an error decays as
        ``exp(-lambda t)`` once ``sigma`` is zero.
    K_D : 4 positive gains (N m s/rad, N s/m), default ``(600, 300, 1000, 60)``: about ``2 x 20 rad/s`` times
        each joint's inertia, so ``B sigma_dot = -K_D sigma + ...`` settles in a few tens of ms.
    K_pi : adaptation weights (see :func:`adaptation_gains`), default ``{"m3": 0.01}``: only the lumped mass
        ``m3 = m_l3 + m_L`` adapts (the payload is the only unknown). With the weight ``g0`` of ``Y`` on the
        quill, the estimate and ``sigma_3`` form a second-order loop of natural frequency
        ``g0 / sqrt(K_pi B33)`` (about 19 rad/s), damped by ``K_D3 / B33``.
    model : ScaraParams, default ``ScaraParams()``: the initial estimate ``pi_hat(0) = dynamic_parameters(model)``
        (no payload), and the geometry and ``g0`` inside ``Y``.
    tau_max, max_error : the stated bounds.

    >>> c = AdaptiveController()
    >>> float(c.initial_state()[0])   # m3 estimate at t = 0: the quill alone
    10.0
    """

    law = staticmethod(adaptive_law)
    name = "adaptive"
    reference_kind = "joint"
    gains_layout = GAINS
    state_layout = STATE
    work_layout = WORK
    signals_layout = SIGNALS

    def __init__(self, Lambda=30.0, K_D=(600.0, 300.0, 1000.0, 60.0), K_pi=None, model: ScaraParams | None = None,
                 tau_max=None, max_error=None):
        self.Lambda = positive_gains(Lambda, "Lambda")
        self.K_D = positive_gains(K_D, "K_D")
        self.K_pi_inv = adaptation_gains({"m3": 0.01} if K_pi is None else K_pi)
        self.model = ScaraParams.resolve(model)
        self._set_bounds(tau_max, max_error)

    @property
    def adapted(self) -> tuple:
        """Names of the parameters that adapt."""
        return tuple(n for n, g in zip(PI_NAMES, self.K_pi_inv) if g > 0)

    def gains_array(self) -> np.ndarray:
        out = np.empty(GAINS.size)
        pack_gains(self.Lambda, self.K_D, self.K_pi_inv, np.ascontiguousarray(self.tau_max, dtype=float),
                   self.max_error, out)
        return out

    def initial_state(self) -> np.ndarray:
        return dynamic_parameters(self.model)

    @staticmethod
    def final_estimate(result) -> np.ndarray:
        """The parameter estimate ``pi_hat`` (13,) at the end of a run of this controller (a run of another
        controller, which keeps no such estimate, raises :class:`~scara.ScaraError`)."""
        return final_state(result, STATE.size, "AdaptiveController.final_estimate")[_X_PI:_X_PI + N_PI]

    def __repr__(self):
        return (f"AdaptiveController(Lambda={self.Lambda.tolist()}, K_D={self.K_D.tolist()}, "
                f"adapted={self.adapted})")
