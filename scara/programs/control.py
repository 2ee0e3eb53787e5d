"""The page program of chapter 6's controllers panel: one move of the panel as one compiled kernel,
:func:`control_program` (numba in Jupyter; translated to JavaScript, the page's engine).

A move (the dropdown's controller, its gains, the true payload) makes the controller as its constructor does (the
same check kernels: :func:`~scara.control.robust.lambda_status`, :func:`~scara.control.operational.integral_status`,
:func:`~scara.control.independent.placed_gains`...; the gain arrays packed by the packers of the laws' layouts),
takes the joint reference of its data (the second-order CLIK of chapter 4, :func:`~scara._clik.kernels._clik2_kernel`,
run once by :func:`fill_joint_reference`) or the operational one, checks the start and the law's arrays (the guard-entry trial of
:func:`~scara._simulate.interface.check_law_bounds`), runs the closed loop of :mod:`scara._simulate` (the law chosen
by index, the plant integrated by RK4: the engine's own kernels), and reduces the run to what the panel shows: the
figures of the chapter's table (:func:`~scara.control.control_summary`), the upper envelope of the position error,
the torques and the controller's own signal thinned to the panel's ``points`` samples, the numbers of the title.
A setting the package refuses returns the code of its refusal, with the numbers its message names written in
``out`` (:func:`control_refusals` words them as :func:`scara.simulate` and the controllers do).

Its ``data`` (:func:`control_data`) is the desired trajectory sampled at ``dt`` (``x_d``, ``xd_d``, ``xdd_d``, each
(N, 4) row-major) and its joint reference (``q``, ``qd``, ``qdd``, computed once, as it depends on the trajectory
alone) after a header (:data:`HEADER`) that declares where each block starts and whether the reference was refused,
with the robot, the controllers' model and the constants of the laws; the output fields are
:func:`control_outputs`.
"""
from __future__ import annotations

import math
import re

import numpy as np

from .._clik.kernels import _clik2_kernel, _solve_exact
from .._clik.records import (COMPONENTS, SEED_K, STATUS_DONE, STATUS_ERROR_BOUND, STATUS_SINGULAR,
                             Reference, SecondOrderLaw)
from .._clik.records import Series as ClikSeries
from .._compile import ArrayLayout, kernel
from .._simulate.engine import (_after_law, _before_law, _loop_start, failure_cause, failure_message,
                                first_bad_signal)
from .._simulate.interface import (DIVERGED, GUARD, JOINT_LIMIT, LAW_FAILED, NOT_FINITE, OK, READS_PAST,
                                   READS_PAST_ANY, SINGULAR_INERTIA, WRITES_PAST, _FILLS, _TRIAL_ARRAYS, described,
                                   fill_text, guard_change, same_entries)
from .._simulate.plant import _plant_constants
from .._simulate.result import _pose_error
from .._simulate.setpoints import START_STROKE_MESSAGE, in_stroke
from ..trajectory._plan import sample_plan
from .thinning import LOG_FLOOR, envelope_kernel, envelope_length, thin_index, thin_length
from ..control._common import FAILURE_CAUSES, MAX_ERROR, TAU_MAX, BoundedController
from ..control.adaptive import FROZEN, SMALL_WEIGHT_MESSAGE, AdaptiveController, adaptation_rates, adaptive_law
from ..control.adaptive import pack_gains as _adaptive_gains
from ..control.independent import (B_BAR, ROUTH_MESSAGE, SLOW_POLE_MESSAGE, IndependentJointController,
                                   independent_law, margin_status, placed_gains)
from ..control.independent import pack_gains as _independent_gains
from ..control.classic import (JURY_MESSAGE, PDG_GAINS, ComputedTorqueController, PDPlusGravityController, computed_torque_law,
                               computed_torque_steady_state, critical_gains, jury_status, pack_bounded_gains,
                               pd_plus_gravity_law, sampling_limit)
from .._simulate.controllers import pd_gravity_steady_state_kernel
from ..control.operational import INTEGRAL_MESSAGE, OperationalSpaceController, integral_status, operational_law
from ..control.operational import pack_gains as _operational_gains
from ..control.robust import B_HAT, LAMBDA_MESSAGE, RobustController, lambda_status, robust_law, sliding_rows
from ..control.robust import pack_gains as _robust_gains
from ..dynamics import (DP_A1, DP_A2, DP_D0, DP_ML, N_DP, N_PI, cholesky_solve4, dynamic_array, gravity_kernel,
                        inertia_kernel, lumped_parameters, pi_kernel)
from ..errors import ScaraError, ShapeError, as_array, check_count
from ..kinematics import IK_OK, IK_OUTSIDE_ANNULUS, SINGULAR_SIN, Geometry, ikine, ikine_kernel, jacobian_kernel
from ..kinematics import planar_jacobian, planar_trig
from ..params import ScaraParams

__all__ = ["LAWS", "OTHER_LAW", "INPUTS", "HEADER", "SCALARS", "ARRAYS", "control_program", "control_core",
           "control_data", "control_outputs", "control_refusals", "run_outputs", "own_run_outputs",
           "joint_reference_rows", "joint_reference_refusal", "thin_length", "thin_index", "envelope_length"]

# --------------------------------------------------------------------------------------------------
# the panel's controls, the laws, the layouts of the data and of the outputs
# --------------------------------------------------------------------------------------------------
#: The controllers of the panel's dropdown, in its order (``inputs[0]`` is the index): the controllers' names
LAWS = ("robust", "adaptive", "operational", "operational_noint", "independent", "pd_plus_gravity", "computed_torque")
ROBUST, ADAPTIVE, OPERATIONAL, NO_INTEGRAL, INDEPENDENT, PD_GRAVITY, COMPUTED_TORQUE = range(7)
#: The index :func:`run_outputs` takes for a law the program does not run (a reader's own controller, run by
#: :func:`scara.simulate`): no error trace of the program's is shown, and its own signal drawn is ``e_z``
OTHER_LAW = len(LAWS)
#: The controller class of each law, and whether it tracks the joint reference (1) or the operational one (0)
_CLASSES = (RobustController, AdaptiveController, OperationalSpaceController, OperationalSpaceController,
            IndependentJointController, PDPlusGravityController, ComputedTorqueController)
_JOINT = tuple(1 if c.reference_kind == "joint" else 0 for c in _CLASSES)
#: The sizes of each law's arrays, from the layouts its controller declares (gains, state, work rows, signals)
_NG = tuple(c.gains_layout.size for c in _CLASSES)
_NS = tuple(c.state_layout.size for c in _CLASSES)
_NW = tuple(c.work_layout.size for c in _CLASSES)
_NSIG = tuple(c.signals_layout.size for c in _CLASSES)
_SIGNAL_NAMES = tuple(c.signals_layout.entry_names for c in _CLASSES)

#: The panel's controls the program reads, in the order of ``inputs`` (the dropdown as the index of its value)
INPUTS = ("controller", "payload", "K_P", "K_D", "Lambda", "rho", "epsilon", "K_D_scale", "K_pi", "K_I", "omega")
_I_LAW, _I_PAYLOAD, _I_KP, _I_KD, _I_LAMBDA, _I_RHO, _I_EPS, _I_KDS, _I_KPI, _I_KI, _I_OMEGA = range(len(INPUTS))

#: The book's adaptive ``K_D`` (N m s/rad, N s/m) that the panel's ``K_D_scale`` multiplies
ADAPTIVE_K_D = (600.0, 300.0, 1000.0, 60.0)
#: What the panel's table measures (s): the error after the first ``SETTLE`` seconds, at rest over the last ``REST``
SETTLE, REST = 1.0, 2.0
#: The bound on any state or torque entry of the run (:func:`scara.simulate`'s default ``limit``)
LIMIT = 1e6

#: The output arrays (their sizes depend on the run's samples and the panel's ``points``): the error's envelope
#: (``err_t``, ``err_y``, m), the thinned time (s), the quill's force (N) and the other torques (N m), the adaptive
#: payload estimate (kg), the envelope of the robust ``||z||`` (on ``err_t``), the vertical error ``e_z`` (mm)
ARRAYS = ("err_t", "err_y", "t", "f3", "tau1", "tau2", "tau4", "estimate", "z_norm", "e_z")
_ENVELOPES = ("err_t", "err_y", "z_norm")
(_A_ERR_T, _A_ERR_Y, _A_T, _A_F3, _A_TAU1, _A_TAU2, _A_TAU4, _A_EST, _A_Z, _A_EZ) = range(len(ARRAYS))

