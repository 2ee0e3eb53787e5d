"""The controller interface of the simulation engine (chapter 5): the contract between a controller and the
engine (:class:`Controller`, read it first), the one function that prepares a controller's arrays
(:func:`law_arrays`), the trial call that checks a law stays inside them (:func:`check_law_bounds`) and the
status codes a run reports. The law's signature and its decorator live beside :func:`scara._compile.kernel`.
"""
from __future__ import annotations

import math

import numpy as np

from .. import _compile
from .._compile import ArrayLayout
from ..dynamics import DYNAMIC_LAYOUT, dynamic_array
from ..errors import ScaraError, check_count, check_positive
from ..params import ScaraParams

__all__ = ["LAW_SIGNATURE", "control_law", "Controller", "OK", "LAW_FAILED", "DIVERGED", "SINGULAR_INERTIA",
           "JOINT_LIMIT", "NOT_FINITE", "law_arrays", "check_law_bounds"]

#: The name of the scratch row into which the contact engine (:func:`scara.interaction.simulate_contact`) writes
#: the force sensor's reading ``[h_x, h_y, h_z, 0]`` (N) before each call of a law that declares it in its
#: ``work_layout``; a replay without the recorded readings cannot give such a law what it read.
MEASURED_FORCE = "measured_force"

#: The status codes of a run, written in ``info[0]`` by the engine's loop. ``OK`` is also what a law returns
#: when all is well (a law's own failure codes are any other integer, e.g. those of :mod:`scara.control`).
#: ``JOINT_LIMIT``: the quill ``d3`` left its stroke ``[d3_min, d3_max]`` (the plant models no end stop).
#: ``NOT_FINITE``: the law returned a NaN or infinite torque or signal (``info[2]`` is its index: 0-3 the
#: torques, then the signals).
OK, LAW_FAILED, DIVERGED, SINGULAR_INERTIA, JOINT_LIMIT, NOT_FINITE = 0, 1, 2, 3, 4, 5


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

#: ``int64 law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)`` (declared in :mod:`scara._compile`)
LAW_SIGNATURE = _compile.LAW_SIGNATURE
control_law = _compile.control_law
_compiled_law = _compile.compiled_law
LawData = _compile.LawData

#: The default model of a controller: the flat parameter array :func:`~scara.dynamics.dynamic_array` of its
#: ``model`` (the offsets ``DP_*`` of :mod:`scara.dynamics`).
MODEL_LAYOUT = DYNAMIC_LAYOUT
#: The width of a scratch row of ``work`` (a 4-vector; a 4x4 matrix takes four rows).
WORK_WIDTH = 4
#: The reference row ``ref`` (12,) a law receives: position, velocity and acceleration, in joint space
#: (``q_d, qd_d, qdd_d``) or in the operational space (``x_d, xd_d, xdd_d``), per ``reference_kind``.
REFERENCE = ArrayLayout(("position", 4), ("velocity", 4), ("acceleration", 4))
REF_POS, REF_VEL, REF_ACC = REFERENCE.offsets


