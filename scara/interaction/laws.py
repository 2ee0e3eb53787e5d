"""The interaction laws of chapter 7 (Siciliano et al., ch. 9), each a compiled law of the contact engine
(:func:`~.engine.simulate_contact`) with the bounds and failure codes of chapter 6, acting on the operational
vector ``x_e = (x, y, z, phi)``. ``h`` below is the wrist sensor's reading of ``h_e`` (the force the end
effector exerts on the environment, eq. 9.1), which the engine writes in the law's scratch row
``measured_force``; ``h_A = [h, 0]`` (no moment). ``x~ = x_d - x_e``, ``v = J_A qd``.

* :class:`ComplianceController` (sec. 9.2, active compliance): PD with gravity compensation,
  ``u = g_hat(q) + J_A^T (K_P x~ + K_D (xd_d - v))``; no force sensor. At rest ``K_P x~ = h_A``.
* :class:`ImpedanceController` (sec. 9.3): inverse dynamics with the measured force,
  ``u = B_hat y + n_hat + J^T h``, ``y = J_A^-1 (xdd_d + M_d^-1 (K_D (xd_d - v) + K_P x~ - h_A) - Jdot_A qd)``,
  which imposes ``M_d x~_ddot + K_D x~_dot + K_P x~ = h_A``.
* :class:`AdmittanceController` (sec. 9.3, admittance): the compliant frame ``x_c`` obeys
  ``M_d (xdd_c - xdd_d) + K_Dd (xd_c - xd_d) + K_Pd (x_c - x_d) = -h_A`` (integrated by the law, semi-implicit
  Euler at ``dt``), and an inner inverse dynamics loop, with the measured force compensated, tracks it:
  ``y = J_A^-1 (xdd_c + K_D (xd_c - v) + K_P (x_c - x_e) - Jdot_A qd)``, ``u = B_hat y + n_hat + J^T h``.
* :class:`ForceController` (sec. 9.4.1-9.4.2): force control with an inner position loop,
  ``y = J_A^-1 (K_P (x_F - x_e) - K_D v - Jdot_A qd)``, ``u = B_hat y + n_hat + J^T h`` (the measured force
  compensated, so that the inner loop is ``xdd_e + K_D xd_e + K_P x_e = K_P x_F``), the position reference made by a
  PI on the force error, ``x_F = x_F0 + K_F (f_d - h) + K_I int (f_d - h) dt`` on (x, y, z) (``x_F0`` the start
  position; phi keeps ``phi_d``): at rest ``h = f_d`` exactly.
* :class:`ParallelController` (sec. 9.4.3): parallel force/position control, the same inner loop on
  ``x~ + x_F``, ``x_F = (0, 0, K_F (f_d - h_z) + K_I int (f_d - h_z) dt, 0)``: at rest ``h_z = f_d`` and
  ``(x, y, phi) = (x_d, y_d, phi_d)``: the force loop prevails along the constrained direction z.

The four laws that read the sensor compensate the measured force (``+ J^T h`` in ``u``): their inner loop is the
free arm's, so along a position-controlled direction they hold the reference whatever the environment pushes
back with. A peg held 0.2 mm into a hole's wall loads it with ``k_w`` times that overlap (200 N for the default
wall), which the actuator bounds ``tau_max`` stop before it grows large.

The inverse dynamics laws' ``K_P``, ``K_D`` are per unit of mass (1/s^2, 1/s: the textbook's ``M_d^-1 K_P``,
``M_d^-1 K_D``); the impedance and admittance ``M_d`` (kg), ``K_D`` (N s/m), ``K_P`` (N/m) are physical (the
phi entries in kg m^2, N m s/rad, N m/rad). ``f_d`` is a desired ``h_e``: its z entry is negative to press down.

Gains. Each default is chosen for the surface of the book (``k_e = 2e4`` N/m, ``d_e = 50`` N s/m) at ``dt = 1``
ms, with the quill's mass ``m = B33 = 22.5`` kg along z; :meth:`check_contact` proves the sampled loop along z
stable on the run's surface (:mod:`.stability`), in contact and in free space, before a run. The failure codes
are chapter 6's: :data:`~scara.control._common.TORQUE_BOUND`, :data:`~scara.control._common.ERROR_BOUND` (on the
position error of the loop that tracks a position), :data:`~scara.control._common.SINGULAR_JACOBIAN`.
"""
from __future__ import annotations

import numpy as np

