"""Independent-joint (decentralised) control (Siciliano et al., sec. 8.3), discrete-time at the sampling period.

Each joint is controlled on its own, from its own error, as if the arm were four separate motors. Motor ``i``
turns ``q_mi = k_ri q_i`` and drives its joint with ``tau_i = k_ri tau_mi``. Split the inertia matrix into a
constant diagonal nominal part and the rest, ``B(q) = B_bar + Delta_B(q)``; seen from the motor, joint ``i``
is the nominal model of chapter 6's equation (eq-ctl-ij-motor), with the disturbance
(eq-ctl-ij-disturbance)

    (B_bar_ii / k_ri^2) qdd_mi + F_mi qd_mi = tau_mi - d_i / k_ri,
    d_i = Delta_B_ii(q) qdd_i + sum_{j != i} B_ij(q) qdd_j + (C(q, qd) qd)_i + g_i(q),

where ``B_bar_ii / k_ri^2 = I_mi + (B_bar_ii - k_ri^2 I_mi) / k_ri^2``: the rotor's own inertia plus the link
side divided by ``k_ri^2``; multiplied by ``k_ri`` it is ``B_bar_ii qdd_i + F_ii qd_i = tau_i - d_i``
(eq-ctl-ij-joint). Everything but the nominal model (configuration-dependent inertia, coupling,
centrifugal and Coriolis terms, gravity and the payload, unknown to the controller) is the disturbance ``d_i``.

The law, per joint, in joint variables (eq-ctl-ij-law): with ``qt = q_d - q`` and the integral
``chi_k = T sum_{j<k} qt_j`` (forward Euler),

    v_i = [B_bar_ii qdd_di + F_ii qd_di] + K_Pi qt_i + K_Di qt_dot_i + K_Ii chi_i
    u_i = sat(v_i) = min(max(v_i, -tau_max_i), tau_max_i)                             (eq-ctl-ij-sat)

(the bracket is the decentralised feedforward, optional; ``K_I = 0`` is PD control). The gains come from pole
placement on the nominal model (eq-ctl-ij-gains): the error obeys ``B_bar s^3 + (F + K_D) s^2 + K_P s + K_I``
(times ``chi``, eq-ctl-ij-error), which is made ``B_bar (s + omega)^3``, a triple pole at ``-omega``
(eq-ctl-ij-poles):

    K_P = 3 omega^2 B_bar,  K_D = 3 omega B_bar - F,  K_I = omega^3 B_bar       (PID)
    K_P = omega^2 B_bar,    K_D = 2 omega B_bar - F                              (PD, a double pole)

Anti-windup by conditional integration (eq-ctl-ij-antiwindup): the integrator of joint ``i`` holds its value
over a sample in which ``v_i`` was clipped and ``qt_i`` has the sign of ``v_i`` (integrating would push the
command further into the limit); otherwise ``chi_{k+1} = chi_k + T qt_k``.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from ..errors import ScaraError, UnstableError, check_finite_result, check_flag
from ..params import ScaraParams
from .._simulate import control_law
from .._simulate.interface import REF_ACC, REF_POS, REF_VEL
from ._common import BOUND_FIELDS, ERROR_BOUND, OK, BoundedController, positive_gains, torque_code

__all__ = ["IndependentJointController", "independent_gains", "nominal_inertia", "joint_inertia_spread", "B_BAR",
           "OMEGA"]

#: The book's nominal inertia ``B_bar`` (kg m^2, kg m^2, kg, kg m^2): the mean of the diagonal of the model's
#: ``B(q)`` (no payload) over the configurations of the reference path (:func:`nominal_inertia`), rounded to three
#: digits. ``B22``, ``B33`` and ``B44`` do not depend on the configuration; ``B11`` ranges from 11.9 to 21.8 kg m^2
#: along the path.
B_BAR = (14.2, 8.77, 22.5, 1.4)
#: The book's closed-loop pole (rad/s): every joint's error polynomial is ``B_bar_ii (s + OMEGA)^3``.
OMEGA = 30.0


# --------------------------------------------------------------------------------------------------
# design: the nominal model, how far the arm strays from it, the gains
# --------------------------------------------------------------------------------------------------
def nominal_inertia(q, p: ScaraParams | None = None) -> np.ndarray:
    """``B_bar`` (4,): the mean over the configurations ``q`` (N, 4) of the diagonal of ``B(q)`` for the
    parameters ``p`` (default ``ScaraParams()``, no payload): the constant inertia each joint's nominal model
    (eq-ctl-ij-joint) keeps. Over the reference path it gives :data:`B_BAR` (rounded)."""
    from .robust import _inertias  # noqa: PLC0415 - the same checked sweep over configurations (one payload)

    p = ScaraParams.resolve(p)
    _, Bs = _inertias(q, None, p)
    return check_finite_result(np.diagonal(Bs, axis1=1, axis2=2).mean(axis=0), "nominal inertia",
                               m_L=p.m_L)


def joint_inertia_spread(q, payloads=(0.0, 10.0), B_bar=B_BAR, p: ScaraParams | None = None) -> dict:
    """How far each joint strays from its nominal model over the configurations ``q`` (N, 4) and the payloads
    (kg): the numbers behind the decoupling argument of the independent-joint section.

    Returns a dict of (4,) arrays, all relative to ``B_bar_ii``:

    * ``"low"``, ``"high"``: smallest and largest ``B_ii(q) / B_bar_ii``, the inertia the motor really feels
      against the nominal one (the ratio is the same on the motor side, both being divided by ``k_ri^2``);
    * ``"coupling"``: largest ``sum_{j != i} |B_ij(q)| / B_bar_ii``, the weight of the other joints'
      accelerations in ``d_i``;
    * ``"rotor"``: ``k_ri^2 I_mi / B_bar_ii``, the share of the nominal inertia that is the motor's own rotor
      (``p``'s ``k_r`` and ``I_m``).
    """
    from .robust import _inertias  # noqa: PLC0415 - the same checked sweep over configurations and payloads

    p = ScaraParams.resolve(p)
    B_bar = positive_gains(B_bar, "B_bar")
    _, Bs = _inertias(q, payloads, p)
    diag = np.diagonal(Bs, axis1=1, axis2=2)
    off = np.abs(Bs).sum(axis=2) - np.abs(diag)
    rotor = np.asarray(p.k_r) ** 2 * np.asarray(p.I_m)
    return {"low": diag.min(axis=0) / B_bar, "high": diag.max(axis=0) / B_bar,
            "coupling": off.max(axis=0) / B_bar, "rotor": rotor / B_bar}


def independent_gains(B_bar=B_BAR, omega=OMEGA, F=None, integral: bool = True) -> tuple:
    """``(K_P, K_D, K_I)`` (4,) each by pole placement on the nominal model (eq-ctl-ij-gains): the error
    polynomial ``B_bar s^3 + (F + K_D) s^2 + K_P s + K_I`` becomes ``B_bar (s + omega)^3`` (PID, ``integral``)
    and ``B_bar s^2 + (F + K_D) s + K_P`` becomes ``B_bar (s + omega)^2`` (PD; ``K_I`` is zero).

    ``B_bar`` (kg m^2, kg), ``omega`` (rad/s) and the friction ``F`` (N m s/rad, N s/m; default the joint
    friction ``diag(k_r^2 F_m)`` of ``ScaraParams()``) are per joint, each a number or 4 numbers. Gains are torque
    gains (N m/rad, N m s/rad, N m/(rad s); N/m, N s/m, N/(m s) for the quill); divided by ``k_ri^2`` they are
    the motor's (:meth:`IndependentJointController.motor_gains`).

    Raises :class:`~scara.ScaraError` for a non-positive ``B_bar`` or ``omega`` or a negative ``F``, and when the
    friction alone damps more than the pole asks (``K_D`` would be ``<= 0``).
    """
    B_bar = positive_gains(B_bar, "B_bar")
    omega = positive_gains(omega, "omega")
    F = positive_gains(ScaraParams().F if F is None else F, "F", rule="nonnegative")
    integral = check_flag(integral, "integral")
    n = 3.0 if integral else 2.0
    K_P, K_D, K_I = np.empty(4), np.empty(4), np.empty(4)
    with np.errstate(over="ignore", invalid="ignore"):
        i = placed_gains(B_bar, omega, F, integral, K_P, K_D, K_I)
    for name, g in (("K_P", K_P), ("K_D", K_D), ("K_I", K_I)):
        check_finite_result(g, name, B_bar=B_bar, omega=omega)
    if i >= 0:
        raise ScaraError(SLOW_POLE_MESSAGE.format(i=i, joint=i + 1, omega=omega[i], F=F[i], n=n,
                                                  reach=n * omega[i] * B_bar[i], K_D=K_D[i],
                                                  omega_min=F[i] / (n * B_bar[i])))
    return K_P, K_D, K_I


#: The refusals of the pole placement and of explicit gains (templates of the joint ``i`` and the numbers): the one
#: wording, in :func:`independent_gains`, :class:`IndependentJointController` and the controllers panel of chapter 6.
SLOW_POLE_MESSAGE = ("omega[{i}] = {omega:g} rad/s is too slow for joint {joint}: its friction F[{i}] = {F:g} alone "
                     "reaches {n:g} omega B_bar = {reach:g}, so K_D[{i}] would be {K_D:g} (it must be > 0); choose "
                     "omega[{i}] > {omega_min:g} rad/s")
ROUTH_MESSAGE = ("K_I[{i}] = {K_I:g} must be < (F + K_D) K_P / B_bar = {limit:g} for joint {joint}: the nominal error "
                 "polynomial B_bar s^3 + (F + K_D) s^2 + K_P s + K_I has roots in the right half-plane (Routh)")


@kernel(light=True)
def placed_gains(B_bar, omega, F, integral, K_P, K_D, K_I):
    """The pole placement (eq-ctl-ij-gains) into ``K_P``, ``K_D``, ``K_I`` (4,) from ``B_bar``, ``omega``, ``F``
    (4,): ``K_P = 3 omega^2 B_bar``, ``K_D = 3 omega B_bar - F``, ``K_I = omega^3 B_bar`` with ``integral`` (PID),
    else ``K_P = omega^2 B_bar``, ``K_D = 2 omega B_bar - F``, ``K_I = 0`` (PD). Returns the first joint whose
    ``K_D <= 0`` (the friction alone damps more than the pole asks), or -1: the one computation of
    :func:`independent_gains` and of the controllers panel's program."""
    c = 3.0 if integral else 1.0
    n = 3.0 if integral else 2.0
    for i in range(4):
        w = omega[i]
        K_P[i] = c * (w * w) * B_bar[i]
        K_D[i] = n * w * B_bar[i] - F[i]
        K_I[i] = w ** 3.0 * B_bar[i] if integral else 0.0
    for i in range(4):
        if K_D[i] <= 0.0:
            return i
    return -1


@kernel(light=True)
def joint_margin(F, K_P, K_D, K_I, B_bar, i):
    """The book's (eq-ctl-ij-margin) for joint ``i``: ``(F + K_D) K_P / K_I / B_bar`` with the integral (``K_I > 0``),
    ``inf`` without (see :meth:`IndependentJointController.inertia_margin`)."""
    if K_I[i] > 0.0:
        return (F[i] + K_D[i]) * K_P[i] / K_I[i] / B_bar[i]
    return math.inf


@kernel(light=True)
def margin_status(F, K_P, K_D, K_I, B_bar):
    """The first joint whose margin :func:`joint_margin` is not above 1 (its nominal loop is unstable: Routh), or -1."""
    for i in range(4):
        if not joint_margin(F, K_P, K_D, K_I, B_bar, i) > 1.0:
            return i
    return -1


# --------------------------------------------------------------------------------------------------
# the law
# --------------------------------------------------------------------------------------------------
#: The law's arrays: gains (the flags are 0.0 or 1.0), state (the integral ``chi``) and signals (no scratch).
GAINS = ArrayLayout(("B_bar", 4), ("F", 4), ("K_P", 4), ("K_D", 4), ("K_I", 4), ("feedforward", 1),
                    ("saturation", 1), ("anti_windup", 1), *BOUND_FIELDS)
(_G_BB, _G_F, _G_KP, _G_KD, _G_KI, _G_FF, _G_SAT, _G_AW, _G_TMAX, _G_EMAX) = GAINS.offsets
STATE = ArrayLayout(("chi", 4))
(_X_CHI,) = STATE.offsets
SIGNALS = ArrayLayout(("integral_action", 4), ("saturated", 1))
_S_IA, _S_SAT = SIGNALS.offsets


@kernel(light=True)
def pack_gains(B_bar, F, K_P, K_D, K_I, feedforward, saturation, anti_windup, tau_max, max_error, out):
    """The law's gain array (:data:`GAINS`, ``out`` of ``GAINS.size``) from ``B_bar``, ``F``, ``K_P``, ``K_D``,
    ``K_I``, ``tau_max`` (4,), the three flags (0.0 or 1.0) and ``max_error``: the one packer of
    :meth:`IndependentJointController.gains_array` and of the controllers panel's program."""
    for i in range(4):
        out[_G_BB + i] = B_bar[i]
        out[_G_F + i] = F[i]
        out[_G_KP + i] = K_P[i]
        out[_G_KD + i] = K_D[i]
        out[_G_KI + i] = K_I[i]
        out[_G_TMAX + i] = tau_max[i]
    out[_G_FF] = feedforward
    out[_G_SAT] = saturation
    out[_G_AW] = anti_windup
    out[_G_EMAX] = max_error


@control_law
def independent_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Independent-joint step (module docstring; the book's eqs. (eq-ctl-ij-law), (eq-ctl-ij-sat)
    and (eq-ctl-ij-antiwindup)); its twelve arguments are the engine's fixed :data:`~scara._compile.LAW_SIGNATURE`.
    ``ref = [q_d, qd_d, qdd_d]``; ``state = chi`` (4,), the integral of the joint error, updated after ``u``.

    ``signals = [K_I1 chi_1, ..., K_I4 chi_4, n_sat]``: the integral action (N m, N) used at this sample and the
    number of joints whose command was clipped. Returns :data:`OK`, :data:`ERROR_BOUND` (a joint error beyond
    ``max_error``) or, without saturation, :data:`TORQUE_BOUND` (a command beyond ``tau_max``).
    """
    emax = gains[_G_EMAX]
    ff = gains[_G_FF]
    sat = gains[_G_SAT] != 0.0
    aw = gains[_G_AW] != 0.0
    n_sat = 0.0
    for i in range(4):
        qt = ref[REF_POS + i] - q[i]
        if not abs(qt) <= emax:
            return ERROR_BOUND
        ia = gains[_G_KI + i] * state[_X_CHI + i]
        signals[_S_IA + i] = ia
        v = gains[_G_KP + i] * qt + gains[_G_KD + i] * (ref[REF_VEL + i] - qd[i]) + ia
        v += ff * (gains[_G_BB + i] * ref[REF_ACC + i] + gains[_G_F + i] * ref[REF_VEL + i])
        u = v
        clipped = False
        if sat:
            lim = gains[_G_TMAX + i]
            if v > lim:
                u = lim
                clipped = True
            elif v < -lim:
                u = -lim
                clipped = True
        tau[i] = u
        if clipped:
            n_sat += 1.0
        # conditional integration: hold chi_i while the clipped command and the error share their sign
        if gains[_G_KI + i] != 0.0 and not (aw and clipped and qt * v > 0.0):
            state[_X_CHI + i] += dt * qt
    signals[_S_SAT] = n_sat
    if sat:
        return OK
    return torque_code(tau, gains, _G_TMAX)


class IndependentJointController(BoundedController):
    """Independent-joint (decentralised) PID or PD control with actuator saturation and anti-windup (module
    docstring; Siciliano et al., sec. 8.3). Tracks the joint reference of the second-order CLIK; each joint
    reads only its own error and reference.

    Parameters
    ----------
    integral : bool, default True: PID (``K_I > 0``); False gives PD (the name becomes ``"independent_pd"``).
    omega : 4 positive numbers (rad/s), default :data:`OMEGA` (30): the triple (PID) or double (PD) pole of
        each joint's nominal error polynomial, from which :func:`independent_gains` places the gains.
    B_bar : 4 positive numbers, default :data:`B_BAR`: the nominal inertia of each joint (kg m^2, kg).
    K_P, K_D, K_I : optional torque gains (4 positive numbers each) that replace the placed ones; ``K_I`` is
        ignored without the integral. The nominal loop must stay stable: ``(F + K_D) K_P > B_bar K_I`` (Routh).
    feedforward : bool, default True: add ``B_bar qdd_d + F qd_d`` (the decentralised feedforward).
    saturation : bool, default True: clip each command to ``+-tau_max``; False stops the run (code 2) when a
        command exceeds its bound, like the other laws of chapter 6.
    anti_windup : bool, default True: conditional integration while a joint is clipped (no effect without
        saturation or integral).
    model : ScaraParams, default ``ScaraParams()``: only its friction ``F = diag(k_r^2 F_m)`` is used (in the
        feedforward and the pole placement); the controller knows neither gravity nor the payload.
    tau_max, max_error : the stated bounds (default :data:`~scara.control.TAU_MAX`, :data:`~scara.control.MAX_ERROR`).

    Raises :class:`~scara.ScaraError` for non-positive gains, poles, nominal inertias or bounds and for flags that
    are not bools, and :class:`~scara.UnstableError` when explicit gains break the Routh condition.

    >>> c = IndependentJointController()
    >>> [round(float(v)) for v in c.K_P]           # 3 omega^2 B_bar
    [38340, 23679, 60750, 3780]
    """

    law = staticmethod(independent_law)
    reference_kind = "joint"
    gains_layout = GAINS
    state_layout = STATE
    signals_layout = SIGNALS

    def __init__(self, integral: bool = True, omega=OMEGA, B_bar=B_BAR, K_P=None, K_D=None, K_I=None,
                 feedforward: bool = True, saturation: bool = True, anti_windup: bool = True, *,
                 model: ScaraParams | None = None, tau_max=None, max_error=None):
        self.integral = check_flag(integral, "integral")
        self.feedforward = check_flag(feedforward, "feedforward")
        self.saturation = check_flag(saturation, "saturation")
        self.anti_windup = check_flag(anti_windup, "anti_windup")
        self.model = ScaraParams.resolve(model)
        self.F = np.asarray(self.model.F, dtype=float)
        self.B_bar = positive_gains(B_bar, "B_bar")
        self.omega = positive_gains(omega, "omega")
        K_P0, K_D0, K_I0 = independent_gains(self.B_bar, self.omega, self.F, self.integral)
        self.K_P = K_P0 if K_P is None else positive_gains(K_P, "K_P")
        self.K_D = K_D0 if K_D is None else positive_gains(K_D, "K_D")
        if self.integral:
            self.K_I = K_I0 if K_I is None else positive_gains(K_I, "K_I")
            with np.errstate(over="ignore", invalid="ignore"):  # B_bar itself beyond the inertia the loop tolerates
                i = margin_status(self.F, self.K_P, self.K_D, self.K_I, self.B_bar)
                if i >= 0:
                    raise UnstableError(ROUTH_MESSAGE.format(
                        i=i, joint=i + 1, K_I=self.K_I[i], limit=(self.F[i] + self.K_D[i]) * self.K_P[i] / self.B_bar[i]))
        else:
            self.K_I = np.zeros(4)
        self.name = "independent" if self.integral else "independent_pd"
        self._set_bounds(tau_max, max_error)

    def gains_array(self) -> np.ndarray:
        out = np.empty(GAINS.size)
        pack_gains(self.B_bar, np.ascontiguousarray(self.F, dtype=float), self.K_P, self.K_D, self.K_I,
                   float(self.feedforward), float(self.saturation), float(self.anti_windup),
                   np.ascontiguousarray(self.tau_max, dtype=float), self.max_error, out)
        return out

    def initial_state(self) -> np.ndarray:
        return np.zeros(STATE.size)

    def motor_gains(self) -> dict:
        """The gains as the motors see them, ``{"K_P": K_P / k_r^2, "K_D": ..., "K_I": ...}`` (N m/rad, N m s/rad,
        N m/(rad s) of rotor angle): ``tau_m = tau / k_r`` and ``q_m = k_r q``, with ``k_r`` of the controller's
        model."""
        kr2 = np.asarray(self.model.k_r, dtype=float) ** 2
        return {"K_P": self.K_P / kr2, "K_D": self.K_D / kr2, "K_I": self.K_I / kr2}

    def inertia_margin(self) -> np.ndarray:
        """The book's (eq-ctl-ij-margin): the largest ratio ``B_ii / B_bar_ii`` (4,) each joint's loop tolerates.
        With the true inertia ``B_ii`` in place of ``B_bar_ii`` the error polynomial is
        ``B_ii s^3 + (F + K_D) s^2 + K_P s + K_I``, Hurwitz (Routh) while ``B_ii < (F + K_D) K_P / K_I``. With
        the placed gains (eq-ctl-ij-gains) ``F + K_D = 3 omega B_bar``,
        so the ratio is ``3 omega 3 omega^2 / omega^3 = 9`` whatever the friction; PD (a second-order loop)
        tolerates any inertia (``inf``)."""
        with np.errstate(over="ignore", invalid="ignore"):
            return np.array([joint_margin(self.F, self.K_P, self.K_D, self.K_I, self.B_bar, i) for i in range(4)])

    def steady_state_error(self, plant: ScaraParams) -> np.ndarray:
        """Joint error ``q_d - q`` (4,) at rest with ``plant``'s weight uncompensated (eq-ctl-ij-sag): the
        quill's ``-m3 g0 / K_P3`` (m; ``d3`` runs past ``d3_d``: the quill sags) for PD, zero with the integral (a
        constant load is integrated away). The revolute joints carry no gravity torque."""
        plant = ScaraParams.resolve(plant)
        e = np.zeros(4)
        if not self.integral:
            e[2] = -plant.m3 * plant.g0 / self.K_P[2]
        return check_finite_result(e, "steady-state error", K_P3=self.K_P[2], m3=plant.m3)

    def __repr__(self):
        return (f"IndependentJointController(integral={self.integral}, omega={self.omega.tolist()}, "
                f"K_P={self.K_P.tolist()}, K_D={self.K_D.tolist()}, K_I={self.K_I.tolist()}, "
                f"saturation={self.saturation}, anti_windup={self.anti_windup})")
