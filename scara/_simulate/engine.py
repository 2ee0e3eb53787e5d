"""The engine of the closed loop (chapter 5): the compiled loop over the samples and :func:`simulate`, the
public entry point that checks its inputs, builds the references, runs the loop and assembles the result."""
from __future__ import annotations

import math
import time
from collections import namedtuple

import numpy as np

from .. import _compile
from .._compile import LawData
from ..dynamics import dynamic_array
from ..errors import ScaraError, ShapeError, UnstableError, check_count, check_positive
from ..params import ScaraParams
from .interface import (
    DIVERGED, JOINT_LIMIT, LAW_FAILED, NOT_FINITE, OK, SINGULAR_INERTIA, _compiled_law, check_law_bounds, fill_text,
    law_arrays,
)
from .plant import _plant_acceleration, _plant_constants, _rk4_step
from .setpoints import _references, _start_state
from .result import SimulationResult, _pose_error

__all__ = ["closed_loop_kernel", "simulate"]

#: What the loop records, one row per sample: ``q, qd, qdd, tau`` (N, 4) and the law's signals (N, n_sig).
Series = namedtuple("Series", ("q", "qd", "qdd", "tau", "signals"))
#: The run's settings: sampling period (s), RK4 steps per period, the bound on any state or torque entry, and
#: the quill's stroke as its middle and half-length (m): ``d3`` must keep ``|d3 - d3_mid| <= d3_half``.
Stepping = namedtuple("Stepping", ("dt", "substeps", "limit", "d3_mid", "d3_half"))

#: The largest number of RK4 steps per sampling period: at 1 ms that is a step of 1 us, far below any time
#: constant of the arm (the fastest, the quill's friction, is about 1 s; the controllers' poles are near
#: 20-30 rad/s), so more steps only cost time (a 70 s run would take minutes).
MAX_SUBSTEPS = 1000

if _compile.COMPILED:
    _t = _compile.numba_types
    _STEPPING = _t.NamedTuple((_t.float64, _t.int64, _t.float64, _t.float64, _t.float64), Stepping)
    _LOOP_SIGNATURE = _t.void(_compile.LAW_TYPE, _t.UniTuple(_compile.VECTOR, 2), _compile.MATRIX, _STEPPING,
                              _compile.VECTOR, _compile.LAW_DATA_TYPE, _t.NamedUniTuple(_compile.MATRIX, 5, Series),
                              _compile.INT_VECTOR)
else:  # pragma: no cover - plain Python
    _LOOP_SIGNATURE = None


@_compile.kernel
def _torque_failure(tau, k, info):
    """Record why a torque of sample ``k`` failed the limit check: :data:`NOT_FINITE` with the index of the
    first NaN or infinite entry of ``tau`` in ``info[2]``, or :data:`DIVERGED` (finite, past the limit)."""
    info[0] = DIVERGED
    info[1] = k
    info[2] = 0
    for i in range(4):
        if not math.isfinite(tau[i]):
            info[0] = NOT_FINITE
            info[2] = i
            return


@_compile.kernel
def first_bad_signal(sig, end):
    """``(k, i)`` of the first NaN or infinite entry of the signals ``sig`` (N, n_sig) among its first ``end`` rows
    (row by row), or ``(-1, -1)``: the check of a run's signals, once after the loop (a check per sample inside the
    loop would cost it about 5 %)."""
    for k in range(end):
        for i in range(sig.shape[1]):
            if not math.isfinite(sig[k, i]):
                return k, i
    return -1, -1


def _first_bad_signal(sig_out, end):
    """``(k, i)`` of the first NaN or infinite signal among the first ``end`` samples, or None
    (:func:`first_bad_signal`)."""
    k, i = first_bad_signal(np.ascontiguousarray(sig_out), int(end))
    return None if k < 0 else (int(k), int(i))


