"""The figures of scara.plots.clik written for the exercises of chapter 4: the gain sweeps (a two-line title that
clears the legend, the numbers of each step against fresh runs), the pseudo-inverse runs with a relaxed component,
the text of a length, and the sample counts every CLIK figure refuses before any work. The reading rules of these
figures are checked with every figure's in test_plots_layout.py."""
from __future__ import annotations

import math

import numpy as np
import pytest

from scara import ScaraError, plan_path, pose
from scara._clik import SEED_K, clik, clik2, second_order_gains, transpose_stability
from scara.errors import UnstableError
from scara.plots._common import thin
from scara.plots.clik import gain_steps_figure, length_text, relaxed_figure

from _figure_rules import title_lines
import _plots_shared
from _plots_shared import P, SAMPLE_COUNTS, check_sample_count_refused, titles_by_state


def _max_error_after_settle(run) -> float:
    """Largest position error after the first 0.1 s, from the run's own arrays (not from its summary)."""
    keep = run.t >= run.t[0] + 0.1 - 1e-12
    return float(np.linalg.norm(run.e[keep][:, :3][:, run.kept[:3]], axis=1).max())


# -------------------------------------------------------------------------------------------------------- length_text
@pytest.mark.parametrize("metres, text", [
    (3.03e-8, "30.3 nm"), (4.7e-3, "4.70 mm"), (2.2449e-3, "2.24 mm"), (0.638, "0.638 m"), (0.3, "0.300 m"),
    (1e-6, "1.00 µm"), (999.6e-9, "1.00 µm"), (0.9996e-3, "1.00 mm"), (0.09996, "0.100 m"), (-2e-3, "-2.00 mm"),
    (0.0, "0 m"), (12.0, "12.0 m"),
])
def test_length_text_picks_the_unit_after_rounding(metres, text):
    assert length_text(metres) == text


# -------------------------------------------------------------------------------------------------------- gain sweeps
@pytest.fixture(scope="module")
def gain_figure(ref):
    return _plots_shared.gain_figure(ref)


@pytest.fixture(scope="module")
def uniform(ref):
    return _plots_shared.uniform_gains(ref)


@pytest.fixture(scope="module")
def relaxed(ref):
    return _plots_shared.relaxed_runs(ref)


def test_gain_slider_titles_keep_to_two_lines_and_state_each_runs_largest_error(ref, gain_figure):
    limit = transpose_stability(ref).scale_limit
    for label, title in titles_by_state(gain_figure).items():
        lines = title_lines(title)
        assert len(lines) == 2 and all(len(ln) <= 45 for ln in lines), title
        scale = float(label)
        assert lines[0] == f"K = {scale:.2f} × seed, largest ‖e_p‖"
        inv = clik(ref, "inverse", scale * np.asarray(SEED_K))
        assert f"inverse: {length_text(_max_error_after_settle(inv))}" in lines[1]
        if scale < limit:
            tra = clik(ref, "transpose", scale * np.asarray(SEED_K))
            assert f"transpose: {length_text(_max_error_after_settle(tra))}" in lines[1]
        else:
            assert "transpose: unstable" in lines[1]
    # the figure opens on the seed, with room for its two-line title and its legend
    assert gain_figure.layout.title.text.startswith("K = 1.00 × seed")


def test_gain_steps_figure_runs_each_gain_and_names_the_refused_ones(ref, uniform):
    st, k_lim, ks, fig = uniform
    # the limit read from the singular values of J_A along the path (every 5 ms) is transpose_stability's
    assert abs(k_lim * st.mu_max * ref.dt / 2 - 1) < 1e-4
    titles = titles_by_state(fig)
    below = clik(ref, "transpose", ks["below"] * np.ones(4))
    assert titles["below"] == f"Jacobian transpose, k: below<br>largest ‖e_p‖: {length_text(_max_error_after_settle(below))}"
    with pytest.raises(UnstableError):
        clik(ref, "transpose", ks["above"] * np.ones(4))
    assert titles["above"] == "Jacobian transpose, k: above<br>refused: past the stability limit"
    # one trace per step, each step shows its own; the refused step has no curve
    assert [len(t.x) > 0 for t in fig.data] == [True, False]
    steps = fig.layout.sliders[0].steps
    assert [list(s.args[0]["visible"]) for s in steps] == [[True, False], [False, True]]
    assert [t.visible for t in fig.data] == [True, False]
    # the drawn curve is the upper envelope of the run's error: its peak is the run's peak
    assert math.isclose(float(np.max(fig.data[0].y)), float(below.position_error.max()), rel_tol=1e-6)


