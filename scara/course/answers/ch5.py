"""The computations answering chapter 5's exercises (see :mod:`scara.course.answers`)."""
import math
from functools import lru_cache

import numpy as np

from scara import (PDGravityController, ScaraParams, TorqueController, clik2, friction, inertia,
                   inverse_dynamics, joint_setpoint, payload_from_pi, reference_trajectory, regressor, simulate)
from scara.course.answers import solves
from scara.errors import ScaraError
from scara.identification import (CUTOFF, EXAMPLE_SEED, book_design, draw_arm, encoder_resolution, identify,
                                  measure)

#: the payloads the course's arm is given (the live panel's and fig-ch5-inertia-elbow's slider: 0 to 20 kg)
PAYLOAD_MAX = 20.0


def _loaded(m_L: float, label: str, low: float = 0.0) -> ScaraParams:
    """The course's arm carrying ``m_L``; a payload outside ``low`` .. :data:`PAYLOAD_MAX` kg raises."""
    if not low <= m_L <= PAYLOAD_MAX:
        raise ScaraError(f"exercise {label}: a payload of {m_L} kg is outside the {low:g} to {PAYLOAD_MAX:g} kg "
                         "the course's arm carries")
    return ScaraParams().with_payload(m_L)


@lru_cache(maxsize=1)
def _q_start() -> tuple:
    """The start configuration of the reference path: the first sample of chapter 4's second-order CLIK."""
    return tuple(float(v) for v in clik2(reference_trajectory()).q[0])


@solves("ex-dyn-rotor")
def dyn_rotor(m_L: float) -> dict:
    """The share of rotor 3 (k_r3² I_m3) in B33 = m3 + k_r3² I_m3 of the arm carrying ``m_L``."""
    p = _loaded(m_L, "ex-dyn-rotor")
    rotor = float(p.k_r[2] ** 2 * p.I_m[2])
    B33 = float(inertia(np.array(_q_start()), p)[2, 2])
    return {"share_pct": 100 * rotor / B33, "B33": B33, "B33_rotor": rotor, "m3": float(p.m3)}


@solves("ex-dyn-stiff")
def dyn_stiff(m_L: float, sag_mm: float) -> dict:
    """The gain K_P3 = m_L g0 / sag that holds the uncompensated payload ``m_L`` at a sag of ``sag_mm``, and the
    sag a 5 s set-point simulation gives with it (K_D3 scaled to keep the damping ratio)."""
    p = _loaded(m_L, "ex-dyn-stiff", low=0.5)
    if not 0.2 <= sag_mm <= 20.0:
        raise ScaraError(f"exercise ex-dyn-stiff: a sag of {sag_mm} mm is outside 0.2 to 20 mm")
    kp = m_L * p.g0 / (sag_mm * 1e-3)
    ctrl = PDGravityController(K_P=(1e4, 4e3, kp, 600), K_D=(1e3, 400, 1e3 * math.sqrt(kp / 1e4), 60))
    res = simulate(ctrl, plant=p, joint_reference=joint_setpoint(np.array(_q_start()), 5.0))
    sim = float(res.e[-1, 2] * 1e3)
    if not math.isclose(sim, sag_mm, rel_tol=1e-3):
        raise ScaraError(f"exercise ex-dyn-stiff: after 5 s the quill sags {sim:.4f} mm, not yet the steady "
                         f"{sag_mm} mm")
    return {"kp": kp, "sag_sim_mm": sim}


@solves("ex-dyn-fall")
def dyn_fall(m_L: float, t: float) -> dict:
    """The quill of the arm carrying ``m_L`` released with the motors off at the start configuration (d3 = 0,
    theta4 = 0): terminal speed m3 g0 / F33, time constant B33 / F33, the first-order speed at ``t`` and the
    simulated one (the arm's rotation included)."""
    p = _loaded(m_L, "ex-dyn-fall")
    if not 0.05 <= t <= 1.0:
        raise ScaraError(f"exercise ex-dyn-fall: {t} s is outside the 0.05 to 1 s of the drop (the quill "
                         "reaches the end of its stroke soon after)")
    q = np.array(_q_start())
    q_drop = np.array([q[0], q[1], 0.0, 0.0])
    F33 = float(friction(p)[2, 2])
    v_inf = p.m3 * p.g0 / F33
    tau3 = float(inertia(q_drop, p)[2, 2]) / F33
    pred = v_inf * (1 - math.exp(-t / tau3))
    drop = simulate(TorqueController(), plant=p, duration=t, q0=q_drop)
    k = int(round(t / (drop.t[1] - drop.t[0])))
    if drop.q[k, 2] > p.d3_max:
        raise ScaraError(f"exercise ex-dyn-fall: after {t} s the quill is past the end of its stroke")
    return {"v_inf": float(v_inf), "tau_3": tau3, "v_pred": float(pred), "v_sim": float(drop.qd[k, 2]),
            "F33": F33}


