"""The computations answering chapter 6's exercises (see :mod:`scara.course.answers`).

Each runs the chapter's 70 s reference at 1 ms; after numba has compiled the laws a run takes 0.02-0.1 s, so the
exercises vary what a student can predict (payload, bound, gain) and re-run the whole path for each set."""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from scara import (AdaptiveController, ComputedTorqueController, IndependentJointController,
                   OperationalSpaceController, PDPlusGravityController, RobustController, ScaraParams, UnstableError,
                   clik2, inertia, reference_trajectory, simulate)
from scara._simulate import joint_setpoint
from scara.control import chattering, control_summary, inertia_eigenvalues
from scara.control import sampling_limit as omega_limit
from scara.course.answers import solves
from scara.errors import ScaraError


@lru_cache(maxsize=1)
def _setup():
    """The chapter's model (no payload), its 70 s reference and the CLIK joint references, computed once."""
    model = ScaraParams()
    traj = reference_trajectory()
    ref = clik2(traj)
    return model, traj, ref, ref.q[::250]


def _rest(run):
    """The samples of the last 2 s, when the arm is at rest at the end of the path."""
    return run.t >= run.t[-1] - 2.0


def _stop_time(exc: UnstableError) -> float:
    return float(str(exc).split("t = ")[1].split(" s")[0])


def _stopped(run, label: str, what: str, cause: str = "") -> float:
    """The time at which ``run()`` is stopped as diverging (its UnstableError naming ``cause``); a run that
    completes means the exercise's parameters miss its point: ScaraError, saying ``what`` completed."""
    try:
        run()
    except UnstableError as exc:
        if cause not in str(exc):
            raise
        return _stop_time(exc)
    raise ScaraError(f"exercise {label}: {what} completes")


def _payload(m_L: float) -> None:
    if not 0.0 <= m_L <= 10.0:
        raise ScaraError(f"a payload of {m_L} kg is outside the 0-10 kg the chapter's controllers are sized for")


@solves("ex-ctl-ij-pd")
def ij_pd(m_L: float, omega: float, sag_max_mm: float) -> dict:
    """PD independent-joint control (double pole at -omega): the quill's sag m3 g0 / (omega^2 B_bar33) at rest,
    the pole that keeps it below ``sag_max_mm``, and runs checking both."""
    _payload(m_L)
    model, traj, ref, _ = _setup()
    plant = model.with_payload(m_L)
    ctl = IndependentJointController(integral=False, omega=omega)
    weight = plant.m3 * plant.g0
    sag = weight / (omega ** 2 * ctl.B_bar[2])
    run = simulate(ctl, traj, plant, joint_reference=ref)
    err = (run.q_d - run.q)[_rest(run)]
    omega_min = math.sqrt(weight / (ctl.B_bar[2] * sag_max_mm * 1e-3))
    if omega_min >= 1.0 / traj.dt:
        raise ScaraError(f"exercise ex-ctl-ij-pd: omega = {omega_min:.0f} rad/s is past the sampling limit 1/T")
    omega_run = math.ceil(omega_min)
    fast = simulate(IndependentJointController(integral=False, omega=omega_run), traj, plant, joint_reference=ref)
    sag_fast = -(fast.q_d - fast.q)[_rest(fast), 2].mean()
    return {"sag_mm": 1e3 * sag, "sag_sim_mm": -1e3 * err[:, 2].mean(),
            "other_rest": float(np.abs(err[:, [0, 1, 3]]).max()), "weight": weight, "B_bar33": ctl.B_bar[2],
            "omega_min": omega_min, "omega_run": float(omega_run), "sag_run_mm": 1e3 * sag_fast,
            "sampling_limit": 1.0 / traj.dt, "kp_ratio": (omega_run / omega) ** 2}


