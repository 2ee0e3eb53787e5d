"""The closed-loop simulation engine: a discrete-time controller at ``dt`` (zero-order hold) driving the
continuous-time plant ``B qdd + C qd + F qd + g = tau`` (the model of chapter 5), integrated by fixed-step RK4.

    result = simulate(controller, traj, plant, dt=1e-3, substeps=1)

At every sample ``t_k = k dt`` the controller reads the measured ``q(t_k), qd(t_k)`` and its reference row
``r_k`` and returns a torque ``tau_k``; ``tau_k`` is held constant while the plant (the true robot, e.g.
``ScaraParams().with_payload(5.0)``) is integrated from ``t_k`` to ``t_{k+1}`` by ``substeps`` RK4 steps.

The controller interface
------------------------
A controller is any object (subclass :class:`Controller` for the defaults) with

``law``
    A compiled step kernel with exactly the signature :data:`LAW_SIGNATURE`, made with the decorator
    :func:`control_law`::

        @control_law
        def law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
            ...            # write tau[0:4] and signals[:]; update state[:] in place
            return 0       # 0 = fine; any other integer stops the run with an UnstableError

    ``k`` (int) sample index, ``t = k dt`` (s), ``dt`` (s) sampling period; ``q``, ``qd`` (4,) measured
    state (read only); ``ref`` (12,) reference row ``[pos(4), vel(4), acc(4)]``; ``gains`` (n_g,) and
    ``model`` (n_m,) constant float arrays; ``state`` (n_s,) persistent memory (integrators, estimates),
    carried from one sample to the next; ``work`` (work_rows, 4) scratch (4x4 matrices are
    ``work[0:4]``...), not kept between samples; ``signals`` (len(signal_names),) the row of internal signals
    recorded at this sample; ``tau`` (4,) the torque to apply. The law must not allocate arrays: it calls the
    compiled kernels of :mod:`scara.dynamics` and :mod:`scara.kinematics` with ``model`` and its scratch.

``reference_kind``
    ``"joint"``: ``ref = [q_d, qd_d, qdd_d]`` from ``clik2(traj)`` (or ``joint_reference=``);
    ``"operational"``: ``ref = [x_d, xd_d, xdd_d]`` from the trajectory; ``"none"``: zeros (open loop).
``gains_array()``, ``model_array()``, ``initial_state()``
    The flat float arrays passed as ``gains``, ``model`` (by default ``dynamic_array`` of the controller's
    own parameter object ``self.model``, which does not know the payload) and the initial ``state``.
``signal_names``, ``work_rows``, ``name``
    Names of the recorded internal signals (they become ``result.signals[name]`` and attributes of the
    result), rows of the scratch array, and the label used in tables and legends.

The engine's loop :func:`closed_loop_kernel` takes the law as a first-class function argument of type
``numba.types.FunctionType(LAW_SIGNATURE)``; because both the loop and the laws are compiled for explicit
signatures, numba's on-disk cache works for every controller (a dispatcher-typed argument would recompile the
loop in every new process). Both are compiled (or loaded from the cache) when first used, by :func:`simulate`,
not at import. Without numba (``SCARA_NO_NUMBA=1``) the same loop and laws run as plain Python.

:class:`PDGravityController` is the worked example; ``.notes/controller_interface.md`` walks through it.
"""
from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _compile
from ._compile import kernel
from .dynamics import (
    DP_A1, DP_A2, DP_FM, DP_G0, DP_IL1, DP_IL2, DP_IL4, DP_IM, DP_KR, DP_L1, DP_L2, DP_ML, DP_ML1, DP_ML2, DP_ML3,
    dynamic_array, gravity_kernel, kinetic_energy, potential_energy,
)
from .errors import ScaraError, ShapeError, UnstableError, as_array, check_positive
from .kinematics import (
    _params, ikine, jacobian, jacobian_dot_kernel, jacobian_kernel, pose, pose_kernel,
)
from .params import ScaraParams

__all__ = [
    "LAW_SIGNATURE", "control_law", "Controller", "PDGravityController", "TorqueController",
    "closed_loop_kernel", "simulate", "SimulationResult", "ikine_reference", "joint_setpoint",
]

# --------------------------------------------------------------------------------------------------
# the law signature and its decorator
# --------------------------------------------------------------------------------------------------
if _compile.COMPILED:
    from numba import types as _t

    _v = _t.float64[::1]
    _m = _t.float64[:, ::1]
    #: ``int64 law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)``
    LAW_SIGNATURE = _t.int64(_t.int64, _t.float64, _t.float64, _v, _v, _v, _v, _v, _v, _m, _v, _v)
    _LAW_TYPE = _t.FunctionType(LAW_SIGNATURE)
    _LOOP_SIGNATURE = _t.void(_LAW_TYPE, _v, _v, _m, _t.float64, _t.int64, _v, _v, _v, _v, _m,
                              _m, _m, _m, _m, _m, _t.float64, _t.int64[::1])
else:  # pragma: no cover - plain Python
    LAW_SIGNATURE = "int64(int64, float64, float64, f8[::1] x6, f8[:, ::1], f8[::1], f8[::1])"
    _LOOP_SIGNATURE = None


