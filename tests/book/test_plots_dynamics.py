"""The figures of scara.plots.dynamics, written for the static page of chapter 5: the window maximum behind the
energy figure's residual panel, the residual panel itself (one line per window, no aliased band, a y title that fits
its panel), the static slider figure of the inertia entries against the elbow angle, whose numbers are checked
against the closed form of the chapter (equations eq-dyn-B11 and eq-dyn-B12), typed here independently of the
package, and the sample counts every torque and energy figure refuses before any work."""
from __future__ import annotations

import math

import numpy as np
import pytest

from scara import ScaraError, ScaraParams, TorqueController, simulate
from scara.plots._common import LOG_FLOOR, MAX_POINTS, MAX_STEPS
from scara.plots.dynamics import energy_figure, inertia_slider_figure, window_max
from scara.plots.layout import _text_width

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone, title_lines
from _plots_shared import SAMPLE_COUNTS, check_sample_count_refused

P = ScaraParams()
P5 = P.with_payload(5.0)


def _closed_form(theta2, r: ScaraParams):
    """B11, B12, B22 of the chapter's hand derivation (eq-dyn-B11, eq-dyn-B12), from the parameters alone."""
    c2 = np.cos(theta2)
    kr, im = r.k_r, r.I_m
    coupling = r.a1 * (r.m_l2 * r.l2 + r.m3 * r.a2)
    b22 = r.I_l2 + r.m_l2 * r.l2 ** 2 + r.m3 * r.a2 ** 2 + r.I_l4 + kr[1] ** 2 * im[1] + im[2] + im[3]
    b12 = r.I_l2 + r.m_l2 * r.l2 ** 2 + r.m3 * r.a2 ** 2 + r.I_l4 + kr[1] * im[1] + im[2] + im[3] + coupling * c2
    b11 = (r.I_l1 + r.m_l1 * r.l1 ** 2 + kr[0] ** 2 * im[0] + r.I_l2 + r.m_l2 * (r.a1 ** 2 + r.l2 ** 2)
           + r.m3 * (r.a1 ** 2 + r.a2 ** 2) + r.I_l4 + im[1] + im[2] + im[3] + 2 * coupling * c2)
    return np.array([b11, b12, np.full_like(c2, b22)])


# ----------------------------------------------------------------------------------------------- window_max
def test_window_max_keeps_every_peak_of_an_alternating_series():
    # a residual that alternates from one sample to the next: large on odd samples, small on even ones
    n, size = 23, 5
    t = 0.001 * np.arange(n)
    y = np.where(np.arange(n) % 2, 1e-10 * (1 + np.arange(n)), -1e-13)
    tt, peak = window_max(t, y, size)
    # windows [0, 5), [5, 10), [10, 15), [15, 23): the last one takes the 3 samples left over
    bounds = [(0, 5), (5, 10), (10, 15), (15, 23)]
    assert len(tt) == len(peak) == len(bounds)
    for (a, b), tk, pk in zip(bounds, tt, peak):
        assert pk == max(abs(v) for v in y[a:b])
        assert math.isclose(tk, 0.5 * (t[a] + t[b - 1]))


def test_window_max_of_a_short_series_is_one_window_and_zeros_sit_on_the_log_floor():
    tt, peak = window_max(np.arange(4.0), np.zeros(4), 10)
    assert tt.tolist() == [1.5] and peak.tolist() == [LOG_FLOOR]
    tt, peak = window_max(np.arange(10.0), np.arange(10.0), 10)
    assert tt.tolist() == [4.5] and peak.tolist() == [9.0]


@pytest.mark.parametrize("size", [0, 2.5, "10", True, MAX_POINTS + 1])
def test_window_max_refuses_a_bad_window(size):
    with pytest.raises(ScaraError, match="size"):
        window_max(np.arange(5.0), np.arange(5.0), size)


def test_window_max_refuses_series_of_different_lengths():
    with pytest.raises(ScaraError, match="same length"):
        window_max(np.arange(5.0), np.arange(4.0), 2)


# ------------------------------------------------------------------------------------------- energy figure
@pytest.fixture(scope="module")
def drop():
    run = simulate(TorqueController(), plant=P5, duration=0.2, q0=[0.6, -2.6, 0.0, 0.0])
    return run, run.energy()


def test_energy_residual_is_one_line_of_window_maxima(drop):
    run, energy = drop
    fig = energy_figure(run.t, energy, window=10)
    resid = fig.data[-1]
    balance = np.abs(np.asarray(energy["balance"]))
    # the residual of the cumulative Simpson rule alternates between samples: drawn sample by sample it is a band
    assert np.any(np.diff(np.sign(np.diff(balance[1:]))) != 0)
    # one point per window of 10 samples (the last one takes the remainder), each the window's largest |residual|
    n_windows = len(run.t) // 10
    assert len(resid.x) == len(resid.y) == n_windows
    for k in range(n_windows):
        lo, hi = 10 * k, (10 * (k + 1) if k < n_windows - 1 else len(run.t))
        assert math.isclose(resid.y[k], max(balance[lo:hi].max(), LOG_FLOOR), rel_tol=1e-6)   # float32 data
    assert resid.yaxis == "y2" and resid.mode == "lines"


