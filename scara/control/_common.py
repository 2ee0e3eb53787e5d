"""What the three controllers of chapter 6 share: gain checks, the bounds a run must respect, the failure
codes of their laws, a compiled replay loop that times a law, and the figures of the chapter's table.

Every law here returns one of the codes of :data:`FAILURE_CAUSES` (0 when all is well); the engine stops the
run at the first non-zero code and :meth:`BoundedController.run` turns it into an
:class:`~scara.UnstableError` that names the time and the cause.
"""
from __future__ import annotations

import math
import statistics
import time

import numpy as np

from .. import _compile
from ..errors import ScaraError, ShapeError, UnstableError, as_array, check_count, check_positive
from ..gains import gain_vector
from ..params import ScaraParams
from .._simulate import OK, Controller, _compiled_law
from .._simulate.interface import MEASURED_FORCE, check_law_bounds, law_arrays

__all__ = [
    "TAU_MAX", "MAX_ERROR", "BOUND_FIELDS", "OK", "TORQUE_BOUND", "ERROR_BOUND", "SINGULAR_JACOBIAN", "FAILURE_CAUSES",
    "BoundedController", "positive_gains", "control_summary", "chattering", "law_cost", "replay_law",
    "recorded_signals", "final_state",
]

#: The stated actuator bounds (N m, N m, N, N m): a law that asks for more stops the run (code 2). They are
#: about three times the largest torque any of the book's runs needs with a 10 kg payload.
TAU_MAX = (200.0, 200.0, 1000.0, 50.0)
#: The largest ``repeats`` of :func:`law_cost` (and :func:`control_summary`): each repeat replays a whole run
#: (70 001 samples for the book's reference), so 1000 of them already take minutes; the median settles with 5-10.
MAX_REPEATS = 1000
#: The stated bound on the tracking error a law tolerates (rad or m, per component): beyond it the run is
#: treated as lost (code 3), long before the state becomes large enough for the engine's own limit.
MAX_ERROR = 0.05

#: The failure codes a chapter-6 law returns: a torque past its bound, a tracking error past its bound, a
#: singular Jacobian (``OK``, 0, is the engine's own "all is well"; a law's codes start at 2).
TORQUE_BOUND, ERROR_BOUND, SINGULAR_JACOBIAN = 2, 3, 4
#: The meaning of each code a chapter-6 law may return.
FAILURE_CAUSES = {
    TORQUE_BOUND: "a commanded torque exceeded its bound tau_max",
    ERROR_BOUND: "a tracking error component exceeded its bound max_error",
    SINGULAR_JACOBIAN: "the Jacobian became singular (the arm reached a stretched or folded configuration)",
}


#: The last fields of every chapter-6 law's gain array (:class:`~scara._compile.ArrayLayout`): the stated bounds.
BOUND_FIELDS = (("tau_max", 4), ("max_error", 1))

@_compile.kernel(light=True)
def torque_code(tau, gains, tau_max_at):
    """:data:`TORQUE_BOUND` when some ``|tau_i|`` exceeds its bound ``gains[tau_max_at + i]`` (or is not finite),
    :data:`OK` otherwise: the torque check of the chapter-6 laws, inside their compiled step."""
    for i in range(4):
        if not abs(tau[i]) <= gains[tau_max_at + i]:
            return TORQUE_BOUND
    return OK


#: the check of every chapter-6 gain and bound (the ``"positive"`` rule of :mod:`scara.gains`)
positive_gains = gain_vector


