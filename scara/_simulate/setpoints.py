"""The references a controller receives (chapter 5): the joint reference ``[q_d, qd_d, qdd_d]`` (from
``clik2``, the closed-form inverse kinematics or a given array) and the operational one ``[x_d, xd_d, xdd_d]``.

A trajectory carries the arm it was planned for (``traj.params``) and its elbow (``traj.elbow``): its joint
reference is computed for that arm and that elbow, and a plant whose lengths ``a1, a2, d0`` differ from the
trajectory's is refused (the path would be another one on that arm)."""
from __future__ import annotations

import warnings

import numpy as np

from .._compile import kernel
from ..errors import ScaraError, ShapeError, UnreachableError, as_array
from ..kinematics import (_elbow_sign, check_regular, ikine, jacobian, jacobian_dot_kernel, jacobian_kernel, pose,
                          tool_motion_kernel)
from ..params import ScaraParams
from .interface import MAX_SAMPLES, _sample_count

__all__ = ["ikine_reference", "joint_setpoint"]

#: the lengths a trajectory and the arm that follows it must share (m)
_GEOMETRY = ("a1", "a2", "d0")


def _arm_of(traj, p=None) -> ScaraParams:
    """The arm a trajectory's joint reference is computed for: ``p`` (default the trajectory's own arm
    ``traj.params``, else the course's robot). A ``p`` whose lengths ``a1, a2, d0`` differ from those ``traj``
    was planned for raises :class:`~scara.ScaraError` naming both."""
    planned = getattr(traj, "params", None)
    if not isinstance(planned, ScaraParams):
        return ScaraParams.resolve(p)
    if p is None:
        return planned
    p = ScaraParams.resolve(p)
    if any(getattr(p, k) != getattr(planned, k) for k in _GEOMETRY):
        lengths = lambda q: ", ".join(f"{k} = {getattr(q, k):g}" for k in _GEOMETRY)  # noqa: E731
        raise ScaraError(f"the trajectory was planned for an arm with {lengths(planned)} m, but the arm given has "
                         f"{lengths(p)} m: its joint reference would follow another path; plan the trajectory for "
                         f"this arm (plan_path(..., p=...)) or give the arm it was planned for")
    return p


def _elbow_of(traj, elbow=None) -> int:
    """``elbow`` (+1 or -1), by default the trajectory's own ``traj.elbow`` (else -1, the course's elbow)."""
    if elbow is None:
        elbow = getattr(traj, "elbow", None)
    return -1 if elbow is None else _elbow_sign(elbow)


def ikine_reference(traj, p: ScaraParams | None = None, elbow: int | None = None) -> np.ndarray:
    """Joint reference ``[q, qd, qdd]`` (N, 12) from the closed-form inverse kinematics of a trajectory.

    ``q = ikine(x_d)`` (angles unwrapped), ``qd = J_A^-1 xd_d``, ``qdd = J_A^-1 (xdd_d - Jdot_A qd)``: the exact
    joint motion that realises ``x_d`` (no CLIK error), for the arm ``p`` (default the trajectory's own,
    ``traj.params``; another arm's lengths are refused) and the elbow ``elbow`` (default the trajectory's,
    ``traj.elbow``, else -1). Raises :class:`~scara.UnreachableError` for an unreachable sample and
    :class:`~scara.UnstableError` at a singular configuration (:func:`~scara.kinematics.check_regular`).
    """
    p = _arm_of(traj, p)
    elbow = _elbow_of(traj, elbow)
    x, xd, xdd = (as_array(_traj_field(traj, f), f"traj.{f}", (4,), allow_batch=True) for f in ("x", "xd", "xdd"))
    if not (x.ndim == 2 and x.shape == xd.shape == xdd.shape):
        raise ShapeError(f"traj.x, traj.xd, traj.xdd must all have shape (N, 4), got {x.shape}, {xd.shape}, "
                         f"{xdd.shape}")
    q = ikine(x, p, elbow=elbow)
    q[:, 0] = np.unwrap(q[:, 0])
    q[:, 3] = x[:, 3] - q[:, 0] - q[:, 1]
    # every sample at once: the same kernels and the same LAPACK calls as sample by sample
    check_regular(q, p, what="the reference")
    J = np.empty((len(q), 4, 4))
    _jacobian_rows(q, p.a1, p.a2, J)
    qd = np.linalg.solve(J, xd[:, :, None])[:, :, 0]
    Jd = np.empty_like(J)
    _jacobian_dot_rows(q, qd, p.a1, p.a2, Jd)
    qdd = np.linalg.solve(J, (xdd - (Jd @ qd[:, :, None])[:, :, 0])[:, :, None])[:, :, 0]
    return np.hstack([q, qd, qdd])