def test_energy_residual_axis_is_a_log_axis_of_whole_decades_with_a_short_title(drop):
    run, energy = drop
    fig = energy_figure(run.t, energy, window=10)
    ax = fig.layout.yaxis2
    assert ax.type == "log" and ax.dtick == 1
    lo, hi = ax.range
    assert lo == int(lo) and hi == int(hi) and hi - lo >= 1
    peak = np.asarray(fig.data[-1].y, float)
    assert 10 ** lo <= peak.min() and peak.max() <= 10 ** hi
    # the y title fits the height of its panel (13 px font; the plot area is what the margins leave)
    plot_px = fig.layout.height - fig.layout.margin.t - fig.layout.margin.b
    panel_px = plot_px * (ax.domain[1] - ax.domain[0])
    assert _text_width(ax.title.text, 13) <= panel_px, (ax.title.text, panel_px)
    assert "(J)" in ax.title.text


def test_energy_figure_reads_on_a_laptop_and_a_phone(drop):
    run, energy = drop
    fig = energy_figure(run.t, energy)
    check_reads_on_a_laptop_and_a_phone("energy", fig)
    check_axis_titles_with_units("energy", fig)


def test_energy_figure_refuses_a_bad_window_before_any_work():
    with pytest.raises(ScaraError, match="window"):
        energy_figure(None, {}, window=0)


# ------------------------------------------------------------------------------- inertia against the elbow
ELBOW = np.arange(-180.0, 181.0, 15.0)
MASSES = [0.0, 5.0, 20.0]


@pytest.fixture(scope="module")
def elbow_figure():
    return inertia_slider_figure(ELBOW, MASSES, q=[0.7, 0.0, 0.3, -1.1], active=1)


def test_inertia_slider_steps_match_the_closed_form(elbow_figure):
    steps = elbow_figure.layout.sliders[0].steps
    assert [s.label for s in steps] == ["0", "5", "20"]
    for m, step in zip(MASSES, steps):
        expected = _closed_form(np.radians(ELBOW), P.with_payload(m))
        drawn = np.array(step.args[0]["y"], float)
        # the steps carry 5 significant digits: a relative rounding error of at most 5e-5
        assert np.allclose(drawn, expected, rtol=5e-5, atol=0), m
        assert list(step.args[2]) == [0, 1, 2] and m == float(step.label)
        assert f"payload {m:g} kg" in step.args[1]["title.text"]


def test_inertia_slider_opens_at_the_active_mass_on_one_y_range(elbow_figure):
    fig = elbow_figure
    assert [t.name for t in fig.data] == ["B11", "B12", "B22"]
    expected = _closed_form(np.radians(ELBOW), P5)
    for k, trace in enumerate(fig.data):
        assert np.allclose(np.asarray(trace.x, float), ELBOW)
        assert np.allclose(np.asarray(trace.y, float), expected[k], rtol=1e-6, atol=0)    # float32 data
    assert fig.layout.sliders[0].active == 1 and "payload 5 kg" in fig.layout.title.text
    every = np.concatenate([_closed_form(np.radians(ELBOW), P.with_payload(m)).ravel() for m in MASSES])
    lo, hi = fig.layout.yaxis.range
    assert lo < every.min() and every.max() < hi
    # B22 does not depend on the elbow, B11 and B12 are largest stretched
    assert np.ptp(np.asarray(fig.data[2].y, float)) == 0
    stretched = int(np.flatnonzero(ELBOW == 0.0)[0])
    assert int(np.argmax(fig.data[0].y)) == stretched and int(np.argmax(fig.data[1].y)) == stretched


def test_inertia_slider_figure_reads_on_a_laptop_and_a_phone(elbow_figure):
    check_reads_on_a_laptop_and_a_phone("inertia_elbow", elbow_figure)
    check_axis_titles_with_units("inertia_elbow", elbow_figure)
    for step in elbow_figure.layout.sliders[0].steps:
        assert all(len(line) <= 45 for line in title_lines(step.args[1]["title.text"]))


@pytest.mark.parametrize("angles, masses, active, what", [
    (np.zeros(1), [5.0], 0, "elbow angles"),
    (np.zeros(2002), [5.0], 0, "elbow angles"),
    (np.zeros(10), np.zeros(MAX_STEPS + 1), 0, "payload masses"),
    (np.zeros(1000), np.zeros(101), 0, "samples per curve"),
    (np.zeros(10), [5.0], 1, "active"),
])
def test_inertia_slider_figure_refuses_sizes_beyond_its_limits(angles, masses, active, what):
    with pytest.raises(ScaraError, match=what):
        inertia_slider_figure(angles, masses, active=active)


def test_inertia_slider_figure_refuses_a_configuration_of_the_wrong_shape():
    with pytest.raises(ScaraError, match="q"):
        inertia_slider_figure(ELBOW, MASSES, q=[0.0, 0.0, 0.5])


# ------------------------------------------------------------------------------------------------------ sample counts
@pytest.mark.parametrize("build, args, count", [
    ("torque_terms_figure", (None, {}), "target"), ("payload_torque_figure", (None, {}), "target"),
    ("payload_slider_figure", (None, {}), "target"), ("energy_figure", (None, {}), "target"),
])
@pytest.mark.parametrize("value, names", SAMPLE_COUNTS)
def test_dynamics_figures_refuse_sample_counts_beyond_the_limit_before_any_work(build, args, count, value, names):
    check_sample_count_refused(build, args, count, value, names)


def test_torque_terms_title_follows_the_dropdown():
    from _plots_shared import run_figures
    fig = run_figures()["dynamics_terms"]
    (menu,) = fig.layout.updatemenus
    titles = [b.args[1]["title.text"] for b in menu.buttons]
    assert len(set(titles)) == len(titles) == 4
    assert all(b.label in t for b, t in zip(menu.buttons, titles))
    assert fig.layout.title.text == titles[0]