#: The header of ``data`` (:func:`control_data`): the run's sampling, where the trajectory's blocks start, the
#: operational start ``q0``, the controllers' model and the plant without its payload (:data:`~scara.dynamics.
#: DYNAMIC_LAYOUT` each), the quill's stroke, the stated bounds, the laws' constants, the CLIK's gains, the
#: panel's ``points`` and the table's windows, the counts and offsets of the output arrays
HEADER = ArrayLayout(("n", 1), ("dt", 1), ("elbow", 1), ("x_at", 1), ("xd_at", 1), ("xdd_at", 1), ("jref_at", 1),
                     ("jref_code", 1), ("q0", 4),
                     ("model", N_DP), ("plant", N_DP), ("d3_min", 1), ("d3_max", 1), ("tau_max", 4),
                     ("max_error", 1), ("limit", 1), ("B_hat", 4), ("B_bar", 4), ("adaptive_K_D", 4),
                     ("clik_K_P", 4), ("clik_K_D", 4), ("clik_max_error", 1), ("points", 1), ("settle", 1),
                     ("rest", 1), ("n_thin", 1), ("n_envelope", 1), ("out_at", len(ARRAYS)))
(_H_N, _H_DT, _H_ELBOW, _H_X, _H_XD, _H_XDD, _H_JREF, _H_JREF_CODE, _H_Q0, _H_MODEL, _H_PLANT, _H_D3_MIN, _H_D3_MAX, _H_TAU_MAX,
 _H_MAX_ERROR, _H_LIMIT, _H_B_HAT, _H_B_BAR, _H_ADAPTIVE_KD, _H_CLIK_KP, _H_CLIK_KD, _H_CLIK_MAX_ERROR, _H_POINTS,
 _H_SETTLE, _H_REST, _H_N_THIN, _H_N_ENV, _H_OUT_AT) = HEADER.offsets

#: The output numbers: the figures of the chapter's table (:func:`~scara.control.control_summary`: m, rad, N m), the
#: title's (mm, N, s, ms), the controllers' own (1/s, kg, N m/rad, mm), the flags of the traces and axes shown and
#: of the note (1 or 0), and the numbers a refusal names
SCALARS = ArrayLayout(
    ("max_position_error", 1), ("rms_position_error", 1), ("max_orientation_error", 1), ("final_position_error", 1),
    ("steady_z_error", 1), ("peak_tau", 4), ("chattering", 1),
    ("max_position_error_mm", 1), ("final_position_error_mm", 1), ("peak_f3", 1), ("duration", 1), ("dt_ms", 1),
    ("rho_over_epsilon", 1), ("payload_estimate", 1), ("largest_K_P", 1), ("steady_z_error_mm", 1), ("theory_mm", 1),
    ("robust_shown", 1), ("adaptive_shown", 1), ("operational_shown", 1), ("operational_noint_shown", 1),
    ("independent_shown", 1), ("pd_plus_gravity_shown", 1), ("computed_torque_shown", 1), ("estimate_shown", 1), ("z_shown", 1), ("e_z_shown", 1), ("not_compensated", 1),
    ("bad_value", 1), ("bad_limit", 1), ("fail_t", 1), ("fail_k", 1), ("fail_value", 1), ("fail_joint", 1),
    ("fail_d3", 1), ("fail_v3", 1), ("fail_code", 1), ("fail_theta2", 1), ("fail_w", 1), ("friction", 1),
    ("reach", 1), ("d3_min", 1), ("d3_max", 1), ("start_px", 1), ("start_py", 1), ("start_pz", 1), ("start_phi_deg", 1))
(_O_MAXP, _O_RMSP, _O_MAXO, _O_FINALP, _O_STEADYZ, _O_PEAK, _O_CHAT, _O_MAXP_MM, _O_FINALP_MM, _O_PEAK_F3,
 _O_DURATION, _O_DT_MS, _O_RHO_EPS, _O_ESTIMATE, _O_LARGEST_KP, _O_STEADYZ_MM, _O_THEORY_MM, _O_SHOWN,
 _O_SHOWN_ADAPTIVE, _O_SHOWN_OP, _O_SHOWN_NOINT, _O_SHOWN_INDEP, _O_SHOWN_PDG, _O_SHOWN_CT, _O_EST_SHOWN, _O_Z_SHOWN, _O_EZ_SHOWN,
 _O_NOT_COMPENSATED, _O_BAD_VALUE, _O_BAD_LIMIT, _O_FAIL_T, _O_FAIL_K, _O_FAIL_VALUE, _O_FAIL_JOINT, _O_FAIL_D3,
 _O_FAIL_V3, _O_FAIL_CODE, _O_FAIL_THETA2, _O_FAIL_W, _O_FRICTION, _O_REACH, _O_D3_MIN, _O_D3_MAX, _O_START_X,
 _O_START_PY, _O_START_PZ, _O_START_PHI) = SCALARS.offsets
_SCALARS_SIZE = SCALARS.size
#: where the outputs of :data:`RUN_FIELDS` are (:func:`run_refusal`)
_RUN_AT = (_O_FAIL_K, _O_FAIL_T, _O_FAIL_VALUE, _O_FAIL_JOINT, _O_D3_MIN, _O_D3_MAX, _O_FAIL_D3, _O_FAIL_V3, _O_FAIL_CODE)
#: The flag of each law's error trace (``robust_shown`` ...), in the order of :data:`LAWS`
SHOWN = tuple(f"{name}_shown" for name in LAWS)

# --------------------------------------------------------------------------------------------------
# the refusal codes (:func:`control_refusals` words each)
# --------------------------------------------------------------------------------------------------
#: The gains the panel's controls give, in the order of the refusal codes (``_R_GAIN + 2 g``: not finite, ``+ 1``:
#: not positive); ``rho`` and ``epsilon`` are numbers (:func:`~scara.errors.check_positive`), the others vectors
_GAINS = ("K_P", "K_D", "Lambda", "rho", "epsilon", "K_pi", "K_I", "omega", "m_L")
_G_KP, _G_KD, _G_LAMBDA, _G_RHO, _G_EPS, _G_KPI, _G_KI, _G_OMEGA, _G_ML = range(len(_GAINS))
_R_START_STROKE, _R_START_SINGULAR, _R_CLIK_ANNULUS, _R_CLIK_STROKE, _R_CLIK_SINGULAR_START = 1, 2, 3, 4, 5
_R_CLIK_NONFINITE, _R_CLIK_SINGULAR, _R_CLIK_ERROR, _R_SHORT = 6, 7, 8, 12   # _R_CLIK_ERROR + component (4)
_R_GAIN = 20                  # + 2 gain + (0 not finite, 1 not positive)
_R_LAMBDA, _R_INTEGRAL, _R_SLOW_POLE, _R_ROUTH, _R_SMALL_WEIGHT, _R_FROZEN = 40, 44, 48, 52, 56, 70   # + joint
_R_SLOW_POLE_PD, _R_JURY = 72, 76   # + joint
#: where both classic laws keep K_P in their gains (the same layout)
_CLASSIC_KP = PDG_GAINS.offsets[0]
_R_TRIAL = 100                # + 20 law + 2 array + (0 writes past, 1 reads past); + 12: reads past some array
_R_RUN = 1000                 # + 100 law + cause (below)
_C_LAW, _C_LAW_OTHER, _C_DIVERGED, _C_SINGULAR, _C_JOINT_MAX, _C_JOINT_MIN, _C_TORQUE, _C_SIGNAL = 0, 9, 10, 11, 12, 13, \
    20, 30   # _C_LAW + the law's code (2, 3, 4); _C_SIGNAL + the signal's index


# --------------------------------------------------------------------------------------------------
# the controller of a move: checks, gains, initial state
# --------------------------------------------------------------------------------------------------
@kernel
def _gain_code(v, gain):
    """0 for a gain ``v`` that is finite and positive, else its refusal code (``_R_GAIN + 2 gain``, ``+ 1``)."""
    if not math.isfinite(v):
        return _R_GAIN + 2 * gain
    if not v > 0.0:
        return _R_GAIN + 2 * gain + 1
    return 0


@kernel
def _filled(v):
    """A new (4,) array of ``v``: a panel's slider gives every joint or component the same gain."""
    a = np.empty(4)
    for i in range(4):
        a[i] = v
    return a


@kernel
def _refuse_gain(v, gain, out):
    """The refusal code of the gain ``v`` (0 if it is fine), its value written for the message."""
    code = _gain_code(v, gain)
    if code != 0:
        out[_O_BAD_VALUE] = v
    return code


@kernel
def _refuse_gains(v1, g1, v2, g2, v3, g3, out):
    """The first refusal of three gains checked in turn (:func:`_refuse_gain`), or 0."""
    code = _refuse_gain(v1, g1, out)
    if code == 0:
        code = _refuse_gain(v2, g2, out)
    if code == 0:
        code = _refuse_gain(v3, g3, out)
    return code


