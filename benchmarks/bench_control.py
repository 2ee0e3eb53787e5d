"""Timing of the three controllers of chapter 6 on the 70 s reference (70,001 samples at 1 ms), compiled vs
plain numpy, and the compute cost of one control step of each law (the chapter's table).

The runs: ``RobustController()``, ``AdaptiveController()``, ``OperationalSpaceController()`` (book gains, models
without payload) driving the plant with the 5 kg payload (one RK4 step per sample, torque held); the joint
controllers follow ``clik2(reference_trajectory())`` (computed once, outside the timing).

For each controller the script times

* ``scara.simulate(...)`` as the book calls it (input checks, result assembly, the compiled loop), median of
  ``--repeats`` runs, and the compiled loop alone (``result.elapsed``);
* the compiled law alone, replayed on the recorded states (``scara.control.law_cost``): the cost of one control
  step, without the plant;
* the same closed loop written the ordinary way, one step at a time with numpy (the law with numpy arrays and
  ``np.linalg.solve``; ``B``, ``C``, ``g`` built as arrays; RK4 on numpy vectors), over the first
  ``--numpy-seconds`` of the run (default 10 s; pass 70 for the whole run) and extrapolated per step; and the
  numpy law alone per step on the recorded states;

and prints ms per 70 s run, ns or us per step, the ratios numpy / compiled measured in this same process (the
compiled and numpy runs alternate so that a change of the machine's load falls on both), and the largest joint
difference between the numpy and the compiled run over their common samples (same recursion: round-off).
Target (the budget of the verification appendix, section Speed): at most 40 ms per 70 s run for each
controller once compiled.

Run: ``python benchmarks/bench_control.py [--repeats 15] [--numpy-seconds 10]``.
"""
from __future__ import annotations

import math
import statistics
import time

import numpy as np

from scara import (AdaptiveController, OperationalSpaceController, RobustController, clik2, reference_trajectory,
                   simulate)
from scara._compile import COMPILED
from scara.control import law_cost

# the plain-numpy model and RK4 step of the engine's benchmark (this folder is on sys.path when run)
from bench_simulate import PLANT, bench_arguments, np_coriolis, np_gravity, np_inertia, np_rk4_step


# --------------------------------------------------------------------------------------------------
# plain numpy: the kinematics and the regressor (B, C, g and the plant step are bench_simulate's)
# --------------------------------------------------------------------------------------------------
def np_pose(q, p):
    t12 = q[0] + q[1]
    return np.array([p.a1 * math.cos(q[0]) + p.a2 * math.cos(t12), -(p.a1 * math.sin(q[0]) + p.a2 * math.sin(t12)),
                     p.d0 - q[2], t12 + q[3]])


def np_jacobian(q, p):
    s1, c1, s12, c12 = math.sin(q[0]), math.cos(q[0]), math.sin(q[0] + q[1]), math.cos(q[0] + q[1])
    return np.array([[-(p.a1 * s1 + p.a2 * s12), -p.a2 * s12, 0, 0], [-(p.a1 * c1 + p.a2 * c12), -p.a2 * c12, 0, 0],
                     [0, 0, -1.0, 0], [1.0, 1.0, 0, 1.0]])


def np_jacobian_dot(q, qd, p):
    s1, c1, s12, c12 = math.sin(q[0]), math.cos(q[0]), math.sin(q[0] + q[1]), math.cos(q[0] + q[1])
    w1, w12 = qd[0], qd[0] + qd[1]
    return np.array([[-(p.a1 * c1 * w1 + p.a2 * c12 * w12), -p.a2 * c12 * w12, 0, 0],
                     [p.a1 * s1 * w1 + p.a2 * s12 * w12, p.a2 * s12 * w12, 0, 0], [0, 0, 0, 0.0], [0, 0, 0, 0.0]])


