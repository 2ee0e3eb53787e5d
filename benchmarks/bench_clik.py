"""Timing of the CLIK loops on the 70 s reference (70,000 Euler steps at 1 ms), compiled vs plain numpy.

For each method the script times

* ``scara.clik`` / ``scara.clik2`` as the book calls them (input checks, reachability, stability check and the
  compiled loop): the median of repeated runs, and the compiled loop alone (``result.elapsed``);
* the same algorithm written the ordinary way, one step at a time with numpy: ``J`` built as an array each
  step, ``np.linalg.inv`` (inverse, second order), ``J.T @ K @ e`` (transpose), ``np.linalg.pinv``
  (pseudo-inverse with the null-space term); run once, in the same process;

and prints the time per run and per step, the ratio, and the largest joint difference between the two
(they implement the same recursion, so they agree to rounding). Target (the budget of the verification appendix,
section Speed): at most 20 ms per run.
Times are this process's CPU time (``time.process_time``), as in ``run.py``; ``elapsed`` is the package's
own wall-clock timer around the loop.

Run: ``python benchmarks/bench_clik.py [--repeats 20] [--numpy-seconds 70]``.
"""
from __future__ import annotations

import math
import statistics
import time

import numpy as np

from scara import ScaraParams, reference_trajectory
from scara._compile import COMPILED
from scara._clik import SEED_K, clik, clik2, second_order_gains

# the command line shared by the bench_*.py scripts (this folder is on sys.path when run)
from bench_simulate import bench_arguments

#: CPU time of this process: on the shared machine the wall clock also counts other processes' turns
CLOCK = time.process_time
P = ScaraParams()
A1, A2, D0 = P.a1, P.a2, P.d0


# --------------------------------------------------------------------------------------------------
# the plain-numpy baseline: what a first implementation looks like
# --------------------------------------------------------------------------------------------------
def np_pose(q):
    t12 = q[0] + q[1]
    return np.array([A1 * math.cos(q[0]) + A2 * math.cos(t12), -(A1 * math.sin(q[0]) + A2 * math.sin(t12)),
                     D0 - q[2], t12 + q[3]])


def np_jacobian(q):
    s1, c1 = math.sin(q[0]), math.cos(q[0])
    s12, c12 = math.sin(q[0] + q[1]), math.cos(q[0] + q[1])
    return np.array([[-(A1 * s1 + A2 * s12), -A2 * s12, 0.0, 0.0],
                     [-(A1 * c1 + A2 * c12), -A2 * c12, 0.0, 0.0],
                     [0.0, 0.0, -1.0, 0.0],
                     [1.0, 1.0, 0.0, 1.0]])


def np_jacobian_dot(q, qd):
    s1, c1 = math.sin(q[0]), math.cos(q[0])
    s12, c12 = math.sin(q[0] + q[1]), math.cos(q[0] + q[1])
    w1, w12 = qd[0], qd[0] + qd[1]
    return np.array([[-(A1 * c1 * w1 + A2 * c12 * w12), -A2 * c12 * w12, 0.0, 0.0],
                     [A1 * s1 * w1 + A2 * s12 * w12, A2 * s12 * w12, 0.0, 0.0],
                     [0.0, 0.0, 0.0, 0.0],
                     [0.0, 0.0, 0.0, 0.0]])


def numpy_clik(traj, method, q0, n, K=SEED_K, k0=1.0):
    dt = traj.dt
    K = np.diag(K)
    q = np.array(q0, dtype=float)
    out = np.empty((n, 4))
    for k in range(n):
        out[k] = q
        e = traj.x[k] - np_pose(q)
        J = np_jacobian(q)
        if method == "inverse":
            qd = np.linalg.inv(J) @ (traj.xd[k] + K @ e)
        elif method == "transpose":
            qd = J.T @ K @ e
        else:  # pseudo-inverse, x relaxed, null-space term climbing sin^2 theta2
            Jr = J[1:]
            Jp = np.linalg.pinv(Jr)
            qd0 = k0 * np.array([0.0, math.sin(2 * q[1]), 0.0, 0.0])
            qd = Jp @ (traj.xd[k, 1:] + K[1:, 1:] @ e[1:]) + (np.eye(4) - Jp @ Jr) @ qd0
        q = q + dt * qd
    return out


def numpy_clik2(traj, q0, qd0, n):
    dt = traj.dt
    KP, KD = (np.diag(g) for g in second_order_gains())
    q, qd = np.array(q0, dtype=float), np.array(qd0, dtype=float)
    out = np.empty((n, 4))
    for k in range(n):
        out[k] = q
        J = np_jacobian(q)
        e = traj.x[k] - np_pose(q)
        ed = traj.xd[k] - J @ qd
        qdd = np.linalg.inv(J) @ (traj.xdd[k] + KD @ ed + KP @ e - np_jacobian_dot(q, qd) @ qd)
        q = q + dt * qd
        qd = qd + dt * qdd
    return out


# --------------------------------------------------------------------------------------------------
def main(argv=None):
    args = bench_arguments(argv, __doc__, repeats=20, numpy_seconds=70.0, runs="runs of each compiled method")

    traj = reference_trajectory()
    N = len(traj.t)
    n_np = min(N, int(round(args.numpy_seconds / traj.dt)) + 1)
    print(f"reference: {N} samples ({traj.t[-1]:g} s at dt = {traj.dt * 1e3:g} ms); numba compiled: {COMPILED}")
    runs = {
        "inverse": lambda: clik(traj, "inverse"),
        "transpose": lambda: clik(traj, "transpose"),
        "pseudoinverse": lambda: clik(traj, "pseudoinverse"),
        "second_order": lambda: clik2(traj),
    }
    head = (f"{'method':<14} {'call ms/run':>11} {'loop ms/run':>11} {'ns/step':>8} | {'numpy s/run':>11} "
            f"{'us/step':>8} | {'ratio':>6} | {'max |dq|':>9}")
    print(head)
    print("-" * len(head))
    for name, fn in runs.items():
        res = fn()  # compile or load from cache
        calls, loops = [], []
        for _ in range(args.repeats):
            t0 = CLOCK()
            res = fn()
            calls.append(CLOCK() - t0)
            loops.append(res.elapsed)
        call, loop = statistics.median(calls), statistics.median(loops)
        t0 = CLOCK()
        if name == "second_order":
            q_np = numpy_clik2(traj, res.q[0], res.qd[0], n_np)
        else:
            q_np = numpy_clik(traj, name, res.q[0], n_np)
        t_np = CLOCK() - t0
        per_np = t_np / n_np
        per_call = call / N
        dq = np.abs(q_np - res.q[:n_np]).max()
        print(f"{name:<14} {call * 1e3:>11.2f} {loop * 1e3:>11.2f} {per_call * 1e9:>8.0f} | "
              f"{per_np * N:>11.2f} {per_np * 1e6:>8.1f} | {per_np / per_call:>5.0f}x | {dq:>9.1e}")
    print(f"(call = the public function with its checks; numpy runs cover {n_np - 1} steps, scaled to {N - 1};"
          f" ratio = numpy per step / call per step; target <= 20 ms per call)")


if __name__ == "__main__":
    main()