@solves("ex-ctl-ij-margin")
def ij_margin(m_L: float) -> dict:
    """The factor on K_I,1 that puts joint 1's frozen PID loop, stretched arm with ``m_L``, on the Routh edge."""
    _payload(m_L)
    model, _, _, _ = _setup()
    ctl = IndependentJointController()
    ratio = inertia([0.0, 0.0, 0.5, 0.0], model.with_payload(m_L))[0, 0] / ctl.B_bar[0]
    folded = inertia([0.0, math.pi, 0.5, 0.0], model)[0, 0] / ctl.B_bar[0]
    c = 9.0 / ratio
    B1 = ratio * ctl.B_bar[0]

    def largest_real_part(k):
        return float(np.roots([B1, ctl.F[0] + ctl.K_D[0], ctl.K_P[0], k * ctl.K_I[0]]).real.max())

    return {"ratio": ratio, "c": c, "folded": folded, "below": largest_real_part(0.99 * c),
            "above": largest_real_part(1.01 * c)}


@solves("ex-ctl-ij-windup")
def ij_windup(bound_fig: float, bound: float) -> dict:
    """The integral the quill's PID winds up to with its force clipped at ``bound_fig`` (no anti-windup), and
    the runs with the tighter ``bound``, with anti-windup (it completes) and without (the error bound stops it)."""
    model, traj, ref, _ = _setup()
    plant = model.with_payload(5.0)
    weight = plant.m3 * plant.g0
    if not weight < bound <= bound_fig:
        raise ScaraError(f"exercise ex-ctl-ij-windup: the bound {bound} N must lie between the weight "
                         f"{weight:.1f} N and the figure's {bound_fig} N")
    fig = simulate(IndependentJointController(tau_max=(200.0, 200.0, bound_fig, 50.0), anti_windup=False), traj,
                   plant, joint_reference=ref)
    tight = (200.0, 200.0, bound, 50.0)
    aw = simulate(IndependentJointController(tau_max=tight), traj, plant, joint_reference=ref)
    stop = _stopped(lambda: IndependentJointController(tau_max=tight, anti_windup=False).run(
        traj, plant, joint_reference=ref), "ex-ctl-ij-windup", f"without anti-windup the run at {bound} N", "max_error")
    return {"integral_N": float(-fig.integral_action_3.min()), "weight": weight,
            "last_clipped": float(aw.t[np.flatnonzero(aw.saturated > 0)[-1]]),
            "max_um": 1e6 * control_summary(aw)["max_position_error"], "stop": stop,
            "max_error": IndependentJointController().max_error, "room": bound - weight}


@solves("ex-ctl-pdg-sag")
def pdg_sag(m_L: float, omega: float) -> dict:
    """PD with gravity compensation, gains placed at a double pole ``omega``: the quill's sag m_L g0 / K_P3 at rest,
    its ratio to the independent PD's m3 g0 / K_P3, and the runs that check both."""
    _payload(m_L)
    model, traj, ref, _ = _setup()
    plant = model.with_payload(m_L)
    ctl = PDPlusGravityController(omega=omega)
    sag = m_L * plant.g0 / ctl.K_P[2]
    run = simulate(ctl, traj, plant, joint_reference=ref)
    err = (run.q_d - run.q)[_rest(run)]
    pd = simulate(IndependentJointController(integral=False, omega=omega), traj, plant, joint_reference=ref)
    return {"sag_mm": 1e3 * sag, "sag_sim_mm": -1e3 * err[:, 2].mean(), "K_P3": ctl.K_P[2],
            "ratio": m_L / plant.m3, "pd_sag_sim_mm": -1e3 * (pd.q_d - pd.q)[_rest(pd), 2].mean(),
            "other_rest": float(np.abs(err[:, [0, 1, 3]]).max())}


@solves("ex-ctl-ct-omega")
def ct_omega(m_L: float, sag_max_mm: float) -> dict:
    """Computed torque: the smallest natural frequency keeping the quill's sag at rest below ``sag_max_mm``. The
    sag K_P^-1 B_hat^-1 (g - g_hat) falls as 1 / omega^2, so omega_min = sqrt(sag(omega = 1) / sag_max), with the
    rotor coupling; a run at the next whole rad/s checks it."""
    _payload(m_L)
    model, traj, ref, q_path = _setup()
    plant = model.with_payload(m_L)
    unit = ComputedTorqueController(omega=1.0)
    sag_1 = -unit.steady_state_error(plant, ref.q[-1])[2]       # m, at omega = 1 rad/s
    omega_min = math.sqrt(sag_1 / (1e-3 * sag_max_mm))
    limit = omega_limit(1.0, traj.dt)
    if omega_min >= limit:
        raise ScaraError(f"exercise ex-ctl-ct-omega: omega = {omega_min:.0f} rad/s is past the sampling limit")
    omega_run = math.ceil(omega_min)
    run = simulate(ComputedTorqueController(omega=omega_run), traj, plant, joint_reference=ref)
    B11 = inertia(q_path, model)[:, 0, 0].max()
    return {"omega_min": omega_min, "B_hat33": inertia(ref.q[-1], model)[2, 2],
            "formula": math.sqrt(m_L * plant.g0 / (inertia(ref.q[-1], model)[2, 2] * 1e-3 * sag_max_mm)),
            "omega_run": float(omega_run), "sag_run_mm": -1e3 * (run.q_d - run.q)[_rest(run), 2].mean(),
            "limit": limit, "nm_per_mrad": 1e-3 * B11 * omega_run ** 2, "B_hat11": B11}


