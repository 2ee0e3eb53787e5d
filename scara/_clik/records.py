"""The constants and the named records of the CLIK loops, each declared once and built by one packer.

A compiled loop takes its data as records: the reference it tracks (:class:`Reference`), the law's settings
(:class:`FirstOrderLaw` for (4.4), (4.8), (4.13), (4.15); :class:`SecondOrderLaw` for (4.16)) and the arrays it
fills (:class:`Series`); the arm's lengths come as :class:`~scara.kinematics.Geometry`. It reports how it ended
with the ``STATUS_*`` codes. The packers (:func:`_reference`, :func:`_first_order_law`,
:func:`_second_order_law`, :func:`_series`) are the one place each record is built.
"""
from __future__ import annotations

from collections import namedtuple

import numpy as np

__all__ = ["METHODS", "COMPONENTS", "SEED_K", "MAX_DAMPING_REACH"]

#: the largest damping ``lambda`` of (4.15), as a multiple of the reach ``a1 + a2``: ``damping <= 10 (a1 + a2)``
#: (10 m for the arm of the course). The entries of ``J_A J_A^T`` are at most about ``(a1 + a2)^2``, so a larger
#: ``lambda^2`` only freezes the arm (and ``lambda`` of 1e300 overflows ``lambda^2`` to inf)
MAX_DAMPING_REACH = 10.0

#: the first-order methods of :func:`~scara.clik`
METHODS = ("inverse", "transpose", "pseudoinverse")
#: names of the operational components, in the order of ``x_e``
COMPONENTS = ("x", "y", "z", "phi")
#: the seed gains of chapter 4 for the inverse and transpose methods (1/s for the inverse)
SEED_K = (400.0, 400.0, 400.0, 100.0)
#: dexterity measures the pseudo-inverse's null-space term can climb
OBJECTIVES = ("sin2", "manipulability")

#: codes of the methods and objectives inside the compiled loops
METHOD_INVERSE = 0
METHOD_TRANSPOSE = 1
METHOD_PSEUDOINVERSE = 2
OBJECTIVE_SIN2 = 0
OBJECTIVE_MANIPULABILITY = 1
_METHOD_CODE = {"inverse": METHOD_INVERSE, "transpose": METHOD_TRANSPOSE, "pseudoinverse": METHOD_PSEUDOINVERSE}
_OBJECTIVE_CODE = {"sin2": OBJECTIVE_SIN2, "manipulability": OBJECTIVE_MANIPULABILITY}

#: status codes a compiled loop writes into ``info[0]``
STATUS_DONE = 0
STATUS_NONFINITE = 1
STATUS_ERROR_BOUND = 2
STATUS_SINGULAR = 3
_CAUSES = {
    STATUS_NONFINITE: "a value became NaN or infinite",
    STATUS_ERROR_BOUND: "the tracking error exceeded max_error",
    STATUS_SINGULAR: "the Jacobian became singular",
}
#: Cholesky pivot, or ``|det J_A|`` (m^2) of the closed-form inverse, below which a loop's solve is refused
_SINGULAR_TOL = 1e-12

#: the reference the loop tracks: ``x``, ``xd`` (N, 4) and, for the second-order law, ``xdd`` (N, 4)
Reference = namedtuple("Reference", "x xd xdd")
#: the settings of the first-order laws (4.4), (4.8), (4.13), (4.15)
FirstOrderLaw = namedtuple("FirstOrderLaw", "dt method K keep lam0sq w_thr k0 objective max_err")
#: the settings of the second-order law (4.16)
SecondOrderLaw = namedtuple("SecondOrderLaw", "dt K_P K_D lam0sq w_thr max_err")
#: the arrays a loop fills: ``q, qd, qdd, x, e`` (N, 4) and ``w`` (N,); ``qdd`` is empty for a first-order run
Series = namedtuple("Series", "q qd qdd x e w")

_NO_ROWS = np.empty((0, 4))


def _reference(x_d, xd_d, xdd_d=None) -> Reference:
    """The :class:`Reference` record (``xdd`` empty for a first-order run), its arrays writable: a read-only one
    (a trajectory's own, which it keeps read-only) is copied. numba types a read-only array apart, and the loops
    would otherwise be compiled twice, once for a trajectory's arrays and once for computed ones (the joint
    reference the controllers' page programs compute): the same values, the same results."""
    rows = (x_d, xd_d, _NO_ROWS if xdd_d is None else xdd_d)
    return Reference(*(a if a.flags.writeable else a.copy() for a in rows))


def _first_order_law(dt, method, K, kept, lam2, w_thr, k0, objective, max_err) -> FirstOrderLaw:
    """The :class:`FirstOrderLaw` record from checked settings (``method`` and ``objective`` by name)."""
    return FirstOrderLaw(float(dt), _METHOD_CODE[method], np.ascontiguousarray(K, float),
                         np.ascontiguousarray(kept, float), float(lam2), float(w_thr), float(k0),
                         _OBJECTIVE_CODE[objective], float(max_err))


def _second_order_law(dt, K_P, K_D, lam2, w_thr, max_err) -> SecondOrderLaw:
    """The :class:`SecondOrderLaw` record from checked settings."""
    return SecondOrderLaw(float(dt), np.ascontiguousarray(K_P, float), np.ascontiguousarray(K_D, float),
                          float(lam2), float(w_thr), float(max_err))


def _series(n: int, second_order: bool) -> Series:
    """The :class:`Series` a run fills, as C-contiguous slices of one allocation: a block this large is backed
    by huge pages where the system allows it, which saves thousands of page faults per run."""
    count = 5 if second_order else 4
    buf = np.empty(n * (4 * count + 1))
    q, qd, *rest = [buf[4 * n * i:4 * n * (i + 1)].reshape(n, 4) for i in range(count)]
    qdd = rest.pop(0) if second_order else _NO_ROWS
    x, e = rest
    return Series(q, qd, qdd, x, e, buf[4 * n * count:])