@kernel
def _make_law(law, inputs, data, model, gains, state, out):
    """Check the gains of ``law`` and pack its arrays, as its controller's constructor and ``gains_array`` /
    ``initial_state`` do (with :func:`~scara.widgets.control.make_controller`'s mapping of the panel's controls):
    ``gains`` and ``state`` of the law's layouts; ``model`` the controllers' model. Returns 0, or the refusal code
    (the numbers it names written in ``out``). The checks run in the constructors' order."""
    tmax = data[_H_TAU_MAX:_H_TAU_MAX + 4]
    emax = data[_H_MAX_ERROR]
    if law == ROBUST:
        kp, kd, rho, eps, lam = inputs[_I_KP], inputs[_I_KD], inputs[_I_RHO], inputs[_I_EPS], inputs[_I_LAMBDA]
        code = _refuse_gains(kp, _G_KP, kd, _G_KD, rho, _G_RHO, out)
        if code == 0:
            code = _refuse_gains(eps, _G_EPS, lam, _G_LAMBDA, lam, _G_LAMBDA, out)
        if code != 0:
            return code
        K_P = _filled(kp)
        K_D = _filled(kd)
        Lam = _filled(lam)
        i = lambda_status(Lam, K_D)
        if i >= 0:
            out[_O_BAD_VALUE] = Lam[i]
            out[_O_BAD_LIMIT] = K_D[i]
            return _R_LAMBDA + i
        Z = np.empty(32)
        sliding_rows(K_P, K_D, Lam, Z)
        _robust_gains(K_P, K_D, Z, rho, eps, data[_H_B_HAT:_H_B_HAT + 4], tmax, emax, gains)
        return 0
    if law == ADAPTIVE:
        lam = inputs[_I_LAMBDA]
        code = _refuse_gain(lam, _G_LAMBDA, out)
        if code != 0:
            return code
        K_D = np.empty(4)
        for i in range(4):
            K_D[i] = inputs[_I_KDS] * data[_H_ADAPTIVE_KD + i]
        for i in range(4):
            code = _refuse_gain(K_D[i], _G_KD, out)
            if code != 0:
                return code
        code = _refuse_gain(inputs[_I_KPI], _G_KPI, out)
        if code != 0:
            return code
        weights = np.empty(N_PI)
        for j in range(N_PI):
            weights[j] = math.inf
        weights[0] = inputs[_I_KPI]   # K_pi = {"m3": value}: only the lumped mass m3 adapts
        rates = np.empty(N_PI)
        i = adaptation_rates(weights, rates)
        if i == FROZEN:
            return _R_FROZEN
        if i >= 0:
            out[_O_BAD_VALUE] = weights[i]
            return _R_SMALL_WEIGHT + i
        _adaptive_gains(_filled(lam), K_D, rates, tmax, emax, gains)
        pi_kernel(model, state)   # the initial estimate: the model's own parameters (no payload)
        return 0
    if law == OPERATIONAL or law == NO_INTEGRAL:
        kp, kd = inputs[_I_KP], inputs[_I_KD]
        code = _refuse_gains(kp, _G_KP, kd, _G_KD, kd, _G_KD, out)
        if code != 0:
            return code
        K_P = _filled(kp)
        K_D = _filled(kd)
        K_I = _filled(0.0)
        if law == OPERATIONAL:
            code = _refuse_gain(inputs[_I_KI], _G_KI, out)
            if code != 0:
                return code
            K_I = _filled(inputs[_I_KI])
            i = integral_status(K_P, K_D, K_I)
            if i >= 0:
                out[_O_BAD_VALUE] = K_I[i]
                out[_O_BAD_LIMIT] = K_D[i] * K_P[i]
                return _R_INTEGRAL + i
        _operational_gains(K_P, K_D, K_I, tmax, emax, gains)
        return 0
    omega = inputs[_I_OMEGA]
    code = _refuse_gain(omega, _G_OMEGA, out)
    if code != 0:
        return code
    W = _filled(omega)
    K_P = np.empty(4)
    K_D = np.empty(4)
    if law == COMPUTED_TORQUE:   # K_P = omega^2, K_D = 2 zeta omega with zeta = 1, checked against the sampling
        critical_gains(W, _filled(1.0), K_P, K_D)
        i = jury_status(K_P, K_D, data[_H_DT])
        if i >= 0:
            out[_O_BAD_VALUE] = K_P[i]
            out[_O_BAD_LIMIT] = sampling_limit(1.0, data[_H_DT])
            out[_O_FAIL_VALUE] = K_D[i]
            out[_O_FAIL_T] = data[_H_DT]
            return _R_JURY + i
        pack_bounded_gains(K_P, K_D, tmax, emax, gains)
        return 0
    # the independent-joint PID and PD + gravity: the pole placement on the nominal model (a triple pole, or a double
    # one without the integral), the controller's friction F = k_r^2 F_m
    lp = lumped_parameters(model)
    F = np.empty(4)
    F[0], F[1], F[2], F[3] = lp.F1, lp.F2, lp.F3, lp.F4
    B_bar = data[_H_B_BAR:_H_B_BAR + 4]
    K_I = np.empty(4)
    integral = law == INDEPENDENT
    order = 3.0 if integral else 2.0
    i = placed_gains(B_bar, W, F, integral, K_P, K_D, K_I)
    if i >= 0:
        out[_O_BAD_VALUE] = omega
        out[_O_BAD_LIMIT] = F[i] / (order * B_bar[i])
        out[_O_FAIL_VALUE] = K_D[i]
        out[_O_REACH] = order * omega * B_bar[i]
        out[_O_FRICTION] = F[i]
        return (_R_SLOW_POLE if integral else _R_SLOW_POLE_PD) + i
    if not integral:
        pack_bounded_gains(K_P, K_D, tmax, emax, gains)
        return 0
    i = margin_status(F, K_P, K_D, K_I, B_bar)
    if i >= 0:
        out[_O_BAD_VALUE] = K_I[i]
        out[_O_BAD_LIMIT] = (F[i] + K_D[i]) * K_P[i] / B_bar[i]
        return _R_ROUTH + i
    largest = K_P[0]
    for j in range(1, 4):
        largest = max(largest, K_P[j])
    out[_O_LARGEST_KP] = largest
    _independent_gains(B_bar, F, K_P, K_D, K_I, 1.0, 1.0, 1.0, tmax, emax, gains)
    return 0


# --------------------------------------------------------------------------------------------------
# the references and the start
# --------------------------------------------------------------------------------------------------
@kernel
def _joint_reference(x, xd, xdd, dt, arm, stroke, elbow, K_P, K_D, max_err, q, qd, qdd, xs, es, ws, out):
    """The joint reference of the controllers that track one: :func:`scara.clik2` of the trajectory ``x``, ``xd``,
    ``xdd`` (N, 4) with its default settings (gains ``K_P``, ``K_D``, no damping, ``max_err``), from the start of
    chapter 4 (the inverse kinematics of ``x[0]`` with ``elbow``, at rest or moving as ``J_A^-1 xd[0]``), into
    ``q``, ``qd``, ``qdd`` (N, 4) (``xs``, ``es``, ``ws`` the CLIK's pose, error and manipulability). ``arm`` is the
    :class:`~scara.kinematics.Geometry`, ``stroke = (d3_min, d3_max)``. Returns 0, or a refusal code."""
    q0 = np.empty(4)
    code = ikine_kernel(x[0], arm.a1, arm.a2, arm.d0, stroke[0], stroke[1], elbow, q0)
    if code != IK_OK:
        for i in range(3):
            out[_O_START_X + i] = x[0, i]   # start_px, start_py, start_pz
        out[_O_START_PHI] = math.degrees(x[0, 3])
        out[_O_FAIL_VALUE] = math.hypot(x[0, 0], x[0, 1])
        out[_O_FAIL_D3] = arm.d0 - x[0, 2]
        return _R_CLIK_ANNULUS if code == IK_OUTSIDE_ANNULUS else _R_CLIK_STROKE
    if abs(math.sin(q0[1])) <= SINGULAR_SIN:
        out[_O_FAIL_THETA2] = q0[1]
        return _R_CLIK_SINGULAR_START
    ok, s = _solve_exact(planar_jacobian(planar_trig(q0[0], q0[1]), arm.a1, arm.a2),
                         (xd[0, 0], xd[0, 1], xd[0, 2], xd[0, 3]))
    for i in range(4):
        q[0, i] = q0[i]
        qd[0, i] = s[i]
    info = np.zeros(2)
    _clik2_kernel(Reference(x, xd, xdd), SecondOrderLaw(dt, K_P, K_D, 0.0, 0.0, max_err), arm,
                  ClikSeries(q, qd, qdd, xs, es, ws), info)
    status = int(info[0])
    if status == STATUS_DONE:
        return 0
    k = int(info[1])
    out[_O_FAIL_K] = k
    out[_O_FAIL_T] = k * dt
    if status == STATUS_ERROR_BOUND:
        i = 0   # the component with the largest error (all four are kept)
        for j in range(1, 4):
            if abs(es[k, j]) > abs(es[k, i]):
                i = j
        out[_O_FAIL_VALUE] = es[k, i]
        return _R_CLIK_ERROR + i
    if status == STATUS_SINGULAR:
        out[_O_FAIL_THETA2] = q[k, 1]
        out[_O_FAIL_W] = ws[k]
        return _R_CLIK_SINGULAR
    return _R_CLIK_NONFINITE