#: The messages of a run the loop stopped, as templates: the text fields (``{controller}``, ``{what}``, ``{end}``,
#: ``{cause}``, filled in by :func:`~.interface.fill_text`) and the numbers (the time ``t``, the sample ``k``...).
#: The one wording of :func:`_raise_failure` and of the page programs that run the loop.
FAILURE_MESSAGES = {
    NOT_FINITE: ("the closed loop of {controller} diverged at t = {t:.4f} s (sample {k:.0f}): the controller's law "
                 "returned {what} = {value:g}, which is not finite"),
    JOINT_LIMIT: ("the run of {controller} left the joint range at t = {t:.4f} s (sample {k:.0f}): joint 3 (d3) = "
                  "{d3:.6g} m (at {v3:.3g} m/s) is past {end} of the quill's stroke [{d3_min:g}, {d3_max:g}] m; the "
                  "engine models no end stop"),
    LAW_FAILED: "the closed loop of {controller} diverged at t = {t:.4f} s (sample {k:.0f}): {cause}",
}
#: The causes of the other stops (``{limit:g}`` and the law's ``{code}`` are filled in as text).
FAILURE_CAUSES = {
    DIVERGED: "a joint state or torque exceeded {limit:g} or is not finite",
    SINGULAR_INERTIA: "the plant's inertia matrix lost positive definiteness",
    LAW_FAILED: "the controller's law returned code {code}",
}


def failure_cause(status: int, code: int = 0, explain=None, limit: float = 0.0) -> str:
    """The cause of a stop of status ``status`` (:data:`LAW_FAILED`, :data:`DIVERGED`, :data:`SINGULAR_INERTIA`):
    for a law's failure its ``code`` and what the controller's ``explain(code)`` says of it."""
    if status == LAW_FAILED:
        return FAILURE_CAUSES[LAW_FAILED].format(code=code) + (f": {explain(code)}" if explain else "")
    return FAILURE_CAUSES[status].format(limit=limit)


def failure_message(status: int, controller: str, **text) -> str:
    """The template (numbers only) of the message of a stop of status ``status`` of ``controller``'s run, the
    text fields ``text`` (``what``, ``end``, ``cause``) written in; a status other than :data:`NOT_FINITE` and
    :data:`JOINT_LIMIT` takes its :func:`failure_cause` as ``cause``."""
    return fill_text(FAILURE_MESSAGES.get(status, FAILURE_MESSAGES[LAW_FAILED]), controller=controller, **text)


@_compile.kernel(inline="always")
def _loop_start(q0, qd0, q, qd, n, info):
    """The start of a closed loop of ``n`` samples: the state ``q``, ``qd`` (4,) set to ``q0``, ``qd0`` and ``info``
    to ``[OK, n, 0]`` (a run that ends with it unchanged went through all ``n`` samples); the one start of the
    engine's loop, of the contact engine's and of the page programs'."""
    for i in range(4):
        q[i] = q0[i]
        qd[i] = qd0[i]
    info[0] = OK
    info[1] = n
    info[2] = 0


@_compile.kernel(inline="always")
def _before_law(k, q, qd, q_out, qd_out, q_law, qd_law, tau, sig):
    """The start of sample ``k`` of the engine's loop: the measured state recorded in row ``k`` of ``q_out``,
    ``qd_out`` and copied to the law's own ``q_law``, ``qd_law``; ``tau`` and the signals ``sig`` zeroed."""
    for i in range(4):
        q_out[k, i] = q[i]
        qd_out[k, i] = qd[i]
        q_law[i] = q[i]
        qd_law[i] = qd[i]
        tau[i] = 0.0
    for i in range(sig.shape[0]):
        sig[i] = 0.0


@_compile.kernel(inline="always")
def _loop_arrays(n_ref, n_sig):
    """The work arrays of a closed loop: ``q``, ``qd``, ``qdd``, ``spare``, ``q_law``, ``qd_law`` (4,) each, the
    reference row ``r`` (``n_ref``,), the torque ``tau`` (4,) and the signals ``sig`` (``n_sig``,)."""
    return (np.empty(4), np.empty(4), np.empty(4), np.empty(4), np.empty(4), np.empty(4), np.empty(n_ref),
            np.empty(4), np.empty(n_sig))


