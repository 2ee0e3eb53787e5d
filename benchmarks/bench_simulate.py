"""Timing of the closed-loop engine on the 70 s reference (70,000 samples at 1 ms), compiled vs plain numpy.

The run: PD plus gravity compensation (``PDGravityController()``, its model without payload) at 1 ms with
zero-order hold, on the plant with the 5 kg payload integrated by one RK4 step per sample, along the joint
reference of ``clik2`` on ``reference_trajectory()`` (computed once, outside the timing).

The script times

* ``scara.simulate(...)`` as the book calls it (input checks, result assembly, the compiled loop): median of
  ``--repeats`` runs; and the compiled loop alone (``result.elapsed``);
* the same loop written the ordinary way, one step at a time with numpy: ``B``, ``C``, ``g`` built as arrays
  every call, ``np.linalg.solve`` for the accelerations, RK4 on numpy vectors, the PD-plus-gravity law in numpy.
  It is run over the first ``--numpy-seconds`` of the reference (default 5 s; pass 70 for the whole run),
  in the same process, and its time per step is compared with the compiled one;

and prints the time per run and per step, the ratio, and the largest joint difference between the two over the
common samples (same recursion: they agree to rounding). Target (the budget of the verification appendix,
section Speed): at most 50 ms per 70 s run.
Times are this process's CPU time (``time.process_time``), as in ``run.py``; ``elapsed`` is the package's
own wall-clock timer around the loop.

Run: ``python benchmarks/bench_simulate.py [--repeats 20] [--numpy-seconds 5]``.
"""
from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from scara import PDGravityController, ScaraParams, reference_trajectory, simulate
from scara._compile import COMPILED
from scara._clik import clik2

#: CPU time of this process: on the shared machine the wall clock also counts other processes' turns
CLOCK = time.process_time
PLANT = ScaraParams().with_payload(5.0)
MODEL = ScaraParams()


# --------------------------------------------------------------------------------------------------
# the plain-numpy baseline
# --------------------------------------------------------------------------------------------------
def np_inertia(q, p):
    c2 = math.cos(q[1])
    m3 = p.m_l3 + p.m_L
    kr, Im = p.k_r, p.I_m
    b11 = (p.I_l1 + p.m_l1 * p.l1 ** 2 + kr[0] ** 2 * Im[0] + p.I_l2 + p.m_l2 * (p.a1 ** 2 + p.l2 ** 2 + 2 * p.a1 * p.l2 * c2)
           + m3 * (p.a1 ** 2 + p.a2 ** 2 + 2 * p.a1 * p.a2 * c2) + p.I_l4 + Im[1] + Im[2] + Im[3])
    b12 = p.I_l2 + p.m_l2 * (p.l2 ** 2 + p.a1 * p.l2 * c2) + m3 * (p.a2 ** 2 + p.a1 * p.a2 * c2) + p.I_l4 + kr[1] * Im[1] + Im[2] + Im[3]
    b22 = p.I_l2 + p.m_l2 * p.l2 ** 2 + m3 * p.a2 ** 2 + p.I_l4 + kr[1] ** 2 * Im[1] + Im[2] + Im[3]
    b13 = kr[2] * Im[2]
    b14 = p.I_l4 + kr[3] * Im[3]
    return np.array([[b11, b12, b13, b14], [b12, b22, b13, b14], [b13, b13, m3 + kr[2] ** 2 * Im[2], 0.0],
                     [b14, b14, 0.0, p.I_l4 + kr[3] ** 2 * Im[3]]])


def np_coriolis(q, qd, p):
    h = p.a1 * (p.m_l2 * p.l2 + (p.m_l3 + p.m_L) * p.a2) * math.sin(q[1])
    return np.array([[-h * qd[1], -h * (qd[0] + qd[1]), 0.0, 0.0], [h * qd[0], 0.0, 0.0, 0.0],
                     [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]])


def np_gravity(p):
    return np.array([0.0, 0.0, -(p.m_l3 + p.m_L) * p.g0, 0.0])


def np_forward(q, qd, tau, p, F):
    return np.linalg.solve(np_inertia(q, p), tau - np_coriolis(q, qd, p) @ qd - F @ qd - np_gravity(p))


