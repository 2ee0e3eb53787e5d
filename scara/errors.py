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
    "check_number",
    "check_positive",
    "is_bool",
    "check_count",
    "check_flag",
    "check_index",
    "check_angles",
    "check_finite_result",
    "MAX_ANGLE",
]

#: largest joint angle (rad) the package accepts in a configuration: beyond it ``sin`` and ``cos`` of the angle
#: keep no significant digit of the motion (the spacing of doubles near 1e6 rad is about 1e-10 rad, near 1e16 rad
#: it exceeds 2 pi), so such an angle is refused rather than turned into a meaningless pose
MAX_ANGLE = 1e6


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
    arr = _numbers(value, f"{name} must be an array of numbers", ShapeError)
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


def _numbers(value, what: str, error=ScaraError) -> np.ndarray:
    """``value`` as a float array if it holds real numbers only (no strings, booleans or other objects); else
    ``error(f"{what}, got {value!r}")``. Shape and finiteness are the caller's to check."""
    try:
        raw = np.asarray(value)
        if isinstance(value, (str, bytes)) or (raw.dtype.kind in "bUSO" and not _numeric_objects(raw)):
            raise TypeError("not numbers")
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:
        raise error(f"{what}, got {value!r}") from exc


def _numeric_objects(arr: np.ndarray) -> bool:
    """True for an object array whose entries are all real numbers (not booleans, not strings)."""
    if arr.dtype.kind != "O":
        return False
    return all(isinstance(v, (int, float, np.integer, np.floating)) and not is_bool(v)
               for v in arr.ravel())


def as_vector(value, name: str, n: int = 4) -> np.ndarray:
    """Return ``value`` as a finite float vector of shape ``(n,)`` (see :func:`as_array`)."""
    return as_array(value, name, (n,))


def check_number(value, name: str, what: str = "a number", unit: str = "") -> float:
    """Return ``value`` as a float after checking it is one finite real number: a bool, a string, an array or
    anything ``float`` refuses raises :class:`ScaraError` ("``name`` must be ``what`` (in ``unit``), got ..."),
    NaN or inf :class:`NonFiniteError`."""
    if unit:
        what = f"{what} (in {unit})"
    if is_bool(value) or isinstance(value, (str, bytes)) or np.ndim(value) != 0:
        raise ScaraError(f"{name} must be {what}, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError) as exc:
        raise ScaraError(f"{name} must be {what}, got {value!r}") from exc
    if not np.isfinite(v):
        raise NonFiniteError(f"{name} = {v} is not finite")
    return v


def check_positive(value, name: str, strict: bool = True) -> float:
    """Return ``value`` as a float after checking it is finite (:func:`check_number`) and positive (or
    non-negative)."""
    v = check_number(value, name)
    if (strict and v <= 0) or (not strict and v < 0):
        raise ScaraError(f"{name} = {v} must be {'> 0' if strict else '>= 0'}")
    return v


def is_bool(value) -> bool:
    """True for ``True``/``False`` and NumPy's bools: the one test of "is this a bool?" (a bool is an ``int`` to
    Python, so every check of a number or a count refuses it first, rather than reading ``True`` as 1)."""
    return isinstance(value, (bool, np.bool_))


def check_count(value, name: str, low: int, high: int, what: str = "", why: str = "") -> int:
    """Return ``value`` as an int after checking it is an integer (not a bool, not a float, not a string) with
    ``low <= value <= high``: the sizes of grids, sample counts, steps, bounded so that no call starts an unbounded
    amount of work. ``what`` says what the count counts and ``why`` where the upper limit comes from (both for the
    message, which names the value and the range).

    >>> check_count(36, "steps", 1, 121, "slider steps")
    36
    """
    unit = f" {what}" if what else ""
    if is_bool(value) or not isinstance(value, (int, np.integer)):
        raise ScaraError(f"{name} = {value!r:.80} must be a whole number (an int) of{unit or ' items'}, between {low} "
                         f"and {high}")
    n = int(value)
    if not low <= n <= high:
        reason = f" ({why})" if why else ""
        raise ScaraError(f"{name} = {n}{unit} is outside the allowed range {low} <= {name} <= {high}{reason}")
    return n


def check_flag(value, name: str) -> bool:
    """Return ``value`` as a bool after checking it is one (``True``/``False``, or a NumPy bool): a string such
    as ``"no"`` is refused rather than read as true."""
    if not is_bool(value):
        raise ScaraError(f"{name} = {value!r:.80} must be True or False (a bool), got {type(value).__name__}")
    return bool(value)


def check_index(value, name: str, size: int) -> int:
    """Return ``value`` as an int after checking it is an integer index ``0 <= value < size`` (not a bool, not a
    float such as 0.7, which would silently truncate)."""
    if is_bool(value) or not isinstance(value, (int, np.integer)):
        raise ScaraError(f"{name} = {value!r} must be an integer index 0..{size - 1}")
    i = int(value)
    if not 0 <= i < size:
        raise ScaraError(f"{name} = {i} is out of range: it must lie in 0..{size - 1}")
    return i


def check_angles(q: np.ndarray, name: str = "q", columns=(0, 1, 3)) -> np.ndarray:
    """Return the (finite) configuration ``q`` (shape (4,) or (N, 4)) after checking its revolute joints
    (``columns``) stay within :data:`MAX_ANGLE` rad; raises :class:`ScaraError` naming the first entry beyond."""
    a = np.abs(q[..., list(columns)])
    if a.size and a.max() > MAX_ANGLE:
        flat = int(np.argmax(a))
        idx = np.unravel_index(flat, a.shape)
        col = columns[idx[-1]]
        where = f"{name}[{col}]" if q.ndim == 1 else f"{name}[{idx[0]}, {col}]"
        raise ScaraError(f"{where} = {q[idx[:-1] + (col,)]:.6g} rad is beyond the largest angle the package accepts, "
                         f"|theta| <= MAX_ANGLE = {MAX_ANGLE:g} rad (beyond it sin and cos lose all precision); "
                         f"reduce the angle modulo 2 pi")
    return q


def check_finite_result(result, what: str, **inputs):
    """Return ``result`` after checking every entry is finite; otherwise raise :class:`NonFiniteError` naming
    the input (among the keyword ``inputs``) with the largest entry, which made the arithmetic overflow:
    ``"qd = [...] gives a non-finite C(q, qd) qd: the inputs are too large ..."``."""
    arr = np.asarray(result, dtype=float)
    if np.all(np.isfinite(arr)):
        return result
    name, worst = None, -1.0
    for k, v in inputs.items():
        m = float(np.max(np.abs(np.asarray(v, dtype=float)))) if np.size(v) else 0.0
        if m > worst:
            name, worst = k, m
    if name is None:
        raise NonFiniteError(f"{what} is not finite")
    shown = np.array2string(np.asarray(inputs[name], dtype=float), precision=4, threshold=12)
    raise NonFiniteError(f"{name} = {shown} gives a non-finite {what}: {name} is too large (an entry of "
                         f"magnitude {worst:.4g}) and the result overflows; every result must be finite")
