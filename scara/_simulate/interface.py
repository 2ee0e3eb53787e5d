"""The controller interface of the simulation engine (chapter 5): the signature of a compiled law, the
decorator that makes one, the base class :class:`Controller` and the status codes a run reports.

See the package's docstring (``help(scara.simulate)``) for the arguments of a law.
"""
from __future__ import annotations

import math
import numbers

import numpy as np

from .. import _compile
from ..dynamics import dynamic_array
from ..errors import NonFiniteError, ScaraError, check_positive
from ..params import ScaraParams

__all__ = ["LAW_SIGNATURE", "control_law", "Controller", "OK", "LAW_FAILED", "DIVERGED", "SINGULAR_INERTIA",
           "JOINT_LIMIT"]

#: The status codes of a run, written in ``info[0]`` by the engine's loop. ``OK`` is also what a law returns
#: when all is well (a law's own failure codes are any other integer, e.g. those of :mod:`scara.control`).
#: ``JOINT_LIMIT``: the quill ``d3`` left its stroke ``[d3_min, d3_max]`` (the plant models no end stop).
OK, LAW_FAILED, DIVERGED, SINGULAR_INERTIA, JOINT_LIMIT = 0, 1, 2, 3, 4


# --------------------------------------------------------------------------------------------------
# the checks of the engine's and the controllers' options (private: shared by scara.simulate and scara.control)
# --------------------------------------------------------------------------------------------------
def _count(value, name: str, low: int, high: int, why: str = "") -> int:
    """``value`` as an int after checking it is a whole number (an ``int`` or numpy integer, not a bool, a float
    or a string) with ``low <= value <= high``; :class:`~scara.ScaraError` naming what was asked and the limit
    otherwise (``why`` says where the upper limit comes from)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise ScaraError(f"{name} = {value!r} must be a whole number (an int) between {low} and {high}")
    v = int(value)
    if v < low:
        raise ScaraError(f"{name} = {v} must be >= {low}")
    if v > high:
        raise ScaraError(f"{name} = {v} exceeds its limit {high}" + (f" ({why})" if why else ""))
    return v


def _flag(value, name: str) -> bool:
    """``value`` as a bool after checking it is one (``bool`` or numpy bool): a string such as ``'no'`` or a
    number is refused rather than read by its truth value."""
    if not isinstance(value, (bool, np.bool_)):
        raise ScaraError(f"{name} = {value!r} must be True or False (a bool), got {type(value).__name__}")
    return bool(value)


def _finite_result(value, what: str, inputs: str):
    """``value`` unchanged when every entry is finite; :class:`~scara.NonFiniteError` naming the result and
    the inputs it came from (an overflow of huge but finite inputs) otherwise."""
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise NonFiniteError(f"{what} is not finite ({arr.tolist() if arr.size <= 16 else 'some entries'}): the "
                             f"inputs {inputs} overflow floating point")
    return value


#: The largest number of samples of a run: its series take about 300 bytes per sample (1.5 GB at this
#: limit, 5000 s at 1 ms; the book's longest run has 70 001).
MAX_SAMPLES = 5_000_000


def _sample_count(duration, dt, name: str = "duration") -> int:
    """The number of sampling periods ``duration / dt`` (an int), after checking ``duration`` is a whole
    number of periods ``dt`` (within 1e-9 of a period) and the run has at most :data:`MAX_SAMPLES` samples."""
    duration = check_positive(duration, name)
    dt = check_positive(dt, "dt")
    periods = duration / dt
    if not periods + 1 <= MAX_SAMPLES:
        raise ScaraError(f"{name} = {duration:g} s at dt = {dt:g} s asks for {periods + 1:.6g} samples, past the "
                         f"limit of {MAX_SAMPLES} samples per run")
    n = round(periods)
    if abs(periods - n) > 1e-9 * max(1.0, periods):
        lo, hi = math.floor(periods), math.ceil(periods)
        raise ScaraError(f"{name} = {duration:g} s is not a whole number of samples of dt = {dt:g} s "
                         f"({periods:.6g} periods); the nearest valid durations are {lo * dt:g} s and {hi * dt:g} s")
    if n < 1:
        raise ScaraError(f"{name} = {duration:g} s is shorter than one sampling period dt = {dt:g} s")
    return int(n)

if _compile.COMPILED:
    from numba import types as _t

    _v = _t.float64[::1]
    _m = _t.float64[:, ::1]
    #: ``int64 law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)``
    LAW_SIGNATURE = _t.int64(_t.int64, _t.float64, _t.float64, _v, _v, _v, _v, _v, _v, _m, _v, _v)
    _LAW_TYPE = _t.FunctionType(LAW_SIGNATURE)
else:  # pragma: no cover - plain Python
    LAW_SIGNATURE = "int64(int64, float64, float64, f8[::1] x6, f8[:, ::1], f8[::1], f8[::1])"
    _LAW_TYPE = None



def control_law(fn):
    """Make ``fn`` a controller's step kernel: a numba dispatcher (cached on disk) that :func:`simulate`
    compiles with the engine's :data:`LAW_SIGNATURE` when it first runs it (``_compiled_law``), not at
    import.

    The law is compiled without numba's reference counting (``_nrt=False``): it must not allocate arrays (it
    writes into the arrays it is given), and in exchange no array view it takes (``work[0]``) costs a
    reference-count update per sample. Without numba the function is returned unchanged. See the module
    docstring for the arguments.
    """
    if not _compile.COMPILED:
        return fn
    return _compile._numba.njit(cache=True, _nrt=False)(fn)


def _compiled_law(law):
    """``law`` compiled for :data:`LAW_SIGNATURE` (loaded from the cache when it is there), ready to be passed
    to :func:`~scara._simulate.engine.closed_loop_kernel`; returned unchanged without numba or when it is not a
    numba dispatcher.
    Raises ``TypeError`` when it was already compiled for the same arguments with another return type."""
    if not _compile.COMPILED:
        return law
    return _compile.ensure_signature(law, LAW_SIGNATURE)


class Controller:
    """Base class of the controllers that :func:`simulate` runs (chapter 5; interface: ``help(scara.simulate)``).

    Subclasses set ``law`` (a :func:`control_law` kernel), ``reference_kind``, ``signal_names``,
    ``work_rows`` and ``name``, and override :meth:`gains_array` (and :meth:`initial_state` when they keep
    memory). ``self.model`` is the parameter object the controller believes in (default ``ScaraParams()``,
    which does not know the payload).
    """

    law = None
    name = "controller"
    reference_kind = "joint"
    signal_names: tuple = ()
    work_rows = 0
    model: ScaraParams = ScaraParams()

    def gains_array(self) -> np.ndarray:
        return np.zeros(0)

    def model_array(self) -> np.ndarray:
        return dynamic_array(self.model)

    def initial_state(self) -> np.ndarray:
        return np.zeros(0)

    def __repr__(self):
        return f"{type(self).__name__}()"