class Controller:
    """Base class of the controllers that :func:`~scara.simulate` runs (chapter 5): the contract between a
    controller and the engine.

    A controller is a constant *model* of the arm and a law; everything a run changes lives in separate
    arrays the engine owns (as a solver keeps a problem apart from its workspace). Read the contract in this
    order:

    1. ``law``: a :func:`control_law` kernel, compiled for :data:`LAW_SIGNATURE`, called once per sample::

           @control_law
           def law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
               ...            # write tau[0:4] and signals[:]; update state[:] in place
               return OK      # OK (0) = fine; any other integer stops the run with an UnstableError

       ``k`` (int) sample index, ``t = k dt`` (s), ``dt`` (s) sampling period; ``q``, ``qd`` (4,) measured state
       (read only); ``ref`` (12,) reference row (:data:`REFERENCE`: offsets ``REF_POS, REF_VEL, REF_ACC``);
       the five arrays below; ``tau`` (4,) the torque to apply. The
       law allocates nothing: it calls the compiled kernels of :mod:`scara.dynamics` and
       :mod:`scara.kinematics` with ``model`` and rows of ``work``. Its twelve positional arguments are fixed
       by the engine.
    2. ``reference_kind``: ``"joint"`` (``ref = [q_d, qd_d, qdd_d]``, from ``clik2(traj)`` or
       ``joint_reference=``), ``"operational"`` (``ref = [x_d, xd_d, xdd_d]``) or ``"none"`` (zeros, open loop).
    3. ``gains_layout`` and :meth:`gains_array`: the constant gains, a flat array packed by the layout
       (:class:`~scara._compile.ArrayLayout`); the law reads them at the layout's offsets.
    4. ``model_layout`` and :meth:`model_array`: the constant model the controller believes in, by default
       :data:`MODEL_LAYOUT`, ``dynamic_array(self.model)`` (``self.model`` does not know the payload); a
       controller whose ``model_array()`` returns another array declares its own ``model_layout``.
    5. ``state_layout`` and :meth:`initial_state`: the memory carried from one sample to the next
       (integrators, estimates); the engine copies it, and the final state is ``result.extra["final_state"]``.
    6. ``work_layout``: named scratch rows of 4 floats (``work`` has shape ``(work_layout.size, 4)``), zeroed
       once per run and not meant to be kept between samples.
    7. ``signals_layout``: the internal signals the law writes at each sample; ``signal_names`` (derived from
       it) become ``result.signals[name]`` and attributes of the result.
    8. ``name``: the label of the controller in tables and legends.

    What the engine guarantees and checks (:func:`law_arrays`, :func:`check_law_bounds`): every array has
    exactly the size its layout declares (a ``gains_array()`` or ``initial_state()`` of another size is refused
    before the run) and none shares memory with the controller; before the compiled run the law is called
    once in plain Python, on bounds-checked copies followed by guard entries, and a law that reads or writes
    past any of its arrays is refused with a :class:`~scara.ScaraError` naming the array and its declared
    size (the compiled law has no bounds check); a NaN or infinite torque stops the run at its sample, and a NaN
    or infinite signal (checked once after the compiled loop, which a check per sample would slow down) fails
    it the same way: an :class:`~scara.UnstableError` naming the time, the torque or signal and the value.

    A controller that declares no layout may still give ``signal_names`` and ``work_rows`` directly (then
    they are the declaration); without ``gains_layout`` / ``state_layout`` the arrays it returns declare their
    own sizes.
    """

    law = None
    name = "controller"
    reference_kind = "joint"
    #: None: the length of :meth:`gains_array` (resp. :meth:`initial_state`) is the declared size
    gains_layout: ArrayLayout | None = None
    model_layout: ArrayLayout = MODEL_LAYOUT
    state_layout: ArrayLayout | None = None
    work_layout: ArrayLayout = ArrayLayout(width=WORK_WIDTH)
    signals_layout: ArrayLayout = ArrayLayout()
    model: ScaraParams = ScaraParams()

    @property
    def signal_names(self) -> tuple:
        """The names of the recorded signals: the entries of ``signals_layout``."""
        return self.signals_layout.entry_names

    @property
    def work_rows(self) -> int:
        """The rows of the scratch array: the size of ``work_layout``."""
        return self.work_layout.size

    def gains_array(self) -> np.ndarray:
        return np.zeros(0)

    def model_array(self) -> np.ndarray:
        return dynamic_array(self.model)

    def initial_state(self) -> np.ndarray:
        return np.zeros(0)

    def __repr__(self):
        return f"{type(self).__name__}()"


# --------------------------------------------------------------------------------------------------
# the controller's arrays, prepared once for the engine and for any replay
# --------------------------------------------------------------------------------------------------
def _label(controller) -> str:
    return str(getattr(controller, "name", type(controller).__name__))


def _declared(controller, part: str, values, layout) -> np.ndarray:
    """``values`` as a new contiguous float vector, after checking its size is what ``layout`` declares."""
    try:
        arr = np.array(values, dtype=float).ravel()
    except (TypeError, ValueError) as exc:
        raise ScaraError(f"the {part} array of controller {_label(controller)} must hold numbers, got "
                         f"{values!r:.80}") from exc
    if layout is not None and arr.size != layout.size:
        raise ScaraError(f"the {part} array of controller {_label(controller)} holds {arr.size} numbers, but its "
                         f"{part}_layout declares {layout.size}: {layout}")
    return arr


#: The most scratch rows a law may declare (a law allocates nothing, so its scratch is small).
MAX_WORK_ROWS = 10_000


def law_layouts(controller) -> tuple:
    """``(work_layout, signals_layout)`` of ``controller``: its declared layouts, or the ones its
    ``work_rows`` and ``signal_names`` give when it sets those directly."""
    work = getattr(controller, "work_layout", None)
    rows = getattr(controller, "work_rows", 0 if work is None else work.size)
    rows = check_count(rows, f"{_label(controller)}.work_rows", 0, MAX_WORK_ROWS, "scratch rows",
                       "a law's scratch is a few 4x4 matrices and vectors")
    if work is None or work.size != rows:
        work = ArrayLayout.rows(rows, WORK_WIDTH)
    signals = getattr(controller, "signals_layout", None)
    names = tuple(str(n) for n in getattr(controller, "signal_names", () if signals is None else
                                          signals.entry_names))
    if signals is None or signals.entry_names != names:
        signals = ArrayLayout.of_names(names)
    return work, signals


