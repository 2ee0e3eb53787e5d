"""Identification of the dynamic parameters from measured motion and torques (chapter 5; Siciliano et al.,
sec. 7.4).

The model is linear in the parameter vector ``pi`` of :data:`~scara.dynamics.PI_NAMES` (the book's
``(eq-dyn-regressor)`` with ``qd_r = qd``, ``qdd_r = qdd``): along a motion sampled at ``t_1 ... t_N``,

    tau_bar = Y_bar pi,   Y_bar = [Y(q_1, qd_1, qd_1, qdd_1); ...; Y(q_N, ...)]  (4N, 13)

(the book's ``(eq-id-stacked)``), and least squares on it gives an estimate ``pi_hat``. This module holds every
step of the chapter's experiment:

* the arm as a black box: :func:`draw_arm` draws a true robot within stated ranges of the nominal one;
* the exciting trajectory: a finite Fourier series per joint (:class:`FourierExcitation`) whose coefficients
  :func:`optimise_excitation` chooses to minimise the condition number of ``Y_bar`` within the quill's stroke,
  speed and torque limits;
* the measurement: :func:`measure` runs the true arm under a joint-space controller, quantises the joint
  positions (:func:`quantise`, :func:`encoder_resolution`) and adds white noise to the torques;
* the processing: :func:`filtered_data` filters positions and torques with the same zero-phase low-pass filter,
  differentiates by central differences and decimates;
* the estimate: :func:`least_squares` (ordinary or weighted, with covariance and confidence intervals),
  :func:`base_parameters` (the identifiable combinations of a rank-deficient ``Y_bar``), :func:`identify` for
  the whole chain.

Units are SI throughout: rad, m, s, N m (N for joint 3); ``pi`` in :data:`~scara.dynamics.PI_UNITS`.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ._compile import kernel
from .dynamics import N_PI, PI_NAMES, dynamic_array, inverse_dynamics, regressor_kernel
from .errors import (NonFiniteError, ScaraError, ShapeError, UnreachableError, _numbers, as_array, check_angles,
                     check_count, check_finite_result, check_positive)
from .params import ScaraParams

__all__ = [
    "ENCODER_COUNTS", "QUILL_RESOLUTION", "NOISE_FRACTION", "PARAM_SPREAD", "PAYLOAD_RANGE", "DRAWN_FIELDS",
    "SPEED_LIMITS", "STROKE_MARGIN", "TORQUE_SHARE", "EXCITATION_OFFSET", "FINE_SAMPLES", "EDGE_PERIODS",
    "EXAMPLE_SEED", "CUTOFF",
    "encoder_resolution", "quantise", "draw_arm", "FourierExcitation", "stacked_regressor", "regressor_condition",
    "excitation_margins", "optimise_excitation", "book_design", "BOOK_DESIGN", "BOOK_DESIGN_ITERATIONS",
    "ExcitationDesign", "Measurement", "measure", "read_sensors", "torque_noise_std",
    "lowpass", "filtered_data", "FilteredData", "least_squares", "Estimate", "base_parameters", "BaseParameters",
    "identify", "predicted_torques",
]

#: Encoder counts per revolution of a revolute joint, after the gear.
ENCODER_COUNTS = 2 ** 17
#: Resolution of the quill's linear encoder (m).
QUILL_RESOLUTION = 1e-6
#: Standard deviation of the torque noise, as a fraction of each joint's peak torque on the run.
NOISE_FRACTION = 0.01
#: Relative spread of the true masses, inertias and frictions around the nominal ones (:func:`draw_arm`).
PARAM_SPREAD = 0.2
#: Range of the true payload (kg) (:func:`draw_arm`).
PAYLOAD_RANGE = (0.0, 10.0)
#: The fields of :class:`~scara.ScaraParams` that :func:`draw_arm` draws (the geometry, the gear ratios and
#: ``g0`` are known to the experimenter and kept).
DRAWN_FIELDS = ("m_l1", "m_l2", "m_l3", "I_l1", "I_l2", "I_l4", "I_m", "F_m")
#: Largest joint speeds of an exciting trajectory (rad/s, rad/s, m/s, rad/s).
SPEED_LIMITS = (2.0, 2.0, 0.5, 4.0)
#: Distance (m) an exciting trajectory keeps from each end of the quill's stroke (room for the tracking error).
STROKE_MARGIN = 0.05
#: Share of the actuator bounds ``TAU_MAX`` an exciting trajectory may ask of the nominal arm carrying the
#: heaviest payload of :data:`PAYLOAD_RANGE` (the rest is room for the unknown true arm and the feedback).
TORQUE_SHARE = 0.5
#: Periods of the cut-off dropped at each end of a filtered series (:func:`filtered_data`): there the filter's
#: start-up transient has not died out (a sine filtered at 5 Hz keeps errors of 2e-5 of its acceleration 1 s in).
EDGE_PERIODS = 5
#: The seed of the arm the book identifies (:func:`draw_arm`).
EXAMPLE_SEED = 7
#: The default cut-off of the low-pass filter of :func:`filtered_data` (Hz): ten times the highest harmonic
#: (0.5 Hz) of the book's excitation (:func:`optimise_excitation`), where the filter passes the motion unchanged.
CUTOFF = 5.0
#: Samples of one period on which :func:`optimise_excitation` checks its result.
FINE_SAMPLES = 10_001
#: The mean configuration of an exciting trajectory: elbow at -90 deg, quill in the middle of its stroke.
EXCITATION_OFFSET = (0.0, -0.5 * math.pi, 0.5, 0.0)


# --------------------------------------------------------------------------------------------------
# the black box: a true arm and its sensors
# --------------------------------------------------------------------------------------------------
def encoder_resolution(counts: int = ENCODER_COUNTS, quill: float = QUILL_RESOLUTION) -> np.ndarray:
    """The resolution of the joint encoders, shape (4,): ``2 pi / counts`` rad on joints 1, 2, 4 (counts per
    revolution after the gear) and ``quill`` m on joint 3.

    >>> [f"{r:.3e}" for r in encoder_resolution()]
    ['4.794e-05', '4.794e-05', '1.000e-06', '4.794e-05']
    """
    counts = check_count(counts, "counts", 1, 2 ** 40, "encoder counts per revolution")
    quill = check_positive(quill, "quill")
    step = 2.0 * math.pi / counts
    return np.array([step, step, quill, step])


def _resolution(resolution) -> np.ndarray:
    r = np.array(as_array(resolution, "resolution", (4,)))
    if np.any(r <= 0):
        i = int(np.argmax(r <= 0))
        raise ScaraError(f"resolution[{i}] = {r[i]:g} must be > 0 (an encoder step, rad or m)")
    return r


def quantise(q, resolution=None) -> np.ndarray:
    """Encoder readings of the joint positions ``q`` (N, 4) or (4,): each entry rounded to the nearest multiple
    of its joint's ``resolution`` (4,) (default :func:`encoder_resolution`), so the error is at most half a
    count. Returns a new array.

    >>> quantise([0.1, 0.2, 0.3000004, 0.0])[2]
    np.float64(0.3)
    """
    q = as_array(q, "q", (4,), allow_batch=True)
    r = encoder_resolution() if resolution is None else _resolution(resolution)
    with np.errstate(over="ignore", invalid="ignore"):
        out = np.round(q / r) * r
    return check_finite_result(out, "quantised q", q=q, resolution=1.0 / r)


def draw_arm(seed: int, spread: float = PARAM_SPREAD, payload=PAYLOAD_RANGE, base: ScaraParams | None = None
             ) -> ScaraParams:
    """A true arm the experimenter does not know: every field of :data:`DRAWN_FIELDS` (the link masses
    ``m_l1, m_l2, m_l3``, the inertias ``I_l1, I_l2, I_l4``, each rotor inertia ``I_m`` and each friction
    ``F_m``) drawn uniformly within ``+-spread`` (default 20 %) of its value in ``base`` (default
    ``ScaraParams()``), and the payload ``m_L`` uniformly in ``payload`` (default 0 to 10 kg). The geometry, the
    gear ratios and ``g0`` are those of ``base``. The same ``seed`` gives the same arm.

    >>> arm = draw_arm(1)
    >>> 8.0 <= arm.m_l3 <= 12.0 and 0.0 <= arm.m_L <= 10.0
    True
    """
    base = ScaraParams.resolve(base)
    seed = check_count(seed, "seed", 0, 2 ** 63 - 1, "seed")
    spread = check_positive(spread, "spread", strict=False)
    if spread >= 1:
        raise ScaraError(f"spread = {spread:g} must be < 1: a relative spread of 100 % or more allows a zero or "
                         f"negative mass")
    lo, hi = (float(v) for v in as_array(payload, "payload", (2,)))
    if not 0 <= lo <= hi:
        raise ScaraError(f"payload = ({lo:g}, {hi:g}) kg must be a range 0 <= low <= high")
    rng = np.random.default_rng(seed)
    changes = {}
    for name in DRAWN_FIELDS:
        nominal = np.asarray(getattr(base, name), dtype=float)
        value = nominal * (1.0 + rng.uniform(-spread, spread, nominal.shape))
        changes[name] = tuple(value.tolist()) if value.ndim else float(value)
    changes["m_L"] = float(rng.uniform(lo, hi))
    return base.replace(**changes)


# --------------------------------------------------------------------------------------------------
# the exciting trajectory
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class FourierExcitation:
    """A periodic joint motion, a finite Fourier series of ``n_h`` harmonics per joint (Swevers et al. 1997; the
    book's ``(eq-id-fourier)``):

        q_i(t) = qbar_i + sum_l [a_il / (l w) sin(l w t) - b_il / (l w) cos(l w t)],   w = 2 pi / period

    so ``qd_i = sum_l a_il cos(l w t) + b_il sin(l w t)`` and ``qdd_i = sum_l l w (b_il cos - a_il sin)``.
    ``a``, ``b`` (4, n_h) in rad/s (m/s for the quill), ``offset`` (4,) the mean ``qbar`` (rad, m), ``period``
    (s). Build it with :meth:`at_rest`, which makes it start (and, being periodic, end) at rest.

    >>> e = FourierExcitation(np.zeros((4, 1)), [[1.0], [0.0], [0.0], [0.0]], [0.0, 0.0, 0.5, 0.0], 2 * np.pi)
    >>> [round(float(v), 12) for v in e.motion([0.0])[0][0]]      # q_1(0) = -b_11 / w
    [-1.0, 0.0, 0.5, 0.0]
    """

    a: np.ndarray
    b: np.ndarray
    offset: np.ndarray
    period: float

    def __post_init__(self):
        a = _matrix(self.a, "a")
        b = _matrix(self.b, "b")
        if a.shape != b.shape:
            raise ShapeError(f"a and b must have the same shape (4, H), got {a.shape} and {b.shape}")
        object.__setattr__(self, "a", a)
        object.__setattr__(self, "b", b)
        object.__setattr__(self, "offset", np.array(as_array(self.offset, "offset", (4,))))
        object.__setattr__(self, "period", check_positive(self.period, "period"))

    @property
    def harmonics(self) -> int:
        """The number ``n_h`` of harmonics per joint."""
        return self.a.shape[1]

    @property
    def omega(self) -> float:
        """The base angular frequency ``w = 2 pi / period`` (rad/s)."""
        return 2.0 * math.pi / self.period

    @classmethod
    def at_rest(cls, free, offset=EXCITATION_OFFSET, period: float = 10.0) -> "FourierExcitation":
        """The series whose first harmonic is chosen so that it starts at rest, ``qd(0) = 0`` and ``qdd(0) = 0``:
        ``a_i1 = -sum_{l>1} a_il`` and ``b_i1 = -sum_{l>1} l b_il``. ``free`` (4, 2 (n_h - 1)) holds the other
        coefficients, ``[a_i2 ... a_in_h, b_i2 ... b_in_h]`` per joint (a flat vector is reshaped).

        >>> e = FourierExcitation.at_rest(np.ones((4, 4)))
        >>> q, qd, qdd = e.motion([0.0, 10.0])
        >>> bool(np.abs(qd).max() < 1e-12 and np.abs(qdd).max() < 1e-12 and np.allclose(q[0], q[1]))
        True
        """
        free = as_array(free, "free", (np.size(free),)) if np.ndim(free) == 1 else _matrix(free, "free")
        if free.size % 8 or free.size == 0:
            raise ShapeError(f"free must hold 2 (H - 1) coefficients per joint, 8 (H - 1) in all with H >= 2, got "
                             f"{free.size}")
        free = _matrix(free.reshape(4, -1), "free")
        h = free.shape[1] // 2 + 1
        l = np.arange(2, h + 1)
        a = np.empty((4, h))
        b = np.empty((4, h))
        a[:, 1:], b[:, 1:] = free[:, :h - 1], free[:, h - 1:]
        a[:, 0] = -a[:, 1:].sum(axis=1)
        b[:, 0] = -(b[:, 1:] * l).sum(axis=1)
        return cls(a, b, offset, period)

    def free(self) -> np.ndarray:
        """The free coefficients of :meth:`at_rest`, a flat vector of ``8 (H - 1)`` entries."""
        return np.hstack([self.a[:, 1:], self.b[:, 1:]]).ravel()

    def motion(self, t) -> tuple:
        """``(q, qd, qdd)``, each (N, 4), at the times ``t`` (N,) (s)."""
        t = as_array(t, "t", (np.size(t),))
        l = np.arange(1, self.harmonics + 1) * self.omega
        s, c = np.sin(np.outer(t, l)), np.cos(np.outer(t, l))
        q = self.offset + s @ (self.a / l).T - c @ (self.b / l).T
        qd = c @ self.a.T + s @ self.b.T
        qdd = c @ (self.b * l).T - s @ (self.a * l).T
        return q, qd, qdd

    def reference(self, periods: int = 1, dt: float = 1e-3) -> np.ndarray:
        """The joint reference ``[q, qd, qdd]`` (N, 12) over ``periods`` whole periods at ``dt``, both ends
        included, as :func:`scara.simulate` takes it (``joint_reference=``); ``period`` must be a whole number
        of samples."""
        periods = check_count(periods, "periods", 1, 1000, "periods")
        dt = check_positive(dt, "dt")
        per = round(self.period / dt)
        if abs(per * dt - self.period) > 1e-9 * self.period:
            raise ScaraError(f"period = {self.period:g} s is not a whole number of samples of dt = {dt:g} s")
        t = np.arange(periods * per + 1) * dt
        return np.hstack(self.motion(t))


def _matrix(value, name) -> np.ndarray:
    arr = _numbers(value, f"{name} must be an array of numbers", ShapeError)
    if arr.ndim != 2 or arr.shape[0] != 4 or arr.shape[1] < 1:
        raise ShapeError(f"{name} must have shape (4, H) with H >= 1, got {arr.shape}")
    return np.array(as_array(arr, name, (arr.shape[1],), allow_batch=True))


@kernel
def _stacked_regressor_kernel(q, qd, qdd, dp, out):
    """``out[4k:4k+4] = Y(q[k], qd[k], qd[k], qdd[k])`` for every sample ``k``: the stacked regressor."""
    for k in range(q.shape[0]):
        regressor_kernel(q[k], qd[k], qd[k], qdd[k], dp, out[4 * k:4 * k + 4])


def _series(q, qd, qdd):
    q = as_array(q, "q", (4,), allow_batch=True)
    qd = as_array(qd, "qd", (4,), allow_batch=True)
    qdd = as_array(qdd, "qdd", (4,), allow_batch=True)
    if q.ndim != 2 or not (q.shape == qd.shape == qdd.shape):
        raise ShapeError(f"q, qd and qdd must all have shape (N, 4), got {q.shape}, {qd.shape}, {qdd.shape}")
    if len(q) < 1:
        raise ShapeError("q, qd and qdd hold no sample: a motion needs at least one (N >= 1)")
    check_angles(q, "q")
    return (np.ascontiguousarray(a, dtype=float) for a in (q, qd, qdd))


def stacked_regressor(q, qd, qdd, p: ScaraParams | None = None) -> np.ndarray:
    """The stacked regressor ``Y_bar`` (4N, 13) of a motion ``q, qd, qdd`` (N, 4) (the book's
    ``(eq-id-stacked)``): rows ``4k .. 4k+3`` are ``Y(q_k, qd_k, qd_k, qdd_k)`` of :func:`scara.regressor`, so
    that ``Y_bar pi`` is the torque series ``tau`` (N, 4) flattened row by row (``tau.ravel()``). Only the
    geometry and ``g0`` of ``p`` enter.

    >>> q = np.zeros((2, 4)); q[:, 2] = 0.5
    >>> stacked_regressor(q, np.zeros((2, 4)), np.zeros((2, 4))).shape
    (8, 13)
    """
    q, qd, qdd = _series(q, qd, qdd)
    out = np.empty((4 * len(q), N_PI))
    _stacked_regressor_kernel(q, qd, qdd, dynamic_array(p), out)
    return check_finite_result(out, "Y_bar", qd=qd, qdd=qdd)


def regressor_condition(q, qd, qdd, p: ScaraParams | None = None) -> float:
    """The condition number of :func:`stacked_regressor` along a motion ``q, qd, qdd`` (N, 4), its largest
    singular value over its smallest (the book's ``(eq-id-cond)``); ``inf`` when ``Y_bar`` is rank deficient.

    >>> q = np.tile([0.0, 1.0, 0.5, 0.0], (3, 1))
    >>> regressor_condition(q, np.zeros((3, 4)), np.zeros((3, 4)))    # at rest only the weight is seen
    inf
    """
    s = np.linalg.svd(stacked_regressor(q, qd, qdd, p), compute_uv=False)
    return float(s[0] / s[-1]) if s[-1] > 0 else math.inf


def _torque_limits(p: ScaraParams) -> np.ndarray:
    from .control._common import TAU_MAX  # noqa: PLC0415 - the actuator bounds of the control chapter
    return TORQUE_SHARE * np.asarray(TAU_MAX)


def excitation_margins(q, qd, qdd, p: ScaraParams | None = None) -> np.ndarray:
    """The constraints of an exciting trajectory along ``q, qd, qdd`` (N, 4), each ``>= 0`` when it holds, in
    one vector: the quill's distance to each end of its stroke less :data:`STROKE_MARGIN` (m), then
    ``1 - (qd_i / v_i)^2`` for the speeds :data:`SPEED_LIMITS`, then ``1 - (tau_i / t_i)^2`` for the torque of
    the arm ``p`` (default the nominal arm carrying the heaviest payload of :data:`PAYLOAD_RANGE`) against
    :data:`TORQUE_SHARE` of the actuator bounds.
    """
    q, qd, qdd = _series(q, qd, qdd)
    p = ScaraParams().with_payload(PAYLOAD_RANGE[1]) if p is None else ScaraParams.resolve(p)
    tau = inverse_dynamics(q, qd, qdd, p)
    with np.errstate(over="ignore"):
        out = np.concatenate([q[:, 2] - p.d3_min - STROKE_MARGIN, p.d3_max - STROKE_MARGIN - q[:, 2],
                              (1.0 - (qd / np.asarray(SPEED_LIMITS)) ** 2).ravel(),
                              (1.0 - (tau / _torque_limits(p)) ** 2).ravel()])
    return check_finite_result(out, "excitation margins", qd=qd, tau=tau)


@dataclass(frozen=True)
class ExcitationDesign:
    """The result of :func:`optimise_excitation`: the optimised ``excitation``, the condition numbers of
    ``Y_bar`` at the start (``cond_start``) and at the end (``cond``) of the search, on the design grid, and
    scipy's ``success`` flag, ``message`` and number of iterations ``iterations``; ``start`` the excitation the
    search started from; ``fine_margin`` the smallest of :func:`excitation_margins` on :data:`FINE_SAMPLES`
    samples of a period (between the grid's samples a limit may be passed by a little: negative then)."""

    excitation: FourierExcitation
    start: FourierExcitation
    cond: float
    cond_start: float
    success: bool
    message: str
    iterations: int
    fine_margin: float


def optimise_excitation(harmonics: int = 5, period: float = 10.0, seed: int = 0, grid: int = 200,
                        offset=EXCITATION_OFFSET, maxiter: int = 200, p: ScaraParams | None = None
                        ) -> ExcitationDesign:
    """The exciting trajectory: the coefficients of a :class:`FourierExcitation` (starting at rest) that minimise
    the condition number of ``Y_bar`` (:func:`regressor_condition`) on ``grid`` samples of one period, subject to
    :func:`excitation_margins` on the same samples (the stroke, the speeds, the torques), by scipy's SLSQP from
    small random coefficients drawn with ``seed``. The objective is ``log cond``, which is smoother. The result
    is checked on :data:`FINE_SAMPLES` samples of a period: the quill must stay in its stroke and the torques
    within the actuator bounds ``TAU_MAX`` (the margins :data:`STROKE_MARGIN` and :data:`TORQUE_SHARE` leave
    room for what happens between the grid's samples).

    The search's path follows the last bits of every SVD and of SLSQP's own linear algebra, which depend on the
    BLAS kernels a CPU gets: two CPUs reach the same optimum to about 1e-6 in its condition number, but not the
    same coefficients bit for bit. The book's design is therefore the one a search found, kept as data
    (:func:`book_design`).

    ``p`` is the arm whose torques are bounded (default: :func:`excitation_margins`'s). Raises
    :class:`~scara.ScaraError` when the start is infeasible or the search ends outside the constraints.
    """
    from scipy.optimize import minimize  # noqa: PLC0415
    from threadpoolctl import threadpool_limits  # noqa: PLC0415

    harmonics = check_count(harmonics, "harmonics", 2, 20, "harmonics per joint")
    grid = check_count(grid, "grid", 4 * harmonics, 5000, "samples of the design grid",
                       "at least twice the samples of the highest harmonic's period on each side")
    maxiter = check_count(maxiter, "maxiter", 1, 10_000, "iterations")
    seed = check_count(seed, "seed", 0, 2 ** 63 - 1, "seed")
    period = check_positive(period, "period")
    offset = np.array(as_array(offset, "offset", (4,)))
    t = np.arange(grid) * (period / grid)
    x0 = _search_start(harmonics, seed)

    def build(x):
        return FourierExcitation.at_rest(x, offset, period)

    def objective(x):
        s = np.linalg.svd(stacked_regressor(*build(x).motion(t), p), compute_uv=False)
        return math.log(s[0] / max(s[-1], 1e-300))

    def margins(x):
        return excitation_margins(*build(x).motion(t), p)

    if margins(x0).min() < 0:
        raise ScaraError("the start of the search breaks the excitation's constraints: choose another offset")
    # SLSQP's path follows the last bits of each SVD, and a multi-threaded BLAS sums in an order that depends on its
    # thread count: one thread makes the design the same on every run of a machine (and, on two cores, faster)
    with threadpool_limits(limits=1, user_api="blas"):
        res = minimize(objective, x0, method="SLSQP", constraints=[{"type": "ineq", "fun": margins}],
                       options={"maxiter": maxiter, "ftol": 1e-6})
    return _design(build(res.x), build(x0), t, p, bool(res.success), str(res.message), int(res.nit))


def _search_start(harmonics: int, seed: int) -> np.ndarray:
    """The start of :func:`optimise_excitation`'s search: small coefficients drawn with ``seed``, a tenth of each
    joint's speed limit spread over the harmonics."""
    scale = np.repeat(0.1 * np.asarray(SPEED_LIMITS) / harmonics, 2 * (harmonics - 1))
    return np.random.default_rng(seed).standard_normal(8 * (harmonics - 1)) * scale


def _design(best: FourierExcitation, start: FourierExcitation, t, p, success: bool, message: str,
            iterations: int) -> ExcitationDesign:
    """The design ``best`` (searched from ``start`` on the grid ``t``) checked and described: its margins on the
    grid (they must hold), the stroke and the actuator bounds on :data:`FINE_SAMPLES` samples, the condition
    numbers of both on the grid."""
    worst = float(excitation_margins(*best.motion(t), p).min())
    if worst < -1e-6:
        raise ScaraError(f"the optimised excitation breaks its constraints on the design grid by {-worst:.3g} "
                         f"({message})")
    fine = np.linspace(0.0, best.period, FINE_SAMPLES)
    q, qd, qdd = best.motion(fine)
    arm = ScaraParams().with_payload(PAYLOAD_RANGE[1]) if p is None else ScaraParams.resolve(p)
    tau = inverse_dynamics(q, qd, qdd, arm)
    from .control._common import TAU_MAX  # noqa: PLC0415
    if q[:, 2].min() < arm.d3_min or q[:, 2].max() > arm.d3_max or np.any(np.abs(tau) > np.asarray(TAU_MAX)):
        raise ScaraError("between the samples of the design grid the optimised excitation leaves the quill's stroke "
                         "or the actuator bounds TAU_MAX: use a finer grid")
    return ExcitationDesign(best, start, regressor_condition(*best.motion(t), p),
                            regressor_condition(*start.motion(t), p), success, message, iterations,
                            float(excitation_margins(q, qd, qdd, p).min()))


#: The book's exciting trajectory: the free coefficients (:meth:`FourierExcitation.at_rest`, rad/s and m/s) that
#: ``optimise_excitation()`` found with its defaults (5 harmonics, 10 s, seed 0, 200 samples) in
#: :data:`BOOK_DESIGN_ITERATIONS` iterations. Kept as data so that the chapter's experiment, and every number
#: after it, is the same on every CPU (the search's last digits are not: see :func:`optimise_excitation`).
BOOK_DESIGN = (-0.014288805581552821, 0.4235203174461984, 0.4409003843283451, -0.16874141856238123,
               -0.2218806215832313, -0.13755485061245526, 0.32735244678191144, -0.0020249957525519525,
               0.18703129767396728, 0.08490958026988092, -0.33018252520977404, 0.38284351152931156,
               -0.24490992730192154, 0.02624985696361509, -0.3245790330197301, 0.2022355398252587,
               -0.21254228114020626, -0.04607638177112201, 0.17218776868386754, 0.1666358565121356,
               -0.012524071783777502, 0.15089827371029857, -0.25625526094087075, 0.13945222574446428,
               0.07407160346097684, 0.004624050371519182, -0.051315604751007764, -0.07754730719530527,
               -0.046770342594671936, 0.015431877063952064, -0.11770349208895385, -0.015626540756073202)
#: the iterations of the search that found :data:`BOOK_DESIGN`
BOOK_DESIGN_ITERATIONS = 33


def book_design() -> ExcitationDesign:
    """The book's excitation design: :data:`BOOK_DESIGN`, checked and described as :func:`optimise_excitation`
    describes its result (the same grid, start and arm), with the iterations of the search that found it. A search
    with the defaults reaches the same condition number to about 1e-6 on any CPU (tested).

    >>> d = book_design()
    >>> round(d.cond, 3), d.iterations
    (29.087, 33)
    """
    t = np.arange(200) * (10.0 / 200)
    return _design(FourierExcitation.at_rest(BOOK_DESIGN), FourierExcitation.at_rest(_search_start(5, 0)), t, None,
                   True, "the book's design (found by optimise_excitation())", BOOK_DESIGN_ITERATIONS)


# --------------------------------------------------------------------------------------------------
# the measurement
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Measurement:
    """What the sensors give along a run: ``t`` (N,) s, the encoder readings ``q`` (N, 4) and the noisy torques
    ``tau`` (N, 4); ``sigma`` (4,) the noise's standard deviation, ``resolution`` (4,) the encoders'. ``run`` is
    the simulation itself (the exact ``q, qd, qdd, tau`` the experimenter never sees; for checks only)."""

    t: np.ndarray
    q: np.ndarray
    tau: np.ndarray
    sigma: np.ndarray
    resolution: np.ndarray
    run: object = field(repr=False, default=None)

    @property
    def dt(self) -> float:
        """The sampling period (s)."""
        return float(self.t[1] - self.t[0])

    def first(self, n: int) -> "Measurement":
        """The first ``n`` samples of this record (a shorter experiment with the same sensors and the same noise
        level ``sigma``), as new arrays; ``run`` is left out."""
        n = check_count(n, "n", 2, len(self.t), "samples", f"the record holds {len(self.t)}")
        return Measurement(self.t[:n].copy(), self.q[:n].copy(), self.tau[:n].copy(), self.sigma.copy(),
                           self.resolution.copy(), None)


def torque_noise_std(tau, fraction: float = NOISE_FRACTION) -> np.ndarray:
    """The standard deviation of the torque noise, ``fraction`` of each joint's peak ``|tau_i|`` over the run
    ``tau`` (N, 4), shape (4,) (N m, N for joint 3).

    >>> torque_noise_std([[1.0, -2.0, 30.0, 0.5], [-4.0, 1.0, 10.0, 0.1]]).tolist()
    [0.04, 0.02, 0.3, 0.005]
    """
    tau = as_array(tau, "tau", (4,), allow_batch=True).reshape(-1, 4)
    if len(tau) == 0:
        raise ShapeError("tau holds no sample: the noise is a share of each joint's peak torque over at least one")
    fraction = check_positive(fraction, "fraction")
    return fraction * np.abs(tau).max(axis=0)


def read_sensors(run, seed: int, noise: float = NOISE_FRACTION, resolution=None, sigma=None) -> Measurement:
    """What the sensors read along a finished ``run`` (a :class:`~scara.SimulationResult`): the joint positions
    quantised to ``resolution`` (default :func:`encoder_resolution`; :func:`quantise`) and the torques with white
    Gaussian noise of standard deviation ``sigma`` (4,) (default ``noise`` times each joint's peak torque on the
    run, :func:`torque_noise_std`), drawn with ``seed``. Returns a :class:`Measurement` of new arrays, without
    the ``run`` (the caller's own object)."""
    from ._simulate.result import SimulationResult  # noqa: PLC0415

    if not isinstance(run, SimulationResult):
        raise ScaraError(f"run must be a SimulationResult (a run of scara.simulate), got {type(run).__name__}")
    seed = check_count(seed, "seed", 0, 2 ** 63 - 1, "seed")
    resolution = encoder_resolution() if resolution is None else _resolution(resolution)
    if len(run.t) < 2:
        raise ShapeError(f"a measurement needs at least 2 samples, the run has {len(run.t)}")
    sigma = torque_noise_std(run.tau, noise) if sigma is None else _positive_vector(sigma, "sigma")
    rng = np.random.default_rng(seed)
    tau = run.tau + rng.standard_normal(run.tau.shape) * sigma
    return Measurement(run.t.copy(), quantise(run.q, resolution), tau, sigma, resolution)


def measure(arm: ScaraParams, reference, seed: int, noise: float = NOISE_FRACTION, resolution=None,
            controller=None, dt: float = 1e-3) -> Measurement:
    """Run the true ``arm`` along the joint ``reference`` (N, 12) ``[q_d, qd_d, qdd_d]`` (e.g.
    :meth:`FourierExcitation.reference`) under ``controller`` (default :class:`~scara.PDGravityController` with
    the nominal model; any joint-space controller) at ``dt``, and read its sensors (:func:`read_sensors`); the
    :class:`Measurement` keeps the run as ``run``.
    A reference whose ``d3`` leaves the quill's stroke raises :class:`~scara.UnreachableError`.
    """
    from ._simulate import PDGravityController, simulate  # noqa: PLC0415

    arm = ScaraParams.resolve(arm)
    ref = as_array(reference, "reference", (12,), allow_batch=True)
    if ref.ndim != 2:
        raise ShapeError(f"reference must have shape (N, 12), got {ref.shape}")
    d3 = ref[:, 2]
    if d3.min() < arm.d3_min or d3.max() > arm.d3_max:
        k = int(np.argmax((d3 < arm.d3_min) | (d3 > arm.d3_max)))
        raise UnreachableError(f"reference[{k}, 2]: d3 = {d3[k]:.6g} m is outside the quill's stroke "
                               f"[{arm.d3_min:g}, {arm.d3_max:g}] m")
    run = simulate(PDGravityController() if controller is None else controller, plant=arm, dt=dt,
                   joint_reference=ref)
    return dataclasses.replace(read_sensors(run, seed, noise, resolution), run=run)


def _positive_vector(value, name) -> np.ndarray:
    v = np.array(as_array(value, name, (4,)))
    if np.any(v <= 0):
        i = int(np.argmax(v <= 0))
        raise ScaraError(f"{name}[{i}] = {v[i]:g} must be > 0")
    return v


# --------------------------------------------------------------------------------------------------
# filtering and differentiation
# --------------------------------------------------------------------------------------------------
def lowpass(x, cutoff: float, dt: float, order: int = 4) -> np.ndarray:
    """Zero-phase low-pass filtering of the series ``x`` (N,) or (N, m) along its first axis: a Butterworth
    filter of ``order`` with cut-off ``cutoff`` (Hz) at the sampling period ``dt`` (s), run forward and
    backward (``scipy.signal.filtfilt``), so it delays nothing. Returns a new array.

    >>> t = np.arange(0, 4, 1e-3)          # 1 Hz kept, 100 Hz removed (away from the ends, see filtered_data)
    >>> y = lowpass(np.sin(2 * np.pi * t) + 0.1 * np.sin(2 * np.pi * 100 * t), 5.0, 1e-3)
    >>> bool(np.abs(y - np.sin(2 * np.pi * t))[1000:-1000].max() < 1e-4)
    True
    """
    from scipy.signal import butter, filtfilt  # noqa: PLC0415

    dt = check_positive(dt, "dt")
    cutoff = check_positive(cutoff, "cutoff")
    order = check_count(order, "order", 1, 10, "filter order")
    if cutoff >= 0.5 / dt:
        raise ScaraError(f"cutoff = {cutoff:g} Hz must be below the Nyquist frequency 1 / (2 dt) = {0.5 / dt:g} Hz")
    x = _numbers(x, "x must be a series of numbers", ShapeError)
    if x.ndim not in (1, 2):
        raise ShapeError(f"x must be a series of shape (N,) or (N, m), got {x.shape}")
    if not np.all(np.isfinite(x)):
        raise NonFiniteError("x holds NaN or infinite entries; every sample must be a finite number")
    b, a = butter(order, cutoff, fs=1.0 / dt)
    need = 3 * max(len(a), len(b))
    if len(x) <= need:
        raise ShapeError(f"x has {len(x)} samples; zero-phase filtering of order {order} needs more than {need}")
    return filtfilt(b, a, x, axis=0)


@dataclass(frozen=True)
class FilteredData:
    """Filtered, differentiated and decimated samples (:func:`filtered_data`): ``t`` (M,), ``q, qd, qdd, tau``
    (M, 4); ``cutoff`` (Hz) and ``step`` (samples kept one in ``step``)."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    tau: np.ndarray
    cutoff: float
    step: int


def filtered_data(t, q, tau, cutoff: float = CUTOFF, order: int = 4) -> FilteredData:
    """Velocities and accelerations from encoder readings (the book's ``(eq-id-filter)``): ``q`` (N, 4) and
    ``tau`` (N, 4) filtered by the same zero-phase low-pass filter (:func:`lowpass`), so that the regressor
    built from them and the torques stay consistent; ``qd`` and ``qdd`` by central differences of the filtered
    ``q`` (``numpy.gradient``, second order). A torque ``tau_k`` is held over ``[t_k, t_k + dt)`` (zero-order
    hold), so the second difference of ``q`` around ``t_k`` sees the mean of ``tau_{k-1}`` and ``tau_k``: that
    mean (the book's ``(eq-id-hold)``) is the torque paired with sample ``k``. Then one sample in ``step = round(1 / (2 cutoff dt))`` kept (the
    Nyquist frequency of the kept samples is the cut-off, so their noise is close to white), leaving out
    :data:`EDGE_PERIODS` periods of the cut-off at each end, where the filter's start-up transient (``filtfilt``
    pads the series by reflection) and the one-sided differences spoil the derivatives.

    For ``q = A sin(w t)`` the kept ``qd`` is ``A w |H(w)|^2 sinc(w dt) cos(w t)`` (``|H|^2`` the filter's gain
    forward and backward, ``sinc(x) = sin(x) / x`` the central difference's), which the tests check.
    """
    t = as_array(t, "t", (np.size(t),))
    q = as_array(q, "q", (4,), allow_batch=True)
    tau = as_array(tau, "tau", (4,), allow_batch=True)
    if q.ndim != 2 or q.shape != tau.shape or len(t) != len(q):
        raise ShapeError(f"t (N,), q (N, 4) and tau (N, 4) must have the same N, got {t.shape}, {q.shape}, "
                         f"{tau.shape}")
    if len(t) < 3:
        raise ShapeError(f"differentiation needs at least 3 samples, got {len(t)}")
    dt = float(t[1] - t[0])
    if dt <= 0 or np.abs(np.diff(t) - dt).max() > 1e-6 * dt:
        raise ScaraError("t must be uniformly increasing: the filter and the differences assume one sampling period")
    held = np.array(tau)
    held[1:] = 0.5 * (tau[1:] + tau[:-1])
    qf = lowpass(q, cutoff, dt, order)
    tf = lowpass(held, cutoff, dt, order)
    qd = np.gradient(qf, dt, axis=0)
    qdd = np.gradient(qd, dt, axis=0)
    step = max(1, round(0.5 / (cutoff * dt)))
    edge = math.ceil(EDGE_PERIODS / (cutoff * dt))
    keep = np.arange(edge, len(t) - edge, step)
    if len(keep) < 1:
        raise ShapeError(f"{len(t)} samples leave none after dropping {edge} at each end (the filter's start and "
                         f"end, {EDGE_PERIODS} periods of the cut-off); record longer")
    return FilteredData(t[keep].copy(), qf[keep], qd[keep], qdd[keep], tf[keep], float(cutoff), int(step))


# --------------------------------------------------------------------------------------------------
# least squares
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Estimate:
    """A least-squares estimate of ``pi`` (:func:`least_squares`): ``pi`` (13,), its ``covariance`` (13, 13),
    ``std`` (13,) standard deviations, ``interval`` (13, 2) the confidence interval at ``confidence``,
    ``sigma`` (4,) the per-joint residual standard deviations (N m, N), ``dof`` the residual degrees of
    freedom, ``rank`` of the stacked regressor, ``weighted`` and ``samples`` (the number N of samples)."""

    pi: np.ndarray
    covariance: np.ndarray
    std: np.ndarray
    interval: np.ndarray
    sigma: np.ndarray
    dof: int
    rank: int
    weighted: bool
    confidence: float
    samples: int

    def table(self) -> list:
        """Rows ``(name, estimate, half-width of the interval)`` in the order of :data:`PI_NAMES`."""
        half = 0.5 * (self.interval[:, 1] - self.interval[:, 0])
        return [(n, float(v), float(h)) for n, v, h in zip(PI_NAMES, self.pi, half)]


def _stack(Y, tau):
    Y = _numbers(Y, "Y must be an array of numbers", ShapeError)
    if Y.ndim != 2 or Y.shape[1] != N_PI or Y.shape[0] % 4:
        raise ShapeError(f"Y must be a stacked regressor of shape (4N, {N_PI}), got {np.shape(Y)}")
    Y = as_array(Y, "Y", (N_PI,), allow_batch=True)
    tau = as_array(tau, "tau", (np.size(tau),))
    if tau.shape != (Y.shape[0],):
        raise ShapeError(f"tau must have shape ({Y.shape[0]},) to match Y {Y.shape} (the torques flattened sample "
                         f"by sample), got {tau.shape}")
    return Y, tau


def _rank(Y) -> tuple:
    """``(rank, singular values)`` of ``Y`` with numpy's default tolerance ``s_max max(shape) eps``."""
    s = np.linalg.svd(Y, compute_uv=False)
    tol = s[0] * max(Y.shape) * np.finfo(float).eps
    return int((s > tol).sum()), s


#: The most re-estimations of the weights of :func:`least_squares` (they settle to 1e-9 in a few).
MAX_REWEIGHTS = 50


def _weighted_fit(Y, tau, w) -> tuple:
    """The least-squares fit of the rows of ``Y pi = tau`` scaled by ``w`` (4N,): ``(pi, sigma)`` with ``sigma``
    (4,) each joint's residual standard deviation, ``|rho_i|^2 / (N - h_i)``, ``h_i`` the sum of the leverages
    (the diagonal of the scaled system's hat matrix) over joint ``i``'s rows: the share of the parameters its
    rows carry (the ``h_i`` add up to 13), which makes ``sigma_i^2`` unbiased when ``w`` are the true weights."""
    Yw = Y * w[:, None]
    Q, R = np.linalg.qr(Yw)
    pi = np.linalg.solve(R, Q.T @ (tau * w))
    resid = (tau - Y @ pi).reshape(-1, 4)
    leverage = (Q ** 2).sum(axis=1).reshape(-1, 4).sum(axis=0)
    return pi, np.sqrt((resid ** 2).sum(axis=0) / (len(resid) - leverage))


def least_squares(Y, tau, weighted: bool = True, confidence: float = 0.95) -> Estimate:
    """The least-squares estimate of ``pi`` from ``Y_bar pi = tau_bar`` (the book's ``(eq-id-ls)``; Siciliano
    et al. eq. 7.86), ``Y`` the stacked regressor (4N, 13) (:func:`stacked_regressor`) and ``tau`` (4N,) the
    torques flattened sample by sample.

    Ordinary least squares: ``pi_hat = (Y^T Y)^-1 Y^T tau`` with covariance ``s^2 (Y^T Y)^-1``,
    ``s^2 = |tau - Y pi_hat|^2 / (4N - 13)``. Weighted (``weighted=True``, Gautier's method; the book's
    ``(eq-id-wls)``): the residual ``rho_i`` of joint ``i`` gives its variance ``sigma_i^2 = |rho_i|^2 /
    (N - h_i)`` (``h_i`` the leverage of joint ``i``'s rows, :func:`_weighted_fit`), each row of joint ``i`` is
    divided by ``sigma_i`` and the scaled system solved again, until the ``sigma_i`` settle (the first pass is the
    ordinary fit); the covariance is ``(Y^T W Y)^-1``, ``W = diag(1 / sigma_i^2)`` repeated sample by sample.
    ``sigma`` holds the ``sigma_i`` (for the ordinary fit, those of its residual). The interval is
    ``pi_hat +- t std`` with ``t`` the Student quantile of ``confidence`` at ``4N - 13`` degrees of freedom.

    Raises :class:`~scara.ScaraError` when the data are too few (``4N <= 13``, or a joint's ``N`` not above the
    number ``n_i`` of parameters its rows involve) or
    ``Y`` is rank deficient (use :func:`base_parameters`).

    >>> rng = np.random.default_rng(0)
    >>> Y = rng.standard_normal((400, 13)); pi = np.arange(13.0)
    >>> est = least_squares(Y, Y @ pi + 1e-3 * rng.standard_normal(400))
    >>> bool(np.all((est.interval[:, 0] < pi + 0.01) & (pi - 0.01 < est.interval[:, 1])))
    True
    """
    from scipy.stats import t as student  # noqa: PLC0415

    Y, tau = _stack(Y, tau)
    confidence = check_positive(confidence, "confidence")
    if confidence >= 1:
        raise ScaraError(f"confidence = {confidence:g} must lie in (0, 1), e.g. 0.95")
    rows, n = Y.shape
    if rows <= n:
        raise ScaraError(f"{rows // 4} samples give {rows} equations for {n} parameters: least squares needs more "
                         f"equations than parameters (more than {n // 4 + 1} samples)")
    rank, _ = _rank(Y)
    if rank < n:
        raise ScaraError(f"the stacked regressor has rank {rank} < {n}: not every parameter is identifiable from "
                         f"this motion; excite it better or estimate the base parameters (base_parameters)")
    samples = rows // 4
    blocks = Y.reshape(-1, 4, n)
    n_i = np.count_nonzero(np.any(blocks != 0.0, axis=0), axis=1)    # the parameters each joint's rows involve
    if np.any(samples <= n_i):
        i = int(np.argmax(samples <= n_i))
        raise ScaraError(f"joint {i + 1} has {samples} samples for the {n_i[i]} parameters its rows involve: its "
                         f"residual variance needs more samples than that")
    dof = rows - n
    w = np.ones(rows)
    pi, sigma = _weighted_fit(Y, tau, w)
    if weighted:
        # Gautier's weights: each joint's rows divided by its residual standard deviation, re-estimated from the
        # weighted fit until they settle (each joint's residual dof is N less its share of the 13 parameters)
        for _ in range(MAX_REWEIGHTS):
            if np.any(sigma <= 0):
                raise ScaraError(f"the residual of joint {int(np.argmax(sigma <= 0)) + 1} is exactly zero: the "
                                 f"weights 1 / sigma_i are undefined (noise-free data); use weighted=False")
            w = np.tile(1.0 / sigma, samples)
            pi, new = _weighted_fit(Y, tau, w)
            settled = np.all(np.abs(new / sigma - 1) < 1e-9)
            sigma = new
            if settled:
                break
        w = np.tile(1.0 / sigma, samples)
        pi = _weighted_fit(Y, tau, w)[0]
        Yw = Y * w[:, None]
        cov = np.linalg.inv(Yw.T @ Yw)
    else:
        s2 = float(((tau - Y @ pi) ** 2).sum() / dof)
        cov = s2 * np.linalg.inv(Y.T @ Y)
    cov = 0.5 * (cov + cov.T)
    std = np.sqrt(np.diag(cov))
    half = float(student.ppf(0.5 + 0.5 * confidence, dof)) * std
    return Estimate(pi, cov, std, np.column_stack([pi - half, pi + half]), sigma, int(dof), rank, bool(weighted),
                    float(confidence), int(samples))


@dataclass(frozen=True)
class BaseParameters:
    """The identifiable combinations of ``pi`` along a motion (:func:`base_parameters`): ``rank``; the
    ``independent`` column indices (length ``rank``) and the ``dependent`` ones; ``K`` (rank, 13 - rank) such
    that the base parameters are ``pi[independent] + K pi[dependent]``; ``names`` those combinations, written
    out; ``singular_values`` of the stacked regressor."""

    rank: int
    independent: tuple
    dependent: tuple
    K: np.ndarray
    names: tuple
    singular_values: np.ndarray

    def of(self, pi) -> np.ndarray:
        """The base parameters ``pi[independent] + K pi[dependent]`` of a full parameter vector ``pi`` (13,)."""
        pi = as_array(pi, "pi", (N_PI,))
        return pi[list(self.independent)] + self.K @ pi[list(self.dependent)]


def base_parameters(Y, rtol: float | None = None) -> BaseParameters:
    """The identifiable combinations of the parameters along a motion whose stacked regressor is ``Y``
    (4N, 13): QR with column pivoting (``scipy.linalg.qr``) picks ``rank`` independent columns ``Y_1``; every
    other column is ``Y_2 = Y_1 K`` (``K = R_11^-1 R_12``), so ``Y pi = Y_1 (pi_1 + K pi_2)``: only the
    combinations ``pi_1 + K pi_2`` can be estimated (Siciliano et al. sec. 7.4; Gautier & Khalil). The rank
    counts singular values above ``rtol`` times the largest (default ``max(shape) eps``).

    >>> Y = np.ones((8, 13)); Y[:, 1:] = np.random.default_rng(0).standard_normal((8, 12))[:, :1]
    >>> base_parameters(Y).rank
    2
    """
    from scipy.linalg import qr, solve_triangular  # noqa: PLC0415

    Y = as_array(Y, "Y", (N_PI,), allow_batch=True)
    if Y.ndim != 2:
        raise ShapeError(f"Y must have shape (M, {N_PI}), got {Y.shape}")
    rank, s = _rank(Y)
    if rtol is not None:
        rtol = check_positive(rtol, "rtol")
        rank = int((s > rtol * s[0]).sum())
    _, R, perm = qr(Y, mode="economic", pivoting=True)
    ind, dep = perm[:rank], perm[rank:]
    K = solve_triangular(R[:rank, :rank], R[:rank, rank:]) if len(dep) else np.zeros((rank, 0))
    names = []
    for r, j in enumerate(ind):
        terms = [PI_NAMES[j]] + [f"{'-' if K[r, c] < 0 else '+'} {_coefficient(abs(K[r, c]))}{PI_NAMES[d]}"
                                 for c, d in enumerate(dep) if abs(K[r, c]) > 1e-9]
        names.append(" ".join(terms))
    return BaseParameters(rank, tuple(int(i) for i in ind), tuple(int(i) for i in dep), K, tuple(names), s)


def _coefficient(k: float) -> str:
    """``k`` as the factor of a term: nothing for 1 (to 9 digits), else ``k`` with 4 significant digits."""
    return "" if abs(k - 1.0) < 1e-9 else f"{k:.4g} "


def identify(measurement: Measurement, cutoff: float = CUTOFF, weighted: bool = True, confidence: float = 0.95,
             p: ScaraParams | None = None) -> tuple:
    """The whole chain: :func:`filtered_data` of the ``measurement`` at ``cutoff`` (Hz), the stacked regressor
    of the filtered motion (:func:`stacked_regressor`, geometry and ``g0`` of ``p``) and :func:`least_squares`.
    Returns ``(Estimate, FilteredData)``."""
    if not isinstance(measurement, Measurement):
        raise ScaraError(f"measurement must be a Measurement (see measure), got {type(measurement).__name__}")
    data = filtered_data(measurement.t, measurement.q, measurement.tau, cutoff)
    Y = stacked_regressor(data.q, data.qd, data.qdd, p)
    return least_squares(Y, data.tau.ravel(), weighted, confidence), data


def predicted_torques(q, qd, qdd, pi, p: ScaraParams | None = None) -> np.ndarray:
    """The torques ``Y(q, qd, qd, qdd) pi`` (N, 4) a parameter vector ``pi`` (13,) predicts along a motion
    ``q, qd, qdd`` (N, 4): the model of the book's ``(eq-dyn-regressor)`` with an estimate in place of the
    truth."""
    pi = as_array(pi, "pi", (N_PI,))
    with np.errstate(over="ignore", invalid="ignore"):
        out = (stacked_regressor(q, qd, qdd, p) @ pi).reshape(-1, 4)
    return check_finite_result(out, "Y pi", pi=pi, q=q, qd=qd, qdd=qdd)
