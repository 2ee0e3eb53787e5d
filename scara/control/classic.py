"""The two classic joint-space motion-control laws of chapter 6 (Siciliano et al., sec. 8.5.1 and 8.5.2),
discrete-time at the sampling period, tracking the joint reference of the second-order CLIK.

PD control with gravity compensation (eq-ctl-pdg; Siciliano et al. eq. 8.53), with ``e = q_d - q``::

    u = K_P e + K_D e_dot + g_hat(q)

With an exact ``g_hat`` and a constant ``q_d`` the energy ``V = qd^T B qd / 2 + e^T K_P e / 2`` decreases as
``Vdot = -qd^T (K_D + F) qd`` (eq-ctl-pdg-vdot), and La Salle's principle leaves ``e = 0`` as the only rest. With
a payload the model misses, the rest is where ``K_P e = g(q) - g_hat(q)``: the quill alone errs,
``e_3 = -m_L g0 / K_P3`` (eq-ctl-pdg-sag).

Inverse dynamics (computed torque) control in joint space (eq-ctl-ct; Siciliano et al. eqs. 8.57-8.58)::

    y = qdd_d + K_D e_dot + K_P e,     u = B_hat(q) y + n_hat(q, qd),    n_hat = C_hat qd + F_hat qd + g_hat

With an exact model ``qdd = y``, so ``e_ddot + K_D e_dot + K_P e = 0``: with ``K_P = omega^2``, ``K_D = 2 zeta
omega`` every joint's error is a second-order system of natural frequency ``omega``, critically damped for
``zeta = 1``. With model errors ``B~ = B_hat - B``, ``n~ = n_hat - n`` the loop is
``e_ddot + K_D e_dot + K_P e = B_hat^-1 (B~ qdd + n~)`` (eq-ctl-ct-error), and at rest ``B_hat K_P e = g - g_hat``
(eq-ctl-ct-sag), the quill's ``e_3 ~ -m_L g0 / (B33_hat K_P3)``.

Sampled at ``T`` with the torque held (an exact model makes each joint a held double integrator), the
computed-torque loop is stable if and only if (Jury) ``K_D T < 2``, ``K_P T / 2 < K_D`` and
``1 - K_D T + K_P T^2 / 2 > -1`` (eq-ctl-ct-jury): with ``K_P = omega^2``, ``K_D = 2 zeta omega`` that is
``omega T < min(4 zeta, 1 / zeta)`` (:func:`sampling_limit`; 1000 rad/s for ``zeta = 1`` at 1 ms).
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from ..dynamics import (cholesky_solve4, dynamic_array, dynamics_workspace, gravity_kernel, inertia_kernel,
                        inverse_dynamics_kernel)
from ..errors import UnstableError, check_angles, check_finite_result, check_positive, as_array
from ..params import ScaraParams
from .._simulate import control_law
from .._simulate.controllers import pd_gravity_steady_state_kernel, pd_gravity_torque
from .._simulate.interface import REF_ACC, REF_POS, REF_VEL, WORK_WIDTH
from ._common import BOUND_FIELDS, ERROR_BOUND, BoundedController, positive_gains, torque_code
from .independent import B_BAR, OMEGA, independent_gains

__all__ = ["PDPlusGravityController", "ComputedTorqueController", "critical_gains", "sampling_limit",
           "computed_torque_steady_state", "OMEGA_CT"]

#: The book's natural frequency of the computed-torque error (rad/s): the double pole of the robust law's nominal
#: loop and of the independent-joint PD, so that the three differ only in what they know of the arm.
OMEGA_CT = 30.0


# --------------------------------------------------------------------------------------------------
# PD control with gravity compensation
# --------------------------------------------------------------------------------------------------
#: The PD + gravity law's arrays: gains (torque gains), scratch (``g_hat``) and signals.
PDG_GAINS = ArrayLayout(("K_P", 4), ("K_D", 4), *BOUND_FIELDS)
_P_KP, _P_KD, _P_TMAX, _P_EMAX = PDG_GAINS.offsets
PDG_WORK = ArrayLayout(("g_hat", 1), width=WORK_WIDTH)
(_P_W_G,) = PDG_WORK.offsets
PDG_SIGNALS = ArrayLayout(("gravity_compensation", 1))
(_P_S_G,) = PDG_SIGNALS.offsets


@kernel(light=True)
def pack_bounded_gains(K_P, K_D, tau_max, max_error, out):
    """The gain array ``[K_P(4), K_D(4), tau_max(4), max_error]`` of both classic laws (:data:`PDG_GAINS` and
    :data:`CT_GAINS`, the same fields) into ``out`` (13,): the one packer of their ``gains_array`` and of the
    controllers panel's program."""
    for i in range(4):
        out[_P_KP + i] = K_P[i]
        out[_P_KD + i] = K_D[i]
        out[_P_TMAX + i] = tau_max[i]
    out[_P_EMAX] = max_error