@_compile.kernel(inline="always")
def _law_failed(k, code, tau, sig, limit, tau_out, sig_out, info):
    """Sample ``k``'s torque ``tau`` and signals ``sig`` recorded in ``tau_out``, ``sig_out``; True, ``info`` saying
    why, when the law returned a failure ``code`` or a torque is past ``limit`` (or not finite). The one reading of
    a law's step in every loop."""
    for i in range(4):
        tau_out[k, i] = tau[i]
    for i in range(sig.shape[0]):
        sig_out[k, i] = sig[i]
    if code != OK:
        info[0] = LAW_FAILED
        info[1] = k
        info[2] = code
        return True
    ok = True
    for i in range(4):
        if not abs(tau[i]) < limit:  # also catches NaN
            ok = False
    if not ok:
        _torque_failure(tau, k, info)
        return True
    return False


@_compile.kernel(inline="always")
def _state_failed(k, q, qd, limit, d3_mid, d3_half, q_out, qd_out, info):
    """The checks of the state reached at sample ``k + 1``: an entry of ``q`` or ``qd`` past ``limit``
    (:data:`DIVERGED`) or the quill outside its stroke ``|d3 - d3_mid| <= d3_half`` (:data:`JOINT_LIMIT`, the state
    recorded in row ``k + 1`` of ``q_out``, ``qd_out``). Returns True, ``info`` saying which, when one failed; the
    one check of every loop (the engine's, the contact engine's, the page programs')."""
    ok = True
    for i in range(4):
        if not (abs(q[i]) < limit and abs(qd[i]) < limit):
            ok = False
    if not ok:
        info[0] = DIVERGED
        info[1] = k + 1
        return True
    if not abs(q[2] - d3_mid) <= d3_half:  # the quill left its stroke (the plant has no end stop)
        for i in range(4):
            q_out[k + 1, i] = q[i]
            qd_out[k + 1, i] = qd[i]
        info[0] = JOINT_LIMIT
        info[1] = k + 1
        return True
    return False


@_compile.kernel(inline="always")
def _after_law(k, n, code, q, qd, qdd, spare, tau, sig, pc, h, substeps, limit, d3_mid, d3_half, q_out, qd_out,
               qdd_out, tau_out, sig_out, info):
    """The rest of sample ``k`` of ``n`` after the law returned ``code``: its torque and signals recorded, the
    checks of the engine (the law's code, the torque's bound, the state's, the quill's stroke), the plant's RK4
    steps with the torque held (``substeps`` of ``h``; the acceleration just after the update in row ``k`` of
    ``qdd_out``). Returns True when the run stops here, ``info`` saying why (see :func:`closed_loop_kernel`)."""
    if _law_failed(k, code, tau, sig, limit, tau_out, sig_out, info):
        return True
    if k == n - 1:
        a, c = _plant_acceleration(math.cos(q[1]), math.sin(q[1]), (qd[0], qd[1], qd[2], qd[3]),
                                   (tau[0], tau[1], tau[2], tau[3]), pc)
        if c != OK:
            info[0] = SINGULAR_INERTIA
            info[1] = k
        else:
            for i in range(4):
                qdd_out[k, i] = a[i]
        return True
    for s in range(substeps):
        if _rk4_step(q, qd, (tau[0], tau[1], tau[2], tau[3]), pc, h, qdd if s == 0 else spare) != OK:
            info[0] = SINGULAR_INERTIA
            info[1] = k
            return True
    for i in range(4):
        qdd_out[k, i] = qdd[i]
    return _state_failed(k, q, qd, limit, d3_mid, d3_half, q_out, qd_out, info)


