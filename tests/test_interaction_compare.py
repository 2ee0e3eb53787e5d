"""scara.interaction.compare: the settling time and the comparison rows against records written by hand, the
stiffness sweep against the series-spring formula written out here and against its own runs, the force loop's
bounds against the cubic's roots; and replay_law's refusal of a law that reads the force sensor."""
from __future__ import annotations

import math
from types import SimpleNamespace as NS

import numpy as np
import pytest

import scara
from scara.control import law_cost, replay_law
from scara.interaction import (ComplianceController, ForceController, ForceSensor, ImpedanceController, Surface,
                               approach_run, force_loop_bounds, force_loop_poly, law_comparison, settling_time,
                               stiffness_sweep)
from scara.interaction.stability import sampled_radius, z_axis


def record(fz, dt=0.1, height=0.3):
    fz = np.asarray(fz, dtype=float)
    n = len(fz)
    force = np.zeros((n, 3))
    force[:, 2] = fz
    x = np.zeros((n, 4))
    x[:, 2] = height + fz / 2e4          # the tool as deep as a 2e4 N/m surface's force says
    return NS(t=np.arange(n) * dt, force=force, in_contact=fz != 0.0, normal_force=-fz, x=x,
              surface=Surface(height=height))


def test_settling_time_counts_from_the_first_touch_to_the_last_sample_outside_the_band():
    r = record([0, 0, -30, -12, -10.4, -9.8, -10.1, -10.0, -10.0, -10.0], dt=0.1)
    # final = mean of the last 0.3 s (-10.0): the last sample off by more than 5 % is -12 at t = 0.3, so the
    # force is within the band from t = 0.4, 0.2 s after the first touch at t = 0.2
    assert settling_time(r, band=0.05, window=0.25) == pytest.approx(0.2, abs=1e-12)
    assert settling_time(r, band=0.01, window=0.25) == pytest.approx(0.4, abs=1e-12)   # -10.4 is 4 % off
    assert math.isnan(settling_time(record([0.0, 0.0, 0.0])))
    with pytest.raises(scara.ScaraError, match="needs a run of simulate_contact"):
        settling_time(NS(t=np.zeros(3)))
    with pytest.raises(scara.ScaraError, match="band"):
        settling_time(r, band=-0.1)


def test_comparison_rows_are_the_records_figures():
    r = record([0, -20, -11, -10, -10, -10], dt=0.5)
    (row,) = law_comparison({"hand": r}, force=9.0, window=1.0)
    assert row["law"] == "hand" and row["force_error"] == pytest.approx(9.0 - 10.0, abs=1e-12)
    assert row["penetration"] == pytest.approx(1e3 * 10.0 / 2e4, rel=1e-9) and row["peak_force"] == 20.0
    assert row["bounced"] is False and row["settling_time"] == pytest.approx(1.0, abs=1e-12)
    bounce = record([0, -20, 0, -12, -10, -10], dt=0.5)
    assert law_comparison({"b": bounce})[0]["bounced"] is True
    with pytest.raises(scara.ScaraError, match="non-empty dict"):
        law_comparison({})
    with pytest.raises(scara.ScaraError, match="needs a run of simulate_contact"):
        law_comparison({"x": NS(t=np.zeros(2))})


def test_stiffness_sweep_is_the_series_spring_and_its_runs_agree():
    depth = 1.5e-3
    out = stiffness_sweep([3000.0, 8000.0], [4e3, 3e4], depth=depth, points=3)
    for i, kp in enumerate(out["gains"]):
        for j, k in enumerate(out["stiffness"]):
            series = 1.0 / (1.0 / kp + 1.0 / k)          # two springs in series, written out
            assert out["formula"][i, j] == pytest.approx(series * depth, rel=1e-12)
            assert abs(out["simulated"][i, j] - out["formula"][i, j]) < 1e-4
    assert out["dense"][0] == pytest.approx(4e3) and out["dense"][-1] == pytest.approx(3e4) and len(out["dense"]) == 3
    assert out["dense_formula"][1, -1] == pytest.approx(8000.0 * 3e4 / (8000.0 + 3e4) * depth, rel=1e-12)


