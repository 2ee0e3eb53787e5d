"""The page program of chapter 7's interaction panel: one move of the panel as one compiled kernel,
:func:`interaction_program` (numba in Jupyter; translated to JavaScript, the page's engine).

A move (the dropdown's law, its gains along z, the pressing force, the surface's stiffness ``k_e``) is the
transition run of :func:`scara.interaction.steady.approach_run`: the tool starts at rest ``lift`` above the surface,
the reference moves by a quintic of ``move`` s to the set point of :func:`~scara.interaction.steady.pressing_target`
(force control keeps its start and lets its force loop lower it; parallel control's reference goes to the surface) and holds ``hold`` s; the wrist sensor of
:class:`~scara.interaction.environment.ForceSensor` (its noise, drawn once in Python, travels in the data; its bias
on ``f_z`` is added here). The law's gains are packed at the offsets of its ``gains_layout`` (the controller's
defaults for the entries the panel does not set), the loop is the contact engine's
(:func:`scara.interaction.engine.contact_loop_kernel`: its own kernels ``_sense`` and ``_step_plant`` around the
law, chosen here by index), and the run is reduced to what the panel shows: the normal force ``-h_z`` and the
tool's height thinned to the panel's ``points``, the figures of
:func:`~scara.interaction.steady.contact_transition` (by its kernel) and the steady force the formulas of
:mod:`scara.interaction.steady` predict. A run the engine stops returns the code of its refusal, worded by
:func:`interaction_refusals` as :func:`~scara.interaction.simulate_contact` words it.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from .._simulate.engine import _before_law, _loop_arrays, _loop_start
from .._simulate.interface import MEASURED_FORCE, OK, WORK_WIDTH
from .._simulate.plant import _plant_constants
from ..dynamics import DP_A1, DP_A2, DP_D0, N_DP, dynamic_array
from ..errors import ScaraError, check_count
from ..interaction.engine import _contact_after_law, _sense
from ..interaction.environment import ENVIRONMENT, ForceSensor, Surface
from ..interaction.laws import (ADMITTANCE_GAINS, COMPLIANCE_GAINS, FORCE_GAINS, IMPEDANCE_GAINS, PARALLEL_GAINS,
                                AdmittanceController, ComplianceController, ForceController, ImpedanceController,
                                ParallelController, admittance_law, compliance_law, force_law, impedance_law,
                                parallel_law)
from ..interaction.laws import Z_ADMITTANCE, Z_COMPLIANCE, Z_FORCE, Z_IMPEDANCE, _gains_text, z_loop
from ..interaction.stability import IN_CONTACT, IN_FREE_SPACE, UNSTABLE_MESSAGE, loop_radius, z_axis
from ..interaction.steady import pressing_height, transition_kernel
from ..kinematics import ikine
from ..params import ScaraParams
from .control import RUN_FIELDS, _fields, _rows, run_refusal, run_refusals
from .thinning import thin_index, thin_length

__all__ = ["LAWS", "INPUTS", "HEADER", "SCALARS", "ARRAYS", "interaction_program", "interaction_data",
           "interaction_outputs", "interaction_refusals", "make_controller", "run_outputs", "own_run_outputs",
           "interaction_run"]

#: The laws of the panel's dropdown, in its order (``inputs[0]`` is the index)
LAWS = ("compliance", "impedance", "admittance", "force", "parallel")
COMPLIANCE, IMPEDANCE, ADMITTANCE, FORCE, PARALLEL = range(5)
_CLASSES = (ComplianceController, ImpedanceController, AdmittanceController, ForceController, ParallelController)
_LAYOUTS = (COMPLIANCE_GAINS, IMPEDANCE_GAINS, ADMITTANCE_GAINS, FORCE_GAINS, PARALLEL_GAINS)
#: The sizes of each law's arrays, from the layouts its controller declares
_NG = tuple(c.gains_layout.size for c in _CLASSES)
_NS = tuple(c.state_layout.size for c in _CLASSES)
_NW = tuple(c.work_layout.size for c in _CLASSES)
_NSIG = tuple(c.signals_layout.size for c in _CLASSES)
#: The scratch row of the sensor's reading (-1: the law reads no sensor), as the engine finds it
_ROW = tuple(int(getattr(c.work_layout.offsets, MEASURED_FORCE)) if MEASURED_FORCE in c.work_layout.names else -1
             for c in _CLASSES)
#: Where each law keeps the gains the panel sets along z (-1: the law has no such gain): its stiffness
#: (compliance ``K_P``, impedance ``K_P``, admittance ``K_Pd``), damping (``K_D``, ``K_D``, ``K_Dd``), mass ``M_d``;
#: the force laws' ``K_F``, ``K_I`` and ``f_d`` (z entry)
_AT_K = (COMPLIANCE_GAINS.offsets.K_P + 2, IMPEDANCE_GAINS.offsets.K_P + 2, ADMITTANCE_GAINS.offsets.K_Pd + 2, -1, -1)
_AT_D = (COMPLIANCE_GAINS.offsets.K_D + 2, IMPEDANCE_GAINS.offsets.K_D + 2, ADMITTANCE_GAINS.offsets.K_Dd + 2, -1, -1)
_AT_M = (-1, IMPEDANCE_GAINS.offsets.M_d + 2, ADMITTANCE_GAINS.offsets.M_d + 2, -1, -1)
_AT_KF = (-1, -1, -1, FORCE_GAINS.offsets.K_F + 2, PARALLEL_GAINS.offsets.K_F)
_AT_KI = (-1, -1, -1, FORCE_GAINS.offsets.K_I + 2, PARALLEL_GAINS.offsets.K_I)
_AT_FD = (-1, -1, -1, FORCE_GAINS.offsets.f_d + 2, PARALLEL_GAINS.offsets.f_d)
#: Each law's linear part along z (:func:`~scara.interaction.laws.z_loop`): its kind and where its gains are
_Z_KIND = (Z_COMPLIANCE, Z_IMPEDANCE, Z_ADMITTANCE, Z_FORCE, Z_FORCE)
_C, _I, _A, _F, _P = (L.offsets for L in (COMPLIANCE_GAINS, IMPEDANCE_GAINS, ADMITTANCE_GAINS, FORCE_GAINS,
                                          PARALLEL_GAINS))
_Z_GAINS = ((_C.K_P + 2, _C.K_D + 2, -1, -1, -1), (_I.M_d + 2, _I.K_D + 2, _I.K_P + 2, -1, -1),
            (_A.M_d + 2, _A.K_Dd + 2, _A.K_Pd + 2, _A.K_P + 2, _A.K_D + 2),
            (_F.K_P + 2, _F.K_D + 2, _F.K_F + 2, _F.K_I + 2, -1), (_P.K_P + 2, _P.K_D + 2, _P.K_F, _P.K_I, -1))

#: The panel's controls the program reads, in the order of ``inputs`` (the dropdown as the index of its value):
#: the law, the pressing force (N), the stiffness, damping and mass along z of the stiffness laws (N/m, N s/m,
#: kg), the force loop's ``K_F`` (m/N) and ``K_I`` (m/(N s)), the surface's stiffness ``k_e`` (N/m)
INPUTS = ("law", "force", "K_z", "D_z", "M_z", "K_F", "K_I", "k_e")
_I_LAW, _I_FORCE, _I_K, _I_D, _I_M, _I_KF, _I_KI, _I_KE = range(len(INPUTS))

#: The run: the start ``LIFT`` m above the surface at ``AT`` (x, y) m, a quintic of ``MOVE`` s, ``HOLD`` s held
LIFT, AT, MOVE, HOLD, DT, SUBSTEPS = 0.02, (0.4, 0.1), 1.0, 2.0, 1e-3, 10
#: The bound on any state or torque entry of the run (:func:`~scara.interaction.simulate_contact`'s ``limit``)
LIMIT = 1e6

#: The output arrays: the thinned time (s), the normal force ``-h_z`` (N), the tool's height above the surface
#: and its set point (mm)
ARRAYS = ("t", "force", "z", "z_d")

#: The header of ``data`` (:func:`interaction_data`): the run's sampling, the start (pose and joints), the
#: surface (:data:`~scara.interaction.environment.ENVIRONMENT`, its stiffness replaced by the move's), the plant
#: and the controllers' model, the sensor's bias, each law's default gains (at ``gains_at + law``, ``gains_size``
#: entries each), the quintic's unit profile, the sensor's noise and the output arrays' offsets
HEADER = ArrayLayout(("n", 1), ("dt", 1), ("substeps", 1), ("limit", 1), ("d3_min", 1), ("d3_max", 1),
                     ("x0", 4), ("q0", 4), ("env", ENVIRONMENT.size), ("plant", N_DP), ("model", N_DP),
                     ("bias", 3), ("m_z", 1), ("c_z", 1), ("gains_at", 5), ("profile_at", 1), ("noise_at", 1), ("points", 1), ("n_thin", 1),
                     ("out_at", len(ARRAYS)))
(_H_N, _H_DT, _H_SUB, _H_LIMIT, _H_D3_MIN, _H_D3_MAX, _H_X0, _H_Q0, _H_ENV, _H_PLANT, _H_MODEL, _H_BIAS, _H_M, _H_C,
 _H_GAINS,
 _H_PROFILE, _H_NOISE, _H_POINTS, _H_N_THIN, _H_OUT_AT) = HEADER.offsets
_E_K = ENVIRONMENT.offsets.stiffness
_N_ENV = ENVIRONMENT.size
_E_Z = ENVIRONMENT.offsets.height
_E_D = ENVIRONMENT.offsets.damping

#: The output numbers: the set point's height above the surface (mm), the figures of the transition
#: (``first_touch`` s, ``peak_force`` N, ``contact_losses``, ``bounced`` 0/1, ``final_force`` N), the steady force
#: the formulas predict (N) and the error of the final force (N), the run's start (0) and length (s), and the numbers a refusal
#: names
SCALARS = ArrayLayout(("target_mm", 1), ("first_touch", 1), ("peak_force", 1), ("contact_losses", 1), ("bounced", 1),
                      ("final_force", 1), ("formula", 1), ("force_error", 1), ("t_start", 1), ("duration", 1), ("radius", 1), ("radius_free", 1),
                      ("fail_t", 1), ("fail_k", 1), ("fail_value", 1), ("fail_joint", 1), ("fail_d3", 1),
                      ("fail_v3", 1), ("fail_code", 1), ("d3_min", 1), ("d3_max", 1))
(_O_TARGET, _O_TOUCH, _O_PEAK, _O_LOSSES, _O_BOUNCED, _O_FINAL, _O_FORMULA, _O_ERROR, _O_T0, _O_DURATION, _O_RADIUS, _O_RADIUS_FREE, _O_FAIL_T,
 _O_FAIL_K, _O_FAIL_VALUE, _O_FAIL_JOINT, _O_FAIL_D3, _O_FAIL_V3, _O_FAIL_CODE, _O_D3_MIN, _O_D3_MAX) = SCALARS.offsets
_SCALARS_SIZE = SCALARS.size

#: where the outputs a stopped run's refusal names are (:data:`~scara.programs.control.RUN_FIELDS`)
_RUN_AT = tuple(getattr(SCALARS.offsets, name) for name in RUN_FIELDS)
#: the refusal codes: an unstable sampled loop along z, ``_R_UNSTABLE + 10 law`` (in contact, ``+ 1`` in free
#: space); a run the engine stopped, ``_R_RUN + 100 law`` + the cause (:func:`~scara.programs.control.run_refusal`)
_R_UNSTABLE = 100
_R_RUN = 1000


# --------------------------------------------------------------------------------------------------
# the law of a move, chosen by index, and the contact loop around it
# --------------------------------------------------------------------------------------------------
@kernel(inline="always")
def _law_step(law, k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """One step of the law of index ``law`` (:data:`LAWS`) with the engine's twelve arguments. Returns its code."""
    if law == COMPLIANCE:
        return compliance_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    elif law == IMPEDANCE:
        return impedance_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    elif law == ADMITTANCE:
        return admittance_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    elif law == FORCE:
        return force_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)
    return parallel_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)