def law_arrays(controller, n: int) -> tuple:
    """The arrays of ``controller``'s law for ``n`` samples: ``(LawData, signals, names)``.

    ``LawData = (gains, model, state, work)`` as :data:`LAW_SIGNATURE` takes them, each a new array of exactly
    the size its layout declares (:class:`Controller`, items 3-6; :class:`~scara.ScaraError` naming the array and
    the declared size otherwise); ``signals`` a zeroed (n, len(names)) array, one row per sample; ``names``
    the signal names. Used by the engine and by every replay of a law (:func:`scara.control.replay_law`).
    """
    work_layout, signals_layout = law_layouts(controller)
    gains = _declared(controller, "gains", controller.gains_array(), getattr(controller, "gains_layout", None))
    model = _declared(controller, "model", controller.model_array(), getattr(controller, "model_layout", None))
    state = _declared(controller, "state", controller.initial_state(), getattr(controller, "state_layout", None))
    work = np.zeros((work_layout.size, WORK_WIDTH))
    names = signals_layout.entry_names
    return LawData(gains, model, state, work), np.zeros((n, len(names))), names


# --------------------------------------------------------------------------------------------------
# the trial call of a law on bounds-checked copies (a compiled law has no bounds check)
# --------------------------------------------------------------------------------------------------
#: Guard entries (rows, for ``work``) after each array of a trial call.
GUARD = 16
#: Two fills of the guard entries: a trial's outputs must not depend on which one is there.
_FILLS = (-1.2345678e300, 7.25)
#: The laws already checked in this process, with the sizes of their arrays.
_CHECKED: dict = {}


class _OutOfBounds(Exception):
    """An index past a trial array's declared size (raised by :class:`_Bounded`)."""


class _Bounded(np.ndarray):
    """A trial array whose indexing (also by slices, and of its rows) is checked against its declared size."""

    def __array_finalize__(self, obj):
        self.label = getattr(obj, "label", "")

    def _check(self, key):
        keys = key if isinstance(key, tuple) else (key,)
        for axis, k in enumerate(keys[:self.ndim]):
            if isinstance(k, slice) and ((k.stop is not None and k.stop > self.shape[axis])
                                         or (k.start is not None and k.start > self.shape[axis])):
                raise _OutOfBounds(f"{self.label}[{k.start}:{k.stop}] on axis {axis} of size {self.shape[axis]}")

    def __getitem__(self, key):
        self._check(key)
        try:
            return super().__getitem__(key)
        except IndexError as exc:
            raise _OutOfBounds(f"{self.label}[{key}]: {exc}") from None

    def __setitem__(self, key, value):
        self._check(key)
        try:
            super().__setitem__(key, value)
        except IndexError as exc:
            raise _OutOfBounds(f"{self.label}[{key}]: {exc}") from None


_TRIAL_ARRAYS = ("gains", "model", "state", "work", "signals", "tau")


def _trial(law, arrays, start, dt, fills):
    """One plain-Python call of ``law`` at sample 0 on guarded copies of ``arrays`` (name: array):
    ``(code, {name: (buffer, size)})``; ``fills`` gives each array's guard value."""
    q, qd, ref = (np.array(v, dtype=float) for v in start)
    bufs, views = {}, []
    for name in _TRIAL_ARRAYS:
        a = arrays[name]
        buf = np.full((a.shape[0] + GUARD,) + a.shape[1:], fills[name])
        buf[:a.shape[0]] = a
        v = buf[:a.shape[0]].view(_Bounded)
        v.label = name
        bufs[name] = (buf, a.shape[0])
        views.append(v)
    with np.errstate(all="ignore"):
        code = law(0, 0.0, dt, q, qd, ref, *views)
    return code, bufs


@_compile.kernel(light=True)
def guard_change(buf, start, fill):
    """The index of the first entry of ``buf`` (1-D: a trial array followed by its guard entries) at or after
    ``start`` that is not ``fill``, or -1: where a law wrote past its declared size (:func:`check_law_bounds`; a NaN
    written there differs from every fill)."""
    for i in range(start, buf.shape[0]):
        if buf[i] != fill:
            return i
    return -1


@_compile.kernel(light=True)
def same_entries(a, b, n):
    """Whether the first ``n`` entries of ``a`` and ``b`` (1-D) are equal, a NaN equal to a NaN: two trial calls
    gave the same outputs (:func:`check_law_bounds`)."""
    for i in range(n):
        x = a[i]
        y = b[i]
        if not (x == y or (x != x and y != y)):
            return False
    return True