@kernel
def fill_joint_reference(data, out):
    """The joint reference of ``data`` (:func:`control_data`), once per panel, not once per move: it depends on the
    trajectory alone. :func:`_joint_reference` of its ``x_d``, ``xd_d``, ``xdd_d`` with the header's CLIK settings
    into the block at ``jref_at`` (``q``, ``qd``, ``qdd``, (N, 4) each), its code in ``jref_code``; the numbers a
    refusal names are written in ``out``. Returns the code (0: the reference is there)."""
    n = int(data[_H_N])
    x = _rows(data, int(data[_H_X]), n, 4)
    xd = _rows(data, int(data[_H_XD]), n, 4)
    xdd = _rows(data, int(data[_H_XDD]), n, 4)
    at = int(data[_H_JREF])
    arm = Geometry(data[_H_PLANT + DP_A1], data[_H_PLANT + DP_A2], data[_H_PLANT + DP_D0])
    code = _joint_reference(x, xd, xdd, data[_H_DT], arm, (data[_H_D3_MIN], data[_H_D3_MAX]), data[_H_ELBOW],
                            data[_H_CLIK_KP:_H_CLIK_KP + 4], data[_H_CLIK_KD:_H_CLIK_KD + 4],
                            data[_H_CLIK_MAX_ERROR], _rows(data, at, n, 4), _rows(data, at + 4 * n, n, 4),
                            _rows(data, at + 8 * n, n, 4), np.empty((n, 4)), np.empty((n, 4)), np.empty(n), out)
    data[_H_JREF_CODE] = code
    return code


@kernel
def _start_velocity(q0, xd0, a1, a2, qd0):
    """``qd0 = J_A(q0)^-1 xd0`` (4,) in closed form (:func:`~scara._clik.kernels._solve_exact`): the start speeds of
    an operational run. Returns False at a singular start (``|sin theta2| <= SINGULAR_SIN``, the rule of
    :func:`~scara.kinematics.check_regular`)."""
    if abs(math.sin(q0[1])) <= SINGULAR_SIN:
        return False
    ok, s = _solve_exact(planar_jacobian(planar_trig(q0[0], q0[1]), a1, a2), (xd0[0], xd0[1], xd0[2], xd0[3]))
    for i in range(4):
        qd0[i] = s[i]
    return ok


# --------------------------------------------------------------------------------------------------
# the law of a move, chosen by index, and the closed loop around it
# --------------------------------------------------------------------------------------------------
@kernel(inline="always")
def _law_step(law, k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """One step of the law of index ``law`` (:data:`LAWS`): the laws of :mod:`scara.control`, with the engine's
    twelve arguments (:data:`~scara._compile.LAW_SIGNATURE`). Returns the law's code."""
    if law == ROBUST:
        return robust_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    elif law == ADAPTIVE:
        return adaptive_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    elif law == OPERATIONAL or law == NO_INTEGRAL:
        return operational_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    elif law == PD_GRAVITY:
        return pd_plus_gravity_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    elif law == COMPUTED_TORQUE:
        return computed_torque_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    return independent_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)


@kernel
def _closed_loop(law, q0, qd0, ref_pos, ref_vel, ref_acc, dt, substeps, limit, d3_mid, d3_half, plant_dp, gains, model,
                 state, work, q_out, qd_out, qdd_out, tau_out, sig_out, info):
    """The engine's loop (:func:`scara._simulate.engine.closed_loop_kernel`: the same steps, its own kernels
    :func:`~scara._simulate.engine._before_law` and :func:`~scara._simulate.engine._after_law` around the law) with
    the law of index ``law`` (:func:`_law_step`, not a law passed as a function, which the page's engine cannot
    take) and the reference rows read from ``ref_pos``, ``ref_vel``, ``ref_acc`` (N, 4) each. ``info`` (3,)
    receives ``[code, k, law_code]``."""
    n = ref_pos.shape[0]
    n_sig = sig_out.shape[1]
    pc = _plant_constants(plant_dp)
    q = np.empty(4)
    qd = np.empty(4)
    qdd = np.empty(4)
    spare = np.empty(4)
    q_law = np.empty(4)
    qd_law = np.empty(4)
    r = np.empty(12)
    tau = np.empty(4)
    sig = np.empty(n_sig)
    _loop_start(q0, qd0, q, qd, n, info)
    h = dt / substeps
    for k in range(n):
        _before_law(k, q, qd, q_out, qd_out, q_law, qd_law, tau, sig)
        for i in range(4):
            r[i] = ref_pos[k, i]
            r[4 + i] = ref_vel[k, i]
            r[8 + i] = ref_acc[k, i]
        code = _law_step(law, k, k * dt, dt, q_law, qd_law, r, gains, model, state, work, sig, tau)
        if _after_law(k, n, code, q, qd, qdd, spare, tau, sig, pc, h, substeps, limit, d3_mid, d3_half, q_out,
                      qd_out, qdd_out, tau_out, sig_out, info):
            return


# --------------------------------------------------------------------------------------------------
# the trial of the law on guarded copies (scara._simulate.interface.check_law_bounds)
# --------------------------------------------------------------------------------------------------
@kernel
def _trial(law, q0, qd0, r0, dt, gains, model, state, work, n_sig, buf, at, fa, fb, special):
    """One call of the law at sample 0 on copies of its six arrays (gains, model, state, work, signals zeroed, tau
    zeroed) laid out in ``buf`` at the offsets ``at`` (7,), each followed by :data:`GUARD` guard entries (rows, for
    ``work``) of ``fb`` for the array ``special`` (every array when ``special`` is 6) and ``fa`` otherwise. Returns
    the law's code."""
    ng = gains.shape[0]
    nm = model.shape[0]
    ns = state.shape[0]
    nw = work.shape[0]
    for j in range(6):
        fill = fb if (special == 6 or special == j) else fa
        for i in range(at[j], at[j + 1]):
            buf[i] = fill
    for i in range(ng):
        buf[at[0] + i] = gains[i]
    for i in range(nm):
        buf[at[1] + i] = model[i]
    for i in range(ns):
        buf[at[2] + i] = state[i]
    for i in range(nw):
        for j in range(4):
            buf[at[3] + 4 * i + j] = work[i, j]
    for i in range(n_sig):
        buf[at[4] + i] = 0.0
    for i in range(4):
        buf[at[5] + i] = 0.0
    q = np.empty(4)
    qd = np.empty(4)
    r = np.empty(12)
    for i in range(4):
        q[i] = q0[i]
        qd[i] = qd0[i]
    for i in range(12):
        r[i] = r0[i]
    w = buf[at[3]:at[3] + 4 * nw].reshape((nw, 4))
    return _law_step(law, 0, 0.0, dt, q, qd, r, buf[at[0]:at[0] + ng], buf[at[1]:at[1] + nm], buf[at[2]:at[2] + ns],
                     w, buf[at[4]:at[4] + n_sig], buf[at[5]:at[5] + 4])


@kernel
def _same_trials(code_a, a, code_b, b, at, sizes):
    """Whether two trials gave the same code and the same entries of every array (its first ``sizes[j]``)."""
    if code_a != code_b:
        return False
    for j in range(6):
        if not same_entries(a[at[j]:at[j] + sizes[j]], b[at[j]:at[j] + sizes[j]], sizes[j]):
            return False
    return True


@kernel
def _bounds_status(law, q0, qd0, r0, dt, gains, model, state, work, n_sig, out):
    """The check of :func:`~scara._simulate.interface.check_law_bounds` (without its plain-Python index checks): the
    law is called at sample 0 on guarded copies of its arrays with two fills of the guard entries; one that
    changed a guard entry wrote past its array, outputs that depend on the fill read past one (found by changing
    one array's fill at a time). Returns 0, or the refusal code (``_R_TRIAL + 20 law + 2 array``, ``+ 1`` for a
    read; ``+ 12``: past some array); the index written past in ``out``."""
    nw = work.shape[0]
    sizes = (gains.shape[0], model.shape[0], state.shape[0], 4 * nw, n_sig, 4)
    widths = (1, 1, 1, 4, 1, 1)
    at0 = 0
    at1 = at0 + sizes[0] + GUARD
    at2 = at1 + sizes[1] + GUARD
    at3 = at2 + sizes[2] + GUARD
    at4 = at3 + sizes[3] + 4 * GUARD
    at5 = at4 + sizes[4] + GUARD
    at6 = at5 + sizes[5] + GUARD
    at = (at0, at1, at2, at3, at4, at5, at6)
    fa = _FILLS[0]
    fb = _FILLS[1]
    a = np.empty(at6)
    b = np.empty(at6)
    code_a = _trial(law, q0, qd0, r0, dt, gains, model, state, work, n_sig, a, at, fa, fb, -1)
    for j in range(6):
        e = guard_change(a[at[j]:at[j + 1]], sizes[j], fa)
        if e >= 0:
            out[_O_FAIL_K] = e // widths[j]
            return _R_TRIAL + 20 * law + 2 * j
    code_b = _trial(law, q0, qd0, r0, dt, gains, model, state, work, n_sig, b, at, fa, fb, 6)
    for j in range(6):
        e = guard_change(b[at[j]:at[j + 1]], sizes[j], fb)
        if e >= 0:
            out[_O_FAIL_K] = e // widths[j]
            return _R_TRIAL + 20 * law + 2 * j
    if _same_trials(code_a, a, code_b, b, at, sizes):
        return 0
    for j in range(6):
        code_b = _trial(law, q0, qd0, r0, dt, gains, model, state, work, n_sig, b, at, fa, fb, j)
        if not _same_trials(code_a, a, code_b, b, at, sizes):
            return _R_TRIAL + 20 * law + 2 * j + 1
    return _R_TRIAL + 20 * law + 12