@kernel
def _contact_loop(law, q0, x0, z1, profile, dt, substeps, limit, d3_mid, d3_half, plant_dp, gains, model, state,
                  work, env, offsets, force_row, q_out, qd_out, qdd_out, tau_out, sig_out, force_out, sensed_out,
                  inside_out, info):
    """The loop of :func:`scara.interaction.engine.contact_loop_kernel` (the same steps, its own kernels
    ``_before_law``, ``_sense`` and ``_step_plant``) with the law of index ``law`` (:func:`_law_step`: the page's
    engine takes no law as a function) and the reference of the approach built row by row: ``x0`` held, its z
    moved to ``z1`` along ``profile`` (N, 3: the quintic's unit ``s``, ``s'``, ``s''``). ``info`` (3,) receives
    ``[code, k, law_code]``."""
    n = q_out.shape[0]
    pc = _plant_constants(plant_dp)
    a1, a2, d0 = plant_dp[DP_A1], plant_dp[DP_A2], plant_dp[DP_D0]
    q, qd, qdd, spare, q_law, qd_law, r, tau, sig = _loop_arrays(12, 4)   # 4: admittance's x_c, the most
    _loop_start(q0, np.zeros(4), q, qd, n, info)   # the approach starts at rest
    h = dt / substeps
    dz = z1 - x0[2]
    for k in range(n):
        _before_law(k, q, qd, q_out, qd_out, q_law, qd_law, tau, sig)
        _sense(k, q, qd, a1, a2, d0, env, inside_out[k], offsets, force_out, sensed_out, work, force_row)
        for i in range(4):
            r[i] = x0[i]
            r[4 + i] = 0.0
            r[8 + i] = 0.0
        r[2] = x0[2] + dz * profile[k, 0]
        r[6] = dz * profile[k, 1]
        r[10] = dz * profile[k, 2]
        code = _law_step(law, k, k * dt, dt, q_law, qd_law, r, gains, model, state, work, sig, tau)
        if _contact_after_law(k, n, code, q, qd, qdd, spare, tau, sig, pc, h, substeps, limit, d3_mid, d3_half,
                              plant_dp, env, inside_out, q_out, qd_out, qdd_out, tau_out, sig_out, info):
            return