@_compile.signature_kernel(_LOOP_SIGNATURE)
def closed_loop_kernel(law, start, ref, stepping, plant_dp, data, out, info):
    """The engine's loop over ``N = ref.shape[0]`` samples (see the package's docstring).

    ``start = (q0, qd0)``; ``stepping`` a :data:`Stepping`; ``plant_dp`` the plant's
    :func:`~scara.dynamics.dynamic_array`; ``data`` the law's :data:`LawData`. Writes the :data:`Series`
    ``out``. ``info`` (3,) int64 receives ``[code, k, law_code]``: :data:`OK` when all samples ran, otherwise
    :data:`LAW_FAILED`, :data:`NOT_FINITE` (a NaN or infinite torque of the law, whose index is in ``info[2]``;
    the signals are checked after the loop, :func:`_first_bad_signal`), :data:`DIVERGED` (a state not finite or
    above ``limit``), :data:`SINGULAR_INERTIA` or
    :data:`JOINT_LIMIT` (``d3`` left its stroke; that state is written in row ``k`` of ``out.q``, ``out.qd``),
    at sample ``k``. Only ``d3`` has limits: one comparison per step checks it.

    The law is called with small buffers owned by the loop (the measured state, the reference row, zeroed
    ``signals`` and ``tau``), copied to and from the output rows: no array view is created per sample.
    """
    q0, qd0 = start
    dt, substeps, limit = stepping.dt, stepping.substeps, stepping.limit
    d3_mid, d3_half = stepping.d3_mid, stepping.d3_half
    gains, model, state, work = data.gains, data.model, data.state, data.work
    q_out, qd_out, qdd_out, tau_out, sig_out = out.q, out.qd, out.qdd, out.tau, out.signals
    n = ref.shape[0]
    n_ref = ref.shape[1]
    n_sig = sig_out.shape[1]
    pc = _plant_constants(plant_dp)
    q, qd, qdd, spare, q_law, qd_law, r, tau, sig = _loop_arrays(n_ref, n_sig)
    _loop_start(q0, qd0, q, qd, n, info)
    h = dt / substeps
    for k in range(n):
        _before_law(k, q, qd, q_out, qd_out, q_law, qd_law, tau, sig)
        for i in range(n_ref):
            r[i] = ref[k, i]
        code = law(k, k * dt, dt, q_law, qd_law, r, gains, model, state, work, sig, tau)
        if _after_law(k, n, code, q, qd, qdd, spare, tau, sig, pc, h, substeps, limit, d3_mid, d3_half, q_out,
                      qd_out, qdd_out, tau_out, sig_out, info):
            return