def np_regressor(q, qd, qr, ar, p):
    """Y (4, 13) with Y pi = B ar + C qr + F qr + g, columns of scara.dynamics.PI_NAMES."""
    a1, a2 = p.a1, p.a2
    c2, s2 = math.cos(q[1]), math.sin(q[1])
    cor1 = -s2 * (qd[1] * qr[0] + (qd[0] + qd[1]) * qr[1])
    cor2 = s2 * qd[0] * qr[0]
    Y = np.zeros((4, 13))
    Y[0, 0] = (a1 ** 2 + a2 ** 2 + 2 * a1 * a2 * c2) * ar[0] + (a2 ** 2 + a1 * a2 * c2) * ar[1] + a1 * a2 * cor1
    Y[0, 1] = a1 * c2 * (2 * ar[0] + ar[1]) + a1 * cor1
    Y[0, [2, 3, 5, 7, 9]] = ar[0], ar[1], ar[2], ar[3], qr[0]
    Y[1, 0] = (a2 ** 2 + a1 * a2 * c2) * ar[0] + a2 ** 2 * ar[1] + a1 * a2 * cor2
    Y[1, 1] = a1 * c2 * ar[0] + a1 * cor2
    Y[1, [3, 4, 5, 7, 10]] = ar[0], ar[1], ar[2], ar[3], qr[1]
    Y[2, [0, 5, 6, 11]] = ar[2] - p.g0, ar[0] + ar[1], ar[2], qr[2]
    Y[3, [7, 8, 12]] = ar[0] + ar[1], ar[3], qr[3]
    return Y


# --------------------------------------------------------------------------------------------------
# plain numpy: the three laws, one step each (same equations as the compiled laws)
# --------------------------------------------------------------------------------------------------
def numpy_law(c):
    """A step function ``law(q, qd, ref, state) -> (tau, state)`` for controller ``c``, in numpy."""
    m = c.model
    F = np.diag(m.F)
    if isinstance(c, RobustController):
        Bh, Z = np.diag(c.B_hat), c.sliding
        KP, KD = np.diag(c.K_P), np.diag(c.K_D)

        def law(q, qd, ref, state):
            xi = np.concatenate([ref[:4] - q, ref[4:8] - qd])
            z = Z @ xi
            nz = np.linalg.norm(z)
            w = c.rho * z / max(nz, c.epsilon)
            y = ref[8:] + KD @ xi[4:] + KP @ xi[:4] + w
            return Bh @ y + F @ qd + np_gravity(m), state
    elif isinstance(c, AdaptiveController):
        Lam, KD, Kinv = np.diag(c.Lambda), np.diag(c.K_D), np.diag(c.K_pi_inv)

        def law(q, qd, ref, state):
            qt, qtd = ref[:4] - q, ref[4:8] - qd
            qr, ar = ref[4:8] + Lam @ qt, ref[8:] + Lam @ qtd
            sigma = qr - qd
            Y = np_regressor(q, qd, qr, ar, m)
            return Y @ state + KD @ sigma, state + 1e-3 * Kinv @ (Y.T @ sigma)
    else:
        KP, KD, KI = np.diag(c.K_P), np.diag(c.K_D), np.diag(c.K_I)

        def law(q, qd, ref, state):
            J = np_jacobian(q, m)
            xt = ref[:4] - np_pose(q, m)
            a = ref[8:] + KD @ (ref[4:8] - J @ qd) + KP @ xt + KI @ state - np_jacobian_dot(q, qd, m) @ qd
            y = np.linalg.solve(J, a)
            tau = np_inertia(q, m) @ y + np_coriolis(q, qd, m) @ qd + F @ qd + np_gravity(m)
            return tau, state + 1e-3 * xt
    return law


def numpy_closed_loop(c, ref, q0, qd0, dt, n):
    law = numpy_law(c)
    F = np.diag(PLANT.F)
    state = np.array(c.initial_state(), float)
    q, qd = np.array(q0, float), np.array(qd0, float)
    out = np.empty((n, 4))
    for k in range(n):
        out[k] = q
        tau, state = law(q, qd, ref[k], state)
        q, qd = np_rk4_step(q, qd, tau, dt, F)
    return out


