"""The page program of chapter 4's CLIK panel: one compiled run of the 70 s reference per move of the panel.

:func:`clik_program` (``inputs, data, out -> status``) is the panel's whole move, the kernel of its
:class:`~scara.plots.panels.PageProgram`: it reads the settings (:data:`INPUTS`: the method as the index of
:data:`PANEL_METHODS`, the relaxed component as the index of ``COMPONENTS``, the gains ``K_x, K_y, K_z, K_phi``
(1/s), the damping ``lambda`` (m) and the null-space gain ``k0`` (1/s)), makes the checks :func:`scara.clik`
and :func:`scara.clik2` make before a run (the same kernels, :mod:`scara._clik.kernels`), runs the first-order
loop (4.4), (4.8), (4.13), (4.15) or the second-order loop (4.16) and writes the summary and the thinned
curves of the panel's figure into ``out``. Its core is :func:`clik_core`; :func:`clik_program` is where a stage
that samples the reference (the planner's kernels) will go in front of it.

``data`` (made once by :func:`clik_data`) starts with a header (:data:`HEADER`: the sample count ``n``, ``dt``,
the points drawn per curve, the arm's ``a1, a2, d0`` and reach, the start ``q0`` and ``qd0``, and the offsets of
the arrays), then holds the reference sampled every ``dt``: ``t`` (n,), ``x_d``, ``xd_d``, ``xdd_d`` (n, 4, row
by row) at the offsets the header gives. ``out`` is laid out by :func:`clik_outputs`: the numbers of
:data:`SCALARS`, then the time axes of the thinned curves and, for each method, its position-error and
orientation-error envelopes and its thinned manipulability (zero for the methods not run).
"""
from __future__ import annotations

import math

import numpy as np

from .._clik.kernels import (CHECK_GAIN, CHECK_K0, CHECK_TRANSPOSE, CHECK_TRANSPOSE_NONFINITE, RES_COMPONENT,
                             RES_ERROR, RES_HIGH, RES_K0_LIMIT, RES_KD, RES_KP, RES_LIMIT, RES_LOW, RES_MU_MAX,
                             RES_RHO, RES_SCALE, RES_SIZE, RES_WORST, _bound_component, _clik1_kernel,
                             _clik2_kernel, _damping_ceiling, _first_order_check, _initial_error_check,
                             _second_order_check)
from .._clik.records import (COMPONENTS, METHOD_INVERSE, METHOD_PSEUDOINVERSE, METHOD_TRANSPOSE, OBJECTIVE_SIN2,
                             STATUS_DONE, STATUS_ERROR_BOUND, STATUS_NONFINITE, FirstOrderLaw, Reference,
                             SecondOrderLaw, Series)
from .._compile import ArrayLayout, kernel
from ..kinematics import Geometry
from ..trajectory._plan import sample_plan
from .thinning import LOG_FLOOR, envelope_kernel, envelope_length, thin_kernel, thin_length  # noqa: F401

__all__ = ["PANEL_METHODS", "INPUTS", "HEADER", "SCALARS", "clik_program", "clik_core", "clik_data",
           "clik_outputs", "clik_start", "refusal_templates", "envelope_kernel", "thin_kernel", "envelope_length",
           "thin_length"]

#: the panel's methods, in the order of its dropdown (the ``method`` input is an index into this)
PANEL_METHODS = ("inverse", "transpose", "pseudoinverse", "second_order")
P_INVERSE = 0
P_TRANSPOSE = 1
P_PSEUDO = 2
P_SECOND = 3
#: the program's inputs, in order
INPUTS = ("method", "relaxed", "Kx", "Ky", "Kz", "Kphi", "damping", "k0")
IN_METHOD = 0
IN_RELAXED = 1
IN_K = 2
IN_DAMPING = 6
IN_K0 = 7
#: the error bound of a run (m or rad; :func:`scara.clik`'s default ``max_error``)
MAX_ERROR = 0.1
#: the start-up the summary's error figures skip (s; :meth:`scara.ClikResult.summary`'s default ``settle``)
SETTLE = 0.1
#: a largest position error above this (m) is flagged in the panel's notes
STRAY = 1e-3

