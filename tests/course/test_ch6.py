"""Chapter 6's exercise computations against closed forms and scalings they must obey, for a few drawn sets."""
import math

import pytest

from scara.course.exercises import draw_params, exercise, solve

STUDENTS = ("s1", "s7")


def drawn(label):
    return [draw_params(exercise(label), b"test", s) for s in STUDENTS]


@pytest.mark.parametrize("params", drawn("ex-ctl-ij-pd"))
def test_ij_pd_sag_scales_as_one_over_omega_squared(params):
    r = solve("ex-ctl-ij-pd", params)
    # m3 g0 / (omega^2 B_bar33) with m3 = m_l3 + m_L = 10 kg + m_L, B_bar33 = m_l3 + k_r3^2 I_m3 = 22.5 kg
    assert r["sag_mm"] == pytest.approx(1e3 * (10.0 + params["m_L"]) * 9.81 / (params["omega"] ** 2 * 22.5), rel=1e-3)
    # the pole of (b) gives exactly the allowed sag: omega_min^2 sag_max = omega^2 sag
    assert r["omega_min"] ** 2 * params["sag_max_mm"] == pytest.approx(params["omega"] ** 2 * r["sag_mm"], rel=1e-12)
    assert r["sag_sim_mm"] == pytest.approx(r["sag_mm"], rel=1e-5) and r["sag_run_mm"] < params["sag_max_mm"]


def test_ij_margin_is_affine_in_the_payload():
    ratios = [solve("ex-ctl-ij-margin", {"m_L": m})["ratio"] for m in (2.0, 5.0, 8.0)]
    assert ratios[1] - ratios[0] == pytest.approx(ratios[2] - ratios[1], rel=1e-9)   # B11 is affine in m3
    r = solve("ex-ctl-ij-margin", {"m_L": 6.5})
    assert r["c"] * r["ratio"] == pytest.approx(9.0) and r["below"] < 0 < r["above"]


def test_windup_integral_dwarfs_the_weight():
    r = solve("ex-ctl-ij-windup")
    assert r["integral_N"] > 3 * r["weight"] and r["room"] == pytest.approx(150.0 - r["weight"])


@pytest.mark.parametrize("params", drawn("ex-ctl-no-robust"))
def test_no_robust_sag_is_proportional_to_the_payload(params):
    r = solve("ex-ctl-no-robust", params)
    half = solve("ex-ctl-no-robust", {"m_L": params["m_L"] / 2})
    assert r["sag_mm"] == pytest.approx(2 * half["sag_mm"], rel=1e-12)
    assert r["sag_mm"] == pytest.approx(1e3 * params["m_L"] * 9.81 / (22.5 * 900.0), rel=1e-3)
    assert r["sim_mm"] == pytest.approx(r["sag_mm"], rel=1e-3)


@pytest.mark.parametrize("epsilon", exercise("ex-ctl-wider-layer").param("epsilon").choices)
def test_wider_layer_closed_form(epsilon):
    r = solve("ex-ctl-wider-layer", {"epsilon": epsilon})
    # rho = 20, lambda = 30, K_P = 900, B_hat33 = 22.5 kg, m_L = 5 kg
    assert r["sag_mm"] == pytest.approx(1e3 * 5 * 9.81 / (22.5 * (900 + 600 / epsilon)), rel=1e-3)
    assert r["margin"] / r["margin_book"] == pytest.approx(epsilon / 0.05)
    assert r["sim_mm"] == pytest.approx(r["sag_mm"], rel=1e-3) and r["chat"] < r["chat_book"]


@pytest.mark.parametrize("params", drawn("ex-ctl-slow-adaptation"))
def test_slow_adaptation_root_and_run(params):
    r = solve("ex-ctl-slow-adaptation", params)
    a, B, c = r["a"], r["B33"], 9.81 ** 2 / params["K_pi"]
    # the slow root of B s^2 + (F33 + K_D3) s + g0^2 / K_pi, with F33 + K_D3 from the sum of the two roots
    assert B * a ** 2 + B * (r["fast"] + r["slow"]) * a + c == pytest.approx(0.0, abs=1e-6 * c)
    assert r["fast"] * r["slow"] == pytest.approx(c / B, rel=1e-9)
    assert r["t_pred"] == pytest.approx(math.log(20) / a) and r["t_sim"] == pytest.approx(r["t_pred"], rel=0.05)


@pytest.mark.parametrize("params", drawn("ex-ctl-stiffer"))
def test_stiffer_gain_scales_with_payload_over_sag(params):
    r = solve("ex-ctl-stiffer", params)
    assert r["kpz_formula"] == pytest.approx(params["m_L"] * 9.81 / (22.5 * params["sag_max_mm"] * 1e-3), rel=1e-3)
    assert 0 < r["coupling"] < 1e-3 and r["sim_mm"] < params["sag_max_mm"]
    assert r["sim_mm"] == pytest.approx(params["sag_max_mm"], rel=1e-3)


