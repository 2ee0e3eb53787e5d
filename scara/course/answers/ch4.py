"""The computations answering chapter 4's exercises (see :mod:`scara.course.answers`)."""
import math
from functools import lru_cache
from types import SimpleNamespace

import numpy as np

from scara import (clik, clik2, ikine, jacobian, plan_path, reference_trajectory, second_order_gains,
                   transpose_stability)
from scara.course.answers import solves
from scara.errors import ScaraError


@solves("ex-clik-lag")
def clik_lag(A: float, K: float, duration: float) -> dict:
    """The steady lag of the second-order CLIK (eq-clik-lag2: T A K_D / (2 K_P)) for a reference accelerating at
    ``A`` along z, predicted and measured at the end of a run of ``duration`` from a fixed pose of the arm."""
    dt = 1e-3
    n = int(round(duration / dt)) + 1
    t = np.arange(n) * dt
    ramp = SimpleNamespace(t=t, x=np.tile([0.4, -0.3, 0.7, 0.2], (n, 1)), xd=np.zeros((n, 4)),
                           xdd=np.zeros((n, 4)), dt=dt)
    ramp.x[:, 2] -= 0.5 * A * t**2
    ramp.xd[:, 2] = -A * t
    ramp.xdd[:, 2] = -A
    run = clik2(ramp, *second_order_gains(np.array([400.0, 400.0, K, 100.0])))
    measured = abs(run.e[-1, 2])
    predicted = dt * A / K
    if not np.isclose(measured, predicted, rtol=1e-4):  # the lag has not settled in the run
        raise ScaraError(f"exercise ex-clik-lag: after {duration} s the error {measured:.3e} m is not yet the "
                         f"steady lag {predicted:.3e} m (K = {K} s^-1 too small for the run)")
    return {"lag_um": measured * 1e6, "pred_um": predicted * 1e6}


@lru_cache(maxsize=1)
def _reference():
    """The 70 s reference of chapter 3 (built once per process)."""
    return reference_trajectory()


@solves("ex-clik-deadbeat")
def clik_deadbeat(T_ms: float) -> dict:
    """The deadbeat gain 1/T and the stability limit 2/T of the Euler-discretised inverse CLIK at a sampling
    period of ``T_ms``, checked by runs from a 1 mm / 1 mrad offset at rest: one step at 1/T leaves only the
    second-order remainder, 1.5/T flips the sign of the error every step."""
    dt = T_ms * 1e-3
    if not 0.1e-3 <= dt <= 10e-3:
        raise ScaraError(f"exercise ex-clik-deadbeat: a sampling period of {T_ms} ms is outside 0.1 to 10 ms")
    x_fixed = np.array([0.45, -0.25, 0.6, 0.3])
    n = 11
    still = SimpleNamespace(t=np.arange(n) * dt, x=np.tile(x_fixed, (n, 1)), xd=np.zeros((n, 4)), dt=dt)
    q_off = ikine(x_fixed, elbow=-1) + np.array([1e-3, -1e-3, 1e-3, 1e-3])
    deadbeat = clik(still, "inverse", 1 / dt, q0=q_off)
    ringing = clik(still, "inverse", 1.5 / dt, q0=q_off)
    ratio = float(np.abs(deadbeat.e[1]).max() / np.abs(deadbeat.e[0]).max())
    flips = bool(np.all(np.sign(ringing.e[1:4, 2]) == -np.sign(ringing.e[0:3, 2])))
    return {"K_deadbeat": 1 / dt, "K_limit": 2 / dt, "ratio": ratio, "ringing_flips": flips}