#: the header of ``data``: sizes, the arm, the start and the offsets (in ``data`` or in ``out``) of the arrays
HEADER = ArrayLayout(("n", 1), ("dt", 1), ("points", 1), ("a1", 1), ("a2", 1), ("d0", 1), ("r_max", 1),
                     ("q0", 4), ("qd0", 4), ("singular_start", 1), ("t_at", 1), ("x_at", 1), ("xd_at", 1),
                     ("xdd_at", 1), ("env_len", 1), ("thin_len", 1), ("t_env_at", 1), ("t_thin_at", 1),
                     ("series_at", 1))
(H_N, H_DT, H_POINTS, H_A1, H_A2, H_D0, H_R_MAX, H_Q0, H_QD0, H_SINGULAR, H_T_AT, H_X_AT, H_XD_AT, H_XDD_AT,
 H_ENV_LEN, H_THIN_LEN, H_T_ENV_AT, H_T_THIN_AT, H_SERIES_AT) = HEADER.offsets

#: the numbers the program writes at the start of ``out``: the run's summary in SI units and in the panel's
#: (mm, mrad), the flags of its notes and traces, and the numbers its refusals name
SCALARS = ArrayLayout(
    ("max_position_error", 1), ("rms_position_error", 1), ("max_orientation_error", 1), ("min_manipulability", 1),
    ("mean_manipulability", 1), ("max_ep_mm", 1), ("rms_ep_mm", 1), ("max_eo_mrad", 1), ("drift", 1),
    ("strays", 1), ("pseudo", 1), ("show_inverse", 1), ("show_transpose", 1), ("show_pseudoinverse", 1),
    ("show_second_order", 1), ("K_bad", 1), ("K_limit", 1), ("k0_value", 1), ("k0_limit", 1), ("mu_max", 1),
    ("t_worst", 1), ("scale_limit", 1), ("KP_bad", 1), ("KD_bad", 1), ("rho", 1), ("jury_low", 1),
    ("jury_high", 1), ("e0", 1), ("max_error", 1), ("damping_limit", 1), ("t_fail", 1), ("step_fail", 1),
    ("e_fail", 1), ("theta2_fail", 1), ("w_fail", 1), ("run_length", 1))
(O_MAX_EP, O_RMS_EP, O_MAX_EO, O_W_MIN, O_W_MEAN, O_MAX_EP_MM, O_RMS_EP_MM, O_MAX_EO_MRAD, O_DRIFT, O_STRAYS,
 O_PSEUDO, O_SHOW, _O_SHOW_T, _O_SHOW_P, _O_SHOW_S, O_K_BAD, O_K_LIMIT, O_K0_VALUE, O_K0_LIMIT, O_MU_MAX,
 O_T_WORST, O_SCALE_LIMIT, O_KP_BAD, O_KD_BAD, O_RHO, O_JURY_LOW, O_JURY_HIGH, O_E0, O_MAX_ERROR,
 O_DAMPING_LIMIT, O_T_FAIL, O_STEP_FAIL, O_E_FAIL, O_THETA2_FAIL, O_W_FAIL, O_RUN_LENGTH) = SCALARS.offsets
# the flag of method m is at O_SHOW + m
assert SCALARS.names[O_SHOW:O_SHOW + 4] == tuple(f"show_{m}" for m in PANEL_METHODS)