def test_sampling_limit_formula():
    r1, r2 = solve("ex-ctl-sampling-limit", {"rho": 40.0}), solve("ex-ctl-sampling-limit", {"rho": 60.0})
    assert r2["eps_min"] == pytest.approx(1.5 * r1["eps_min"], rel=1e-12)      # proportional to rho
    lam = r1["lam_max"]
    assert r1["eps_min"] == pytest.approx(lam * 40.0 * 1e-3 / (2 - lam * 60.0 * 1e-3), rel=1e-12)
    assert 0 < r1["stop"] < 70 and r2["b11rho"] == pytest.approx(8.6 * 60.0)


@pytest.mark.parametrize("params", drawn("ex-ctl-integral-limit"))
def test_integral_limit_closed_forms(params):
    r = solve("ex-ctl-integral-limit", params)
    assert r["routh"] == 900.0 * 60.0
    assert r["cont"] == pytest.approx(54000.0 * 22.5 / (22.5 + 5.0 + params["m_L"] - 5.0), rel=1e-9)
    assert r["disc"] < r["cont"] and r["disc"] == pytest.approx(r["cont"], rel=0.1)
    assert r["radius_below"] < 1.0 < r["radius_above"]


@pytest.mark.parametrize("params", drawn("ex-ctl-pdg-sag"))
def test_pdg_sag_is_the_payloads_weight_over_the_spring(params):
    r = solve("ex-ctl-pdg-sag", params)
    # m_L g0 / (omega^2 B_bar33), B_bar33 = m_l3 + k_r3^2 I_m3 = 22.5 kg
    assert r["sag_mm"] == pytest.approx(1e3 * params["m_L"] * 9.81 / (params["omega"] ** 2 * 22.5), rel=1e-3)
    assert r["ratio"] == pytest.approx(params["m_L"] / (10.0 + params["m_L"]), rel=1e-12)
    # the runs: the law's own sag, and the independent PD's with the same spring carrying the quill as well
    assert r["sag_sim_mm"] == pytest.approx(r["sag_mm"], rel=1e-6)
    assert r["sag_sim_mm"] / r["pd_sag_sim_mm"] == pytest.approx(r["ratio"], rel=1e-6)


@pytest.mark.parametrize("params", drawn("ex-ctl-ct-omega"))
def test_ct_omega_squared_scales_with_payload_over_sag(params):
    r = solve("ex-ctl-ct-omega", params)
    half = solve("ex-ctl-ct-omega", {**params, "sag_max_mm": 2 * params["sag_max_mm"]}) \
        if 2 * params["sag_max_mm"] <= 1.0 else None
    assert r["formula"] == pytest.approx(math.sqrt(params["m_L"] * 9.81 / (22.5 * 1e-3 * params["sag_max_mm"])),
                                         rel=1e-12)
    assert 0 < r["omega_min"] / r["formula"] - 1 < 1e-3       # the rotor coupling, a few parts in 10^4
    if half is not None:                                        # omega^2 sag is constant
        assert half["omega_min"] ** 2 * 2 == pytest.approx(r["omega_min"] ** 2, rel=1e-12)
    # the run at the next whole rad/s ends within the bound, and within the 1/omega^2 scaling of it
    assert r["sag_run_mm"] < params["sag_max_mm"]
    assert r["sag_run_mm"] == pytest.approx(params["sag_max_mm"] * (r["omega_min"] / r["omega_run"]) ** 2, rel=1e-6)


@pytest.mark.parametrize("params", drawn("ex-ctl-ct-step"))
def test_ct_step_bounds_differ_by_the_modelled_weight(params):
    r = solve("ex-ctl-ct-step", params)
    k = 22.5 * params["omega"] ** 2        # B_hat33 K_P3, N/m
    assert r["delta_down_mm"] == pytest.approx(1e3 * (params["f_max"] + 98.1) / k, rel=1e-12)
    assert r["delta_up_mm"] == pytest.approx(1e3 * (params["f_max"] - 98.1) / k, rel=1e-12)
    # (down - up) k = twice the modelled weight, whatever the bound
    assert 1e-3 * (r["delta_down_mm"] - r["delta_up_mm"]) * k == pytest.approx(2 * 98.1, rel=1e-12)
    # 99 % of each step: the peak force is 99 % of (f_max +- weight) -+ weight, inside the bound; 101 % stops at once
    assert r["peak_down"] == pytest.approx(0.99 * (params["f_max"] + 98.1) - 98.1, rel=1e-9)
    assert r["peak_up"] == pytest.approx(0.99 * (params["f_max"] - 98.1) + 98.1, rel=1e-9)
    assert r["stop_down"] == r["stop_up"] == 0.0
