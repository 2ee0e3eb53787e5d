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

import math

import numpy as np

from .._compile import kernel
from ..dynamics import friction, inertia
from ..errors import UnstableError
from ..params import ScaraParams

__all__ = ["sampled_radius", "z_axis", "UNSTABLE_MESSAGE", "IN_CONTACT", "IN_FREE_SPACE"]

#: The refusal of an unstable sampled loop (:func:`check_sampled`), ``{place}`` one of the two below
UNSTABLE_MESSAGE = ("the sampled loop of {name} along z, {place}, at dt = {dt:g} s, has spectral radius {r:.6g}, "
                    "which must be < 1: the law is unstable there with {gains}; lower the gains (or the sampling "
                    "period)")
IN_CONTACT = "in contact with a surface of stiffness k_e = {k:g} N/m and damping d_e = {d:g} N s/m"
IN_FREE_SPACE = "in free space"


def z_axis(plant: ScaraParams | None = None) -> tuple:
    """``(m, c)``: the mass (kg) moving along z, ``B33``, and the viscous friction (N s/m) of joint 3, ``F_3``,
    of the arm ``plant`` (``B33`` does not depend on ``q``)."""
    plant = ScaraParams.resolve(plant)
    return float(inertia(np.zeros(4), plant)[2, 2]), float(friction(plant)[2, 2])


@kernel
def plant_step(m, c, k, d, dt, phi, gamma):
    """The exact step over ``dt`` of ``m z_ddot = u - k z - (d + c) z_dot`` with ``u`` held (the plant of the
    book's (eq-int-sampled)): ``phi`` (2, 2) and
    ``gamma`` (2,) of ``exp([[0, 1, 0], [-k/m, -(d+c)/m, 1/m], [0, 0, 0]] dt)`` (its first two rows), by scaling
    and squaring of the Taylor series (degree 20 on a matrix of norm below 1/2: the series' remainder is below
    the rounding)."""
    a = np.zeros((3, 3))
    a[0, 1] = dt
    a[1, 0] = -k / m * dt
    a[1, 1] = -(d + c) / m * dt
    a[1, 2] = dt / m
    norm = 0.0
    for j in range(3):
        col = 0.0
        for i in range(3):
            col += abs(a[i, j])
        norm = max(norm, col)
    squarings = 0
    while norm > 0.5:
        norm *= 0.5
        squarings += 1
    scale = 0.5 ** squarings
    for i in range(3):
        for j in range(3):
            a[i, j] *= scale
    e = np.zeros((3, 3))
    term = np.zeros((3, 3))
    nxt = np.zeros((3, 3))
    for i in range(3):
        e[i, i] = 1.0
        term[i, i] = 1.0
    for p in range(1, 21):
        for i in range(3):
            for j in range(3):
                v = 0.0
                for q in range(3):
                    v += term[i, q] * a[q, j]
                nxt[i, j] = v / p
        for i in range(3):
            for j in range(3):
                term[i, j] = nxt[i, j]
                e[i, j] += nxt[i, j]
    for _ in range(squarings):
        for i in range(3):
            for j in range(3):
                v = 0.0
                for q in range(3):
                    v += e[i, q] * e[q, j]
                nxt[i, j] = v
        for i in range(3):
            for j in range(3):
                e[i, j] = nxt[i, j]
    for i in range(2):
        for j in range(2):
            phi[i, j] = e[i, j]
        gamma[i] = e[i, 2]