@kernel
def make_gains(law, inputs, data, gains):
    """The gains of ``law`` for the move ``inputs``: the controller's defaults (in ``data``) with the panel's
    gains written at the offsets of the law's ``gains_layout``, as the controller built by :func:`make_controller`
    packs them (``gains_array``); ``f_d`` of a force law is ``-force`` (press down)."""
    at = int(data[_H_GAINS + law])
    for i in range(gains.shape[0]):
        gains[i] = data[at + i]
    if _AT_K[law] >= 0:
        gains[_AT_K[law]] = inputs[_I_K]
        gains[_AT_D[law]] = inputs[_I_D]
    if _AT_M[law] >= 0:
        gains[_AT_M[law]] = inputs[_I_M]
    if _AT_KF[law] >= 0:
        gains[_AT_KF[law]] = inputs[_I_KF]
        gains[_AT_KI[law]] = inputs[_I_KI]
        gains[_AT_FD[law]] = -inputs[_I_FORCE]


@kernel
def z_radius(law, gains, m, c, k, d, dt, contact):
    """The spectral radius of the sampled loop along z of ``law`` with its ``gains`` (packed), in contact with
    the surface ``k``, ``d`` or in free space: the check of ``check_contact`` (:mod:`scara.interaction.stability`)."""
    g = np.zeros(5)
    for i in range(5):
        if _Z_GAINS[law][i] >= 0:
            g[i] = gains[_Z_GAINS[law][i]]
    Dy = np.zeros(2)
    Cw = np.zeros(2)
    Aw = np.zeros((2, 2))
    By = np.zeros((2, 2))
    n = z_loop(_Z_KIND[law], g, m, c, k, d, dt, contact, Dy, Cw, Aw, By)
    return loop_radius(Dy, Cw, Aw, By, n, m, c, k if contact else 0.0, d if contact else 0.0, dt)