@solves("ex-dyn-weigh")
def dyn_weigh(m_L: float) -> dict:
    """The payload found by least squares on the regressor from 40 random states (seed 4, as the solution's code)
    of the arm carrying ``m_L``."""
    p = _loaded(m_L, "ex-dyn-weigh")
    rng = np.random.default_rng(4)
    states = [(rng.uniform(-3, 3, 4), *rng.uniform(-2, 2, (2, 4))) for _ in range(40)]
    rows = [regressor(q, v, v, a) for q, v, a in states]
    taus = [inverse_dynamics(q, v, a, p) for q, v, a in states]
    Y = np.vstack(rows)
    pi_hat = np.linalg.lstsq(Y, np.concatenate(taus), rcond=None)[0]
    return {"mL_hat": float(payload_from_pi(pi_hat)), "rank": int(np.linalg.matrix_rank(Y)),
            "n_params": int(Y.shape[1])}


@solves("ex-dyn-energy")
def dyn_energy(m_L: float, w1: float, w2: float, w4: float) -> dict:
    """The arm carrying ``m_L`` at the start configuration, the quill held by tau3 = -m3 g0, pushed to
    qd(0) = [w1, w2, 0, w4] and left to coast for 10 s: kinetic energy, each joint's friction work, the end
    speeds, and the angular momentum (B qd)_1 about the joint-1 axis."""
    p = _loaded(m_L, "ex-dyn-energy")
    if abs(w4) < 0.5:
        raise ScaraError(f"exercise ex-dyn-energy: joint 4 pushed at {w4} rad/s carries too little energy to "
                         "compare the joints' friction")
    push = simulate(TorqueController(tau=(0.0, 0.0, -p.m3 * p.g0, 0.0)), plant=p, duration=10.0,
                    q0=np.array(_q_start()), qd0=[w1, w2, 0.0, w4])
    en = push.energy()
    if np.abs(en["balance"]).max() > 1e-6:
        raise ScaraError("exercise ex-dyn-energy: the energy balance is not kept (the integration failed)")
    w_joint = [float(np.trapezoid(p.F[j] * push.qd[:, j] ** 2, push.t)) for j in range(4)]
    L0 = float((inertia(push.q[0], p) @ push.qd[0])[0])
    L1 = float((inertia(push.q[-1], p) @ push.qd[-1])[0])
    return {"share4_pct": 100 * w_joint[3] / sum(w_joint), "T0": float(en["kinetic"][0]),
            "T1": float(en["kinetic"][-1]), "w4_end": float(push.qd[-1, 3]), "w1_end": float(push.qd[-1, 0]),
            "L0": L0, "L1": L1, "balance": float(np.abs(en["balance"]).max())}


@solves("ex-dyn-fold")
def dyn_fold(m_L: float) -> dict:
    """B11 of the arm carrying ``m_L`` stretched (theta2 = 0), at a right angle (-90 deg) and folded (180 deg),
    and B22, at theta1 = 0.3, d3 = 0.4, theta4 = -0.2 (any other values give the same)."""
    p = _loaded(m_L, "ex-dyn-fold")
    B = {deg: inertia(np.array([0.3, math.radians(deg), 0.4, -0.2]), p) for deg in (0, -90, 180)}
    return {"B11_0": float(B[0][0, 0]), "B11_90": float(B[-90][0, 0]), "B11_180": float(B[180][0, 0]),
            "B22": float(B[-90][1, 1]), "amp": float(2 * p.a1 * (p.m_l2 * p.l2 + p.m3 * p.a2)),
            "ratio": float(B[0][0, 0] / B[180][0, 0]), "m3": float(p.m3)}