#: The refusals of :func:`check_law_bounds` (templates: ``{controller}``, ``{array}`` and the sizes are filled in
#: as text, ``{index}`` is a number): the one wording, in the engine and in the page programs.
WRITES_PAST = ("the law of controller {controller} writes {array}[{index:.0f}], past its declared size: "
               "{described}")
READS_PAST = "the law of controller {controller} reads past {array}: {described}"
READS_PAST_ANY = ("the law of controller {controller} reads past its arrays (its outputs depend on the entries after "
                  "them)")


def described(name: str, size: int, label: str) -> str:
    """The declared size of the trial array ``name`` in a refusal of :func:`check_law_bounds`."""
    unit = "rows of 4" if name == "work" else "entries"
    return f"{name} holds {size} {unit} (declared by {label}'s {name}_layout)"


def _described(name, size, controller) -> str:
    return described(name, size, _label(controller))


def fill_text(template: str, **text) -> str:
    """``template`` with its text fields ``{name}`` (``text``: name -> str) written in, each with its braces
    doubled: what is left is a template of numbers only (the form of :class:`scara.plots.panels.Text`)."""
    for name, value in text.items():
        template = template.replace("{" + name + "}", str(value).replace("{", "{{").replace("}", "}}"))
    return template


def check_law_bounds(controller, data: LawData, n_signals: int, start, dt: float) -> None:
    """Refuse a law that reads or writes past its arrays, before its compiled run (which has no bounds check).

    The law's plain-Python function is called once at sample 0 (``start = (q0, qd0, ref_row0)``), on copies of
    ``data``, of zeroed ``signals`` (n_signals,) and ``tau`` (4,), each followed by :data:`GUARD` guard entries:
    indexing past a declared size in the law's own code raises at once (:class:`_Bounded` checks indices and
    slices), a compiled kernel the law calls that writes past it changes a guard entry, and one that reads
    past it makes the outputs depend on the guards' value (the call is made with two fills and compared).
    The copies leave the controller's arrays untouched; a law already checked with arrays of these sizes is
    not called again. Raises :class:`~scara.ScaraError` naming the array and its declared size.
    """
    law = _compile.python_law(controller.law)
    arrays = dict(zip(LawData._fields, data), signals=np.zeros(n_signals), tau=np.zeros(4))
    key = (law, tuple(a.shape for a in arrays.values()))
    if key in _CHECKED:
        return
    results = []
    for fill in _FILLS:
        try:
            code, bufs = _trial(law, arrays, start, dt, dict.fromkeys(_TRIAL_ARRAYS, fill))
        except _OutOfBounds as exc:
            name = str(exc).split("[", 1)[0]
            raise ScaraError(f"the law of controller {_label(controller)} indexes {exc}, past its declared size: "
                             f"{_described(name, arrays[name].shape[0], controller)}") from None
        except Exception as exc:  # noqa: BLE001 - any failure of the trial call refuses the law
            raise ScaraError(f"the law of controller {_label(controller)} failed on its trial call at t = 0 "
                             f"(plain Python, bounds-checked): {type(exc).__name__}: {exc}") from exc
        for name, (buf, size) in bufs.items():
            width = buf.size // buf.shape[0]
            past = guard_change(buf.reshape(-1), size * width, fill)
            if past >= 0:
                raise ScaraError(fill_text(WRITES_PAST, controller=_label(controller), array=name,
                                           described=_described(name, size, controller)).format(index=past // width))
        results.append((int(code), bufs))
    _check_reads(controller, law, arrays, start, dt, results)
    _CHECKED[key] = True


def _same_outputs(a, b) -> bool:
    if a[0] != b[0]:
        return False
    for name, (buf, size) in a[1].items():
        width = buf.size // buf.shape[0]
        if not same_entries(buf.reshape(-1), b[1][name][0].reshape(-1), size * width):
            return False
    return True


def _check_reads(controller, law, arrays, start, dt, results):
    """Refuse a law whose outputs depend on the guard entries (it read past an array), naming that array."""
    if _same_outputs(*results):
        return
    base = dict.fromkeys(_TRIAL_ARRAYS, _FILLS[0])
    for name in _TRIAL_ARRAYS:
        code, bufs = _trial(law, arrays, start, dt, dict(base, **{name: _FILLS[1]}))
        if not _same_outputs(results[0], (int(code), bufs)):
            raise ScaraError(READS_PAST.format(controller=_label(controller), array=name,
                                               described=_described(name, arrays[name].shape[0], controller)))
    raise ScaraError(READS_PAST_ANY.format(controller=_label(controller)))
