"""The stability of a sampled interaction law in contact, along z (chapter 7).

Along z a SCARA is a single mass: ``p_z = d0 - d3`` moves with the quill alone (its inertia ``m = B33``, up to the
rotor coupling ``B13``, a relative 1e-2 of it here), under the viscous friction ``c = F_3`` of joint 3. Pressed on
the surface the tool meets a spring ``k_e`` and a damper ``d_e``, and the force sensor reads ``h = k_e z + d_e
z_dot`` (``z`` measured from the equilibrium). A law sampled every ``dt`` and held (zero-order hold) closes the
loop

    m z_ddot = u_k - k_e z - (d_e + c) z_dot  on [t_k, t_k + dt),    u_k = C_w w_k + D_y y_k,
    w_{k+1} = A_w w_k + B_y y_k,      y_k = (z(t_k), z_dot(t_k))

(``w`` the law's own state: an integral, a compliant frame). With the plant's exact step ``(Phi, Gamma)`` over
``dt`` the closed loop is the linear map ``[[Phi + Gamma D_y, Gamma C_w], [B_y, A_w]]``: it is stable iff its
spectral radius is below 1, a necessary condition for the law to press on the surface without chattering or
bouncing (the unilateral contact only adds ways to lose it). Each law gives its ``(D_y, C_w, A_w, B_y)``.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import expm

from ..dynamics import friction, inertia
from ..errors import UnstableError
from ..params import ScaraParams

__all__ = ["sampled_radius", "z_axis"]


def z_axis(plant: ScaraParams | None = None) -> tuple:
    """``(m, c)``: the mass (kg) moving along z, ``B33``, and the viscous friction (N s/m) of joint 3, ``F_3``,
    of the arm ``plant`` (``B33`` does not depend on ``q``)."""
    plant = ScaraParams.resolve(plant)
    return float(inertia(np.zeros(4), plant)[2, 2]), float(friction(plant)[2, 2])


def sampled_radius(loop, m: float, c: float, k: float, d: float, dt: float) -> float:
    """The spectral radius of the sampled loop along z (module docstring) of the law whose linear part is
    ``loop = (D_y (2,), C_w (n,), A_w (n, n), B_y (n, 2))`` on the mass ``m`` (kg) with friction ``c`` (N s/m), on a
    surface of stiffness ``k`` (N/m) and damping ``d`` (N s/m) (``k = d = 0``: free space), sampled every ``dt``.

    >>> round(sampled_radius((np.array([-1e4, -400.0]), np.zeros(0), np.zeros((0, 0)), np.zeros((0, 2))),
    ...                      20.0, 0.0, 0.0, 0.0, 1e-3), 4)
    0.9901
    """
    Dy, Cw, Aw, By = (np.asarray(a, dtype=float) for a in loop)
    n = len(Cw)
    A = np.array([[0.0, 1.0, 0.0], [-k / m, -(d + c) / m, 1.0 / m], [0.0, 0.0, 0.0]])
    E = expm(A * dt)
    Phi, Gamma = E[:2, :2], E[:2, 2:3]
    M = np.zeros((2 + n, 2 + n))
    M[:2, :2] = Phi + Gamma @ Dy.reshape(1, 2)
    M[:2, 2:] = Gamma @ Cw.reshape(1, n)
    M[2:, :2] = By.reshape(n, 2)
    M[2:, 2:] = Aw.reshape(n, n)
    return float(np.max(np.abs(np.linalg.eigvals(M))))


def check_sampled(name: str, loops: dict, m: float, c: float, k: float, d: float, dt: float, gains: str) -> None:
    """Refuse (:class:`~scara.UnstableError`) a law whose sampled loop along z has a spectral radius ``>= 1``, in
    contact (``loops["contact"]``, on ``k``, ``d``) or in free space (``loops["free"]``), naming the radius, the
    limit 1 and the gains ``gains``."""
    for where, loop in loops.items():
        kk, dd = (k, d) if where == "contact" else (0.0, 0.0)
        r = sampled_radius(loop, m, c, kk, dd, dt)
        if not r < 1.0:
            place = (f"in contact with a surface of stiffness k_e = {k:g} N/m and damping d_e = {d:g} N s/m"
                     if where == "contact" else "in free space")
            raise UnstableError(f"the sampled loop of {name} along z, {place}, at dt = {dt:g} s, has spectral radius "
                                f"{r:.6g}, which must be < 1: the law is unstable there with {gains}; lower the "
                                f"gains (or the sampling period)")