@solves("ex-ctl-ct-step")
def ct_step(omega: float, f_max: float) -> dict:
    """Computed torque at rest, the quill's reference stepping down or up: the largest steps whose first force
    B_hat33 omega^2 Delta - m3_hat g0 stays within ``f_max``; runs 1 % below complete, 1 % above stop at t = 0."""
    model, _, _, _ = _setup()
    plant = model.with_payload(5.0)
    q_set = np.array([0.0, -math.pi / 2, 0.5, 0.0])
    B33 = inertia(q_set, model)[2, 2]
    weight = model.m3 * model.g0
    down = (f_max + weight) / (B33 * omega ** 2)
    up = (f_max - weight) / (B33 * omega ** 2)
    bounds = (200.0, 200.0, f_max, 50.0)
    ctl = ComputedTorqueController(omega=omega, tau_max=bounds)
    if max(down, up) >= ctl.max_error:
        raise ScaraError(f"exercise ex-ctl-ct-step: a step of {1e3 * max(down, up):.1f} mm passes the error bound")
    setpoint = joint_setpoint(q_set, 0.3)
    peaks, stops = {}, {}
    for name, sign, delta in (("down", 1.0, down), ("up", -1.0, up)):
        start = q_set - sign * np.array([0.0, 0.0, 0.99 * delta, 0.0])   # q_d - q = +-Delta on the quill
        run = simulate(ctl, None, plant, joint_reference=setpoint, q0=start)
        peaks[name] = float(np.abs(run.tau[:, 2]).max())
        stops[name] = _stopped(lambda: simulate(ctl, None, plant, joint_reference=setpoint,
                                                q0=q_set - sign * np.array([0.0, 0.0, 1.01 * delta, 0.0])),
                               "ex-ctl-ct-step", f"the {name} step 1 % past the limit", "tau_max")
    return {"delta_down_mm": 1e3 * down, "delta_up_mm": 1e3 * up, "B_hat33": B33, "weight": weight,
            "K_P3": ctl.K_P[2], "peak_down": peaks["down"], "peak_up": peaks["up"], "stop_down": stops["down"],
            "stop_up": stops["up"]}


@solves("ex-ctl-no-robust")
def no_robust(m_L: float, rho: float) -> dict:
    """Robust control with a negligible robust term: PD with B_hat33, whose quill sags m_L g0 / (B_hat33 K_P3)."""
    _payload(m_L)
    model, traj, ref, _ = _setup()
    plant = model.with_payload(m_L)
    ctl = RobustController(rho=rho)
    theory = m_L * plant.g0 / (ctl.B_hat[2] * ctl.K_P[2])
    run = simulate(ctl, traj, plant, joint_reference=ref)
    book = simulate(RobustController(), traj, plant, joint_reference=ref)
    sim = run.e[_rest(run), 2].mean()
    return {"sag_mm": 1e3 * theory, "sim_mm": 1e3 * sim, "ratio": sim / book.e[_rest(book), 2].mean(),
            "B_hat33": ctl.B_hat[2], "K_P3": ctl.K_P[2]}


