"""The plant in contact: one RK4 step of ``B qdd + C qd + F qd + g = tau - J^T h_e`` (Siciliano et al., eq. 9.1)
with the torque held, the contact force evaluated at every stage.

The free plant's step (:func:`scara._simulate.plant._rk4_step`) carries only ``theta2``, the one joint ``B`` and
``C`` depend on; the contact force depends on the tool's position and velocity, so each stage here carries the
whole configuration. ``B^-1`` is the free plant's :func:`~scara._simulate.plant._plant_acceleration`, the tool's
position and Jacobian the kinematics kernels of chapter 1, the force :func:`.environment.contact_force_kernel`.
"""
from __future__ import annotations

import math

from .._compile import kernel
from .._simulate.interface import OK, SINGULAR_INERTIA
from .._simulate.plant import _plant_acceleration
from ..kinematics import planar_jacobian_at, planar_position, planar_trig
from .environment import contact_force_kernel

__all__ = []


@kernel
def tool_state(t1, t2, d3, u, a1, a2, d0):
    """The tool's position and velocity and the planar Jacobian at the configuration ``(t1, t2, d3)`` with the
    joint velocities ``u`` (4-tuple): ``(px, py, pz, vx, vy, vz, J11, J12, J21, J22)`` (the kernels of (1.5),
    (1.6); ``v = J u``, ``v_z = -u_3``)."""
    sc = planar_trig(t1, t2)
    px, py = planar_position(sc, a1, a2)
    J11, J12, J21, J22 = planar_jacobian_at(px, py, sc[2], sc[3], a2)
    return (px, py, d0 - d3, J11 * u[0] + J12 * u[1], J21 * u[0] + J22 * u[1], -u[2], J11, J12, J21, J22)


@kernel
def contact_acceleration(t1, t2, d3, u, t, pc, a1, a2, d0, env, inside):
    """``qdd = B^-1 (tau + J^T f - C qd - F qd - g)`` (the book's (eq-int-plant)) at the configuration ``(t1, t2,
    d3)`` (theta4 enters nothing) with the joint velocities ``u`` and torque ``t`` (4-tuples), ``f = -h_e`` the
    environment's force on the tool (:func:`.environment.contact_force_kernel`): ``(qdd, code, f)``."""
    px, py, pz, vx, vy, vz, J11, J12, J21, J22 = tool_state(t1, t2, d3, u, a1, a2, d0)
    fx, fy, fz = contact_force_kernel(px, py, pz, vx, vy, vz, env, inside)
    tt = (t[0] + J11 * fx + J21 * fy, t[1] + J12 * fx + J22 * fy, t[2] - fz, t[3])
    qdd, code = _plant_acceleration(math.cos(t2), math.sin(t2), u, tt, pc)
    return qdd, code, (fx, fy, fz)


@kernel
def _contact_stage(q, v, slope, a, step, t, pc, a1, a2, d0, env, inside):
    """One RK4 stage: the velocities ``u = v + step a`` at ``q + step slope`` and their acceleration."""
    u = (v[0] + step * a[0], v[1] + step * a[1], v[2] + step * a[2], v[3] + step * a[3])
    qdd, code, f = contact_acceleration(q[0] + step * slope[0], q[1] + step * slope[1], q[2] + step * slope[2], u, t,
                                        pc, a1, a2, d0, env, inside)
    return u, qdd, code


@kernel
def contact_rk4_step(q, qd, t, pc, h, qdd0, a1, a2, d0, env, inside):
    """One classical RK4 step of ``h`` s of the plant in contact with the torque ``t`` (4-tuple) held; ``q``,
    ``qd`` (4,) updated in place, ``qdd0`` (4,) receives the first stage's acceleration. ``inside`` (the peg's
    state, :func:`.environment.inside_after`) is held over the step. Returns :data:`OK` or
    :data:`SINGULAR_INERTIA`."""
    v = (qd[0], qd[1], qd[2], qd[3])
    z = (0.0, 0.0, 0.0, 0.0)
    hh = 0.5 * h
    v, a, c1 = _contact_stage(q, v, z, z, 0.0, t, pc, a1, a2, d0, env, inside)
    u, b, c2 = _contact_stage(q, v, v, a, hh, t, pc, a1, a2, d0, env, inside)
    w, e, c3 = _contact_stage(q, v, u, b, hh, t, pc, a1, a2, d0, env, inside)
    y, f, c4 = _contact_stage(q, v, w, e, h, t, pc, a1, a2, d0, env, inside)
    s = h / 6.0
    for i in range(4):
        qdd0[i] = a[i]
        q[i] += s * (v[i] + 2.0 * u[i] + 2.0 * w[i] + y[i])
        qd[i] += s * (a[i] + 2.0 * b[i] + 2.0 * e[i] + f[i])
    return SINGULAR_INERTIA if (c1 != OK or c2 != OK or c3 != OK or c4 != OK) else OK