def numpy_law_cost(c, res, n):
    law = numpy_law(c)
    state = np.array(c.initial_state(), float)
    t0 = time.perf_counter()
    for k in range(n):
        _, state = law(res.q[k], res.qd[k], res.reference[k], state)
    return (time.perf_counter() - t0) / n


# --------------------------------------------------------------------------------------------------
def main(argv=None):
    args = bench_arguments(argv, __doc__, repeats=15, numpy_seconds=10.0, runs="compiled runs per controller")

    traj = reference_trajectory()
    jr = clik2(traj)
    N = len(traj.t)
    steps = N - 1
    print(f"reference: {N} samples ({traj.t[-1]:g} s at dt = {traj.dt * 1e3:g} ms); plant payload 5 kg; "
          f"numba compiled: {COMPILED}")
    ctrls = [RobustController(), AdaptiveController(), OperationalSpaceController()]
    n_np = min(N, int(round(args.numpy_seconds / traj.dt)) + 1)
    rows = []
    for c in ctrls:
        kw = dict(joint_reference=jr) if c.reference_kind == "joint" else {}
        t0 = time.perf_counter()
        res = simulate(c, traj, PLANT, **kw)
        first = time.perf_counter() - t0
        calls, loops = [], []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            res = simulate(c, traj, PLANT, **kw)
            calls.append(time.perf_counter() - t0)
            loops.append(res.elapsed)
        law_c = law_cost(c, res, repeats=args.repeats)
        # numpy: the closed loop over n_np samples and the law alone, between two compiled calls
        t0 = time.perf_counter()
        q_np = numpy_closed_loop(c, res.reference, res.q[0], res.qd[0], traj.dt, n_np)
        t_np = (time.perf_counter() - t0) / n_np
        law_np = numpy_law_cost(c, res, min(n_np, 5000))
        t0 = time.perf_counter()
        simulate(c, traj, PLANT, **kw)
        calls.append(time.perf_counter() - t0)
        call, loop = statistics.median(calls), statistics.median(loops)
        rows.append(dict(name=c.name, first=first, call=call, loop=loop, law=law_c, np_step=t_np, np_law=law_np,
                         diff=float(np.abs(q_np - res.q[:n_np]).max())))

    head = (f"{'controller':<12} {'simulate() ms':>14} {'loop ms':>8} {'law ns/step':>12} {'numpy ms/run':>13} "
            f"{'numpy law us/step':>18} {'run ratio':>10} {'law ratio':>10} {'max |dq|':>9}")
    print(head)
    print("-" * len(head))
    for r in rows:
        print(f"{r['name']:<12} {1e3 * r['call']:>14.1f} {1e3 * r['loop']:>8.1f} {1e9 * r['law']:>12.0f} "
              f"{1e3 * r['np_step'] * steps:>13.0f} {1e6 * r['np_law']:>18.1f} "
              f"{r['np_step'] * steps / r['call']:>9.0f}x {r['np_law'] / r['law']:>9.0f}x {r['diff']:>9.1e}")
    how = "measured" if n_np == N else f"extrapolated from {n_np - 1} steps"
    print(f"numpy runs: {how}; simulate() is the median of {args.repeats + 1} calls; the law's cost is the compiled "
          f"law replayed alone on the recorded states (median of {args.repeats}).")
    print("first call (load from cache or compile): " + ", ".join(f"{r['name']} {1e3 * r['first']:.0f} ms" for r in rows))
    ok = all(r["call"] <= 0.040 for r in rows)
    times = ", ".join(f"{1e3 * r['call']:.1f}" for r in rows)
    print(f"target: <= 40 ms per 70 s run for each controller -> {'met' if ok else 'NOT met'} ({times} ms)")


if __name__ == "__main__":
    main()
