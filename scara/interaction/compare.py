"""The figures chapter 7 compares the interaction laws by, and the sweeps its figures draw: how fast a run settles
on the surface, the comparison table of the five laws (:func:`law_comparison`), the steady force of compliance
control against the surface's stiffness (:func:`stiffness_sweep`, formula (eq-int-equilibrium) beside the
simulation) and the force loop's polynomial and stability bound (:func:`force_loop_poly`,
:func:`force_loop_bounds`, (eq-int-force-routh) beside the sampled loop's).
"""
from __future__ import annotations

import numpy as np

from ..errors import ScaraError, as_array, check_count, check_positive
from .environment import ForceSensor, Surface
from .laws import ComplianceController, ForceController
from .stability import sampled_radius, z_axis
from .steady import _surface, approach_reference, contact_transition, elastic_equilibrium

__all__ = ["settling_time", "law_comparison", "stiffness_sweep", "force_loop_poly", "force_loop_bounds"]


def _contact_run(result, what: str):
    if getattr(result, "force", None) is None:
        raise ScaraError(f"{what} needs a run of simulate_contact, got {type(result).__name__}")
    return result


def _last(t, window: float) -> np.ndarray:
    """The samples of ``t`` (N,) within the last ``window`` s of the run, and at least the last one."""
    last = np.asarray(t) >= t[-1] - window + 1e-12
    last[-1] = True
    return last


def settling_time(result, band: float = 0.05, window: float = 1.0) -> float:
    """The time (s) from the first touch until the normal force ``-h_z`` stays within ``band`` (relative, default
    5 %) of its mean over the last ``window`` s of the run: NaN when the tool never touches, and the whole rest of
    the run when it is still outside the band at the end.

    >>> from types import SimpleNamespace as NS
    >>> t = np.arange(5) * 0.5
    >>> run = NS(t=t, force=np.array([[0, 0, 0], [0, 0, -20], [0, 0, -9], [0, 0, -10], [0, 0, -10.0]]),
    ...          in_contact=np.array([False, True, True, True, True]))
    >>> settling_time(run, window=0.5)
    1.0
    """
    _contact_run(result, "settling_time")
    band = check_positive(band, "band")
    window = check_positive(window, "window")
    touching = np.asarray(result.in_contact)
    if not touching.any():
        return float("nan")
    fn = -np.asarray(result.force)[:, 2]
    t = np.asarray(result.t)
    final = fn[_last(t, window)].mean()
    k0 = int(np.argmax(touching))
    out = np.flatnonzero(np.abs(fn[k0:] - final) > band * abs(final))
    if out.size == 0:
        return 0.0
    last = k0 + int(out[-1]) + 1
    return float(t[min(last, len(t) - 1)] - t[k0])


def law_comparison(runs: dict, force: float = 10.0, window: float = 1.0, band: float = 0.05) -> list[dict]:
    """One row per run of ``runs`` (``{name: ContactResult}``, runs that press the surface with ``force`` N):
    ``law``; ``force_error`` (N), ``force`` less the mean normal force over the last ``window`` s;
    ``penetration`` (mm), the mean of ``z_s - p_z`` over that window; ``peak_force`` (N) and ``bounced`` (the
    contact lost after the first touch) of :func:`~.steady.contact_transition`; ``settling_time`` (s, from the
    first touch, :func:`settling_time` with ``band``)."""
    if not isinstance(runs, dict) or not runs:
        raise ScaraError(f"runs must be a non-empty dict {{name: run of simulate_contact}}, got {runs!r:.80}")
    force = check_positive(force, "force")
    window = check_positive(window, "window")
    band = check_positive(band, "band")
    rows = []
    for name, run in runs.items():
        _contact_run(run, "law_comparison")
        last = _last(run.t, window)
        tr = contact_transition(run)
        rows.append({"law": name, "force_error": float(force - run.normal_force[last].mean()),
                     "penetration": float(1e3 * (run.surface.height - run.x[last, 2]).mean()),
                     "peak_force": tr["peak_force"], "bounced": tr["bounced"],
                     "settling_time": settling_time(run, band, window)})
    return rows


#: the largest number of runs a sweep may ask for (each run is a few thousand samples of the contact engine)
MAX_SWEEP_RUNS = 60


