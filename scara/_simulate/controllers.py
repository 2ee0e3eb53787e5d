"""The two controllers of chapter 5 that come with the engine: PD control with gravity compensation (the
worked example of the interface) and a constant torque (open loop)."""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from ..dynamics import DP_G0, dynamic_array, gravity_kernel, lumped_parameters
from ..errors import as_array, check_finite_result
from ..gains import gain_vector
from ..params import ScaraParams
from .interface import OK, REF_POS, REF_VEL, WORK_WIDTH, Controller, control_law

__all__ = ["PDGravityController", "TorqueController", "pd_gravity_law", "torque_law", "pd_gravity_steady_state_kernel",
           "pd_gravity_torque", "PD_GAINS", "TORQUE_GAINS"]

#: The arrays of the two controllers below (gains, scratch rows, signals; neither keeps a state).
PD_GAINS = ArrayLayout(("K_P", 4), ("K_D", 4))
_PD_KP, _PD_KD = PD_GAINS.offsets
PD_WORK = ArrayLayout(("g_hat", 1), width=WORK_WIDTH)
(_PD_W_G,) = PD_WORK.offsets
PD_SIGNALS = ArrayLayout(("gravity_compensation", 1))
(_PD_S_G,) = PD_SIGNALS.offsets
TORQUE_GAINS = ArrayLayout(("tau", 4))
(_TORQUE,) = TORQUE_GAINS.offsets


@kernel
def pd_gravity_torque(q, qd, ref, gains, kp_at, kd_at, model, g, tau):
    """The PD plus gravity compensation torque (Siciliano et al. eq. 8.53) into ``tau`` (4,): ``tau = K_P (q_d -
    q) + K_D (qd_d - qd) + g_hat(q)``, with ``K_P = gains[kp_at:kp_at + 4]``, ``K_D = gains[kd_at:kd_at + 4]``,
    ``ref = [q_d, qd_d, ...]`` and ``g_hat`` (written into ``g`` (4,)) from the flat parameter array ``model``: the
    one computation of the law of chapter 5 (:func:`pd_gravity_law`) and of chapter 6's bounded one."""
    gravity_kernel(q, model, g)
    for i in range(4):
        tau[i] = gains[kp_at + i] * (ref[REF_POS + i] - q[i]) + gains[kd_at + i] * (ref[REF_VEL + i] - qd[i]) + g[i]


@control_law
def pd_gravity_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """PD plus gravity compensation (Siciliano et al. eq. 8.53): ``tau = K_P (q_d - q) + K_D (qd_d - qd) +
    g_hat(q)`` (:func:`pd_gravity_torque`), with ``gains = [K_P(4), K_D(4)]`` and ``g_hat`` from the controller's
    ``model``. ``signals = [g_hat_3]`` (the compensated quill weight, N). The twelve arguments are the engine's
    fixed :data:`~scara._compile.LAW_SIGNATURE`, as for every law."""
    g = work[_PD_W_G]
    pd_gravity_torque(q, qd, ref, gains, _PD_KP, _PD_KD, model, g, tau)
    signals[_PD_S_G] = g[2]
    return OK


@kernel(light=True)
def pd_gravity_steady_state_kernel(model, plant, K_P3):
    """The quill's joint error ``q_d3 - q_3`` at rest under PD plus gravity compensation, where ``K_P e = g(q) -
    g_hat(q)`` (Siciliano et al. eq. 8.53 at rest): ``e_3 = (m3_hat g0_hat - m3 g0) / K_P3`` (m) with ``m3 = m_l3 +
    m_L`` and ``g0`` of the flat parameter arrays ``model`` (the controller's belief) and ``plant`` (the true
    robot, :func:`~scara.dynamics.dynamic_array`); ``inf`` for ``K_P3 <= 0`` (the quill uncorrected). The other
    joints carry no gravity, so they have no error."""
    if K_P3 > 0.0:
        return (lumped_parameters(model).m3 * model[DP_G0] - lumped_parameters(plant).m3 * plant[DP_G0]) / K_P3
    return math.inf


