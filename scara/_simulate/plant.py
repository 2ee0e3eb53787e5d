"""The plant of the simulation engine: the arm's joint accelerations ``qdd = B^-1 (tau - C qd - F qd - g)`` (the
model of chapter 5) in scalars, and one RK4 step with the torque held.

``B`` comes from :func:`scara.dynamics.inertia_parts` (the one place it is written); the solve exploits its
structure (a constant, diagonal quill/wrist block), which the tests check against the general Cholesky solve of
:func:`scara.dynamics.forward_dynamics_kernel`.
"""
from __future__ import annotations

import math
from collections import namedtuple

from .._compile import kernel
from ..dynamics import DP_A1, DP_A2, DP_G0, inertia_parts, lumped_parameters
from .interface import OK, SINGULAR_INERTIA

#: The run's constants of the plant (:func:`_plant_constants`), read by name in compiled code.
PlantConstants = namedtuple("PlantConstants", ("S11_0", "S12_0", "S22", "b", "B13", "B14", "u3", "u4", "inv_B33",
                                               "inv_B44", "F1", "F2", "F3", "F4", "m3g", "ok"))


@kernel
def _plant_constants(dp):
    """The constant part of the plant's ``B`` and right-hand side, from the flat array ``dp`` (once per run).

    ``B`` is :func:`~scara.dynamics.inertia_parts`: only ``B11 = B11_0 + 2 b cos theta2`` and
    ``B12 = B12_0 + b cos theta2`` depend on the state; ``B23 = B13``, ``B24 = B14``, ``B34 = 0``, so the
    lower-right block ``D = diag(B33, B44)`` is diagonal. Eliminating ``qdd3``, ``qdd4`` leaves the Schur
    complement ``S = B_12block - c [[1, 1], [1, 1]]``, ``c = B13^2 / B33 + B14^2 / B44``, whose constant parts are
    returned here (see :func:`_plant_acceleration`).

    Returns a :data:`PlantConstants` record with ``u3 = B13 / B33``, ``u4 = B14 / B44``, ``F_i = k_ri^2 F_mi``;
    ``ok`` is 1.0 when ``B33 > 0`` and ``B44 > 0`` (otherwise ``B`` is singular for every ``q`` and the other
    entries are not used).
    """
    lp = lumped_parameters(dp)
    bp = inertia_parts(dp[DP_A1], dp[DP_A2], lp)
    if not (bp.B33 > 0.0 and bp.B44 > 0.0):
        return PlantConstants(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    u3 = bp.B13 / bp.B33
    u4 = bp.B14 / bp.B44
    c = bp.B13 * u3 + bp.B14 * u4
    return PlantConstants(bp.B11_0 - c, bp.B12_0 - c, bp.B22 - c, bp.b, bp.B13, bp.B14, u3, u4, 1.0 / bp.B33,
                          1.0 / bp.B44, lp.F1, lp.F2, lp.F3, lp.F4, lp.m3 * dp[DP_G0], 1.0)


@kernel
def _plant_acceleration(c2, s2, v, t, pc):
    """``qdd = B^-1 (tau - C qd - F qd - g)`` (chapter 5) in scalars: ``((qdd1, qdd2, qdd3, qdd4), code)`` for the
    joint velocities ``v`` and torques ``t`` (4-tuples).

    ``c2, s2`` are ``cos theta2, sin theta2`` (the only configuration ``B`` and ``C`` depend on), ``pc`` the
    record of :func:`_plant_constants`. With ``r = tau - C qd - F qd - g``, the last two rows give
    ``qdd3 = (r3 - B13 s) / B33``, ``qdd4 = (r4 - B14 s) / B44`` with ``s = qdd1 + qdd2``; substituting them in the
    first two rows leaves the 2x2 system ``S [qdd1, qdd2] = [r1, r2] - (B13 r3 / B33 + B14 r4 / B44)``, solved by
    Cramer's rule. ``B`` is positive definite iff ``B33, B44 > 0`` and ``S`` is (``S11 > 0``, ``det S > 0``);
    ``code`` is :data:`OK`, or :data:`SINGULAR_INERTIA` (and zeros) when it is not. Equal to
    :func:`~scara.dynamics.forward_dynamics_kernel`
    (Cholesky) up to round-off, at a fraction of the cost.
    """
    v1, v2, v3, v4 = v
    t1, t2, t3, t4 = t
    b = pc.b
    s22 = pc.S22
    S11 = pc.S11_0 + 2.0 * b * c2
    S12 = pc.S12_0 + b * c2
    det = S11 * s22 - S12 * S12
    if not (pc.ok > 0.0 and S11 > 0.0 and det > 0.0):
        return (0.0, 0.0, 0.0, 0.0), SINGULAR_INERTIA
    h = b * s2
    y3 = (t3 - pc.F3 * v3 + pc.m3g) * pc.inv_B33
    y4 = (t4 - pc.F4 * v4) * pc.inv_B44
    w = pc.B13 * y3 + pc.B14 * y4
    r1 = t1 + h * (v2 * v1 + (v1 + v2) * v2) - pc.F1 * v1 - w
    r2 = t2 - h * v1 * v1 - pc.F2 * v2 - w
    idet = 1.0 / det
    x1 = (s22 * r1 - S12 * r2) * idet
    x2 = (S11 * r2 - S12 * r1) * idet
    s = x1 + x2
    return (x1, x2, y3 - pc.u3 * s, y4 - pc.u4 * s), OK


@kernel
def _stage(th, v, slope, a, step, t, pc):
    """One stage of RK4: the velocities ``u = v + step a`` at ``theta2 = th + step slope`` and their acceleration
    :func:`_plant_acceleration`; returns ``(u, qdd, code)``."""
    u = (v[0] + step * a[0], v[1] + step * a[1], v[2] + step * a[2], v[3] + step * a[3])
    th_s = th + step * slope
    qdd, code = _plant_acceleration(math.cos(th_s), math.sin(th_s), u, t, pc)
    return u, qdd, code


@kernel
def _rk4_step(q, qd, t, pc, h, qdd0):
    """One classical RK4 step of ``h`` seconds with the torque ``t`` (a 4-tuple) held; ``q``, ``qd`` (4,) are
    updated in place and ``qdd0`` (4,) receives the first stage's acceleration (``qdd`` at the start).

    The state is ``(q, qd)`` and its derivative ``(qd, qdd)``; only ``theta2`` enters ``B`` and ``C``, so the
    four stages (:func:`_stage`) carry ``theta2`` and the velocities in scalars, with the run's constants ``pc``
    (:func:`_plant_constants`). Returns :data:`OK`, or :data:`SINGULAR_INERTIA` if ``B`` lost definiteness.
    """
    th = q[1]
    v = (qd[0], qd[1], qd[2], qd[3])
    hh = 0.5 * h
    v, a, c1 = _stage(th, v, 0.0, (0.0, 0.0, 0.0, 0.0), 0.0, t, pc)
    u, b, c2 = _stage(th, v, v[1], a, hh, t, pc)
    w, e, c3 = _stage(th, v, u[1], b, hh, t, pc)
    z, f, c4 = _stage(th, v, w[1], e, h, t, pc)
    qdd0[0] = a[0]
    qdd0[1] = a[1]
    qdd0[2] = a[2]
    qdd0[3] = a[3]
    s = h / 6.0
    q[0] += s * (v[0] + 2.0 * u[0] + 2.0 * w[0] + z[0])
    q[1] += s * (v[1] + 2.0 * u[1] + 2.0 * w[1] + z[1])
    q[2] += s * (v[2] + 2.0 * u[2] + 2.0 * w[2] + z[2])
    q[3] += s * (v[3] + 2.0 * u[3] + 2.0 * w[3] + z[3])
    qd[0] += s * (a[0] + 2.0 * b[0] + 2.0 * e[0] + f[0])
    qd[1] += s * (a[1] + 2.0 * b[1] + 2.0 * e[1] + f[1])
    qd[2] += s * (a[2] + 2.0 * b[2] + 2.0 * e[2] + f[2])
    qd[3] += s * (a[3] + 2.0 * b[3] + 2.0 * e[3] + f[3])
    return SINGULAR_INERTIA if (c1 != OK or c2 != OK or c3 != OK or c4 != OK) else OK