from .._compile import ArrayLayout, kernel
from .._simulate import control_law
from .._simulate.interface import OK, REF_ACC, REF_POS, REF_VEL, WORK_WIDTH
from ..control._common import (
    BOUND_FIELDS, ERROR_BOUND, SINGULAR_JACOBIAN, BoundedController, positive_gains, torque_code,
)
from ..dynamics import DP_A1, DP_A2, DP_D0, gravity_kernel, inverse_dynamics_kernel
from ..errors import ScaraError, ShapeError, _numbers, as_array, check_number
from ..kinematics import jacobian_dot_kernel, jacobian_kernel, pose_kernel
from ..control.operational import jacobian_solve
from ..params import ScaraParams
from .stability import check_sampled, z_axis

__all__ = ["ComplianceController", "ImpedanceController", "AdmittanceController", "ForceController",
           "ParallelController"]

_AXES = ("x", "y", "z", "phi")


# --------------------------------------------------------------------------------------------------
# the kernels every law shares
# --------------------------------------------------------------------------------------------------
@kernel
def tracking_terms(q, qd, ref, model, J, xt, v):
    """``J_A`` (1.6) into ``J`` (4, 4), ``x~ = x_d - x_e`` into ``xt`` and ``v = J_A qd`` into ``v`` (4,)."""
    a1 = model[DP_A1]
    a2 = model[DP_A2]
    pose_kernel(q, a1, a2, model[DP_D0], xt)
    jacobian_kernel(q, a1, a2, J)
    for i in range(4):
        xt[i] = ref[REF_POS + i] - xt[i]
        s = 0.0
        for j in range(4):
            s += J[i, j] * qd[j]
        v[i] = s


@kernel
def jdot_qd(q, qd, model, Jd, out):
    """``Jdot_A qd`` (4,) into ``out`` (``Jdot_A`` into ``Jd``, (4, 4))."""
    jacobian_dot_kernel(q, qd, model[DP_A1], model[DP_A2], Jd)
    for i in range(4):
        s = 0.0
        for j in range(4):
            s += Jd[i, j] * qd[j]
        out[i] = s


@kernel
def within(e, emax):
    """Whether every ``|e_i| <= emax`` (a NaN is not)."""
    for i in range(4):
        if not abs(e[i]) <= emax:
            return False
    return True


@kernel
def inverse_dynamics_step(q, qd, J, a, y, h, model, work, tau, gains, tmax_at):
    """``u = B_hat y + n_hat + J^T h``, ``y = J_A^-1 a`` solved by the block structure of (1.6) (the planar 2x2
    block, then ``y3 = -a_z``, ``y4 = a_phi - y1 - y2``); ``B_hat`` goes into the first four rows of ``work``
    (:func:`~scara.dynamics.inverse_dynamics_kernel`); ``J^T h`` compensates the measured force (J the positional
    rows of ``J_A``).
    Returns :data:`SINGULAR_JACOBIAN` or the torque check's code."""
    if not jacobian_solve(J, a, model[DP_A1] * model[DP_A2], y):
        return SINGULAR_JACOBIAN
    inverse_dynamics_kernel(q, qd, y, model, work, tau)
    for i in range(4):
        tau[i] += J[0, i] * h[0] + J[1, i] * h[1] + J[2, i] * h[2]
    return torque_code(tau, gains, tmax_at)


#: The scratch rows of the inverse dynamics laws (``B_hat`` first: the scratch of the inverse dynamics kernel).
ID_WORK = ArrayLayout(("B_hat", 4), ("J_A", 4), ("Jdot_A", 4), ("xt", 1), ("v", 1), ("a", 1), ("y", 1), ("jdq", 1),
                      ("a_c", 1), ("measured_force", 1), width=WORK_WIDTH)
_W_B, _W_J, _W_JD, _W_XT, _W_V, _W_A, _W_Y, _W_JDQ, _W_AC, _W_H = ID_WORK.offsets
assert _W_B == 0, "inverse_dynamics_kernel writes B_hat into the first four rows of work"


@kernel
def id_terms(q, qd, ref, model, work):
    """The terms every inverse dynamics law starts from, into its scratch rows (:data:`ID_WORK`): ``J_A``,
    ``x~ = x_d - x_e`` (row ``xt``), ``v = J_A qd`` (row ``v``), ``Jdot_A qd`` (row ``jdq``)."""
    tracking_terms(q, qd, ref, model, work[_W_J:_W_J + 4], work[_W_XT], work[_W_V])
    jdot_qd(q, qd, model, work[_W_JD:_W_JD + 4], work[_W_JDQ])