#: refusal codes: a gain past (4.6) (+ 4 j + i, j = 0 inverse, 1 pseudo-inverse, i the component), ``k0`` past
#: (4.14), transpose gains past (4.12) (or overflowing it), second-order gains past Jury's test (+ i), an
#: initial error above the bound (+ i), a damping above its ceiling, a singular start for the second order, a
#: run shorter than the settling time, and a run that diverged (+ 8 m + c, m the panel's method, c = 0 a
#: non-finite value, 1 + i the error of component i past the bound, 5 a singular Jacobian)
R_GAIN = 10
R_K0 = 20
R_TRANSPOSE = 21
R_TRANSPOSE_NONFINITE = 22
R_JURY = 30
R_INITIAL = 40
R_DAMPING = 50
R_SINGULAR_START = 51
R_SHORT = 52
R_DIVERGED = 60


# --------------------------------------------------------------------------------------------------
# the summary of a run (the figures of scara.ClikResult.summary)
# --------------------------------------------------------------------------------------------------
@kernel
def _summary(t, e, w, keep, settle, ep, eo, res):
    """The summary of a run: ``ep[k] = ||e_p||`` over the kept position components and ``eo[k] = |e_phi|`` (0 if
    phi is relaxed) at every sample, and in ``res`` the largest and RMS position error and the largest
    orientation error over the samples from ``t[0] + settle`` on, then the smallest and mean manipulability
    over the whole run (sums compensated, as Kahan's)."""
    n = t.shape[0]
    start = t[0] + settle - 1e-12
    max_ep = -math.inf
    max_eo = -math.inf
    s = 0.0
    c = 0.0
    count = 0
    for k in range(n):
        sq = 0.0
        for i in range(3):
            if keep[i] > 0.0:
                sq += e[k, i] * e[k, i]
        ep[k] = math.sqrt(sq)
        eo[k] = abs(e[k, 3]) if keep[3] > 0.0 else 0.0
        if t[k] >= start:
            if ep[k] > max_ep:
                max_ep = ep[k]
            if eo[k] > max_eo:
                max_eo = eo[k]
            yk = ep[k] * ep[k] - c
            tk = s + yk
            c = (tk - s) - yk
            s = tk
            count += 1
    w_min = math.inf
    sw = 0.0
    cw = 0.0
    for k in range(n):
        if w[k] < w_min:
            w_min = w[k]
        yk = w[k] - cw
        tk = sw + yk
        cw = (tk - sw) - yk
        sw = tk
    res[0] = max_ep
    res[1] = math.sqrt(s / count)
    res[2] = max_eo
    res[3] = w_min
    res[4] = sw / n


# --------------------------------------------------------------------------------------------------
# the program
# --------------------------------------------------------------------------------------------------
@kernel
def _loop_method(method):
    """The first-order loop's code of the panel's ``method``."""
    if method == P_TRANSPOSE:
        return METHOD_TRANSPOSE
    if method == P_PSEUDO:
        return METHOD_PSEUDOINVERSE
    return METHOD_INVERSE


