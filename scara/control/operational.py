"""Inverse dynamics control in the operational space, with integral action (chapter 6; Siciliano et al.,
sec. 8.6.3), discrete-time at the sampling period.

    xt = x_d - x_e(q),   xt_dot = xd_d - J_A(q) qd,   s_k = dt sum_{j<k} xt_j   (the integral, forward Euler)
    y = J_A^-1 (xdd_d + K_D xt_dot + K_P xt + K_I s - Jdot_A qd)
    u = B_hat(q) y + n_hat(q, qd),        n_hat = C_hat(q, qd) qd + F qd + g_hat(q)

``B_hat``, ``C_hat``, ``g_hat`` come from the controller's own model, which does not know the payload. With
``K_I = 0`` (``integral=False``) the uncompensated weight ``m_L g0`` leaves, at rest, the vertical error
``xt_z = m_L g0 / (B33_hat K_P,z)`` (chapter 6); the integral removes it.
"""
from __future__ import annotations

import numpy as np

from .._compile import ArrayLayout, kernel
from ..dynamics import DP_A1, DP_A2, DP_D0, inverse_dynamics_kernel
from ..errors import UnstableError, check_finite_result, check_flag
from ..kinematics import jacobian_dot_kernel, jacobian_kernel, pose_kernel
from ..params import ScaraParams
from .._simulate import control_law
from .._simulate.interface import REF_ACC, REF_POS, REF_VEL, WORK_WIDTH
from ._common import BOUND_FIELDS, ERROR_BOUND, SINGULAR_JACOBIAN, BoundedController, positive_gains, torque_code

__all__ = ["OperationalSpaceController"]

#: The law's arrays: gains, state (the integral ``s``), scratch rows (``B_hat`` is the scratch of
#: :func:`~scara.dynamics.inverse_dynamics_kernel`, which takes the first four rows) and signals.
GAINS = ArrayLayout(("K_P", 4), ("K_D", 4), ("K_I", 4), *BOUND_FIELDS)
_G_KP, _G_KD, _G_KI, _G_TMAX, _G_EMAX = GAINS.offsets
STATE = ArrayLayout(("s", 4))
(_X_S,) = STATE.offsets
WORK = ArrayLayout(("B_hat", 4), ("J_A", 4), ("Jdot_A", 4), ("xt", 1), ("a", 1), ("y", 1), width=WORK_WIDTH)
_W_B, _W_J, _W_JD, _W_XT, _W_A, _W_Y = WORK.offsets
assert _W_B == 0, "inverse_dynamics_kernel writes B_hat into the first four rows of work"
SIGNALS = ArrayLayout(("integral_action", ("x", "y", "z", "phi")))
(_S_IA,) = SIGNALS.offsets


#: The refusal of an integral gain that makes the nominal error polynomial unstable (a template of the component
#: ``i``, ``K_I`` and ``K_D K_P``): the one wording, in the controller and in the controllers panel of chapter 6.
INTEGRAL_MESSAGE = ("K_I[{i}] = {K_I:g} must be < K_D[{i}] K_P[{i}] = {K_DK_P:g}: the error polynomial s^3 + K_D s^2 + "
                    "K_P s + K_I has roots in the right half-plane (Routh)")


@kernel(light=True)
def integral_status(K_P, K_D, K_I):
    """The first component ``i`` (of 4) whose ``K_D_i K_P_i <= K_I_i``, or -1: by Routh, the nominal error polynomial
    ``s^3 + K_D s^2 + K_P s + K_I`` of the integral law has all its roots in the left half-plane iff (the gains
    being positive) ``K_D K_P > K_I``."""
    for i in range(4):
        if K_D[i] * K_P[i] <= K_I[i]:
            return i
    return -1


@kernel(light=True)
def pack_gains(K_P, K_D, K_I, tau_max, max_error, out):
    """The law's gain array (:data:`GAINS`, ``out`` of ``GAINS.size``) from ``K_P``, ``K_D``, ``K_I``, ``tau_max``
    (4,) and ``max_error``: the one packer of :meth:`OperationalSpaceController.gains_array` and of the
    controllers panel's program."""
    for i in range(4):
        out[_G_KP + i] = K_P[i]
        out[_G_KD + i] = K_D[i]
        out[_G_KI + i] = K_I[i]
        out[_G_TMAX + i] = tau_max[i]
    out[_G_EMAX] = max_error


