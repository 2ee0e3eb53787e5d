"""The page program of chapter 5's inertia panel: for the payload, the configuration and the quill's gain
``K_P3``, the inertia matrix ``B(q)`` with the make-up of its diagonal, its eigenvalues and condition number, the
gravity torques ``g(q)`` and the quill's steady-state sag under PD plus gravity with a payload-free model, all in
one compiled kernel (:func:`dynamics_program`; its drawing part is :func:`inertia_core`).

The eigenvalues of ``B`` come from :func:`symmetric_eigenvalues` (cyclic Jacobi rotations). For the SCARA, ``B``
has ``B34 = 0`` and ``B13 = B23``, ``B14 = B24``: in the basis ``(e1 - e2)/sqrt 2, (e1 + e2)/sqrt 2, e3, e4`` the
first vector couples with the second only, and the second with ``e3`` and ``e4``, but no block splits off (the
rotor coupling ``B13 = k_r3 I_m3`` and ``B14 = I_l4 + k_r4 I_m4`` are not zero), so the eigenvalues are the
roots of a quartic: a few Jacobi sweeps (each rotation zeroes one off-diagonal pair) find them to within a few
units in the last place of each eigenvalue, the small ones included (``B`` is positive definite).

The fields of the kernel's vectors are declared here (:data:`DYNAMICS_INPUTS`, :data:`DYNAMICS_DATA`,
:data:`DYNAMICS_OUTPUTS`); how the outputs are drawn is declared beside the figure, in :mod:`scara.plots.dynamics`.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from .._simulate.controllers import pd_gravity_steady_state_kernel
from ..dynamics import DP_IM, DP_ML, N_DP, dynamic_array, gravity_kernel, inertia_kernel

__all__ = ["DYNAMICS_INPUTS", "DYNAMICS_DATA", "DYNAMICS_OUTPUTS", "B_FIELDS", "SAG_NOTE", "REFUSED_SAG",
           "REFUSED_PAYLOAD", "REFUSED_GAIN", "JACOBI_SWEEPS", "symmetric_eigenvalues", "inertia_core",
           "dynamics_program", "dynamics_data", "inertia_values"]

#: the controls the kernel reads, in order: kg, degrees, degrees, m, degrees, N/m
DYNAMICS_INPUTS = ("payload", "theta1", "theta2", "d3", "theta4", "K_P3")
#: the panel's fixed numbers: the robot's flat parameter array (:func:`scara.dynamics.dynamic_array`; its payload
#: is replaced by the slider's) and the quill's stroke (m)
DYNAMICS_DATA = ArrayLayout(("dp", N_DP), ("d3_min", 1), ("d3_max", 1))
_DP, _D3_MIN, _D3_MAX = DYNAMICS_DATA.offsets

#: the names of the 16 entries of ``B`` as outputs of one number each, row by row: ``B11, B12, ..., B44``
B_FIELDS = tuple(f"B{i}{j}" for i in range(1, 5) for j in range(1, 5))
#: the kernel's outputs: the entries of ``B`` (kg m², kg m, kg); ``shade = log10(|B_ij| + 1e-3)`` (row by row)
#: and ``cmax = max(max shade, 0)``, the top of its colour scale; the diagonal of ``B`` split into links,
#: rotors and payload (:func:`scara.dynamics.inertia_split`); the eigenvalues ``eig1 <= ... <= eig4`` and
#: ``cond = eig4 / eig1``; ``g1 ... g4`` (N m, N m, N, N m); the sag ``m_L g0 / K_P3`` (m, and ``sag_mm`` in
#: mm), the ``d3_need = d3 + sag`` it takes, and ``sag_note`` (1 when the sag passes :data:`SAG_NOTE`)
DYNAMICS_OUTPUTS = ArrayLayout(
    *((name, 1) for name in B_FIELDS), ("shade", 16), ("cmax", 1), ("d_links", 4), ("d_rotors", 4),
    ("d_payload", 4), ("eig1", 1), ("eig2", 1), ("eig3", 1), ("eig4", 1), ("cond", 1),
    ("g1", 1), ("g2", 1), ("g3", 1), ("g4", 1), ("sag", 1), ("sag_mm", 1), ("d3_need", 1), ("sag_note", 1))
_O = DYNAMICS_OUTPUTS.offsets
_B = _O.B11
_SHADE, _CMAX, _D_LINKS, _D_ROTORS, _D_PAYLOAD = _O.shade, _O.cmax, _O.d_links, _O.d_rotors, _O.d_payload
_EIG, _COND, _G = _O.eig1, _O.cond, _O.g1
_SAG, _SAG_MM, _D3_NEED, _SAG_NOTE = _O.sag, _O.sag_mm, _O.d3_need, _O.sag_note

#: m: a quill sag above this is flagged in the panel
SAG_NOTE = 0.003
#: the refusals: the sag runs the quill past the end of its stroke; a negative payload; a gain not above 0
REFUSED_SAG = 1
REFUSED_PAYLOAD = 2
REFUSED_GAIN = 3
#: the most Jacobi sweeps :func:`symmetric_eigenvalues` makes (a 4x4 matrix needs 4 to 6)
JACOBI_SWEEPS = 50


@kernel
def symmetric_eigenvalues(A, out):
    """The eigenvalues of the symmetric matrix ``A`` (n, n), in ascending order, into ``out`` (n,), by cyclic
    Jacobi rotations (Golub and Van Loan, *Matrix Computations*, alg. 8.5.3; the rotation written as in
    Rutishauser's ``jacobi``): each rotation of the plane ``(p, q)`` zeroes ``a_pq`` and updates the diagonal by
    ``-/+ t a_pq``; an off-diagonal entry too small to change either diagonal entry is set to zero after the
    fourth sweep, and the sweeps stop when every off-diagonal entry is zero (at most :data:`JACOBI_SWEEPS`).
    ``A`` is not changed."""
    n = A.shape[0]
    a = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            a[i, j] = A[i, j]
    for sweep in range(JACOBI_SWEEPS):
        off = 0.0
        for p in range(n - 1):
            for q in range(p + 1, n):
                off += abs(a[p, q])
        if off == 0.0:
            break
        for p in range(n - 1):
            for q in range(p + 1, n):
                apq = a[p, q]
                if apq == 0.0:
                    continue
                app = a[p, p]
                aqq = a[q, q]
                g = 100.0 * abs(apq)
                if sweep > 3 and abs(app) + g == abs(app) and abs(aqq) + g == abs(aqq):
                    a[p, q] = 0.0
                    a[q, p] = 0.0
                    continue
                h = aqq - app
                if abs(h) + g == abs(h):
                    t = apq / h
                else:
                    theta = 0.5 * h / apq
                    t = 1.0 / (abs(theta) + math.sqrt(1.0 + theta * theta))
                    if theta < 0.0:
                        t = -t
                c = 1.0 / math.sqrt(1.0 + t * t)
                s = t * c
                tau = s / (1.0 + c)
                a[p, p] = app - t * apq
                a[q, q] = aqq + t * apq
                a[p, q] = 0.0
                a[q, p] = 0.0
                for r in range(n):
                    if r != p and r != q:
                        arp = a[r, p]
                        arq = a[r, q]
                        a[r, p] = arp - s * (arq + tau * arp)
                        a[p, r] = a[r, p]
                        a[r, q] = arq + s * (arp - tau * arq)
                        a[q, r] = a[r, q]
    for i in range(n):
        out[i] = a[i, i]
    for i in range(1, n):  # insertion sort: n is 4
        v = out[i]
        j = i - 1
        while j >= 0 and out[j] > v:
            out[j + 1] = out[j]
            j -= 1
        out[j + 1] = v


@kernel
def inertia_core(q, dp, payload, out):
    """Everything the inertia figure and the table draw, for the configuration ``q`` (rad, rad, m, rad) of the
    robot ``dp`` (:func:`~scara.dynamics.dynamic_array`) carrying ``payload`` (kg), into ``out`` of
    :data:`DYNAMICS_OUTPUTS` (the sag fields excepted): ``B(q)`` (:func:`~scara.dynamics.inertia_kernel`); its
    diagonal split as :func:`~scara.dynamics.inertia_split` does, as differences of ``B`` of the robot without
    rotors and payload, without payload, and with it; the shades ``log10(|B_ij| + 1e-3)``; the eigenvalues
    (:func:`symmetric_eigenvalues`) and ``cond = eig4 / eig1``; ``g(q)`` (:func:`~scara.dynamics.gravity_kernel`)."""
    full = np.empty(N_DP)
    bare = np.empty(N_DP)
    links = np.empty(N_DP)
    for i in range(N_DP):
        full[i] = dp[i]
        bare[i] = dp[i]
        links[i] = dp[i]
    full[DP_ML] = payload
    bare[DP_ML] = 0.0
    links[DP_ML] = 0.0
    for i in range(4):
        links[DP_IM + i] = 0.0
    B = out[_B:_B + 16].reshape((4, 4))
    inertia_kernel(q, full, B)
    B_bare = np.empty((4, 4))
    B_links = np.empty((4, 4))
    inertia_kernel(q, bare, B_bare)
    inertia_kernel(q, links, B_links)
    for i in range(4):
        out[_D_LINKS + i] = B_links[i, i]
        out[_D_ROTORS + i] = B_bare[i, i] - B_links[i, i]
        out[_D_PAYLOAD + i] = B[i, i] - B_bare[i, i]
    top = 0.0
    for k in range(16):
        v = math.log10(abs(out[_B + k]) + 1e-3)
        out[_SHADE + k] = v
        top = max(top, v)
    out[_CMAX] = top
    symmetric_eigenvalues(B, out[_EIG:_EIG + 4])
    out[_COND] = out[_EIG + 3] / out[_EIG]
    gravity_kernel(q, full, out[_G:_G + 4])


@kernel
def dynamics_program(inputs, data, out):
    """The inertia panel's move: ``inputs = [payload (kg), theta1 (°), theta2 (°), d3 (m), theta4 (°), K_P3
    (N/m)]``, ``data`` of :data:`DYNAMICS_DATA`, ``out`` of :data:`DYNAMICS_OUTPUTS`.

    Returns :data:`REFUSED_PAYLOAD` for a payload below 0, :data:`REFUSED_GAIN` for ``K_P3`` not above 0 and
    :data:`REFUSED_SAG` (with ``sag_mm`` and ``d3_need`` written) when the quill's sag under PD plus gravity with
    a payload-free model (:func:`~scara._simulate.controllers.pd_gravity_steady_state_kernel`, ``m_L g0 / K_P3``) would
    take it past ``d3_max``; otherwise 0, with :func:`inertia_core` written."""
    payload = inputs[0]
    d3 = inputs[3]
    K_P3 = inputs[5]
    if payload < 0.0:
        return REFUSED_PAYLOAD
    if not K_P3 > 0.0:
        return REFUSED_GAIN
    dp = data[_DP:_DP + N_DP]
    model = np.empty(N_DP)
    plant = np.empty(N_DP)
    for i in range(N_DP):
        model[i] = dp[i]
        plant[i] = dp[i]
    model[DP_ML] = 0.0
    plant[DP_ML] = payload
    sag = -pd_gravity_steady_state_kernel(model, plant, K_P3)
    out[_SAG] = sag
    out[_SAG_MM] = sag * 1e3
    out[_D3_NEED] = d3 + sag
    if d3 + sag > data[_D3_MAX]:
        return REFUSED_SAG
    out[_SAG_NOTE] = 1.0 if sag > SAG_NOTE else 0.0
    q = np.empty(4)
    q[0] = math.radians(inputs[1])
    q[1] = math.radians(inputs[2])
    q[2] = d3
    q[3] = math.radians(inputs[4])
    inertia_core(q, dp, payload, out)
    return 0


def dynamics_data(p) -> np.ndarray:
    """The ``data`` vector of :func:`dynamics_program` for the robot ``p`` (a :class:`~scara.ScaraParams`)."""
    return DYNAMICS_DATA.pack(dp=dynamic_array(p), d3_min=p.d3_min, d3_max=p.d3_max)


def inertia_values(q, p) -> dict:
    """The outputs of :func:`inertia_core` for the configuration ``q`` (4,) of the robot ``p`` with its own
    payload, by field (one number as a float, more as an array): what a static inertia figure draws."""
    out = np.zeros(DYNAMICS_OUTPUTS.size)
    inertia_core(np.ascontiguousarray(q, dtype=np.float64), dynamic_array(p), float(p.m_L), out)
    values = {}
    for name, start in zip(DYNAMICS_OUTPUTS.names, DYNAMICS_OUTPUTS.offsets):
        n = DYNAMICS_OUTPUTS.sizes[name]
        values[name] = float(out[start]) if n == 1 else np.array(out[start:start + n])
    return values
