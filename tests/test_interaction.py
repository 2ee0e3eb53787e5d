"""Tests of scara.interaction (chapter 7): the contact force model by hand, the J^T h mapping by virtual work,
energy conservation of a free bounce, the engine against scara.simulate without contact, each law's steady state
against its formula, the contact transitions, the peg-in-hole run, the sensor's statistics and bad inputs."""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import _largest
from scara import (ScaraError, ScaraParams, ShapeError, TorqueController, UnstableError, forward_dynamics, ikine,
                   jacobian, kinetic_energy, potential_energy, pose, simulate)
from scara.control import OperationalSpaceController
from scara.dynamics import dynamic_array
from scara.interaction import (AdmittanceController, ComplianceController, ForceController, ForceSensor, Hole,
                               ImpedanceController, ParallelController, Surface, approach_reference,
                               contact_force, contact_transition, force_equilibrium, insertion_summary,
                               approach_run, law_equilibrium, peg_frames, peg_in_hole, pressing_target,
                               sensor_coupling, simulate_contact, wrench_torque)
from scara.interaction.environment import inside_after
from scara.interaction.plant import contact_acceleration
from scara.interaction.stability import sampled_radius, z_axis
from scara._simulate.plant import _plant_constants

S = Surface()
IDEAL = ForceSensor(noise=0.0, bias=(0.0, 0.0, 0.0))
BIASED = ForceSensor(noise=0.0)  # 0.5 N on f_z, no noise: the bias alone, deterministic
LAWS = (ComplianceController, ImpedanceController, AdmittanceController, ForceController, ParallelController)


def _start(z=0.32, xy=(0.4, 0.1)):
    q = ikine([xy[0], xy[1], z, 0.0], elbow=-1)
    return np.array([xy[0], xy[1], z, q[0] + q[1]])


# --------------------------------------------------------------------------------------------------
# the contact force model, by hand
# --------------------------------------------------------------------------------------------------
def test_surface_force_by_hand():
    k, d, mu, vs = S.stiffness, S.damping, S.friction, S.v_s
    assert np.all(contact_force([0.4, 0.1, 0.3001], [0.0, 0.0, -1.0]) == 0.0)  # above: nothing
    h = contact_force([0.4, 0.1, 0.299], [0.0, 0.0, 0.0])  # 1 mm in, at rest: the spring alone
    assert h == pytest.approx([0.0, 0.0, -k * (0.3 - 0.299)], rel=1e-14, abs=0)
    h = contact_force([0.4, 0.1, 0.299], [0.0, 0.0, -0.1])  # pressing in at 0.1 m/s: spring + damper
    assert h[2] == pytest.approx(-(k * (0.3 - 0.299) + d * 0.1), rel=1e-14)
    # leaving fast: k delta + d delta_dot < 0, and the surface never pulls
    assert np.all(contact_force([0.4, 0.1, 0.2999], [0.0, 0.0, 1.0]) == 0.0)
    # sliding along +x at 10 v_s: the tool pushes the surface along its own motion (the surface resists it)
    fn = k * 1e-3
    h = contact_force([0.4, 0.1, 0.299], [10 * vs, 0.0, 0.0])
    assert h[0] == pytest.approx(mu * fn * math.tanh(10.0), rel=1e-14)
    assert h[1] == 0.0
    h = contact_force([0.4, 0.1, 0.299], [-3 * vs, 4 * vs, 0.0])  # |v_t| = 5 v_s, along (-0.6, 0.8)
    assert h[:2] == pytest.approx(mu * fn * math.tanh(5.0) * np.array([-0.6, 0.8]), rel=1e-14)