def control_law(fn):
    """Make ``fn`` a controller's step kernel: a numba dispatcher (cached on disk) that :func:`simulate`
    compiles with the engine's :data:`LAW_SIGNATURE` when it first runs it (``_compiled_law``), not at
    import.

    Without numba the function is returned unchanged. See the module docstring for the arguments.
    """
    if not _compile.COMPILED:
        return fn
    return _compile._numba.njit(cache=True)(fn)


def _compiled_law(law):
    """``law`` compiled for :data:`LAW_SIGNATURE` (loaded from the cache when it is there), ready to be passed
    to :func:`closed_loop_kernel`; returned unchanged without numba or when it is not a numba dispatcher.
    Raises ``TypeError`` when it was already compiled for the same arguments with another return type."""
    if not _compile.COMPILED:
        return law
    return _compile.ensure_signature(law, LAW_SIGNATURE)


# --------------------------------------------------------------------------------------------------
# the compiled engine
# --------------------------------------------------------------------------------------------------
#: codes written in ``info[0]`` by :func:`closed_loop_kernel`
OK, LAW_FAILED, DIVERGED, SINGULAR_INERTIA = 0, 1, 2, 3


@kernel
def _plant_constants(dp):
    """The constant part of the plant's ``B`` and right-hand side, from the flat array ``dp`` (once per run).

    In chapter 5's model only ``B11 = beta11 + 2 b cos theta2`` and ``B12 = beta12 + b cos theta2`` depend on the
    state (``b = a1 (m_l2 l2 + m3 a2)``); the rest of ``B`` is constant, with ``B23 = B13``, ``B24 = B14``,
    ``B34 = 0``, so the lower-right block ``D = diag(B33, B44)`` is diagonal. Eliminating ``qdd3``, ``qdd4``
    leaves the Schur complement ``S = B_12block - c [[1, 1], [1, 1]]``, ``c = B13^2 / B33 + B14^2 / B44``,
    whose constant parts are returned here (see :func:`_plant_acceleration`).

    Returns ``(S11_0, S12_0, S22, b, B13, B14, u3, u4, 1/B33, 1/B44, F1, F2, F3, F4, m3 g0, ok)`` with
    ``u3 = B13 / B33``, ``u4 = B14 / B44``, ``F_i = k_ri^2 F_mi``; ``ok`` is 1.0 when ``B33 > 0`` and
    ``B44 > 0`` (otherwise ``B`` is singular for every ``q`` and the other entries are not used).
    """
    a1 = dp[DP_A1]
    a2 = dp[DP_A2]
    l1 = dp[DP_L1]
    l2 = dp[DP_L2]
    m3 = dp[DP_ML3] + dp[DP_ML]
    ml2 = dp[DP_ML2]
    kr1 = dp[DP_KR]
    kr2 = dp[DP_KR + 1]
    kr3 = dp[DP_KR + 2]
    kr4 = dp[DP_KR + 3]
    im1 = dp[DP_IM]
    im2 = dp[DP_IM + 1]
    im3 = dp[DP_IM + 2]
    im4 = dp[DP_IM + 3]
    il4 = dp[DP_IL4]
    j2 = dp[DP_IL2] + ml2 * l2 * l2
    b = a1 * (ml2 * l2 + m3 * a2)
    B11c = (dp[DP_IL1] + dp[DP_ML1] * l1 * l1 + kr1 * kr1 * im1 + j2 + ml2 * a1 * a1 + il4 + im2 + im3 + im4
            + m3 * (a1 * a1 + a2 * a2))
    B12c = j2 + il4 + kr2 * im2 + im3 + im4 + m3 * a2 * a2
    B22 = j2 + il4 + kr2 * kr2 * im2 + im3 + im4 + m3 * a2 * a2
    B13 = kr3 * im3
    B33 = m3 + kr3 * kr3 * im3
    B14 = il4 + kr4 * im4
    B44 = il4 + kr4 * kr4 * im4
    F1 = kr1 * kr1 * dp[DP_FM]
    F2 = kr2 * kr2 * dp[DP_FM + 1]
    F3 = kr3 * kr3 * dp[DP_FM + 2]
    F4 = kr4 * kr4 * dp[DP_FM + 3]
    if not (B33 > 0.0 and B44 > 0.0):
        return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    u3 = B13 / B33
    u4 = B14 / B44
    c = B13 * u3 + B14 * u4
    return (B11c - c, B12c - c, B22 - c, b, B13, B14, u3, u4, 1.0 / B33, 1.0 / B44, F1, F2, F3, F4,
            m3 * dp[DP_G0], 1.0)