@kernel
def id_finish(q, qd, model, work, tau, gains, tmax_at, emax_at):
    """The end of every inverse dynamics law: :data:`ERROR_BOUND` when the position error in row ``xt`` breaks
    ``gains[emax_at]``, else ``u`` of :func:`inverse_dynamics_step` for the acceleration in row ``a``."""
    if not within(work[_W_XT], gains[emax_at]):
        return ERROR_BOUND
    return inverse_dynamics_step(q, qd, work[_W_J:_W_J + 4], work[_W_A], work[_W_Y], work[_W_H], model, work, tau,
                                 gains, tmax_at)


# --------------------------------------------------------------------------------------------------
# compliance control
# --------------------------------------------------------------------------------------------------
COMPLIANCE_GAINS = ArrayLayout(("K_P", 4), ("K_D", 4), *BOUND_FIELDS)
_C_KP, _C_KD, _C_TMAX, _C_EMAX = COMPLIANCE_GAINS.offsets
COMPLIANCE_WORK = ArrayLayout(("J_A", 4), ("xt", 1), ("v", 1), ("g_hat", 1), width=WORK_WIDTH)
_CW_J, _CW_XT, _CW_V, _CW_G = COMPLIANCE_WORK.offsets


@control_law
def compliance_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Active compliance (module docstring; the book's (eq-int-compliance)): ``u = g_hat + J_A^T (K_P x~ + K_D (xd_d -
    v))``; the engine's fixed twelve arguments. No signals, no state."""
    J = work[_CW_J:_CW_J + 4]
    xt = work[_CW_XT]
    v = work[_CW_V]
    g = work[_CW_G]
    tracking_terms(q, qd, ref, model, J, xt, v)
    if not within(xt, gains[_C_EMAX]):
        return ERROR_BOUND
    gravity_kernel(q, model, g)
    for i in range(4):
        s = g[i]
        for j in range(4):
            s += J[j, i] * (gains[_C_KP + j] * xt[j] + gains[_C_KD + j] * (ref[REF_VEL + j] - v[j]))
        tau[i] = s
    return torque_code(tau, gains, _C_TMAX)


# --------------------------------------------------------------------------------------------------
# impedance control
# --------------------------------------------------------------------------------------------------
IMPEDANCE_GAINS = ArrayLayout(("M_d", 4), ("K_D", 4), ("K_P", 4), *BOUND_FIELDS)
_I_MD, _I_KD, _I_KP, _I_TMAX, _I_EMAX = IMPEDANCE_GAINS.offsets