def test_hole_force_by_hand():
    hole = Hole(centre=(0.4, 0.1), clearance=5e-4, depth=0.03, wall_stiffness=1e6)
    s = Surface(hole=hole)
    k, mu, vs = s.stiffness, s.friction, s.v_s
    # over the hole (within the clearance), below the plane, not yet marked inside: nothing bears the peg
    assert np.all(contact_force([0.4003, 0.1, 0.295], [0, 0, 0], s) == 0.0)
    # off-centre beyond the clearance: the surface bears it
    assert contact_force([0.4008, 0.1, 0.299], [0, 0, 0], s)[2] == pytest.approx(-k * 1e-3, rel=1e-12)
    # inside, 0.2 mm into the wall along -y, moving down at 5 v_s: the wall's normal force and its friction
    h = contact_force([0.4, 0.1 - 7e-4, 0.28], [0.0, 0.0, -5 * vs], s, inside=True)
    fw = 1e6 * 2e-4
    assert h == pytest.approx([0.0, -fw, -mu * fw * math.tanh(5.0)], rel=1e-9, abs=1e-12)
    # inside, on the bottom (z_s - depth = 0.27), 0.5 mm in
    h = contact_force([0.4, 0.1, 0.2695], [0, 0, 0], s, inside=True)
    assert h == pytest.approx([0.0, 0.0, -k * 5e-4], rel=1e-9)
    env = s.array()
    assert inside_after(0.4003, 0.1, 0.2999, env, 0.0) == 1.0  # crossed the plane within the clearance
    assert inside_after(0.4008, 0.1, 0.2999, env, 0.0) == 0.0  # beyond it: on the surface
    assert inside_after(0.4008, 0.1, 0.2999, env, 1.0) == 1.0  # once inside, stays while below the plane
    assert inside_after(0.4, 0.1, 0.3001, env, 1.0) == 0.0  # above the plane: out


@settings(max_examples=300)
@given(st.tuples(*[st.floats(-0.01, 0.01)] * 3), st.tuples(*[st.floats(-1.0, 1.0)] * 3), st.booleans())
def test_contact_force_pushes_never_pulls_and_friction_resists(dp, v, inside):
    s = Surface(hole=Hole(centre=(0.4, 0.1)))
    p = np.array([0.4, 0.1, 0.29]) + dp
    h = contact_force(p, v, s, inside=inside)
    f = -h  # the environment's force on the tool
    vt = np.array(v[:2])
    if not inside:  # on the surface: the normal force is up, the friction opposes sliding and is at most mu f_n
        assert f[2] >= 0.0
        assert np.hypot(*f[:2]) <= s.friction * f[2] * (1 + 1e-12)
        assert f[:2] @ vt <= 1e-15
    else:  # the walls push toward the axis, the friction along z opposes the vertical motion of a wall contact
        r = p[:2] - np.array(s.hole.centre)
        assert f[:2] @ r <= 1e-12  # never outward


# --------------------------------------------------------------------------------------------------
# J^T h: virtual work, and the plant's acceleration against the general forward dynamics
# --------------------------------------------------------------------------------------------------
@settings(max_examples=100)
@given(st.tuples(st.floats(-3, 3), st.floats(0.3, 2.8), st.floats(0.1, 0.9), st.floats(-3, 3)),
       st.tuples(*[st.floats(-50, 50)] * 3))
def test_wrench_torque_is_the_virtual_work_gradient(q, f):
    """tau = J^T f equals d(f . p(q))/dq (central differences, step 1e-6: error O(1e-12) relative)."""
    q, f = np.array(q), np.array(f)
    tau = wrench_torque(q, f)
    num = np.empty(4)
    for i in range(4):
        dq = np.zeros(4)
        dq[i] = 1e-6
        num[i] = (f @ pose(q + dq)[:3] - f @ pose(q - dq)[:3]) / 2e-6
    err = _largest.record("J^T f vs d(f.p)/dq", np.max(np.abs(tau - num)) / (1 + np.max(np.abs(f))))
    assert err < 1e-7