@kernel
def run_outputs(n, dt, force_out, q_out, z0, z1, profile, height, formula, data, out):
    """What the panel shows of a run that went through (``force_out`` (N, 3) the forces ``h_e``, ``q_out`` (N, 4)
    the joints, its set point's height moved from ``z0`` to ``z1`` (m) along ``profile``), written in ``out``: the
    figures of :func:`~scara.interaction.steady.contact_transition` (its kernel), the steady force of the formulas
    ``formula`` (N) and the final force's error, the normal force, the tool's and the set point's heights above the
    surface at ``height`` (mm) thinned to the panel's points. The one reduction of the program's runs and of a
    run of the reader's own controller (:func:`own_run_outputs`)."""
    figures = np.zeros(5)
    transition_kernel(force_out, figures)
    out[_O_TOUCH] = figures[0] * dt if figures[0] >= 0 else math.nan
    out[_O_PEAK] = figures[1] if figures[0] >= 0 else 0.0
    out[_O_LOSSES] = figures[2]
    out[_O_BOUNCED] = 1.0 if figures[2] > 0 else 0.0
    out[_O_FINAL] = figures[3]
    out[_O_FORMULA] = formula
    out[_O_ERROR] = figures[3] - formula
    out[_O_TARGET] = 1e3 * (z1 - height)
    out[_O_DURATION] = (n - 1) * dt
    points = int(data[_H_POINTS])
    m = int(data[_H_N_THIN])
    ot = int(data[_H_OUT_AT])
    of = int(data[_H_OUT_AT + 1])
    oz = int(data[_H_OUT_AT + 2])
    od = int(data[_H_OUT_AT + 3])
    d0 = data[_H_PLANT + DP_D0]
    dz = z1 - z0
    for j in range(m):
        k = thin_index(n, points, j)
        out[ot + j] = k * dt
        out[of + j] = -force_out[k, 2]
        out[oz + j] = 1e3 * (d0 - q_out[k, 2] - height)
        out[od + j] = 1e3 * (z0 + dz * profile[k, 0] - height)