@kernel
def jacobian_solve(J, a, scale, y):
    """``y = J_A^-1 a`` (4,) into ``y`` from the analytic Jacobian ``J`` (4, 4) of (1.6), by its block structure:
    the planar 2x2 block for ``y1, y2`` (determinant ``-a1 a2 sin theta2``, (1.7)), then ``y3 = -a_z`` and
    ``y4 = a_phi - y1 - y2``. Returns False (``y`` untouched) when ``|det| <= 1e-12 scale`` (``scale = a1 a2``):
    the stretched or folded arm. The one solve of the operational-space inverse dynamics laws (chapter 6's and
    chapter 7's)."""
    det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
    if not abs(det) > 1e-12 * scale:
        return False
    y[0] = (J[1, 1] * a[0] - J[0, 1] * a[1]) / det
    y[1] = (J[0, 0] * a[1] - J[1, 0] * a[0]) / det
    y[2] = -a[2]
    y[3] = a[3] - y[0] - y[1]
    return True


@control_law
def operational_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Operational-space inverse dynamics step (module docstring; the twelve arguments are the engine's fixed
    :data:`~scara._compile.LAW_SIGNATURE`). ``ref = [x_d, xd_d, xdd_d]``; ``state`` is
    the integral ``s`` (4,) of the error, updated after ``u`` is formed.

    ``x_e``, ``J_A`` and ``Jdot_A`` are the kernels of :mod:`scara.kinematics` (chapter 1), and ``J_A y = a`` is
    solved by its block structure: the planar 2x2 block (determinant ``-a1 a2 sin theta2``) for ``y1, y2``,
    then ``y3 = -a_z`` and ``y4 = a_phi - y1 - y2``. ``u = B_hat y + n_hat`` is the controller's model's
    inverse dynamics at ``qdd = y`` (:func:`~scara.dynamics.inverse_dynamics_kernel`).

    ``signals = K_I s`` (4,) (m/s^2, rad/s^2): the integral action. Returns :data:`OK`, :data:`TORQUE_BOUND`,
    :data:`ERROR_BOUND` or :data:`SINGULAR_JACOBIAN`.
    """
    J = work[_W_J:_W_J + 4]
    Jd = work[_W_JD:_W_JD + 4]
    xt = work[_W_XT]
    a = work[_W_A]
    y = work[_W_Y]
    a1 = model[DP_A1]
    a2 = model[DP_A2]
    pose_kernel(q, a1, a2, model[DP_D0], xt)
    jacobian_kernel(q, a1, a2, J)
    jacobian_dot_kernel(q, qd, a1, a2, Jd)
    emax = gains[_G_EMAX]
    for i in range(4):
        xt[i] = ref[REF_POS + i] - xt[i]
        if not abs(xt[i]) <= emax:
            return ERROR_BOUND
    for i in range(4):
        v = 0.0
        jdq = 0.0
        for j in range(4):
            v += J[i, j] * qd[j]
            jdq += Jd[i, j] * qd[j]
        ia = gains[_G_KI + i] * state[_X_S + i]
        signals[_S_IA + i] = ia
        a[i] = ref[REF_ACC + i] + gains[_G_KP + i] * xt[i] + gains[_G_KD + i] * (ref[REF_VEL + i] - v) + ia - jdq
    if not jacobian_solve(J, a, a1 * a2, y):  # y = J_A^-1 a
        return SINGULAR_JACOBIAN
    # u = B_hat y + C_hat qd + F qd + g_hat (B_hat goes into the first four rows of work, the kernel's scratch)
    inverse_dynamics_kernel(q, qd, y, model, work, tau)
    code = torque_code(tau, gains, _G_TMAX)
    for i in range(4):
        state[_X_S + i] += dt * xt[i]
    return code


class OperationalSpaceController(BoundedController):
    """Operational-space inverse dynamics control with (``integral=True``) or without integral action, the
    last controller of chapter 6. Tracks the operational reference ``[x_d, xd_d, xdd_d]`` directly.

    Parameters
    ----------
    integral : bool, default True (a ``bool`` or numpy bool: any other value raises :class:`~scara.ScaraError`).
    K_P, K_D, K_I : 4 positive gains each (1/s^2, 1/s, 1/s^3), per component ``[x, y, z, phi]``. Defaults
        ``K_P = 1200``, ``K_D = 60``, ``K_I = 8000``: with the integral, ``(s + 20)^3`` is the nominal error
        polynomial ``s^3 + K_D s^2 + K_P s + K_I`` (a triple pole at 20 rad/s). ``K_I`` is ignored when
        ``integral=False``.
    model : ScaraParams, default ``ScaraParams()`` (no payload): ``B_hat``, ``C_hat``, ``g_hat``.
    tau_max, max_error : the stated bounds.

    Raises :class:`~scara.ScaraError` for non-positive gains and :class:`~scara.UnstableError` when the
    nominal error polynomial is not Hurwitz (``K_D K_P <= K_I``).

    >>> float(OperationalSpaceController().steady_state_error(ScaraParams().with_payload(5.0))[2])  # integral
    0.0
    >>> round(1e3 * float(OperationalSpaceController(integral=False).steady_state_error(
    ...     ScaraParams().with_payload(5.0))[2]), 4)                                            # mm
    1.8173
    """

    law = staticmethod(operational_law)
    reference_kind = "operational"
    gains_layout = GAINS
    state_layout = STATE
    work_layout = WORK
    signals_layout = SIGNALS

    def __init__(self, integral: bool = True, K_P=1200.0, K_D=60.0, K_I=8000.0, model: ScaraParams | None = None,
                 tau_max=None, max_error=None):
        self.integral = check_flag(integral, "integral")
        self.K_P = positive_gains(K_P, "K_P")
        self.K_D = positive_gains(K_D, "K_D")
        if self.integral:
            self.K_I = positive_gains(K_I, "K_I")
            i = integral_status(self.K_P, self.K_D, self.K_I)
            if i >= 0:
                raise UnstableError(INTEGRAL_MESSAGE.format(i=i, K_I=self.K_I[i], K_DK_P=self.K_D[i] * self.K_P[i]))
        else:
            self.K_I = np.zeros(4)
        self.name = "operational" if self.integral else "operational_noint"
        self.model = ScaraParams.resolve(model)
        self._set_bounds(tau_max, max_error)

    def gains_array(self) -> np.ndarray:
        out = np.empty(GAINS.size)
        pack_gains(self.K_P, self.K_D, self.K_I, np.ascontiguousarray(self.tau_max, dtype=float), self.max_error, out)
        return out

    def initial_state(self) -> np.ndarray:
        return np.zeros(STATE.size)

    def steady_state_error(self, plant: ScaraParams, q=None) -> np.ndarray:
        """Operational error ``x_d - x_e`` (4,) (m, m, m, rad) left at rest by the payload the model misses.

        At rest ``B_hat y = g(q) - g_hat(q)`` and ``J_A y = K_P xt``: without the integral this gives
        ``xt = K_P^-1 J_A B_hat^-1 (g - g_hat)``, whose vertical entry is ``m_L g0 / (B33_hat K_P,z)`` up to the
        small coupling ``B13 = B23`` of the rotor of motor 3 (a relative 3e-4 here); with it, zero.
        ``q`` (default ``[0, -pi/2, 0.5, 0]``) matters only through that coupling.
        """
        plant = ScaraParams.resolve(plant)
        if self.integral:
            return np.zeros(4)
        from ..dynamics import gravity, inertia  # noqa: PLC0415
        from ..kinematics import jacobian  # noqa: PLC0415

        if q is None:
            q = np.array([0.0, -np.pi / 2, 0.5, 0.0])
        y = np.linalg.solve(inertia(q, self.model), gravity(q, plant) - gravity(q, self.model))
        with np.errstate(over="ignore", invalid="ignore"):
            e = jacobian(q, self.model) @ y / self.K_P
        return check_finite_result(e, "steady-state error", K_P=self.K_P, m_L=plant.m_L)

    def __repr__(self):
        return (f"OperationalSpaceController(integral={self.integral}, K_P={self.K_P.tolist()}, "
                f"K_D={self.K_D.tolist()}, K_I={self.K_I.tolist()})")