@kernel
def spectral_radius(a, size):
    """The largest modulus of the eigenvalues of the leading ``size`` x ``size`` block of ``a`` (``size`` <= 4): the
    roots of its characteristic polynomial (Faddeev-LeVerrier) found together by the Durand-Kerner iteration."""
    coef = np.zeros(size + 1)   # monic: coef[size] = 1, the polynomial sum coef[i] x^i
    coef[size] = 1.0
    mk = np.zeros((size, size))
    prod = np.zeros((size, size))
    for kk in range(1, size + 1):
        for i in range(size):
            for j in range(size):
                v = 0.0
                for q in range(size):
                    v += a[i, q] * mk[q, j]
                prod[i, j] = v
        for i in range(size):
            for j in range(size):
                mk[i, j] = prod[i, j] + (coef[size - kk + 1] if i == j else 0.0)
        tr = 0.0
        for i in range(size):
            for q in range(size):
                tr += a[i, q] * mk[q, i]
        coef[size - kk] = -tr / kk
    bound = 1.0
    for i in range(size):
        bound = max(bound, 1.0 + abs(coef[i]))
    re = np.zeros(size)
    im = np.zeros(size)
    wr, wi = 0.4 * bound, 0.9 * bound
    zr, zi = 1.0, 0.0
    for i in range(size):
        zr, zi = zr * wr / bound - zi * wi / bound, zr * wi / bound + zi * wr / bound
        re[i] = zr * bound
        im[i] = zi * bound
    for _ in range(2000):
        moved = 0.0
        for i in range(size):
            pr, pi_ = 1.0, 0.0   # p(z_i) by Horner
            pr = coef[size]
            for q in range(size - 1, -1, -1):
                pr, pi_ = pr * re[i] - pi_ * im[i] + coef[q], pr * im[i] + pi_ * re[i]
            dr, di = 1.0, 0.0   # prod (z_i - z_j)
            for j in range(size):
                if j != i:
                    xr = re[i] - re[j]
                    xi = im[i] - im[j]
                    dr, di = dr * xr - di * xi, dr * xi + di * xr
            den = dr * dr + di * di
            if den == 0.0:
                continue
            cr = (pr * dr + pi_ * di) / den
            ci = (pi_ * dr - pr * di) / den
            re[i] -= cr
            im[i] -= ci
            moved = max(moved, math.hypot(cr, ci) / max(1.0, math.hypot(re[i], im[i])))
        if moved <= 1e-16:
            break
    r = 0.0
    for i in range(size):
        r = max(r, math.hypot(re[i], im[i]))
    return r


@kernel
def loop_radius(Dy, Cw, Aw, By, n, m, c, k, d, dt):
    """The spectral radius of the sampled loop (module docstring) whose law has the linear part ``Dy`` (2,),
    ``Cw`` (n,), ``Aw`` (n, n), ``By`` (n, 2) (its state of ``n`` entries, ``n <= 2``): :func:`sampled_radius`."""
    phi = np.zeros((2, 2))
    gamma = np.zeros(2)
    plant_step(m, c, k, d, dt, phi, gamma)
    big = np.zeros((2 + n, 2 + n))
    for i in range(2):
        for j in range(2):
            big[i, j] = phi[i, j] + gamma[i] * Dy[j]
        for j in range(n):
            big[i, 2 + j] = gamma[i] * Cw[j]
    for i in range(n):
        for j in range(2):
            big[2 + i, j] = By[i, j]
        for j in range(n):
            big[2 + i, 2 + j] = Aw[i, j]
    return spectral_radius(big, 2 + n)


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
    return float(loop_radius(np.ascontiguousarray(Dy.reshape(2)), np.ascontiguousarray(Cw.reshape(n)),
                             np.ascontiguousarray(Aw.reshape(n, n)), np.ascontiguousarray(By.reshape(n, 2)), n,
                             float(m), float(c), float(k), float(d), float(dt)))


def check_sampled(name: str, loops: dict, m: float, c: float, k: float, d: float, dt: float, gains: str) -> None:
    """Refuse (:class:`~scara.UnstableError`) a law whose sampled loop along z has a spectral radius ``>= 1``, in
    contact (``loops["contact"]``, on ``k``, ``d``) or in free space (``loops["free"]``), naming the radius, the
    limit 1 and the gains ``gains``."""
    for where, loop in loops.items():
        kk, dd = (k, d) if where == "contact" else (0.0, 0.0)
        r = sampled_radius(loop, m, c, kk, dd, dt)
        if not r < 1.0:
            place = IN_CONTACT.format(k=k, d=d) if where == "contact" else IN_FREE_SPACE
            raise UnstableError(UNSTABLE_MESSAGE.format(name=name, place=place, dt=dt, r=r, gains=gains))
