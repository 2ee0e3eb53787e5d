"""Dynamic model of the SCARA arm with its motors and payload (chapter 5).

    B(q) qdd + C(q, qd) qd + F qd + g(q) = tau

``B`` is the inertia matrix of the links, the quill with its payload and the rotors (Siciliano et al. ch. 7
rotor model: motor i rides on link i-1 and spins at ``omega_{i-1} + k_ri qdot_i`` about the vertical);
``C`` comes from the Christoffel symbols of ``B``, so ``Bdot - 2C`` is skew-symmetric; ``F = diag(k_ri^2
F_mi)``; ``g = [0, 0, -m3 g0, 0]`` with ``m3 = m_l3 + m_L``. The model is linear in the parameter vector
``pi`` of :data:`PI_NAMES`: ``Y(q, qd, qd_r, qdd_r) pi = B qdd_r + C(q, qd) qd_r + F qd_r + g``.

Two layers
----------
*Compiled kernels* (``*_kernel``) take floats and float arrays only and write into arrays passed by the
caller; compiled loops (the simulation engine, controllers) call them with no Python objects. Every kernel
reads the robot from one flat float array ``dp = dynamic_array(p)`` that holds the robot's data (the table of
the introduction) in this order (index constants ``DP_*`` are exported)::

    0 d0   1 a1   2 a2   3 l1   4 l2   5 m_l1   6 m_l2   7 m_l3   8 I_l1   9 I_l2   10 I_l4
    11..14 k_r1..k_r4    15..18 I_m1..I_m4    19..22 F_m1..F_m4    23 m_L    24 g0

The fields are declared once, in :data:`DYNAMIC_LAYOUT`, which gives both the offsets and the packer. A
controller that holds a wrong model (e.g. no payload) simply passes its own ``dynamic_array``.

Each formula is written once: the lumped parameters ``pi`` in :func:`lumped_parameters`, the inertia matrix
``B(q)`` in :func:`inertia_parts` (from ``pi``; the plant of :mod:`scara.simulate` and the controllers use it
too), ``C(q, qd) v`` in :func:`coriolis_vector_kernel`, ``g(q)`` in :func:`gravity_kernel` (``C qd + F qd + g`` in
:func:`bias_kernel` calls it), ``U(q)`` in :func:`potential_energy_kernel`, the split of ``B`` into links, rotors
and payload in :func:`inertia_split`, and the symmetric positive definite 4x4 solve in :func:`cholesky_solve4`.

*Public functions* (``inertia``, ``coriolis``, ...) check their inputs, take an optional
:class:`~scara.ScaraParams` (``None`` is the robot of the introduction, without payload) and return new arrays.
They are formulas: ``d3`` may lie outside the quill's stroke (only a motion's start is held to it), the revolute
angles must stay within ``MAX_ANGLE = 1e6`` rad (:data:`scara.errors.MAX_ANGLE`; beyond it ``sin`` and ``cos``
lose all precision), and a result that overflows (speeds of 1e300 rad/s) raises
:class:`~scara.errors.NonFiniteError` naming the input that was too large.
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ._compile import ArrayLayout, kernel
from .errors import (ScaraError, ShapeError, UnstableError, as_array, check_angles, check_finite_result,
                     check_positive)
from .params import ScaraParams

__all__ = [
    # flat parameter array
    "DP_NAMES", "N_DP", "dynamic_array",
    # parameter vector pi
    "PI_NAMES", "PI_UNITS", "N_PI", "dynamic_parameters", "params_from_pi", "payload_from_pi",
    # public model
    "inertia", "coriolis", "gravity", "friction", "inverse_dynamics", "forward_dynamics", "regressor",
    "kinetic_energy", "potential_energy", "total_energy", "torque_breakdown", "TORQUE_TERMS", "inertia_split",
    # kernels
    "inertia_kernel", "coriolis_kernel", "coriolis_vector_kernel", "gravity_kernel", "friction_kernel",
    "inverse_dynamics_kernel", "bias_kernel", "forward_dynamics_kernel", "regressor_kernel", "pi_kernel",
    "lumped_parameters", "LumpedParameters", "inertia_parts", "InertiaParts",
    "kinetic_energy_kernel", "potential_energy_kernel", "cholesky_solve4",
    "dynamics_workspace", "FD_WORK_ROWS",
]

# --------------------------------------------------------------------------------------------------
# the flat parameter array
# --------------------------------------------------------------------------------------------------
#: The fields of the flat parameter array, declared once: the offsets ``DP_*`` the kernels read and the packer
#: :func:`dynamic_array` both come from it (each name is the attribute of :class:`~scara.ScaraParams`).
DYNAMIC_LAYOUT = ArrayLayout(("d0", 1), ("a1", 1), ("a2", 1), ("l1", 1), ("l2", 1), ("m_l1", 1), ("m_l2", 1),
                             ("m_l3", 1), ("I_l1", 1), ("I_l2", 1), ("I_l4", 1), ("k_r", 4), ("I_m", 4), ("F_m", 4),
                             ("m_L", 1), ("g0", 1))
(DP_D0, DP_A1, DP_A2, DP_L1, DP_L2, DP_ML1, DP_ML2, DP_ML3, DP_IL1, DP_IL2, DP_IL4,
 DP_KR, DP_IM, DP_FM,  # first of four entries each
 DP_ML, DP_G0) = DYNAMIC_LAYOUT.offsets
#: The length of the flat parameter array :func:`dynamic_array` (the ``model`` a compiled law receives).
N_DP = DYNAMIC_LAYOUT.size
#: The name of each entry of :func:`dynamic_array`, in order (``k_r1`` ... for the per-joint fields).
DP_NAMES = tuple(name if size == 1 else f"{name}{i + 1}"
                 for name, size in DYNAMIC_LAYOUT.sizes.items() for i in range(size))


def dynamic_array(p: ScaraParams | None = None) -> np.ndarray:
    """The robot's data in ``p`` (the table of the introduction) as one flat float array of shape ``(25,)``, in
    the order of :data:`DP_NAMES`: the form every compiled dynamics kernel takes.

    >>> dynamic_array()[[1, 7, 23, 24]]
    array([ 0.5 , 10.  ,  0.  ,  9.81])
    """
    p = ScaraParams.resolve(p)
    return DYNAMIC_LAYOUT.pack(**{name: getattr(p, name) for name in DYNAMIC_LAYOUT.names})


# --------------------------------------------------------------------------------------------------
# the parameter vector pi of the linear-in-parameters model
# --------------------------------------------------------------------------------------------------
#: Names of the 13 dynamic parameters in ``pi``, in order, for the regressor form ``Y pi`` of chapter 5.
#: ``beta_ij`` is the constant part of ``B_ij`` (everything in ``B_ij`` that does not multiply ``m3`` or
#: ``m_l2 l2``); ``F1`` to ``F4`` are the joints' viscous friction. Units: :data:`PI_UNITS`.
PI_NAMES = ("m3", "m_l2 l2", "beta11", "beta12", "beta22", "beta13", "beta33", "beta14", "beta44",
            "F1", "F2", "F3", "F4")
#: The unit of each entry of ``pi`` (:data:`PI_NAMES`).
PI_UNITS = ("kg", "kg m", "kg m^2", "kg m^2", "kg m^2", "kg m", "kg", "kg m^2", "kg m^2",
            "N m s/rad", "N m s/rad", "N s/m", "N m s/rad")
#: The number of dynamic parameters in ``pi``.
N_PI = 13
PI_M3 = 0

#: ``pi`` as a record read by name in compiled code (fields in the order of :data:`PI_NAMES`):
#: ``m3``, ``ml2_l2`` (``m_l2 l2``), ``beta11`` ... ``beta44``, ``F1`` ... ``F4``.
LumpedParameters = namedtuple("LumpedParameters", ("m3", "ml2_l2", "beta11", "beta12", "beta22", "beta13", "beta33",
                                                   "beta14", "beta44", "F1", "F2", "F3", "F4"))


@kernel(light=True)
def lumped_parameters(dp):
    """The parameter vector ``pi`` of :data:`PI_NAMES` from the flat array ``dp``, as a
    :data:`LumpedParameters` record: the one place the lumped parameters are formed (chapter 5).

    ``m3 = m_l3 + m_L`` and

    * ``beta11 = I_l1 + m_l1 l1^2 + k_r1^2 I_m1 + I_l2 + m_l2 (a1^2 + l2^2) + I_l4 + I_m2 + I_m3 + I_m4``
    * ``beta12 = I_l2 + m_l2 l2^2 + I_l4 + k_r2 I_m2 + I_m3 + I_m4``
    * ``beta22 = I_l2 + m_l2 l2^2 + I_l4 + k_r2^2 I_m2 + I_m3 + I_m4``
    * ``beta13 = k_r3 I_m3``, ``beta33 = k_r3^2 I_m3``, ``beta14 = I_l4 + k_r4 I_m4``,
      ``beta44 = I_l4 + k_r4^2 I_m4``, ``F_i = k_ri^2 F_mi``.
    """
    a1 = dp[DP_A1]
    l1 = dp[DP_L1]
    l2 = dp[DP_L2]
    kr1 = dp[DP_KR]
    kr2 = dp[DP_KR + 1]
    kr3 = dp[DP_KR + 2]
    kr4 = dp[DP_KR + 3]
    im1 = dp[DP_IM]
    im2 = dp[DP_IM + 1]
    im3 = dp[DP_IM + 2]
    im4 = dp[DP_IM + 3]
    il4 = dp[DP_IL4]
    j2 = dp[DP_IL2] + dp[DP_ML2] * l2 * l2
    return LumpedParameters(
        dp[DP_ML3] + dp[DP_ML],
        dp[DP_ML2] * l2,
        dp[DP_IL1] + dp[DP_ML1] * l1 * l1 + kr1 * kr1 * im1 + j2 + dp[DP_ML2] * a1 * a1 + il4 + im2 + im3 + im4,
        j2 + il4 + kr2 * im2 + im3 + im4,
        j2 + il4 + kr2 * kr2 * im2 + im3 + im4,
        kr3 * im3,
        kr3 * kr3 * im3,
        il4 + kr4 * im4,
        il4 + kr4 * kr4 * im4,
        kr1 * kr1 * dp[DP_FM],
        kr2 * kr2 * dp[DP_FM + 1],
        kr3 * kr3 * dp[DP_FM + 2],
        kr4 * kr4 * dp[DP_FM + 3])


@kernel(light=True)
def pi_kernel(dp, out):
    """The parameter vector ``pi`` (13,) of :data:`PI_NAMES` from the flat array ``dp``, into ``out``
    (the entries of :func:`lumped_parameters`)."""
    pi = lumped_parameters(dp)
    for i in range(N_PI):
        out[i] = pi[i]


# --------------------------------------------------------------------------------------------------
# compiled kernels
# --------------------------------------------------------------------------------------------------
#: The constant entries of ``B(q)`` and the coefficient ``b`` of ``cos theta2`` (see :func:`inertia_parts`).
InertiaParts = namedtuple("InertiaParts", ("B11_0", "B12_0", "B22", "B13", "B33", "B14", "B44", "b"))


@kernel
def inertia_parts(a1, a2, lp):
    """The inertia matrix ``B(q)`` of chapter 5 from the lumped parameters ``lp`` (:func:`lumped_parameters`)
    and the link lengths: the one place ``B`` is written. Returns an :data:`InertiaParts` record.

    With ``b = a1 (m_l2 l2 + m3 a2)``: ``B11 = B11_0 + 2 b c2``, ``B11_0 = beta11 + m3 (a1^2 + a2^2)``;
    ``B12 = B12_0 + b c2``, ``B12_0 = beta12 + m3 a2^2``; ``B22 = beta22 + m3 a2^2``; ``B13 = B23 = beta13``;
    ``B33 = m3 + beta33``; ``B14 = B24 = beta14``; ``B44 = beta44``; ``B34 = 0`` (``c2 = cos theta2``, the only
    configuration ``B`` depends on; ``C`` of :func:`coriolis_kernel` carries ``h = b sin theta2``).
    """
    m3 = lp.m3
    return InertiaParts(lp.beta11 + m3 * (a1 * a1 + a2 * a2), lp.beta12 + m3 * a2 * a2, lp.beta22 + m3 * a2 * a2,
                        lp.beta13, m3 + lp.beta33, lp.beta14, lp.beta44, a1 * (lp.ml2_l2 + m3 * a2))


@kernel
def inertia_kernel(q, dp, out):
    """Inertia matrix ``B(q)`` (chapter 5) written into ``out`` (4, 4): the entries of :func:`inertia_parts`."""
    bp = inertia_parts(dp[DP_A1], dp[DP_A2], lumped_parameters(dp))
    c2 = math.cos(q[1])
    out[0, 0] = bp.B11_0 + 2.0 * bp.b * c2
    out[0, 1] = bp.B12_0 + bp.b * c2
    out[1, 1] = bp.B22
    out[0, 2] = bp.B13
    out[1, 2] = bp.B13
    out[2, 2] = bp.B33
    out[0, 3] = bp.B14
    out[1, 3] = bp.B14
    out[2, 3] = 0.0
    out[3, 3] = bp.B44
    for i in range(4):
        for j in range(i):
            out[i, j] = out[j, i]


@kernel
def _coriolis_coefficient(q, dp):
    """``h = b sin theta2`` with ``b`` of :func:`inertia_parts`: the one factor of ``C(q, qd)``."""
    return inertia_parts(dp[DP_A1], dp[DP_A2], lumped_parameters(dp)).b * math.sin(q[1])


@kernel
def coriolis_kernel(q, qd, dp, out):
    """Coriolis and centrifugal matrix ``C(q, qd)`` from the Christoffel symbols, into ``out`` (4, 4).

    Only ``B11`` and ``B12`` depend on ``q`` (through ``c2``), so with ``h = b sin(theta2)`` (``b`` of
    :func:`inertia_parts`):
    ``C11 = -h qd2``, ``C12 = -h (qd1 + qd2)``, ``C21 = h qd1``, every other entry 0.
    """
    h = _coriolis_coefficient(q, dp)
    for i in range(4):
        for j in range(4):
            out[i, j] = 0.0
    out[0, 0] = -h * qd[1]
    out[0, 1] = -h * (qd[0] + qd[1])
    out[1, 0] = h * qd[0]


@kernel
def _coriolis_entries(q, qd, v, dp):
    """The two entries of ``C(q, qd) v`` that are not zero (rows 1 and 2), as floats."""
    h = _coriolis_coefficient(q, dp)
    return -h * (qd[1] * v[0] + (qd[0] + qd[1]) * v[1]), h * qd[0] * v[0]


@kernel
def coriolis_vector_kernel(q, qd, v, dp, out):
    """``C(q, qd) v`` written into ``out`` (4,) without forming ``C`` (``v = qd`` gives the usual term)."""
    c1, c2 = _coriolis_entries(q, qd, v, dp)
    out[0] = c1
    out[1] = c2
    out[2] = 0.0
    out[3] = 0.0


@kernel
def gravity_kernel(q, dp, out):
    """Gravity torques ``g(q) = [0, 0, -m3 g0, 0]`` (chapter 5) written into ``out`` (4,)."""
    out[0] = 0.0
    out[1] = 0.0
    out[2] = -lumped_parameters(dp).m3 * dp[DP_G0]
    out[3] = 0.0


@kernel
def friction_kernel(qd, dp, out):
    """Viscous friction torques ``F qd`` with ``F = diag(k_ri^2 F_mi)`` written into ``out`` (4,)."""
    lp = lumped_parameters(dp)  # fields read by name: a runtime index into the record would keep all of it
    out[0] = lp.F1 * qd[0]
    out[1] = lp.F2 * qd[1]
    out[2] = lp.F3 * qd[2]
    out[3] = lp.F4 * qd[3]


@kernel
def bias_kernel(q, qd, dp, out):
    """``n(q, qd) = C(q, qd) qd + F qd + g(q)`` (chapter 5), every torque but ``B qdd``, into ``out`` (4,): the
    sum of :func:`friction_kernel`, the Coriolis entries and :func:`gravity_kernel`."""
    gravity_kernel(q, dp, out)
    g1, g2, g3, g4 = out[0], out[1], out[2], out[3]
    friction_kernel(qd, dp, out)
    c1, c2 = _coriolis_entries(q, qd, qd, dp)
    out[0] = out[0] + c1 + g1
    out[1] = out[1] + c2 + g2
    out[2] += g3
    out[3] += g4


@kernel
def inverse_dynamics_kernel(q, qd, qdd, dp, work, out):
    """``tau = B(q) qdd + C(q, qd) qd + F qd + g(q)`` into ``out`` (4,); ``work`` is scratch of shape (5, 4)."""
    B = work[0:4]
    inertia_kernel(q, dp, B)
    bias_kernel(q, qd, dp, out)
    for i in range(4):
        s = out[i]
        for j in range(4):
            s += B[i, j] * qdd[j]
        out[i] = s


@kernel
def cholesky_solve4(A, b, out):
    """Solve ``A x = b`` for a symmetric positive definite 4x4 ``A`` by Cholesky, into ``out`` (4,).

    ``A`` is overwritten by its Cholesky factor (lower triangle). Returns 0, or 1 when ``A`` is not
    positive definite (``out`` is then left unchanged). ``out`` may be ``b`` itself.
    """
    n = 4
    for j in range(n):
        s = A[j, j]
        for k in range(j):
            s -= A[j, k] * A[j, k]
        if not s > 0.0:
            return 1
        d = math.sqrt(s)
        A[j, j] = d
        for i in range(j + 1, n):
            s = A[i, j]
            for k in range(j):
                s -= A[i, k] * A[j, k]
            A[i, j] = s / d
    # forward substitution L y = b (y kept in out)
    y0 = b[0] / A[0, 0]
    y1 = (b[1] - A[1, 0] * y0) / A[1, 1]
    y2 = (b[2] - A[2, 0] * y0 - A[2, 1] * y1) / A[2,2]
    y3 = (b[3] - A[3, 0] * y0 - A[3, 1] * y1 - A[3, 2] * y2) / A[3, 3]
    # back substitution L^T x = y
    x3 = y3 / A[3, 3]
    x2 = (y2 - A[3, 2] * x3) / A[2, 2]
    x1 = (y1 - A[2, 1] * x2 - A[3, 1] * x3) / A[1, 1]
    x0 = (y0 - A[1, 0] * x1 - A[2, 0] * x2 - A[3, 0] * x3) / A[0, 0]
    out[0] = x0
    out[1] = x1
    out[2] = x2
    out[3] = x3
    return 0


#: rows of the ``(rows, 4)`` scratch array that :func:`forward_dynamics_kernel` needs
FD_WORK_ROWS = 5


def dynamics_workspace() -> np.ndarray:
    """A scratch array of shape ``(FD_WORK_ROWS, 4)`` for :func:`forward_dynamics_kernel` and friends."""
    return np.zeros((FD_WORK_ROWS, 4))


@kernel
def forward_dynamics_kernel(q, qd, tau, dp, work, out):
    """``qdd = B(q)^-1 (tau - C(q, qd) qd - F qd - g(q))`` into ``out`` (4,), with no allocation.

    ``B`` (:func:`inertia_kernel`) goes into ``work[0:4]`` and the right-hand side into ``work[4]``
    (``work`` of shape (5, 4), :func:`dynamics_workspace`); the system is solved by :func:`cholesky_solve4`.
    Returns 0, or 1 if ``B`` is not positive definite (``out`` then unchanged).
    """
    B = work[0:4]
    r = work[4]
    bias_kernel(q, qd, dp, r)
    for i in range(4):
        r[i] = tau[i] - r[i]
    inertia_kernel(q, dp, B)
    return cholesky_solve4(B, r, out)


@kernel
def regressor_kernel(q, qd, qd_r, qdd_r, dp, out):
    """Regressor ``Y(q, qd, qd_r, qdd_r)`` (4, 13) into ``out``: ``Y pi = B qdd_r + C(q, qd) qd_r + F qd_r + g``.

    Only ``a1``, ``a2`` and ``g0`` are read from ``dp`` (geometry and gravity are known); the columns follow
    :data:`PI_NAMES`.
    """
    a1 = dp[DP_A1]
    a2 = dp[DP_A2]
    g0 = dp[DP_G0]
    c2 = math.cos(q[1])
    s2 = math.sin(q[1])
    v1 = qd[0]
    v2 = qd[1]
    r1 = qd_r[0]
    r2 = qd_r[1]
    u1 = qdd_r[0]
    u2 = qdd_r[1]
    u3 = qdd_r[2]
    u4 = qdd_r[3]
    for i in range(4):
        for j in range(13):
            out[i, j] = 0.0
    cor1 = -s2 * (v2 * r1 + (v1 + v2) * r2)   # (C qd_r)_1 / b,  b = a1 (m_l2 l2 + m3 a2)
    cor2 = s2 * v1 * r1                        # (C qd_r)_2 / b
    # row 1
    out[0, 0] = (a1 * a1 + a2 * a2 + 2.0 * a1 * a2 * c2) * u1 + (a2 * a2 + a1 * a2 * c2) * u2 + a1 * a2 * cor1
    out[0, 1] = a1 * c2 * (2.0 * u1 + u2) + a1 * cor1
    out[0, 2] = u1
    out[0, 3] = u2
    out[0, 5] = u3
    out[0, 7] = u4
    out[0, 9] = r1
    # row 2
    out[1, 0] = (a2 * a2 + a1 * a2 * c2) * u1 + a2 * a2 * u2 + a1 * a2 * cor2
    out[1, 1] = a1 * c2 * u1 + a1 * cor2
    out[1, 3] = u1
    out[1, 4] = u2
    out[1, 5] = u3
    out[1, 7] = u4
    out[1, 10] = r2
    # row 3
    out[2, 0] = u3 - g0
    out[2, 5] = u1 + u2
    out[2, 6] = u3
    out[2, 11] = qd_r[2]
    # row 4
    out[3, 7] = u1 + u2
    out[3, 8] = u4
    out[3, 12] = qd_r[3]


@kernel
def kinetic_energy_kernel(q, qd, dp, work):
    """Kinetic energy ``T = qd^T B(q) qd / 2`` (J); ``work`` is scratch of shape (>= 4, 4)."""
    B = work[0:4]
    inertia_kernel(q, dp, B)
    s = 0.0
    for i in range(4):
        for j in range(4):
            s += qd[i] * B[i, j] * qd[j]
    return 0.5 * s


@kernel
def _potential_batch(q, dp, out):
    """``out[k] = potential_energy_kernel(q[k], dp)`` for every row of ``q`` (N, 4)."""
    for k in range(q.shape[0]):
        out[k] = potential_energy_kernel(q[k], dp)


@kernel
def potential_energy_kernel(q, dp):
    """Potential energy ``U = g0 [(m_l1 + m_l2) d0 + m3 (d0 - d3)]`` (J), zero at the base-frame floor.

    Links 1 and 2 move in the horizontal plane at height ``d0``; the quill and payload sit at ``p_z = d0 - d3``;
    link 4 and the rotors have no mass.
    """
    d0 = dp[DP_D0]
    return dp[DP_G0] * ((dp[DP_ML1] + dp[DP_ML2]) * d0 + (dp[DP_ML3] + dp[DP_ML]) * (d0 - q[2]))


# --------------------------------------------------------------------------------------------------
# public functions
# --------------------------------------------------------------------------------------------------
def _vec(value, name):
    return np.ascontiguousarray(as_array(value, name, (4,)))


def _config(value, name="q", allow_batch=False):
    """A configuration: finite, of shape (4,) (or (N, 4)), revolute angles within ``MAX_ANGLE``."""
    return np.ascontiguousarray(check_angles(as_array(value, name, (4,), allow_batch=allow_batch), name))


def inertia(q, p: ScaraParams | None = None) -> np.ndarray:
    """Inertia matrix ``B(q)`` of the arm with rotors and payload (chapter 5), shape (4, 4); a series ``q`` (N, 4)
    gives the N matrices, shape (N, 4, 4), in one compiled loop.

    Units: kg m^2 for the revolute entries, kg for ``B33``, kg m for ``B13``/``B23``. Raises
    :class:`~scara.ShapeError` / :class:`~scara.NonFiniteError` for a bad ``q``.

    >>> round(float(inertia([0, 0, 0.5, 0])[2, 2]), 6)   # m3 + k_r3^2 I_m3 = 10 + 2500 * 0.005
    22.5
    """
    q = _config(q, allow_batch=True)
    out = np.empty(q.shape[:-1] + (4, 4))
    if q.ndim == 1:
        inertia_kernel(q, dynamic_array(p), out)
    else:
        inertia_rows(q, dynamic_array(p), out)
    return check_finite_result(out, "B(q)", q=q)


@kernel
def inertia_rows(q, dp, out):
    """``out[k] = B(q[k])`` (:func:`inertia_kernel`) for every row of ``q`` (N, 4); ``out`` (N, 4, 4)."""
    for k in range(q.shape[0]):
        inertia_kernel(q[k], dp, out[k])


def coriolis(q, qd, p: ScaraParams | None = None) -> np.ndarray:
    """Coriolis and centrifugal matrix ``C(q, qd)`` from the Christoffel symbols of ``B``, shape (4, 4).

    ``c_ij = sum_k (dB_ij/dq_k + dB_ik/dq_j - dB_jk/dq_i) qd_k / 2``, which makes ``Bdot - 2C`` skew-symmetric.

    >>> float(abs(coriolis([0, 1.0, 0.5, 0], [0, 0, 0, 0])[0, 0]))   # C vanishes at rest
    0.0
    """
    out = np.empty((4, 4))
    q, qd = _config(q), _vec(qd, "qd")
    coriolis_kernel(q, qd, dynamic_array(p), out)
    return check_finite_result(out, "C(q, qd)", qd=qd)


def gravity(q, p: ScaraParams | None = None) -> np.ndarray:
    """Gravity torques ``g(q) = dU/dq = [0, 0, -m3 g0, 0]`` (N m, N m, N, N m), shape (4,).

    >>> gravity([0, 0, 0.5, 0], ScaraParams().with_payload(5.0))
    array([   0.  ,    0.  , -147.15,    0.  ])
    """
    p = ScaraParams.resolve(p)
    out = np.empty(4)
    gravity_kernel(_config(q), dynamic_array(p), out)
    return check_finite_result(out, "g(q)", m3=p.m3, g0=p.g0)


def friction(p: ScaraParams | None = None) -> np.ndarray:
    """Viscous friction matrix ``F = diag(k_ri^2 F_mi)`` at the joints (chapter 5), shape (4, 4).

    >>> np.diag(friction()).tolist()
    [5e-05, 5e-05, 25.0, 2.0]
    """
    return np.diag(ScaraParams.resolve(p).F)


def inverse_dynamics(q, qd, qdd, p: ScaraParams | None = None) -> np.ndarray:
    """Joint torques ``tau = B(q) qdd + C(q, qd) qd + F qd + g(q)``: the model of chapter 5.

    ``q``, ``qd``, ``qdd`` have shape (4,) or all (N, 4) (a time series; the result then has shape (N, 4)).
    """
    dp = dynamic_array(p)
    q = _config(q, allow_batch=True)
    qd = as_array(qd, "qd", (4,), allow_batch=True)
    qdd = as_array(qdd, "qdd", (4,), allow_batch=True)
    if not (q.shape == qd.shape == qdd.shape):
        raise ShapeError(f"q, qd and qdd must have the same shape, got {q.shape}, {qd.shape}, {qdd.shape}")
    work = dynamics_workspace()
    # a trajectory's own series are read-only, which numba types apart: copied, they meet the kernels compiled for
    # every other caller (the operational-space law) instead of compiling them once more
    q, qd, qdd = (a if a.flags.writeable else a.copy() for a in (np.ascontiguousarray(a) for a in (q, qd, qdd)))
    if q.ndim == 1:
        out = np.empty(4)
        inverse_dynamics_kernel(q, qd, qdd, dp, work, out)
    else:
        out = np.empty_like(q)
        _inverse_dynamics_batch(q, qd, qdd, dp, work, out)
    return check_finite_result(out, "tau = B qdd + C qd + F qd + g", q=q, qd=qd, qdd=qdd)


@kernel
def _inverse_dynamics_batch(q, qd, qdd, dp, work, out):
    for k in range(q.shape[0]):
        inverse_dynamics_kernel(q[k], qd[k], qdd[k], dp, work, out[k])


def forward_dynamics(q, qd, tau, p: ScaraParams | None = None) -> np.ndarray:
    """Joint accelerations ``qdd = B(q)^-1 (tau - C(q, qd) qd - F qd - g(q))``, shape (4,).

    Solved with a 4x4 Cholesky factorisation of ``B``. Raises :class:`~scara.ShapeError` /
    :class:`~scara.NonFiniteError` for bad inputs and :class:`~scara.UnstableError` if ``B`` is not
    positive definite (only possible with non-physical parameters).

    >>> bool(np.abs(forward_dynamics([0, 1.0, 0.5, 0], [0, 0, 0, 0], [0, 0, -98.1, 0])).max() < 1e-12)   # quill held
    True
    """
    out = np.empty(4)
    q, qd, tau = _config(q), _vec(qd, "qd"), _vec(tau, "tau")
    code = forward_dynamics_kernel(q, qd, tau, dynamic_array(p), dynamics_workspace(), out)
    if code:
        raise UnstableError(_singular_inertia_message(q, p))
    return check_finite_result(out, "qdd = B^-1 (tau - C qd - F qd - g)", q=q, qd=qd, tau=tau)


#: the fields of :class:`~scara.ScaraParams` that give joint i inertia of its own (its diagonal entry of ``B``
#: beyond what the joints after it add): joint 3 moves the quill and payload, joint 4 the link 4 and its rotor
_JOINT_INERTIA_FIELDS = (
    "I_l1, m_l1 l1^2, k_r1^2 I_m1 (link 1 and its rotor)",
    "I_l2, m_l2 l2^2, m3 a2^2, k_r2^2 I_m2 (link 2, the quill it carries and its rotor)",
    "m_l3 + m_L, k_r3^2 I_m3 (the quill, the payload and rotor 3)",
    "I_l4, k_r4^2 I_m4 (link 4 and its rotor)",
)


def _singular_inertia_message(q, p) -> str:
    """Why ``B(q)`` is not positive definite: the first joint whose pivot of the Cholesky factorisation is not
    positive (it has no inertia of its own), with the fields that would give it some."""
    B = inertia(q, p)
    j = 3
    for k in range(1, 5):
        if not np.linalg.eigvalsh(B[:k, :k]).min() > 0.0:
            j = k - 1
            break
    return (f"B(q) at q = {np.round(q, 6).tolist()} is not positive definite: joint {j + 1} has no inertia of its own "
            f"(B{j + 1}{j + 1} = {B[j, j]:.6g}), so qdd = B^-1 (tau - C qd - F qd - g) does not exist; "
            f"{_JOINT_INERTIA_FIELDS[j]} must not all be 0")


def regressor(q, qd, qd_r, qdd_r, p: ScaraParams | None = None) -> np.ndarray:
    """Regressor ``Y(q, qd, qd_r, qdd_r)``, shape (4, 13), with ``Y pi = B qdd_r + C(q, qd) qd_r + F qd_r + g``.

    ``pi = dynamic_parameters(p)``; the columns follow :data:`PI_NAMES`; column 0 multiplies the lumped mass
    ``m3 = m_l3 + m_L`` on the joint-3/4 axis. Only the geometry ``a1, a2`` and ``g0`` of ``p`` are used
    (they are known to a controller; the masses and inertias are in ``pi``).

    >>> Y = regressor([0, 1, 0.5, 0], [0.1, 0.2, 0, 0], [0.1, 0.2, 0, 0], [1, 2, 3, 4])
    >>> bool(np.allclose(Y @ dynamic_parameters(), inverse_dynamics([0, 1, 0.5, 0], [0.1, 0.2, 0, 0], [1, 2, 3, 4])))
    True
    """
    out = np.empty((4, N_PI))
    q, qd, qd_r, qdd_r = _config(q), _vec(qd, "qd"), _vec(qd_r, "qd_r"), _vec(qdd_r, "qdd_r")
    regressor_kernel(q, qd, qd_r, qdd_r, dynamic_array(p), out)
    return check_finite_result(out, "Y(q, qd, qd_r, qdd_r)", qd=qd, qd_r=qd_r, qdd_r=qdd_r)


def dynamic_parameters(p: ScaraParams | None = None) -> np.ndarray:
    """The parameter vector ``pi`` (13,) of :data:`PI_NAMES` for ``p`` (units :data:`PI_UNITS`).

    ``pi[0] = m3 = m_l3 + m_L`` so that a payload estimate is ``pi_hat[0] - m_l3``
    (:func:`payload_from_pi`).

    >>> float(dynamic_parameters(ScaraParams().with_payload(5.0))[0])
    15.0
    """
    out = np.empty(N_PI)
    pi_kernel(dynamic_array(p), out)
    return out


def payload_from_pi(pi, base: ScaraParams | None = None) -> float | np.ndarray:
    """Payload mass ``m_L = pi[0] - m_l3`` (kg) read from a parameter vector (13,) or a series (N, 13)."""
    base = ScaraParams.resolve(base)
    pi = as_array(pi, "pi", (N_PI,), allow_batch=True)
    m = pi[..., PI_M3] - base.m_l3
    return float(m) if np.ndim(m) == 0 else m


def params_from_pi(pi, base: ScaraParams | None = None, rtol: float = 1e-9) -> ScaraParams:
    """The parameter object whose ``dynamic_parameters`` is ``pi``, filling in what ``pi`` cannot tell from
    ``base`` (default :class:`ScaraParams()`).

    ``pi`` fixes the lumped combinations of :data:`PI_NAMES`; the physical entries recovered are
    ``m_L = m3 - m_l3``, ``m_l2 = (m_l2 l2) / l2``, ``F_m = F / k_r^2``, ``I_m3 = beta13 / k_r3``,
    ``I_m4`` and ``I_l4`` from ``beta14, beta44`` (needs ``k_r4 != 1``), ``I_m2`` from ``beta22 - beta12``
    (needs ``k_r2 != 1``; otherwise ``base.I_m2`` is kept), ``I_l2`` from ``beta22`` and ``I_l1`` from
    ``beta11``. The geometry, ``m_l1``, ``m_l3``, ``I_m1``, ``k_r`` and ``g0`` come from ``base``.

    Raises :class:`~scara.ScaraError` when ``pi`` is inconsistent with ``base`` (e.g. ``beta33 != k_r3
    beta13``, or ``beta12 != beta22`` while ``k_r2 = 1``) beyond ``rtol``, or gives a negative physical value.

    >>> p = ScaraParams().with_payload(2.5)
    >>> params_from_pi(dynamic_parameters(p)).m_L
    2.5
    """
    base = ScaraParams.resolve(base)
    pi = as_array(pi, "pi", (N_PI,))
    rtol = check_positive(rtol, "rtol")
    m3, m2l2, b11, b12, b22, b13, b33, b14, b44 = (float(v) for v in pi[:9])
    kr = np.asarray(base.k_r)  # every gear ratio is > 0 (ScaraParams refuses 0): I_m = beta / k_r is defined

    def close(a, b, what):
        if abs(a - b) > rtol * max(1.0, abs(a), abs(b)):
            raise ScaraError(f"pi is inconsistent with the base parameters: {what} ({a:.12g} != {b:.12g})")

    I_m3 = b13 / kr[2]
    close(b33, kr[2] ** 2 * I_m3, "beta33 must equal k_r3 * beta13")
    if abs(kr[3] ** 2 - kr[3]) > 1e-12:
        I_m4 = (b44 - b14) / (kr[3] ** 2 - kr[3])
        I_l4 = b14 - kr[3] * I_m4
    else:
        I_m4 = base.I_m[3]
        I_l4 = b14 - kr[3] * I_m4
        close(b44, b14, "beta44 must equal beta14 when k_r4 = 1")
    if abs(kr[1] ** 2 - kr[1]) > 1e-12:
        I_m2 = (b22 - b12) / (kr[1] ** 2 - kr[1])
    else:
        I_m2 = base.I_m[1]
        close(b22, b12, "beta22 must equal beta12 when k_r2 = 1")
    if base.l2 > 0:
        m_l2 = m2l2 / base.l2
    else:  # a centre of mass on joint 2: pi holds m_l2 l2 = 0 and no trace of m_l2
        m_l2 = base.m_l2
        close(m2l2, 0.0, "m_l2 l2 must be 0 when l2 = 0")
    j2 = b22 - I_l4 - kr[1] ** 2 * I_m2 - I_m3 - I_m4
    I_l2 = j2 - m_l2 * base.l2 ** 2
    I_l1 = (b11 - j2 - m_l2 * base.a1 ** 2 - I_l4 - I_m2 - I_m3 - I_m4
            - base.m_l1 * base.l1 ** 2 - kr[0] ** 2 * base.I_m[0])
    F_m = np.asarray(pi[9:13], dtype=float) / kr ** 2
    I_m = (base.I_m[0], I_m2, I_m3, I_m4)
    # tiny negative round-off (e.g. -1e-17) is clipped; real negatives are refused by ScaraParams
    fix = lambda v: 0.0 if -1e-12 < v < 0 else v  # noqa: E731
    try:
        return base.replace(m_L=fix(m3 - base.m_l3), m_l2=fix(m_l2), I_l1=fix(I_l1), I_l2=fix(I_l2),
                            I_l4=fix(I_l4), I_m=tuple(fix(v) for v in I_m), F_m=tuple(fix(v) for v in F_m))
    except ScaraError as exc:
        raise ScaraError(f"pi does not correspond to a physical robot with these base parameters: {exc}") from exc


def kinetic_energy(q, qd, p: ScaraParams | None = None):
    """Kinetic energy ``qd^T B(q) qd / 2`` (J) of links, quill, payload and rotors.

    ``q``, ``qd`` of shape (4,) give a float; (N, 4) series give shape (N,).
    """
    dp = dynamic_array(p)
    q = _config(q, allow_batch=True)
    qd = np.ascontiguousarray(as_array(qd, "qd", (4,), allow_batch=True))
    if q.shape != qd.shape:
        raise ShapeError(f"q and qd must have the same shape, got {q.shape} and {qd.shape}")
    work = dynamics_workspace()
    if q.ndim == 1:
        e = float(kinetic_energy_kernel(q, qd, dp, work))
        return check_finite_result(e, "kinetic energy qd^T B qd / 2", qd=qd)
    out = np.empty(q.shape[0])
    _kinetic_batch(q, qd, dp, work, out)
    return check_finite_result(out, "kinetic energy qd^T B qd / 2", qd=qd)


@kernel
def _kinetic_batch(q, qd, dp, work, out):
    for k in range(q.shape[0]):
        out[k] = kinetic_energy_kernel(q[k], qd[k], dp, work)


def potential_energy(q, p: ScaraParams | None = None):
    """Gravitational potential energy ``U(q)`` (J) of chapter 5, zero at the base-frame floor; shape (4,) gives
    a float, (N, 4) gives (N,)."""
    dp = dynamic_array(p)
    q = _config(q, allow_batch=True)
    if q.ndim == 1:
        u = float(potential_energy_kernel(q, dp))
    else:
        u = np.empty(len(q))
        _potential_batch(q, dp, u)
    return check_finite_result(u, "potential energy U(q)", d3=q[..., 2])


def total_energy(q, qd, p: ScaraParams | None = None):
    """Total energy (J), kinetic plus potential: :func:`kinetic_energy` plus :func:`potential_energy`."""
    with np.errstate(over="ignore", invalid="ignore"):
        e = kinetic_energy(q, qd, p) + potential_energy(q, p)
    return check_finite_result(e, "total energy T + U", q=q, qd=qd)


#: the terms of :func:`torque_breakdown`, in display order
TORQUE_TERMS = ("links", "rotors", "payload", "coriolis", "friction", "gravity")


def _split_robots(p) -> tuple:
    """The three robots whose differences split the model into links, rotors and payload: ``p`` without rotors
    and payload (links and quill alone), ``p`` without payload, and ``p`` itself."""
    p = ScaraParams.resolve(p)
    bare = p.replace(m_L=0.0)
    return bare.replace(I_m=(0.0, 0.0, 0.0, 0.0)), bare, p


def inertia_split(q, p: ScaraParams | None = None) -> dict:
    """``B(q)`` (chapter 5) split into what carries it: a dict of (4, 4) matrices whose sum is :func:`inertia`:

    * ``links``: the inertia of links and quill alone (rotors and payload removed);
    * ``rotors``: what the rotors add, the reflected inertia ``k_r^2 I_m`` and their coupling with the links
      that carry them (a constant matrix);
    * ``payload``: what the payload ``m_L`` adds.

    The same split gives the inertial terms of :func:`torque_breakdown`.

    >>> parts = inertia_split([0, 0, 0.5, 0], ScaraParams().with_payload(5.0))
    >>> [round(float(parts[k][2, 2]), 6) for k in ("links", "rotors", "payload")]   # B33 = m_l3 + k_r3^2 I_m3 + m_L
    [10.0, 12.5, 5.0]
    """
    links_only, bare, p = _split_robots(p)
    B_links, B_bare, B = inertia(q, links_only), inertia(q, bare), inertia(q, p)
    return {"links": B_links, "rotors": B_bare - B_links, "payload": B - B_bare}


def torque_breakdown(q, qd, qdd, p: ScaraParams | None = None) -> dict:
    """Split the joint torque ``tau = B qdd + C qd + F qd + g`` along a motion into physical contributions.

    Returns a dict of (N, 4) arrays (or (4,) for a single state) whose sum is :func:`inverse_dynamics`:

    * ``links``: ``B_0 qdd`` with ``B_0`` the inertia of links and quill alone (rotors and payload removed);
    * ``rotors``: ``(B - B_no rotors) qdd``, the reflected rotor inertia ``k_r^2 I_m`` and the rotors' coupling
      with the links that carry them (a constant matrix);
    * ``payload``: every term ``m_L`` brings: its inertia, Coriolis and weight;
    * ``coriolis``: ``C qd`` of the robot without payload; ``friction``: ``F qd``; ``gravity``: ``g`` of the
      robot without payload (the quill's weight, on joint 3 only).
    """
    links_only, bare, p = _split_robots(p)
    q = as_array(q, "q", (4,), allow_batch=True)
    qd = as_array(qd, "qd", (4,), allow_batch=True)
    qdd = as_array(qdd, "qdd", (4,), allow_batch=True)
    if not (q.shape == qd.shape == qdd.shape):
        raise ShapeError(f"q, qd and qdd must have the same shape, got {q.shape}, {qd.shape}, {qdd.shape}")
    zero = np.zeros_like(q)
    links = inverse_dynamics(q, zero, qdd, links_only.replace(F_m=(0.0,) * 4, g0=0.0))
    with_rotors = inverse_dynamics(q, zero, qdd, bare.replace(F_m=(0.0,) * 4, g0=0.0))
    coriolis_only = inverse_dynamics(q, qd, zero, bare.replace(F_m=(0.0,) * 4, g0=0.0))
    total_bare = inverse_dynamics(q, qd, qdd, bare)
    total = inverse_dynamics(q, qd, qdd, p)
    fr = np.asarray(p.F) * qd
    grav = inverse_dynamics(q, zero, zero, bare.replace(F_m=(0.0,) * 4))  # g(q): tau at rest, no acceleration
    return {"links": links, "rotors": with_rotors - links, "payload": total - total_bare,
            "coriolis": coriolis_only, "friction": fr, "gravity": grav}