@kernel
def joint_error_code(q, ref, emax):
    """:data:`ERROR_BOUND` when some ``|q_d,i - q_i|`` exceeds ``emax`` (or is not finite), 0 otherwise."""
    for i in range(4):
        if not abs(ref[REF_POS + i] - q[i]) <= emax:
            return ERROR_BOUND
    return 0


@control_law
def pd_plus_gravity_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """PD control with gravity compensation, bounded (module docstring; the book's (eq-ctl-pdg)): the torque of
    :func:`~scara._simulate.controllers.pd_gravity_torque`, the same computation as chapter 5's law, with the
    chapter's bounds. ``ref = [q_d, qd_d, qdd_d]`` (``qdd_d`` unused); the twelve arguments are the engine's fixed
    :data:`~scara._compile.LAW_SIGNATURE`. ``signals = [g_hat_3]`` (N). Returns :data:`OK`,
    :data:`TORQUE_BOUND` or :data:`ERROR_BOUND`."""
    code = joint_error_code(q, ref, gains[_P_EMAX])
    if code != 0:
        return code
    g = work[_P_W_G]
    pd_gravity_torque(q, qd, ref, gains, _P_KP, _P_KD, model, g, tau)
    signals[_P_S_G] = g[2]
    return torque_code(tau, gains, _P_TMAX)


class PDPlusGravityController(BoundedController):
    """PD control with gravity compensation in joint space (module docstring; Siciliano et al., sec. 8.5.1,
    eq. 8.53), with the chapter's bounds. Tracks the joint reference of the second-order CLIK, although the law
    is made for regulation: it has no feedforward, so during the motion the error supplies the torque that
    accelerates the arm.

    Parameters
    ----------
    omega : 4 positive numbers (rad/s), default :data:`~scara.control.OMEGA` (30): the double pole of each joint's
        nominal loop ``B_bar s^2 + (F + K_D) s + K_P = B_bar (s + omega)^2``, which places ``K_P = omega^2 B_bar``,
        ``K_D = 2 omega B_bar - F`` (:func:`~scara.control.independent_gains`, the independent-joint PD's gains).
    B_bar : 4 positive numbers (kg m^2, kg), default :data:`~scara.control.B_BAR`: the nominal inertia.
    K_P, K_D : optional torque gains (4 positive numbers each; N m/rad, N m s/rad, N/m and N s/m for the
        quill) that replace the placed ones.
    model : ScaraParams, default ``ScaraParams()`` (no payload): ``g_hat`` and the friction of the placement.
    tau_max, max_error : the stated bounds (default :data:`~scara.control.TAU_MAX`, :data:`~scara.control.MAX_ERROR`).

    Raises :class:`~scara.ScaraError` for a non-positive, non-finite or misshapen gain, pole or bound.

    >>> c = PDPlusGravityController()
    >>> [round(float(v)) for v in c.K_P]                  # omega^2 B_bar
    [12780, 7893, 20250, 1260]
    >>> round(1e3 * float(c.steady_state_error(ScaraParams().with_payload(5.0))[2]), 4)   # -m_L g0 / K_P3, mm
    -2.4222
    """

    law = staticmethod(pd_plus_gravity_law)
    name = "pd_plus_gravity"
    reference_kind = "joint"
    gains_layout = PDG_GAINS
    state_layout = ArrayLayout()
    work_layout = PDG_WORK
    signals_layout = PDG_SIGNALS

    def __init__(self, omega=OMEGA, B_bar=B_BAR, K_P=None, K_D=None, *, model: ScaraParams | None = None,
                 tau_max=None, max_error=None):
        self.model = ScaraParams.resolve(model)
        self.omega = positive_gains(omega, "omega")
        self.B_bar = positive_gains(B_bar, "B_bar")
        K_P0, K_D0, _ = independent_gains(self.B_bar, self.omega, self.model.F, integral=False)
        self.K_P = K_P0 if K_P is None else positive_gains(K_P, "K_P")
        self.K_D = K_D0 if K_D is None else positive_gains(K_D, "K_D")
        self._set_bounds(tau_max, max_error)

    def gains_array(self) -> np.ndarray:
        out = np.empty(PDG_GAINS.size)
        pack_bounded_gains(self.K_P, self.K_D, np.ascontiguousarray(self.tau_max, dtype=float), self.max_error, out)
        return out

    def steady_state_error(self, plant: ScaraParams) -> np.ndarray:
        """Joint error ``q_d - q`` (4,) at rest on ``plant`` (the book's (eq-ctl-pdg-sag)): ``K_P e = g - g_hat``, so
        only the quill errs, by ``(m3_hat - m3) g0 / K_P3 = -m_L g0 / K_P3`` (m) for a payload the model misses
        (:func:`~scara._simulate.controllers.pd_gravity_steady_state_kernel`)."""
        plant = ScaraParams.resolve(plant)
        e = np.zeros(4)
        e[2] = pd_gravity_steady_state_kernel(dynamic_array(self.model), dynamic_array(plant), float(self.K_P[2]))
        return check_finite_result(e, "steady-state error", K_P3=self.K_P[2], m_L=plant.m_L)

    def __repr__(self):
        return f"PDPlusGravityController(K_P={self.K_P.tolist()}, K_D={self.K_D.tolist()})"