@kernel
def _checks(method, K, keep, lam, k0, dt, t, xr, q0, data, out):
    """The checks of :func:`scara.clik` / :func:`scara.clik2` before a run, in their order: the damping's
    ceiling (4.15), the initial error, the start velocity of the second order, the stability limits (4.6),
    (4.12), (4.14), (4.19). Returns 0 or the refusal code, with the numbers it names written into ``out``."""
    a1 = data[H_A1]
    a2 = data[H_A2]
    res = np.zeros(RES_SIZE)
    out[O_MAX_ERROR] = MAX_ERROR
    lam_max = _damping_ceiling(data[H_R_MAX])
    out[O_DAMPING_LIMIT] = lam_max
    if lam > lam_max:
        return R_DAMPING
    i = _initial_error_check(xr[0], q0, a1, a2, data[H_D0], keep, MAX_ERROR, res)
    if i >= 0:
        out[O_E0] = res[RES_ERROR]
        return R_INITIAL + i
    if method == P_SECOND:
        if data[H_SINGULAR] != 0.0:
            return R_SINGULAR_START
        KP = np.empty(4)
        KD = np.empty(4)
        for j in range(4):
            KP[j] = K[j] * K[j]
            KD[j] = 2.0 * K[j]
        i = _second_order_check(KP, KD, dt, res)
        if i >= 0:
            out[O_KP_BAD] = res[RES_KP]
            out[O_KD_BAD] = res[RES_KD]
            out[O_RHO] = res[RES_RHO]
            out[O_JURY_LOW] = res[RES_LOW]
            out[O_JURY_HIGH] = res[RES_HIGH]
            return R_JURY + i
        return 0
    code = _first_order_check(_loop_method(method), K, keep, dt, k0, OBJECTIVE_SIN2, xr, a1, a2, q0[1], res)
    out[O_K_LIMIT] = res[RES_LIMIT]
    if code == CHECK_GAIN:
        i = int(res[RES_COMPONENT])
        out[O_K_BAD] = K[i]
        return R_GAIN + 4 * (1 if method == P_PSEUDO else 0) + i
    if code == CHECK_K0:
        out[O_K0_VALUE] = k0
        out[O_K0_LIMIT] = res[RES_K0_LIMIT]
        return R_K0
    if code == CHECK_TRANSPOSE or code == CHECK_TRANSPOSE_NONFINITE:
        out[O_MU_MAX] = res[RES_MU_MAX]
        out[O_T_WORST] = t[int(res[RES_WORST])]
        out[O_SCALE_LIMIT] = res[RES_SCALE]
        return R_TRANSPOSE if code == CHECK_TRANSPOSE else R_TRANSPOSE_NONFINITE
    return 0


@kernel
def _diagnosis(method, info, t, q, e, w, keep, out):
    """The refusal code of a run that stopped with ``info = [status, step]`` (the cause of
    :func:`scara._clik.result._fail`), with the time, the step and the values it names written into ``out``."""
    status = int(info[0])
    k = int(info[1])
    out[O_T_FAIL] = t[k]
    out[O_STEP_FAIL] = k
    base = R_DIVERGED + 8 * method
    if status == STATUS_NONFINITE:
        return base
    if status == STATUS_ERROR_BOUND:
        i = _bound_component(e, k, keep)
        out[O_E_FAIL] = e[k, i]
        return base + 1 + i
    out[O_THETA2_FAIL] = q[k, 1]
    out[O_W_FAIL] = w[k]
    return base + 5