@kernel
def _plant_acceleration(c2, s2, v1, v2, v3, v4, t1, t2, t3, t4, pc):
    """``qdd = B^-1 (tau - C qd - F qd - g)`` (chapter 5) in scalars: ``(qdd1, qdd2, qdd3, qdd4, code)``.

    ``c2, s2`` are ``cos theta2, sin theta2`` (the only configuration ``B`` and ``C`` depend on), ``pc`` the
    tuple of :func:`_plant_constants`. With ``r = tau - C qd - F qd - g``, the last two rows give
    ``qdd3 = (r3 - B13 s) / B33``, ``qdd4 = (r4 - B14 s) / B44`` with ``s = qdd1 + qdd2``; substituting them in the
    first two rows leaves the 2x2 system ``S [qdd1, qdd2] = [r1, r2] - (B13 r3 / B33 + B14 r4 / B44)``, solved by
    Cramer's rule. ``B`` is positive definite iff ``B33, B44 > 0`` and ``S`` is (``S11 > 0``, ``det S > 0``);
    ``code`` is 0, or 1 (and zeros) when it is not. Equal to :func:`~scara.dynamics.forward_dynamics_kernel`
    (Cholesky) up to round-off, at a fraction of the cost.
    """
    s11c, s12c, s22, b, B13, B14, u3, u4, i33, i44, F1, F2, F3, F4, m3g, ok = pc
    S11 = s11c + 2.0 * b * c2
    S12 = s12c + b * c2
    det = S11 * s22 - S12 * S12
    if not (ok > 0.0 and S11 > 0.0 and det > 0.0):
        return 0.0, 0.0, 0.0, 0.0, 1
    h = b * s2
    y3 = (t3 - F3 * v3 + m3g) * i33
    y4 = (t4 - F4 * v4) * i44
    w = B13 * y3 + B14 * y4
    r1 = t1 + h * (v2 * v1 + (v1 + v2) * v2) - F1 * v1 - w
    r2 = t2 - h * v1 * v1 - F2 * v2 - w
    idet = 1.0 / det
    x1 = (s22 * r1 - S12 * r2) * idet
    x2 = (S11 * r2 - S12 * r1) * idet
    s = x1 + x2
    return x1, x2, y3 - u3 * s, y4 - u4 * s, 0


@kernel
def _rk4_step(q, qd, t1, t2, t3, t4, pc, h, qdd0):
    """One classical RK4 step of ``h`` seconds with the torque ``(t1, t2, t3, t4)`` held; ``q``, ``qd`` (4,)
    are updated in place and ``qdd0`` (4,) receives the first stage's acceleration (``qdd`` at the start).

    The state is ``(q, qd)`` and its derivative ``(qd, qdd)``; only ``theta2`` enters ``B`` and ``C``, so the
    four stages carry ``theta2`` and the velocities in scalars and call :func:`_plant_acceleration` with the
    run's constants ``pc`` (:func:`_plant_constants`). Returns 0, or 3 if ``B`` lost definiteness.
    """
    th = q[1]
    v1 = qd[0]
    v2 = qd[1]
    v3 = qd[2]
    v4 = qd[3]
    a1, a2, a3, a4, c1 = _plant_acceleration(math.cos(th), math.sin(th), v1, v2, v3, v4, t1, t2, t3, t4, pc)
    hh = 0.5 * h
    u1 = v1 + hh * a1
    u2 = v2 + hh * a2
    u3 = v3 + hh * a3
    u4 = v4 + hh * a4
    th2 = th + hh * v2
    b1, b2, b3, b4, c2 = _plant_acceleration(math.cos(th2), math.sin(th2), u1, u2, u3, u4, t1, t2, t3, t4, pc)
    w1 = v1 + hh * b1
    w2 = v2 + hh * b2
    w3 = v3 + hh * b3
    w4 = v4 + hh * b4
    th3 = th + hh * u2
    e1, e2, e3, e4, c3 = _plant_acceleration(math.cos(th3), math.sin(th3), w1, w2, w3, w4, t1, t2, t3, t4, pc)
    z1 = v1 + h * e1
    z2 = v2 + h * e2
    z3 = v3 + h * e3
    z4 = v4 + h * e4
    th4 = th + h * w2
    f1, f2, f3, f4, c4 = _plant_acceleration(math.cos(th4), math.sin(th4), z1, z2, z3, z4, t1, t2, t3, t4, pc)
    qdd0[0] = a1
    qdd0[1] = a2
    qdd0[2] = a3
    qdd0[3] = a4
    s = h / 6.0
    q[0] += s * (v1 + 2.0 * u1 + 2.0 * w1 + z1)
    q[1] += s * (v2 + 2.0 * u2 + 2.0 * w2 + z2)
    q[2] += s * (v3 + 2.0 * u3 + 2.0 * w3 + z3)
    q[3] += s * (v4 + 2.0 * u4 + 2.0 * w4 + z4)
    qd[0] += s * (a1 + 2.0 * b1 + 2.0 * e1 + f1)
    qd[1] += s * (a2 + 2.0 * b2 + 2.0 * e2 + f2)
    qd[2] += s * (a3 + 2.0 * b3 + 2.0 * e3 + f3)
    qd[3] += s * (a4 + 2.0 * b4 + 2.0 * e4 + f4)
    return 3 if (c1 + c2 + c3 + c4) != 0 else 0


@kernel
def rk4_step_kernel(q, qd, tau, dp, h, qdd0):
    """One classical RK4 step of ``h`` seconds of the plant ``dp`` (:func:`~scara.dynamics.dynamic_array`)
    with ``tau`` (4,) held, updating ``q``, ``qd`` in place; ``qdd0`` (4,) receives ``qdd`` at the start of the
    step. Returns 0, or 3 if ``B`` lost definiteness. (The engine's loop calls :func:`_rk4_step` with the
    plant's constants computed once per run.)
    """
    return _rk4_step(q, qd, tau[0], tau[1], tau[2], tau[3], _plant_constants(dp), h, qdd0)


