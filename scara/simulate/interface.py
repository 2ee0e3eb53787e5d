"""The controller interface of the simulation engine (chapter 5): the signature of a compiled law, the
decorator that makes one, the base class :class:`Controller` and the status codes a run reports.

See the package's docstring (``help(scara.simulate)``) for the arguments of a law.
"""
from __future__ import annotations

import numpy as np

from .. import _compile
from ..dynamics import dynamic_array
from ..params import ScaraParams

__all__ = ["LAW_SIGNATURE", "control_law", "Controller", "OK", "LAW_FAILED", "DIVERGED", "SINGULAR_INERTIA"]

#: The status codes of a run, written in ``info[0]`` by the engine's loop. ``OK`` is also what a law returns
#: when all is well (a law's own failure codes are any other integer, e.g. those of :mod:`scara.control`).
OK, LAW_FAILED, DIVERGED, SINGULAR_INERTIA = 0, 1, 2, 3

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
    to :func:`~scara.simulate.engine.closed_loop_kernel`; returned unchanged without numba or when it is not a
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