def test_plant_acceleration_in_contact_matches_forward_dynamics():
    """qdd of the contact plant = B^-1 (tau - J^T h_e - C qd - F qd - g) of the general (Cholesky) solve."""
    p = ScaraParams()
    pc = _plant_constants(dynamic_array(p))
    s = Surface()
    rng = np.random.default_rng(3)
    for _ in range(20):
        q = np.array([rng.uniform(-2, 2), rng.uniform(0.5, 2.5), 0.0, rng.uniform(-2, 2)])
        q[2] = p.d0 - (s.height - rng.uniform(0, 2e-3))  # up to 2 mm into the surface
        qd = rng.normal(0, 0.05, 4)
        tau = rng.normal(0, 20, 4)
        qdd, code, f = contact_acceleration(q[0], q[1], q[2], tuple(qd), tuple(tau), pc, p.a1, p.a2, p.d0,
                                            s.array(), 0.0)
        h_e = contact_force(pose(q)[:3], jacobian(q)[:3] @ qd, s)
        assert np.array(f) == pytest.approx(-h_e, rel=1e-12, abs=1e-12)
        want = forward_dynamics(q, qd, tau - jacobian(q)[:3].T @ h_e, p)
        err = _largest.record("contact qdd vs forward_dynamics", np.max(np.abs(np.array(qdd) - want)))
        assert err < 1e-9 * (1 + np.max(np.abs(want)))


def test_sensor_coupling_is_the_acceleration_a_tool_force_gives_the_arm_at_rest():
    """c = J_A B^-1 J^T b against the general forward dynamics: at rest with gravity balanced, a force b on the
    tool accelerates the tool by J_A qdd, qdd = forward_dynamics(q, 0, g(q) + J^T b)."""
    from scara import gravity

    rng = np.random.default_rng(5)
    for _ in range(10):
        q = np.array([rng.uniform(-2, 2), rng.uniform(0.4, 2.7), rng.uniform(0.2, 0.8), rng.uniform(-2, 2)])
        b = rng.normal(0, 1, 3)
        qdd = forward_dynamics(q, np.zeros(4), gravity(q) + jacobian(q)[:3].T @ b)
        want = jacobian(q) @ qdd
        assert sensor_coupling(b, q) == pytest.approx(want, rel=1e-12, abs=1e-14)


def test_contact_transition_counts_by_hand():
    """A made-up record: free, touching at sample 2, lost at 4, back at 6 and to the end (forces in N)."""
    from types import SimpleNamespace

    fz = np.array([0.0, 0.0, -3.0, -12.0, 0.0, 0.0, -8.0, -10.0])
    force = np.column_stack([np.zeros(8), np.zeros(8), fz])
    r = SimpleNamespace(t=np.arange(8) * 1e-3, force=force, in_contact=fz != 0.0)
    tr = contact_transition(r)
    assert tr == {"first_touch": 2e-3, "peak_force": 12.0, "contact_losses": 1, "bounced": True, "final_force": 10.0}


# --------------------------------------------------------------------------------------------------
# the engine: no contact = scara.simulate; energy of a free bounce; the step's accuracy
# --------------------------------------------------------------------------------------------------
def test_no_environment_run_is_simulate_bit_for_bit():
    start = _start(0.5)
    ref = approach_reference(start, start + [0.02, 0.01, -0.05, 0.1], 0.3, 0.1)
    c = OperationalSpaceController()
    for substeps in (1, 10):
        a = simulate(c, ref, substeps=substeps)
        b = simulate_contact(c, ref, surface=None, substeps=substeps)
        for name in ("q", "qd", "qdd", "tau", "x", "e"):
            assert np.array_equal(getattr(a, name), getattr(b, name)), (substeps, name)
    assert np.all(b.force == 0.0) and not b.in_contact.any()


def test_untouched_surface_run_equals_simulate_to_round_off():
    """With a surface the tool never reaches, the contact step (the whole configuration in each stage) gives the
    free plant's run up to round-off."""
    start = _start(0.5)
    ref = approach_reference(start, start + [0.02, 0.01, -0.05, 0.1], 0.3, 0.1)
    c = OperationalSpaceController()
    a = simulate(c, ref, substeps=10)
    b = simulate_contact(c, ref, surface=Surface(height=0.1), substeps=10)
    err = _largest.record("untouched surface vs simulate", np.max(np.abs(a.q - b.q)))
    assert err < 1e-13
    assert not b.in_contact.any()


