"""Fuzz test of every public numeric function and constructor of the package.

Each callable of :data:`TABLE` is called with hypothesis-generated arguments: valid ones, and in most examples one
or two hostile ones (NaN, +-inf, 1e300, 1e-300, negative numbers, scalars for vectors, (3,) for (4,), 2-D for
1-D, strings, None, lists of strings, booleans, dicts, empty arrays, singular configurations, trajectory- and
result-like objects with a NaN or a wrong shape inside; see tests/_fuzz_inputs.py). The property: the call either
returns a result whose numbers are all finite (arrays, floats, tuples, lists, dicts, dataclasses and objects'
attributes, walked by ``_fuzz_inputs.non_finite``) or raises :class:`scara.ScaraError`. Any other exception, a
non-finite number in the result, an example over the deadline or a hang fails the test with the callable, the
inputs and the exception.

``test_table_covers_public_names`` compares the table with the public names of ``scara`` and its sub-modules:
a new public function needs an entry here (or a place, with its reason, in :data:`NOT_FUZZED`).
``test_probe`` re-runs fixed hostile calls (:data:`PROBES`: the minimal inputs of past findings, and special
inputs a random draw reaches rarely).

Settings: ``derandomize=True`` (the same examples on every run), :data:`EXAMPLES` examples per callable
(:data:`EXPENSIVE_EXAMPLES` for the runs; both overridable by environment variables), a deadline of 2 s per
example, a timeout of :data:`TIMEOUT_S` s per call (``signal.setitimer``; ``faulthandler`` ends the process if a
compiled loop ignores it). The expensive callables get short inputs: trajectories of 0.3-0.4 s, set points and
open-loop runs of 0.1 s. Each callable first runs a few examples without deadline and without reporting, so that
the compilation of its kernels does not count against the deadline.

``SCARA_FUZZ_LOG=path`` records every failing example (one JSON line each; also the valid calls the package
refuses, and per-callable counts) instead of failing at the first: the way to list all the distinct failures at
once.
"""
from __future__ import annotations

import collections
import dataclasses
import faulthandler
import functools
import importlib
import json
import os
import signal
import time
import traceback
import types
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, Verbosity, given, settings
from hypothesis import strategies as st

import _fuzz_inputs as fz
from _fuzz_inputs import BAD_FLOATS, BAD_TYPES, Arg, choice, contract, fixed, gain, integer, scalar, vector

import scara

EXAMPLES = int(os.environ.get("SCARA_FUZZ_EXAMPLES", "50"))
EXPENSIVE_EXAMPLES = int(os.environ.get("SCARA_FUZZ_EXPENSIVE_EXAMPLES", "40"))
WARMUP_EXAMPLES = 3
DEADLINE_MS = 2000
TIMEOUT_S = 10.0  # per example: SIGALRM turns a longer call into a failure naming the callable and the inputs
HARD_TIMEOUT_FACTOR = 3  # a call that ignores SIGALRM (compiled code) ends the process after 3 x the timeout
LOG = os.environ.get("SCARA_FUZZ_LOG")

MODULES = ("kinematics", "_manipulability", "trajectory", "_clik", "dynamics", "_simulate", "control", "identification",
           "gains", "params", "errors")


def _mod(name):
    return importlib.import_module(f"scara.{name}")