@solves("ex-dyn-heavy")
def dyn_heavy(m_L: float, sag_max_mm: float) -> dict:
    """The quill's sag at rest under PD with gravity compensation of the arm alone, carrying ``m_L``, at
    K_P3 = 1e4 N/m; the gain needed for a sag of at most ``sag_max_mm`` and the smallest slider gain
    10^(k/10) N/m above it, with the sag at each slider gain from 10^4 to 10^5 N/m (keys ``sag_40_mm``...)."""
    p = _loaded(m_L, "ex-dyn-heavy", low=1.0)
    if not 1.0 <= sag_max_mm <= 20.0:
        raise ScaraError(f"exercise ex-dyn-heavy: a sag limit of {sag_max_mm} mm is outside 1 to 20 mm")
    sag_at = lambda kp: float(-PDGravityController(K_P=(1e4, 4e3, kp, 600)).steady_state_error(p)[2])  # noqa: E731
    k_needed = m_L * p.g0 / (sag_max_mm * 1e-3)
    k_step = math.ceil(10 * math.log10(k_needed) - 1e-9)
    if not 41 <= k_step <= 50:
        raise ScaraError(f"exercise ex-dyn-heavy: the gain needed, {k_needed:.0f} N/m, is not within the table's "
                         "10^4.1 to 10^5 N/m")
    out = {"sag_mm": 1e3 * sag_at(1e4), "k_needed": k_needed, "k_step": k_step / 10,
           "k_slider": 10 ** (k_step / 10), "sag2_mm": 1e3 * sag_at(10 ** (k_step / 10)),
           "B33": float(inertia(np.array(_q_start()), p)[2, 2])}
    for k in range(40, 51):
        out[f"kp_{k}"] = 10 ** (k / 10)
        out[f"sag_{k}_mm"] = 1e3 * sag_at(10 ** (k / 10))
    return out


@solves("ex-dyn-encoder")
def dyn_encoder(bits: float) -> dict:
    """An encoder of 2^bits counts per revolution read every 1 ms: its step, the RMS error of a reading (uniform
    over ± half a step) and the largest error of a first and a second difference of readings."""
    if not (float(bits).is_integer() and 8 <= bits <= 30):
        raise ScaraError(f"exercise ex-dyn-encoder: {bits} bits is not a whole number from 8 to 30")
    step = float(encoder_resolution(2 ** int(bits))[0])
    dt = 1e-3
    return {"step_urad": 1e6 * step, "rms_urad": 1e6 * step / math.sqrt(12.0), "speed_err": step / dt,
            "acc_err": 2 * step / dt ** 2}


@lru_cache(maxsize=1)
def _excitation():
    """The exciting trajectory of the chapter (``book_design``: the one ``optimise_excitation`` found)."""
    return book_design().excitation


@lru_cache(maxsize=32)
def _identified(m_L: float, periods: int, seed: int):
    """The weighted estimate of the chapter's arm (``draw_arm(EXAMPLE_SEED)``) carrying ``m_L`` instead of its own
    payload (None: its own), from ``periods`` periods of the chapter's excitation, noise drawn with ``seed``, the
    chapter's cut-off."""
    arm = draw_arm(EXAMPLE_SEED)
    arm = arm if m_L is None else arm.replace(m_L=m_L)
    return identify(measure(arm, _excitation().reference(periods), seed=seed), CUTOFF)[0]


def _half(est, j: int = 0) -> float:
    """The half-width of the 95 % interval of entry ``j`` of an estimate."""
    return float(0.5 * (est.interval[j, 1] - est.interval[j, 0]))


@solves("ex-dyn-record")
def dyn_record(target_g: float) -> dict:
    """The record length that the 1/sqrt(N) law predicts for a 95 % interval of m3 of ± ``target_g`` g, from the
    chapter's 40 s experiment (4 periods, noise seed 1), and the whole periods of 10 s that covers."""
    if not 0.5 <= target_g <= 2.0:
        raise ScaraError(f"exercise ex-dyn-record: ± {target_g} g is outside 0.5 to 2 g (the 40 s experiment "
                         "gives about ± 2 g; a narrower interval needs minutes of data)")
    h40 = _half(_identified(None, 4, 1))
    duration = 40.0 * (1e3 * h40 / target_g) ** 2
    return {"duration_s": duration, "h40_g": 1e3 * h40,
            "periods": float(math.ceil(duration / _excitation().period - 1e-9))}


@solves("ex-dyn-weighing")
def dyn_weighing(m_L: float) -> dict:
    """The chapter's arm carrying ``m_L``, identified with it (noise seed 1) and without it (seed 2) over 4
    periods: the payload as the difference of the two m3, its 95 % interval, and what payload_from_pi says."""
    if not 0.0 <= m_L <= 10.0:
        raise ScaraError(f"exercise ex-dyn-weighing: a payload of {m_L} kg is outside the 0 to 10 kg of the "
                         "identification's arm")
    loaded, empty = _identified(float(m_L), 4, 1), _identified(0.0, 4, 2)
    quantile = _half(loaded) / float(loaded.std[0])
    return {"payload_kg": float(loaded.pi[0] - empty.pi[0]),
            "half_g": 1e3 * quantile * math.hypot(loaded.std[0], empty.std[0]),
            "nominal_kg": float(payload_from_pi(loaded.pi)), "ml3": float(draw_arm(EXAMPLE_SEED).m_l3)}