def _bounce_energy(substeps):
    p = ScaraParams(F_m=(0.0, 0.0, 0.0, 0.0))
    s = Surface(damping=0.0, friction=0.0)
    q0 = ikine([0.4, 0.1, 0.31, 0.0], p, elbow=-1)  # 1 cm above the surface, at rest
    r = simulate_contact(TorqueController(), duration=0.6, q0=q0, plant=p, surface=s, substeps=substeps,
                         sensor=IDEAL)
    delta = np.maximum(s.height - r.x[:, 2], 0.0)
    E = kinetic_energy(r.q, r.qd, p) + potential_energy(r.q, p) + 0.5 * s.stiffness * delta ** 2
    return r, E


def test_free_bounce_conserves_energy():
    """No damping, no friction (surface and joints): kinetic + potential + the surface's spring energy is constant
    to the integrator's accuracy, and the drift shrinks with the RK4 step. The contact force has a kink at
    delta = 0: the error of a step that straddles it depends on where in the step the kink falls, so the drift
    does not shrink by the same factor from one step to the next (4.8e-6 of the drop's energy at 5 steps per
    period, 2.5e-7 at 10, 7e-8 at 20 and 40, 3e-9 at 160); a step 16 times smaller must cut it tenfold."""
    r, E = _bounce_energy(10)
    assert contact_transition(r)["contact_losses"] >= 1  # it bounces (and comes back)
    scale = 10.0 * 9.81 * 0.01  # the quill's drop of 1 cm (J)
    drift10 = np.max(np.abs(E - E[0]))
    drift160 = np.max(np.abs(_bounce_energy(160)[1] - E[0]))
    _largest.record("bounce energy drift / m g dh (10 substeps)", drift10 / scale)
    assert drift10 < 1e-6 * scale
    assert drift160 < drift10 / 10


@pytest.mark.parametrize("damped", [False, True])
def test_energy_balance_of_a_run_in_contact(damped):
    """ContactResult.energy: kinetic + potential - input work + friction work - the environment's work stays at its
    start to the quadrature's accuracy on the 1 ms samples. At each touch-down or lift-off the contact power
    has a kink (its slope jumps by k_e v^2) and, with the damper, a jump (by d_e v^2): Simpson's rule errs there by
    at most about jump * dt (damper) or slope jump * dt^2 (spring) per event."""
    plant = ScaraParams() if damped else ScaraParams(F_m=(0.0, 0.0, 0.0, 0.0))
    s = Surface() if damped else Surface(damping=0.0, friction=0.0)
    q0 = ikine([0.4, 0.1, 0.31, 0.0], plant, elbow=-1)
    r = simulate_contact(TorqueController(), duration=0.6, q0=q0, plant=plant, surface=s)
    e = r.energy()
    events = 2 * (contact_transition(r)["contact_losses"] + 1)
    v2 = np.max(r.qd[r.in_contact, 2] ** 2)
    bound = events * (s.damping * v2 * r.dt + s.stiffness * v2 * r.dt ** 2)
    err = _largest.record("energy balance in contact / bound", np.abs(e["balance"]).max() / bound)
    assert err < 1.0
    assert np.abs(e["contact_work"]).max() > 100 * np.abs(e["balance"]).max()


def test_sliding_run_is_resolved_by_ten_substeps():
    """The friction's tanh (v_s = 1 mm/s) and the contact stiffness are resolved at 10 RK4 steps per period: the
    forces of a run pressing and sliding 2 cm differ from a 40-step run by < 1e-4 of the normal force."""
    start = _start(0.3)
    ref = approach_reference(start, start + [0.02, 0.0, 0.0, 0.0], 0.5, 0.3)
    r10 = simulate_contact(ParallelController(), ref, surface=S, sensor=IDEAL, substeps=10)
    r40 = simulate_contact(ParallelController(), ref, surface=S, sensor=IDEAL, substeps=40)
    assert r10.in_contact[200:].all()
    err = _largest.record("force, 10 vs 40 substeps (N)", np.max(np.abs(r10.force - r40.force)))
    assert err < 1e-4 * np.max(np.abs(r40.force[:, 2]))