def np_rk4_step(q, qd, tau, dt, F, p=PLANT):
    """One classical RK4 step of the plant ``p`` (viscous friction matrix ``F``) over ``dt`` with ``tau`` held:
    the engine's integration, in numpy. Returns ``(q, qd)`` at the end of the step."""
    a1 = np_forward(q, qd, tau, p, F)
    v2 = qd + 0.5 * dt * a1
    a2 = np_forward(q + 0.5 * dt * qd, v2, tau, p, F)
    v3 = qd + 0.5 * dt * a2
    a3 = np_forward(q + 0.5 * dt * v2, v3, tau, p, F)
    v4 = qd + dt * a3
    a4 = np_forward(q + dt * v3, v4, tau, p, F)
    return q + dt / 6 * (qd + 2 * v2 + 2 * v3 + v4), qd + dt / 6 * (a1 + 2 * a2 + 2 * a3 + a4)


def numpy_closed_loop(ref, q0, qd0, dt, n, K_P, K_D):
    F = np.diag(PLANT.F)
    KP, KD = np.diag(K_P), np.diag(K_D)
    q, qd = np.array(q0, float), np.array(qd0, float)
    out = np.empty((n, 4))
    for k in range(n):
        out[k] = q
        tau = KP @ (ref[k, :4] - q) + KD @ (ref[k, 4:8] - qd) + np_gravity(MODEL)
        q, qd = np_rk4_step(q, qd, tau, dt, F)
    return out


# --------------------------------------------------------------------------------------------------
def bench_arguments(argv, doc: str, repeats: int, numpy_seconds: float, runs: str = "compiled runs"):
    """The command line of the ``bench_*.py`` scripts: ``--repeats`` (of ``runs``, median reported) and
    ``--numpy-seconds`` (the length of the plain-numpy run, in seconds of reference)."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=repeats, help=f"{runs} (median reported)")
    ap.add_argument("--numpy-seconds", type=float, default=numpy_seconds,
                    help="length of the numpy run (s of reference)")
    return ap.parse_args(argv)


def main(argv=None):
    args = bench_arguments(argv, __doc__, repeats=20, numpy_seconds=5.0)

    traj = reference_trajectory()
    ref2 = clik2(traj)
    jref = np.hstack([ref2.q, ref2.qd, ref2.qdd])
    N = len(traj.t)
    c = PDGravityController()
    print(f"reference: {N} samples ({traj.t[-1]:g} s at dt = {traj.dt * 1e3:g} ms); numba compiled: {COMPILED}")
    t0 = time.perf_counter()
    res = simulate(c, traj, PLANT, joint_reference=jref)
    print(f"first call (compile or load from cache): {1e3 * (time.perf_counter() - t0):.0f} ms")

    calls, loops = [], []
    for _ in range(args.repeats):
        t0 = CLOCK()
        res = simulate(c, traj, PLANT, joint_reference=jref)
        calls.append(CLOCK() - t0)
        loops.append(res.elapsed)
    call, loop = statistics.median(calls), statistics.median(loops)
    steps = N - 1

    n_np = min(N, int(round(args.numpy_seconds / traj.dt)) + 1)
    t0 = CLOCK()
    q_np = numpy_closed_loop(jref, jref[0, :4], jref[0, 4:8], traj.dt, n_np, c.K_P, c.K_D)
    t_np = CLOCK() - t0
    per_np = t_np / n_np
    diff = np.abs(q_np - res.q[:n_np]).max()

    head = (f"{'':<26} {'ms/run (70 s)':>14} {'ns/step':>9}")
    print(head)
    print("-" * len(head))
    print(f"{'simulate() whole call':<26} {1e3 * call:>14.1f} {1e9 * call / steps:>9.0f}")
    print(f"{'compiled loop alone':<26} {1e3 * loop:>14.1f} {1e9 * loop / steps:>9.0f}")
    print(f"{'plain numpy per step':<26} {1e3 * per_np * steps:>14.0f} {1e9 * per_np:>9.0f}   "
          f"({'measured' if n_np == N else f'extrapolated from {n_np - 1} steps'})")
    print(f"ratio numpy / simulate(): {per_np * steps / call:.0f}x   (numpy / compiled loop: {per_np * steps / loop:.0f}x)")
    print(f"largest joint difference over the {n_np} common samples: {diff:.2e}")
    print(f"target: <= 50 ms per run -> {'met' if call <= 0.050 else 'NOT met'} ({1e3 * call:.1f} ms, median of {args.repeats})")
    s = res.summary()
    print(f"steady-state e_z = {s['steady_state_error_components'][2] * 1e3:.3f} mm "
          f"(theory m_L g0 / K_P3 = {PLANT.m_L * PLANT.g0 / c.K_P[2] * 1e3:.3f} mm)")


if __name__ == "__main__":
    main()
