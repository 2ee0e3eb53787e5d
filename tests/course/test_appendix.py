"""The appendix's exercise computations against the closed forms of the robot's data, for a few drawn sets."""
import pytest

from scara.course.exercises import draw_params, exercise, solve

STUDENTS = ("s1", "s2", "s9")


def drawn(label):
    return [draw_params(exercise(label), b"test", s) for s in STUDENTS]


def test_bound_is_calls_times_steps():
    r = solve("ex-ver-bound")
    assert r["bound_s"] == pytest.approx(4 * r["call_us"] * 1e-6 * 70000)
    assert 0 < r["share_pct"] < 100


@pytest.mark.parametrize("params", drawn("ex-ver-coupling"))
def test_coupling_force(params):
    # k_r3 I_m3 = 50 * 0.005 = 0.25 kg m
    assert solve("ex-ver-coupling", params)["force_N"] == pytest.approx(0.25 * (params["qdd1"] + params["qdd2"]))


@pytest.mark.parametrize("params", drawn("ex-ver-signs"))
def test_signs(params):
    r = solve("ex-ver-signs", params)
    assert r["phidot"] == pytest.approx(params["qd1"]) and r["omega_z"] == pytest.approx(-params["qd1"])


@pytest.mark.parametrize("params", drawn("ex-ver-com"))
def test_misplaced_com(params):
    # a1 = 0.5 m, l1 = 0.25 m: (0.75^2 - 0.25^2) = 0.5 m^2
    assert solve("ex-ver-com", params)["dB"] == pytest.approx(0.5 * params["m_l1"])
