"""The discrete-time stability limits of the CLIK (Euler's rule at the sampling period ``dt``), checked before a
run: ``dt K < 2`` for the inverse and the pseudo-inverse (4.6) and ``dt k0 |d^2 w_0 / d theta2^2| < 2`` for the
null-space term (4.14), ``dt mu_max < 2`` along the reference for the transpose (4.12), and Jury's test on the
characteristic polynomial (4.19) of the second-order law."""
from __future__ import annotations

import numpy as np

from ..errors import UnstableError, check_finite_result
from .kernels import (CHECK_GAIN, CHECK_K0, CHECK_TRANSPOSE, CHECK_TRANSPOSE_NONFINITE, RES_COMPONENT, RES_HIGH,
                      RES_K0_LIMIT, RES_KD, RES_KP, RES_LIMIT, RES_LOW, RES_MU_MAX, RES_RHO, RES_SCALE, RES_SIZE,
                      RES_WORST, _first_order_check, _second_order_check, _transpose_rate_kernel)
from .records import COMPONENTS
from .result import TransposeStability


def _transpose_margin(t, x, dt, K, p, elbow: int) -> TransposeStability:
    """The :class:`TransposeStability` (4.12) of the checked reference ``t`` (N,), ``x`` (N, 4) sampled every
    ``dt``, for the gains ``K`` (4,) at the inverse-kinematics configurations of ``elbow``."""
    mu = np.empty(len(t))
    _transpose_rate_kernel(x, K, p.a1, p.a2, float(elbow), mu)
    check_finite_result(mu, "largest eigenvalue mu of J_A J_A^T K", K=K)
    k = int(np.argmax(mu))
    limit = 2.0 / dt
    return TransposeStability(t, mu, float(mu[k]), float(t[k]), limit, float(limit / mu[k]))


def _gain_limit_text(component: str, method: str) -> str:
    """The refusal of a gain past (4.6), as a template with the fields ``K_bad`` (the gain) and ``K_limit``
    (``2 / dt``)."""
    return (f"K[{component}] = {{K_bad:g}} is past the discrete-time stability limit of the {method} CLIK: Euler's "
            "step gives e_(k+1) = (1 - dt K) e_k, stable only for K < 2 / dt = {K_limit:g} 1/s")


def _k0_limit_text(objective: str) -> str:
    """The refusal of a null-space gain past (4.14), as a template with the fields ``k0_value`` and
    ``k0_limit``."""
    return ("k0 = {k0_value:g} is past the null-space stability limit: the gradient step on theta2 needs "
            f"dt k0 |d^2 w_0/d theta2^2| < 2, i.e. k0 < {{k0_limit:g}} for objective {objective!r}")


#: the refusal of transpose gains past (4.12), a template with the fields ``Kx``, ``Ky``, ``Kz``, ``Kphi`` (the
#: gains), ``mu_max``, ``t_worst``, ``K_limit`` (``2 / dt``) and ``scale_limit``
TRANSPOSE_LIMIT_TEXT = (
    "K = [{Kx:.5g}, {Ky:.5g}, {Kz:.5g}, {Kphi:.5g}] is past the discrete-time stability limit of the transpose "
    "CLIK: along the reference the largest eigenvalue of J J^T K reaches {mu_max:.5g} 1/s (t = {t_worst:.3f} s), "
    "but Euler's step needs it below 2 / dt = {K_limit:g} 1/s; scale K by less than {scale_limit:.5g}")


def _jury_text(component: str) -> str:
    """The refusal of second-order gains past Jury's test of (4.19), as a template with the fields ``KP_bad``,
    ``KD_bad``, ``rho`` (the largest pole modulus), ``jury_low`` and ``jury_high`` (the bounds of ``K_D``)."""
    return (f"K_P[{component}] = {{KP_bad:g}}, K_D[{component}] = {{KD_bad:g}} are past the discrete-time stability "
            "limit of the second-order CLIK: Euler's step puts a pole at |z| = {rho:.4g} >= 1; it needs "
            "dt K_P < K_D < 2 / dt + dt K_P / 2 (here {jury_low:g} < {KD_bad:g} < {jury_high:g} fails)")


def _check_first_order_stability(method, law, objective, t, x_d, q_start, p):
    """Refuse gains past the discrete-time stability limits: ``dt K < 2`` for the inverse and pseudo-inverse
    (4.6), ``dt k0 |d^2 w_0 / d theta2^2| < 2`` for the null-space term (4.14), and (4.12) for the transpose, on
    the elbow of the start ``q_start`` (the checks of :func:`~.kernels._first_order_check`)."""
    K, dt = law.K, law.dt
    res = np.zeros(RES_SIZE)
    code = _first_order_check(law.method, K, law.keep, dt, law.k0, law.objective, x_d, p.a1, p.a2,
                              float(q_start[1]), res)
    if code == CHECK_GAIN:
        i = int(res[RES_COMPONENT])
        raise UnstableError(_gain_limit_text(COMPONENTS[i], method).format(K_bad=K[i], K_limit=res[RES_LIMIT]))
    if code == CHECK_K0:
        raise UnstableError(_k0_limit_text(objective).format(k0_value=law.k0, k0_limit=res[RES_K0_LIMIT]))
    if code == CHECK_TRANSPOSE_NONFINITE:
        check_finite_result(res[RES_MU_MAX], "largest eigenvalue mu of J_A J_A^T K", K=K)
    if code == CHECK_TRANSPOSE:
        raise UnstableError(TRANSPOSE_LIMIT_TEXT.format(
            Kx=K[0], Ky=K[1], Kz=K[2], Kphi=K[3], mu_max=res[RES_MU_MAX], t_worst=float(t[int(res[RES_WORST])]),
            K_limit=res[RES_LIMIT], scale_limit=res[RES_SCALE]))


def _check_second_order_stability(K_P, K_D, dt):
    """Refuse gains that put a discrete pole of (4.19) on or outside the unit circle (Jury's test,
    :func:`~.kernels._second_order_check`)."""
    res = np.zeros(RES_SIZE)
    i = _second_order_check(np.ascontiguousarray(K_P, float), np.ascontiguousarray(K_D, float), float(dt), res)
    if i >= 0:
        raise UnstableError(_jury_text(COMPONENTS[i]).format(KP_bad=res[RES_KP], KD_bad=res[RES_KD], rho=res[RES_RHO],
                                                            jury_low=res[RES_LOW], jury_high=res[RES_HIGH]))