@solves("ex-ctl-wider-layer")
def wider_layer(epsilon: float) -> dict:
    """The robust controller's sag at rest, m_L g0 / (B_hat33 (K_P3 + rho lambda3 / epsilon)), with a wider layer,
    and what it buys: the chattering measure and the margin to the sampling limit."""
    model, traj, ref, q_path = _setup()
    plant = model.with_payload(5.0)
    book = RobustController()
    ctl = RobustController(epsilon=epsilon)
    if epsilon <= book.epsilon:
        raise ScaraError(f"exercise ex-ctl-wider-layer: epsilon = {epsilon} is not wider than the book's")
    gain = ctl.rho * ctl.Lambda[2] / epsilon
    theory = plant.m_L * plant.g0 / (ctl.B_hat[2] * (ctl.K_P[2] + gain))
    run = simulate(ctl, traj, plant, joint_reference=ref)
    base = simulate(book, traj, plant, joint_reference=ref)
    lam_max = inertia_eigenvalues(book.B_hat, q_path, payloads=(plant.m_L,))[1]
    eps_min = book.epsilon_bound(lam_max)
    return {"sag_mm": 1e3 * theory, "sim_mm": 1e3 * run.e[_rest(run), 2].mean(), "margin": epsilon / eps_min,
            "gain_book": book.rho * book.Lambda[2] / book.epsilon, "gain": gain,
            "chat_book": chattering(base), "chat": chattering(run), "margin_book": book.epsilon / eps_min}


@solves("ex-ctl-slow-adaptation")
def slow_adaptation(K_pi: float) -> dict:
    """How long the payload estimate needs to come within 0.25 kg of 5 kg: ln 20 / a, a the slow root of
    B33 s^2 + (F33 + K_D3) s + g0^2 / K_pi, against the last 0.25 kg crossing of a run."""
    model, traj, ref, _ = _setup()
    plant = model.with_payload(5.0)
    ctl = AdaptiveController(K_pi=K_pi)
    B33 = inertia(ref.q[0], plant)[2, 2]
    roots = np.sort(np.roots([B33, plant.F[2] + ctl.K_D[2], plant.g0 ** 2 / K_pi]))
    if np.iscomplexobj(roots) and np.abs(roots.imag).max() > 0:
        raise ScaraError(f"exercise ex-ctl-slow-adaptation: K_pi = {K_pi} makes the loop oscillate")
    roots = roots.real
    a = -roots[-1]
    pred = math.log(plant.m_L / 0.25) / a
    run = simulate(ctl, traj, plant, joint_reference=ref)
    off = np.flatnonzero(np.abs(run.payload_estimate - plant.m_L) > 0.25)
    sim = float(run.t[off[-1] + 1])
    if not (pred < 0.9 * traj.t[-1] and abs(sim - pred) < 0.05 * pred):
        raise ScaraError(f"exercise ex-ctl-slow-adaptation: K_pi = {K_pi}: the run crosses 0.25 kg at {sim:.1f} s, "
                         f"not near the predicted {pred:.1f} s")
    return {"t_pred": pred, "t_sim": sim, "fast": roots[0], "slow": roots[-1], "a": a, "B33": B33,
            "K_D3": ctl.K_D[2], "err_mm": 1e3 * control_summary(run)["max_position_error"]}


@solves("ex-ctl-stiffer")
def stiffer(m_L: float, sag_max_mm: float) -> dict:
    """The vertical gain K_P,z that keeps the quill's sag without integral below ``sag_max_mm`` with ``m_L``:
    m_L g0 / (B_hat33 sag) raised by the rotor coupling, and a run with its rounded-up value."""
    _payload(m_L)
    model, traj, _, _ = _setup()
    plant = model.with_payload(m_L)
    B33_hat = inertia(np.zeros(4), model)[2, 2]
    formula = m_L * plant.g0 / (B33_hat * sag_max_mm * 1e-3)
    book = OperationalSpaceController(integral=False)
    full = book.steady_state_error(plant, _setup()[2].q[-1])   # at rest at the path's end
    coupling = full[2] / (m_L * plant.g0 / (B33_hat * book.K_P[2])) - 1.0
    kpz_min = formula * (1.0 + coupling)
    kpz = math.ceil(kpz_min)
    run = simulate(OperationalSpaceController(integral=False, K_P=(1200, 1200, kpz, 1200)), traj, plant)
    rest = _rest(run)
    if not run.e[rest, 2].max() < sag_max_mm * 1e-3:
        raise ScaraError(f"exercise ex-ctl-stiffer: K_P,z = {kpz} leaves the quill {1e3 * run.e[rest, 2].max():.4f} "
                         f"mm low, above {sag_max_mm} mm")
    return {"kpz_min": kpz_min, "kpz_formula": formula, "coupling": coupling, "kpz": float(kpz),
            "sim_mm": 1e3 * run.e[rest, 2].mean(), "B33_hat": B33_hat}