@kernel
def clik_core(inputs, data, out):
    """One move of the CLIK panel: check the settings ``inputs`` (:data:`INPUTS`) as :func:`scara.clik` and
    :func:`scara.clik2` do, run the chosen CLIK ((4.4), (4.8), (4.13) with the null-space term (4.14) and the
    damping (4.15), or the second order (4.16) with ``K_P = K^2``, ``K_D = 2 K``) along the reference of
    ``data`` (:func:`clik_data`), and write the summary and the thinned curves into ``out``
    (:func:`clik_outputs`). Returns 0, or the refusal code (``R_*``) with the numbers its message names in
    ``out``."""
    n = int(data[H_N])
    dt = data[H_DT]
    points = int(data[H_POINTS])
    t_at = int(data[H_T_AT])
    x_at = int(data[H_X_AT])
    xd_at = int(data[H_XD_AT])
    xdd_at = int(data[H_XDD_AT])
    t = data[t_at:t_at + n]
    xr = data[x_at:x_at + 4 * n].reshape((n, 4))
    vr = data[xd_at:xd_at + 4 * n].reshape((n, 4))
    ar = data[xdd_at:xdd_at + 4 * n].reshape((n, 4))
    q0 = data[H_Q0:H_Q0 + 4]
    method = int(inputs[IN_METHOD])
    relaxed = int(inputs[IN_RELAXED])
    K = np.empty(4)
    keep = np.empty(4)
    for i in range(4):
        K[i] = inputs[IN_K + i]
        keep[i] = 1.0
    if method == P_PSEUDO:
        keep[relaxed] = 0.0
    lam = inputs[IN_DAMPING] if method != P_TRANSPOSE else 0.0  # the transpose solves nothing: no damping
    k0 = inputs[IN_K0] if method == P_PSEUDO else 0.0

    status = _checks(method, K, keep, lam, k0, dt, t, xr, q0, data, out)
    if status != 0:
        return status

    # one block for every series of the run (as scara._clik.records._series): a block this large is backed by
    # huge pages where the system allows it, where five separate ones cost thousands of page faults per run
    rows = 5 if method == P_SECOND else 4
    buf = np.empty(n * (4 * rows + 3))
    q = buf[0:4 * n].reshape((n, 4))
    qd = buf[4 * n:8 * n].reshape((n, 4))
    x = buf[8 * n:12 * n].reshape((n, 4))
    e = buf[12 * n:16 * n].reshape((n, 4))
    w = buf[16 * n:17 * n]
    ep = buf[17 * n:18 * n]
    eo = buf[18 * n:19 * n]
    info = np.zeros(2)
    for i in range(4):
        q[0, i] = q0[i]
    arm = Geometry(data[H_A1], data[H_A2], data[H_D0])
    ref = Reference(xr, vr, ar)
    if method == P_SECOND:
        qdd = buf[19 * n:23 * n].reshape((n, 4))
        KP = np.empty(4)
        KD = np.empty(4)
        for i in range(4):
            KP[i] = K[i] * K[i]
            KD[i] = 2.0 * K[i]
            qd[0, i] = data[H_QD0 + i]
        _clik2_kernel(ref, SecondOrderLaw(dt, KP, KD, lam * lam, 0.0, MAX_ERROR), arm, Series(q, qd, qdd, x, e, w),
                      info)
    else:
        qdd = np.empty((0, 4))
        law = FirstOrderLaw(dt, _loop_method(method), K, keep, lam * lam, 0.0, k0, OBJECTIVE_SIN2, MAX_ERROR)
        _clik1_kernel(ref, law, arm, Series(q, qd, qdd, x, e, w), info)
    if int(info[0]) != STATUS_DONE:
        return _diagnosis(method, info, t, q, e, w, keep, out)
    length = t[n - 1] - t[0]
    if not (0.0 <= SETTLE < length):
        out[O_RUN_LENGTH] = length
        return R_SHORT

    res = np.zeros(5)
    _summary(t, e, w, keep, SETTLE, ep, eo, res)
    out[O_MAX_EP] = res[0]
    out[O_RMS_EP] = res[1]
    out[O_MAX_EO] = res[2]
    out[O_W_MIN] = res[3]
    out[O_W_MEAN] = res[4]
    out[O_MAX_EP_MM] = res[0] * 1e3
    out[O_RMS_EP_MM] = res[1] * 1e3
    out[O_MAX_EO_MRAD] = res[2] * 1e3
    out[O_STRAYS] = 1.0 if res[0] > STRAY else 0.0
    out[O_SHOW + method] = 1.0
    if method == P_PSEUDO:
        out[O_PSEUDO] = 1.0
        drift = 0.0
        for k in range(n):
            v = abs(e[k, relaxed])
            if v > drift:
                drift = v
        out[O_DRIFT] = drift

    le = int(data[H_ENV_LEN])
    lt = int(data[H_THIN_LEN])
    t_env = out[int(data[H_T_ENV_AT]):int(data[H_T_ENV_AT]) + le]
    t_thin = out[int(data[H_T_THIN_AT]):int(data[H_T_THIN_AT]) + lt]
    at = int(data[H_SERIES_AT]) + method * (2 * le + lt)
    envelope_kernel(t, ep, points, t_env, out[at:at + le])
    envelope_kernel(t, eo, points, t_env, out[at + le:at + 2 * le])
    thin_kernel(t, w, points, t_thin, out[at + 2 * le:at + 2 * le + lt])
    return 0


@kernel
def clik_program(inputs, data, out):
    """The CLIK panel's page program: :func:`clik_core` on the reference held in ``data`` (the place where a
    stage sampling the reference from the planner's kernels will run first)."""
    return clik_core(inputs, data, out)