# --------------------------------------------------------------------------------------------------
# what the panel shows of a run
# --------------------------------------------------------------------------------------------------
@kernel
def _run_figures(e, tau, n, dt, settle, rest, pos, out):
    """The figures of :func:`~scara.control.control_summary` of a run (``e = x_d - x_e``, ``tau`` (N, 4) at
    ``t_k = k dt``) into ``out``: the largest and RMS norm of the position error after ``settle`` s (m), the largest
    orientation error after ``settle`` (rad), the largest position error over the last ``rest`` s and the mean
    vertical error there (m), the peak torques (N m, N) and the chattering (the RMS of the norm of the torque's
    second difference); ``pos`` (N,) receives the position error's norm. Returns False when nothing is left after
    ``settle`` (a run too short)."""
    after = 0.0 + settle - 1e-12
    last = (n - 1) * dt - rest + 1e-12
    top = 0.0
    top_o = 0.0
    top_last = 0.0
    s2 = 0.0
    sz = 0.0
    n_after = 0
    n_last = 0
    for i in range(4):
        out[_O_PEAK + i] = 0.0
    for k in range(n):
        p = math.sqrt(e[k, 0] * e[k, 0] + e[k, 1] * e[k, 1] + e[k, 2] * e[k, 2])
        pos[k] = p
        tk = k * dt
        if tk >= after:
            if n_after == 0 or p > top:
                top = p
            if n_after == 0 or abs(e[k, 3]) > top_o:
                top_o = abs(e[k, 3])
            s2 += p * p
            n_after += 1
        if tk >= last:
            if n_last == 0 or p > top_last:
                top_last = p
            sz += e[k, 2]
            n_last += 1
        for i in range(4):
            if abs(tau[k, i]) > out[_O_PEAK + i]:
                out[_O_PEAK + i] = abs(tau[k, i])
    if n_after == 0:
        return False
    chat = 0.0
    for k in range(1, n - 1):
        s = 0.0
        for i in range(4):
            d = tau[k + 1, i] - 2.0 * tau[k, i] + tau[k - 1, i]
            s += d * d
        chat += s
    out[_O_MAXP] = top
    out[_O_RMSP] = math.sqrt(s2 / n_after)
    out[_O_MAXO] = top_o
    out[_O_FINALP] = top_last
    out[_O_STEADYZ] = sz / n_last
    out[_O_CHAT] = math.sqrt(chat / (n - 2)) if n >= 3 else 0.0
    return True


@kernel
def _theory_z(q, model, plant, K_P_z):
    """The vertical error at rest of the operational law without integral action (m),
    :meth:`~scara.control.OperationalSpaceController.steady_state_error`: ``J_A B_hat^-1 (g - g_hat) / K_P`` at ``q``,
    its z entry, with the controllers' ``model`` and the ``plant`` (flat parameter arrays)."""
    B = np.empty((4, 4))
    inertia_kernel(q, model, B)
    g = np.empty(4)
    g_hat = np.empty(4)
    gravity_kernel(q, plant, g)
    gravity_kernel(q, model, g_hat)
    r = np.empty(4)
    for i in range(4):
        r[i] = g[i] - g_hat[i]
    y = np.empty(4)
    cholesky_solve4(B, r, y)
    J = np.empty((4, 4))
    jacobian_kernel(q, model[DP_A1], model[DP_A2], J)
    ez = 0.0
    for j in range(4):
        ez += J[2, j] * y[j]
    return ez / K_P_z


@kernel
def _drawn(law, n, dt, points, e, tau, sig, pos, t, data, out):
    """The arrays the panel draws (:data:`ARRAYS`, at the offsets the header gives): the envelope of the position
    error's norm ``pos``, the thinned time, torques and the law's own signal (the payload estimate, the envelope of
    ``||z||`` or ``e_z`` in mm). ``t`` (N,) receives the sample times."""
    ne = int(data[_H_N_ENV])
    nt = int(data[_H_N_THIN])
    err_t = out[int(data[_H_OUT_AT + _A_ERR_T]):int(data[_H_OUT_AT + _A_ERR_T]) + ne]
    for k in range(n):
        t[k] = k * dt
    envelope_kernel(t, pos, points, err_t, out[int(data[_H_OUT_AT + _A_ERR_Y]):int(data[_H_OUT_AT + _A_ERR_Y]) + ne])
    if law == ROBUST:
        for k in range(n):
            pos[k] = sig[k, 0]   # z_norm, the first signal of the robust law
        envelope_kernel(t, pos, points, err_t, out[int(data[_H_OUT_AT + _A_Z]):int(data[_H_OUT_AT + _A_Z]) + ne])
    t_at = int(data[_H_OUT_AT + _A_T])
    f3_at = int(data[_H_OUT_AT + _A_F3])
    t1_at = int(data[_H_OUT_AT + _A_TAU1])
    t2_at = int(data[_H_OUT_AT + _A_TAU2])
    t4_at = int(data[_H_OUT_AT + _A_TAU4])
    est_at = int(data[_H_OUT_AT + _A_EST])
    ez_at = int(data[_H_OUT_AT + _A_EZ])
    for j in range(nt):
        k = thin_index(n, points, j)
        out[t_at + j] = k * dt
        out[f3_at + j] = tau[k, 2]
        out[t1_at + j] = tau[k, 0]
        out[t2_at + j] = tau[k, 1]
        out[t4_at + j] = tau[k, 3]
        if law == ADAPTIVE:
            out[est_at + j] = sig[k, 0]   # payload_estimate, the first signal of the adaptive law
        elif law != ROBUST:
            out[ez_at + j] = 1e3 * e[k, 2]


#: The outputs a stopped run's refusal names, in the order of :func:`run_refusal`'s ``at``
RUN_FIELDS = ("fail_k", "fail_t", "fail_value", "fail_joint", "d3_min", "d3_max", "fail_d3", "fail_v3", "fail_code")


@kernel
def run_refusal(base, info, dt, q_out, qd_out, tau_out, sig_out, d3_min, d3_max, out, at):
    """The refusal code (``base`` + the cause) of a run the loop stopped (``info = [code, k, law_code]``), as
    :func:`scara._simulate.engine._raise_failure` words it, and the numbers it names in ``out`` at the offsets
    ``at`` of :data:`RUN_FIELDS`: the one reading of a stopped run of every page program that runs a loop."""
    status = int(info[0])
    k = int(info[1])
    out[at[0]] = k
    out[at[1]] = k * dt
    if status == NOT_FINITE:
        i = int(info[2])
        if i < 4:
            out[at[2]] = tau_out[k, i]
            out[at[3]] = i + 1
            return base + _C_TORQUE
        out[at[2]] = sig_out[k, i - 4]
        return base + _C_SIGNAL + i - 4
    if status == JOINT_LIMIT:
        out[at[4]] = d3_min
        out[at[5]] = d3_max
        out[at[6]] = q_out[k, 2]
        out[at[7]] = qd_out[k, 2]
        return base + (_C_JOINT_MAX if q_out[k, 2] > d3_max else _C_JOINT_MIN)
    if status == DIVERGED:
        return base + _C_DIVERGED
    if status == SINGULAR_INERTIA:
        return base + _C_SINGULAR
    code = int(info[2])
    out[at[8]] = code
    if 2 <= code <= 4:
        return base + _C_LAW + code
    return base + _C_LAW_OTHER