@control_law
def impedance_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Impedance control (module docstring; the book's (eq-int-impedance)): inverse dynamics with the measured
    force; the engine's arguments."""
    id_terms(q, qd, ref, model, work)
    for i in range(4):
        hi = work[_W_H, i] if i < 3 else 0.0
        work[_W_A, i] = (ref[REF_ACC + i] + (gains[_I_KD + i] * (ref[REF_VEL + i] - work[_W_V, i])
                                             + gains[_I_KP + i] * work[_W_XT, i] - hi) / gains[_I_MD + i]
                         - work[_W_JDQ, i])
    return id_finish(q, qd, model, work, tau, gains, _I_TMAX, _I_EMAX)


# --------------------------------------------------------------------------------------------------
# admittance control
# --------------------------------------------------------------------------------------------------
ADMITTANCE_GAINS = ArrayLayout(("M_d", 4), ("K_Dd", 4), ("K_Pd", 4), ("K_P", 4), ("K_D", 4), *BOUND_FIELDS)
_A_MD, _A_KDD, _A_KPD, _A_KP, _A_KD, _A_TMAX, _A_EMAX = ADMITTANCE_GAINS.offsets
ADMITTANCE_STATE = ArrayLayout(("x_c", 4), ("v_c", 4), ("started", 1))
_AS_X, _AS_V, _AS_ON = ADMITTANCE_STATE.offsets
ADMITTANCE_SIGNALS = ArrayLayout(("compliant_frame", _AXES))
(_AG_XC,) = ADMITTANCE_SIGNALS.offsets


@control_law
def admittance_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Admittance control (module docstring; the book's (eq-int-admittance), (eq-int-admittance-inner)): the compliant
    frame ``x_c`` (state, started at ``x_d(0)``) and the inner loop; ``signals`` = ``x_c`` (4,)."""
    if not state[_AS_ON] > 0.0:
        for i in range(4):
            state[_AS_X + i] = ref[REF_POS + i]
            state[_AS_V + i] = ref[REF_VEL + i]
        state[_AS_ON] = 1.0
    id_terms(q, qd, ref, model, work)
    for i in range(4):
        hi = work[_W_H, i] if i < 3 else 0.0
        xc = state[_AS_X + i]
        vc = state[_AS_V + i]
        signals[_AG_XC + i] = xc
        ac = ref[REF_ACC + i] + (gains[_A_KDD + i] * (ref[REF_VEL + i] - vc)
                                 + gains[_A_KPD + i] * (ref[REF_POS + i] - xc) - hi) / gains[_A_MD + i]
        work[_W_AC, i] = ac
        work[_W_XT, i] = xc - (ref[REF_POS + i] - work[_W_XT, i])  # x_c - x_e
        work[_W_A, i] = (ac + gains[_A_KD + i] * (vc - work[_W_V, i]) + gains[_A_KP + i] * work[_W_XT, i]
                         - work[_W_JDQ, i])
    code = id_finish(q, qd, model, work, tau, gains, _A_TMAX, _A_EMAX)
    for i in range(4):
        state[_AS_V + i] += dt * work[_W_AC, i]
        state[_AS_X + i] += dt * state[_AS_V + i]
    return code


# --------------------------------------------------------------------------------------------------
# force control with an inner position loop, and parallel force/position control
# --------------------------------------------------------------------------------------------------
FORCE_GAINS = ArrayLayout(("K_P", 4), ("K_D", 4), ("K_F", 3), ("K_I", 3), ("f_d", 3), *BOUND_FIELDS)
_F_KP, _F_KD, _F_KF, _F_KI, _F_FD, _F_TMAX, _F_EMAX = FORCE_GAINS.offsets
FORCE_STATE = ArrayLayout(("x_F0", 3), ("s", 3), ("started", 1))
_FS_X0, _FS_S, _FS_ON = FORCE_STATE.offsets
FORCE_SIGNALS = ArrayLayout(("x_F", ("x", "y", "z")))
(_FG_XF,) = FORCE_SIGNALS.offsets


@control_law
def force_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Force control with an inner position loop and a PI on the force error (module docstring; the book's
    (eq-int-force-inner), (eq-int-force-pi)); ``state`` =
    ``x_F0`` (the start position, set at the first sample) and the integral ``s`` of ``f_d - h`` (N s);
    ``signals`` = ``x_F`` (3,) m."""
    id_terms(q, qd, ref, model, work)
    if not state[_FS_ON] > 0.0:
        for i in range(3):
            state[_FS_X0 + i] = ref[REF_POS + i] - work[_W_XT, i]
        state[_FS_ON] = 1.0
    for i in range(3):
        xf = (state[_FS_X0 + i] + gains[_F_KF + i] * (gains[_F_FD + i] - work[_W_H, i])
              + gains[_F_KI + i] * state[_FS_S + i])
        signals[_FG_XF + i] = xf
        work[_W_XT, i] = xf - (ref[REF_POS + i] - work[_W_XT, i])  # x_F - x_e
        work[_W_A, i] = gains[_F_KP + i] * work[_W_XT, i] - gains[_F_KD + i] * work[_W_V, i] - work[_W_JDQ, i]
    work[_W_A, 3] = (ref[REF_ACC + 3] + gains[_F_KP + 3] * work[_W_XT, 3]
                     + gains[_F_KD + 3] * (ref[REF_VEL + 3] - work[_W_V, 3]) - work[_W_JDQ, 3])
    code = id_finish(q, qd, model, work, tau, gains, _F_TMAX, _F_EMAX)
    for i in range(3):
        state[_FS_S + i] += dt * (gains[_F_FD + i] - work[_W_H, i])
    return code


PARALLEL_GAINS = ArrayLayout(("K_P", 4), ("K_D", 4), ("K_F", 1), ("K_I", 1), ("f_d", 1), *BOUND_FIELDS)
_P_KP, _P_KD, _P_KF, _P_KI, _P_FD, _P_TMAX, _P_EMAX = PARALLEL_GAINS.offsets
PARALLEL_STATE = ArrayLayout(("s", 1))
(_PS_S,) = PARALLEL_STATE.offsets
PARALLEL_SIGNALS = ArrayLayout(("x_F", 1))
(_PG_XF,) = PARALLEL_SIGNALS.offsets


@control_law
def parallel_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Parallel force/position control (module docstring; the book's (eq-int-parallel)); ``state`` = the integral
    ``s`` of ``f_d - h_z`` (N s), ``signals`` = ``x_F`` (m), the force loop's share of the z reference."""
    id_terms(q, qd, ref, model, work)
    xf = gains[_P_KF] * (gains[_P_FD] - work[_W_H, 2]) + gains[_P_KI] * state[_PS_S]
    signals[_PG_XF] = xf
    work[_W_XT, 2] += xf
    for i in range(4):
        work[_W_A, i] = (ref[REF_ACC + i] + gains[_P_KD + i] * (ref[REF_VEL + i] - work[_W_V, i])
                         + gains[_P_KP + i] * work[_W_XT, i] - work[_W_JDQ, i])
    code = id_finish(q, qd, model, work, tau, gains, _P_TMAX, _P_EMAX)
    state[_PS_S] += dt * (gains[_P_FD] - work[_W_H, 2])
    return code


# --------------------------------------------------------------------------------------------------
# the controllers
# --------------------------------------------------------------------------------------------------
#: The kinds of z loop (:func:`z_loop`): the laws' linear parts along z
Z_COMPLIANCE, Z_IMPEDANCE, Z_ADMITTANCE, Z_FORCE = range(4)


@kernel
def z_loop(kind, g, m, c, k, d, dt, contact, Dy, Cw, Aw, By):
    """The linear part ``(D_y, C_w, A_w, B_y)`` of a law along z (:mod:`.stability`) into ``Dy`` (2,), ``Cw`` (2,),
    ``Aw`` (2, 2), ``By`` (2, 2) (their first ``n`` entries, rows); returns ``n``, the size of the law's state.
    ``kind`` one of ``Z_COMPLIANCE`` (``g = (K_P, K_D)`` z entries), ``Z_IMPEDANCE`` (``M_d, K_D, K_P``),
    ``Z_ADMITTANCE`` (``M_d, K_Dd, K_Pd, K_P, K_D``), ``Z_FORCE`` (``K_P, K_D, K_F, K_I``); on the mass ``m`` (kg)
    with friction ``c`` (N s/m), in contact (``contact`` true) with the surface ``k`` (N/m), ``d`` (N s/m), or in
    free space, sampled every ``dt`` (s)."""
    kk = k if contact else 0.0
    dd = d if contact else 0.0
    if kind == Z_COMPLIANCE:
        Dy[0] = -g[0]
        Dy[1] = -g[1]
        return 0
    if kind == Z_IMPEDANCE:
        r = m / g[0]
        Dy[0] = -r * (g[2] + kk) + kk
        Dy[1] = -r * (g[1] + dd) + c + dd
        return 0
    if kind == Z_ADMITTANCE:
        Md, Kd, Kp, KP, KD = g[0], g[1], g[2], g[3], g[4]
        acw0, acw1 = -Kp / Md, -Kd / Md
        acy0, acy1 = -kk / Md, -dd / Md
        Cw[0] = m * (acw0 + KP)
        Cw[1] = m * (acw1 + KD)
        Dy[0] = m * (acy0 - KP) + kk
        Dy[1] = m * (acy1 - KD) + (c + dd)
        col0, col1 = dt * dt, dt
        Aw[0, 0] = 1.0 + col0 * acw0
        Aw[0, 1] = dt + col0 * acw1
        Aw[1, 0] = 0.0 + col1 * acw0
        Aw[1, 1] = 1.0 + col1 * acw1
        By[0, 0] = col0 * acy0
        By[0, 1] = col0 * acy1
        By[1, 0] = col1 * acy0
        By[1, 1] = col1 * acy1
        return 2
    KP, KD, KF, KI = g[0], g[1], g[2], g[3]
    if not contact:   # only the inner position loop (the integral then ramps the reference on purpose)
        Dy[0] = -m * KP
        Dy[1] = -m * KD + c
        return 0
    Dy[0] = m * KP * (-KF * k - 1.0) + k
    Dy[1] = m * (-KP * KF * d - KD) + c + d
    Cw[0] = m * KP * KI
    Aw[0, 0] = 1.0
    By[0, 0] = -dt * k
    By[0, 1] = -dt * d
    return 1


def _z_loops(kind, gains, m, c, k, d, dt) -> dict:
    """``{"contact": ..., "free": ...}`` of :func:`z_loop` as arrays of their sizes."""
    out = {}
    for where in ("contact", "free"):
        Dy, Cw, Aw, By = np.zeros(2), np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
        n = z_loop(kind, np.array(gains, dtype=float), float(m), float(c), float(k), float(d), float(dt),
                   where == "contact", Dy, Cw, Aw, By)
        out[where] = (Dy, Cw[:n].copy(), Aw[:n, :n].copy(), By[:n].copy())
    return out


def _gains_text(**gains) -> str:
    return ", ".join(f"{name} = {np.round(np.atleast_1d(v), 6).tolist()}" for name, v in gains.items())


class _InteractionController(BoundedController):
    """What the five controllers share: the operational reference, the model (``ScaraParams()``), the bounds,
    and the check of the sampled loop along z on a surface (:meth:`check_contact`)."""

    reference_kind = "operational"
    state_layout = ArrayLayout()
    work_layout = ID_WORK

    def _setup(self, gains: dict, model, tau_max, max_error):
        """Check each gain of ``gains`` (positive, as many entries as its field of ``gains_layout``; a field of one
        entry is kept as a float) and keep it as an attribute; the model and chapter 6's bounds."""
        for name, value in gains.items():
            n = self.gains_layout.sizes[name]
            g = positive_gains(value, name, n, labels=_AXES[:n] if n > 1 else None)
            setattr(self, name, float(g[0]) if n == 1 else g)
        self.model = ScaraParams.resolve(model)
        self._set_bounds(tau_max, max_error)

    def _gain_fields(self) -> dict:
        """The gains by name (every field of ``gains_layout`` but the bounds and the desired force)."""
        skip = {name for name, _ in BOUND_FIELDS} | {"f_d"}
        return {name: getattr(self, name) for name in self.gains_layout.names if name not in skip}

    def gains_array(self) -> np.ndarray:
        extra = {"f_d": self.f_d} if "f_d" in self.gains_layout.names else {}
        return self.gains_layout.pack(**self._gain_fields(), **extra, **self._bounds())

    def initial_state(self) -> np.ndarray:
        return self.state_layout.zeros()

    #: the gain that is the stiffness the tool shows the environment at rest (None: the law sets a force)
    stiffness_field: str | None = None

    def stiffness(self) -> np.ndarray:
        """The stiffness (4,) (N/m, N m/rad) the tool shows the environment at rest (see ``stiffness_field``)."""
        if self.stiffness_field is None:
            raise ScaraError(f"{type(self).__name__} sets a force, not a stiffness")
        return getattr(self, self.stiffness_field).copy()

    def bias_gain(self):
        """``G`` (4,) such that at rest ``S x~ = h_A + b_A - G J_A B^-1 J^T b`` with the sensor's bias ``b`` and
        the stiffness ``S`` (:func:`~.steady.law_equilibrium`); None for a law that reads no sensor."""
        return None

    def z_loops(self, m: float, c: float, k: float, d: float, dt: float) -> dict:
        """The linear part ``(D_y, C_w, A_w, B_y)`` of the law along z (:mod:`.stability`), ``{"contact": ...,
        "free": ...}``, on the mass ``m`` with friction ``c``, surface ``k``, ``d``, period ``dt``."""
        raise NotImplementedError

    def check_contact(self, surface, plant=None, dt: float = 1e-3) -> None:
        """Refuse gains whose sampled loop along z is unstable on ``surface`` or in free space
        (:func:`.stability.check_sampled`: :class:`~scara.UnstableError` naming the spectral radius, the limit
        1 and the gains)."""
        m, c = z_axis(plant)
        k, d = surface.stiffness, surface.damping
        check_sampled(self.name, self.z_loops(m, c, k, d, dt), m, c, k, d, dt, _gains_text(**self._gain_fields()))


class ComplianceController(_InteractionController):
    """Active compliance control (the book's (eq-int-compliance); Siciliano et al., sec. 9.2): PD in the operational
    space with gravity compensation; no force sensor. At rest on an elastic surface the tool settles at
    ``x = (K_P + K)^-1 (K_P x_d + K x_r)`` (:func:`~.steady.elastic_equilibrium`).

    Parameters
    ----------
    K_P : (4,) N/m, N/m, N/m, N m/rad, default ``(5000, 5000, 5000, 200)``: the active stiffness.
    K_D : (4,) N s/m ... N m s/rad, default ``(600, 600, 600, 25)``: along z, on the 22.5 kg quill, a damping
        ratio of 0.93 in free space and 0.45 on the book's surface (``k_e = 2e4`` N/m).
    model, tau_max, max_error : the controller's model (only ``g_hat`` is used) and chapter 6's bounds.

    >>> ComplianceController().K_P.tolist()
    [5000.0, 5000.0, 5000.0, 200.0]
    """

    law = staticmethod(compliance_law)
    name = "compliance"
    gains_layout = COMPLIANCE_GAINS
    work_layout = COMPLIANCE_WORK
    stiffness_field = "K_P"

    def __init__(self, K_P=(5000.0, 5000.0, 5000.0, 200.0), K_D=(600.0, 600.0, 600.0, 25.0),
                 model: ScaraParams | None = None, tau_max=None, max_error=None):
        self._setup({"K_P": K_P, "K_D": K_D}, model, tau_max, max_error)

    def z_loops(self, m, c, k, d, dt):
        return _z_loops(Z_COMPLIANCE, (self.K_P[2], self.K_D[2]), m, c, k, d, dt)


class ImpedanceController(_InteractionController):
    """Impedance control in the operational space (Siciliano et al., sec. 9.3): inverse dynamics with the
    measured force (the book's (eq-int-impedance)), imposing ``M_d x~_ddot + K_D x~_dot + K_P x~ = h_A``
    (eq-int-impedance-closed).

    Parameters
    ----------
    M_d : (4,) kg, kg, kg, kg m^2, default ``(10, 10, 10, 1)``.
    K_D : (4,) N s/m ..., default ``(650, 650, 650, 40)``.
    K_P : (4,) N/m ..., default ``(5000, 5000, 5000, 400)``: free, ``(s^2 + 65 s + 500)`` (overdamped); on the
        book's surface the z impedance has ``omega_n = 50`` rad/s and damping ratio 0.7.
    model, tau_max, max_error : as :class:`ComplianceController`.

    >>> ImpedanceController().stiffness().tolist()
    [5000.0, 5000.0, 5000.0, 400.0]
    """

    law = staticmethod(impedance_law)
    name = "impedance"
    gains_layout = IMPEDANCE_GAINS
    stiffness_field = "K_P"

    def __init__(self, M_d=(10.0, 10.0, 10.0, 1.0), K_D=(650.0, 650.0, 650.0, 40.0),
                 K_P=(5000.0, 5000.0, 5000.0, 400.0), model: ScaraParams | None = None, tau_max=None,
                 max_error=None):
        self._setup({"M_d": M_d, "K_D": K_D, "K_P": K_P}, model, tau_max, max_error)

    def bias_gain(self) -> np.ndarray:
        """``G = M_d`` (4,) (see :meth:`_InteractionController.bias_gain`)."""
        return self.M_d.copy()

    def z_loops(self, m, c, k, d, dt):
        return _z_loops(Z_IMPEDANCE, (self.M_d[2], self.K_D[2], self.K_P[2]), m, c, k, d, dt)


class AdmittanceController(_InteractionController):
    """Admittance control (the book's (eq-int-admittance); Siciliano et al., sec. 9.3): a compliant frame driven by
    the measured force, tracked by an inner inverse dynamics loop that compensates the measured force.

    Parameters
    ----------
    M_d, K_Dd, K_Pd : (4,) the compliant frame's mass (kg), damping (N s/m) and stiffness (N/m) (phi: kg m^2,
        N m s/rad, N m/rad), default ``(20, 20, 20, 1)``, ``(940, 940, 940, 40)``, ``(5000, 5000, 5000, 400)``:
        on the book's surface the frame's z motion has ``omega_n = 35`` rad/s and damping ratio 0.7.
    K_P, K_D : (4,) the inner loop's gains per unit mass (1/s^2, 1/s), default ``4900`` and ``140``: a double
        pole at 70 rad/s, twice as fast as the frame.
    model, tau_max, max_error : as :class:`ComplianceController`.

    >>> AdmittanceController().stiffness().tolist()
    [5000.0, 5000.0, 5000.0, 400.0]
    """

    law = staticmethod(admittance_law)
    name = "admittance"
    gains_layout = ADMITTANCE_GAINS
    stiffness_field = "K_Pd"
    state_layout = ADMITTANCE_STATE
    signals_layout = ADMITTANCE_SIGNALS

    def __init__(self, M_d=(20.0, 20.0, 20.0, 1.0), K_Dd=(940.0, 940.0, 940.0, 40.0),
                 K_Pd=(5000.0, 5000.0, 5000.0, 400.0), K_P=4900.0, K_D=140.0, model: ScaraParams | None = None,
                 tau_max=None, max_error=None):
        self._setup({"M_d": M_d, "K_Dd": K_Dd, "K_Pd": K_Pd, "K_P": K_P, "K_D": K_D}, model, tau_max, max_error)

    def bias_gain(self) -> np.ndarray:
        """``G = K_Pd / K_P`` (4,): the inner loop lags the compliant frame by ``K_P^-1 J_A B^-1 J^T b`` (see
        :meth:`_InteractionController.bias_gain`)."""
        return self.K_Pd / self.K_P

    def z_loops(self, m, c, k, d, dt):
        return _z_loops(Z_ADMITTANCE, (self.M_d[2], self.K_Dd[2], self.K_Pd[2], self.K_P[2], self.K_D[2]), m, c, k,
                        d, dt)


def _force_loops(m, c, k, d, dt, KP, KD, KF, KI):
    """The sampled loop along z of the force laws (:func:`z_loop`, ``Z_FORCE``): the integral of the force error
    as the law's state, the measured force compensated (``+h`` in ``u``); in free space only the inner position
    loop."""
    return _z_loops(Z_FORCE, (KP, KD, KF, KI), m, c, k, d, dt)


class ForceController(_InteractionController):
    """Force control with an inner position loop (the book's (eq-int-force-inner), (eq-int-force-pi); Siciliano
    et al., sec. 9.4.1-9.4.2), with a PI on the force error: at rest (eq-int-force-rest) the measured force equals
    ``f_d`` exactly, so the true force errs by the sensor's bias.

    Parameters
    ----------
    f_d : (3,) N, the desired ``h_e`` (default ``(0, 0, -10)``: press down with 10 N); a number is the z entry.
    K_P, K_D : (4,) the inner position loop per unit mass (1/s^2, 1/s), default 2500 and 70 (``omega_n = 50``
        rad/s, damping ratio 0.7).
    K_F, K_I : (3,) m/N and m/(N s), default ``2e-5`` and ``2e-3``. Pressing on the book's surface (the inner
        loop holding ``x_e = x_F`` at rest), ``h = k_e (x_F - x_r)`` and the force error would decay with the
        time constant ``(1 + K_F k_e) / (K_I k_e) = 35`` ms, the proportional part ``K_F k_e = 0.4``. The inner
        loop is not that much faster: the whole loop's slowest poles (:func:`~.compare.force_loop_poly`) are a
        damped pair at ``-15.9 +- 46.9j`` 1/s, whose envelope decays in 63 ms. In free space the reference moves
        toward the surface at ``K_I |f_d|`` (2 cm/s for 10 N).
    model, tau_max, max_error : as :class:`ComplianceController` (``max_error`` bounds ``x_F - x_e``).

    >>> ForceController().f_d.tolist()
    [0.0, 0.0, -10.0]
    """

    law = staticmethod(force_law)
    name = "force"
    gains_layout = FORCE_GAINS
    state_layout = FORCE_STATE
    signals_layout = FORCE_SIGNALS

    def __init__(self, f_d=(0.0, 0.0, -10.0), K_P=2500.0, K_D=70.0, K_F=2e-5, K_I=2e-3,
                 model: ScaraParams | None = None, tau_max=None, max_error=None):
        self.f_d = _force_vector(f_d)
        self._setup({"K_P": K_P, "K_D": K_D, "K_F": K_F, "K_I": K_I}, model, tau_max, max_error)

    def z_loops(self, m, c, k, d, dt):
        return _force_loops(m, c, k, d, dt, self.K_P[2], self.K_D[2], self.K_F[2], self.K_I[2])


class ParallelController(_InteractionController):
    """Parallel force/position control (the book's (eq-int-parallel); Siciliano et al., sec. 9.4.3): the inner
    position loop of :class:`ForceController` on ``x~ + x_F``, the force loop (a PI on ``f_d - h_z``) along z only. At
    rest the measured ``h_z = f_d`` and ``(x, y, phi) = (x_d, y_d, phi_d)``.

    Parameters
    ----------
    f_d : N, the desired ``h_z`` (default -10: press down with 10 N).
    K_P, K_D, K_F, K_I : as :class:`ForceController` (``K_F``, ``K_I`` numbers: z only).

    >>> ParallelController().f_d
    -10.0
    """

    law = staticmethod(parallel_law)
    name = "parallel"
    gains_layout = PARALLEL_GAINS
    state_layout = PARALLEL_STATE
    signals_layout = PARALLEL_SIGNALS

    def __init__(self, f_d=-10.0, K_P=2500.0, K_D=70.0, K_F=2e-5, K_I=2e-3, model: ScaraParams | None = None,
                 tau_max=None, max_error=None):
        self.f_d = float(_force_vector(f_d)[2])
        self._setup({"K_P": K_P, "K_D": K_D, "K_F": K_F, "K_I": K_I}, model, tau_max, max_error)

    def z_loops(self, m, c, k, d, dt):
        return _force_loops(m, c, k, d, dt, self.K_P[2], self.K_D[2], self.K_F, self.K_I)


#: The largest desired force accepted (N): far above what the quill's actuator (1000 N) could press.
MAX_FORCE = 1e4


def _force_vector(value) -> np.ndarray:
    """``f_d`` as a (3,) vector (a number is its z entry), finite and within :data:`MAX_FORCE` N."""
    if np.ndim(_numbers(value, "f_d must be a number or a vector of 3 numbers (N)", ShapeError)) == 0:
        f = np.array([0.0, 0.0, check_number(value, "f_d", unit="N")])
    else:
        f = np.array(as_array(value, "f_d", (3,)), dtype=float)
    if np.max(np.abs(f)) > MAX_FORCE:
        raise ScaraError(f"f_d = {f.tolist()} N has an entry above {MAX_FORCE:g} N in magnitude, beyond any force the "
                         f"arm can press with")
    return f