# --------------------------------------------------------------------------------------------------
# the sensor
# --------------------------------------------------------------------------------------------------
def test_sensor_statistics_and_what_the_law_reads():
    sensor = ForceSensor()  # 0.2 N, bias 0.5 N on f_z, seed 0
    n = 400_000
    e = sensor.offsets(n)
    assert np.array_equal(e, ForceSensor().offsets(n))  # seeded
    se = 0.2 / math.sqrt(n)
    assert np.all(np.abs(e.mean(axis=0) - [0.0, 0.0, 0.5]) < 5 * se)
    assert np.all(np.abs(e.std(axis=0) - 0.2) < 5 * 0.2 / math.sqrt(2 * n))
    start = _start(0.31)
    r = simulate_contact(ForceController(), approach_reference(start, start, 0.1, 0.5), surface=S, sensor=sensor)
    # the reading is the true force plus the seeded offsets (to the round-off of that one addition)
    assert np.max(np.abs(r.measured_force - r.force - sensor.offsets(len(r.t)))) < 1e-14 * (1 + np.abs(r.force).max())
    assert r.in_contact.any()


# --------------------------------------------------------------------------------------------------
# steady states: each law against its formula
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("law", [ComplianceController, ImpedanceController, AdmittanceController,
                                 ParallelController])
@pytest.mark.parametrize("sensor", [IDEAL, BIASED], ids=["ideal", "biased"])
def test_steady_state_matches_the_formula(law, sensor):
    """After an approach (1 s) and 8 s pressing, pose and force equal law_equilibrium's: the remaining transient
    (the slowest, the friction's creep at the tanh's slope mu f_n / v_s, decays as exp(-t / 0.6 s)) is below
    1e-9 m and 1e-6 N."""
    c = law()
    start = _start()
    target = pressing_target(c, start)
    r = simulate_contact(c, approach_reference(start, target, 1.0, 8.0), surface=S, sensor=sensor)
    x, h = law_equilibrium(c, target, S, sensor)
    ex = _largest.record("steady pose vs formula (m)", np.max(np.abs(r.x[-1] - x)))
    eh = _largest.record("steady force vs formula (N)", np.max(np.abs(r.force[-1] - h)))
    assert ex < 1e-9
    assert eh < 1e-6
    if sensor is IDEAL or law is ComplianceController:  # the target was chosen for 10 N (compliance reads no sensor)
        assert -h[2] == pytest.approx(10.0, rel=1e-12)


def test_compliance_force_is_the_surface_stiffness_times_the_predicted_penetration():
    c = ComplianceController()
    start = _start()
    target = pressing_target(c, start)
    r = simulate_contact(c, approach_reference(start, target, 1.0, 8.0), surface=S)
    kz = c.K_P[2]
    penetration = kz / (kz + S.stiffness) * (S.height - target[2])  # (K_P + K)^-1 K_P (x_r - x_d), along z
    assert S.height - r.x[-1, 2] == pytest.approx(penetration, abs=1e-12)
    assert -r.force[-1, 2] == pytest.approx(S.stiffness * penetration, rel=1e-9)
    assert -r.force[-1, 2] == pytest.approx(10.0, rel=1e-9)


@pytest.mark.parametrize("sensor", [IDEAL, BIASED], ids=["ideal", "biased"])
def test_force_control_reaches_f_d_and_errs_by_exactly_the_bias(sensor):
    c = ForceController()
    start = _start()
    r = simulate_contact(c, approach_reference(start, start, 1.0, 5.0), surface=S, sensor=sensor)
    z, h = force_equilibrium(c.f_d, S, sensor)
    err = c.f_d[2] - r.force[-1, 2]
    assert _largest.record("force error - bias (N)", abs(err - sensor.bias[2])) < 1e-9
    assert abs(r.x[-1, 2] - z) < 1e-12
    assert abs(r.measured_force[-1, 2] - c.f_d[2]) < 1e-9  # the integral makes the reading f_d