def stiffness_sweep(gains, stiffnesses, depth: float = 2e-3, at=(0.4, 0.1), lift: float = 0.01,
                    move: float = 0.5, hold: float = 1.5, points: int = 101, surface: Surface | None = None) -> dict:
    """Compliance control (:class:`~.laws.ComplianceController`, its ``K_P,z`` from ``gains`` (G,) N/m, the other
    gains the defaults) held ``depth`` m below the undeformed surface, on surfaces of stiffness ``stiffnesses``
    (K,) N/m (the rest of ``surface``, default ``Surface()``): the tool starts at rest ``lift`` m above the surface
    at ``at``, moves down in ``move`` s (a quintic) and holds ``hold`` s.

    Returns ``stiffness`` (K,), ``gains`` (G,), ``simulated`` (G, K) N: the normal force ``-h_z`` at the end of
    each run; ``formula`` (G, K) N: ``k_e K_P,z / (K_P,z + k_e) depth``, (eq-int-equilibrium); ``dense`` (points,)
    N/m and ``dense_formula`` (G, points) N: the formula on a log-spaced grid over the stiffnesses' range, for a
    curve. At most :data:`MAX_SWEEP_RUNS` runs.

    >>> out = stiffness_sweep([5000.0], [2e4], move=0.3, hold=0.7, points=2)
    >>> round(float(out["formula"][0, 0]), 6), bool(abs(out["simulated"][0, 0] - out["formula"][0, 0]) < 1e-3)
    (8.0, True)
    """
    from ..kinematics import ikine  # noqa: PLC0415
    from .engine import simulate_contact  # noqa: PLC0415

    g = np.atleast_1d(as_array(gains, "gains", (), allow_batch=True))
    k = np.atleast_1d(as_array(stiffnesses, "stiffnesses", (), allow_batch=True))
    if g.size < 1 or k.size < 1 or np.any(g <= 0) or np.any(k <= 0):
        raise ScaraError(f"gains = {g.tolist()} and stiffnesses = {k.tolist()} N/m must be non-empty and positive")
    check_count(g.size * k.size, "the runs (gains x stiffnesses)", 1, MAX_SWEEP_RUNS, "runs",
                "a sweep stays within a few seconds of simulation")
    points = check_count(points, "points", 2, 10_000, "samples of the formula's curve")
    depth = check_positive(depth, "depth")
    base = _surface(surface)
    xy = as_array(at, "at", (2,))
    lift = check_positive(lift, "lift")
    q = ikine([xy[0], xy[1], base.height + lift, 0.0], elbow=-1)
    start = np.array([xy[0], xy[1], base.height + lift, q[0] + q[1]])
    target = start.copy()
    target[2] = base.height - depth
    ref = approach_reference(start, target, move, hold)
    dense = np.geomspace(k.min(), k.max(), points)
    out = {"stiffness": k.copy(), "gains": g.copy(), "simulated": np.empty((g.size, k.size)),
           "formula": np.empty((g.size, k.size)), "dense": dense, "dense_formula": np.empty((g.size, points))}
    ideal = ForceSensor(noise=0.0, bias=(0.0, 0.0, 0.0))
    for i, kp in enumerate(g):
        law = ComplianceController(K_P=(5000.0, 5000.0, kp, 200.0))
        for j, ke in enumerate(k):
            s = Surface(height=base.height, stiffness=ke, damping=base.damping, friction=base.friction, v_s=base.v_s)
            run = simulate_contact(law, ref, surface=s, sensor=ideal, elbow=-1)
            out["simulated"][i, j] = run.normal_force[-1]
            out["formula"][i, j] = -elastic_equilibrium(law.K_P, target, s)[1][2]
        out["dense_formula"][i] = dense * kp / (kp + dense) * depth
    return out


def force_loop_poly(controller: ForceController | None = None, surface: Surface | None = None) -> np.ndarray:
    """The coefficients (4,) of the continuous-time characteristic polynomial of force control pressing on
    ``surface`` along z, highest power first, (eq-int-force-poly):
    ``s^3 + (K_D + K_P K_F d_e) s^2 + K_P (1 + K_F k_e + K_I d_e) s + K_P K_I k_e`` (the inner loop's per-mass
    ``K_P``, ``K_D``; ``np.roots`` gives its poles, 1/s).

    >>> force_loop_poly().round(6).tolist()
    [1.0, 72.5, 3750.0, 100000.0]
    """
    law = ForceController() if controller is None else controller
    if not isinstance(law, ForceController):
        raise ScaraError(f"force_loop_poly takes a ForceController, got {type(law).__name__}")
    s = _surface(surface)
    KP, KD, KF, KI = law.K_P[2], law.K_D[2], law.K_F[2], law.K_I[2]
    k, d = s.stiffness, s.damping
    return np.array([1.0, KD + KP * KF * d, KP * (1.0 + KF * k + KI * d), KP * KI * k])


def force_loop_bounds(controller: ForceController | None = None, surface: Surface | None = None,
                      dt: float = 1e-3, plant=None) -> dict:
    """The largest integral gain ``K_I`` (m/(N s)) of force control (:class:`~.laws.ForceController`, its other
    gains kept) pressing on ``surface``: ``routh``, the continuous-time bound (eq-int-force-routh),
    ``K_I < (K_D + K_P K_F d_e)(1 + K_F k_e) / (k_e - (K_D + K_P K_F d_e) d_e)``; ``sampled``, where the sampled
    loop along z (:func:`~.stability.sampled_radius`, period ``dt``) reaches the unit circle (bisection to a
    relative 1e-9); and ``radius``, the spectral radius of the controller's own loop.

    >>> b = force_loop_bounds()
    >>> round(b["routh"] * 1e3, 3), b["sampled"] < b["routh"]
    (6.198, True)
    """
    law = ForceController() if controller is None else controller
    if not isinstance(law, ForceController):
        raise ScaraError(f"force_loop_bounds takes a ForceController, got {type(law).__name__}")
    s = _surface(surface)
    dt = check_positive(dt, "dt")
    m, c = z_axis(plant)
    k, d = s.stiffness, s.damping
    KF = law.K_F[2]
    a2 = force_loop_poly(law, s)[1]
    if not k > a2 * d:
        raise ScaraError(f"k_e = {k:g} N/m must exceed (K_D + K_P K_F d_e) d_e = {a2 * d:g} N/m for the integral "
                         f"gain to be bounded")
    routh = a2 * (1.0 + KF * k) / (k - a2 * d)

    def radius(ki):
        trial = ForceController(law.f_d, law.K_P, law.K_D, law.K_F, [ki] * 3, law.model)
        return sampled_radius(trial.z_loops(m, c, k, d, dt)["contact"], m, c, k, d, dt)

    lo, hi = 0.0, 2.0 * routh
    if radius(hi) < 1.0:
        raise ScaraError(f"the sampled loop stays stable up to K_I = {hi:g} m/(N s), twice the continuous bound")
    while hi - lo > 1e-9 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if radius(mid) < 1.0 else (lo, mid)
    return {"routh": float(routh), "sampled": float(0.5 * (lo + hi)), "radius": radius(law.K_I[2])}
