"""Thinning a long run to the samples a figure draws, as kernels (the arithmetic of
:func:`scara.plots._common.envelope` and :func:`~scara.plots._common.thin`): the page programs of the CLIK and the
controllers panels draw through them, in Jupyter and in the page."""
from __future__ import annotations

import math

from .._compile import kernel

__all__ = ["LOG_FLOOR", "envelope_length", "thin_length", "envelope_kernel", "thin_index", "thin_kernel"]

#: A log axis's floor: the envelope draws exact zeros there
LOG_FLOOR = 1e-12


# --------------------------------------------------------------------------------------------------
@kernel(light=True)
def envelope_length(n, points):
    """The number of samples :func:`envelope_kernel` gives for ``n`` samples thinned to about ``points``."""
    if n <= points:
        return n
    size = int(math.ceil(n / points))
    m = n // size
    return m + 1 if m * size < n else m


@kernel(light=True)
def thin_length(n, points):
    """The number of samples :func:`thin_kernel` gives: ``min(n, points)`` (the rounded, evenly spaced indices
    of more samples than points never repeat, as they are more than one apart)."""
    return n if n <= points else points


@kernel
def envelope_kernel(t, y, points, tt, yy):
    """The upper envelope of ``|y|`` (N,) over ``ceil(N / points)``-sample blocks, written into ``tt`` and ``yy``
    (their first :func:`envelope_length` entries, returned): each block's largest value, floored at
    :data:`LOG_FLOOR` for a log axis, at the middle of the block (the last, shorter block at ``t[-1]``), so that
    thinning a long run loses no peak. With ``N <= points``, ``|y|`` itself."""
    n = t.shape[0]
    if n <= points:
        for k in range(n):
            tt[k] = t[k]
            yy[k] = max(abs(y[k]), LOG_FLOOR)
        return n
    size = int(math.ceil(n / points))
    m = n // size
    half = 0.5 * size * (t[1] - t[0])
    for j in range(m):
        top = abs(y[j * size])
        for k in range(j * size + 1, (j + 1) * size):
            v = abs(y[k])
            if v > top:
                top = v
        tt[j] = t[j * size] + half
        yy[j] = max(top, LOG_FLOOR)
    if m * size < n:
        top = abs(y[m * size])
        for k in range(m * size + 1, n):
            v = abs(y[k])
            if v > top:
                top = v
        tt[m] = t[n - 1]
        yy[m] = max(top, LOG_FLOOR)
        return m + 1
    return m


@kernel
def _round_half_even(v):
    """``v`` (>= 0) rounded to the nearest integer, a half to the even one (numpy's ``round``)."""
    f = math.floor(v)
    d = v - f
    r = int(f)
    if d > 0.5 or (d == 0.5 and r % 2 == 1):
        return r + 1
    return r


@kernel
def thin_index(n, points, j):
    """The index of the ``j``-th kept sample of ``n``: about ``points`` evenly spaced samples, the first and the last
    included, as :func:`scara.plots._common.thin` (``round(linspace(0, n - 1, points))``, rounding a half to even;
    with ``n > points`` the spacing is above 1, so no index repeats)."""
    if n <= points:
        return j
    if j == points - 1:
        return n - 1
    step = (n - 1) / (points - 1)
    return _round_half_even(j * step)


@kernel
def thin_kernel(t, y, points, tt, yy):
    """``t`` and ``y`` (N,) at about ``points`` evenly spaced samples, first and last included (indices
    ``round(i (N - 1) / (points - 1))``), written into ``tt`` and ``yy``; returns their number
    (:func:`thin_length`)."""
    n = t.shape[0]
    if n <= points:
        for k in range(n):
            tt[k] = t[k]
            yy[k] = y[k]
        return n
    for i in range(points):
        k = thin_index(n, points, i)
        tt[i] = t[k]
        yy[i] = y[k]
    return points
