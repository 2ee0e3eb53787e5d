"""The cost of every public whole-run call of the package, for comparing two versions of the code.

    python benchmarks/public_runs.py [--repeats 15] [--json out.json]

Each row is one call as the book makes it, on the 70 s reference of chapter 3 (70,001 samples at 1 ms):
CLIK with each method (``clik``, ``clik2``), each controller of chapter 6 on the plant with the 5 kg payload
(``RobustController``, ``AdaptiveController``, ``OperationalSpaceController`` with and without integral
action, PD with gravity compensation and computed torque; the joint controllers follow ``clik2``'s joints,
computed once outside the timing), the PD closed loop with gravity compensation of chapter 5, and chapter 7's
approach and press of the surface under force control (3 s, 10 RK4 steps per sample). Times are the median of ``--repeats`` calls in CPU time
of this process (``time.process_time``: another process holding the core does not count), after one call
that compiles or loads the compiled code. *call* is the whole public call (checks, loop, result); *loop* is
the compiled loop alone, as the result reports it. With ``--json`` the medians are written to a file, and
``--compare before.json`` prints the ratio of this run to an earlier one.
"""
from __future__ import annotations

import argparse
import json
import statistics
import time

from scara import (AdaptiveController, ComputedTorqueController, OperationalSpaceController, PDGravityController,
                   PDPlusGravityController, RobustController, ScaraParams, clik, clik2, reference_trajectory, simulate)
from scara.interaction import ForceController, ForceSensor, Surface, approach_run

CLOCK = time.process_time


def runs():
    traj = reference_trajectory()
    plant = ScaraParams().with_payload(5.0)
    jref = clik2(traj)

    def controller(c):
        return lambda: c.run(traj, plant, joint_reference=jref if c.reference_kind == "joint" else None)

    return {
        "clik inverse": (lambda: clik(traj, "inverse"), "elapsed"),
        "clik transpose": (lambda: clik(traj, "transpose"), "elapsed"),
        "clik pseudoinverse": (lambda: clik(traj, "pseudoinverse"), "elapsed"),
        "clik2 (second order)": (lambda: clik2(traj), "elapsed"),
        "robust, 70 s": (controller(RobustController()), "elapsed"),
        "adaptive, 70 s": (controller(AdaptiveController()), "elapsed"),
        "operational + integral, 70 s": (controller(OperationalSpaceController(integral=True)), "elapsed"),
        "operational, no integral, 70 s": (controller(OperationalSpaceController(integral=False)), "elapsed"),
        "PD + gravity, 70 s": (lambda: simulate(PDGravityController(), traj, plant, joint_reference=jref), "elapsed"),
        "PD + gravity (chapter 6), 70 s": (controller(PDPlusGravityController()), "elapsed"),
        "computed torque, 70 s": (controller(ComputedTorqueController()), "elapsed"),
        "force control, approach and press, 3 s": (
            lambda: approach_run(ForceController(), Surface(), ForceSensor(), hold=2.0), "elapsed"),
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15, help="calls per row (median reported)")
    ap.add_argument("--json", help="write the medians (ms) to this file")
    ap.add_argument("--compare", help="an earlier --json file: print this run's time over that one's")
    args = ap.parse_args(argv)
    before = json.load(open(args.compare)) if args.compare else {}
    out = {}
    head = f"{'run':<32} {'call ms':>8} {'loop ms':>8}" + (f" {'call / before':>14}" if before else "")
    print(head)
    print("-" * len(head))
    for name, (fn, attr) in runs().items():
        fn()  # compile or load from the cache
        calls, loops = [], []
        for _ in range(args.repeats):
            t0 = CLOCK()
            res = fn()
            calls.append(CLOCK() - t0)
            loops.append(getattr(res, attr))
        call, loop = 1e3 * statistics.median(calls), 1e3 * statistics.median(loops)
        out[name] = {"call_ms": call, "loop_ms": loop}
        line = f"{name:<32} {call:8.2f} {loop:8.2f}"
        if name in before:
            line += f" {call / before[name]['call_ms']:14.2f}"
        print(line)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