def test_stiffness_sweep_refuses_before_any_run():
    with pytest.raises(scara.ScaraError, match="must be non-empty and positive"):
        stiffness_sweep([-1.0], [2e4])
    with pytest.raises(scara.ScaraError, match=r"the runs \(gains x stiffnesses\) = 61"):
        stiffness_sweep(np.linspace(1e3, 2e3, 61), [2e4])


def test_force_loop_bounds_are_routh_and_the_unit_circle():
    surface = Surface()
    law = ForceController()
    b = force_loop_bounds(law, surface)
    KP, KD, KF, k, d = 2500.0, 70.0, 2e-5, 2e4, 50.0
    a2 = KD + KP * KF * d

    def max_real(ki):
        return np.roots([1.0, a2, KP * (1 + KF * k + ki * d), KP * ki * k]).real.max()

    assert max_real(0.999 * b["routh"]) < 0 < max_real(1.001 * b["routh"])       # the cubic's roots cross there
    assert np.allclose(force_loop_poly(ForceController(K_I=3e-3), Surface(stiffness=3e4, damping=20.0)),
                       [1.0, 70.0 + 2500.0 * 2e-5 * 20.0, 2500.0 * (1 + 2e-5 * 3e4 + 3e-3 * 20.0), 2500.0 * 3e-3 * 3e4],
                       rtol=1e-14)
    with pytest.raises(scara.ScaraError, match="force_loop_poly takes a ForceController"):
        force_loop_poly(ComplianceController())
    m, c = z_axis()

    def radius(ki):
        trial = ForceController(K_I=ki)
        return sampled_radius(trial.z_loops(m, c, k, d, 1e-3)["contact"], m, c, k, d, 1e-3)

    assert radius(0.999 * b["sampled"]) < 1.0 < radius(1.001 * b["sampled"])
    assert b["sampled"] < b["routh"] and b["radius"] == radius(2e-3)
    with pytest.raises(scara.UnstableError, match="spectral radius"):
        ForceController(K_I=1.001 * b["sampled"]).check_contact(surface)
    with pytest.raises(scara.ScaraError, match="takes a ForceController"):
        force_loop_bounds(ComplianceController())
    with pytest.raises(scara.ScaraError, match="must exceed"):
        force_loop_bounds(law, Surface(stiffness=100.0))


def test_the_force_loop_settles_at_its_slowest_pole_not_at_the_first_order_estimate():
    """The book's force control: the cubic's slowest poles are a damped pair whose envelope decays in about 63 ms,
    the sampled loop's largest eigenvalue gives the same rate, and ForceController's docstring states both."""
    law, surface = ForceController(), Surface()
    roots = np.roots(force_loop_poly(law, surface))
    slow = roots[np.argmax(roots.real)]
    assert abs(slow.imag) > 0 and slow.real == pytest.approx(-15.9, abs=0.05) and abs(slow.imag) == pytest.approx(46.9, abs=0.05)
    m, c = z_axis()
    r = sampled_radius(law.z_loops(m, c, 2e4, 50.0, 1e-3)["contact"], m, c, 2e4, 50.0, 1e-3)
    assert -1e-3 / math.log(r) == pytest.approx(-1.0 / slow.real, rel=0.02)     # the sampled loop's rate
    first_order = (1 + 2e-5 * 2e4) / (2e-3 * 2e4)
    assert -1.0 / slow.real > 1.7 * first_order
    assert "63 ms" in ForceController.__doc__ and "-15.9 +- 46.9j" in ForceController.__doc__


def test_replay_refuses_a_law_that_reads_the_force_sensor():
    ideal = ForceSensor(noise=0.0, bias=(0.0, 0.0, 0.0))
    run = approach_run(ImpedanceController(), Surface(), ideal, move=0.2, hold=0.1)
    with pytest.raises(scara.ScaraError, match=r"cannot replay impedance: its law reads the force sensor .*'measured_force'"):
        replay_law(ImpedanceController(), run)
    with pytest.raises(scara.ScaraError, match="reads the force sensor"):
        law_cost(ImpedanceController(), run, repeats=1)
    # compliance control reads no sensor: its replay gives the run's torques
    comp = approach_run(ComplianceController(), Surface(), ideal, move=0.2, hold=0.1)
    tau, _, _ = replay_law(ComplianceController(), comp)
    assert np.array_equal(tau, comp.tau)