# --------------------------------------------------------------------------------------------------
# inverse dynamics (computed torque) control in joint space
# --------------------------------------------------------------------------------------------------
#: The computed-torque law's arrays: gains (the same fields as PD + gravity's, acceleration gains here), scratch
#: (``B_hat`` is the scratch of :func:`~scara.dynamics.inverse_dynamics_kernel`, which takes the first four rows)
#: and signals (the commanded acceleration ``y``).
CT_GAINS = PDG_GAINS
CT_WORK = ArrayLayout(("B_hat", 4), ("y", 1), width=WORK_WIDTH)
_C_W_B, _C_W_Y = CT_WORK.offsets
assert _C_W_B == 0, "inverse_dynamics_kernel writes B_hat into the first four rows of work"
CT_SIGNALS = ArrayLayout(("y", 4))
(_C_S_Y,) = CT_SIGNALS.offsets


@kernel(light=True)
def critical_gains(omega, zeta, K_P, K_D):
    """``K_P = omega^2`` and ``K_D = 2 zeta omega`` (4,) into ``K_P``, ``K_D`` from ``omega`` (rad/s) and ``zeta``
    (4,): the error polynomial ``s^2 + K_D s + K_P`` gets natural frequency ``omega`` and damping ``zeta``
    (a double pole at ``-omega`` for ``zeta = 1``; the book's (eq-ctl-ct-gains))."""
    for i in range(4):
        K_P[i] = omega[i] * omega[i]
        K_D[i] = 2.0 * zeta[i] * omega[i]


@kernel(light=True)
def sampling_limit(zeta, dt):
    """The largest natural frequency ``omega`` (rad/s) the sampled computed-torque loop of damping ``zeta`` takes at
    the period ``dt`` (s): ``min(4 zeta, 1 / zeta) / dt`` (the book's (eq-ctl-ct-omega-max), from the Jury
    conditions :func:`jury_status` with ``K_P = omega^2``, ``K_D = 2 zeta omega``)."""
    return min(4.0 * zeta, 1.0 / zeta) / dt


@kernel(light=True)
def jury_status(K_P, K_D, dt):
    """The first joint ``i`` whose sampled loop is unstable, or -1. With an exact model and the torque held over
    ``dt``, each joint is a double integrator driven by ``y = -K_P e - K_D e_dot``; its error obeys
    ``x_{k+1} = Phi x_k`` with characteristic polynomial ``z^2 + a1 z + a0``, ``a1 = K_P dt^2 / 2 + K_D dt - 2``,
    ``a0 = 1 - K_D dt + K_P dt^2 / 2``, whose roots lie inside the unit circle iff (Jury) ``|a0| < 1`` and
    ``1 - a1 + a0 > 0`` (``1 + a1 + a0 = K_P dt^2 > 0`` always): ``K_P dt / 2 < K_D``, ``K_D dt - K_P dt^2 / 2 < 2``
    and ``K_D dt < 2`` (the book's (eq-ctl-ct-jury))."""
    for i in range(4):
        a0 = 1.0 - K_D[i] * dt + 0.5 * K_P[i] * dt * dt
        if not (abs(a0) < 1.0 and K_D[i] * dt < 2.0):
            return i
    return -1


