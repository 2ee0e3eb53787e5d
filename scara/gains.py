"""One check for every gain the package accepts: CLIK's ``K``, ``K_P``, ``K_D`` (chapter 4), the controllers'
gains and bounds (chapter 6) and the PD gains of the simulation engine's worked example (chapter 5).

A diagonal gain may be given as a number (the same gain for every component), a vector or a diagonal matrix; it
is returned as a fresh float vector. Two rules, one per kind of gain:

* ``"positive"``: every entry ``> 0``. The gains that make an error decay (``K`` of the CLIK laws (4.5),
  (4.14), ``K_P``, ``K_D``, ``Lambda`` of chapter 6) and the bounds a run must respect: a zero gain leaves a
  component uncorrected, a negative one drives it away.
* ``"nonnegative"``: every entry ``>= 0``. The gains of the worked PD example of chapter 5, where a zero gain
  switches a term off on purpose (a negative one still destabilises the loop).
"""
from __future__ import annotations

import numpy as np

from .errors import ScaraError, ShapeError, _numeric_objects, is_bool

__all__ = ["gain_vector", "RULES"]

#: the rule of each kind of gain, and what it demands of every entry
RULES = {"positive": "> 0", "nonnegative": ">= 0"}


def gain_vector(value, name: str, n: int = 4, *, default=None, rule: str = "positive", labels=None,
                allow_inf: bool = False) -> np.ndarray:
    """``value`` as a fresh (n,) float vector of diagonal gains, checked by ``rule`` (see the module).

    Parameters
    ----------
    value : a number, a vector of ``n`` numbers or a diagonal ``n x n`` matrix; None takes ``default``.
    name : the gain's name in messages (``"K_P"``).
    labels : optional names of the ``n`` entries (``("x", "y", "z", "phi")``): a message then says "its z entry"
        rather than ``K_P[2]``.
    allow_inf : accept ``inf`` entries (an adaptation weight that freezes a parameter).

    Raises :class:`~scara.ShapeError` for another shape, a matrix with off-diagonal entries or a value that is not
    numeric, and :class:`~scara.ScaraError` naming the first entry that is not finite or breaks the rule.
    """
    if rule not in RULES:
        raise ScaraError(f"rule = {rule!r} is not a gain rule; use one of {sorted(RULES)}")
    if value is None:
        value = default
    what = f"{name} must be a number, a vector of {n} numbers or a diagonal {n}x{n} matrix"
    if value is None or isinstance(value, (str, bytes)) or is_bool(value):
        raise ShapeError(f"{what}, got {value!r}")
    try:
        raw = np.asarray(value)
        if raw.dtype.kind not in "iuf" and not _numeric_objects(raw):  # booleans, strings: not gains
            raise TypeError("not numbers")
        arr = np.array(raw, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:
        raise ShapeError(f"{what}, got {value!r}") from exc
    if arr.ndim == 0:
        arr = np.full(n, float(arr))
    elif arr.ndim == 2 and arr.shape == (n, n):
        off = arr - np.diag(np.diag(arr))
        if np.any(off != 0):
            raise ShapeError(f"{name} must be diagonal (one gain per component); its largest off-diagonal entry "
                             f"is {np.max(np.abs(off)):g}")
        arr = np.diag(arr).copy()
    if arr.shape != (n,):
        raise ShapeError(f"{what}, got shape {arr.shape}")

    def entry(i):
        return f"its {labels[i]} entry is {arr[i]:g}" if labels else f"{name}[{i}] = {arr[i]:g}"

    bad = np.isnan(arr) if allow_inf else ~np.isfinite(arr)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ScaraError(f"{name} must be finite: {entry(i)}")
    low = arr <= 0 if rule == "positive" else arr < 0
    if np.any(low):
        i = int(np.argmax(low))
        kind = "positive definite" if rule == "positive" else "positive semi-definite"
        raise ScaraError(f"{name} must be {kind}: {entry(i)} (every entry must be {RULES[rule]})")
    return arr