@_compile.signature_kernel(_LOOP_SIGNATURE)
def closed_loop_kernel(law, q0, qd0, ref, dt, substeps, plant_dp, gains, model, state, work,
                       q_out, qd_out, qdd_out, tau_out, sig_out, limit, info):
    """The engine's loop over ``N = ref.shape[0]`` samples (see the module docstring).

    Writes ``q, qd, qdd, tau`` (N, 4) and the signals (N, n_sig). ``info`` (3,) int64 receives
    ``[code, k, law_code]``: code 0 when all samples ran, otherwise :data:`LAW_FAILED`, :data:`DIVERGED`
    (a state not finite or above ``limit``) or :data:`SINGULAR_INERTIA`, at sample ``k``.

    The law is called with small buffers owned by the loop (the measured state, the reference row, zeroed
    ``signals`` and ``tau``), copied to and from the output rows: no array view is created per sample.
    """
    n = ref.shape[0]
    n_ref = ref.shape[1]
    n_sig = sig_out.shape[1]
    pc = _plant_constants(plant_dp)
    q = np.empty(4)
    qd = np.empty(4)
    qdd = np.empty(4)
    spare = np.empty(4)
    q_law = np.empty(4)
    qd_law = np.empty(4)
    r = np.empty(n_ref)
    tau = np.empty(4)
    sig = np.empty(n_sig)
    for i in range(4):
        q[i] = q0[i]
        qd[i] = qd0[i]
    h = dt / substeps
    info[0] = 0
    info[1] = n
    info[2] = 0
    for k in range(n):
        for i in range(4):
            q_out[k, i] = q[i]
            qd_out[k, i] = qd[i]
            q_law[i] = q[i]
            qd_law[i] = qd[i]
            tau[i] = 0.0
        for i in range(n_ref):
            r[i] = ref[k, i]
        for i in range(n_sig):
            sig[i] = 0.0
        code = law(k, k * dt, dt, q_law, qd_law, r, gains, model, state, work, sig, tau)
        for i in range(4):
            tau_out[k, i] = tau[i]
        for i in range(n_sig):
            sig_out[k, i] = sig[i]
        if code != 0:
            info[0] = 1
            info[1] = k
            info[2] = code
            return
        ok = True
        for i in range(4):
            if not abs(tau[i]) < limit:
                ok = False
        if not ok:
            info[0] = 2
            info[1] = k
            return
        if k == n - 1:
            a1, a2, a3, a4, c = _plant_acceleration(math.cos(q[1]), math.sin(q[1]), qd[0], qd[1], qd[2], qd[3],
                                                    tau[0], tau[1], tau[2], tau[3], pc)
            if c != 0:
                info[0] = 3
                info[1] = k
            else:
                qdd_out[k, 0] = a1
                qdd_out[k, 1] = a2
                qdd_out[k, 2] = a3
                qdd_out[k, 3] = a4
            return
        for s in range(substeps):
            if _rk4_step(q, qd, tau[0], tau[1], tau[2], tau[3], pc, h, qdd if s == 0 else spare) != 0:
                info[0] = 3
                info[1] = k
                return
        for i in range(4):
            qdd_out[k, i] = qdd[i]
        for i in range(4):
            if not (abs(q[i]) < limit and abs(qd[i]) < limit):
                ok = False
        if not ok:
            info[0] = 2
            info[1] = k + 1
            return


# --------------------------------------------------------------------------------------------------
# controllers
# --------------------------------------------------------------------------------------------------
class Controller:
    """Base class of the controllers that :func:`simulate` runs (chapter 5; interface: ``help(scara.simulate)``).

    Subclasses set ``law`` (a :func:`control_law` kernel), ``reference_kind``, ``signal_names``,
    ``work_rows`` and ``name``, and override :meth:`gains_array` (and :meth:`initial_state` when they keep
    memory). ``self.model`` is the parameter object the controller believes in (default ``ScaraParams()``,
    which does not know the payload).
    """

    law = None
    name = "controller"
    reference_kind = "joint"
    signal_names: tuple = ()
    work_rows = 0
    model: ScaraParams = ScaraParams()

    def gains_array(self) -> np.ndarray:
        return np.zeros(0)

    def model_array(self) -> np.ndarray:
        return dynamic_array(self.model)

    def initial_state(self) -> np.ndarray:
        return np.zeros(0)

    def __repr__(self):
        return f"{type(self).__name__}()"


@control_law
def pd_gravity_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """PD plus gravity compensation (Siciliano et al. eq. 8.53): ``tau = K_P (q_d - q) + K_D (qd_d - qd) +
    g_hat(q)``, with ``gains = [K_P(4), K_D(4)]`` and ``g_hat`` from the controller's ``model``.
    ``signals = [g_hat_3]`` (the compensated quill weight, N)."""
    g = work[0]
    gravity_kernel(q, model, g)
    for i in range(4):
        tau[i] = gains[i] * (ref[i] - q[i]) + gains[4 + i] * (ref[4 + i] - qd[i]) + g[i]
    signals[0] = g[2]
    return 0


