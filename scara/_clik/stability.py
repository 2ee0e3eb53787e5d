"""The discrete-time stability limits of the CLIK (Euler's rule at the sampling period ``dt``), checked before a
run: ``dt K < 2`` for the inverse and the pseudo-inverse (4.6) and ``dt k0 |d^2 w_0 / d theta2^2| < 2`` for the
null-space term (4.14), ``dt mu_max < 2`` along the reference for the transpose (4.12), and Jury's test on the
characteristic polynomial (4.19) of the second-order law."""
from __future__ import annotations

import numpy as np

from ..errors import UnstableError, check_finite_result
from .kernels import _transpose_check_kernel, _transpose_rate_kernel
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


def _check_first_order_stability(method, law, objective, t, x_d, q_start, p):
    """Refuse gains past the discrete-time stability limits: ``dt K < 2`` for the inverse and pseudo-inverse
    (4.6), ``dt k0 |d^2 w_0 / d theta2^2| < 2`` for the null-space term (4.14), and (4.12) for the transpose, on
    the elbow of the start ``q_start``."""
    K, kept, dt, k0v = law.K, law.keep, law.dt, law.k0
    if method in ("inverse", "pseudoinverse"):
        bad = (K * dt >= 2.0) & (kept > 0)
        if bad.any():
            i = int(np.argmax(bad))
            raise UnstableError(
                f"K[{COMPONENTS[i]}] = {K[i]:g} is past the discrete-time stability limit of the {method} CLIK: "
                f"Euler's step gives e_(k+1) = (1 - dt K) e_k, stable only for K < 2 / dt = {2.0 / dt:g} 1/s")
        if method == "pseudoinverse" and k0v > 0:
            curv = 2.0 if objective == "sin2" else p.a1 * p.a2  # max |d^2 w_0 / d theta2^2|
            k0_lim = 2.0 / (dt * curv)
            if k0v >= k0_lim:
                raise UnstableError(
                    f"k0 = {k0v:g} is past the null-space stability limit: the gradient step on theta2 needs "
                    f"dt k0 |d^2 w_0/d theta2^2| < 2, i.e. k0 < {k0_lim:g} for objective {objective!r}")
        return
    elbow = -1 if q_start[1] < 0 else 1
    if _transpose_check_kernel(x_d, K, p.a1, p.a2, float(elbow), 2.0 / dt) >= 0:
        st = _transpose_margin(t, x_d, dt, K, p, elbow)
        raise UnstableError(
            f"K = [{', '.join(f'{k:.5g}' for k in K)}] is past the discrete-time stability limit of the transpose CLIK: along the "
            f"reference the largest eigenvalue of J J^T K reaches {st.mu_max:.5g} 1/s (t = {st.t_worst:.3f} s), "
            f"but Euler's step needs it below 2 / dt = {st.limit:g} 1/s; scale K by less than "
            f"{st.scale_limit:.5g}")


def _check_second_order_stability(K_P, K_D, dt):
    """Refuse gains that put a discrete pole of (4.19) on or outside the unit circle (Jury's test)."""
    a, b = dt * K_D, dt * dt * K_P
    bad = ~((b < a) & (2 * a - b < 4))
    if bad.any():
        i = int(np.argmax(bad))
        rho = max(abs(z) for z in np.roots([1.0, -(2.0 - a[i]), 1.0 - a[i] + b[i]]))
        raise UnstableError(
            f"K_P[{COMPONENTS[i]}] = {K_P[i]:g}, K_D[{COMPONENTS[i]}] = {K_D[i]:g} are past the discrete-time "
            f"stability limit of the second-order CLIK: Euler's step puts a pole at |z| = {rho:.4g} >= 1; it "
            f"needs dt K_P < K_D < 2 / dt + dt K_P / 2 (here {b[i] / dt:g} < {K_D[i]:g} < {(4 + b[i]) / (2 * dt):g} fails)")
