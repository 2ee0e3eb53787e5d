"""Agreement and speed of ``scara`` side by side with Peter Corke's Robotics Toolbox, Pinocchio and plain numpy.

    python benchmarks/run.py            # full run: agreement, per-call costs, whole 70 s runs (a few minutes)
    python benchmarks/run.py --quick    # fewer states and repeats (a smoke test, about a minute)

Prints the tables and writes ``benchmarks/results.json`` (machine, versions, date, every figure), which the
book's verification appendix reads. Needs the extras of ``requirements-bench.txt``.

Method
------
* Every time is the median of repeats; every ratio compares two times measured in this same run. Times are
  this process's CPU time (``time.process_time``): the machine is shared, and the wall clock would also count
  the time other processes held the core. Everything timed is single-threaded.
* Per-call cost: the call is repeated in a timing loop long enough to last ~20 ms, and that loop is repeated,
  round-robin over the implementations of one quantity.
  "ours" is the public, input-checking function; "ours (kernel)" the compiled kernel the loops use, called
  from Python. The toolbox column uses its fastest path for each quantity (``ETS.eval``/``ETS.jacob0`` in C
  for kinematics; ``DHRobot.rne`` in C, ``inertia`` and ``accel`` built on it, for dynamics).
* Whole 70 s runs (70,001 samples at 1 ms):
  - CLIK with the Jacobian inverse, Euler rule, ``K = diag(400, 400, 400, 100)``: ours is ``scara.clik(traj,
    "inverse")`` (the whole call); each library runs the same loop in Python with its own forward kinematics
    and Jacobian and ``numpy.linalg.solve``.
  - Closed loop: PD plus gravity compensation at 1 ms (zero-order hold) on the plant integrated by one RK4
    step per sample. Ours is ``scara.simulate(PDGravityController(), ...)`` (the whole call); each library
    runs the same loop in Python with its own gravity (controller) and forward dynamics (plant). Every
    loop, ours included, reuses the first RK4 stage as the recorded acceleration (4 forward-dynamics
    evaluations per step).
  - MuJoCo runs the same loop on the exported MJCF (``scara.export.to_mjcf``): gravity by ``mj_rne`` at rest for
    the controller, and its own ``mj_step`` (RK4 in C, one step per sample, torque held in ``ctrl``) for the plant.
  - So that the loops must produce the same motion, the closed-loop plant has its rotor inertias set to
    zero here (the libraries would otherwise miss the rotor coupling, see ``agreement.py``); parameter
    values do not change the cost of a step. Each run's largest joint difference from ours is reported.
  - A loop estimated to take longer than ``--budget`` seconds for 70 s is timed over a fixed number of
    steps and extrapolated linearly to 70,001 steps (marked "extrapolated" in the table).
  - Ours and each library loop are timed alternately (three runs of ours, then one library run, per
    repeat), and the ratio is the median of the per-repeat ratios, so that a change in the machine's load
    (two shared cores) falls on both sides of a ratio.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import platform
import statistics
import sys
import time
import timeit

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import scara  # noqa: E402
from scara import dynamics as dyn  # noqa: E402
from scara import kinematics as kin  # noqa: E402
from scara._clik import clik  # noqa: E402
from scara._simulate import PDGravityController, ikine_reference, simulate  # noqa: E402
from scara.trajectory import reference_trajectory  # noqa: E402

import agreement as A  # noqa: E402
import libraries as L  # noqa: E402

SEED_K = np.array([400.0, 400.0, 400.0, 100.0])
#: The clock of every timing: this process's CPU time. On a shared machine the wall clock also counts the time
#: other processes held the core; every computation timed here is single-threaded, so on an idle machine the
#: two agree.
CLOCK = time.process_time
TARGETS = {
    "closed_loop_vs_pinocchio": 50.0,
    "closed_loop_vs_toolbox": 500.0,
    "clik_vs_numpy": 100.0,
}


# ------------------------------------------------------------------------------------------------------
# machine and versions
# ------------------------------------------------------------------------------------------------------
def machine_info() -> dict:
    cpu = platform.processor() or "unknown"
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    mem = None
    try:
        with open("/proc/meminfo") as fh:
            mem = round(int(fh.readline().split()[1]) / 2 ** 20, 1)
    except (OSError, ValueError, IndexError):
        pass
    try:
        load = os.getloadavg()[0]
    except OSError:
        load = None
    return dict(cpu=cpu, cores=os.cpu_count(), memory_gib=mem, system=platform.platform(),
                python=platform.python_version(), load_average_1min=load, hostname=platform.node())


def versions() -> dict:
    import importlib.metadata as md

    out = {}
    for name in ("scara", "numpy", "scipy", "numba", "roboticstoolbox-python", "spatialmath-python", "pin", "mujoco"):
        try:
            out[name] = md.version(name)
        except md.PackageNotFoundError:
            out[name] = None
    from scara import _compile

    out["numba_compiled"] = bool(_compile.COMPILED)
    return out


# ------------------------------------------------------------------------------------------------------
# timing helpers
# ------------------------------------------------------------------------------------------------------
def per_call(fns: dict, repeats: int, target_s: float = 0.02) -> dict:
    """Median seconds per call of each ``fn()`` in ``fns`` over ``repeats`` timing loops of ~``target_s``.

    The implementations are timed round-robin (one loop of each, then again), so that a burst of load on
    the shared machine spreads over all of them instead of spoiling one.
    """
    timers, numbers = {}, {}
    for name, fn in fns.items():
        fn()
        timer = timeit.Timer(fn, timer=CLOCK)
        number, _ = timer.autorange()  # >= 0.2 s worth, then scale down to the target
        t_one = timer.timeit(number) / number
        timers[name] = timer
        numbers[name] = max(1, int(target_s / max(t_one, 1e-9)))
    samples = {name: [] for name in fns}
    for _ in range(repeats):
        for name, timer in timers.items():
            samples[name].append(timer.timeit(numbers[name]) / numbers[name])
    return {name: statistics.median(v) for name, v in samples.items()}


# ------------------------------------------------------------------------------------------------------
# library adapters for the loops
# ------------------------------------------------------------------------------------------------------
def _wrap(a):
    return (a + math.pi) % (2.0 * math.pi) - math.pi


class PinocchioCalls:
    """Pinocchio as used in the loops: kinematics via joint Jacobians + frame placement, dynamics via
    ``computeGeneralizedGravity`` and ``aba`` (friction ``F qd`` subtracted in Python)."""

    name = "pinocchio"

    def __init__(self, p, rotors=True):
        import pinocchio as pin

        self.pin = pin
        self.model, self.data = L.pinocchio_model(p, rotors)
        self.ee = self.model.getFrameId("ee")
        self.F = np.asarray(p.F)
        self.LWA = pin.LOCAL_WORLD_ALIGNED

    def pose_jacobian(self, q):
        pin, m, d = self.pin, self.model, self.data
        pin.computeJointJacobians(m, d, q)
        M = pin.updateFramePlacement(m, d, self.ee)
        Jg = pin.getFrameJacobian(m, d, self.ee, self.LWA)
        R = M.rotation
        t = M.translation
        x = np.array([t[0], t[1], t[2], math.atan2(-R[0, 1], R[0, 0])])
        J = Jg[[0, 1, 2, 5]]
        J[3] = -J[3]
        return x, J

    def gravity(self, q):
        return self.pin.computeGeneralizedGravity(self.model, self.data, q)

    def accel(self, q, qd, tau):
        return self.pin.aba(self.model, self.data, q, qd, tau - self.F * qd)


class ToolboxCalls:
    """The Robotics Toolbox as used in the loops: ``ETS.eval``/``ETS.jacob0`` (C) for kinematics,
    ``DHRobot.gravload`` and ``DHRobot.accel`` (built on the C ``rne``; friction included) for dynamics."""

    name = "toolbox"

    def __init__(self, p, rotors=True):
        self.robot = L.toolbox_robot(p, rotors)
        self.ets = self.robot.ets()

    def pose_jacobian(self, q):
        T = self.ets.eval(q)
        Jg = self.ets.jacob0(q)
        x = np.array([T[0, 3], T[1, 3], T[2, 3], math.atan2(-T[0, 1], T[0, 0])])
        J = Jg[[0, 1, 2, 5]]
        J[3] = -J[3]
        return x, J

    def gravity(self, q):
        return self.robot.gravload(q)

    def accel(self, q, qd, tau):
        return self.robot.accel(q, qd, tau)


class MuJoCoCalls:
    """MuJoCo on the exported MJCF (``scara.export.to_mjcf``, via ``libraries.mujoco_model``): gravity by ``mj_rne``
    at rest (controller), and the plant stepped by ``mj_step``: MuJoCo's own RK4 in C, one step per sample with the
    torque held in ``ctrl`` (friction is the MJCF's joint damping)."""

    name = "mujoco"

    def __init__(self, p, rotors=True):
        import mujoco

        self.mj = mujoco
        self.model, self.data = L.mujoco_model(p, rotors)
        self.out = np.empty(self.model.nv)

    def gravity(self, q):
        mj, m, d = self.mj, self.model, self.data
        d.qpos[:] = q
        d.qvel[:] = 0.0
        mj.mj_kinematics(m, d)
        mj.mj_comPos(m, d)
        mj.mj_comVel(m, d)
        mj.mj_rne(m, d, 0, self.out)
        return self.out.copy()

    def step(self, q, qd, tau, h):
        """One ``mj_step`` of ``h`` (the MJCF's timestep) from ``(q, qd)`` with ``tau`` held: ``(q, qd, qdd)``, ``qdd``
        the acceleration at the start (MuJoCo's first RK4 stage)."""
        m, d = self.model, self.data
        if m.opt.timestep != h:
            m.opt.timestep = h
        d.qpos[:] = q
        d.qvel[:] = qd
        d.ctrl[:] = tau
        self.mj.mj_step(m, d)
        return d.qpos.copy(), d.qvel.copy(), d.qacc.copy()


class NumpyCalls:
    """The plain-numpy twin (``libraries.NumpyRobot``): the book's closed forms, arrays built per call."""

    name = "numpy"

    def __init__(self, p, rotors=True):
        self.r = L.NumpyRobot(p if rotors else p.replace(I_m=A.NO_ROTORS))

    def pose_jacobian(self, q):
        return self.r.pose(q), self.r.jacobian(q)

    def gravity(self, q):
        return self.r.gravity(q)

    def accel(self, q, qd, tau):
        return self.r.accel(q, qd, tau)


# ------------------------------------------------------------------------------------------------------
# the loops written with library calls
# ------------------------------------------------------------------------------------------------------
def clik_loop(lib, xr, vr, q0, dt, K, steps):
    """First-order CLIK with the Jacobian inverse, Euler rule, ``steps`` samples. Returns ``q`` (steps, 4)."""
    Q = np.empty((steps, 4))
    QD = np.empty((steps, 4))
    X = np.empty((steps, 4))
    E = np.empty((steps, 4))
    W = np.empty(steps)
    q = np.array(q0, dtype=float)
    for k in range(steps):
        Q[k] = q
        x, J = lib.pose_jacobian(q)
        e = xr[k] - x
        e[3] = _wrap(e[3])
        X[k] = x
        E[k] = e
        W[k] = abs(np.linalg.det(J))
        qd = np.linalg.solve(J, vr[k] + K * e)
        QD[k] = qd
        q = q + dt * qd
    return Q


def closed_loop(lib_plant, lib_ctrl, ref, q0, qd0, dt, KP, KD, steps):
    """PD + gravity at ``dt`` (ZOH) on the plant, one RK4 step per sample (the library's own ``step`` where it has
    one, MuJoCo's ``mj_step``; else RK4 in Python on its ``accel``). Returns ``q`` (steps, 4)."""
    Q = np.empty((steps, 4))
    QD = np.empty((steps, 4))
    QDD = np.empty((steps, 4))
    TAU = np.empty((steps, 4))
    q = np.array(q0, dtype=float)
    qd = np.array(qd0, dtype=float)
    h = dt
    step = getattr(lib_plant, "step", None)  # a library that steps its own RK4 (MuJoCo's mj_step)
    if step is None:  # else RK4 in Python on the library's forward dynamics

        def step(q, qd, tau, h, fd=lib_plant.accel):
            return A.rk4_step(fd, q, qd, tau, h)

    for k in range(steps):
        Q[k] = q
        QD[k] = qd
        r = ref[k]
        tau = KP * (r[0:4] - q) + KD * (r[4:8] - qd) + lib_ctrl.gravity(q)
        TAU[k] = tau
        if k == steps - 1:
            break
        q, qd, QDD[k] = step(q, qd, tau, h)
    return Q


def time_loop(run, ours, n_total, repeats, budget, pilot_steps=200):
    """Time ``run(steps)`` against ``ours()`` (our whole 70 s call), interleaved so that both see the same
    machine load: each repeat times ``ours`` three times (median) and then the library loop once.

    The library loop runs all ``n_total`` samples if a pilot of ``pilot_steps`` says it fits in ``budget``
    seconds, otherwise a fixed number of steps (what fits the budget) whose time is extrapolated linearly.
    Returns a dict with ``seconds`` (median, for ``n_total`` samples), ``ratio_to_ours`` (median of the
    per-repeat ratios), ``steps_timed``, ``extrapolated``, ``ours_seconds`` (all our timings) and ``q``.
    """
    t0 = CLOCK()
    run(pilot_steps)
    est = (CLOCK() - t0) / pilot_steps * n_total
    steps = n_total if est <= budget else max(pilot_steps, int(n_total * budget / est))
    lib_times, ratios, ours_times = [], [], []
    q = None
    for _ in range(repeats):
        mine = []
        for _ in range(3):
            t0 = CLOCK()
            ours()
            mine.append(CLOCK() - t0)
        t0 = CLOCK()
        q = run(steps)
        t_lib = (CLOCK() - t0) * n_total / steps
        lib_times.append(t_lib)
        ours_times.extend(mine)
        ratios.append(t_lib / statistics.median(mine))
    return dict(seconds=statistics.median(lib_times), ratio_to_ours=statistics.median(ratios), steps_timed=steps,
                extrapolated=steps < n_total, ours_seconds=ours_times, q=q)


# ------------------------------------------------------------------------------------------------------
# benchmarks
# ------------------------------------------------------------------------------------------------------
def bench_per_call(repeats: int) -> dict:
    p = scara.ScaraParams().with_payload(5.0)
    q = np.array([0.3, -1.2, 0.4, 0.1])
    qd = np.array([0.1, 0.2, -0.1, 0.3])
    qdd = np.array([1.0, -0.5, 0.2, 2.0])
    tau = np.array([1.0, 2.0, -100.0, 0.3])
    dp = dyn.dynamic_array(p)
    work = dyn.dynamics_workspace()
    o4, o44 = np.empty(4), np.empty((4, 4))
    a1, a2, d0 = p.a1, p.a2, p.d0
    pc = PinocchioCalls(p)
    pin, m, d, ee = pc.pin, pc.model, pc.data, pc.ee
    F = pc.F
    tb = L.toolbox_robot(p)
    ets = tb.ets()
    npr = L.NumpyRobot(p)

    def pin_fk():
        pin.forwardKinematics(m, d, q)
        return pin.updateFramePlacement(m, d, ee)

    calls = {
        "fkine": {
            "ours": ("scara.fkine(q)", lambda: scara.fkine(q, p)),
            "ours (kernel)": ("kinematics.pose_kernel", lambda: kin.pose_kernel(q, a1, a2, d0, o4)),
            "numpy": ("NumpyRobot.fkine", lambda: npr.fkine(q)),
            "pinocchio": ("forwardKinematics + updateFramePlacement", pin_fk),
            "toolbox": ("ETS.eval", lambda: ets.eval(q)),
            "toolbox (DHRobot)": ("DHRobot.fkine", lambda: tb.fkine(q)),
        },
        "jacobian": {
            "ours": ("scara.jacobian(q)", lambda: scara.jacobian(q, p)),
            "ours (kernel)": ("kinematics.jacobian_kernel", lambda: kin.jacobian_kernel(q, a1, a2, o44)),
            "numpy": ("NumpyRobot.jacobian", lambda: npr.jacobian(q)),
            "pinocchio": ("computeFrameJacobian (LOCAL_WORLD_ALIGNED)",
                          lambda: pin.computeFrameJacobian(m, d, q, ee, pin.LOCAL_WORLD_ALIGNED)),
            "toolbox": ("ETS.jacob0", lambda: ets.jacob0(q)),
            "toolbox (DHRobot)": ("DHRobot.jacob0", lambda: tb.jacob0(q)),
        },
        "inertia": {
            "ours": ("scara.inertia(q)", lambda: dyn.inertia(q, p)),
            "ours (kernel)": ("dynamics.inertia_kernel", lambda: dyn.inertia_kernel(q, dp, o44)),
            "numpy": ("NumpyRobot.inertia", lambda: npr.inertia(q)),
            "pinocchio": ("crba (upper triangle)", lambda: pin.crba(m, d, q)),
            "toolbox": ("DHRobot.inertia", lambda: tb.inertia(q)),
        },
        "inverse_dynamics": {
            "ours": ("scara.dynamics.inverse_dynamics", lambda: dyn.inverse_dynamics(q, qd, qdd, p)),
            "ours (kernel)": ("dynamics.inverse_dynamics_kernel",
                              lambda: dyn.inverse_dynamics_kernel(q, qd, qdd, dp, work, o4)),
            "numpy": ("NumpyRobot.rne", lambda: npr.rne(q, qd, qdd)),
            "pinocchio": ("rnea + F qd", lambda: pin.rnea(m, d, q, qd, qdd) + F * qd),
            "toolbox": ("DHRobot.rne (C)", lambda: tb.rne(q, qd, qdd)),
        },
        "forward_dynamics": {
            "ours": ("scara.forward_dynamics", lambda: dyn.forward_dynamics(q, qd, tau, p)),
            "ours (kernel)": ("dynamics.forward_dynamics_kernel",
                              lambda: dyn.forward_dynamics_kernel(q, qd, tau, dp, work, o4)),
            "numpy": ("NumpyRobot.accel", lambda: npr.accel(q, qd, tau)),
            "pinocchio": ("aba(tau - F qd)", lambda: pin.aba(m, d, q, qd, tau - F * qd)),
            "toolbox": ("DHRobot.accel", lambda: tb.accel(q, qd, tau)),
        },
    }
    out = {}
    for op, impls in calls.items():
        times = per_call({impl: fn for impl, (_, fn) in impls.items()}, repeats)
        out[op] = {impl: dict(call=label, us=times[impl] * 1e6) for impl, (label, _) in impls.items()}
        ours = out[op]["ours"]["us"]
        for impl, e in out[op].items():
            e["ratio_to_ours"] = e["us"] / ours
    return out


def _whole_runs(ours, libs, loop, n, q_ours, repeats, budget, pilot_steps) -> dict:
    out = {}
    all_ours = []
    for lib in libs:
        r = time_loop(lambda s, lib=lib: loop(lib, s), ours, n, max(1, (repeats + 1) // 2), budget, pilot_steps)
        q = r.pop("q")
        all_ours.extend(r.pop("ours_seconds"))
        r["max_q_difference"] = float(np.max(np.abs(q - q_ours[:r["steps_timed"]])))
        out[lib.name] = r
    return all_ours, out


def bench_clik(traj, repeats: int, budget: float) -> dict:
    """The whole 70 s CLIK (Jacobian inverse): ``scara.clik`` against the same loop on each library."""
    p = scara.ScaraParams()
    n = len(traj.t)

    def ours():
        return clik(traj, "inverse")

    res = ours()
    xr = np.ascontiguousarray(traj.x)
    vr = np.ascontiguousarray(traj.xd)
    q0 = res.q[0].copy()
    loop_alone = [ours().elapsed for _ in range(repeats)]
    all_ours, libs = _whole_runs(
        ours, (NumpyCalls(p), PinocchioCalls(p), ToolboxCalls(p)),
        lambda lib, s: clik_loop(lib, xr, vr, q0, traj.dt, SEED_K, s), n, res.q, repeats, budget, 200)
    return _run_entry('scara.clik(traj, "inverse")', all_ours, loop_alone, libs,
                      "Python loop: {name} pose + Jacobian, numpy.linalg.solve", n)


def _run_entry(call: str, all_ours, loop_alone, libs: dict, lib_call: str, n: int) -> dict:
    """The stored entry of a whole-run task: ours (``call``, the reference of every ratio), then each library's
    timing ``libs[name]`` labelled ``lib_call.format(name=name)``, and the number of samples."""
    out = {"ours": dict(call=call, seconds=statistics.median(all_ours), steps_timed=n, extrapolated=False,
                        max_q_difference=0.0, ratio_to_ours=1.0, loop_only_seconds=statistics.median(loop_alone))}
    for name, e in libs.items():
        e["call"] = lib_call.format(name=name)
        out[name] = e
    out["_samples"] = n
    return out


def bench_closed_loop(traj, repeats: int, budget: float) -> dict:
    """The whole 70 s PD + gravity closed loop: ``scara.simulate`` against the same loop on each library."""
    plant = scara.ScaraParams().with_payload(5.0).replace(I_m=A.NO_ROTORS)
    ctrl_model = scara.ScaraParams().replace(I_m=A.NO_ROTORS)
    ctrl = PDGravityController(model=ctrl_model)
    KP, KD = ctrl.K_P, ctrl.K_D
    ref = np.ascontiguousarray(ikine_reference(traj, plant))
    n = len(ref)

    def ours():
        return simulate(ctrl, traj, plant, joint_reference=ref)

    res = ours()
    q0, qd0 = ref[0, :4].copy(), ref[0, 4:8].copy()
    loop_alone = [ours().elapsed for _ in range(repeats)]
    pairs = {cls.name: (cls(plant, rotors=False), cls(ctrl_model, rotors=False))
             for cls in (NumpyCalls, PinocchioCalls, ToolboxCalls, MuJoCoCalls)}

    class _Pair:
        def __init__(self, name):
            self.name = name
            self.plant, self.ctrl = pairs[name]

    all_ours, libs = _whole_runs(
        ours, [_Pair(k) for k in pairs],
        lambda lib, s: closed_loop(lib.plant, lib.ctrl, ref, q0, qd0, traj.dt, KP, KD, s), n, res.q, repeats,
        budget, 100)
    out = _run_entry("scara.simulate(PDGravityController(), ...)", all_ours, loop_alone, libs,
                     "Python loop: {name} gravity (controller) + forward dynamics (plant), RK4", n)
    out["mujoco"]["call"] = "Python loop: mujoco gravity (mj_rne, controller) + mj_step (plant, its RK4 in C)"
    return out


# ------------------------------------------------------------------------------------------------------
# printing
# ------------------------------------------------------------------------------------------------------
def _fmt_time(s: float) -> str:
    if s < 1e-3:
        return f"{s * 1e6:8.2f} us"
    if s < 1.0:
        return f"{s * 1e3:8.2f} ms"
    return f"{s:8.2f} s "


def print_tables(res: dict) -> None:
    m, v = res["machine"], res["versions"]
    print(f"\n{res['date']}  on {m['cpu']} ({m['cores']} cores), Python {m['python']}")
    print("versions: " + ", ".join(f"{k} {val}" for k, val in v.items() if k != "numba_compiled"))
    if "agreement" in res:
        print()
        A._print(res["agreement"])
    pc = res["per_call"]
    impls = ["ours", "ours (kernel)", "numpy", "pinocchio", "toolbox"]
    print("\nPer-call cost (median, microseconds; in brackets: time / ours)")
    print(f"  {'':18s}" + "".join(f"{i:>22s}" for i in impls))
    for op, e in pc.items():
        row = f"  {op:18s}"
        for i in impls:
            row += f"{e[i]['us']:>12.2f} ({e[i]['ratio_to_ours']:6.2f}x)"
        print(row)
    for op in ("fkine", "jacobian"):
        e = pc[op]["toolbox (DHRobot)"]
        print(f"  (toolbox {e['call']}: {e['us']:.1f} us)")
    for key, title in (("clik", "Whole 70 s CLIK, Jacobian inverse (median)"),
                       ("closed_loop", "Whole 70 s closed loop, PD + gravity, RK4 (median)")):
        r = res[key]
        print(f"\n{title}, {r['_samples']} samples")
        print(f"  {'':10s}{'time':>12s}{'ours faster by':>16s}{'max |q - q_ours|':>18s}  note")
        for name in ("ours", "numpy", "pinocchio", "toolbox", "mujoco"):
            if name not in r:
                continue
            e = r[name]
            note = (f"extrapolated from {e['steps_timed']} steps" if e["extrapolated"] else "whole run")
            if name == "ours":
                note += f"; compiled loop alone {_fmt_time(e['loop_only_seconds']).strip()} (wall clock)"
            print(f"  {name:10s}{_fmt_time(e['seconds']):>12s}{e['ratio_to_ours']:>15.1f}x"
                  f"{e['max_q_difference']:>18.1e}  {note}")
    print("\nTargets")
    for k, t in res["targets"].items():
        print(f"  {k:28s} target >= {t['target']:6.0f}x   measured {t['measured']:8.1f}x   "
              f"{'met' if t['met'] else 'NOT met'}")


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer states and repeats (smoke test)")
    ap.add_argument("--repeats", type=int, default=None, help="repeats of each timing (default 7, quick 3)")
    ap.add_argument("--budget", type=float, default=None,
                    help="seconds a library loop may take for 70 s before it is extrapolated (default 10)")
    ap.add_argument("--no-agreement", action="store_true", help="skip the agreement checks")
    ap.add_argument("--out", default=os.path.join(HERE, "results.json"), help="where to write the JSON")
    args = ap.parse_args(argv)
    repeats = args.repeats or (3 if args.quick else 7)
    budget = args.budget if args.budget is not None else (3.0 if args.quick else 10.0)

    res = dict(date=_dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"), machine=machine_info(),
               versions=versions(),
               settings=dict(clock="process CPU time (time.process_time)", repeats=repeats, library_run_repeats=max(1, (repeats + 1) // 2), budget_s=budget, quick=args.quick, dt=1e-3, duration_s=70.0,
                             clik_K=SEED_K.tolist(), closed_loop_K_P=PDGravityController().K_P.tolist(),
                             closed_loop_K_D=PDGravityController().K_D.tolist(),
                             closed_loop_plant="the book's robot + 5 kg payload, rotor inertias zero",
                             rk4_steps_per_sample=1))
    t_start = time.perf_counter()  # wall clock, for the report only
    if not args.no_agreement:
        print("agreement ...", flush=True)
        res["agreement"] = A.all_agreement(*((100, 60) if args.quick else (500, 300)))
        print("MuJoCo runs ...", flush=True)
        res["agreement"]["mujoco_runs"] = A.mujoco_agreement()
    traj = reference_trajectory()
    print("per-call costs ...", flush=True)
    res["per_call"] = bench_per_call(repeats)
    print("70 s CLIK runs ...", flush=True)
    res["clik"] = bench_clik(traj, repeats, budget)
    print("70 s closed-loop runs ...", flush=True)
    res["closed_loop"] = bench_closed_loop(traj, repeats, budget)
    measured = {
        "closed_loop_vs_pinocchio": res["closed_loop"]["pinocchio"]["ratio_to_ours"],
        "closed_loop_vs_toolbox": res["closed_loop"]["toolbox"]["ratio_to_ours"],
        "clik_vs_numpy": res["clik"]["numpy"]["ratio_to_ours"],
    }
    res["targets"] = {k: dict(target=TARGETS[k], measured=measured[k], met=bool(measured[k] >= TARGETS[k]))
                      for k in TARGETS}
    res["benchmark_seconds"] = time.perf_counter() - t_start
    print_tables(res)
    with open(args.out, "w") as fh:
        json.dump(res, fh, indent=1, default=float)
        fh.write("\n")
    print(f"\nwrote {os.path.relpath(args.out)} ({res['benchmark_seconds']:.0f} s)")
    return res


if __name__ == "__main__":
    main()