def _traj_field(traj, name):
    """``traj.<name>``, or :class:`~scara.ScaraError` naming what a trajectory must have."""
    if not hasattr(traj, name):
        raise ScaraError(f"traj = {type(traj).__name__} has no attribute {name!r}: a trajectory needs t, x, xd, xdd "
                         f"(N, 4) and dt (see scara.plan_path)")
    return getattr(traj, name)


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
    """A constant joint reference ``[q_d, 0, 0]`` of ``duration / dt + 1`` samples, shape (N, 12).

    ``duration`` must be a whole number of periods ``dt`` (``joint_setpoint(q, 1.0, dt=0.3)`` raises
    :class:`~scara.ScaraError` naming 0.9 s and 1.2 s rather than giving 0.9 s), with at most
    :data:`~scara._simulate.interface.MAX_SAMPLES` samples. Like any joint reference array it carries no time:
    :func:`scara.simulate` takes its rows at its own ``dt``, so pass the same ``dt`` to both."""
    q_d = as_array(q_d, "q_d", (4,))
    n = _sample_count(duration, dt) + 1
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
    """The joint reference ``clik2`` gives along ``traj`` for the arm it was planned for (``traj.params``, else
    the plant ``p``; a plant of other lengths is refused, see :func:`_arm_of`), or, without chapter 4,
    :func:`ikine_reference`."""
    p = _arm_of(traj, p)
    planned = getattr(traj, "params", None)
    arm = planned if isinstance(planned, ScaraParams) else p   # clik2 holds a trajectory to the arm of its plan
    try:
        from .._clik import clik2  # noqa: PLC0415 - optional until chapter 4 exists
    except ImportError:
        warnings.warn("scara._clik.clik2 is not available: joint references come from the closed-form inverse "
                      "kinematics of the trajectory instead", RuntimeWarning, stacklevel=3)
        return ikine_reference(traj, p)
    return _joint_reference_array(clik2(traj, p=arm))


def _operational_from_joint(ref, p):
    """``[x, xd, xdd]`` (N, 12) of a joint reference ``[q, qd, qdd]`` (:func:`~scara.kinematics.tool_motion_kernel`)."""
    ref = np.ascontiguousarray(ref)
    out = np.empty((len(ref), 12))
    tool_motion_kernel(ref[:, 0:4], ref[:, 4:8], ref[:, 8:12], p.a1, p.a2, p.d0, out)
    return out


