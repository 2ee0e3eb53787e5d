"""Kinematics of the SCARA arm (chapter 1): DH table, link frames, ``T_e^b``, ``x_e``, ``J_A``,
``Jdot_A``, closed-form inverse kinematics and reachability.

Each formula of the planar part is written once, as a small compiled building block taking and returning
scalars (``planar_trig``, ``planar_position``, ``planar_jacobian_at``, ``planar_jacobian``, ``planar_det``,
``planar_jacobian_dot``, ``elbow_cosine``), which the compiler inlines into every loop that calls it. The array kernels
(``*_kernel``) write into arrays passed by the caller; the later chapters' compiled loops (CLIK, simulation)
call the building blocks or these kernels directly, with the arm's lengths as a :class:`Geometry` record or
as numbers. The public functions check their inputs and wrap the kernels.

Configurations and the stroke: the functions that take a configuration ``q`` (:func:`pose`, :func:`fkine`,
:func:`jacobian`, ...) are formulas and accept any finite ``d3``, also outside the quill's stroke
``p.d3_min <= d3 <= p.d3_max`` (:class:`~scara.ScaraParams`); their revolute angles must stay within
``MAX_ANGLE = 1e6`` rad (:data:`scara.errors.MAX_ANGLE`), beyond which ``sin`` and ``cos`` lose all precision, and
a result that overflows (a ``qd`` of 1e300 rad/s in :func:`jacobian_dot`) raises
:class:`~scara.errors.NonFiniteError` naming the input. The inverse kinematics and the reachability tests
(:func:`ikine`, :func:`is_reachable`, :func:`check_reachable`) honour the stroke: a point needing
``d3 = d0 - p_z`` outside ``[d3_min, d3_max]`` is unreachable.
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ._compile import kernel
from .errors import (ScaraError, UnreachableError, UnstableError, as_array, check_angles, check_finite_result,
                     is_bool, _numbers)
from .params import ScaraParams

__all__ = [
    "base_transform",
    "dh_table",
    "dh_matrix",
    "link_frames",
    "fkine",
    "pose",
    "jacobian",
    "jacobian_dot",
    "ikine",
    "is_reachable",
    "check_reachable",
    "pose_kernel",
    "pose_of",
    "jacobian_kernel",
    "jacobian_dot_kernel",
    "ikine_kernel",
    "tool_motion_kernel",
    "reach_kernel",
    "REACH_TOL",
    "Geometry",
    "geometry",
    "planar_trig",
    "planar_position",
    "planar_jacobian",
    "planar_jacobian_at",
    "planar_det",
    "planar_jacobian_dot",
    "elbow_cosine",
    "SINGULAR_SIN",
    "check_regular",
]

#: ``|sin theta2|`` at or below which a configuration counts as singular for the solves that need ``J_A^-1``
#: (``det J_A = a1 a2 sin theta2``, (1.9)): 1e-12 leaves ``J_A^-1`` with entries up to about 1e12 times the arm's
#: scale, beyond which the solve keeps no significant digit of a velocity
SINGULAR_SIN = 1e-12

#: How far outside the workspace a point may lie and still count as reachable (rounding at the rim): ``cos theta2``
#: of (1.9) may exceed ``[-1, 1]`` by it, and ``d3 = d0 - p_z`` the stroke by it (m). The one tolerance of
#: :func:`ikine`, :func:`is_reachable` and :func:`check_reachable` (see :func:`reach_kernel`).
REACH_TOL = 1e-12



def _elbow_sign(elbow) -> int:
    """``elbow`` checked to be +1 or -1 (an int or a float equal to it; not a bool, a string or an array)."""
    ok = (not is_bool(elbow) and isinstance(elbow, (int, float, np.integer, np.floating))
          and elbow in (1, -1))
    if not ok:
        raise ScaraError(f"elbow = {elbow!r} is not allowed: use +1 (sin theta2 >= 0) or -1 (sin theta2 <= 0)")
    return int(elbow)


def base_transform(p: ScaraParams | None = None) -> np.ndarray:
    """``A_0^b`` (1.1): frame 0 hangs at height ``d0`` with its z axis pointing down.

    >>> base_transform()[2].tolist()
    [0.0, 0.0, -1.0, 1.0]
    """
    p = ScaraParams.resolve(p)
    return np.array([[1.0, 0, 0, 0], [0, -1.0, 0, 0], [0, 0, -1.0, p.d0], [0, 0, 0, 1.0]])


# --------------------------------------------------------------------------------------------------
# the arm's geometry as one record for compiled code
# --------------------------------------------------------------------------------------------------
#: The lengths the kinematics needs (m), as compiled loops read them: ``a1``, ``a2`` and the height ``d0``.
Geometry = namedtuple("Geometry", "a1 a2 d0")


def geometry(p: ScaraParams | None = None) -> Geometry:
    """The :class:`Geometry` record of ``p`` (default the robot of the book's introduction)."""
    p = ScaraParams.resolve(p)
    return Geometry(float(p.a1), float(p.a2), float(p.d0))


# --------------------------------------------------------------------------------------------------
# planar building blocks: scalars in, tuples out, inlined by the compiler into every loop that calls them
# --------------------------------------------------------------------------------------------------
@kernel
def planar_trig(t1, t2):
    """``(s1, c1, s12, c12)``: the sines and cosines of ``theta1`` and ``theta1 + theta2``, the step's only
    trigonometric calls."""
    t12 = t1 + t2
    return math.sin(t1), math.cos(t1), math.sin(t12), math.cos(t12)


@kernel
def planar_position(sc, a1, a2):
    """``(p_x, p_y) = (a1 c1 + a2 c12, -(a1 s1 + a2 s12))`` of the direct kinematics (1.5), from
    ``sc = planar_trig(theta1, theta2)``."""
    s1, c1, s12, c12 = sc
    return a1 * c1 + a2 * c12, -(a1 * s1 + a2 * s12)


@kernel
def planar_jacobian_at(px, py, s12, c12, a2):
    """The four non-constant entries ``(J_11, J_12, J_21, J_22)`` of the analytic Jacobian (1.6) written with
    the position (1.5): ``J_11 = p_y``, ``J_12 = -a2 s12``, ``J_21 = -p_x``, ``J_22 = -a2 c12``. The other rows
    are constant: z is ``[0, 0, -1, 0]``, phi is ``[1, 1, 0, 1]``."""
    return py, -a2 * s12, -px, -a2 * c12


@kernel
def planar_jacobian(sc, a1, a2):
    """The entries ``(J_11, J_12, J_21, J_22)`` of (1.6) from ``sc = planar_trig(theta1, theta2)``."""
    px, py = planar_position(sc, a1, a2)
    return planar_jacobian_at(px, py, sc[2], sc[3], a2)


@kernel
def planar_det(J):
    """The determinant ``J_11 J_22 - J_12 J_21 = -a1 a2 sin theta2`` of the horizontal block of (1.6), from the
    entries ``J = (J_11, J_12, J_21, J_22)``; ``det J_A`` (1.7) is its opposite."""
    return J[0] * J[3] - J[1] * J[2]


@kernel
def planar_jacobian_dot(sc, a1, a2, w1, w12):
    """The four non-constant entries of ``Jdot_A`` (chapter 4), differentiating (1.6) entry by entry with
    ``w1 = qd1`` and ``w12 = qd1 + qd2``: ``d/dt J11 = -(a1 c1 w1 + a2 c12 w12)``, ``d/dt J12 = -a2 c12 w12``,
    ``d/dt J21 = a1 s1 w1 + a2 s12 w12``, ``d/dt J22 = a2 s12 w12``; every other entry is constant."""
    s1, c1, s12, c12 = sc
    return -(a1 * c1 * w1 + a2 * c12 * w12), -a2 * c12 * w12, a1 * s1 * w1 + a2 * s12 * w12, a2 * s12 * w12


@kernel
def elbow_cosine(px, py, a1, a2):
    """``cos theta2 = (p_x^2 + p_y^2 - a1^2 - a2^2) / (2 a1 a2)`` of the inverse kinematics (1.9)
    (numbers or arrays)."""
    return (px * px + py * py - a1 * a1 - a2 * a2) / (2.0 * a1 * a2)


# --------------------------------------------------------------------------------------------------
# compiled kernels on arrays
# --------------------------------------------------------------------------------------------------
@kernel
def pose_kernel(q, a1, a2, d0, out):
    """``x_e = k(q) = [p_x, p_y, p_z, phi]`` (1.5) written into ``out`` (4,)."""
    out[0], out[1], out[2], out[3] = pose_of(q[0], q[1], q[2], q[3], a1, a2, d0)


@kernel
def pose_of(t1, t2, d3, t4, a1, a2, d0):
    """``(p_x, p_y, p_z, phi) = k(q)`` (1.5) of the joint values as scalars: the direct kinematics, written once
    (a loop over a run's samples calls it on ``q[k, i]``, with no view of a row)."""
    px, py = planar_position(planar_trig(t1, t2), a1, a2)
    return px, py, d0 - d3, t1 + t2 + t4


@kernel
def _zero(out):
    """Set every entry of ``out`` (4, 4) to 0."""
    for i in range(4):
        for j in range(4):
            out[i, j] = 0.0


@kernel
def jacobian_kernel(q, a1, a2, out):
    """Analytic Jacobian ``J_A = dx_e/dq`` (1.6) written into ``out`` (4, 4)."""
    _zero(out)
    out[0, 0], out[0, 1], out[1, 0], out[1, 1] = planar_jacobian(planar_trig(q[0], q[1]), a1, a2)
    out[2, 2] = -1.0
    out[3, 0] = 1.0
    out[3, 1] = 1.0
    out[3, 3] = 1.0


@kernel
def jacobian_dot_kernel(q, qd, a1, a2, out):
    """Time derivative ``Jdot_A(q, qd)`` of the analytic Jacobian (see :func:`planar_jacobian_dot`), written
    into ``out`` (4, 4)."""
    _zero(out)
    out[0, 0], out[0, 1], out[1, 0], out[1, 1] = planar_jacobian_dot(planar_trig(q[0], q[1]), a1, a2, qd[0],
                                                                      qd[0] + qd[1])


#: :func:`ikine_kernel`'s return codes
IK_OK = 0
IK_OUTSIDE_ANNULUS = 1
IK_OUTSIDE_STROKE = 2


@kernel
def reach_kernel(x, a1, a2, d0, d3_min, d3_max):
    """The one reachability rule, ``(code, c2)``: :data:`IK_OK` when the point ``x`` (its ``p_x, p_y, p_z``) lies
    in the annulus, ``|c2| <= 1 + REACH_TOL`` with ``c2 = cos theta2`` of (1.9) (:func:`elbow_cosine`), and needs
    ``d3 = d0 - p_z`` within the stroke ``[d3_min, d3_max]`` widened by :data:`REACH_TOL`;
    :data:`IK_OUTSIDE_ANNULUS` or :data:`IK_OUTSIDE_STROKE` otherwise (also for a NaN coordinate)."""
    c2 = elbow_cosine(x[0], -x[1], a1, a2)
    if not (-1.0 - REACH_TOL <= c2 <= 1.0 + REACH_TOL):
        return IK_OUTSIDE_ANNULUS, c2
    d3 = d0 - x[2]
    if not (d3_min - REACH_TOL <= d3 <= d3_max + REACH_TOL):
        return IK_OUTSIDE_STROKE, c2
    return IK_OK, c2


@kernel
def ikine_kernel(x, a1, a2, d0, d3_min, d3_max, elbow, out):
    """Closed-form inverse kinematics (1.8)-(1.10) written into ``out`` (4,).

    With ``y' = -p_y`` the horizontal problem is the planar two-link arm:
    ``c2 = (p_x^2 + y'^2 - a1^2 - a2^2) / (2 a1 a2)`` (:func:`elbow_cosine`), ``s2 = elbow sqrt(1 - c2^2)``,
    ``theta2 = atan2(s2, c2)``, ``theta1 = atan2(y', p_x) - atan2(a2 s2, a1 + a2 c2)``,
    ``d3 = d0 - p_z``, ``theta4 = phi - theta1 - theta2``.
    Returns the code of :func:`reach_kernel` (:data:`IK_OK`, :data:`IK_OUTSIDE_ANNULUS` or
    :data:`IK_OUTSIDE_STROKE`, ``d3`` outside the stroke ``[d3_min, d3_max]`` of :class:`~scara.ScaraParams`). The
    caller checks the code; ``out`` is left unchanged on failure.
    """
    px = x[0]
    py = -x[1]
    code, c2 = reach_kernel(x, a1, a2, d0, d3_min, d3_max)
    if code != IK_OK:
        return code
    d3 = d0 - x[2]
    if c2 > 1.0:
        c2 = 1.0
    elif c2 < -1.0:
        c2 = -1.0
    s2 = elbow * math.sqrt(1.0 - c2 * c2)
    t2 = math.atan2(s2, c2)
    t1 = math.atan2(py, px) - math.atan2(a2 * s2, a1 + a2 * c2)
    if t1 > math.pi:
        t1 -= 2.0 * math.pi
    elif t1 <= -math.pi:
        t1 += 2.0 * math.pi
    out[0] = t1
    out[1] = t2
    out[2] = d3
    out[3] = x[3] - t1 - t2
    return IK_OK


@kernel
def _reach_batch_kernel(pts, a1, a2, d0, d3_min, d3_max, out):
    """``out[k] = reach_kernel(pts[k], ...)[0]`` for every row of ``pts`` (N, >= 3)."""
    for k in range(pts.shape[0]):
        out[k] = reach_kernel(pts[k], a1, a2, d0, d3_min, d3_max)[0]


@kernel
def tool_motion_kernel(q, qd, qdd, a1, a2, d0, out):
    """The tool's motion ``[x, xd, xdd]`` (N, 12) of a joint motion ``q, qd, qdd`` (N, 4) each: ``x = k(q)``
    (1.5), ``xd = J_A qd`` (1.6) and ``xdd = J_A qdd + Jdot_A qd`` (4.17), written into ``out`` (N, 12)."""
    J = np.empty((4, 4))
    Jd = np.empty((4, 4))
    for k in range(q.shape[0]):
        pose_kernel(q[k], a1, a2, d0, out[k, 0:4])
        jacobian_kernel(q[k], a1, a2, J)
        jacobian_dot_kernel(q[k], qd[k], a1, a2, Jd)
        for i in range(4):
            v = 0.0
            a = 0.0
            for j in range(4):
                v += J[i, j] * qd[k, j]
                a += J[i, j] * qdd[k, j] + Jd[i, j] * qd[k, j]
            out[k, 4 + i] = v
            out[k, 8 + i] = a


@kernel
def pose_batch_kernel(q, a1, a2, d0, out):
    """:func:`pose_kernel` for every row of ``q`` (N, 4), written into ``out`` (N, 4)."""
    for k in range(q.shape[0]):
        pose_kernel(q[k], a1, a2, d0, out[k])


# --------------------------------------------------------------------------------------------------
# public functions
# --------------------------------------------------------------------------------------------------
def dh_table(q=None, p: ScaraParams | None = None) -> np.ndarray:
    """The DH table (1.2) as rows ``(a_i, alpha_i, d_i, theta_i)``, shape (4, 4).

    With ``q`` the joint variables are filled in; without it they are zero.
    """
    p = ScaraParams.resolve(p)
    q = np.zeros(4) if q is None else check_angles(as_array(q, "q", (4,)))
    return np.array([
        [p.a1, 0.0, 0.0, q[0]],
        [p.a2, 0.0, 0.0, q[1]],
        [0.0, 0.0, q[2], 0.0],
        [0.0, 0.0, 0.0, q[3]],
    ])


def dh_matrix(a: float, alpha: float, d: float, theta: float) -> np.ndarray:
    """Homogeneous transform ``A_i^{i-1}`` of one DH row (Siciliano et al., eq. 2.52), shape (4, 4)."""
    a, alpha, d, theta = (float(v) for v in as_array([a, alpha, d, theta], "DH row (a, alpha, d, theta)", (4,)))
    check_angles(np.array([alpha, theta, 0.0, 0.0]), "DH angles (alpha, theta)", columns=(0, 1))
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([
        [ct, -st * ca, st * sa, a * ct],
        [st, ct * ca, -ct * sa, a * st],
        [0.0, sa, ca, d],
        [0.0, 0.0, 0.0, 1.0],
    ])


def link_frames(q, p: ScaraParams | None = None) -> np.ndarray:
    """Every frame of the arm in the base frame, for drawing: ``[A_0^b, T_1^b, T_2^b, T_3^b, T_4^b, T_e^b]``.

    Computed as the running product of the DH matrices of :func:`dh_table`, shape (6, 4, 4).
    """
    p = ScaraParams.resolve(p)
    q = check_angles(as_array(q, "q", (4,)))
    frames = [base_transform(p)]
    for row in dh_table(q, p):
        frames.append(frames[-1] @ dh_matrix(*row))
    frames.append(frames[-1].copy())  # A_e^4 = I
    return np.array(frames)


def pose(q, p: ScaraParams | None = None) -> np.ndarray:
    """Operational vector ``x_e = [p_x, p_y, p_z, phi]`` (1.5).

    ``q`` has shape (4,) or (N, 4); the result has the same shape. Units m and rad.

    >>> pose([0.0, 0.0, 0.5, 0.0])
    array([ 1. , -0. ,  0.5,  0. ])
    """
    p = ScaraParams.resolve(p)
    q = check_angles(as_array(q, "q", (4,), allow_batch=True))
    if q.ndim == 1:
        out = np.empty(4)
        pose_kernel(q, p.a1, p.a2, p.d0, out)
    else:
        out = np.empty_like(q)
        pose_batch_kernel(q, p.a1, p.a2, p.d0, out)
    return check_finite_result(out, "pose x_e", q=q)


def fkine(q, p: ScaraParams | None = None) -> np.ndarray:
    """Direct kinematics ``T_e^b(q)`` (1.4) in closed form, shape (4, 4).

    ``R_e^b = [[c, -s, 0], [-s, -c, 0], [0, 0, -1]]`` with ``c, s = cos phi, sin phi`` and the position of
    :func:`pose`.
    """
    x = pose(as_array(q, "q", (4,)), p)
    c, s = math.cos(x[3]), math.sin(x[3])
    return np.array([[c, -s, 0.0, x[0]], [-s, -c, 0.0, x[1]], [0.0, 0.0, -1.0, x[2]], [0.0, 0.0, 0.0, 1.0]])


def jacobian(q, p: ScaraParams | None = None) -> np.ndarray:
    """Analytic Jacobian ``J_A(q) = dx_e/dq`` (1.6), shape (4, 4).

    ``det J_A = a1 a2 sin(theta2)``: singular with the arm stretched or folded.
    """
    p = ScaraParams.resolve(p)
    q = check_angles(as_array(q, "q", (4,)))
    out = np.empty((4, 4))
    jacobian_kernel(q, p.a1, p.a2, out)
    return out


def jacobian_dot(q, qd, p: ScaraParams | None = None) -> np.ndarray:
    """``Jdot_A(q, qd)``, the time derivative of :func:`jacobian` along a motion (4.17), shape (4, 4)."""
    p = ScaraParams.resolve(p)
    q = check_angles(as_array(q, "q", (4,)))
    qd = as_array(qd, "qd", (4,))
    out = np.empty((4, 4))
    jacobian_dot_kernel(q, qd, p.a1, p.a2, out)
    return check_finite_result(out, "Jdot_A(q, qd)", qd=qd)


def _unreachable_message(x, code, p, label="point"):
    r = math.hypot(x[0], x[1])
    if code == IK_OUTSIDE_ANNULUS:
        return (f"{label} x = {np.array2string(np.asarray(x), precision=4)} is unreachable: its distance from the "
                f"joint-1 axis r = {r:.10g} m is outside the annulus |a1 - a2| = {p.r_min:g} m <= r <= "
                f"a1 + a2 = {p.r_max:g} m")
    d3 = p.d0 - x[2]
    return (f"{label} x = {np.array2string(np.asarray(x), precision=4)} is unreachable: p_z = {x[2]:.10g} m needs "
            f"d3 = d0 - p_z = {d3:.10g} m, outside the stroke d3_min = {p.d3_min:g} m <= d3 <= "
            f"d3_max = {p.d3_max:g} m")


@kernel
def ikine_batch_kernel(xs, a1, a2, d0, d3_min, d3_max, elbow, out):
    """:func:`ikine_kernel` for every row of ``xs`` (N, 4), written into ``out`` (N, 4), in one compiled loop.
    Returns -1 when every row is reachable, else the index of the first row that is not."""
    for k in range(xs.shape[0]):
        if ikine_kernel(xs[k], a1, a2, d0, d3_min, d3_max, elbow, out[k]) != IK_OK:
            return k
    return -1


def ikine(x, p: ScaraParams | None = None, elbow: int = +1) -> np.ndarray:
    """Closed-form inverse kinematics: the joint vector ``q`` with ``pose(q) == x`` (1.8)-(1.10).

    Parameters
    ----------
    x : array (4,) or (N, 4)
        ``[p_x, p_y, p_z, phi]`` in m and rad.
    elbow : +1 or -1
        Sign of ``sin theta2``: ``+1`` gives ``0 <= theta2 <= pi``, ``-1`` gives ``-pi <= theta2 <= 0``.

    Returns ``q = [theta1, theta2, d3, theta4]`` with ``theta1`` in ``(-pi, pi]``.

    Raises
    ------
    UnreachableError
        The point is outside the annulus ``|a1 - a2| <= r <= a1 + a2`` or needs ``d3 = d0 - p_z`` outside the
        stroke ``[p.d3_min, p.d3_max]`` (for a batch, the message names the first such sample).
    ScaraError
        ``elbow`` is not +1 or -1; ``|phi|`` beyond ``MAX_ANGLE = 1e6`` rad.

    >>> ikine(pose([0.3, -1.2, 0.4, 0.1]), elbow=-1).round(6)
    array([ 0.3, -1.2,  0.4,  0.1])
    """
    p = ScaraParams.resolve(p)
    elbow = _elbow_sign(elbow)
    x = as_array(x, "x", (4,), allow_batch=True)
    batch = x.ndim == 2
    xs = x if batch else x[None, :]
    if not xs.flags.writeable:  # a trajectory's own poses: numba would compile the kernels once more for them
        xs = xs.copy()
    out = np.empty_like(xs)
    check_angles(x, "x", columns=(3,))
    k = ikine_batch_kernel(xs, p.a1, p.a2, p.d0, p.d3_min, p.d3_max, float(elbow), out)
    if k >= 0:
        code = ikine_kernel(xs[k], p.a1, p.a2, p.d0, p.d3_min, p.d3_max, float(elbow), np.empty(4))
        raise UnreachableError(_unreachable_message(xs[k], code, p, f"sample {k}: point" if batch else "point"))
    check_finite_result(out, "inverse kinematics q", x=x)
    return out if batch else out[0]


def is_reachable(points, p: ScaraParams | None = None) -> np.ndarray:
    """Boolean mask: which points (shape (3,)/(4,) or (N, 3)/(N, 4), positions first) the arm can reach: inside
    the annulus ``|a1 - a2| <= r <= a1 + a2`` with ``d3 = d0 - p_z`` in the stroke ``[p.d3_min, p.d3_max]``, by
    the rule :func:`ikine` applies (:func:`reach_kernel`, tolerance :data:`REACH_TOL`), so that a point is
    reachable exactly when :func:`ikine` solves it. A point holding NaN or inf is not reachable (False).

    >>> is_reachable([[1.0, 0.0, 0.5], [1.0 + 1e-9, 0.0, 0.5]]).tolist()
    [True, False]
    """
    p = ScaraParams.resolve(p)
    pts = _numbers(points, "points must be an array of numbers")
    if pts.ndim not in (1, 2) or pts.shape[-1] not in (3, 4):
        raise ScaraError(f"points must have shape (3,), (4,), (N, 3) or (N, 4), got {pts.shape}")
    rows = np.ascontiguousarray(pts.reshape(-1, pts.shape[-1]))
    codes = np.empty(len(rows), dtype=np.int64)
    _reach_batch_kernel(rows, p.a1, p.a2, p.d0, p.d3_min, p.d3_max, codes)
    ok = (codes == IK_OK) & np.all(np.isfinite(rows), axis=-1)
    return ok.reshape(pts.shape[:-1])


def check_reachable(point, p: ScaraParams | None = None, label: str = "point") -> None:
    """Raise :class:`UnreachableError` naming the point and the limit it breaks if the arm cannot reach it."""
    p = ScaraParams.resolve(p)
    try:
        three = np.shape(point) == (3,)
    except ValueError:  # a ragged sequence: as_array names it
        three = False
    x = as_array(point, label, (3,)) if three else as_array(point, label, (4,))
    code = reach_kernel(x, p.a1, p.a2, p.d0, p.d3_min, p.d3_max)[0]
    if code != IK_OK:
        raise UnreachableError(_unreachable_message(x, code, p, label))


def check_regular(q, p: ScaraParams | None = None, what: str = "the start configuration") -> np.ndarray:
    """Return ``q`` after checking that ``J_A(q)`` can be inverted: the one rule for "is this configuration
    singular?" wherever the package needs ``J_A^-1`` (a start velocity ``qd0 = J_A^-1 xd_d(0)``, a CLIK start, the
    joint reference of the closed-form inverse kinematics). ``det J_A = a1 a2 sin theta2`` (1.9), so ``q`` is
    refused when ``|sin theta2| <= SINGULAR_SIN``, with an :class:`~scara.UnstableError` naming ``what``, ``q``
    and ``theta2``. ``q`` has shape (4,) or (N, 4) (a series: the message names its first singular sample); the
    result is a copy.

    >>> check_regular([0.0, 1.0, 0.5, 0.0]).tolist()
    [0.0, 1.0, 0.5, 0.0]
    """
    ScaraParams.resolve(p)
    q = as_array(q, "q", (4,), allow_batch=True)
    if q.ndim == 1:
        k, qk = -1, q
        singular = abs(math.sin(q[1])) <= SINGULAR_SIN
    else:
        bad = np.abs(np.sin(q[:, 1])) <= SINGULAR_SIN
        singular = bool(bad.any())
        k = int(np.argmax(bad))
        qk = q[k]
    if singular:
        where = what if k < 0 else f"{what} at sample {k}:"
        hint = ("give the start speeds qd0 explicitly, or start away from theta2 = 0 and pi" if k < 0 else
                "keep the path off the circles r = |a1 - a2| and r = a1 + a2, where theta2 = 0 or pi")
        raise UnstableError(f"{where} q = {np.round(qk, 6).tolist()} is singular (theta2 = {qk[1]:.6g} rad; "
                            f"det J_A = a1 a2 sin theta2 vanishes): J_A cannot be inverted there; {hint}")
    return q.copy()