@kernel
def run_outputs(law, n, dt, e, tau, sig, pos, t, data, out):
    """What the panel shows of a run that went through (``e = x_d - x_e``, ``tau`` (N, 4), ``sig`` (N, n_sig) the
    law's signals, at ``t_k = k dt``), written in ``out`` (:func:`control_outputs`, on the data of
    :func:`control_data`): the figures of the chapter's table (:func:`_run_figures`), the title's numbers (mm, N,
    s, ms), the note's flag and the arrays drawn (:func:`_drawn`; ``pos`` and ``t`` (N,) are work space). ``law``
    is the index of :data:`LAWS`, or :data:`OTHER_LAW` for a law the panel does not know (its own signal is then
    ``e_z``). Returns 0, or the refusal code of a run with nothing after the settling time. The one definition of
    a run's figures for every law the panel runs: the seven of its program and a reader's own
    (:func:`own_run_outputs`)."""
    out[_O_DURATION] = (n - 1) * dt
    if not _run_figures(e, tau, n, dt, data[_H_SETTLE], data[_H_REST], pos, out):
        return _R_SHORT
    out[_O_MAXP_MM] = 1e3 * out[_O_MAXP]
    out[_O_FINALP_MM] = 1e3 * out[_O_FINALP]
    out[_O_PEAK_F3] = out[_O_PEAK + 2]
    out[_O_DT_MS] = 1e3 * dt
    out[_O_NOT_COMPENSATED] = 1.0 if out[_O_FINALP] > 1e-3 else 0.0
    _drawn(law, n, dt, int(data[_H_POINTS]), e, tau, sig, pos, t, data, out)
    return 0


# --------------------------------------------------------------------------------------------------
# the program
# --------------------------------------------------------------------------------------------------
@kernel
def _rows(block, at, n, m):
    """The (n, m) rows of ``block`` (1-D) from entry ``at``: a view."""
    return block[at:at + n * m].reshape((n, m))


@kernel
def control_core(inputs, data, out):
    """One move of the controllers panel (see the module's docstring): ``inputs`` the controls of :data:`INPUTS`,
    ``data`` of :func:`control_data`, ``out`` (zeroed) of :func:`control_outputs`. Returns 0, or a refusal code of
    :func:`control_refusals` with the numbers it names written in ``out``."""
    law = int(inputs[_I_LAW])
    n = int(data[_H_N])
    dt = data[_H_DT]
    d3_min = data[_H_D3_MIN]
    d3_max = data[_H_D3_MAX]
    out[_O_D3_MIN] = d3_min
    out[_O_D3_MAX] = d3_max
    # the controller (its checks, its arrays) and the plant carrying the payload
    model = np.empty(N_DP)
    for i in range(N_DP):
        model[i] = data[_H_MODEL + i]
    gains = np.zeros(_NG[law])
    state = np.zeros(_NS[law])
    work = np.zeros((_NW[law], 4))
    n_sig = _NSIG[law]
    code = _make_law(law, inputs, data, model, gains, state, out)
    if code != 0:
        return code
    payload = inputs[_I_PAYLOAD]
    if not (math.isfinite(payload) and payload >= 0.0):
        out[_O_BAD_VALUE] = payload
        return _R_GAIN + 2 * _G_ML
    plant = np.empty(N_DP)
    for i in range(N_DP):
        plant[i] = data[_H_PLANT + i]
    plant[DP_ML] = payload
    # the reference and the start
    x_at = int(data[_H_X])
    xd_at = int(data[_H_XD])
    xdd_at = int(data[_H_XDD])
    x = data[x_at:x_at + 4 * n].reshape((n, 4))
    xd = data[xd_at:xd_at + 4 * n].reshape((n, 4))
    xdd = data[xdd_at:xdd_at + 4 * n].reshape((n, 4))
    q0 = np.empty(4)
    qd0 = np.empty(4)
    # the series of the move, all in one block: the run's q, qd, qdd, tau (N, 4), e (N, 4), the signals
    # (N, n_sig), the error's norm and the sample times (N,); the panel's scratch after the data (control_scratch),
    # or one allocation when the data has none
    joint = _JOINT[law] == 1
    need = (22 + n_sig) * n
    at_block = int(data[_H_JREF]) + 12 * n
    block = data[at_block:at_block + need] if data.shape[0] >= at_block + need else np.empty(need)
    q_out = _rows(block, 0, n, 4)
    qd_out = _rows(block, 4 * n, n, 4)
    qdd_out = _rows(block, 8 * n, n, 4)
    tau_out = _rows(block, 12 * n, n, 4)
    e = _rows(block, 16 * n, n, 4)
    pos = block[20 * n:21 * n]
    sig_out = _rows(block, 21 * n, n, n_sig)
    t = block[(21 + n_sig) * n:(22 + n_sig) * n]
    if joint:
        if data[_H_JREF_CODE] != 0:   # the reference refused: its run again, for the numbers its message names
            return fill_joint_reference(data.copy(), out)
        at = int(data[_H_JREF])
        ref_pos = _rows(data, at, n, 4)
        ref_vel = _rows(data, at + 4 * n, n, 4)
        ref_acc = _rows(data, at + 8 * n, n, 4)
        for i in range(4):
            q0[i] = ref_pos[0, i]
            qd0[i] = ref_vel[0, i]
    else:
        ref_pos = x
        ref_vel = xd
        ref_acc = xdd
        for i in range(4):
            q0[i] = data[_H_Q0 + i]
    if not in_stroke(q0[2], d3_min, d3_max):
        out[_O_FAIL_D3] = q0[2]
        return _R_START_STROKE
    if not joint:
        if not _start_velocity(q0, xd[0], data[_H_PLANT + DP_A1], data[_H_PLANT + DP_A2], qd0):
            out[_O_FAIL_THETA2] = q0[1]
            return _R_START_SINGULAR
    # the law's trial on guarded copies, then the run
    r0 = np.empty(12)
    for i in range(4):
        r0[i] = ref_pos[0, i]
        r0[4 + i] = ref_vel[0, i]
        r0[8 + i] = ref_acc[0, i]
    code = _bounds_status(law, q0, qd0, r0, dt, gains, model, state, work, n_sig, out)
    if code != 0:
        return code
    info = np.zeros(3)
    _closed_loop(law, q0, qd0, ref_pos, ref_vel, ref_acc, dt, 1, data[_H_LIMIT], 0.5 * (d3_min + d3_max),
                 0.5 * (d3_max - d3_min), plant, gains, model, state, work, q_out, qd_out, qdd_out, tau_out, sig_out,
                 info)
    end = n if int(info[0]) == OK else int(info[1]) + 1
    kb, ib = first_bad_signal(sig_out, end)
    if kb >= 0 and (int(info[0]) == OK or kb < int(info[1])):  # the run's first failure
        info[0] = NOT_FINITE
        info[1] = kb
        info[2] = 4 + ib
    if int(info[0]) != OK:
        return run_refusal(_R_RUN + 100 * law, info, dt, q_out, qd_out, tau_out, sig_out, d3_min, d3_max, out,
                           _RUN_AT)
    # what the panel shows of the run
    _pose_error(q_out, x, data[_H_PLANT + DP_A1], data[_H_PLANT + DP_A2], data[_H_PLANT + DP_D0], qdd_out, e)
    code = run_outputs(law, n, dt, e, tau_out, sig_out, pos, t, data, out)
    if code != 0:
        return code
    out[_O_SHOWN + law] = 1.0
    if law == ROBUST:
        out[_O_Z_SHOWN] = 1.0
        out[_O_RHO_EPS] = inputs[_I_RHO] / inputs[_I_EPS]
    elif law == ADAPTIVE:
        out[_O_EST_SHOWN] = 1.0
        out[_O_ESTIMATE] = sig_out[n - 1, 0]
    else:
        out[_O_EZ_SHOWN] = 1.0
    if law == NO_INTEGRAL:
        out[_O_STEADYZ_MM] = 1e3 * out[_O_STEADYZ]
        out[_O_THEORY_MM] = 1e3 * _theory_z(q_out[n - 1], model, plant, inputs[_I_KP])
    elif law == PD_GRAVITY or law == COMPUTED_TORQUE:   # e_z = d3 - d3_d = -e_3 at rest, by the laws' own kernels
        out[_O_STEADYZ_MM] = 1e3 * out[_O_STEADYZ]
        if law == PD_GRAVITY:
            e3 = pd_gravity_steady_state_kernel(model, plant, gains[_CLASSIC_KP + 2])
        else:
            e = np.empty(4)
            computed_torque_steady_state(q_out[n - 1], model, plant, gains[_CLASSIC_KP:_CLASSIC_KP + 4], np.zeros((5, 4)),
                                         e)
            e3 = e[2]
        out[_O_THEORY_MM] = -1e3 * e3
    return 0


@kernel
def control_program(inputs, data, out):
    """The controllers panel's page program: :func:`control_core` on the data of :func:`control_data` (the sampled
    trajectory; a stage that samples it from the plan would come first)."""
    return control_core(inputs, data, out)