class BoundedController(Controller):
    """Base of the chapter-6 controllers: the stated bounds, the failure causes and a runner that names them.

    Attributes ``tau_max`` (4,) (N m, N m, N, N m) and ``max_error`` (rad or m) are the bounds a run must
    respect; the law returns :data:`TORQUE_BOUND` or :data:`ERROR_BOUND` when it would break one.
    """

    failure_causes = FAILURE_CAUSES
    tau_max: np.ndarray = np.asarray(TAU_MAX)
    max_error: float = MAX_ERROR

    def _set_bounds(self, tau_max, max_error):
        self.tau_max = positive_gains(TAU_MAX if tau_max is None else tau_max, "tau_max")
        if max_error is None:
            max_error = MAX_ERROR
        self.max_error = float(positive_gains(max_error, "max_error", 1)[0])

    def _bounds(self) -> dict:
        """The values of :data:`BOUND_FIELDS`, for a gain layout's ``pack``."""
        return {"tau_max": self.tau_max, "max_error": self.max_error}

    def explain(self, code: int) -> str:
        """The cause behind a law's return code (see :data:`FAILURE_CAUSES`), with the bound it broke.

        :func:`scara.simulate` calls it when a law stops a run, so the :class:`~scara.UnstableError` names the
        time, the cause and the limit.
        """
        code = int(code)
        cause = self.failure_causes.get(code, f"the law returned the unknown code {code}")
        if code == TORQUE_BOUND:
            cause += f" (tau_max = {self.tau_max.tolist()})"
        elif code == ERROR_BOUND:
            cause += f" (max_error = {self.max_error:g})"
        return cause

    def run(self, traj=None, plant: ScaraParams | None = None, **kwargs):
        """``scara.simulate(self, traj, plant, **kwargs)``: the run, returning a
        :class:`~scara._simulate.SimulationResult`; a failure of the law raises :class:`~scara.UnstableError`
        with the time, the cause and the bound (see :meth:`explain`)."""
        from .._simulate import simulate  # noqa: PLC0415

        return simulate(self, traj, plant, **kwargs)


# --------------------------------------------------------------------------------------------------
# replaying a law on recorded samples: its own cost per step, and a check against another implementation
# --------------------------------------------------------------------------------------------------
def _run_series(result, shapes: dict) -> dict:
    """The arrays ``{name: trailing shape}`` of a recorded run (a :class:`~scara._simulate.SimulationResult` or
    any object with those attributes), each checked finite with shape ``(N, *trailing)`` and one common ``N``;
    :class:`~scara.ScaraError` naming the missing or wrong attribute otherwise."""
    out = {}
    for name, trailing in shapes.items():
        if not hasattr(result, name):
            raise ScaraError(f"result = {type(result).__name__} has no attribute {name!r}: pass the result of "
                             f"scara.simulate")
        v = getattr(result, name)
        out[name] = as_array(v, f"result.{name}", trailing, allow_batch=True) if trailing else \
            as_array(v, f"result.{name}", (len(np.atleast_1d(v)),))
    lengths = {name: len(v) for name, v in out.items()}
    if len(set(lengths.values())) > 1:
        raise ShapeError(f"the series of result must have one length (one row per sample), got {lengths}")
    if min(lengths.values(), default=1) < 1:
        raise ScaraError("result holds no sample")
    return out


def _check_controller(controller):
    """``controller`` has what :func:`replay_law` needs (a controller of :mod:`scara.simulate`'s interface)."""
    needs = ("law", "gains_array", "model_array", "initial_state")
    missing = [a for a in needs if not hasattr(controller, a)]
    if missing or getattr(controller, "law", None) is None:
        raise ScaraError(f"controller = {controller!r} is not a controller of scara.simulate's interface (missing "
                         f"{missing or ['a compiled law']})")


def _replay(law, q, qd, ref, dt, data, sig, tau):
    """The law alone over the recorded samples (no plant): the index of the first sample whose law code is not
    :data:`OK`, or -1. Compiled with :data:`~scara._compile.LAW_TYPE` and :data:`~scara._compile.LAW_DATA_TYPE`."""
    gains, model, state, work = data.gains, data.model, data.state, data.work
    n = q.shape[0]
    for k in range(n):
        code = law(k, k * dt, dt, q[k], qd[k], ref[k], gains, model, state, work, sig[k], tau[k])
        if code != 0:
            return k
    return -1


if _compile.COMPILED:
    _t, _m = _compile.numba_types, _compile.MATRIX
    # compiled (or loaded from the cache) on the first replay, not at import
    _replay_kernel = _compile.signature_kernel(
        _t.int64(_compile.LAW_TYPE, _m, _m, _m, _t.float64, _compile.LAW_DATA_TYPE, _m, _m))(_replay)
else:  # pragma: no cover - plain Python
    _replay_kernel = _replay