# --------------------------------------------------------------------------------------------------
# shared valid objects (built once, on first use)
# --------------------------------------------------------------------------------------------------
class F:
    """Valid objects: short trajectories, controllers, runs. Each is built once."""

    @staticmethod
    @functools.lru_cache(maxsize=None)
    def trajs():
        T = _mod("trajectory")
        a = fz.label(T.plan_path([(0.5, 0.3, 0.5), (0.55, 0.3, 0.5)], [0.3]), "<plan_path 0.3 s line>")
        b = fz.label(T.plan_path([(0.5, 0.3, 0.5), (0.5, 0.35, 0.45), (0.45, 0.35, 0.5)], [0.2, 0.2]),
                     "<plan_path 0.4 s two lines>")
        return a, b

    @staticmethod
    def bad_trajs():
        """Trajectory-like objects that are not valid trajectories."""
        a = F.trajs()[0]
        t, x, xd, xdd = (np.array(v) for v in (a.t, a.x, a.xd, a.xdd))

        def ns(**over):
            d = dict(t=t, x=x, xd=xd, xdd=xdd, dt=a.dt, elbow=-1)
            d.update(over)
            return types.SimpleNamespace(**d)

        def poison(arr, v):
            arr = arr.copy()
            arr[len(arr) // 2, 0] = v
            return arr

        out = [ns(x=poison(x, np.nan)), ns(xd=poison(xd, np.inf)), ns(xdd=poison(xdd, -1e300)),
               ns(x=x[:, :3]), ns(x=x[:10]), ns(t=t[:0], x=x[:0], xd=xd[:0], xdd=xdd[:0]),
               ns(dt=0.0), ns(dt=-1e-3), ns(dt=np.nan), ns(dt=1e300), ns(dt=1e-300), ns(dt="abc"),
               ns(x=poison(x, 5.0)), ns(x=x * 0 + np.array([0.0, 0.0, 0.5, 0.0])),  # unreachable, singular
               ns(x=np.full_like(x, 1e300)), ns(t=t[:1], x=x[:1], xd=xd[:1], xdd=xdd[:1]),
               ns(elbow=0), ns(elbow="up"), types.SimpleNamespace(x=x), types.SimpleNamespace()]
        return st.sampled_from(out + list(BAD_TYPES) + list(BAD_FLOATS[:3]))

    @staticmethod
    def traj_arg(name="traj", optional=False):
        return fixed(name, st.sampled_from(range(2)).map(lambda i: F.trajs()[i]),
                     st.deferred(F.bad_trajs), optional)

    @staticmethod
    @functools.lru_cache(maxsize=None)
    def controllers():
        S, C = _mod("_simulate"), _mod("control")
        return tuple(fz.label(c, f"<{type(c).__name__}()>") for c in (
            S.PDGravityController(), S.TorqueController(), C.RobustController(), C.AdaptiveController(),
            C.OperationalSpaceController(), C.OperationalSpaceController(integral=False),
            C.IndependentJointController(), C.PDPlusGravityController(), C.ComputedTorqueController()))

    @staticmethod
    @functools.lru_cache(maxsize=None)
    def runs():
        """(controller, result) pairs of short runs with a 5 kg payload."""
        S = _mod("_simulate")
        traj = F.trajs()[0]
        plant = scara.ScaraParams().with_payload(5.0)
        out = []
        for c in F.controllers():
            res = S.simulate(c, traj, plant)
            out.append((c, fz.label(res, f"<run of {type(c).__name__} on the 0.3 s line>")))
        return tuple(out)

    @staticmethod
    def bad_results():
        res = F.runs()[2][1]

        def ns(**over):
            d = {f.name: getattr(res, f.name) for f in dataclasses.fields(res)}
            d.update(over)
            return types.SimpleNamespace(**d)

        tau = res.tau.copy()
        tau[5, 1] = np.nan
        out = [ns(tau=tau), ns(tau=res.tau[:, :3]), ns(tau=np.zeros((0, 4))), ns(q=res.q[:, :2]),
               ns(t=res.t[:0], q=res.q[:0], qd=res.qd[:0], tau=res.tau[:0], e=res.e[:0], reference=res.reference[:0]),
               ns(dt=np.nan), ns(dt=-1.0), ns(e=res.e * np.nan), ns(reference=res.reference[:, :4]),
               types.SimpleNamespace(tau=[["a"]]), types.SimpleNamespace()]
        return st.sampled_from(out + list(BAD_TYPES) + list(BAD_FLOATS[:3]))

    @staticmethod
    def params_arg(name="p", optional=True):
        P = scara.ScaraParams
        valid = st.sampled_from([None, fz.label(P(), "ScaraParams()"),
                                 fz.label(P().with_payload(5.0), "ScaraParams().with_payload(5.0)")])
        return Arg(name, valid, st.sampled_from(BAD_TYPES + BAD_FLOATS + ({"a1": 0.5},)), optional)


#: configurations of the right type and shape that are special: singular (theta2 = 0 or pi, the arm stretched or
#: folded), the quill outside its stroke, angles beyond any meaning (1e7, 1e17 rad)
SPECIAL_Q = (np.zeros(4), np.array([0.3, 0.0, 0.5, 0.0]), np.array([0.3, np.pi, 0.5, 0.0]),
             np.array([0.3, 1.0, -1.0, 0.0]), np.array([0.3, 1.0, 5.0, 0.0]), np.array([1e7, 1.0, 0.5, 0.0]),
             np.array([0.3, 1e17, 0.5, 0.0]), np.array([0.3, 1.0, 0.5, -1e17]))


def q_arg(name="q", optional=False, lo=-3.0, hi=3.0):
    a = vector(name, 4, lo, hi, optional)
    return Arg(name, a.valid, st.one_of(a.hostile, st.sampled_from(SPECIAL_Q)), optional)


def elbow_arg(name="elbow", optional=True):
    return Arg(name, st.sampled_from([1, -1]),
               st.sampled_from([0, 2, -2, 0.5, np.nan, np.inf, "up", None, True, [1], {}]), optional)


def pose_arg(name="x", optional=False):
    """A reachable pose (x, y, z, phi)."""
    pts = fz.reachable_points()
    valid = st.tuples(st.sampled_from(pts), st.floats(-3, 3)).map(lambda a: np.array([*a[0], a[1]]))
    unreachable = st.sampled_from([np.array([5.0, 5.0, 0.5, 0.0]), np.array([0.0, 0.0, 0.5, 0.0]),
                                   np.array([0.5, 0.3, 5.0, 0.0]), np.array([1.0, 0.0, 0.5, 0.0])])
    a = vector(name, 4, valid=valid, optional=optional)
    return Arg(name, valid, st.one_of(a.hostile, unreachable), optional)


def point_arg(name="point", optional=False):
    pts = fz.reachable_points()
    valid = st.sampled_from(pts).map(np.array)
    a = vector(name, 3, valid=valid, optional=optional)
    return Arg(name, valid, st.one_of(a.hostile, st.just(np.array([5.0, 5.0, 0.5]))), optional)


def pi_arg(name="pi"):
    D = _mod("dynamics")
    valid = st.sampled_from([0.0, 2.0, 5.0]).map(
        lambda m: D.dynamic_parameters(scara.ScaraParams().with_payload(m)))
    return vector(name, D.N_PI, valid=valid)


def small_int(name, lo, hi, optional=True):
    return integer(name, lo, hi, optional)


def bool_arg(name, optional=True):
    return Arg(name, st.booleans(), st.sampled_from(["yes", None, 2, np.nan, [True], {}]), optional)


def plan_path_args():
    pts = fz.reachable_points()

    @st.composite
    def plan(draw):
        n = draw(st.integers(2, 3))
        wps = draw(st.lists(st.sampled_from(pts), min_size=n, max_size=n, unique=True))
        durs = draw(st.lists(st.sampled_from([0.1, 0.15, 0.2]), min_size=n - 1, max_size=n - 1))
        return wps, durs

    plans = plan()
    bad_wps = st.sampled_from(BAD_TYPES + BAD_FLOATS + (
        [(0.5, 0.3, 0.5)], [(0.5, 0.3, 0.5), (5.0, 5.0, 0.5)], [(0.5, 0.3, 0.5), (0.5, 0.3, 0.5)],
        [(0.5, 0.3, 0.5), (np.nan, 0.3, 0.5)], [(0.5, 0.3), (0.5, 0.4)], [("a", "b", "c"), (0.5, 0.3, 0.5)],
        [(0.5, 0.3, 0.5), (0.55, 0.3, 0.5, 0.1)], [(0.5, 0.3, 0.5), (0.55, 0.3, 1e300)]))
    # the waypoints and the durations come from one draw (their lengths must agree)
    return [
        Arg("waypoints", plans.map(lambda a: a[0]), bad_wps),
        Arg("durations", st.just(None),  # the valid value comes with the waypoints (see _fill_linked)
            st.sampled_from(BAD_TYPES + BAD_FLOATS + ([0.1234], [-0.2], [np.nan], [0.0], [1e300], [0.1, 0.1, 0.1]))),
        Arg("blends", st.just(None),
            st.one_of(fz.HOSTILE_SCALAR, st.sampled_from([[np.nan], [0.0], [-0.01], [1e300], [0.02, 0.02, 0.02]])),
            optional=True),
        Arg("arcs", st.just(None), st.sampled_from(BAD_TYPES + ({0: (0.5, 0.3, 0.5)}, {5: (0.1, 0.1, 0.1)},
                                                               {0: (np.nan, 0.0, 0.0)})), optional=True),
        Arg("phi", st.one_of(st.none(), st.floats(-3, 3)), fz.HOSTILE_SCALAR, optional=True),
        Arg("total", st.sampled_from([None, 0.5]), fz.HOSTILE_SCALAR, optional=True),
        Arg("dt", st.sampled_from([1e-3, 5e-3]), fz.HOSTILE_SCALAR, optional=True),
        F.params_arg(),
        elbow_arg(),
        bool_arg("check"),
    ], plans


# --------------------------------------------------------------------------------------------------
# the table: every fuzzed callable and how to build its arguments
# --------------------------------------------------------------------------------------------------
@dataclasses.dataclass
class Entry:
    """A fuzzed callable: ``module:name`` (``Class.method`` for a method of a shared instance), its arguments
    (a function returning the list of :class:`Arg`, called when the test runs), and its options."""

    module: str
    name: str
    args: Callable[[], list]
    examples: int = EXAMPLES
    allow_inf: bool = False  # +-inf is a documented result value (NaN never is)
    target: Callable | None = None  # the callable, when it is not ``getattr(module, name)``
    mutate_max: int = 2
    documented_non_finite: tuple = ()  # result paths whose NaN/inf is documented (see each entry's comment)
    #: coherent valid keyword sets (a strategy of dicts): a call then takes one of them, with the hostile
    #: arguments laid over it, instead of drawing each valid argument on its own
    scenario: Callable | None = None

    @property
    def key(self):
        return f"{self.module}:{self.name}"

    def resolve(self):
        return self.target() if self.target is not None else getattr(_mod(self.module), self.name)


def _p():
    return F.params_arg()


TABLE = [
    # ---- kinematics --------------------------------------------------------------------------------------
    Entry("kinematics", "base_transform", lambda: [_p()]),
    Entry("kinematics", "dh_table", lambda: [q_arg(optional=True), _p()]),
    Entry("kinematics", "dh_matrix", lambda: [scalar("a", 0, 1), scalar("alpha", -3, 3), scalar("d", 0, 1),
                                              scalar("theta", -3, 3)]),
    Entry("kinematics", "link_frames", lambda: [q_arg(), _p()]),
    Entry("kinematics", "fkine", lambda: [q_arg(), _p()]),
    Entry("kinematics", "pose", lambda: [q_arg(), _p()]),
    Entry("kinematics", "jacobian", lambda: [q_arg(), _p()]),
    Entry("kinematics", "check_regular", lambda: [q_arg(), _p(), contract("what", "q0")]),
    Entry("kinematics", "jacobian_dot", lambda: [q_arg(), q_arg("qd"), _p()]),
    Entry("kinematics", "ikine", lambda: [pose_arg(), _p(), elbow_arg()]),
    Entry("kinematics", "is_reachable", lambda: [point_arg("points"), _p()]),
    Entry("kinematics", "check_reachable", lambda: [point_arg(), _p(),
                                                    Arg("label", st.just("p"), st.sampled_from([None, 3, {}]), True)]),
    Entry("kinematics", "geometry", lambda: [_p()]),
    # ---- manipulability ----------------------------------------------------------------------------------
    Entry("_manipulability", "manipulability", lambda: [q_arg(), _p()]),
    Entry("_manipulability", "velocity_ellipsoid", lambda: [q_arg(), _p(), _rows()]),
    # documented: "reciprocal lengths 1/sigma_i (inf where sigma_i = 0)"
    Entry("_manipulability", "force_ellipsoid", lambda: [q_arg(), _p(), _rows()],
          documented_non_finite=("result.lengths",)),
    # documented: W is "NaN where the point is outside the annulus"
    Entry("_manipulability", "workspace_map", lambda: [_p(), small_int("n", 3, 25)],
          documented_non_finite=("result[2]",)),
    Entry("_manipulability", "singular_radii", lambda: [_p()]),
    # ---- trajectory --------------------------------------------------------------------------------------
    Entry("trajectory", "Line", lambda: [vector("start", 3), vector("end", 3)]),
    Entry("trajectory", "Arc", lambda: _arc_args()),
    Entry("trajectory", "Arc.through", lambda: [vector("start", 3, valid=st.just(np.array([0.5, 0.3, 0.5]))),
                                                vector("via", 3, valid=st.just(np.array([0.55, 0.35, 0.5]))),
                                                vector("end", 3, valid=st.just(np.array([0.6, 0.3, 0.5])))],
          target=lambda: _mod("trajectory").Arc.through),
    Entry("trajectory", "Trapezoidal", lambda: _trapezoidal_args()),
    Entry("trajectory", "trapezoidal", lambda: [vector("tau", 5, 0, 3)] + _trapezoidal_args(True)),
    Entry("trajectory", "Waypoint", lambda: [point_arg("position"), scalar("anticipation", 0, 1, True),
                                             scalar("phi", -3, 3, True),
                                             Arg("label", st.just("w"), st.sampled_from([3, {}, ["a"]]), True)]),
    Entry("trajectory", "plan_path", lambda: plan_path_args(), examples=EXPENSIVE_EXAMPLES),
    Entry("trajectory", "Trajectory.evaluate", lambda: [vector("t", 6, -0.1, 0.5)],
          target=lambda: F.trajs()[1].evaluate),
    Entry("trajectory", "start_orientation", lambda: [point_arg(), _p(), elbow_arg()]),
    Entry("trajectory", "reference_plan", lambda: []),
    Entry("trajectory", "cubic", lambda: [q_arg("q0", lo=-1, hi=1), q_arg("q1", lo=-1, hi=1),
                                          scalar("duration", 0.05, 2), q_arg("qd_start", True, -1, 1),
                                          q_arg("qd_end", True, -1, 1), _p()]),
    Entry("trajectory", "quintic", lambda: [q_arg("q0", lo=-1, hi=1), q_arg("q1", lo=-1, hi=1),
                                            scalar("duration", 0.05, 2), q_arg("qd_start", True, -1, 1),
                                            q_arg("qd_end", True, -1, 1), q_arg("qdd_start", True, -1, 1),
                                            q_arg("qdd_end", True, -1, 1), _p()]),
    Entry("trajectory", "joint_trajectory", lambda: [
        vector("points", (3, 4), valid=st.sampled_from([JOINT_POINTS, JOINT_POINTS[::-1].copy()])),
        vector("times", 3, valid=st.sampled_from([np.array([0.0, 0.2, 0.4]), np.array([0.1, 0.15, 0.5])])),
        choice("kind", ("cubic", "quintic"), True), choice("velocities", ("mean", "spline"), True), _p()]),
    Entry("trajectory", "joint_counterpart", lambda: [F.traj_arg(), choice("kind", ("cubic", "quintic"), True),
                                                      small_int("extra", 0, 3)], examples=EXPENSIVE_EXAMPLES),
    Entry("trajectory", "passage_times", lambda: [F.traj_arg()]),
    Entry("trajectory", "path_deviation", lambda: [_joint_counterpart_arg(), F.traj_arg()]),
    Entry("trajectory", "segment_deviations", lambda: [_joint_counterpart_arg(), F.traj_arg()]),
    Entry("trajectory", "compare_joint_space", lambda: [F.traj_arg(), small_int("extra", 0, 2), _p()],
          examples=EXPENSIVE_EXAMPLES),
    Entry("trajectory", "reference_trajectory",
          lambda: [scalar("dt", 0, 0, True, valid=st.sampled_from([1e-3, 1e-2])), _p()],
          examples=EXPENSIVE_EXAMPLES),
    # ---- clik --------------------------------------------------------------------------------------------
    Entry("_clik", "clik", lambda: _clik_args(), examples=EXPENSIVE_EXAMPLES, mutate_max=2),
    Entry("_clik", "clik2", lambda: _clik2_args(), examples=EXPENSIVE_EXAMPLES, mutate_max=2),
    Entry("_clik", "start_configuration", lambda: [F.traj_arg(), _p()]),
    Entry("_clik", "transpose_stability", lambda: [F.traj_arg(), gain("K", optional=True), _p(),
                                                  elbow_arg()]),
    Entry("_clik", "second_order_gains", lambda: [gain("K", optional=True)]),
    Entry("_clik", "dexterity", lambda: [q_arg(), choice("objective", ("sin2", "manipulability"), True), _p()]),
    # ---- dynamics ----------------------------------------------------------------------------------------
    Entry("dynamics", "dynamic_array", lambda: [_p()]),
    Entry("dynamics", "dynamic_parameters", lambda: [_p()]),
    Entry("dynamics", "params_from_pi", lambda: [pi_arg(), F.params_arg("base"), scalar("rtol", 1e-12, 1e-3, True)]),
    Entry("dynamics", "payload_from_pi", lambda: [pi_arg(), F.params_arg("base")]),
    Entry("dynamics", "inertia", lambda: [q_arg(), _p()]),
    Entry("dynamics", "inertia_split", lambda: [q_arg(), _p()]),
    Entry("dynamics", "coriolis", lambda: [q_arg(), q_arg("qd"), _p()]),
    Entry("dynamics", "gravity", lambda: [q_arg(), _p()]),
    Entry("dynamics", "friction", lambda: [_p()]),
    Entry("dynamics", "inverse_dynamics", lambda: [q_arg(), q_arg("qd"), q_arg("qdd", hi=10, lo=-10), _p()]),
    Entry("dynamics", "forward_dynamics", lambda: [q_arg(), q_arg("qd"), q_arg("tau", lo=-100, hi=100), _p()]),
    Entry("dynamics", "regressor", lambda: [q_arg(), q_arg("qd"), q_arg("qd_r"), q_arg("qdd_r"), _p()]),
    Entry("dynamics", "kinetic_energy", lambda: [q_arg(), q_arg("qd"), _p()]),
    Entry("dynamics", "potential_energy", lambda: [q_arg(), _p()]),
    Entry("dynamics", "total_energy", lambda: [q_arg(), q_arg("qd"), _p()]),
    Entry("dynamics", "torque_breakdown", lambda: [q_arg(), q_arg("qd"), q_arg("qdd"), _p()]),
    Entry("dynamics", "dynamics_workspace", lambda: []),
    # ---- simulate ----------------------------------------------------------------------------------------
    Entry("_simulate", "Controller", lambda: []),
    Entry("_simulate", "PDGravityController", lambda: [gain("K_P", lo=0, hi=1e4, optional=True),
                                                      gain("K_D", lo=0, hi=1e3, optional=True),
                                                      F.params_arg("model")]),
    Entry("_simulate", "TorqueController", lambda: [q_arg("tau", optional=True, lo=-10, hi=10)]),
    Entry("_simulate", "simulate", lambda: _simulate_args(), examples=EXPENSIVE_EXAMPLES,
          scenario=lambda: _simulate_scenarios(None)),
    Entry("_simulate", "ikine_reference", lambda: [F.traj_arg(), _p(), elbow_arg()]),
    Entry("_simulate", "joint_setpoint", lambda: [q_arg("q_d"),
                                                 scalar("duration", 0, 0, valid=st.sampled_from([0.05, 0.1, 0.3])),
                                                 scalar("dt", 0, 0, True, valid=st.sampled_from([1e-3, 1e-2]))]),
    # ---- control -----------------------------------------------------------------------------------------
    Entry("control", "RobustController", lambda: [
        gain("K_P", lo=100, hi=2000, optional=True), gain("K_D", lo=40, hi=100, optional=True),
        scalar("rho", 1, 50, True), scalar("epsilon", 0.01, 0.1, True), gain("Lambda", lo=1, hi=30, optional=True),
        Arg("P", st.just(None), st.sampled_from(BAD_TYPES + BAD_FLOATS + (np.eye(8), -np.eye(8), np.eye(4),
                                                                           np.full((8, 8), np.nan))), True),
        gain("B_hat", lo=0.5, hi=20, optional=True), F.params_arg("model"),
        gain("tau_max", lo=10, hi=1000, optional=True), scalar("max_error", 0.01, 0.1, True)]),
    Entry("control", "AdaptiveController", lambda: [
        gain("Lambda", lo=1, hi=30, optional=True), gain("K_D", lo=50, hi=1000, optional=True),
        Arg("K_pi", st.sampled_from([None, 0.5, {"m3": 0.5}]),
            st.sampled_from(BAD_TYPES + BAD_FLOATS + ({"nope": 1.0}, {"m3": -1.0}, np.full(13, np.inf),
                                                      np.ones(12))), True),
        F.params_arg("model"), gain("tau_max", lo=10, hi=1000, optional=True), scalar("max_error", 0.01, 0.1, True)],
          allow_inf=True),
    Entry("control", "OperationalSpaceController", lambda: [
        bool_arg("integral"), gain("K_P", lo=1000, hi=2000, optional=True), gain("K_D", lo=40, hi=100, optional=True),
        gain("K_I", lo=100, hi=9000, optional=True), F.params_arg("model"),
        gain("tau_max", lo=10, hi=1000, optional=True), scalar("max_error", 0.01, 0.1, True)]),
    Entry("control", "IndependentJointController", lambda: [
        bool_arg("integral"), gain("omega", lo=5, hi=60, optional=True), gain("B_bar", lo=0.5, hi=30, optional=True),
        bool_arg("feedforward"), bool_arg("saturation"), bool_arg("anti_windup"), F.params_arg("model"),
        gain("tau_max", lo=10, hi=1000, optional=True), scalar("max_error", 0.01, 0.1, True)]),
    Entry("control", "PDPlusGravityController", lambda: [
        gain("omega", lo=5, hi=60, optional=True), gain("B_bar", lo=0.5, hi=30, optional=True),
        gain("K_P", lo=100, hi=30000, optional=True), gain("K_D", lo=10, hi=2000, optional=True), F.params_arg("model"),
        gain("tau_max", lo=10, hi=1000, optional=True), scalar("max_error", 0.01, 0.1, True)]),
    Entry("control", "ComputedTorqueController", lambda: [
        gain("omega", lo=5, hi=300, optional=True), gain("zeta", lo=0.5, hi=2, optional=True),
        gain("K_P", lo=100, hi=2000, optional=True), gain("K_D", lo=40, hi=100, optional=True),
        scalar("dt", 1e-4, 1e-3, True), F.params_arg("model"),
        gain("tau_max", lo=10, hi=1000, optional=True), scalar("max_error", 0.01, 0.1, True)]),
    Entry("control", "ComputedTorqueController.steady_state_error", lambda: [F.params_arg("plant", optional=False), q_arg(optional=True)],
          target=lambda: _mod("control").ComputedTorqueController().steady_state_error),
    Entry("control", "PDPlusGravityController.run", lambda: _run_args(), examples=EXPENSIVE_EXAMPLES,
          target=lambda: F.controllers()[7].run, scenario=lambda: _simulate_scenarios(7)),
    Entry("control", "ComputedTorqueController.run", lambda: _run_args(), examples=EXPENSIVE_EXAMPLES,
          target=lambda: F.controllers()[8].run, scenario=lambda: _simulate_scenarios(8)),
    Entry("control", "IndependentJointController.run", lambda: _run_args(), examples=EXPENSIVE_EXAMPLES,
          target=lambda: F.controllers()[6].run, scenario=lambda: _simulate_scenarios(6)),
    Entry("control", "independent_gains", lambda: [gain("B_bar", lo=0.5, hi=30, optional=True),
                                                   gain("omega", lo=5, hi=60, optional=True),
                                                   gain("F", lo=0, hi=1, optional=True), bool_arg("integral")]),
    Entry("control", "nominal_inertia", lambda: [_qs(), _p()]),
    Entry("control", "joint_inertia_spread", lambda: [_qs(), _payloads(), gain("B_bar", lo=0.5, hi=30, optional=True),
                                                      _p()]),
    Entry("control", "BoundedController", lambda: []),
    Entry("control", "RobustController.run", lambda: _run_args(), examples=EXPENSIVE_EXAMPLES,
          target=lambda: F.controllers()[2].run, scenario=lambda: _simulate_scenarios(2)),
    Entry("control", "AdaptiveController.run", lambda: _run_args(), examples=EXPENSIVE_EXAMPLES,
          target=lambda: F.controllers()[3].run, scenario=lambda: _simulate_scenarios(3)),
    Entry("control", "OperationalSpaceController.run", lambda: _run_args(), examples=EXPENSIVE_EXAMPLES,
          target=lambda: F.controllers()[4].run, scenario=lambda: _simulate_scenarios(4)),
    Entry("control", "control_summary", lambda: [_result_arg(), _controller_arg(optional=True),
                                                 scalar("settle", 0.01, 0.2, True), scalar("rest", 0.01, 0.2, True),
                                                 small_int("repeats", 1, 2)], examples=EXPENSIVE_EXAMPLES,
          scenario=lambda: _run_pairs(("controller", "result"), settle=0.1),
          # documented: step_cost is "NaN" when no controller is given
          documented_non_finite=("result['step_cost']",)),
    Entry("control", "chattering", lambda: [_result_arg()]),
    # what a helper reads of a run of another kind of controller: a ScaraError naming what it needs
    Entry("control", "recorded_signals", lambda: [_result_arg(), contract("names", ("payload_estimate",)),
                                                  contract("who", "a helper")]),
    Entry("control", "final_state", lambda: [_result_arg(), small_int("size", 0, 14, False), contract("who", "a helper")]),
    Entry("control", "law_cost", lambda: [_controller_arg(), _result_arg(), small_int("repeats", 1, 2)],
          examples=EXPENSIVE_EXAMPLES, scenario=lambda: _run_pairs(("controller", "result"))),
    Entry("control", "replay_law", lambda: [_controller_arg(), _result_arg(), small_int("n", 1, 300)],
          scenario=lambda: _run_pairs(("controller", "result"))),
    Entry("control", "adaptation_gains", lambda: [Arg("K_pi", st.sampled_from([0.5, {"m3": 0.5, "F1": 2.0},
                                                                               np.r_[1.0, np.full(12, np.inf)]]),
                                                      st.sampled_from(BAD_TYPES + BAD_FLOATS + (
                                                          {"nope": 1.0}, {"m3": -1.0}, np.full(13, np.inf),
                                                          np.ones(12), {"m3": np.nan})))],
          allow_inf=False),
    Entry("control", "sliding_weight", lambda: [gain("K_P", lo=100, hi=2000), gain("K_D", lo=40, hi=100),
                                                gain("Lambda", lo=1, hi=30)]),
    Entry("control", "lyapunov_matrix", lambda: [gain("K_P", lo=100, hi=2000), gain("K_D", lo=40, hi=100),
                                                 _p8()]),
    Entry("control", "sliding_matrix", lambda: [gain("K_P", lo=100, hi=2000), gain("K_D", lo=40, hi=100),
                                                _p8()]),
    Entry("control", "inertia_uncertainty", lambda: [gain("B_hat", lo=0.5, hi=20), _qs(), _payloads(), _p()]),
    Entry("control", "inertia_eigenvalues", lambda: [gain("B_hat", lo=0.5, hi=20), _qs(), _payloads(), _p()]),
    Entry("control", "design_inertia_estimate", lambda: [_qs(), _payloads(), _p()], examples=EXPENSIVE_EXAMPLES),
    Entry("control", "rho_bound", lambda: [scalar("alpha", 0, 0.99), scalar("qdd_max", 0, 100),
                                           scalar("eta0_max", 0, 100)]),
    # ---- identification ----------------------------------------------------------------------------------
    Entry("identification", "encoder_resolution", lambda: [integer("counts", 1, 2 ** 20, True),
                                                           scalar("quill", 1e-7, 1e-3, True)]),
    Entry("identification", "quantise", lambda: [vector("q", (3, 4), -3, 3), vector("resolution", 4, 1e-6, 1e-2, True)]),
    Entry("identification", "draw_arm", lambda: [
        integer("seed", 0, 10 ** 6), scalar("spread", 0, 0.5, True),
        Arg("payload", st.sampled_from([(0.0, 10.0), (1.0, 2.0)]),
            st.sampled_from(BAD_TYPES + BAD_FLOATS + ((2.0, 1.0), (-1.0, 2.0), (np.nan, 1.0), (1.0,))), True),
        F.params_arg("base")]),
    Entry("identification", "FourierExcitation", lambda: [vector("a", (4, 3)), vector("b", (4, 3)), q_arg("offset"),
                                                          scalar("period", 0.5, 20)]),
    Entry("identification", "FourierExcitation.at_rest", lambda: [
        vector("free", 16), q_arg("offset", True, -1, 1), scalar("period", 0.5, 20, True)],
          target=lambda: _mod("identification").FourierExcitation.at_rest),
    Entry("identification", "stacked_regressor", lambda: _ident_motion_args() + [_p()]),
    Entry("identification", "regressor_condition", lambda: _ident_motion_args() + [_p()], allow_inf=True),
    Entry("identification", "excitation_margins", lambda: _ident_motion_args() + [_p()]),
    # every argument given (the defaults search 200 samples for up to 200 iterations): a few iterations on a small
    # grid keep an example within the deadline
    Entry("identification", "optimise_excitation", lambda: [
        integer("harmonics", 2, 3), scalar("period", 2, 10), integer("seed", 0, 5), integer("grid", 12, 24),
        vector("offset", 4, valid=st.sampled_from([np.array([0.0, -1.5, 0.5, 0.0]), np.array([1.0, 1.0, 0.3, 2.0])])),
        integer("maxiter", 1, 3), _p()], examples=EXPENSIVE_EXAMPLES),
    Entry("identification", "torque_noise_std", lambda: [vector("tau", (6, 4), -100, 100),
                                                         scalar("fraction", 1e-4, 0.1, True)]),
    Entry("identification", "measure", lambda: [
        F.params_arg("arm", optional=False), vector("reference", (301, 12), valid=st.just(None).map(
            lambda _: _ident_reference())), integer("seed", 0, 100), scalar("noise", 1e-4, 0.1, True),
        vector("resolution", 4, 1e-6, 1e-2, True)], examples=EXPENSIVE_EXAMPLES),
    Entry("identification", "read_sensors", lambda: [
        _result_arg("run"), integer("seed", 0, 100), scalar("noise", 1e-4, 0.1, True),
        vector("resolution", 4, 1e-6, 1e-2, True), vector("sigma", 4, 1e-3, 1, True)]),
    Entry("identification", "lowpass", lambda: [vector("x", (60, 2)), scalar("cutoff", 0.5, 100), scalar("dt", 1e-3, 2e-3),
                                                integer("order", 1, 6, True)]),
    Entry("identification", "filtered_data", lambda: [
        vector("t", 3001, valid=st.just(np.arange(3001) * 1e-3)),
        vector("q", (3001, 4), valid=st.just(None).map(lambda _: _ident_measurement().q)),
        vector("tau", (3001, 4), valid=st.just(None).map(lambda _: _ident_measurement().tau)),
        scalar("cutoff", 5, 20, True), integer("order", 1, 6, True)]),
    Entry("identification", "least_squares", lambda: [
        vector("Y", (80, 13), valid=st.just(None).map(lambda _: _ident_system()[0])),
        vector("tau", 80, valid=st.just(None).map(lambda _: _ident_system()[1])),
        bool_arg("weighted"), scalar("confidence", 0.5, 0.99, True)]),
    Entry("identification", "base_parameters", lambda: [
        vector("Y", (80, 13), valid=st.just(None).map(lambda _: _ident_system()[0])), scalar("rtol", 1e-14, 1e-3, True)]),
    Entry("identification", "identify", lambda: [
        fixed("measurement", st.just(None).map(lambda _: _ident_measurement())), scalar("cutoff", 5, 20, True),
        bool_arg("weighted"), scalar("confidence", 0.5, 0.99, True), _p()]),
    Entry("identification", "predicted_torques", lambda: _ident_motion_args() + [pi_arg(), _p()]),
    # ---- gains, params, errors ---------------------------------------------------------------------------
    Entry("gains", "gain_vector", lambda: [
        gain("value"), contract("name", "K"), contract("n", 4), contract("default", None),
        contract("rule", "positive"), contract("labels", ("x", "y", "z", "phi")), contract("allow_inf", False)]),
    Entry("params", "ScaraParams", lambda: _scara_params_args()),
    Entry("params", "ScaraParams.with_payload", lambda: [scalar("m_L", 0, 20)],
          target=lambda: scara.ScaraParams().with_payload),
    # the checks of scara.errors: only the checked value is hostile; the caller's own arguments (a name for the
    # message, the expected shape, the bounds) are contract arguments, always valid
    Entry("errors", "as_array", lambda: [vector("value", 4), contract("name", "v"), contract("trailing", (4,)),
                                         contract("allow_batch", True)]),
    Entry("errors", "as_vector", lambda: [vector("value", 4), contract("name", "v"), contract("n", 4)]),
    Entry("errors", "check_number", lambda: [scalar("value", -1e3, 1e3), contract("name", "v"),
                                             contract("what", "a number")]),
    Entry("errors", "check_positive", lambda: [scalar("value", 1e-3, 1e3), contract("name", "v"),
                                               contract("strict", True)]),
    Entry("errors", "check_count", lambda: [integer("value", 0, 10), contract("name", "n"), contract("low", 0),
                                            contract("high", 10), contract("what", "samples")]),
    Entry("errors", "check_flag", lambda: [bool_arg("value", False), contract("name", "f")]),
    Entry("errors", "is_bool", lambda: [bool_arg("value", False)]),
    Entry("errors", "check_index", lambda: [integer("value", 0, 3), contract("name", "i"), contract("size", 4)]),
    # check_angles takes an array already checked finite by as_array: hostile = large angles, other batch shapes
    Entry("errors", "check_angles", lambda: [
        Arg("q", _arrays_of(4, -10, 10), st.sampled_from([np.array([1e7, 0, 0, 0]), np.array([0, -1e300, 0, 0]),
                                                           np.array([0, 0, 1e300, 1e300]), np.full((3, 4), 2e6),
                                                           np.zeros((0, 4)), np.array([0, 0, 0, np.inf])])),
        contract("name", "q"), contract("columns", (0, 1, 3))]),
    Entry("errors", "check_finite_result", lambda: [
        Arg("result", _arrays_of(4, -1, 1), st.sampled_from([np.array([np.nan, 0, 0, 0]), np.full((2, 4), np.inf),
                                                             np.array(-np.inf), np.zeros(0), 1e300 * np.ones(3)])),
        contract("what", "x"), contract("q", np.array([1e300, 0.0, 0.0, 0.0]))]),
    # ---- interaction -------------------------------------------------------------------------------------
    Entry("interaction", "Surface", lambda: [
        scalar("height", 0.1, 0.5, True), scalar("stiffness", 1e3, 1e5, True), scalar("damping", 0, 100, True),
        scalar("friction", 0, 1, True), scalar("v_s", 1e-4, 1e-2, True), _hole_arg()]),
    Entry("interaction", "Hole", lambda: [vector("centre", 2, 0.3, 0.5, True), scalar("clearance", 1e-4, 1e-3, True),
                                          scalar("depth", 0.01, 0.05, True), scalar("wall_stiffness", 1e5, 1e7, True)]),
    Entry("interaction", "ForceSensor", lambda: [scalar("noise", 0, 1, True), vector("bias", 3, -1, 1, True),
                                                 integer("seed", 0, 100, True)]),
    Entry("interaction", "contact_force", lambda: [vector("position", 3, 0.28, 0.42), vector("velocity", 3, -1, 1),
                                                   _surface_arg(), bool_arg("inside")]),
    Entry("interaction", "wrench_torque", lambda: [q_arg(), vector("force", 3, -50, 50), _p()]),
    Entry("interaction", "sensor_coupling", lambda: [vector("bias", 3, -1, 1), q_arg(), _p()]),
    Entry("interaction", "ComplianceController", lambda: [
        gain("K_P", lo=100, hi=5000, optional=True), gain("K_D", lo=10, hi=600, optional=True), F.params_arg("model"),
        gain("tau_max", lo=10, hi=1000, optional=True), scalar("max_error", 0.01, 0.1, True)]),
    Entry("interaction", "ImpedanceController", lambda: [
        gain("M_d", lo=1, hi=20, optional=True), gain("K_D", lo=10, hi=600, optional=True),
        gain("K_P", lo=100, hi=5000, optional=True), F.params_arg("model")]),
    Entry("interaction", "AdmittanceController", lambda: [
        gain("M_d", lo=1, hi=20, optional=True), gain("K_Dd", lo=10, hi=900, optional=True),
        gain("K_Pd", lo=100, hi=5000, optional=True), gain("K_P", lo=100, hi=5000, optional=True),
        gain("K_D", lo=10, hi=140, optional=True), F.params_arg("model")]),
    Entry("interaction", "ForceController", lambda: [
        vector("f_d", 3, -20, 0, True), gain("K_P", lo=100, hi=2500, optional=True),
        gain("K_D", lo=10, hi=70, optional=True), gain("K_F", 3, lo=1e-6, hi=1e-4, optional=True),
        gain("K_I", 3, lo=1e-4, hi=1e-2, optional=True), F.params_arg("model")]),
    Entry("interaction", "ParallelController", lambda: [
        scalar("f_d", -20, 0, True), gain("K_P", lo=100, hi=2500, optional=True),
        gain("K_D", lo=10, hi=70, optional=True), scalar("K_F", 1e-6, 1e-4, True), scalar("K_I", 1e-4, 1e-2, True),
        F.params_arg("model")]),
    Entry("interaction", "simulate_contact", lambda: [
        _contact_controller_arg(), F.traj_arg(), F.params_arg("plant"), _surface_arg(), _sensor_arg(),
        q_arg("q0", optional=True, lo=-1, hi=1), small_int("substeps", 1, 3), elbow_arg()],
          examples=EXPENSIVE_EXAMPLES),
    Entry("interaction", "elastic_equilibrium", lambda: [gain("K_P", lo=100, hi=1e4), pose_arg("x_d"), _surface_arg(),
                                                         vector("offset", 4, -1, 1, True)]),
    Entry("interaction", "force_equilibrium", lambda: [scalar("f_d", -50, -1), _surface_arg(), _sensor_arg()]),
    Entry("interaction", "parallel_equilibrium", lambda: [pose_arg("x_d"), scalar("f_d", -50, -1), _surface_arg(),
                                                          _sensor_arg()]),
    Entry("interaction", "law_equilibrium", lambda: [_contact_controller_arg(laws=(0, 1, 2, 4)), pose_arg("x_d"),
                                                     _surface_arg(), _sensor_arg(), _p(), elbow_arg()]),
    Entry("interaction", "contact_transition", lambda: [_contact_result_arg()],
          documented_non_finite=("result['first_touch']",)),  # documented: NaN when the tool never touched
    Entry("interaction", "approach_reference", lambda: [
        pose_arg("start"), pose_arg("target"), scalar("move", 0, 0, True, valid=st.sampled_from([0.05, 0.1])),
        scalar("hold", 0, 0, True, valid=st.sampled_from([0.0, 0.05])), contract("dt", 1e-3)]),
    Entry("interaction", "pressing_target", lambda: [_contact_controller_arg(), pose_arg("start"), _surface_arg(),
                                                     scalar("force", 1, 50, True)]),
    Entry("interaction", "approach_run", lambda: [
        _contact_controller_arg(), _surface_arg(), _sensor_arg(), vector("at", 2, 0.3, 0.5, True),
        scalar("lift", 1e-3, 5e-3, True), scalar("force", 1, 20, True),
        scalar("move", 0, 0, True, valid=st.sampled_from([0.1, 0.2])),
        scalar("hold", 0, 0, True, valid=st.sampled_from([0.0, 0.05])), small_int("substeps", 1, 3)],
          examples=EXPENSIVE_EXAMPLES),
    Entry("interaction", "peg_in_hole", lambda: [
        vector("offset", 2, -2e-3, 2e-3, True), scalar("lift", 1e-3, 5e-3, True), _peg_surface_arg(),
        scalar("move", 0, 0, True, valid=st.sampled_from([0.1, 0.2])),
        scalar("pause", 0, 0, True, valid=st.sampled_from([0.0, 0.1])),
        scalar("rest", 0, 0, True, valid=st.sampled_from([0.1])), _sensor_arg(), small_int("substeps", 1, 3)],
          examples=EXPENSIVE_EXAMPLES),
    Entry("interaction", "insertion_summary", lambda: [_peg_result_arg()],
          # documented: NaN when the peg never entered the hole, or never reached the bottom
          documented_non_finite=("result['entered']", "result['bottom_reached']")),
    Entry("interaction", "peg_frames", lambda: [_peg_result_arg(), small_int("every", 1, 100),
                                                scalar("peg_radius", 1e-3, 1e-2, True),
                                                scalar("peg_length", 1e-2, 0.1, True)]),
    Entry("interaction", "settling_time", lambda: [_contact_result_arg(), scalar("band", 0.01, 0.5, True),
                                                   scalar("window", 0.01, 0.1, True)]),
    Entry("interaction", "law_comparison", lambda: [
        Arg("runs", st.just(3).map(lambda i: {"run": _contact_objects()[i]}),
            st.one_of(st.deferred(F.bad_results), st.sampled_from(BAD_TYPES + ({},)))),
        scalar("force", 1, 20, True), scalar("window", 0.01, 0.1, True), scalar("band", 0.01, 0.5, True)]),
    Entry("interaction", "stiffness_sweep", lambda: [
        vector("gains", 1, 1e3, 2e4), vector("stiffnesses", 1, 1e3, 1e5), scalar("depth", 1e-4, 3e-3, True),
        scalar("move", 0, 0, True, valid=st.sampled_from([0.1, 0.2])),
        scalar("hold", 0, 0, True, valid=st.sampled_from([0.05, 0.1])), small_int("points", 2, 50)],
          examples=EXPENSIVE_EXAMPLES),
    Entry("interaction", "force_loop_poly", lambda: [_contact_controller_arg(laws=(3,)), _surface_arg()]),
    Entry("interaction", "force_loop_bounds", lambda: [_contact_controller_arg(laws=(3,)), _surface_arg(),
                                                       scalar("dt", 5e-4, 2e-3, True)]),
]


# ---- the interaction chapter's shared objects ----------------------------------------------------------
@functools.lru_cache(maxsize=None)
def _contact_objects():
    I = _mod("interaction")
    surfaces = (None, fz.label(I.Surface(), "Surface()"), fz.label(I.Surface(hole=I.Hole()), "Surface(hole=Hole())"))
    sensors = (None, fz.label(I.ForceSensor(noise=0.0), "ForceSensor(noise=0)"))
    laws = tuple(fz.label(c(), f"<{c.__name__}()>") for c in (
        I.ComplianceController, I.ImpedanceController, I.AdmittanceController, I.ForceController,
        I.ParallelController))
    q = scara.ikine([0.4, 0.1, 0.305, 0.0], elbow=-1)
    start = np.array([0.4, 0.1, 0.305, q[0] + q[1]])
    ref = I.approach_reference(start, start - [0.0, 0.0, 0.01, 0.0], 0.2, 0.1)
    run = fz.label(I.simulate_contact(laws[0], ref, surface=surfaces[1]), "<compliance run onto Surface()>")
    peg = fz.label(I.peg_in_hole(move=0.2, pause=0.0, rest=0.2), "<peg_in_hole, 0.4 s>")
    return surfaces, sensors, laws, run, peg


def _hole_arg():
    return Arg("hole", st.just(None).map(lambda _: _mod("interaction").Hole()),
               st.sampled_from(BAD_TYPES[:4] + BAD_FLOATS[:3]), True)


def _surface_arg(name="surface"):
    return Arg(name, st.sampled_from(range(3)).map(lambda i: _contact_objects()[0][i]),
               st.sampled_from(BAD_TYPES + BAD_FLOATS[:3]), True)


def _peg_surface_arg():
    return Arg("surface", st.just(2).map(lambda i: _contact_objects()[0][i]),
               st.sampled_from(BAD_TYPES + BAD_FLOATS[:3] + ("surface without a hole",)).map(
                   lambda v: _contact_objects()[0][1] if isinstance(v, str) and v == "surface without a hole" else v),
               True)


def _sensor_arg():
    return Arg("sensor", st.sampled_from(range(2)).map(lambda i: _contact_objects()[1][i]),
               st.sampled_from(BAD_TYPES + BAD_FLOATS[:3]), True)


def _contact_controller_arg(name="controller", laws=(0, 1, 2, 3, 4)):
    return Arg(name, st.sampled_from(laws).map(lambda i: _contact_objects()[2][i]),
               st.sampled_from(BAD_TYPES + BAD_FLOATS[:3]))


def _contact_result_arg():
    return Arg("result", st.just(3).map(lambda i: _contact_objects()[i]), st.deferred(F.bad_results))


def _peg_result_arg():
    return Arg("result", st.just(4).map(lambda i: _contact_objects()[i]),
               st.one_of(st.deferred(F.bad_results), st.just(3).map(lambda i: _contact_objects()[i])))


def _arrays_of(n, lo, hi):
    return st.lists(st.floats(lo, hi), min_size=n, max_size=n).map(np.array)


def _rows():
    return Arg("rows", st.sampled_from([(0, 1, 2), (0, 1), (0, 1, 2, 3), [2]]),
               st.sampled_from(BAD_TYPES + BAD_FLOATS + ((0, 7), (-1,), (0, 0), (0.5,), ("x",), ())), True)


def _arc_args():
    @st.composite
    def arc(draw):
        c = np.array([draw(st.floats(-0.5, 0.5)), draw(st.floats(-0.5, 0.5)), draw(st.floats(0, 1))])
        r = draw(st.floats(0.01, 0.3))
        a0, a1 = draw(st.floats(0, 3)), draw(st.floats(3.2, 6))
        pt = lambda a: c + r * np.array([np.cos(a), np.sin(a), 0.0])  # noqa: E731
        return c, pt(a0), pt(a1)

    arcs = arc()
    return [vector("centre", 3, valid=arcs.map(lambda a: a[0])), vector("start", 3, valid=st.none()),
            vector("end", 3, valid=st.none()),
            vector("normal", 3, optional=True, valid=st.just(np.array([0.0, 0.0, 1.0]))),
            scalar("radius", 0, 0, True, valid=st.none())], arcs


def _trapezoidal_args(blend_optional=False):
    return [scalar("length", 1e-3, 2), scalar("duration", 0.1, 10), scalar("blend", 0.01, 0.05, blend_optional)]


def _q0_arg():
    """The start configuration: valid = None (the start configuration of the reference); hostile as any q."""
    return Arg("q0", st.none(), q_arg("q0").hostile, optional=True)  # includes SPECIAL_Q


def _clik_args():
    return [F.traj_arg(), choice("method", ("inverse", "transpose", "pseudoinverse"), True), gain("K", optional=True),
            _q0_arg(), _p(), scalar("damping", 0, 0.05, True),
            scalar("damping_threshold", 1e-3, 0.1, True),
            Arg("relaxed", st.sampled_from([None, "x", 3]), st.sampled_from(["w", 4, -1, 1.5, np.nan, [0], {}]), True),
            scalar("k0", 0, 20, True), choice("objective", ("sin2", "manipulability"), True),
            scalar("max_error", 0.01, 1, True), bool_arg("check_stability")]


def _clik2_args():
    return [F.traj_arg(), gain("K_P", lo=1e3, hi=1e5, optional=True), gain("K_D", lo=100, hi=500, optional=True),
            _q0_arg(), q_arg("qd0", optional=True, lo=-0.1, hi=0.1), _p(),
            scalar("damping", 0, 0.05, True), scalar("damping_threshold", 1e-3, 0.1, True),
            scalar("max_error", 0.01, 1, True), bool_arg("check_stability")]


def _controller_arg(name="controller", optional=False):
    return Arg(name, st.sampled_from(range(6)).map(lambda i: F.controllers()[i]),
               st.sampled_from(BAD_TYPES + BAD_FLOATS[:3]), optional)


def _result_arg(name="result"):
    return Arg(name, st.sampled_from(range(6)).map(lambda i: F.runs()[i][1]), st.deferred(F.bad_results))


def _simulate_args():
    def setpoint(d):
        return fz.label(_mod("_simulate").joint_setpoint(np.array([0.3, 1.0, 0.4, 0.0]), d),
                        f"<joint_setpoint([0.3, 1, 0.4, 0], {d})>")

    bad_jref = st.sampled_from(BAD_TYPES + BAD_FLOATS + (np.zeros((10, 4)), np.full((10, 12), np.nan),
                                                         (np.zeros((5, 4)), np.zeros((4, 4)), np.zeros((5, 4))),
                                                         np.zeros((0, 12))))
    return [_controller_arg(), F.traj_arg(optional=True), F.params_arg("plant"),
            scalar("dt", 0, 0, True, valid=st.sampled_from([1e-3])),
            Arg("joint_reference", st.sampled_from([0.1, 0.3]).map(setpoint), bad_jref, True),
            q_arg("q0", optional=True, lo=-1, hi=1), q_arg("qd0", optional=True, lo=-0.1, hi=0.1),
            small_int("substeps", 1, 3), scalar("duration", 0.05, 0.3, True), elbow_arg(),
            scalar("limit", 1e3, 1e7, True)]


def _simulate_scenarios(fixed_controller):
    """Coherent valid runs: a trajectory; a joint set point from its own start; an open loop of 0.1 s."""
    q_set = np.array([0.3, 1.0, 0.4, 0.0])
    setpoint = _mod("_simulate").joint_setpoint(q_set, 0.1)
    fz.label(setpoint, "<joint_setpoint([0.3, 1, 0.4, 0], 0.1)>")
    payload = fz.label(scara.ScaraParams().with_payload(5.0), "ScaraParams().with_payload(5.0)")

    def build(args):
        i, kind, plant, substeps = args
        i = fixed_controller if fixed_controller is not None else i
        c = F.controllers()[i]
        kw = {} if fixed_controller is not None else {"controller": c}
        if kind == "traj" or (kind == "setpoint" and c.reference_kind != "joint"):
            kw["traj"] = F.trajs()[i % 2]
        elif kind == "setpoint":
            kw.update(joint_reference=setpoint, q0=q_set)
        else:
            kw.update(duration=0.1, q0=q_set) if c.reference_kind == "none" else kw.update(traj=F.trajs()[0])
        if plant:
            kw["plant"] = payload
        if substeps > 1:
            kw["substeps"] = substeps
        return kw

    return st.tuples(st.integers(0, 5), st.sampled_from(["traj", "setpoint", "open"]), st.booleans(),
                     st.integers(1, 2)).map(build)


def _run_pairs(names, **extra):
    """A controller and the run it made (law_cost, replay_law, control_summary)."""
    def build(i):
        c, res = F.runs()[i]
        return {names[0]: c, names[1]: res, **extra}
    return st.integers(0, 5).map(build)


def _run_args():
    a = _simulate_args()
    return a[1:3] + a[4:]  # no controller; dt only through the trajectory


def _p8():
    return Arg("P", st.sampled_from([np.eye(8), np.diag(np.arange(1.0, 9.0))]),
               st.sampled_from(BAD_TYPES + BAD_FLOATS + (-np.eye(8), np.eye(4), np.full((8, 8), np.nan),
                                                         np.triu(np.ones((8, 8))), np.zeros((8, 8)),
                                                         np.eye(8) * 1e300, np.eye(8) * 1e-300)))


#: three configurations within the joint limits, for the joint-space trajectories
JOINT_POINTS = np.array([[0.0, 1.0, 0.3, 0.0], [0.2, 0.8, 0.35, 0.1], [0.4, 0.5, 0.3, 0.2]])


def _joint_counterpart_arg():
    """The joint-space counterpart of the first short trajectory (a valid ``jt`` for its path deviations)."""
    return fixed("jt", st.just(None).map(lambda _: _mod("trajectory").joint_counterpart(F.trajs()[0])))


def _qs():
    return vector("q", (3, 4), -2, 2, valid=st.sampled_from([np.array([[0.1, 1.0, 0.3, 0.0]]),
                                                              np.array([[0.1, 1.0, 0.3, 0.0], [0.5, -1.5, 0.5, 1.0]]),
                                                              np.array([0.1, 2.0, 0.3, 0.0])]))


def _payloads():
    return Arg("payloads", st.sampled_from([(0.0, 10.0), (5.0,), 2.0]),
               st.sampled_from(BAD_TYPES + BAD_FLOATS + ((-1.0, 2.0), (np.nan,), ((1.0, 2.0), (3.0,)))), True)


def _scara_params_args():
    fields = {"d0": (0.5, 2), "a1": (0.2, 1), "a2": (0.2, 1), "l1": (0.05, 0.2), "l2": (0.05, 0.2),
              "m_l1": (1, 30), "m_l2": (1, 30), "m_l3": (1, 20), "I_l1": (0.1, 5), "I_l2": (0.1, 5),
              "I_l4": (0.1, 2), "m_L": (0, 10), "g0": (0, 10)}
    args = [scalar(k, lo, hi, True) for k, (lo, hi) in fields.items()]
    args += [vector("k_r", 4, 1, 50, True), vector("I_m", 4, 1e-3, 1e-2, True), vector("F_m", 4, 0, 1e-2, True)]
    args += [scalar("d3_min", 0, 0.1, True), scalar("d3_max", 0.5, 1, True)]
    return args



# --------------------------------------------------------------------------------------------------
# valid objects of the identification entries (built once, on first use)
# --------------------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=None)
def _ident_excitation():
    """A small exciting motion: three harmonics, a period of 3 s, starting at rest."""
    I = _mod("identification")
    free = np.random.default_rng(0).standard_normal(16) * 0.05
    return fz.label(I.FourierExcitation.at_rest(free, period=3.0), "<FourierExcitation 3 s>")


def _ident_reference():
    return _ident_excitation().reference(1)[:301]


@functools.lru_cache(maxsize=None)
def _ident_measurement():
    """A 3 s measurement of the arm carrying 5 kg along the small excitation (3001 samples)."""
    I = _mod("identification")
    m = I.measure(scara.ScaraParams().with_payload(5.0), _ident_excitation().reference(1), seed=0)
    return fz.label(m, "<measure 3 s>")


@functools.lru_cache(maxsize=None)
def _ident_system():
    """A stacked regressor (80, 13) of 20 samples of the small excitation and its exact torques."""
    I = _mod("identification")
    q, qd, qdd = _ident_excitation().motion(np.linspace(0.1, 2.9, 20))
    Y = I.stacked_regressor(q, qd, qdd)
    return Y, Y @ _mod("dynamics").dynamic_parameters(scara.ScaraParams().with_payload(5.0))


def _ident_motion_args():
    """q, qd, qdd (5, 4) of the small excitation (hostile: wrong shapes, NaN, strings...)."""
    valid = [st.just(None).map(lambda _, k=k: _ident_excitation().motion(np.linspace(0.2, 2.8, 5))[k]) for k in range(3)]
    return [vector(name, (5, 4), valid=v) for name, v in zip(("q", "qd", "qdd"), valid)]


def _table():
    return {e.key: e for e in TABLE}


# --------------------------------------------------------------------------------------------------
# names that are not fuzzed, and why
# --------------------------------------------------------------------------------------------------
#: Public callables that are not numeric entry points. Constants, sub-modules and other non-callable public
#: names (``PI_NAMES``, ``TAU_MAX``, ``scara.dynamics``...) are skipped by ``_public_callables`` itself.
NOT_FUZZED = {
    # exception classes
    "ScaraError", "ShapeError", "NonFiniteError", "UnreachableError", "UnstableError",
    # result containers: dataclasses/classes the package fills (their fields are checked through the callables
    # that return them); Trajectory is built by plan_path (its constructor takes the planner's private _built)
    "Ellipsoid", "ClikResult", "TransposeStability", "SimulationResult", "Trajectory", "ContactResult",
    # built by cubic, quintic and joint_trajectory (its constructor takes their solved coefficients)
    "JointTrajectory",
    # named-tuple records of the compiled kernels' constants (built by geometry(), lumped_parameters...)
    "Geometry", "LumpedParameters", "InertiaParts",
    # raw numba kernels: no input checks by design (they write into caller-given buffers); the checked wrappers
    # above (fkine, inertia, simulate...) are what the fuzz test calls
    "pose_kernel", "pose_of", "jacobian_kernel", "jacobian_dot_kernel", "ikine_kernel", "planar_trig", "planar_position",
    "planar_jacobian", "planar_jacobian_at", "planar_det", "planar_jacobian_dot", "elbow_cosine",
    "manipulability_kernel", "inertia_kernel", "coriolis_kernel", "coriolis_vector_kernel", "gravity_kernel",
    "friction_kernel", "inverse_dynamics_kernel", "bias_kernel", "forward_dynamics_kernel", "regressor_kernel",
    "pi_kernel", "lumped_parameters", "inertia_parts", "kinetic_energy_kernel", "potential_energy_kernel",
    "cholesky_solve4", "closed_loop_kernel", "tool_motion_kernel", "reach_kernel",
    "critical_gains", "sampling_limit", "computed_torque_steady_state",
    # the decorator that compiles a user's control law (takes a Python function, not numbers)
    "control_law",
    # the chapter-6 name of scara.gains.gain_vector (the same function, fuzzed under that name)
    "positive_gains",
    # the identification's result containers (filled by optimise_excitation, measure, filtered_data, least_squares,
    # base_parameters, which are fuzzed)
    "ExcitationDesign", "Measurement", "FilteredData", "Estimate", "BaseParameters",
    # the book's excitation design: no argument to fuzz (its checks are optimise_excitation's, which is fuzzed)
    "book_design",
}


def _public_callables():
    """``{name: (module, object)}`` of the public callables of ``scara.__all__`` and of the sub-modules'
    ``__all__`` (modules and non-callable constants left out)."""
    out = {}
    sources = [("scara", scara, scara.__all__)] + [(m, _mod(m), _mod(m).__all__) for m in MODULES]
    for modname, mod, names in sources:
        for name in names:
            obj = getattr(mod, name)
            if isinstance(obj, types.ModuleType) or not callable(obj):
                continue
            out.setdefault(name, (modname, obj))
    return out


def test_table_covers_public_names():
    """Every public callable has an entry in TABLE or a reason in NOT_FUZZED; no entry names a missing
    callable."""
    public = _public_callables()
    covered = {e.name for e in TABLE if "." not in e.name}
    missing = sorted(set(public) - covered - NOT_FUZZED)
    assert not missing, f"public callables with no fuzz entry (add them to TABLE or NOT_FUZZED): {missing}"
    stale = sorted((covered | NOT_FUZZED) - set(public))
    assert not stale, f"TABLE/NOT_FUZZED name callables that are not public any more: {stale}"
    both = sorted(covered & NOT_FUZZED)
    assert not both, f"names both fuzzed and excluded: {both}"
    for e in TABLE:  # each entry resolves to the public object of its module
        if "." not in e.name:
            assert getattr(_mod(e.module), e.name) is public[e.name][1], e.key


# --------------------------------------------------------------------------------------------------
# the fuzz test
# --------------------------------------------------------------------------------------------------
#: per callable: how the examples ended (returned / raised ScaraError, with all-valid or hostile arguments)
STATS: dict = collections.defaultdict(collections.Counter)


class HangError(Exception):
    """An example ran longer than TIMEOUT_S."""


def _on_alarm(signum, frame):
    raise HangError(f"no answer after {TIMEOUT_S:g} s")


def _log(record):
    with open(LOG, "a") as fh:
        fh.write(json.dumps(record) + "\n")


def _where(exc):
    tb = traceback.extract_tb(exc.__traceback__)
    frames = [f for f in tb if "/scara/" in f.filename] or tb
    f = frames[-1]
    return f"{f.filename.split('/scara/')[-1] if '/scara/' in f.filename else f.filename}:{f.lineno} ({f.name})"


def _check_call(entry, fn, kwargs, hostile, timeout):
    """Call ``fn(**kwargs)``; return None or a failure description."""
    old = signal.signal(signal.SIGALRM, _on_alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    # SIGALRM's handler runs only between Python bytecodes: a loop inside a compiled kernel would not see it.
    # The backstop ends the whole process (with every thread's traceback) so that such a hang cannot block CI.
    faulthandler.dump_traceback_later(HARD_TIMEOUT_FACTOR * timeout, exit=True)
    owned = fz.Ownership(kwargs) if entry.module != "errors" else None  # the checks hand back what they checked
    try:
        try:
            result = fn(**kwargs)
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, old)
            faulthandler.cancel_dump_traceback_later()
    except scara.ScaraError as exc:
        STATS[entry.key]["scara_error" if hostile else "valid_scara_error"] += 1
        if LOG and not hostile:  # a valid call the package refuses: worth a look (an over-strict check?)
            _log(dict(kind="valid_refused", key=entry.key, exc=type(exc).__name__, msg=str(exc)[:300],
                      call=fz.show_call(entry.name, kwargs)))
        return None
    except HangError as exc:
        return dict(kind="hang", exc="HangError", msg=str(exc), where=_where(exc))
    except Exception as exc:  # noqa: BLE001 - the point of the test
        return dict(kind="exception", exc=type(exc).__name__, msg=str(exc)[:400], where=_where(exc))
    bad = fz.non_finite(result, allow_inf=entry.allow_inf, skip=entry.documented_non_finite)
    if bad:
        return dict(kind="non-finite", exc="-", msg=bad, where="-")
    shared = owned.problem(result) if owned is not None else None
    if shared:
        return dict(kind="shared memory", exc="-", msg=shared, where="-")
    STATS[entry.key]["returned" if hostile else "valid_returned"] += 1
    return None


def _run(entry, examples, deadline, valid_only, timeout, quiet=False):
    fn = entry.resolve()
    built = entry.args()
    linked = None
    if isinstance(built, tuple):  # (args, a strategy of linked valid values: plan_path, Arc)
        built, linked = built
    args = built
    scenario = entry.scenario() if entry.scenario is not None else None

    @settings(max_examples=examples, deadline=deadline, derandomize=True, database=None,
              suppress_health_check=list(HealthCheck), phases=[Phase.generate, Phase.shrink] if not valid_only
              else [Phase.generate], print_blob=False, verbosity=Verbosity.quiet)  # the message names the call
    @given(st.data())
    def one(data):
        kwargs, hostile = fz.arguments(data.draw, args, 0 if valid_only else entry.mutate_max)
        if entry.scenario is not None:
            base = data.draw(scenario, label="valid scenario")
            kwargs = {**base, **{k: kwargs[k] for k in hostile}}
        if linked is not None:
            _fill_linked(entry, data, linked, kwargs, hostile)
        failure = _check_call(entry, fn, kwargs, hostile, timeout)
        if failure and quiet:
            return
        if failure:
            STATS[entry.key]["failed"] += 1
            call = fz.show_call(entry.name, kwargs)
            if LOG:
                _log(dict(key=entry.key, call=call, hostile=hostile, **failure))
                return
            raise AssertionError(f"{entry.key}: {failure['kind']} {failure['exc']}: {failure['msg']}\n"
                                 f"  at {failure['where']}\n  call: {call}")

    one()


def _fill_linked(entry, data, linked, kwargs, hostile):
    """Arguments whose valid values depend on each other (a plan's waypoints and durations; an arc's points)."""
    values = data.draw(linked, label="linked")
    if entry.name == "plan_path":
        wps, durs = values
        if "waypoints" not in hostile:
            kwargs["waypoints"] = wps
        if "durations" not in hostile:
            n = len(kwargs["waypoints"]) if "waypoints" not in hostile else len(wps)
            kwargs["durations"] = durs if len(durs) == n - 1 else [0.1] * (n - 1)
    elif entry.name == "Arc":
        c, s, e = values
        for k, v in (("centre", c), ("start", s), ("end", e)):
            if k not in hostile:
                kwargs[k] = v
        if "radius" not in hostile:
            kwargs.pop("radius", None)


#: Fixed hostile calls: the minimal inputs of failures the fuzz test found (kept as regression probes, also after
#: the fix), and special inputs a random draw reaches rarely. ``(table key, function returning the kwargs)``.
PROBES = [
    ("trajectory:plan_path", lambda: dict(waypoints=[(0.5, 0.3, 0.5), (0.45, 0.35, 0.5)], durations=[0.1],
                                          blends=0.02)),
    ("trajectory:plan_path", lambda: dict(waypoints=[(0.5, 0.3, 0.5), (0.45, 0.35, 0.5)], durations=[0.1],
                                          phi={"a": 1.0})),
    ("trajectory:Line", lambda: dict(start=np.array([1e300, 0.0, 0.0]), end=np.zeros(3))),
    ("trajectory:Arc", lambda: dict(centre=[0.5, 0.3, 0.5], start=[0.6, 0.3, 0.5], end=[0.4, 0.3, 0.5], radius="")),
    ("dynamics:params_from_pi", lambda: dict(pi=_mod("dynamics").dynamic_parameters(), rtol={})),
    ("dynamics:params_from_pi", lambda: dict(pi=_mod("dynamics").dynamic_parameters(), rtol=np.array([]))),
    ("_clik:second_order_gains", lambda: dict(K=np.array([1e300, 2.0, 2.0, 2.0]))),
    ("_clik:transpose_stability", lambda: dict(traj=F.trajs()[1], K=1e300)),
    ("_clik:start_configuration", lambda: dict(traj=types.SimpleNamespace(t=np.zeros(0), x=np.zeros(0), xd=np.zeros(0),
                                                                           xdd=np.zeros(0), dt=1e-3, elbow=-1))),
    ("control:design_inertia_estimate", lambda: dict(q=np.array([]), payloads=(5.0,))),
    ("control:design_inertia_estimate", lambda: dict(q=np.zeros((0, 4)), payloads=(5.0,))),  # an empty batch
    ("control:inertia_uncertainty", lambda: dict(B_hat=1.0, q=np.zeros((0, 4)))),
    ("control:inertia_eigenvalues", lambda: dict(B_hat=1.0, q=np.zeros((0, 4)))),
    ("dynamics:inertia", lambda: dict(q=np.zeros((0, 4)))),
    ("_clik:dexterity", lambda: dict(q=np.zeros((0, 4)))),
    ("kinematics:ikine", lambda: dict(x=np.zeros((0, 4)))),
    ("trajectory:Arc", lambda: dict(centre=[0.5, 0.3, 0.5], start=[0.6, 0.3, 0.5], end=[0.4, 0.3, 0.5],
                                    radius=np.array([]))),
    ("trajectory:plan_path", lambda: dict(waypoints=[(0.5, 0.3, 0.5), (0.45, 0.35, 0.5)], durations=[0.1],
                                          arcs=True)),
    ("control:OperationalSpaceController.run", lambda: dict(traj=F.trajs()[0], q0=np.zeros(4))),
    ("control:OperationalSpaceController.run", lambda: dict(traj=F.trajs()[0], q0=np.array([0.3, 0.0, 0.5, 0.0]))),
    ("_simulate:simulate", lambda: dict(controller=F.controllers()[4], traj=F.trajs()[0], q0=np.zeros(4))),
    ("_simulate:simulate", lambda: dict(controller=F.controllers()[0], traj=F.trajs()[0], q0=np.zeros(4))),
    ("_simulate:ikine_reference", lambda: dict(traj=types.SimpleNamespace())),
    ("control:chattering", lambda: dict(result=types.SimpleNamespace(tau=np.array([[np.nan] * 4] * 4)))),
    ("control:chattering", lambda: dict(result=[])),
    ("control:control_summary", lambda: dict(result=_nan_tau_run(), settle=0.1)),
    ("control:law_cost", lambda: dict(controller="abc", result=F.runs()[0][1])),
    ("control:replay_law", lambda: dict(controller=F.controllers()[0], result=["a", "b"])),
    ("control:control_summary", lambda: dict(result=F.runs()[0][1], controller="abc", settle=0.1)),
    ("control:inertia_uncertainty", lambda: dict(B_hat=1.0, q=np.array([[0.1, 1.0, 0.3, 0.0]]), payloads="abc")),
    ("control:inertia_eigenvalues", lambda: dict(B_hat=1.0, q=np.array([[0.1, 1.0, 0.3, 0.0]]), payloads={})),
    ("control:design_inertia_estimate", lambda: dict(q=np.array([[0.1, 1.0, 0.3, 0.0]]), payloads=np.array([]))),
    ("params:ScaraParams", lambda: dict(m_l1=["a", "b", "c", "d"])),
    ("params:ScaraParams.with_payload", lambda: dict(m_L=["a", "b"])),
    ("control:RobustController.run", lambda: dict(traj=1 + 2j)),
    ("_manipulability:velocity_ellipsoid", lambda: dict(q=np.zeros(4))),
    ("kinematics:ikine", lambda: dict(x=np.array([1.0, 0.0, 0.5, 0.0]))),
    ("kinematics:ikine", lambda: dict(x=np.array([0.0, 0.0, 0.5, 0.0]))),
    ("dynamics:forward_dynamics", lambda: dict(q=np.zeros(4), qd=np.full(4, 1e200), tau=np.zeros(4))),
    ("dynamics:coriolis", lambda: dict(q=np.zeros(4), qd=np.full(4, 1e200))),
    ("dynamics:kinetic_energy", lambda: dict(q=np.zeros(4), qd=np.full(4, 1e200))),
    ("dynamics:inverse_dynamics", lambda: dict(q=np.zeros(4), qd=np.zeros(4), qdd=np.full(4, 1e308))),
    ("kinematics:jacobian_dot", lambda: dict(q=np.zeros(4), qd=np.full(4, 1e200))),
    ("trajectory:trapezoidal", lambda: dict(tau=np.array([0.0, 1e300]), length=1e300, duration=1e-300)),
    ("trajectory:Trapezoidal", lambda: dict(length=1e300, duration=1e-300, blend=1e-300)),
    ("_simulate:joint_setpoint", lambda: dict(q_d=np.zeros(4), duration=1e300)),
    ("_simulate:joint_setpoint", lambda: dict(q_d=np.zeros(4), duration=0.3, dt=1e-300)),
    ("trajectory:reference_trajectory", lambda: dict(dt=1e-300)),
    ("_manipulability:workspace_map", lambda: dict(n=10 ** 9)),
    ("control:rho_bound", lambda: dict(alpha=0.5, qdd_max=1e308, eta0_max=1e308)),
    ("control:sliding_weight", lambda: dict(K_P=1e300, K_D=1e300, Lambda=1e300)),
]


def _nan_tau_run():
    res = F.runs()[2][1]
    tau = res.tau.copy()
    tau[5, 1] = np.nan
    return types.SimpleNamespace(**{**{f.name: getattr(res, f.name) for f in dataclasses.fields(res)}, "tau": tau})


@pytest.mark.parametrize("i", range(len(PROBES)), ids=[f"{k}-{i}" for i, (k, _) in enumerate(PROBES)])
def test_probe(i):
    key, build = PROBES[i]
    entry = _table()[key]
    kwargs = build()
    failure = _check_call(entry, entry.resolve(), kwargs, list(kwargs), TIMEOUT_S)
    if failure:
        call = fz.show_call(entry.name, kwargs)
        if LOG:
            _log(dict(key=entry.key, call=call, hostile=list(kwargs), probe=True, **failure))
            return
        raise AssertionError(f"{entry.key}: {failure['kind']} {failure['exc']}: {failure['msg']}\n"
                             f"  at {failure['where']}\n  call: {call}")


@pytest.mark.parametrize("key", [e.key for e in TABLE])
def test_fuzz(key):
    entry = _table()[key]
    # a few calls first, without deadline and without reporting: the first call of a kernel compiles it (numba's
    # disk cache is invalidated by every edit of the package), which must not count against the deadline
    _run(entry, WARMUP_EXAMPLES, None, True, 300.0)
    _run(entry, WARMUP_EXAMPLES, None, False, 300.0, quiet=True)
    t0 = time.perf_counter()
    try:
        _run(entry, entry.examples, DEADLINE_MS, False, TIMEOUT_S)
    finally:
        if LOG:
            _log(dict(kind="stats", key=key, seconds=round(time.perf_counter() - t0, 2), **STATS[key]))