@solves("ex-ctl-sampling-limit")
def sampling_limit(rho: float) -> dict:
    """The thinnest boundary layer lam_max rho T / (2 - lam_max K_D T) for ``rho``, a run at the book's
    epsilon, and one at 0.8 of the limit, stopped by joint 1's torque bound."""
    model, traj, ref, q_path = _setup()
    plant = model.with_payload(5.0)
    ctl = RobustController(rho=rho)
    lam_max = inertia_eigenvalues(ctl.B_hat, q_path, payloads=(plant.m_L,))[1]
    eps = ctl.epsilon_bound(lam_max)
    if not eps < ctl.epsilon:
        raise ScaraError(f"exercise ex-ctl-sampling-limit: rho = {rho} puts the limit {eps:.4f} above epsilon")
    if not ctl.B_hat[0] * rho > ctl.tau_max[0]:
        raise ScaraError(f"exercise ex-ctl-sampling-limit: rho = {rho} cannot drive joint 1 past its bound")
    run = simulate(ctl, traj, plant, joint_reference=ref)
    stop = _stopped(lambda: RobustController(rho=rho, epsilon=0.8 * eps).run(traj, plant, joint_reference=ref),
                    "ex-ctl-sampling-limit", f"the run at 0.8 eps_min with rho = {rho}", "tau_max")
    return {"eps_min": eps, "lam_max": lam_max, "chat": chattering(run), "sag_mm": 1e3 * run.e[_rest(run), 2].mean(),
            "b11rho": ctl.B_hat[0] * rho, "tau1max": ctl.tau_max[0], "B_hat11": ctl.B_hat[0], "stop": stop}


@solves("ex-ctl-integral-limit")
def integral_limit(m_L: float, K_P: float, K_D: float) -> dict:
    """The largest integral gain: K_D K_P with an exact model (Routh), beta K_D K_P with the payload the model
    misses (beta = B_hat33 / B33), and lower still when sampled at 1 ms; runs 2 % either side of the last."""
    _payload(m_L)
    model, traj, ref, _ = _setup()
    plant = model.with_payload(m_L)
    B33_hat, B33 = inertia(ref.q[0], model)[2, 2], inertia(ref.q[0], plant)[2, 2]
    beta = B33_hat / B33
    T = traj.dt

    def sampled_radius(KI):
        # quill error, its rate and the running sum; the held command reaches the quill scaled by beta
        A = np.array([[1.0, T, 0.0], [0.0, 1.0, 0.0], [T, 0.0, 1.0]])
        A -= np.outer([beta * T ** 2 / 2, beta * T, 0.0], [K_P, K_D, KI])
        return float(np.abs(np.linalg.eigvals(A)).max())

    routh, cont = K_D * K_P, beta * K_D * K_P
    disc = brentq(lambda k: sampled_radius(k) - 1.0, 0.5 * cont, cont)
    simulate(OperationalSpaceController(K_P=K_P, K_D=K_D, K_I=0.98 * disc), traj, plant)  # completes
    c = OperationalSpaceController(K_P=K_P, K_D=K_D, K_I=1.02 * disc)
    stop = _stopped(lambda: simulate(c, traj, plant), "ex-ctl-integral-limit",
                    f"with {m_L} kg the run 2 % above the limit")
    book = OperationalSpaceController()
    return {"routh": routh, "cont": cont, "disc": disc, "beta": beta, "stop": stop, "f3max": float(c.tau_max[2]),
            "routh_book": float(book.K_D[2] * book.K_P[2]), "B33_hat": B33_hat, "B33": B33,
            "radius_below": sampled_radius(0.98 * disc), "radius_above": sampled_radius(1.02 * disc),
            "beta10": B33_hat / inertia(ref.q[0], model.with_payload(10.0))[2, 2]}