def test_force_control_with_noise_errs_by_the_bias_on_average():
    """With the 0.2 N noise the true force jitters about f_d - b: its mean over the last 2 s (2000 samples)
    errs from f_d by the bias to within 0.02 N (the loop passes the noise filtered; 5 standard errors of the
    raw noise are 0.022 N)."""
    c = ForceController()
    start = _start()
    r = simulate_contact(c, approach_reference(start, start, 1.0, 5.0), surface=S, sensor=ForceSensor())
    err = c.f_d[2] - r.force[-2000:, 2].mean()
    assert abs(err - 0.5) < 0.02


# --------------------------------------------------------------------------------------------------
# contact transitions
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("law", LAWS)
def test_transition_onto_the_surface_does_not_bounce(law):
    """From 2 cm above to pressing with 10 N (the default sensor: noise and bias): no law loses the contact
    once made, and the impact overshoots the 10 N only boundedly."""
    r = approach_run(law(), S, ForceSensor())
    tr = contact_transition(r)
    assert not tr["bounced"], tr
    assert 0.3 < tr["first_touch"] < 1.5
    assert 10.0 <= tr["peak_force"] < 40.0
    assert r.in_contact[-1]


def test_summary_carries_the_contact_figures():
    r = approach_run(ForceController(), S, BIASED, hold=3.0)
    summary = r.summary(window=0.5)
    assert summary["bounced"] is False and summary["first_touch"] > 0
    assert summary["mean_force"][2] == pytest.approx(-10.5, abs=1e-6)  # f_d less the bias, at rest
    assert summary["peak_force"] == contact_transition(r)["peak_force"]


def test_a_lightly_damped_law_bounces():
    """The same approach with compliance damped 10 times less loses contact after the first touch."""
    c = ComplianceController(K_D=(600.0, 600.0, 30.0, 25.0))
    start = _start()
    r = simulate_contact(c, approach_reference(start, pressing_target(c, start), 0.5, 1.0), surface=S)
    tr = contact_transition(r)
    assert tr["bounced"] and tr["contact_losses"] >= 1


# --------------------------------------------------------------------------------------------------
# peg-in-hole
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("offset, landed", [((3e-4, 0.0), False), ((0.0, 1.5e-3), True)])
def test_peg_goes_to_the_bottom(offset, landed):
    r = peg_in_hole(offset)
    s = r.surface
    summary = insertion_summary(r)
    assert summary["landed_on_surface"] is landed
    assert summary["bottom_reached"] < r.t[-1] - 1.0
    # at rest on the bottom with the parallel law's force, less the sensor's bias
    z, h = force_equilibrium(-10.0, Surface(height=s.height - s.hole.depth), r.sensor)
    assert r.x[-1, 2] == pytest.approx(z, abs=1e-6)
    assert r.force[-1, 2] == pytest.approx(h[2], abs=0.1)  # the noise (0.2 N) jitters the last sample
    frames = peg_frames(r, every=50)
    assert frames["tip"].shape == (len(range(0, len(r.t), 50)), 3)
    assert frames["hole_radius"] == pytest.approx(5e-3 + 5e-4)


def test_a_peg_pushed_into_the_wall_loads_it_by_the_commanded_overlap():
    """Inside the hole, the reference moved 0.7 mm off the axis (0.2 mm past the clearance): parallel control
    compensates the measured force, so its position loop holds x_d exactly and the wall bears k_w (rho - c) =
    1e6 * 2e-4 = 200 N, along +x (the tool pushes the wall outward); the bottom still bears f_d."""
    from scara.interaction.peg import _concatenate

    s = Surface(hole=Hole())
    c = np.array(s.hole.centre)
    p0 = _start(0.302, c)
    down = p0 - [0.0, 0.0, 0.002, 0.0]
    side = down + [7e-4, 0.0, 0.0, 0.0]
    ref = _concatenate([approach_reference(p0, down, 0.3, 1.7), approach_reference(down, side, 0.5, 2.5)], 1e-3)
    r = simulate_contact(ParallelController(), ref, surface=s, sensor=IDEAL)
    assert r.inside[-1]
    assert np.abs(r.x[-1, [0, 1, 3]] - side[[0, 1, 3]]).max() < 1e-12
    want = s.hole.wall_stiffness * (7e-4 - s.hole.clearance)
    assert r.force[-1, 0] == pytest.approx(want, rel=1e-9)
    assert r.force[-1, 2] == pytest.approx(-10.0, rel=1e-6)