# --------------------------------------------------------------------------------------------------
# the data, the outputs and the refusals (Python, once per panel)
# --------------------------------------------------------------------------------------------------
def control_outputs(n: int, points: int) -> ArrayLayout:
    """The output fields of a run of ``n`` samples drawn with ``points`` samples per curve: :data:`SCALARS`, then
    :data:`ARRAYS` (the envelopes :func:`envelope_length` entries each, the thinned series :func:`thin_length`)."""
    ne, nt = int(envelope_length(n, points)), int(thin_length(n, points))
    fields = [(name, SCALARS.labels[name] if SCALARS.sizes[name] > 1 else 1) for name in SCALARS.names]
    fields += [(name, ne if name in _ENVELOPES else nt) for name in ARRAYS]
    return ArrayLayout(*fields)


def _trajectory_blocks(traj):
    """``(x, xd, xdd)`` (N, 4) of a trajectory, checked (shapes, finite numbers, N >= 2) and its ``dt``."""
    missing = [a for a in ("t", "x", "xd", "xdd") if not hasattr(traj, a)]
    if missing:
        raise ScaraError(f"traj must have attributes t, x, xd, xdd (and dt); {type(traj).__name__} lacks "
                         f"{', '.join(missing)}")
    n = int(np.size(traj.t))
    if n < 2:
        raise ShapeError(f"traj.t must hold at least 2 samples, got {n}")
    blocks = [np.ascontiguousarray(as_array(getattr(traj, f), f"traj.{f}", (n, 4))) for f in ("x", "xd", "xdd")]
    dt = getattr(traj, "dt", None)
    dt = float(traj.t[1] - traj.t[0]) if dt is None else float(dt)
    return blocks, dt


_HEADER_SIZE = HEADER.size


@kernel
def control_prepare(compact, data):
    """The ``data`` of :func:`control_program` from its compact form (:func:`control_compact`): the header as it
    is, then ``x_d``, ``xd_d``, ``xdd_d`` sampled from the plan that follows it by the planner's own kernel
    (:func:`~scara.programs.path.sample_plan`), then the joint reference (:func:`fill_joint_reference`). Returns 0,
    or the sampler's code (1: the sizes disagree)."""
    hs = _HEADER_SIZE
    for i in range(hs):
        data[i] = compact[i]
    n = int(compact[_H_N])
    if data.shape[0] != hs + 24 * n:
        return 1
    t = np.empty(n)
    x = data[hs:hs + 4 * n].reshape((n, 4))
    xd = data[hs + 4 * n:hs + 8 * n].reshape((n, 4))
    xdd = data[hs + 8 * n:hs + 12 * n].reshape((n, 4))
    code = sample_plan(compact[hs:], t, x, xd, xdd)
    if code != 0:
        return code
    fill_joint_reference(data, np.zeros(_SCALARS_SIZE))
    return 0


def control_scratch(n: int) -> int:
    """The entries of work space :func:`control_core` takes after the data of a run of ``n`` samples (the
    panel's :attr:`~scara.plots.panels.PageProgram.scratch`): the series of the law with the most signals."""
    return (22 + max(_NSIG)) * int(n)


def control_compact(traj, p: ScaraParams | None = None, points: int = 600):
    """``(compact, size)``: the compact form of :func:`control_data` for a planned trajectory (one with a
    ``plan_vector``): its header, then the plan, which :func:`control_prepare` samples back into the data
    (``size`` floats); None for a trajectory with no plan."""
    if getattr(traj, "plan_vector", None) is None:
        return None
    data = control_data(traj, p, points)
    return np.concatenate([data[:HEADER.size], np.asarray(traj.plan_vector, float)]), data.size


def control_data(traj, p: ScaraParams | None = None, points: int = 600) -> np.ndarray:
    """The ``data`` of :func:`control_program` for the trajectory ``traj`` (``t``, ``x``, ``xd``, ``xdd`` sampled at
    ``dt``, as the panel's trajectory gives them) on the arm ``p`` (default the trajectory's own, ``traj.params``;
    the plant before its payload), drawn with ``points`` samples per curve: :data:`HEADER`, then ``x_d``, ``xd_d``,
    ``xdd_d`` (N, 4) each, row-major. The controllers' model is ``ScaraParams()`` (they do not know the payload).
    Raises :class:`~scara.ScaraError` for a trajectory without those arrays, another geometry than its plan's, or a
    ``points`` outside 2 to 10 000."""
    from ..plots._common import FIGURE_BUDGET, MAX_POINTS  # noqa: PLC0415 - the figures' limits

    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    p = ScaraParams.for_trajectory(traj, p)
    (x, xd, xdd), dt = _trajectory_blocks(traj)
    n = len(x)
    elbow = getattr(traj, "elbow", None)
    elbow = -1.0 if elbow is None else float(elbow)
    q0 = getattr(traj, "q0", None)
    q0 = ikine(x[0], p, elbow=int(elbow)) if q0 is None else as_array(q0, "traj.q0", (4,))
    outputs = control_outputs(n, points)
    K_P = np.asarray(SEED_K, dtype=float) ** 2   # scara.clik2's default gains (second_order_gains of the seed K)
    K_D = 2.0 * np.asarray(SEED_K, dtype=float)
    head = HEADER.size
    header = HEADER.pack(
        n=n, dt=dt, elbow=elbow, x_at=head, xd_at=head + 4 * n, xdd_at=head + 8 * n, jref_at=head + 12 * n,
        jref_code=0, q0=q0,
        model=dynamic_array(ScaraParams()), plant=dynamic_array(p.with_payload(0.0)), d3_min=p.d3_min,
        d3_max=p.d3_max, tau_max=TAU_MAX, max_error=MAX_ERROR, limit=LIMIT, B_hat=B_HAT, B_bar=B_BAR,
        adaptive_K_D=ADAPTIVE_K_D, clik_K_P=K_P, clik_K_D=K_D, clik_max_error=0.1, points=points, settle=SETTLE,
        rest=REST, n_thin=thin_length(n, points), n_envelope=envelope_length(n, points),
        out_at=[getattr(outputs.offsets, name) for name in ARRAYS])
    data = np.concatenate([header, x.ravel(), xd.ravel(), xdd.ravel(), np.zeros(12 * n)])
    fill_joint_reference(data, np.zeros(SCALARS.size))
    return data


def joint_reference_rows(data: np.ndarray) -> np.ndarray | None:
    """The joint reference held in ``data`` (:func:`control_data`: the second-order CLIK of its trajectory, run
    once) as the ``(N, 12)`` rows ``[q_d, qd_d, qdd_d]`` that :func:`scara.simulate` takes as its
    ``joint_reference`` (a new array), or None when the reference was refused (its code is in the header)."""
    if data[_H_JREF_CODE] != 0:
        return None
    n, at = int(data[_H_N]), int(data[_H_JREF])
    blocks = [data[at + 4 * n * j:at + 4 * n * (j + 1)].reshape(n, 4) for j in range(3)]
    return np.hstack(blocks)


def own_run_outputs(result, data: np.ndarray, size: int) -> tuple:
    """``(code, out)``: the outputs of the panel's program (:func:`control_outputs`, ``size`` entries) for a run of
    a controller the program does not know (a :class:`~scara._simulate.SimulationResult` of :func:`scara.simulate`
    on the trajectory of ``data``), made by the kernel that makes them for the program's own runs,
    :func:`run_outputs` (the error ``result.e`` is the program's ``x_d - x_e``, by the same
    :func:`~scara._simulate.result._pose_error`): the same figures, title, notes and arrays, the run's own signal
    drawn as ``e_z``. ``code`` is 0 or the refusal code of :func:`control_refusals` (a run too short)."""
    n = len(result.t)
    if n != int(data[_H_N]):
        raise ShapeError(f"the run holds {n} samples but the panel's trajectory {int(data[_H_N])}")
    out = np.zeros(size)
    e = np.ascontiguousarray(result.e, dtype=float)
    tau = np.ascontiguousarray(result.tau, dtype=float)
    code = int(run_outputs(OTHER_LAW, n, float(result.dt), e, tau, np.zeros((n, 1)), np.empty(n), np.empty(n),
                           data, out))
    if code == 0:
        out[_O_EZ_SHOWN] = 1.0
    return code, out


def joint_reference_refusal(data: np.ndarray, size: int) -> tuple:
    """``(code, out)`` of a joint reference that ``data`` holds as refused: its run again, with the numbers its
    message (:func:`control_refusals`) names written in ``out`` (the program's outputs, ``size`` entries)."""
    out = np.zeros(size)
    return int(fill_joint_reference(data.copy(), out)), out


#: a stand-in for a number field written into a text field (replaced once the text is in)
_CODE = "\x00"
_FIELD = re.compile(r"\{([A-Za-z_][A-Za-z0-9_]*)(:[^{}]*)?\}")


def _fields(template: str, **names) -> str:
    """``template`` with its number fields renamed (``names``: field -> output field), their specs kept."""
    return _FIELD.sub(lambda m: "{" + names.get(m.group(1), m.group(1)) + (m.group(2) or "") + "}", template)