_HEADER_SIZE = HEADER.size


@kernel
def clik_prepare(compact, data):
    """The ``data`` of :func:`clik_program` from its compact form (:func:`clik_compact`): the header as it is,
    then the reference sampled from the plan that follows it by the planner's own kernel
    (:func:`~scara.programs.path.sample_plan`). Returns 0, or the sampler's code (1: the sizes disagree)."""
    hs = _HEADER_SIZE
    for i in range(hs):
        data[i] = compact[i]
    n = int(compact[H_N])
    if data.shape[0] != hs + 13 * n:
        return 1
    t = data[hs:hs + n]
    x = data[hs + n:hs + 5 * n].reshape((n, 4))
    xd = data[hs + 5 * n:hs + 9 * n].reshape((n, 4))
    xdd = data[hs + 9 * n:hs + 13 * n].reshape((n, 4))
    return sample_plan(compact[hs:], t, x, xd, xdd)


# --------------------------------------------------------------------------------------------------
# packing (Python, once per panel)
# --------------------------------------------------------------------------------------------------
def clik_outputs(n: int, points: int) -> ArrayLayout:
    """The layout of ``out`` for a reference of ``n`` samples drawn with ``points`` points per curve: the
    numbers of :data:`SCALARS`, the time axes ``t_env`` (the envelopes') and ``t_thin`` (the thinned
    manipulability's), then for each method ``m`` of :data:`PANEL_METHODS` its curves ``ep_m``, ``eo_m``
    (envelopes of ``||e_p||`` and ``|e_phi|``, m and rad) and ``w_m`` (m^2)."""
    le, lt = envelope_length(int(n), int(points)), thin_length(int(n), int(points))
    fields = [(name, 1) for name in SCALARS.names] + [("t_env", le), ("t_thin", lt)]
    for m in PANEL_METHODS:
        fields += [(f"ep_{m}", le), (f"eo_{m}", le), (f"w_{m}", lt)]
    layout = ArrayLayout(*fields)
    base = layout.offsets.t_env + le + lt
    for k, m in enumerate(PANEL_METHODS):  # the block of each method, as clik_core finds it
        assert getattr(layout.offsets, f"ep_{m}") == base + k * (2 * le + lt)
    return layout


def clik_start(traj, p=None):
    """The start of the panel's runs on ``traj``: ``(q0, qd0, message)``, ``q0`` of
    :func:`scara.start_configuration`, ``qd0 = J_A^-1 xd_d(0)`` of the second order (zeros and the message of
    its refusal when ``q0`` is singular, else ``message`` is None)."""
    from .._clik.api import _start_velocity, start_configuration  # noqa: PLC0415
    from .._clik.checks import _params  # noqa: PLC0415
    from ..errors import UnstableError  # noqa: PLC0415

    p = _params(traj, p)
    q0 = start_configuration(traj, p)
    try:
        return q0, _start_velocity(q0, np.asarray(traj.xd, float)[0], None, p), None
    except UnstableError as exc:
        return q0, np.zeros(4), str(exc)