def test_gain_steps_figure_second_order_uses_k_squared_and_two_k(ref):
    gains = {"400": [400.0, 400.0, 400.0, 100.0], "1990": [400.0, 400.0, 1990.0, 100.0],
             "2010": [400.0, 400.0, 2010.0, 100.0]}
    fig = gain_steps_figure(ref, gains, "second_order", prefix="K_z = ", suffix=" s⁻¹")
    titles = titles_by_state(fig)
    for label in ("400", "1990"):
        K = np.array(gains[label])
        run = clik2(ref, K**2, 2 * K)                       # K_P = K^2, K_D = 2 K, written out
        assert np.allclose(second_order_gains(K), (K**2, 2 * K))
        assert titles[label] == (f"second order, K_z = {label} s⁻¹<br>"
                                 f"largest ‖e_p‖: {length_text(_max_error_after_settle(run))}")
    # the double pole 1 - K_z T leaves the unit circle at K_z = 2 / T = 2000 1/s
    assert titles["2010"].endswith("refused: past the stability limit")
    assert fig.layout.sliders[0].currentvalue.suffix == " s⁻¹"


@pytest.mark.parametrize("kwargs, match", [
    (dict(gains={"a": SEED_K}, method="pseudoinverse"), "use 'inverse', 'transpose' or 'second_order'"),
    (dict(gains={f"{k}": SEED_K for k in range(26)}), "1 to 25 gain vectors"),
    (dict(gains={}), "1 to 25 gain vectors"),
    (dict(gains={"a": [400.0, 400.0, 400.0]}), r"gains\['a'\] must have shape \(4,\)"),
    (dict(gains={"a": [400.0, 400.0, np.nan, 100.0]}), "not finite"),
    (dict(gains={f"{k}": SEED_K for k in range(20)}, points=6000), "<= 100000"),
])
def test_gain_steps_figure_refuses_bad_requests_before_any_run(kwargs, match):
    short = plan_path([[0.3, 0.2, 0.5], [0.45, 0.1, 0.45]], durations=[0.5], total=0.6)
    with pytest.raises(ScaraError, match=match):
        gain_steps_figure(short, **kwargs)


# ------------------------------------------------------------------------------------------------- relaxed components
def test_relaxed_figure_draws_each_relaxed_component_and_its_price(relaxed):
    runs, inv, fig = relaxed
    buttons = fig.layout.updatemenus[0].buttons
    assert [b.label for b in buttons] == ["x relaxed", "y relaxed", "z relaxed"]
    for k, (b, r) in enumerate(zip(buttons, runs)):
        c = "xyz"[k]
        w_run, w_inv, drift = [t for t, v in zip(fig.data, b.args[0]["visible"]) if v]
        idx = thin(len(r.t), 1000)
        assert np.array_equal(drift.x, np.float32(r.t[idx]))
        # the drift x_e - x_d of the relaxed component, from the pose the run's joints reach
        x_e = np.array([pose(q) for q in r.q[idx]])
        assert np.allclose(np.asarray(drift.y, float), x_e[:, k] - r.x_d[idx, k], atol=1e-6)
        # w = a1 a2 |sin theta2| along the run
        assert np.allclose(np.asarray(w_run.y, float), P.a1 * P.a2 * np.abs(np.sin(r.q[idx, 1])), atol=1e-6)
        assert w_inv.name == "w · Jacobian inverse" and w_inv.line.dash == "dash"
        mean_w = float(np.mean(P.a1 * P.a2 * np.abs(np.sin(r.q[:, 1]))))
        title = b.args[1]["title.text"]
        assert title == (f"{c} relaxed: mean w = {mean_w:.3f} m²<br>"
                         f"largest drift of {c}: {length_text(np.abs(r.e[:, k]).max())}")
        assert b.args[1]["yaxis2.title.text"] == f"{c}_e − {c}_d (m)"
    # relaxing z frees only the quill, which the null-space term never moves: w is the inverse's
    assert np.allclose(runs[2].w, inv.w, atol=1e-12)


def test_relaxed_figure_needs_pseudoinverse_runs(relaxed):
    runs, inv, _ = relaxed
    with pytest.raises(ScaraError, match="pseudo-inverse runs"):
        relaxed_figure([inv])


# ------------------------------------------------------------------------------------------------------ sample counts
@pytest.mark.parametrize("build, args, count", [
    ("clik_joints_figure", (None,), "points"), ("clik_error_figure", (None,), "points"),
    ("error_components_figure", (None,), "points"), ("manipulability_figure", (None,), "points"),
    ("drift_figure", (None,), "points"), ("damping_figure", ({},), "points"),
    ("second_order_figure", (None,), "points"), ("gain_slider_figure", (None,), "points"),
])
@pytest.mark.parametrize("value, names", SAMPLE_COUNTS)
def test_clik_figures_refuse_sample_counts_beyond_the_limit_before_any_work(build, args, count, value, names):
    check_sample_count_refused(build, args, count, value, names)