def _joint_template(template: str, i: int, **names) -> str:
    """A per-joint template of the package (fields ``{i}`` and ``{joint}``) for joint ``i``, as the panel shows it: the
    panel gives every joint the same gain, so its ``[0]`` is dropped (its former ``explain``)."""
    text = template.replace("[{i}]", "" if i == 0 else f"[{i}]").replace("{i}", str(i))
    return _fields(text.replace("{joint}", str(i + 1)), **names)


def run_refusals(name: str, base: int, signals, limit: float) -> dict:
    """The messages of :func:`run_refusal`'s codes from ``base`` for the law ``name`` with the signals ``signals``
    run with the bound ``limit``: :func:`scara.simulate`'s wordings (templates of the outputs :data:`RUN_FIELDS`)."""
    bounded = BoundedController()   # the stated bounds of every law (TAU_MAX, MAX_ERROR): its explain
    run = dict(t="fail_t", k="fail_k", value="fail_value", d3="fail_d3", v3="fail_v3")
    refusals = {}
    for code in FAILURE_CAUSES:
        refusals[base + _C_LAW + code] = _fields(failure_message(
            LAW_FAILED, name, cause=failure_cause(LAW_FAILED, code, bounded.explain)), **run)
    refusals[base + _C_LAW_OTHER] = _fields(failure_message(LAW_FAILED, name, cause=failure_cause(
        LAW_FAILED, 0, bounded.explain).replace("code 0", "code " + _CODE)), **run).replace(_CODE, "{fail_code:.0f}")
    refusals[base + _C_DIVERGED] = _fields(failure_message(DIVERGED, name, cause=failure_cause(
        DIVERGED, limit=limit)), **run)
    refusals[base + _C_SINGULAR] = _fields(failure_message(SINGULAR_INERTIA, name, cause=failure_cause(
        SINGULAR_INERTIA)), **run)
    for code, end in ((_C_JOINT_MAX, "d3_max"), (_C_JOINT_MIN, "d3_min")):
        refusals[base + code] = _fields(failure_message(JOINT_LIMIT, name, end=end), **run)
    refusals[base + _C_TORQUE] = _fields(failure_message(NOT_FINITE, name, what="the torque tau_" + _CODE),
                                         **run).replace(_CODE, "{fail_joint:.0f}")
    for s, signal in enumerate(signals):
        refusals[base + _C_SIGNAL + s] = _fields(failure_message(NOT_FINITE, name, what=f"the signal {signal!r}"),
                                                 **run)
    return refusals


def control_refusals(p: ScaraParams | None = None) -> dict:
    """The messages of :func:`control_program`'s refusal codes, as :class:`~scara.plots.panels.Text` templates of
    its outputs: the package's own wordings (the controllers' checks, :func:`scara.simulate`'s failures), as the
    panel shows them (a gain's ``[0]`` dropped, every joint having the same gain)."""
    from ..plots.panels import Text  # noqa: PLC0415 - the panels' template class

    p = ScaraParams.resolve(p)
    refusals = {
        _R_START_STROKE: _fields(START_STROKE_MESSAGE, d3="fail_d3"),
        _R_START_SINGULAR: ("the start configuration q0 is singular (theta2 = {fail_theta2:.6g} rad; det J_A = a1 a2 "
                            "sin theta2 vanishes): J_A cannot be inverted there; give the start speeds qd0 "
                            "explicitly, or start away from theta2 = 0 and pi"),
        _R_CLIK_ANNULUS: ("point (x, y, z) = ({start_px:.4g}, {start_py:.4g}, {start_pz:.4g}) m, "
                          "φ = {start_phi_deg:.4g}° is unreachable: "
                          "its distance from the joint-1 axis r = {fail_value:.10g} m is outside the annulus "
                          f"|a1 - a2| = {p.r_min:g} m <= r <= a1 + a2 = {p.r_max:g} m"),
        _R_CLIK_STROKE: ("point (x, y, z) = ({start_px:.4g}, {start_py:.4g}, {start_pz:.4g}) m, "
                         "φ = {start_phi_deg:.4g}° is unreachable: "
                         "p_z = {start_pz:.10g} m needs d3 = d0 - p_z = {fail_d3:.10g} m, outside the stroke "
                         f"d3_min = {p.d3_min:g} m <= d3 <= d3_max = {p.d3_max:g} m"),
        _R_CLIK_SINGULAR_START: ("the start configuration q is singular (theta2 = {fail_theta2:.6g} rad; det J_A = a1 a2 "
                                 "sin theta2 vanishes): J_A cannot be inverted there; give the start speeds qd0 "
                                 "explicitly, or start away from theta2 = 0 and pi"),
        _R_CLIK_NONFINITE: ("the second-order CLIK diverged at t = {fail_t:.4f} s (step {fail_k:.0f}): a value became "
                            "NaN or infinite"),
        _R_CLIK_SINGULAR: ("the second-order CLIK diverged at t = {fail_t:.4f} s (step {fail_k:.0f}): the Jacobian "
                           "became singular (theta2 = {fail_theta2:.6g} rad, manipulability {fail_w:.3g} m^2)"),
        _R_SHORT: "the run lasts {duration:g} s: nothing after settle = " + f"{SETTLE:g} s",
        _R_GAIN + 2 * _G_ML: "m_L = {bad_value:g} must be finite and >= 0",
        _R_GAIN + 2 * _G_ML + 1: "m_L = {bad_value:g} must be finite and >= 0",
        _R_FROZEN: "K_pi freezes every parameter (all entries infinite): nothing would adapt",
    }
    for i, comp in enumerate(COMPONENTS):
        refusals[_R_CLIK_ERROR + i] = ("the second-order CLIK diverged at t = {fail_t:.4f} s (step {fail_k:.0f}): the "
                                       f"tracking error exceeded max_error ({comp} error " + "{fail_value:.4g})")
    for g, name in enumerate(_GAINS[:-1]):
        label = "K_pi['m3']" if name == "K_pi" else name
        if name in ("rho", "epsilon"):   # scara.errors.check_positive
            refusals[_R_GAIN + 2 * g] = f"{name} = " + "{bad_value:g} is not finite"
            refusals[_R_GAIN + 2 * g + 1] = f"{name} = " + "{bad_value:g} must be > 0"
        else:                            # scara.gains.gain_vector, the panel's [0] dropped
            refusals[_R_GAIN + 2 * g] = f"{label} must be finite: {label} = " + "{bad_value:g}"
            refusals[_R_GAIN + 2 * g + 1] = (f"{label} must be positive definite: {label} = " +
                                             "{bad_value:g} (every entry must be > 0)")
    for i in range(4):
        refusals[_R_LAMBDA + i] = _joint_template(LAMBDA_MESSAGE, i, Lambda="bad_value", K_D="bad_limit")
        refusals[_R_INTEGRAL + i] = _joint_template(INTEGRAL_MESSAGE, i, K_I="bad_value", K_DK_P="bad_limit")
        refusals[_R_SLOW_POLE + i] = _joint_template(
            SLOW_POLE_MESSAGE, i, omega="bad_value", F="friction", reach="reach", K_D="fail_value",
            omega_min="bad_limit").replace("{n:g}", "3")
        refusals[_R_ROUTH + i] = _joint_template(ROUTH_MESSAGE, i, K_I="bad_value", limit="bad_limit")
        refusals[_R_SLOW_POLE_PD + i] = _joint_template(
            SLOW_POLE_MESSAGE, i, omega="bad_value", F="friction", reach="reach", K_D="fail_value",
            omega_min="bad_limit").replace("{n:g}", "2")
        refusals[_R_JURY + i] = _joint_template(JURY_MESSAGE, i, K_P="bad_value", K_D="fail_value", dt="fail_t",
                                                omega_max="bad_limit")
    for i in range(N_PI):
        from ..dynamics import PI_NAMES  # noqa: PLC0415

        refusals[_R_SMALL_WEIGHT + i] = _joint_template(SMALL_WEIGHT_MESSAGE, i, K_pi="bad_value").replace(
            "{name}", PI_NAMES[i])
    for law, name in enumerate(LAWS):
        sizes = (_NG[law], N_DP, _NS[law], _NW[law], _NSIG[law], 4)
        for j, array in enumerate(_TRIAL_ARRAYS):
            text = described(array, sizes[j], name)
            refusals[_R_TRIAL + 20 * law + 2 * j] = _fields(fill_text(WRITES_PAST, controller=name, array=array,
                                                                      described=text), index="fail_k")
            refusals[_R_TRIAL + 20 * law + 2 * j + 1] = fill_text(READS_PAST, controller=name, array=array,
                                                                  described=text)
        refusals[_R_TRIAL + 20 * law + 12] = fill_text(READS_PAST_ANY, controller=name)
        refusals.update(run_refusals(name, _R_RUN + 100 * law, _SIGNAL_NAMES[law], LIMIT))
    return {code: Text(template) for code, template in refusals.items()}