@solves("ex-clik-fragile")
def clik_fragile() -> dict:
    """The largest uniform gain kappa of the transpose on the reference, 2 / (T sigma_max^2), where sigma_max
    peaks, and the runs just below and above it on the panel's log grid (0.01 in log10 kappa)."""
    traj = _reference()
    dt = traj.dt
    stab = transpose_stability(traj, np.ones(4))
    kappa = 2 / dt / stab.mu_max
    q_w = ikine(traj.x[int(np.argmax(stab.mu))], elbow=-1)
    sigma = float(np.linalg.svd(jacobian(q_w), compute_uv=False).max())
    k_below = 10 ** (math.floor(100 * math.log10(kappa)) / 100)
    k_above = 10 ** (math.ceil(100 * math.log10(kappa)) / 100)
    below = clik(traj, "transpose", k_below)
    return {"kappa_max": float(kappa), "t_worst": float(stab.t_worst), "sigma_max": sigma, "mu_max": float(stab.mu_max),
            "k_below": float(k_below), "k_above": float(k_above),
            "below_mm": float(below.summary()["max_position_error"] * 1e3)}


@solves("ex-clik-relax")
def clik_relax() -> dict:
    """The pseudo-inverse with y, then z, relaxed on the reference: mean manipulability and drift of the relaxed
    coordinate, against the inverse's mean manipulability."""
    traj = _reference()
    relax_y = clik(traj, "pseudoinverse", relaxed="y")
    relax_z = clik(traj, "pseudoinverse", relaxed="z")
    w_inv = clik(traj, "inverse").summary()["mean_manipulability"]
    return {"w_y": float(relax_y.summary()["mean_manipulability"]),
            "w_z": float(relax_z.summary()["mean_manipulability"]), "w_inv": float(w_inv),
            "drift_y": float(np.abs(relax_y.e[:, 1]).max()), "drift_z": float(np.abs(relax_z.e[:, 2]).max())}


DAMPINGS = (0.01, 0.02, 0.05, 0.1)


@solves("ex-clik-damping")
def clik_damping(offset_mm: float) -> dict:
    """Damped least squares on the line y = ``offset_mm`` from x = -0.2 to 0.2 m (3 s, at rest 0.5 s), for each
    lambda of :data:`DAMPINGS`: peak joint-1 rate, largest position error, and the largest position error where
    the planned point is more than 5 cm from the axis. Keys ``rate_10``, ``err_10``, ``away_10`` for lambda =
    0.01 m, and so on (lambda in mm)."""
    if not 0.5 <= offset_mm <= 20.0:
        raise ScaraError(f"exercise ex-clik-damping: a line {offset_mm} mm from the axis is not 'near the axis' "
                         "(0.5 to 20 mm)")
    y = offset_mm * 1e-3
    line = plan_path([[-0.2, y, 0.5], [0.2, y, 0.5]], durations=[3.0], total=3.5)
    away = np.hypot(line.x[:, 0], line.x[:, 1]) > 0.05
    out = {}
    for lam in DAMPINGS:
        run = clik(line, "inverse", damping=lam)
        key = int(round(lam * 1000))
        out[f"rate_{key}"] = float(np.abs(run.qd[:, 0]).max())
        out[f"err_{key}"] = float(run.summary()["max_position_error"] * 1e3)
        out[f"away_{key}"] = float(np.linalg.norm(run.e[away, :3], axis=1).max() * 1e6)
    return out


@solves("ex-clik-second-limit")
def clik_second_limit() -> dict:
    """The stability limit 2/T of the second-order CLIK with K_P = K^2, K_D = 2K, and the largest errors on the
    reference as K_z rises (400, 1000 and 0.995 of the limit), against eq-clik-lag2's T A / K."""
    traj = _reference()
    dt = traj.dt
    k_limit = 2 / dt
    k_ok = 0.995 * k_limit
    runs = {name: clik2(traj, *second_order_gains(np.array([400.0, 400.0, kz, 100.0])))
            for name, kz in (("400", 400.0), ("1000", 1000.0), ("ok", k_ok))}
    A_z = float(np.abs(traj.xdd[:, 2]).max())
    out = {"k_limit": k_limit, "k_ok": k_ok, "Az": A_z,
           "pred_400_nm": dt * A_z / 400.0 * 1e9, "pred_1000_nm": dt * A_z / 1000.0 * 1e9}
    for name, run in runs.items():
        out[f"ez_{name}_nm"] = float(np.abs(run.e[100:, 2]).max() * 1e9)
        out[f"ep_{name}_nm"] = float(run.summary()["max_position_error"] * 1e9)
    return out
