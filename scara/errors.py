"""The package's exceptions and the input checks that raise them.

Every exception is a :class:`ScaraError`, itself a :class:`ValueError`, so ``except ValueError`` catches
them all. Messages name the offending value and the limit it breaks.
"""
from __future__ import annotations

import numpy as np

__all__ = [
    "ScaraError",
    "ShapeError",
    "NonFiniteError",
    "UnreachableError",
    "UnstableError",
    "as_array",
    "as_vector",
    "check_positive",
]


class ScaraError(ValueError):
    """Base class of every error raised by :mod:`scara` for bad input or a failed computation."""


class ShapeError(ScaraError):
    """An array has the wrong shape (the message gives the expected and the received shape)."""


class NonFiniteError(ScaraError):
    """An input holds NaN or an infinity (the message names the first offending entry)."""


class UnreachableError(ScaraError):
    """A point lies outside the workspace: outside the annulus of the arm or the stroke of ``d3``."""


class UnstableError(ScaraError):
    """A setting is unstable, or a run diverged (the message gives the time and the cause)."""


def as_array(value, name: str, trailing: tuple[int, ...], allow_batch: bool = False) -> np.ndarray:
    """Return ``value`` as a finite float array whose last axes are ``trailing``.

    With ``allow_batch`` one extra leading axis is accepted (a time series of shape ``(N, *trailing)``).
    Raises :class:`ShapeError` for another shape and :class:`NonFiniteError` for NaN or inf.
    """
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ShapeError(f"{name} must be an array of numbers, got {value!r}") from exc
    nd = len(trailing)
    ok = arr.shape == trailing or (allow_batch and arr.ndim == nd + 1 and arr.shape[1:] == trailing)
    if not ok:
        want = f"{trailing}" + (f" or (N, {', '.join(map(str, trailing))})" if allow_batch else "")
        raise ShapeError(f"{name} must have shape {want}, got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        idx = tuple(int(i) for i in np.argwhere(~np.isfinite(arr))[0])
        where = idx[0] if len(idx) == 1 else idx
        raise NonFiniteError(f"{name}[{where}] = {arr[idx]} is not finite; every entry of {name} must be a finite number")
    return arr


def as_vector(value, name: str, n: int = 4) -> np.ndarray:
    """Return ``value`` as a finite float vector of shape ``(n,)`` (see :func:`as_array`)."""
    return as_array(value, name, (n,))


def check_positive(value, name: str, strict: bool = True) -> float:
    """Return ``value`` as a float after checking it is finite and positive (or non-negative)."""
    try:
        v = float(value)
    except (TypeError, ValueError) as exc:
        raise ScaraError(f"{name} must be a number, got {value!r}") from exc
    if not np.isfinite(v):
        raise NonFiniteError(f"{name} = {v} is not finite")
    if (strict and v <= 0) or (not strict and v < 0):
        raise ScaraError(f"{name} = {v} must be {'> 0' if strict else '>= 0'}")
    return v