def _check_kind(controller, result):
    """The run's reference is what ``controller``'s law reads (a joint law replayed on an operational run would
    read positions as angles)."""
    kind = getattr(result, "reference_kind", None)
    want = getattr(controller, "reference_kind", None)
    if kind is not None and want is not None and kind != want:
        raise ScaraError(f"controller {getattr(controller, 'name', controller)} reads a {want!r} reference, but the "
                         f"run of {getattr(result, 'controller', '?')} recorded a {kind!r} one: replay it on a run of "
                         f"a controller of the same reference_kind")


def replay_law(controller, result, n: int | None = None):
    """Run ``controller``'s law alone on the states a run recorded (no plant): ``(tau, signals, state)``.

    The law sees the measured ``q``, ``qd`` and the reference of ``result`` sample by sample, starting from
    ``controller.initial_state()``, with the arrays the engine would give it
    (:func:`scara._simulate.interface.law_arrays`, checked by the same trial call); its torques (n, 4) must
    equal ``result.tau`` when the same controller produced the run. Used to time the law (:func:`law_cost`) and
    to check it against another implementation. The run's ``reference_kind`` must be the controller's. A law that
    reads the force sensor (its ``work_layout`` declares the row ``MEASURED_FORCE``, the interaction laws of
    chapter 7) is refused with a :class:`~scara.ScaraError`: the replay does not feed the readings.
    """
    _check_controller(controller)
    if MEASURED_FORCE in getattr(getattr(controller, "work_layout", None), "names", ()):
        raise ScaraError(f"replay_law cannot replay {controller.name}: its law reads the force sensor (the scratch row "
                         f"{MEASURED_FORCE!r}), which a replay without the recorded readings would leave at zero")
    run = _run_series(result, {"t": (), "q": (4,), "qd": (4,), "reference": (12,)})
    _check_kind(controller, result)
    dt = check_positive(getattr(result, "dt", None), "result.dt")
    n_run = len(run["t"])
    n = n_run if n is None else check_count(n, "n", 1, n_run, "samples", f"the run has {n_run} samples")
    q = np.ascontiguousarray(run["q"][:n])
    qd = np.ascontiguousarray(run["qd"][:n])
    ref = np.ascontiguousarray(run["reference"][:n])
    data, sig, names = law_arrays(controller, n)
    check_law_bounds(controller, data, len(names), (q[0], qd[0], ref[0]), dt)
    tau = np.zeros((n, 4))
    k = _replay_kernel(_compiled_law(controller.law), q, qd, ref, dt, data, sig, tau)
    if k >= 0:
        raise UnstableError(f"the law of {controller.name} returned a failure at sample {k} while replaying")
    return tau, sig, data.state


def law_cost(controller, result, repeats: int = 7) -> float:
    """Compute time of one control step of ``controller``'s compiled law (s): the median over ``repeats``
    replays of the recorded run (:func:`replay_law`) divided by the number of samples. It includes the call
    through the engine's function pointer, as in a real run, and nothing of the plant.

    ``repeats`` is a whole number from 1 to :data:`MAX_REPEATS` (1000); anything else raises
    :class:`~scara.ScaraError` before any replay."""
    repeats = check_count(repeats, "repeats", 1, MAX_REPEATS, "replays", "each repeat replays the whole run")
    _check_controller(controller)
    n = len(_run_series(result, {"t": ()})["t"])
    replay_law(controller, result, min(n, 100))  # warm up
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        replay_law(controller, result)
        times.append(time.perf_counter() - t0)
    return statistics.median(times) / n


# --------------------------------------------------------------------------------------------------
# the chapter's figures of merit
# --------------------------------------------------------------------------------------------------
def chattering(result) -> float:
    """Chattering measure of a run: the RMS over the run of the norm of the torque's second difference
    ``tau_{k+1} - 2 tau_k + tau_{k-1}`` (N m and N together, like ``||z||`` mixes units).

    A smooth torque changes by ``O(dt^2)`` in its second difference (about ``1e-4`` here); a torque that
    switches sign every sample of amplitude ``A`` gives ``4 A``.
    """
    tau = _run_series(result, {"tau": (4,)})["tau"]
    if len(tau) < 3:
        return 0.0
    d2 = tau[2:] - 2.0 * tau[1:-1] + tau[:-2]
    return float(np.sqrt(np.mean(np.sum(d2 ** 2, axis=1))))


