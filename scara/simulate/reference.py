"""The references a controller receives (chapter 5): the joint reference ``[q_d, qd_d, qdd_d]`` (from
``clik2``, the closed-form inverse kinematics or a given array) and the operational one ``[x_d, xd_d, xdd_d]``."""
from __future__ import annotations

import warnings

import numpy as np

from .._compile import kernel
from ..errors import ScaraError, ShapeError, as_array, check_positive
from ..kinematics import _params, ikine, jacobian, jacobian_dot_kernel, jacobian_kernel, pose, pose_kernel
from ..params import ScaraParams

__all__ = ["ikine_reference", "joint_setpoint"]

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
        from ..clik import clik2  # noqa: PLC0415 - optional until chapter 4 exists
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


def _operational_from_joint(ref, p):
    out = np.empty((len(ref), 12))
    _operational_kernel(np.ascontiguousarray(ref), p.a1, p.a2, p.d0, out)
    return out


def _references(kind, traj, joint_reference, duration, dt, p):
    """The references of a run of a controller of ``reference_kind`` ``kind`` (see :func:`scara.simulate`):
    ``(ref, jref, x_d, xop, n)`` with ``ref`` (n, 12) what the law receives, ``jref`` the joint reference (or
    None), ``x_d`` (n, 4) the desired pose (or None for an open-loop run), ``xop`` the operational reference
    (or None) and ``n`` the number of samples."""
    jref = None
    if joint_reference is not None:
        jref = np.ascontiguousarray(_joint_reference_array(joint_reference))
    elif kind == "joint":
        if traj is None:
            raise ScaraError("a joint-space controller needs traj or joint_reference")
        jref = np.ascontiguousarray(_clik2_reference(traj, p))
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
        xop = _operational_from_joint(jref, p) if kind == "operational" else None
        x_d = pose(jref[:, :4], p)
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
    return ref, jref, x_d, xop, n


def _start_state(q0, qd0, jref, xop, traj, p, elbow):
    """The initial ``(q0, qd0)`` of a run: the given ones, or the reference's first sample (joint reference),
    ``traj.q0``, or the inverse kinematics of the operational reference's first sample with ``elbow``."""
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
    if qd0 is None:
        if jref is not None:
            qd0 = jref[0, 4:8]
        elif xop is not None:
            qd0 = np.linalg.solve(jacobian(q0, p), xop[0, 4:8])
        else:
            qd0 = np.zeros(4)
    qd0 = np.ascontiguousarray(as_array(qd0, "qd0", (4,)), dtype=float).copy()
    return q0, qd0