#: The refusal of gains the sampled loop cannot take (a template): the one wording, in the controller and in the
#: controllers panel of chapter 6.
JURY_MESSAGE = ("K_P[{i}] = {K_P:g}, K_D[{i}] = {K_D:g} make the sampled computed-torque loop unstable at dt = {dt:g} s "
                "(Jury: K_P dt / 2 < K_D, K_D dt < 2 and 1 - K_D dt + K_P dt^2 / 2 > -1); with K_P = omega^2, "
                "K_D = 2 zeta omega this is omega < min(4 zeta, 1 / zeta) / dt = {omega_max:g} rad/s")


@control_law
def computed_torque_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Joint-space inverse dynamics step (module docstring; the book's (eq-ctl-ct)): ``y = qdd_d + K_D e_dot +
    K_P e`` and ``u = B_hat(q) y + C_hat qd + F_hat qd + g_hat``, the controller's model's inverse dynamics at
    ``qdd = y`` (:func:`~scara.dynamics.inverse_dynamics_kernel`, the one definition of ``B``, ``C``, ``g``).
    ``ref = [q_d, qd_d, qdd_d]``; the twelve arguments are the engine's fixed :data:`~scara._compile.LAW_SIGNATURE`.
    ``signals = y`` (4,) (rad/s^2, m/s^2). Returns :data:`OK`, :data:`TORQUE_BOUND` or :data:`ERROR_BOUND`."""
    code = joint_error_code(q, ref, gains[_P_EMAX])
    if code != 0:
        return code
    y = work[_C_W_Y]
    for i in range(4):
        y[i] = (ref[REF_ACC + i] + gains[_P_KD + i] * (ref[REF_VEL + i] - qd[i])
                + gains[_P_KP + i] * (ref[REF_POS + i] - q[i]))
        signals[_C_S_Y + i] = y[i]
    inverse_dynamics_kernel(q, qd, y, model, work, tau)
    return torque_code(tau, gains, _P_TMAX)


@kernel
def computed_torque_steady_state(q, model, plant, K_P, work, out):
    """The joint error ``e = q_d - q`` (4,) at rest under computed torque, into ``out``: ``B_hat(q) K_P e = g(q) -
    g_hat(q)`` (the book's (eq-ctl-ct-sag)), with the flat parameter arrays ``model`` (the controller's belief) and
    ``plant`` (the true arm) and ``work`` of shape (5, 4) (:func:`~scara.dynamics.dynamics_workspace`). Returns 0, or
    1 when ``B_hat`` is not positive definite. With a payload the model misses, ``e_3 = -m_L g0 (B_hat^-1)_33 /
    K_P3``, within the rotor coupling ``B13 = B23`` of ``-m_L g0 / (B33_hat K_P3)``; ``e_1``, ``e_2`` are that
    coupling's share."""
    B = work[0:4]
    r = work[4]
    gravity_kernel(q, plant, r)
    gravity_kernel(q, model, out)
    for i in range(4):
        r[i] = r[i] - out[i]
    inertia_kernel(q, model, B)
    code = cholesky_solve4(B, r, out)
    for i in range(4):
        out[i] = out[i] / K_P[i]
    return code


class ComputedTorqueController(BoundedController):
    """Inverse dynamics (computed torque) control in joint space (module docstring; Siciliano et al., sec. 8.5.2,
    eqs. 8.57-8.58). Tracks the joint reference of the second-order CLIK with the model it believes in.

    Parameters
    ----------
    omega : 4 positive numbers (rad/s), default :data:`OMEGA_CT` (30): the natural frequency of each joint's error.
    zeta : 4 positive numbers, default 1 (critically damped: the fastest error without overshoot).
    K_P, K_D : optional acceleration gains (4 positive numbers each, 1/s^2 and 1/s) that replace
        ``omega^2`` and ``2 zeta omega``.
    dt : float > 0 (s), default 1e-3: the sampling period the gains are checked against (:func:`jury_status`);
        ``omega`` must stay below :func:`sampling_limit`, 1000 rad/s for ``zeta = 1`` at 1 ms.
    model : ScaraParams, default ``ScaraParams()`` (no payload): ``B_hat``, ``C_hat``, ``F_hat``, ``g_hat``.
    tau_max, max_error : the stated bounds (default :data:`~scara.control.TAU_MAX`, :data:`~scara.control.MAX_ERROR`).

    Raises :class:`~scara.ScaraError` for a non-positive, non-finite or misshapen gain, ``omega``, ``zeta``, ``dt``
    or bound, and :class:`~scara.UnstableError` for gains the sampled loop cannot take.

    >>> c = ComputedTorqueController()
    >>> c.K_P.tolist(), c.K_D.tolist()              # omega^2 and 2 zeta omega
    ([900.0, 900.0, 900.0, 900.0], [60.0, 60.0, 60.0, 60.0])
    >>> round(1e3 * float(c.steady_state_error(ScaraParams().with_payload(5.0))[2]), 4)   # mm
    -2.4231
    """

    law = staticmethod(computed_torque_law)
    name = "computed_torque"
    reference_kind = "joint"
    gains_layout = CT_GAINS
    state_layout = ArrayLayout()
    work_layout = CT_WORK
    signals_layout = CT_SIGNALS

    def __init__(self, omega=OMEGA_CT, zeta=1.0, K_P=None, K_D=None, *, dt: float = 1e-3,
                 model: ScaraParams | None = None, tau_max=None, max_error=None):
        self.omega = positive_gains(omega, "omega")
        self.zeta = positive_gains(zeta, "zeta")
        self.dt = check_positive(dt, "dt")
        K_P0, K_D0 = np.empty(4), np.empty(4)
        with np.errstate(over="ignore", invalid="ignore"):
            critical_gains(self.omega, self.zeta, K_P0, K_D0)
        self.K_P = positive_gains(K_P0, "K_P = omega^2") if K_P is None else positive_gains(K_P, "K_P")
        self.K_D = positive_gains(K_D0, "K_D = 2 zeta omega") if K_D is None else positive_gains(K_D, "K_D")
        i = jury_status(self.K_P, self.K_D, self.dt)
        if i >= 0:
            raise UnstableError(JURY_MESSAGE.format(i=i, K_P=self.K_P[i], K_D=self.K_D[i], dt=self.dt,
                                                    omega_max=sampling_limit(self.zeta[i], self.dt)))
        self.model = ScaraParams.resolve(model)
        self._set_bounds(tau_max, max_error)

    def gains_array(self) -> np.ndarray:
        out = np.empty(CT_GAINS.size)
        pack_bounded_gains(self.K_P, self.K_D, np.ascontiguousarray(self.tau_max, dtype=float), self.max_error, out)
        return out

    def steady_state_error(self, plant: ScaraParams, q=None) -> np.ndarray:
        """Joint error ``q_d - q`` (4,) at rest at the configuration ``q`` (default ``[0, -pi/2, 0.5, 0]``; only
        ``theta2`` matters, through ``B_hat``) on ``plant``: ``e = K_P^-1 B_hat(q)^-1 (g - g_hat)`` (the book's
        (eq-ctl-ct-sag); :func:`computed_torque_steady_state`)."""
        plant = ScaraParams.resolve(plant)
        q = np.array([0.0, -math.pi / 2, 0.5, 0.0]) if q is None else \
            np.ascontiguousarray(check_angles(as_array(q, "q", (4,)), "q"))
        e = np.empty(4)
        with np.errstate(over="ignore", invalid="ignore"):
            code = computed_torque_steady_state(q, dynamic_array(self.model), dynamic_array(plant), self.K_P,
                                                dynamics_workspace(), e)
        if code:
            raise UnstableError(f"B_hat(q) of the controller's model is not positive definite at q = {q.tolist()}")
        return check_finite_result(e, "steady-state error", K_P=self.K_P, m_L=plant.m_L)

    def __repr__(self):
        return (f"ComputedTorqueController(omega={self.omega.tolist()}, zeta={self.zeta.tolist()}, "
                f"K_P={self.K_P.tolist()}, K_D={self.K_D.tolist()})")