@control_law
def torque_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Open loop: a constant torque ``tau = gains[0:4]`` (zero for free motion)."""
    for i in range(4):
        tau[i] = gains[i]
    return 0


def _diag_gain(value, name):
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 2:
        if arr.shape != (4, 4) or np.any(arr != np.diag(np.diag(arr))):
            raise ShapeError(f"{name} must be a diagonal 4x4 matrix or a vector of 4 gains, got {arr.tolist()}")
        arr = np.diag(arr)
    if arr.ndim == 0:
        arr = np.full(4, float(arr))
    arr = as_array(arr, name, (4,))
    if np.any(arr < 0):
        raise ScaraError(f"{name} = {arr.tolist()} must be >= 0 (a negative gain destabilises the loop)")
    return arr.copy()


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
    signal_names = ("gravity_compensation",)
    work_rows = 1

    def __init__(self, K_P=(10000.0, 4000.0, 10000.0, 600.0), K_D=(1000.0, 400.0, 1000.0, 60.0),
                 model: ScaraParams | None = None):
        self.K_P = _diag_gain(K_P, "K_P")
        self.K_D = _diag_gain(K_D, "K_D")
        self.model = _params(model)

    def gains_array(self) -> np.ndarray:
        return np.concatenate([self.K_P, self.K_D])

    def steady_state_error(self, plant: ScaraParams) -> np.ndarray:
        """Theoretical joint error ``q_d - q`` at rest: ``K_P^-1 (g_hat - g)``, i.e. only joint 3 errs by
        ``(m3_hat - m3) g0 / K_P3`` (m), shape (4,)."""
        plant = _params(plant)
        e = np.zeros(4)
        e[2] = (self.model.m3 * self.model.g0 - plant.m3 * plant.g0) / self.K_P[2] if self.K_P[2] > 0 else np.inf
        return e

    def __repr__(self):
        return f"PDGravityController(K_P={self.K_P.tolist()}, K_D={self.K_D.tolist()})"


class TorqueController(Controller):
    """Open loop: a constant joint torque (default zero: the arm moves freely under gravity and friction)."""

    law = staticmethod(torque_law)
    name = "torque"
    reference_kind = "none"

    def __init__(self, tau=(0.0, 0.0, 0.0, 0.0)):
        self.tau = as_array(tau, "tau", (4,)).copy()

    def gains_array(self) -> np.ndarray:
        return self.tau.copy()


# --------------------------------------------------------------------------------------------------
# references
# --------------------------------------------------------------------------------------------------
def ikine_reference(traj, p: ScaraParams | None = None, elbow: int = -1) -> np.ndarray:
    """Joint reference ``[q, qd, qdd]`` (N, 12) from the closed-form inverse kinematics of a trajectory.

    ``q = ikine(x_d)`` (angles unwrapped), ``qd = J_A^-1 xd_d``, ``qdd = J_A^-1 (xdd_d - Jdot_A qd)``: the exact
    joint motion that realises ``x_d`` (no CLIK error). Raises :class:`~scara.UnreachableError` for an
    unreachable sample and :class:`~scara.ScaraError` at a singular configuration.
    """
    p = _params(p)
    x = as_array(traj.x, "traj.x", (4,), allow_batch=True)
    xd = as_array(traj.xd, "traj.xd", (4,), allow_batch=True)
    xdd = as_array(traj.xdd, "traj.xdd", (4,), allow_batch=True)
    q = ikine(x, p, elbow=elbow)
    q[:, 0] = np.unwrap(q[:, 0])
    q[:, 3] = x[:, 3] - q[:, 0] - q[:, 1]
    # every sample at once: the same kernels and the same LAPACK calls as sample by sample
    J = np.empty((len(q), 4, 4))
    _jacobian_rows(q, p.a1, p.a2, J)
    singular = np.abs(np.linalg.det(J)) < 1e-9
    if singular.any():
        k = int(np.argmax(singular))
        raise ScaraError(f"sample {k}: q = {q[k].round(4).tolist()} is singular (sin theta2 = 0)")
    qd = np.linalg.solve(J, xd[:, :, None])[:, :, 0]
    Jd = np.empty_like(J)
    _jacobian_dot_rows(q, qd, p.a1, p.a2, Jd)
    qdd = np.linalg.solve(J, (xdd - (Jd @ qd[:, :, None])[:, :, 0])[:, :, None])[:, :, 0]
    return np.hstack([q, qd, qdd])


@kernel
def _jacobian_rows(q, a1, a2, out):
    """``out[k] = J_A(q[k])`` for every row of ``q`` (N, 4); ``out`` (N, 4, 4)."""
    for k in range(q.shape[0]):
        jacobian_kernel(q[k], a1, a2, out[k])


@kernel
def _jacobian_dot_rows(q, qd, a1, a2, out):
    """``out[k] = Jdot_A(q[k], qd[k])`` for every row; ``out`` (N, 4, 4)."""
    for k in range(q.shape[0]):
        jacobian_dot_kernel(q[k], qd[k], a1, a2, out[k])


def joint_setpoint(q_d, duration: float, dt: float = 1e-3) -> np.ndarray:
    """A constant joint reference ``[q_d, 0, 0]`` of ``round(duration / dt) + 1`` samples, shape (N, 12)."""
    q_d = as_array(q_d, "q_d", (4,))
    n = int(round(check_positive(duration, "duration") / check_positive(dt, "dt"))) + 1
    ref = np.zeros((n, 12))
    ref[:, :4] = q_d
    return ref


def _joint_reference_array(joint_reference):
    jr = joint_reference
    if hasattr(jr, "q") and hasattr(jr, "qd"):
        qdd = getattr(jr, "qdd", None)
        q = np.asarray(jr.q, dtype=float)
        qdd = np.zeros_like(q) if qdd is None else qdd
        jr = (q, jr.qd, qdd)
    if isinstance(jr, (tuple, list)) and len(jr) == 3:
        parts = [as_array(a, f"joint_reference[{i}]", (4,), allow_batch=True) for i, a in enumerate(jr)]
        if not (parts[0].shape == parts[1].shape == parts[2].shape) or parts[0].ndim != 2:
            raise ShapeError(f"joint_reference q, qd, qdd must all have shape (N, 4), got "
                             f"{[a.shape for a in parts]}")
        out = np.empty((len(parts[0]), 12))
        for i, a in enumerate(parts):
            out[:, 4 * i:4 * i + 4] = a
        return out
    return as_array(jr, "joint_reference", (12,), allow_batch=True)


def _clik2_reference(traj, p):
    try:
        from .clik import clik2  # noqa: PLC0415 - optional until chapter 4 exists
    except ImportError:
        warnings.warn("scara.clik.clik2 is not available: joint references come from the closed-form inverse "
                      "kinematics of the trajectory instead", RuntimeWarning, stacklevel=3)
        return ikine_reference(traj, p)
    return _joint_reference_array(clik2(traj))


@kernel
def _operational_kernel(ref, a1, a2, d0, out):
    """``[x, xd, xdd]`` (N, 12) of a joint reference ``[q, qd, qdd]``: ``x = k(q)``, ``xd = J_A qd``,
    ``xdd = J_A qdd + Jdot_A qd``."""
    J = np.empty((4, 4))
    Jd = np.empty((4, 4))
    for k in range(ref.shape[0]):
        q = ref[k, 0:4]
        pose_kernel(q, a1, a2, d0, out[k, 0:4])
        jacobian_kernel(q, a1, a2, J)
        jacobian_dot_kernel(q, ref[k, 4:8], a1, a2, Jd)
        for i in range(4):
            v = 0.0
            a = 0.0
            for j in range(4):
                v += J[i, j] * ref[k, 4 + j]
                a += J[i, j] * ref[k, 8 + j] + Jd[i, j] * ref[k, 4 + j]
            out[k, 4 + i] = v
            out[k, 8 + i] = a


@kernel
def _pose_error(q, x_d, a1, a2, d0, x, e):
    """``x[k] = k(q[k])`` (chapter 1) and ``e[k] = x_d[k] - x[k]`` for every sample, in one pass."""
    for k in range(q.shape[0]):
        q1 = q[k, 0]
        t12 = q1 + q[k, 1]
        x0 = a1 * math.cos(q1) + a2 * math.cos(t12)
        x1 = -(a1 * math.sin(q1) + a2 * math.sin(t12))
        x2 = d0 - q[k, 2]
        x3 = t12 + q[k, 3]
        x[k, 0] = x0
        x[k, 1] = x1
        x[k, 2] = x2
        x[k, 3] = x3
        e[k, 0] = x_d[k, 0] - x0
        e[k, 1] = x_d[k, 1] - x1
        e[k, 2] = x_d[k, 2] - x2
        e[k, 3] = x_d[k, 3] - x3


def _operational_from_joint(ref, p):
    out = np.empty((len(ref), 12))
    _operational_kernel(np.ascontiguousarray(ref), p.a1, p.a2, p.d0, out)
    return out


# --------------------------------------------------------------------------------------------------
# the result
# --------------------------------------------------------------------------------------------------
@dataclass
class SimulationResult:
    """A closed-loop run: samples at ``t`` (N,) of the measured state, the applied torque and the errors.

    Attributes: ``t`` (N,) s; ``q, qd, qdd, tau`` (N, 4) (``qdd`` is the plant's acceleration just after the
    controller's update, ``tau`` the torque held over ``[t_k, t_k + dt)``); ``x`` (N, 4) = ``pose(q)``;
    ``x_d`` (N, 4) desired pose; ``e = x_d - x`` (N, 4); ``reference`` (N, 12) what the controller received;
    ``q_d`` (N, 4) the joint reference (None for operational controllers); ``signals`` dict of the
    controller's internal signals (N,), also readable as attributes (``result.payload_estimate``).
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    tau: np.ndarray
    x: np.ndarray
    x_d: np.ndarray
    e: np.ndarray
    reference: np.ndarray
    reference_kind: str
    q_d: np.ndarray | None
    signals: dict
    controller: str
    plant: ScaraParams
    dt: float
    substeps: int
    elapsed: float = 0.0
    extra: dict = field(default_factory=dict)

    def __getattr__(self, name):
        signals = self.__dict__.get("signals", {})
        if name in signals:
            return signals[name]
        raise AttributeError(f"{type(self).__name__} has no attribute or signal {name!r}; "
                             f"signals: {sorted(signals)}")

    @property
    def joint_error(self) -> np.ndarray:
        """``q_d - q`` (N, 4) for joint-space controllers."""
        if self.q_d is None:
            raise ScaraError("an operational-space run has no joint reference; use .e")
        return self.q_d - self.q

    def energy(self) -> dict:
        """Energy bookkeeping of the plant (J), each (N,): ``kinetic``, ``potential``, ``total``,
        ``input_work`` (exact under zero-order hold: ``sum tau_k^T (q_{k+1} - q_k)``), ``friction_work``
        (``int qd^T F qd dt``, cumulative Simpson on the samples) and ``balance`` =
        ``total - total[0] - input_work + friction_work`` (zero up to integration error)."""
        from scipy.integrate import cumulative_simpson  # noqa: PLC0415

        T = kinetic_energy(self.q, self.qd, self.plant)
        U = potential_energy(self.q, self.plant)
        E = T + U
        dq = np.diff(self.q, axis=0)
        w_in = np.concatenate([[0.0], np.cumsum(np.einsum("ij,ij->i", self.tau[:-1], dq))])
        power = np.einsum("ij,j,ij->i", self.qd, self.plant.F, self.qd)
        w_f = cumulative_simpson(power, x=self.t, initial=0.0) if len(self.t) > 2 else np.zeros_like(power)
        return dict(kinetic=T, potential=U, total=E, input_work=w_in, friction_work=w_f,
                    balance=E - E[0] - w_in + w_f)

    def summary(self, window: float = 2.0) -> dict:
        """Figures for a chapter's table: per component of ``e = x_d - x`` (m, m, m, rad) its maximum
        absolute value, RMS, and steady-state value (mean over the last ``window`` seconds); the largest
        absolute torques; and the run's time."""
        last = self.t >= self.t[-1] - window + 1e-12
        return {
            "controller": self.controller,
            "max_abs_error": np.abs(self.e).max(axis=0),
            "rms_error": np.sqrt(np.mean(self.e ** 2, axis=0)),
            "steady_state_error": self.e[last].mean(axis=0),
            "max_abs_tau": np.abs(self.tau).max(axis=0),
            "elapsed_s": self.elapsed,
        }


# --------------------------------------------------------------------------------------------------
# the public entry point
# --------------------------------------------------------------------------------------------------
def simulate(controller, traj=None, plant: ScaraParams | None = None, dt: float | None = None, *,
             joint_reference=None, q0=None, qd0=None, substeps: int = 1, duration: float | None = None,
             elbow: int = -1, limit: float = 1e6) -> SimulationResult:
    """Run ``controller`` in closed loop on ``plant`` along ``traj``: the simulation engine of chapter 5.

    Parameters
    ----------
    controller : a :class:`Controller` (the engine's interface).
    traj : trajectory with ``t, x, xd, xdd`` (N,)/(N, 4) and ``dt``; may be None when ``joint_reference`` or
        ``duration`` (open loop) is given.
    plant : the true robot, default ``ScaraParams()`` (pass ``ScaraParams().with_payload(5.0)`` for
        the control chapter).
    dt : sampling period (s); default ``traj.dt`` or 1e-3. Must match ``traj.dt`` when both are given.
    joint_reference : (N, 12) ``[q_d, qd_d, qdd_d]``, a ``(q, qd, qdd)`` tuple or an object with
        ``q, qd, qdd`` (a ``clik2`` result). Default for joint controllers: ``clik2(traj)``.
    q0, qd0 : initial state; default the reference's first sample (joint controllers) or the inverse
        kinematics of ``x_d(0)`` with ``elbow`` (operational controllers); ``qd0`` default zero / reference.
    substeps : RK4 steps per sampling period (the torque is held over all of them).
    duration : length (s) of an open-loop run (``reference_kind == "none"``) without trajectory.
    limit : a state or torque entry above this magnitude stops the run with :class:`~scara.UnstableError`.

    Returns :class:`SimulationResult`. Raises :class:`~scara.ScaraError` for inconsistent inputs and
    :class:`~scara.UnstableError` (with the time and cause) when the run diverges.
    """
    plant = _params(plant)
    if not hasattr(controller, "law") or controller.law is None:
        raise ScaraError(f"controller {controller!r} has no compiled law: see scara.simulate's interface")
    if isinstance(substeps, bool) or int(substeps) != substeps or substeps < 1:
        raise ScaraError(f"substeps = {substeps!r} must be a whole number >= 1")
    substeps = int(substeps)
    kind = controller.reference_kind
    if kind not in ("joint", "operational", "none"):
        raise ScaraError(f"reference_kind = {kind!r}; expected 'joint', 'operational' or 'none'")
    tdt = getattr(traj, "dt", None) if traj is not None else None
    if dt is None:
        dt = tdt if tdt is not None else 1e-3
    dt = check_positive(dt, "dt")
    if tdt is not None and abs(tdt - dt) > 1e-12 * dt:
        raise ScaraError(f"dt = {dt} differs from the trajectory's sampling period {tdt}; resample the trajectory")

    # references
    jref = None
    if joint_reference is not None:
        jref = np.ascontiguousarray(_joint_reference_array(joint_reference))
    elif kind == "joint":
        if traj is None:
            raise ScaraError("a joint-space controller needs traj or joint_reference")
        jref = np.ascontiguousarray(_clik2_reference(traj, plant))
    x_d = None
    xop = None
    if traj is not None:
        x_d = as_array(traj.x, "traj.x", (4,), allow_batch=True)
        n = len(x_d)
        if kind == "operational" or jref is None:
            xop = np.empty((n, 12))
            xop[:, 0:4] = x_d
            xop[:, 4:8] = as_array(traj.xd, "traj.xd", (4,), allow_batch=True)
            xop[:, 8:12] = as_array(traj.xdd, "traj.xdd", (4,), allow_batch=True)
    elif jref is not None:
        # the operational reference realised by the joint reference (x_d for the error e)
        xop = _operational_from_joint(jref, plant) if kind == "operational" else None
        x_d = pose(jref[:, :4], plant)
        n = len(jref)
    elif duration is not None:
        n = int(round(check_positive(duration, "duration") / dt)) + 1
    else:
        raise ScaraError("give traj, joint_reference or (for an open-loop run) duration")
    if jref is not None and len(jref) != n:
        raise ShapeError(f"joint_reference has {len(jref)} samples but the trajectory has {n}")
    if kind == "joint":
        ref = jref
    elif kind == "operational":
        ref = np.ascontiguousarray(xop)
    else:
        ref = np.zeros((n, 12))

    # initial state
    if q0 is None:
        if jref is not None:
            q0 = jref[0, :4]
        elif getattr(traj, "q0", None) is not None:
            q0 = traj.q0
        elif xop is not None:
            q0 = ikine(xop[0, :4], plant, elbow=elbow)
        else:
            raise ScaraError("an open-loop run without reference needs q0")
    q0 = np.ascontiguousarray(as_array(q0, "q0", (4,)), dtype=float).copy()
    if qd0 is None:
        if jref is not None:
            qd0 = jref[0, 4:8]
        elif xop is not None:
            qd0 = np.linalg.solve(jacobian(q0, plant), xop[0, 4:8])
        else:
            qd0 = np.zeros(4)
    qd0 = np.ascontiguousarray(as_array(qd0, "qd0", (4,)), dtype=float).copy()

    gains = np.ascontiguousarray(controller.gains_array(), dtype=float)
    model = np.ascontiguousarray(controller.model_array(), dtype=float)
    state = np.ascontiguousarray(controller.initial_state(), dtype=float).copy()
    names = tuple(controller.signal_names)
    work = np.zeros((max(int(controller.work_rows), 0), 4))
    # one allocation for the six (N, 4) series (each a C-contiguous slice): a block this large is backed by
    # huge pages where the system allows it, which saves thousands of page faults per run
    block = np.empty((6, n, 4))
    q_out, qd_out, qdd_out, tau_out, x, e = block
    sig_out = np.zeros((n, len(names)))
    info = np.zeros(3, dtype=np.int64)
    law = _compiled_law(controller.law)  # compile (or load) the law and the loop before the clock starts
    loop = _compile.dispatcher_of(closed_loop_kernel)
    t0 = time.perf_counter()
    loop(law, q0, qd0, ref, dt, substeps, dynamic_array(plant), gains, model, state, work, q_out, qd_out, qdd_out,
         tau_out, sig_out, float(limit), info)
    elapsed = time.perf_counter() - t0
    if info[0] != OK:
        k = int(info[1])
        code = int(info[2])
        explain = getattr(controller, "explain", None)  # a controller may name the cause behind its codes
        law_cause = f"the controller's law returned code {code}" + (f": {explain(code)}" if explain else "")
        cause = {LAW_FAILED: law_cause,
                 DIVERGED: f"a joint state or torque exceeded {limit:g} or is not finite",
                 SINGULAR_INERTIA: "the plant's inertia matrix lost positive definiteness"}[int(info[0])]
        raise UnstableError(f"the closed loop of {getattr(controller, 'name', controller)} diverged at "
                            f"t = {k * dt:.4f} s (sample {k}): {cause}")
    t = np.arange(n) * dt
    _pose_error(q_out, q_out if x_d is None else np.ascontiguousarray(x_d), plant.a1, plant.a2, plant.d0, x, e)
    if x_d is None:
        x_d = x.copy()
        e[:] = 0.0
    return SimulationResult(t=t, q=q_out, qd=qd_out, qdd=qdd_out, tau=tau_out, x=x, x_d=x_d, e=e,
                            reference=ref, reference_kind=kind, q_d=None if jref is None else jref[:, :4],
                            signals={nm: np.ascontiguousarray(sig_out[:, i]) for i, nm in enumerate(names)},
                            controller=getattr(controller, "name", type(controller).__name__), plant=plant,
                            dt=dt, substeps=substeps, elapsed=elapsed,
                            extra={"final_state": state})