@kernel
def interaction_core(inputs, data, out, q_out, qd_out, qdd_out, tau_out, sig_out, force_out, sensed_out, offsets,
                     inside):
    """:func:`interaction_program` on the work arrays of a run of ``n`` samples: ``q_out`` ... ``sig_out`` (N, 4),
    ``force_out``, ``sensed_out``, ``offsets`` (N, 3), ``inside`` (N,). Returns 0 or the refusal code."""
    law = int(inputs[_I_LAW])
    n = int(data[_H_N])
    dt = data[_H_DT]
    env = data[_H_ENV:_H_ENV + _N_ENV].copy()
    env[_E_K] = inputs[_I_KE]
    height = env[_E_Z]
    gains = np.empty(_NG[law])
    make_gains(law, inputs, data, gains)
    r = z_radius(law, gains, data[_H_M], data[_H_C], env[_E_K], env[_E_D], dt, True)
    out[_O_RADIUS] = r
    if not r < 1.0:
        return _R_UNSTABLE + 10 * law
    r = z_radius(law, gains, data[_H_M], data[_H_C], env[_E_K], env[_E_D], dt, False)
    out[_O_RADIUS_FREE] = r
    if not r < 1.0:
        return _R_UNSTABLE + 10 * law + 1
    state = np.zeros(_NS[law])
    work = np.zeros((_NW[law], WORK_WIDTH))
    x0 = data[_H_X0:_H_X0 + 4]
    z1 = x0[2]   # force control keeps its start; parallel control's position loop goes to the surface
    if law == PARALLEL:
        z1 = height
    if _AT_K[law] >= 0:
        z1 = pressing_height(height, inputs[_I_FORCE], inputs[_I_K], inputs[_I_KE])
    bias = data[_H_BIAS:_H_BIAS + 3]
    at = int(data[_H_NOISE])
    for k in range(n):
        for i in range(3):
            offsets[k, i] = data[at + 3 * k + i] + bias[i]
        inside[k] = 0.0
    at = int(data[_H_PROFILE])
    profile = data[at:at + 3 * n].reshape(n, 3)
    info = np.zeros(3)
    d3_min = data[_H_D3_MIN]
    d3_max = data[_H_D3_MAX]
    _contact_loop(law, data[_H_Q0:_H_Q0 + 4], x0, z1, profile, dt, int(data[_H_SUB]), data[_H_LIMIT],
                  0.5 * (d3_min + d3_max), 0.5 * (d3_max - d3_min), data[_H_PLANT:_H_PLANT + N_DP], gains,
                  data[_H_MODEL:_H_MODEL + N_DP], state, work, env, offsets, _ROW[law], q_out, qd_out,
                  qdd_out, tau_out, sig_out, force_out, sensed_out, inside, info)
    if info[0] != OK:
        return run_refusal(_R_RUN + 100 * law, info, dt, q_out, qd_out, tau_out, sig_out, d3_min, d3_max, out,
                           _RUN_AT)
    # the steady normal force of the formulas: a stiffness law pressing at its set point
    # (elastic_equilibrium, whose force pressing_height sets), a force law the measured f_d less the bias
    # (force_equilibrium)
    formula = inputs[_I_FORCE] if _AT_K[law] >= 0 else inputs[_I_FORCE] + bias[2]
    run_outputs(n, dt, force_out, q_out, x0[2], z1, profile, height, formula, data, out)
    return 0