def simulate(controller, traj=None, plant: ScaraParams | None = None, dt: float | None = None, *,
             joint_reference=None, q0=None, qd0=None, substeps: int = 1, duration: float | None = None,
             elbow: int | None = None, limit: float = 1e6) -> SimulationResult:
    """Run ``controller`` in closed loop on ``plant`` along ``traj``: the simulation engine of chapter 5.

    Parameters
    ----------
    controller : a :class:`Controller` (the engine's interface).
    traj : trajectory with ``t, x, xd, xdd`` (N,)/(N, 4) and ``dt``; may be None when ``joint_reference`` or
        ``duration`` (open loop) is given.
    plant : the true robot, default ``ScaraParams()`` (pass ``ScaraParams().with_payload(5.0)`` for
        the control chapter).
    dt : sampling period (s); default ``traj.dt`` or 1e-3. Must match ``traj.dt`` when both are given, and the
        spacing of ``traj.t`` (and of ``joint_reference.t`` when it has one), which must be uniform. A joint
        reference array carries no time: its rows are taken at ``dt``.
    joint_reference : (N, 12) ``[q_d, qd_d, qdd_d]``, a ``(q, qd, qdd)`` tuple or an object with
        ``q, qd, qdd`` (a ``clik2`` result). Default for joint controllers: ``clik2(traj)``.
    q0, qd0 : initial state; default the reference's first sample (joint controllers) or the inverse
        kinematics of ``x_d(0)`` with ``elbow`` (operational controllers; default the trajectory's own
        ``traj.elbow``, else -1); ``qd0`` default zero / reference.
    substeps : RK4 steps per sampling period (the torque is held over all of them), a whole number from 1 to
        :data:`MAX_SUBSTEPS` (1000).
    duration : length (s) of an open-loop run (``reference_kind == "none"``) without trajectory: a whole number
        of periods ``dt``. A run has at most :data:`~scara._simulate.interface.MAX_SAMPLES` samples.
    limit : a state or torque entry above this magnitude stops the run with :class:`~scara.UnstableError`.

    The start state must have ``d3`` within the quill's stroke ``[plant.d3_min, plant.d3_max]``
    (:class:`~scara.UnreachableError` otherwise), and a run in which ``d3`` leaves it stops with an
    :class:`~scara.UnstableError` naming joint 3, the time and the value: the plant models no end stop.

    A law compiled by :func:`~scara.control_law` runs in the compiled loop; a plain Python function (a law not
    yet decorated) runs in the same loop as plain Python, the same arithmetic: about a second for the 70 s
    reference instead of a few hundredths.

    Returns :class:`SimulationResult`. Raises :class:`~scara.ScaraError` for inconsistent inputs and
    :class:`~scara.UnstableError` (with the time and cause) when the run diverges.
    """
    plant = ScaraParams.resolve(plant)
    kind, dt, substeps = _check_run(controller, traj, dt, substeps)
    limit = check_positive(limit, "limit")
    ref, jref, x_d, xop, n = _references(kind, traj, joint_reference, duration, dt, plant)
    if n < 1:
        raise ShapeError(f"the reference holds {n} samples: a run needs at least one (N >= 1)")
    q0, qd0 = _start_state(q0, qd0, jref, xop, traj, plant, elbow)
    stepping = Stepping(float(dt), int(substeps), float(limit), 0.5 * (plant.d3_min + plant.d3_max),
                        0.5 * (plant.d3_max - plant.d3_min))
    out, state, info, elapsed, names = _run_loop(controller, (q0, qd0), ref, stepping, plant)
    bad_signal = _first_bad_signal(out[6], n if info[0] == OK else int(info[1]) + 1)
    if bad_signal is not None and (info[0] == OK or bad_signal[0] < info[1]):  # the run's first failure
        info[:] = NOT_FINITE, bad_signal[0], 4 + bad_signal[1]
    if info[0] != OK:
        _raise_failure(controller, info, dt, limit, out, plant, names)
    q_out, qd_out, qdd_out, tau_out, x, e, sig_out, spare = out
    _pose_error(q_out, q_out if x_d is None else np.ascontiguousarray(x_d), plant.a1, plant.a2, plant.d0, x, e)
    if x_d is None:
        spare[:] = x
        x_d = spare
        e[:] = 0.0
    inputs = (traj, joint_reference)
    ref, x_d = _owned(ref, inputs), _owned(x_d, inputs, into=spare)  # x_d is often the caller's traj.x
    return SimulationResult(t=np.arange(n) * dt, q=q_out, qd=qd_out, qdd=qdd_out, tau=tau_out, x=x, x_d=x_d, e=e,
                            reference=ref, reference_kind=kind,
                            q_d=None if jref is None else _owned(jref[:, :4], inputs),
                            signals={nm: np.ascontiguousarray(sig_out[:, i]) for i, nm in enumerate(names)},
                            controller=getattr(controller, "name", type(controller).__name__), plant=plant,
                            dt=dt, substeps=substeps, elapsed=elapsed,
                            extra={"final_state": state})


def _check_run(controller, traj, dt, substeps):
    """The checked ``(reference_kind, dt, substeps)`` of a run (see :func:`simulate`)."""
    if not hasattr(controller, "law") or controller.law is None:
        raise ScaraError(f"controller {controller!r} has no compiled law: see scara.simulate's interface")
    substeps = check_count(substeps, "substeps", 1, MAX_SUBSTEPS, "RK4 steps per period", "1000 RK4 steps per "
                           "period are already a step of 1 us at 1 ms, far below the arm's time constants")
    kind = controller.reference_kind
    if kind not in ("joint", "operational", "none"):
        raise ScaraError(f"reference_kind = {kind!r}; expected 'joint', 'operational' or 'none'")
    tdt = getattr(traj, "dt", None) if traj is not None else None
    if dt is None:
        dt = tdt if tdt is not None else 1e-3
    dt = check_positive(dt, "dt")
    if tdt is not None and abs(tdt - dt) > 1e-12 * dt:
        raise ScaraError(f"dt = {dt} differs from the trajectory's sampling period {tdt}; resample the trajectory")
    return kind, dt, substeps