def _check_time_base(obj, name, dt):
    """Check that the samples of ``obj`` (a trajectory, or a joint reference object such as a ``clik2`` result)
    are the run's samples: its ``t`` (when it has one; an array carries no time and is taken at ``dt``) must be
    uniform with spacing ``dt`` (within 1e-6 of a period). Raises :class:`~scara.ScaraError` naming both
    spacings."""
    t = getattr(obj, "t", None)
    if t is None or isinstance(obj, (np.ndarray, tuple, list)):
        return
    try:
        t = np.asarray(t, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ShapeError(f"{name}.t must be a vector of sample times (s), got {t!r}") from exc
    if t.ndim != 1:
        raise ShapeError(f"{name}.t must be a vector of sample times (N,), got shape {t.shape}")
    t = as_array(t, f"{name}.t", (len(t),))
    if len(t) < 2:
        return
    step = np.diff(t)
    lo, hi = float(step.min()), float(step.max())
    tol = 1e-6 * dt
    if hi - lo > tol:
        k = int(np.argmax(np.abs(step - step[0]) > tol))
        raise ScaraError(f"{name}.t is not uniform: its spacing ranges from {lo:g} s to {hi:g} s (first change at "
                         f"sample {k}); the engine samples every dt = {dt:g} s: resample the reference")
    if abs(lo - dt) > tol:
        raise ScaraError(f"{name}.t is sampled every {lo:g} s but the run's dt = {dt:g} s; pass dt={lo:g} (or give "
                         f"the reference a matching dt attribute) or resample it")


def _references(kind, traj, joint_reference, duration, dt, p):
    """The references of a run of a controller of ``reference_kind`` ``kind`` (see :func:`scara.simulate`):
    ``(ref, jref, x_d, xop, n)`` with ``ref`` (n, 12) what the law receives, ``jref`` the joint reference (or
    None), ``x_d`` (n, 4) the desired pose (or None for an open-loop run), ``xop`` the operational reference
    (or None) and ``n`` the number of samples."""
    jref = None
    if duration is not None and (traj is not None or joint_reference is not None):
        given = "traj" if traj is not None else "joint_reference"
        raise ScaraError(f"duration = {duration!r} applies to an open-loop run without reference only, but {given} is "
                         f"given: the run lasts as long as its reference; leave duration out")
    if traj is not None:
        _arm_of(traj, p)
        _check_time_base(traj, "traj", dt)
    if joint_reference is not None:
        _check_time_base(joint_reference, "joint_reference", dt)
        jref = np.array(_joint_reference_array(joint_reference), dtype=float, order="C")  # the run's own copy
    elif kind == "joint":
        if traj is None:
            raise ScaraError("a joint-space controller needs traj or joint_reference")
        jref = np.ascontiguousarray(_clik2_reference(traj, p))
    x_d = None
    xop = None
    if traj is not None:
        x_d = np.array(as_array(_traj_field(traj, "x"), "traj.x", (4,), allow_batch=True))  # the run's own copy
        if x_d.ndim != 2:
            raise ShapeError(f"traj.x must have shape (N, 4), got {x_d.shape}")
        n = len(x_d)
        if kind == "operational" or jref is None:
            xop = np.empty((n, 12))
            xop[:, 0:4] = x_d
            for i, f in ((1, "xd"), (2, "xdd")):
                v = as_array(_traj_field(traj, f), f"traj.{f}", (4,), allow_batch=True)
                if v.shape != x_d.shape:
                    raise ShapeError(f"traj.{f} must have the shape of traj.x {x_d.shape}, got {v.shape}")
                xop[:, 4 * i:4 * i + 4] = v
    elif jref is not None:
        # the operational reference realised by the joint reference (x_d for the error e)
        xop = _operational_from_joint(jref, p) if kind == "operational" else None
        x_d = pose(jref[:, :4], p)
        n = len(jref)
    elif duration is not None:
        n = _sample_count(duration, dt) + 1
    else:
        raise ScaraError("give traj, joint_reference or (for an open-loop run) duration")
    if n > MAX_SAMPLES:
        raise ScaraError(f"the reference has {n} samples, past the limit of {MAX_SAMPLES} samples per run")
    if jref is not None and len(jref) != n:
        raise ShapeError(f"joint_reference has {len(jref)} samples but the trajectory has {n}")
    if kind == "joint":
        ref = jref
    elif kind == "operational":
        ref = np.ascontiguousarray(xop)
    else:
        ref = np.zeros((n, 12))
    return ref, jref, x_d, xop, n


#: The refusal of a start outside the quill's stroke (a template of numbers): the one wording, in
#: :func:`scara.simulate` and in the page programs that start a run.
START_STROKE_MESSAGE = "q0: joint 3 (d3) = {d3:g} m is outside the quill's stroke [{d3_min:g}, {d3_max:g}] m"


@kernel(light=True)
def in_stroke(d3, d3_min, d3_max):
    """Whether the quill's ``d3`` (m) lies in its stroke ``[d3_min, d3_max]`` (a NaN does not): the check of a run's
    start (:func:`_start_state`)."""
    return d3_min <= d3 <= d3_max


def _start_state(q0, qd0, jref, xop, traj, p, elbow=None):
    """The initial ``(q0, qd0)`` of a run: the given ones, or the reference's first sample (joint reference),
    ``traj.q0``, or the inverse kinematics of the operational reference's first sample with ``elbow`` (default the
    trajectory's ``traj.elbow``, else -1)."""
    elbow = _elbow_of(traj, elbow)
    if q0 is None:
        if jref is not None:
            q0 = jref[0, :4]
        elif getattr(traj, "q0", None) is not None:
            q0 = traj.q0
        elif xop is not None:
            q0 = ikine(xop[0, :4], p, elbow=elbow)
        else:
            raise ScaraError("an open-loop run without reference needs q0")
    q0 = np.ascontiguousarray(as_array(q0, "q0", (4,)), dtype=float).copy()
    if not in_stroke(q0[2], p.d3_min, p.d3_max):
        raise UnreachableError(START_STROKE_MESSAGE.format(d3=q0[2], d3_min=p.d3_min, d3_max=p.d3_max))
    if qd0 is None:
        if jref is not None:
            qd0 = jref[0, 4:8]
        elif xop is not None:
            qd0 = _start_velocity(q0, xop[0, 4:8], p)
        else:
            qd0 = np.zeros(4)
    qd0 = np.ascontiguousarray(as_array(qd0, "qd0", (4,)), dtype=float).copy()
    return q0, qd0


def _start_velocity(q0, xd0, p):
    """``qd0 = J_A(q0)^-1 xd0``: the joint speeds that give the reference's first operational velocity; refused
    at (or numerically at) a singular configuration, where no such speeds exist (the one rule,
    :func:`~scara.kinematics.check_regular`, raises :class:`~scara.UnstableError`)."""
    check_regular(q0, p, what="the start configuration q0")
    return np.linalg.solve(jacobian(q0, p), xd0)