# --------------------------------------------------------------------------------------------------
# the sampled loop's stability, and bad inputs
# --------------------------------------------------------------------------------------------------
def test_sampled_radius_of_a_pd_on_a_mass_by_hand():
    """Free mass, PD held over dt: the exact map is [[1 - K_P dt^2/2m, dt - K_D dt^2/2m], [-K_P dt/m, 1 - K_D dt/m]]."""
    m, KP, KD, dt = 20.0, 1e4, 400.0, 1e-3
    M = np.array([[1 - KP * dt ** 2 / (2 * m), dt - KD * dt ** 2 / (2 * m)], [-KP * dt / m, 1 - KD * dt / m]])
    want = np.max(np.abs(np.linalg.eigvals(M)))
    loop = (np.array([-KP, -KD]), np.zeros(0), np.zeros((0, 0)), np.zeros((0, 2)))
    assert sampled_radius(loop, m, 0.0, 0.0, 0.0, dt) == pytest.approx(want, rel=1e-12)


@pytest.mark.parametrize("law", LAWS)
def test_default_gains_are_stable_on_the_books_surface(law):
    m, c = z_axis()
    loops = law().z_loops(m, c, S.stiffness, S.damping, 1e-3)
    assert sampled_radius(loops["contact"], m, c, S.stiffness, S.damping, 1e-3) < 1
    assert sampled_radius(loops["free"], m, c, 0.0, 0.0, 1e-3) < 1


@pytest.mark.parametrize("make", [lambda: ComplianceController(K_D=(600, 600, 5e4, 25)),
                                  lambda: ImpedanceController(M_d=(10, 10, 0.1, 1)),
                                  lambda: ForceController(K_I=(2e-3, 2e-3, 0.05)),
                                  lambda: ParallelController(K_I=0.5)])
def test_unstable_gains_are_refused_before_the_run(make):
    start = _start()
    with pytest.raises(UnstableError, match=r"spectral radius [0-9.]+, which must be < 1"):
        simulate_contact(make(), approach_reference(start, start, 0.1, 0.1), surface=S)


def test_the_sampled_radius_tells_the_simulation_apart():
    """Compliance along z with K_D = 3e4 N s/m (radius 0.9992) presses steadily; with 5e4 (radius 1.22) the
    same run, its check switched off, is lost within the first second."""
    start = _start()
    ok = ComplianceController(K_D=(600, 600, 3e4, 25))
    ref = approach_reference(start, pressing_target(ok, start), 1.0, 1.0)
    r = simulate_contact(ok, ref, surface=S)
    assert r.in_contact[-500:].all()
    bad = ComplianceController(K_D=(600, 600, 5e4, 25))
    bad.check_contact = None
    with pytest.raises(UnstableError):
        simulate_contact(bad, ref, surface=S)