def clik_data(traj, p=None, points: int = 800) -> np.ndarray:
    """The ``data`` of :func:`clik_program` for the trajectory ``traj`` (its ``t``, ``x``, ``xd``, ``xdd``, checked
    as :func:`scara.clik2` checks them) on the robot ``p`` (default ``traj.params``), drawn with ``points`` points
    per curve: :data:`HEADER`, then ``t`` (n,), ``x_d``, ``xd_d``, ``xdd_d`` (n, 4, flattened row by row) at the
    offsets the header gives."""
    from .._clik.checks import _params, _trajectory  # noqa: PLC0415
    from ..errors import check_count  # noqa: PLC0415

    points = check_count(points, "points", 2, 10_000, "samples per curve")  # scara.plots._common.MAX_POINTS
    p = _params(traj, p)
    t, x, xd, xdd, dt = _trajectory(traj, True, p)
    n = len(t)
    q0, qd0, message = clik_start(traj, p)
    out = clik_outputs(n, points)
    at = HEADER.size
    header = HEADER.pack(n=n, dt=dt, points=points, a1=p.a1, a2=p.a2, d0=p.d0, r_max=p.r_max, q0=q0, qd0=qd0,
                         singular_start=message is not None, t_at=at, x_at=at + n, xd_at=at + 5 * n,
                         xdd_at=at + 9 * n, env_len=out.sizes["t_env"], thin_len=out.sizes["t_thin"],
                         t_env_at=out.offsets.t_env, t_thin_at=out.offsets.t_thin,
                         series_at=out.offsets.t_thin + out.sizes["t_thin"])
    return np.concatenate([header, t, x.ravel(), xd.ravel(), xdd.ravel()])


def clik_compact(traj, p=None, points: int = 800):
    """``(compact, size)``: the compact form of :func:`clik_data` for a planned trajectory ``traj`` (one with a
    ``plan_vector``, as :func:`~scara.trajectory.plan_path` makes): its header, then the plan, which
    :func:`clik_prepare` samples back into the data (``size`` floats); None for a trajectory with no plan."""
    if getattr(traj, "plan_vector", None) is None:
        return None
    data = clik_data(traj, p, points)
    return np.concatenate([data[:HEADER.size], np.asarray(traj.plan_vector, float)]), data.size


def refusal_templates(singular_start: str | None = None) -> dict:
    """The message of every refusal code of :func:`clik_program`, as a template of the program's fields (the
    same words as :func:`scara.clik` and :func:`scara.clik2`; the templates come from their checks).
    ``singular_start`` is the message of a singular start (:func:`clik_start`)."""
    from .._clik.checks import _damping_text, _initial_error_text  # noqa: PLC0415
    from .._clik.records import STATUS_SINGULAR  # noqa: PLC0415
    from .._clik.result import _divergence_text, _settle_text  # noqa: PLC0415
    from .._clik.stability import TRANSPOSE_LIMIT_TEXT, _gain_limit_text, _jury_text, _k0_limit_text  # noqa: PLC0415

    out = {}
    for j, method in enumerate(("inverse", "pseudoinverse")):
        for i, c in enumerate(COMPONENTS):
            out[R_GAIN + 4 * j + i] = _gain_limit_text(c, method)
    out[R_K0] = _k0_limit_text("sin2")
    out[R_TRANSPOSE] = TRANSPOSE_LIMIT_TEXT
    out[R_TRANSPOSE_NONFINITE] = ("K = [{Kx:.5g}, {Ky:.5g}, {Kz:.5g}, {Kphi:.5g}] gives a non-finite largest "
                                  "eigenvalue mu of J_A J_A^T K: K is too large and the result overflows")
    for i, c in enumerate(COMPONENTS):
        out[R_JURY + i] = _jury_text(c)
        out[R_INITIAL + i] = _initial_error_text(c)
    out[R_DAMPING] = _damping_text()
    text = singular_start or "the start configuration is singular"
    if "{" in text or "}" in text:  # pragma: no cover - the package's messages hold no braces
        raise ValueError(f"a refusal's fixed text holds a brace: {text!r}")
    out[R_SINGULAR_START] = text
    out[R_SHORT] = _settle_text(SETTLE)
    for m, method in enumerate(PANEL_METHODS):
        what = "the second-order CLIK" if method == "second_order" else f"the {method} CLIK"
        base = R_DIVERGED + 8 * m
        out[base] = _divergence_text(what, STATUS_NONFINITE)
        for i, c in enumerate(COMPONENTS):
            out[base + 1 + i] = _divergence_text(what, STATUS_ERROR_BOUND, c)
        out[base + 5] = _divergence_text(what, STATUS_SINGULAR)
    return out