@control_law
def torque_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Open loop: a constant torque ``tau = gains[0:4]`` (zero for free motion); the engine's fixed signature."""
    for i in range(4):
        tau[i] = gains[_TORQUE + i]
    return OK


class PDGravityController(Controller):
    """PD control with gravity compensation in joint space (chapter 5; Siciliano et al., sec. 8.5.1).

    ``tau = K_P (q_d - q) + K_D (qd_d - qd) + g_hat(q)``, with ``g_hat`` from ``model`` (default
    ``ScaraParams()``: no payload). Held at a set point, the loop settles where ``K_P e = g(q) - g_hat(q)``:
    with an unknown payload ``m_L`` the quill sags by ``e_3 = q_d3 - q_3 = -m_L g0 / K_P3`` (so
    ``e_z = m_L g0 / K_P3``); the other joints have no error.

    Parameters
    ----------
    K_P, K_D : 4 gains (vector or diagonal matrix), N m/rad and N m s/rad (N/m and N s/m for joint 3);
        default ``K_P = diag(10000, 4000, 10000, 600)``, ``K_D = diag(1000, 400, 1000, 60)``: natural
        frequencies near 20 rad/s for the arm's inertia.
    model : ScaraParams, the controller's belief (only ``m3`` and ``g0`` matter here).

    >>> c = PDGravityController()
    >>> c.gains_array()[:4]
    array([10000.,  4000., 10000.,   600.])
    """

    law = staticmethod(pd_gravity_law)
    name = "pd_gravity"
    reference_kind = "joint"
    gains_layout = PD_GAINS
    state_layout = ArrayLayout()
    work_layout = PD_WORK
    signals_layout = PD_SIGNALS

    def __init__(self, K_P=(10000.0, 4000.0, 10000.0, 600.0), K_D=(1000.0, 400.0, 1000.0, 60.0),
                 model: ScaraParams | None = None):
        self.K_P = gain_vector(K_P, "K_P", rule="nonnegative")
        self.K_D = gain_vector(K_D, "K_D", rule="nonnegative")
        self.model = ScaraParams.resolve(model)

    def gains_array(self) -> np.ndarray:
        return PD_GAINS.pack(K_P=self.K_P, K_D=self.K_D)

    def steady_state_error(self, plant: ScaraParams) -> np.ndarray:
        """Theoretical joint error ``q_d - q`` at rest: ``K_P^-1 (g_hat - g)``, i.e. only joint 3 errs by
        ``(m3_hat - m3) g0 / K_P3`` (m; :func:`pd_gravity_steady_state_kernel`), shape (4,)."""
        plant = ScaraParams.resolve(plant)
        e = np.zeros(4)
        e[2] = pd_gravity_steady_state_kernel(dynamic_array(self.model), dynamic_array(plant), float(self.K_P[2]))
        if self.K_P[2] > 0:  # K_P3 = 0 leaves the quill uncorrected: an infinite error, on purpose
            check_finite_result(e, "steady-state error", K_P3=self.K_P[2], m_L=plant.m_L)
        return e

    def __repr__(self):
        return f"PDGravityController(K_P={self.K_P.tolist()}, K_D={self.K_D.tolist()})"


class TorqueController(Controller):
    """Open loop: a constant joint torque (default zero: the arm moves freely under gravity and friction)."""

    law = staticmethod(torque_law)
    name = "torque"
    reference_kind = "none"
    gains_layout = TORQUE_GAINS
    state_layout = ArrayLayout()

    def __init__(self, tau=(0.0, 0.0, 0.0, 0.0)):
        self.tau = as_array(tau, "tau", (4,)).copy()

    def gains_array(self) -> np.ndarray:
        return TORQUE_GAINS.pack(tau=self.tau)