def control_summary(result, controller=None, *, settle: float = 1.0, rest: float = 2.0,
                    repeats: int = 5) -> dict:
    """The row of the chapter's comparison table for one run.

    Keys: ``controller``; ``max_position_error`` and ``rms_position_error`` (m): largest and RMS norm of the
    position error ``x_d - x_e`` (x, y, z) after the first ``settle`` seconds; ``max_orientation_error`` (rad):
    largest ``|phi_d - phi|`` after ``settle``; ``final_position_error`` (m): largest position-error norm over the
    final rest (the last ``rest`` seconds, where the arm is still); ``steady_z_error`` (m): mean vertical error
    there (signed); ``peak_tau`` (4,) largest absolute
    torques (N m, N m, N, N m); ``chattering`` (:func:`chattering`); ``step_cost`` (s): compute time per
    control step (:func:`law_cost`; only when ``controller`` is given, else NaN).

    ``settle`` (s) must be finite and ``>= 0``, ``rest`` (s) finite and ``> 0``, ``repeats`` a whole number from 1
    to :data:`MAX_REPEATS`: :class:`~scara.ScaraError` otherwise.
    """
    settle = check_positive(settle, "settle", strict=False)
    rest = check_positive(rest, "rest")
    repeats = check_count(repeats, "repeats", 1, MAX_REPEATS, "replays", "each repeat replays the whole run")
    if controller is not None:
        _check_controller(controller)
        made_by = getattr(result, "controller", None)
        if made_by is not None and made_by != getattr(controller, "name", made_by):
            raise ScaraError(f"control_summary times the law of the controller that made the run: result is a run "
                             f"of {made_by!r}, controller = {controller.name!r}")
    run = _run_series(result, {"t": (), "e": (4,), "tau": (4,)})
    t, e = run["t"], run["e"]
    pos = np.linalg.norm(e[:, :3], axis=1)
    after = t >= t[0] + settle - 1e-12
    if not after.any():
        raise ScaraError(f"the run lasts {t[-1] - t[0]:g} s: nothing after settle = {settle:g} s")
    last = t >= t[-1] - rest + 1e-12
    return {
        "controller": getattr(result, "controller", ""),
        "max_position_error": float(pos[after].max()),
        "rms_position_error": float(np.sqrt(np.mean(pos[after] ** 2))),
        "max_orientation_error": float(np.abs(e[after, 3]).max()),
        "final_position_error": float(pos[last].max()),
        "steady_z_error": float(e[last, 2].mean()),
        "peak_tau": np.abs(run["tau"]).max(axis=0),
        "chattering": chattering(result),
        "step_cost": law_cost(controller, result, repeats) if controller is not None else math.nan,
    }


# --------------------------------------------------------------------------------------------------
# what a helper of one kind of controller reads from a run (refused, with what it needs, for another kind)
# --------------------------------------------------------------------------------------------------
def recorded_signals(result, names, who: str) -> np.ndarray:
    """The signals ``names`` of a run as an (N, len(names)) array; :class:`~scara.ScaraError` naming ``who``
    needs them, and what the run recorded, when the run (of another kind of controller) has not got them."""
    signals = getattr(result, "signals", None)
    missing = [n for n in names if not isinstance(signals, dict) or n not in signals]
    if missing:
        have = sorted(signals) if isinstance(signals, dict) else "no signals"
        raise ScaraError(f"{who} needs a run that records the signals {list(names)}; the run of "
                         f"{getattr(result, 'controller', type(result).__name__)!r} records {have}")
    return np.column_stack([np.asarray(signals[n], dtype=float) for n in names])


#: the largest state a law may keep (entries): far above any law's (the adaptive law keeps 14)
MAX_STATE = 100_000


def final_state(result, size: int, who: str) -> np.ndarray:
    """A copy of the law's state (``size`` numbers) at the end of a run; :class:`~scara.ScaraError` naming
    ``who`` needs it when the run's controller kept another state."""
    size = check_count(size, "size", 0, MAX_STATE, "state entries")
    extra = getattr(result, "extra", None)
    state = extra.get("final_state") if isinstance(extra, dict) else None
    got = None if state is None else np.size(state)
    if got != size:
        raise ScaraError(f"{who} needs a run whose law keeps a state of {size} numbers; the run of "
                         f"{getattr(result, 'controller', type(result).__name__)!r} kept "
                         f"{'none' if got is None else f'{got} numbers'}")
    return np.array(state, dtype=float)