def _caller_arrays(obj):
    """The arrays a caller handed in ``obj`` (an array, a tuple of them, or an object with array attributes)."""
    if isinstance(obj, np.ndarray):
        return [obj]
    if isinstance(obj, (tuple, list)):
        return [a for item in obj for a in _caller_arrays(item)]
    fields = [getattr(obj, f, None) for f in ("t", "x", "xd", "xdd", "q", "qd", "qdd")]  # a trajectory, a clik2 result
    return [v for v in fields + list(getattr(obj, "__dict__", {}).values()) if isinstance(v, np.ndarray)]


def _owned(arr, inputs, into=None):
    """``arr``, or a copy of it (written into ``into`` when given) when it shares memory with an array of
    ``inputs``: a result never shares memory with its caller's input."""
    if arr is into or not any(np.may_share_memory(arr, a) for a in _caller_arrays(inputs)):
        return arr
    if into is None:
        return arr.copy()
    into[:] = arr
    return into


def _run_loop(controller, start, ref, stepping, plant):
    """Run :func:`closed_loop_kernel` with the controller's arrays (:func:`~.interface.law_arrays`, checked by a
    trial call, :func:`~.interface.check_law_bounds`): ``(series, final state, info, elapsed s, signal names)``,
    ``series = (q, qd, qdd, tau, x, e, signals, spare)`` (``x``, ``e`` still to be filled; ``spare`` (N, 4) for
    the result's own ``x_d``)."""
    n = len(ref)
    data, sig_out, names = law_arrays(controller, n)
    check_law_bounds(controller, data, len(names), (start[0], start[1], ref[0]), stepping.dt)
    # one allocation for the six (N, 4) series and a spare one for x_d (each a C-contiguous slice; the spare is
    # touched only when used): a block this large is backed by
    # huge pages where the system allows it, which saves thousands of page faults per run
    block = np.empty((7, n, 4))
    q_out, qd_out, qdd_out, tau_out, x, e, spare = block
    info = np.zeros(3, dtype=np.int64)
    law = _compiled_law(controller.law)  # compile (or load) the law and the loop before the clock starts
    if _compile.python_law(law) is law:
        # a law that is no compiled kernel (a plain Python function, e.g. a reader's first draft without
        # @control_law) runs in the loop's plain-Python code: the same steps, about a second for a 70 s run
        loop = getattr(closed_loop_kernel, "py_func", closed_loop_kernel)
    else:
        loop = _compile.dispatcher_of(closed_loop_kernel)
    t0 = time.perf_counter()
    loop(law, start, ref, stepping, dynamic_array(plant), data, Series(q_out, qd_out, qdd_out, tau_out, sig_out), info)
    elapsed = time.perf_counter() - t0
    return (q_out, qd_out, qdd_out, tau_out, x, e, sig_out, spare), data.state, info, elapsed, names


def _raise_failure(controller, info, dt, limit, out, plant, names):
    """The :class:`~scara.UnstableError` of a run the loop stopped (``info = [code, k, law_code]``), worded by
    :data:`FAILURE_MESSAGES`."""
    k = int(info[1])
    status = int(info[0])
    label = str(getattr(controller, "name", controller))
    if status == NOT_FINITE:
        i = int(info[2])
        what, value = ((f"the torque tau_{i + 1}", out[3][k, i]) if i < 4 else
                       (f"the signal {names[i - 4]!r}", out[6][k, i - 4]))
        raise UnstableError(failure_message(status, label, what=what).format(t=k * dt, k=k, value=value))
    if status == JOINT_LIMIT:
        d3, v3 = float(out[0][k, 2]), float(out[1][k, 2])
        end = "d3_max" if d3 > plant.d3_max else "d3_min"
        raise UnstableError(failure_message(status, label, end=end).format(
            t=k * dt, k=k, d3=d3, v3=v3, d3_min=plant.d3_min, d3_max=plant.d3_max))
    cause = failure_cause(status, int(info[2]), getattr(controller, "explain", None), limit)
    raise UnstableError(failure_message(status, label, cause=cause).format(t=k * dt, k=k))