_HEADER_SIZE = HEADER.size


@kernel
def interaction_program(inputs, data, out):
    """One move of the interaction panel (module docstring): ``inputs`` of :data:`INPUTS`, ``data`` of
    :func:`interaction_data` followed by its scratch (:func:`interaction_scratch`), ``out`` of
    :func:`interaction_outputs`. Returns 0 or the refusal code (:func:`interaction_refusals`)."""
    n = int(data[_H_N])
    at = int(data[_H_NOISE]) + 3 * n   # the scratch follows the data
    if data.shape[0] < at + 30 * n:    # none: the move allocates its own
        return interaction_core(inputs, data, out, np.empty((n, 4)), np.empty((n, 4)), np.empty((n, 4)),
                                np.empty((n, 4)), np.empty((n, 4)), np.empty((n, 3)), np.empty((n, 3)),
                                np.empty((n, 3)), np.empty(n))
    return interaction_core(inputs, data, out, _rows(data, at, n, 4), _rows(data, at + 4 * n, n, 4),
                            _rows(data, at + 8 * n, n, 4), _rows(data, at + 12 * n, n, 4),
                            _rows(data, at + 16 * n, n, 4), _rows(data, at + 20 * n, n, 3),
                            _rows(data, at + 23 * n, n, 3), _rows(data, at + 26 * n, n, 3),
                            data[at + 29 * n:at + 30 * n])


def own_run_outputs(result, data: np.ndarray, size: int, formula: float) -> np.ndarray:
    """The outputs of the panel's program (``size`` entries) for a run of a controller the program does not know
    (a :class:`~scara.interaction.engine.ContactResult` of the panel's approach, :func:`interaction_run`), made by
    the kernel that makes them for the program's own runs, :func:`run_outputs`: the same figures and curves, the
    steady force of the formulas ``formula`` (N; NaN when none applies) and the spectral radii NaN (the program
    does not know the law's linear part)."""
    n = int(data[_H_N])
    if len(result.t) != n:
        raise ScaraError(f"the run holds {len(result.t)} samples but the panel's approach {n}")
    out = np.zeros(size)
    at = int(data[_H_PROFILE])
    run_outputs(n, float(result.dt), np.ascontiguousarray(result.force), np.ascontiguousarray(result.q),
                float(result.x_d[0, 2]), float(result.x_d[-1, 2]), data[at:at + 3 * n].reshape(n, 3),
                float(data[_H_ENV + _E_Z]), float(formula), data, out)
    out[_O_RADIUS] = out[_O_RADIUS_FREE] = math.nan
    return out