@pytest.mark.parametrize("make, match", [
    (lambda: Surface(stiffness=-1.0), "stiffness"), (lambda: Surface(stiffness=0.0), "stiffness"),
    (lambda: Surface(damping=-1.0), "damping"), (lambda: Surface(friction=-0.1), "friction"),
    (lambda: Surface(friction=11.0), "friction"), (lambda: Surface(v_s=0.0), "v_s"),
    (lambda: Surface(height=float("nan")), "height"), (lambda: Hole(clearance=0.0), "clearance"),
    (lambda: Hole(depth=-0.01), "depth"), (lambda: Hole(centre=(0.4,)), "centre"),
    (lambda: ForceSensor(noise=-0.2), "noise"), (lambda: ForceSensor(bias=(0.0, 0.5)), "bias"),
    (lambda: ForceSensor(seed=-1), "seed"), (lambda: ForceSensor().offsets(-1), "n = -1"),
    (lambda: ForceSensor().offsets(2.5), "n = 2.5"), (lambda: ComplianceController(K_P=-1.0), "K_P"),
    (lambda: ImpedanceController(M_d=0.0), "M_d"), (lambda: ForceController(K_I=(1e-3, 1e-3, 0.0)), "K_I"),
    (lambda: ParallelController(f_d=float("nan")), "f_d"), (lambda: ForceController(f_d=(0, 0, 1e6)), "f_d"),
    (lambda: contact_force([0.4, 0.1], [0, 0, 0]), "position"),
    (lambda: contact_force([0.4, 0.1, np.nan], [0, 0, 0]), "position"),
    (lambda: wrench_torque(np.zeros(4), [1.0, 2.0]), "force"),
    (lambda: approach_reference([1.2, 0.0, 0.3, 0.0], [0.4, 0.1, 0.3, 0.0]), "start .* outside the annulus"),
    (lambda: approach_reference([0.4, 0.1, 0.3, 0.0], [0.4, 0.1, 1.5, 0.0]), "target .* outside the stroke"),
])
def test_bad_inputs_raise_clear_errors(make, match):
    with pytest.raises(ScaraError, match=match):
        make()


def test_a_surface_the_tool_cannot_reach_is_refused():
    start = _start(0.5)
    ref = approach_reference(start, start, 0.1, 0.1)
    with pytest.raises(ScaraError, match=r"below the lowest point the tool reaches, d0 - d3_max = 0 m"):
        simulate_contact(ComplianceController(), ref, surface=Surface(height=-0.05))
    with pytest.raises(ScaraError, match="hole's bottom"):
        simulate_contact(ComplianceController(), ref, surface=Surface(height=0.02, hole=Hole(depth=0.03)))
    with pytest.raises(ScaraError, match="at or above the highest point"):
        simulate_contact(ComplianceController(), ref, surface=Surface(height=1.0))
    with pytest.raises(ShapeError):
        simulate_contact(ComplianceController(), ref, surface=S, q0=[0.0, 1.0])
    with pytest.raises(ScaraError, match="surface must be a Surface"):
        simulate_contact(ComplianceController(), ref, surface="floor")


# --------------------------------------------------------------------------------------------------
# the plain-Python path
# --------------------------------------------------------------------------------------------------
def test_plain_python_contact_run_gives_the_same_numbers():
    """The engine in contact, its laws and kernels run without numba (SCARA_NO_NUMBA=1) and give the compiled
    run's numbers: parallel control landing 0.5 mm on the surface of a hole, 0.15 s."""
    import json
    import os
    import subprocess
    import sys

    code = ("import json, numpy as np, scara._compile as c; from scara import ikine;"
            "from scara.interaction import *; assert not c.COMPILED;"
            "q=ikine([0.4012, 0.1, 0.3005, 0.0], elbow=-1); s=np.array([0.4012, 0.1, 0.3005, q[0]+q[1]]);"
            "r=simulate_contact(ParallelController(), approach_reference(s, s-[0,0,5e-4,0], 0.1, 0.05),"
            " surface=Surface(hole=Hole()), substeps=2);"
            "print(json.dumps(np.r_[r.q.ravel(), r.force.ravel(), r.tau.ravel()].tolist()))")
    env = dict(os.environ, SCARA_NO_NUMBA="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    s = _start(0.3005, (0.4012, 0.1))
    r = simulate_contact(ParallelController(), approach_reference(s, s - [0, 0, 5e-4, 0], 0.1, 0.05),
                         surface=Surface(hole=Hole()), substeps=2)
    assert r.in_contact.any()
    ref = np.r_[r.q.ravel(), r.force.ravel(), r.tau.ravel()]
    err = _largest.record("plain Python contact run vs compiled", np.abs(np.array(json.loads(out)) - ref).max())
    assert err < 1e-9  # FMA contraction in compiled code: round-off, amplified by the loops' gains