def interaction_run(controller, k_e: float, force: float, p: ScaraParams | None = None):
    """The panel's approach for ``controller`` (any interaction controller: an object with the interface of
    :class:`scara.Controller`, reading the sensor in its scratch row ``measured_force`` if it declares one) on the
    default surface of stiffness ``k_e`` (N/m), pressing with ``force`` N:
    :func:`~scara.interaction.steady.approach_run` with the program's start, move, hold and sensor."""
    from ..interaction.steady import approach_run  # noqa: PLC0415

    return approach_run(controller, Surface(stiffness=k_e), interaction_sensor(), at=AT, lift=LIFT, force=force,
                        move=MOVE, hold=HOLD, substeps=SUBSTEPS)


def interaction_scratch(n: int) -> int:
    """The entries of work space :func:`interaction_program` takes after the data of a run of ``n`` samples."""
    return 30 * int(n)


def interaction_outputs(n: int, points: int) -> ArrayLayout:
    """The output fields of :func:`interaction_program` for a run of ``n`` samples drawn with ``points`` samples
    per curve: :data:`SCALARS`, then the arrays of :data:`ARRAYS`."""
    m = thin_length(n, points)
    return ArrayLayout(*((name, 1) for name in SCALARS.names), *((name, m) for name in ARRAYS))


def make_controller(law: str, force: float, K_z: float, D_z: float, M_z: float, K_F: float, K_I: float):
    """The controller the panel's settings describe (the panel's own mapping, exposed for tests): ``law`` one of
    :data:`LAWS`, the gains along z of its sliders (the controller's defaults elsewhere)."""
    cls = _CLASSES[LAWS.index(law)]
    default = cls()
    if law in ("compliance", "impedance", "admittance"):
        k_name, d_name = ("K_Pd", "K_Dd") if law == "admittance" else ("K_P", "K_D")
        kw = {}
        for name, value in ((k_name, K_z), (d_name, D_z)) + ((("M_d", M_z),) if law != "compliance" else ()):
            g = getattr(default, name).copy()
            g[2] = value
            kw[name] = g
        return cls(**kw)
    if law == "force":
        KF, KI = default.K_F.copy(), default.K_I.copy()
        KF[2], KI[2] = K_F, K_I
        return cls(f_d=(0.0, 0.0, -force), K_F=KF, K_I=KI)
    return cls(f_d=-force, K_F=K_F, K_I=K_I)


def interaction_sensor() -> ForceSensor:
    """The panel's wrist sensor: the package's default (0.2 N noise, 0.5 N bias on ``f_z``, seed 0)."""
    return ForceSensor()


def interaction_data(p: ScaraParams | None = None, points: int = 600) -> np.ndarray:
    """The ``data`` of :func:`interaction_program` on the arm ``p`` with the default surface
    (:class:`~scara.interaction.environment.Surface`, its stiffness set by every move) and sensor
    (:func:`interaction_sensor`), drawn with ``points`` samples per curve (2 to 10 000)."""
    from ..plots._common import FIGURE_BUDGET, MAX_POINTS  # noqa: PLC0415 - the figures' limits

    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    p = ScaraParams.resolve(p)
    s = Surface()
    q = ikine([AT[0], AT[1], s.height + LIFT, 0.0], p, elbow=-1)
    x0 = np.array([AT[0], AT[1], s.height + LIFT, q[0] + q[1]])
    ref = _unit_profile()
    n = len(ref)
    sensor = interaction_sensor()
    noise = ForceSensor(noise=sensor.noise, bias=(0.0, 0.0, 0.0), seed=sensor.seed).offsets(n)
    gains = [c().gains_array() for c in _CLASSES]
    head = HEADER.size
    gains_at, at = [], head
    for g in gains:
        gains_at.append(at)
        at += g.size
    profile_at = at
    noise_at = profile_at + 3 * n
    outputs = interaction_outputs(n, points)
    m_z, c_z = z_axis(p)
    header = HEADER.pack(m_z=m_z, c_z=c_z, n=n, dt=DT, substeps=SUBSTEPS, limit=LIMIT, d3_min=p.d3_min, d3_max=p.d3_max, x0=x0,
                         q0=ikine(x0, p, elbow=-1), env=s.array(), plant=dynamic_array(p),
                         model=dynamic_array(ScaraParams()), bias=sensor.bias, gains_at=gains_at,
                         profile_at=profile_at, noise_at=noise_at, points=points, n_thin=thin_length(n, points),
                         out_at=[getattr(outputs.offsets, name) for name in ARRAYS])
    return np.concatenate([header, *gains, ref.ravel(), noise.ravel()])


def _unit_profile() -> np.ndarray:
    """The quintic's unit profile (N, 3): ``s``, ``s'``, ``s''`` of the approach's z from 0 to 1
    (:func:`~scara.interaction.steady.approach_reference`)."""
    from ..trajectory import quintic  # noqa: PLC0415

    jt = quintic(np.zeros(4), np.array([0.0, 0.0, 1.0, 0.0]), MOVE, dt=DT, check=False)
    n_hold = int(round(HOLD / DT))
    prof = np.column_stack([jt.q[:, 2], jt.qd[:, 2], jt.qdd[:, 2]])
    return np.vstack([prof, np.repeat([[1.0, 0.0, 0.0]], n_hold, axis=0)])


#: the panel's control of each gain's z entry, by law and gain name (the other entries are the defaults)
_SET = ({"K_P": "K_z", "K_D": "D_z"}, {"M_d": "M_z", "K_D": "D_z", "K_P": "K_z"},
        {"M_d": "M_z", "K_Dd": "D_z", "K_Pd": "K_z"}, {"K_F": "K_F", "K_I": "K_I"}, {"K_F": "K_F", "K_I": "K_I"})


def _gains_template(law: int) -> str:
    """The gains as ``check_contact`` names them (``K_P = [...], ...``, rounded to 6 decimals, of the law's default
    controller), the z entry of each gain the panel sets a field of its control (``{K_z:g}``)."""
    ctl = _CLASSES[law]()
    parts = []
    for name, value in ctl._gain_fields().items():
        text = _gains_text(**{name: value})
        if name in _SET[law]:
            field = "{" + _SET[law][name] + ":g}"
            entries = np.round(np.atleast_1d(value), 6).tolist()
            if len(entries) > 1:
                entries = [repr(v) for v in entries]
                entries[2] = field
                text = f"{name} = [" + ", ".join(entries) + "]"
            else:
                text = f"{name} = [{field}]"
        parts.append(text)
    return ", ".join(parts)


def interaction_refusals() -> dict:
    """The messages of :func:`interaction_program`'s refusal codes, as :class:`~scara.plots.panels.Text`
    templates of its outputs: :func:`~scara.interaction.simulate_contact`'s wordings of a stopped run."""
    from ..plots.panels import Text  # noqa: PLC0415 - the panels' template class
    refusals = {}
    d_e = Surface().damping
    places = (_fields(IN_CONTACT, k="k_e").replace("{d:g}", f"{d_e:g}"), IN_FREE_SPACE)
    for law, name in enumerate(LAWS):
        for where, place in enumerate(places):
            text = (UNSTABLE_MESSAGE.replace("{name}", name).replace("{place}", place).replace("{dt:g}", f"{DT:g}")
                    .replace("{r:.6g}", "{" + ("radius" if where == 0 else "radius_free") + ":.6g}"))
            refusals[_R_UNSTABLE + 10 * law + where] = text.replace("{gains}", _gains_template(law))
    for law, name in enumerate(LAWS):
        refusals.update(run_refusals(name, _R_RUN + 100 * law, _CLASSES[law].signals_layout.entry_names, LIMIT))
    return {code: Text(template) for code, template in refusals.items()}
