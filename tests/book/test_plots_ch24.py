"""Figure builders added or changed for the exercises of chapters 2 and 4: the gain sweeps of chapter 4 (a
two-line title that clears the legend, the numbers of each step against fresh runs), the pseudo-inverse runs
with a relaxed component, and the turn of the base in chapter 2 (ellipses turning rigidly with the arm). Every
figure follows the book's reading rules, and, in Chromium at a phone's and a laptop's width, no slider step or
dropdown entry puts the title over the legend or the legend over the plot."""
from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np
import plotly.io as pio
import pytest

from plotly.offline import get_plotlyjs

from scara import ScaraError, ScaraParams, ikine, jacobian, manipulability, plan_path, pose, velocity_ellipsoid
from scara._clik import SEED_K, clik, clik2, second_order_gains, transpose_stability
from scara.errors import UnstableError
from scara.plots import ellipse_slider_figure
from scara.plots._common import thin
from scara.plots.clik import gain_slider_figure, gain_steps_figure, length_text, relaxed_figure
from scara.plots.manipulability import base_turn_figure, major_axis_angle

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone, title_lines

P = ScaraParams()


def _titles(fig) -> dict:
    """Label of each slider step or dropdown entry -> the title it sets."""
    controls = ([s for sl in fig.layout.sliders for s in sl.steps]
                + [b for m in fig.layout.updatemenus for b in m.buttons])
    return {c.label: c.args[1]["title.text"] for c in controls}


def _max_error_after_settle(run) -> float:
    """Largest position error after the first 0.1 s, from the run's own arrays (not from its summary)."""
    keep = run.t >= run.t[0] + 0.1 - 1e-12
    return float(np.linalg.norm(run.e[keep][:, :3][:, run.kept[:3]], axis=1).max())


# ------------------------------------------------------------------------------------------- length_text
@pytest.mark.parametrize("metres, text", [
    (3.03e-8, "30.3 nm"), (4.7e-3, "4.70 mm"), (2.2449e-3, "2.24 mm"), (0.638, "0.638 m"), (0.3, "0.300 m"),
    (1e-6, "1.00 µm"), (999.6e-9, "1.00 µm"), (0.9996e-3, "1.00 mm"), (0.09996, "0.100 m"), (-2e-3, "-2.00 mm"),
    (0.0, "0 m"), (12.0, "12.0 m"),
])
def test_length_text_picks_the_unit_after_rounding(metres, text):
    assert length_text(metres) == text


# ------------------------------------------------------------------------------------------- chapter 4
@pytest.fixture(scope="module")
def gain_figure(ref):
    return gain_slider_figure(ref, scales=[0.5, 1.0, 4.5])


def test_gain_slider_titles_keep_to_two_lines_and_state_each_runs_largest_error(ref, gain_figure):
    limit = transpose_stability(ref).scale_limit
    for label, title in _titles(gain_figure).items():
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


@pytest.fixture(scope="module")
def uniform(ref):
    """The transpose with K = k I around its limit on the reference, k_lim = 2 / (T sigma_max(J_A)^2)."""
    st = transpose_stability(ref, np.ones(4))
    sigma_max = max(np.linalg.svd(jacobian(q), compute_uv=False).max() for q in ikine(ref.x[::5], elbow=-1))
    k_lim = 2.0 / ref.dt / sigma_max**2
    ks = {"below": 0.97 * k_lim, "above": 1.03 * k_lim}
    fig = gain_steps_figure(ref, {name: k * np.ones(4) for name, k in ks.items()}, "transpose", prefix="k: ")
    return st, k_lim, ks, fig


def test_gain_steps_figure_runs_each_gain_and_names_the_refused_ones(ref, uniform):
    st, k_lim, ks, fig = uniform
    # the limit read from the singular values of J_A along the path (every 5 ms) is transpose_stability's
    assert abs(k_lim * st.mu_max * ref.dt / 2 - 1) < 1e-4
    titles = _titles(fig)
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
    titles = _titles(fig)
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
    (dict(gains={f"{k}": SEED_K for k in range(20)}, points=6000), "limit of 100000"),
])
def test_gain_steps_figure_refuses_bad_requests_before_any_run(kwargs, match):
    short = plan_path([[0.3, 0.2, 0.5], [0.45, 0.1, 0.45]], durations=[0.5], total=0.6)
    with pytest.raises(ScaraError, match=match):
        gain_steps_figure(short, **kwargs)


@pytest.fixture(scope="module")
def relaxed(ref):
    runs = [clik(ref, "pseudoinverse", relaxed=c) for c in ("x", "y", "z")]
    inv = clik(ref, "inverse")
    return runs, inv, relaxed_figure(runs, inv)


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


# ------------------------------------------------------------------------------------------- chapter 2
def _major_by_eigh(q) -> float:
    """Direction (degrees, modulo 180, in (-90, 90]) of the eigenvector of H H^T with the larger eigenvalue, H
    the horizontal block of J_A: the major axis of the velocity ellipse, found without the package's SVD."""
    H = jacobian(q)[:2, :2]
    vals, vecs = np.linalg.eigh(H @ H.T)
    u = vecs[:, int(np.argmax(vals))]
    a = math.degrees(math.atan2(u[1], u[0])) % 180.0
    return a - 180.0 if a > 90.0 else a


def test_major_axis_angle_is_the_top_eigenvector_of_h_h_transpose():
    rng = np.random.default_rng(7)
    for t1, t2 in rng.uniform(-3.0, 3.0, (200, 2)):
        if abs(math.sin(t2)) < 0.05 or abs(math.cos(t2) + 0.2) < 0.05:
            continue  # near-singular or near-round ellipses have no well-defined major axis
        q = np.array([t1, t2, 0.5, 0.0])
        got = major_axis_angle(velocity_ellipsoid(q, rows=(0, 1)))
        assert -90.0 < got <= 90.0
        diff = (got - _major_by_eigh(q) + 90.0) % 180.0 - 90.0
        assert abs(diff) < 1e-7, (q, got)


def test_base_turn_figure_turns_the_ellipses_rigidly_with_the_arm():
    fig = base_turn_figure(theta1_deg=[0, 20, 60], theta2=math.pi / 4)
    steps = fig.layout.sliders[0].steps
    assert [s.label for s in steps] == ["0", "20", "60"]
    w = P.a1 * P.a2 * math.sin(math.pi / 4)
    angles = []
    for s in steps:
        q = np.array([math.radians(float(s.label)), math.pi / 4, 0.5 * P.d0, 0.0])
        data, layout, idx = s.args
        arm_x, arm_y = data["x"][0], data["y"][0]
        assert np.allclose([arm_x[-1], arm_y[-1]], pose(q)[:2], atol=1e-4)          # the arm drawn at q
        line1, line2 = title_lines(layout["title.text"])
        major = _major_by_eigh(q)
        assert line1 == f"θ1 = {float(s.label):.0f}°: w = {w:.3f} m², major axis {major:.1f}°"
        assert math.isclose(manipulability(q), w, rel_tol=1e-12)
        angles.append(major)
        sv = np.linalg.svd(jacobian(q)[:2, :2], compute_uv=False)
        assert line2.startswith(f"σ: {sv[0]:.3f}, {sv[1]:.3f} m/s; 1/σ: {1 / sv[0]:.3g}, {1 / sv[1]:.3g} N")
    # turning theta1 by +d turns the picture by -d seen from above (frame 0 points down)
    for a, b, d in ((angles[0], angles[1], 20.0), (angles[0], angles[2], 60.0)):
        assert abs((b - a + d + 90.0) % 180.0 - 90.0) < 1e-9


@pytest.mark.parametrize("kwargs, error", [
    (dict(theta1_deg=[10.0]), "2 and 61"), (dict(theta1_deg=np.arange(62.0)), "2 and 61"),
    (dict(scale=0.0), "> 0"), (dict(theta2=float("nan")), "not finite"), (dict(theta2="45°"), "an angle in rad"),
])
def test_base_turn_figure_refuses_bad_arguments(kwargs, error):
    with pytest.raises(ScaraError, match=error):
        base_turn_figure(**kwargs)


# ------------------------------------------------------------------------------------------- reading rules
@pytest.fixture(scope="module")
def figures(ref, gain_figure, uniform, relaxed):
    return {
        "clik_gain": gain_figure,
        "clik_uniform": uniform[3],
        "clik_kz": gain_steps_figure(ref, {"400": [400, 400, 400, 100], "2500": [400, 400, 2500, 100]},
                                     "second_order", prefix="K_z = ", suffix=" s⁻¹"),
        "clik_relaxed": relaxed[2],
        "manip_turn": base_turn_figure(),
        "manip_stretch": ellipse_slider_figure([60, 50, 40, 30, 20, 10, 5, 0]),
    }


def test_new_figures_read_on_a_laptop_and_a_phone(figures):
    for name, fig in figures.items():
        check_reads_on_a_laptop_and_a_phone(name, fig)
        check_axis_titles_with_units(name, fig)
        # at most two title lines in every state: a third would run into the legend
        assert all(len(title_lines(t)) <= 2 for t in _titles(fig).values()), name


# In the page: every state of every figure (each slider step, each dropdown entry), the bounding boxes of
# the title, the legend and the plot area.
_BOXES = """async (gd) => {
  const box = (sel) => { const e = gd.querySelector(sel); if (!e) return null;
                         const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]; };
  const states = [];
  const take = (label) => states.push({label, title: box('.gtitle'), legend: box('.legend'), plot: box('.nsewdrag'),
      drawn: gd.data.some(t => t.visible !== false && t.showlegend !== false && t.x && t.x.length > 0)});
  take('start');
  const controls = [...(gd.layout.sliders || []).flatMap(s => s.steps),
                    ...(gd.layout.updatemenus || []).flatMap(m => m.buttons)];
  for (const c of controls) {
    await Plotly.update(gd, c.args[0] || {}, c.args[1] || {}, c.args[2]);
    take(c.label);
  }
  return states;
}"""


def _overlap(a, b) -> bool:
    return a is not None and b is not None and min(a[2], b[2]) - max(a[0], b[0]) > 1 and \
        min(a[3], b[3]) - max(a[1], b[1]) > 1


def test_titles_clear_the_legend_in_every_state_at_phone_and_laptop_width(figures):
    from jupyterlab_driver import ARGS, CHROMIUM, chromium_available

    if not chromium_available():
        pytest.skip(f"Chromium is not installed at {CHROMIUM}")
    sync_playwright = pytest.importorskip("playwright.sync_api").sync_playwright
    divs = "".join(f'<div id="{name}" style="width:100%">'
                   f'{pio.to_html(fig, include_plotlyjs=False, full_html=False, div_id=name + "-plot")}</div>'
                   for name, fig in figures.items())
    with tempfile.TemporaryDirectory() as tmp:
        page = Path(tmp) / "figures.html"
        page.write_text(f"<html><head><meta charset='utf-8'><script>{get_plotlyjs()}</script></head>"
                        f"<body style='margin:8px'>{divs}</body></html>")
        problems = []
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
            for width in (390, 1280):
                pg = browser.new_page(viewport={"width": width, "height": 900})
                pg.goto(page.as_uri())
                pg.wait_for_function("() => Array.from(document.querySelectorAll('.plotly-graph-div'))"
                                     ".every(gd => gd._fullLayout)")
                for name in figures:
                    gd = pg.query_selector(f"#{name}-plot")
                    for st in gd.evaluate(_BOXES):
                        # a legend whenever a curve is drawn (a refused gain draws none, and plotly shows no legend)
                        assert st["title"] and st["plot"] and (st["legend"] or not st["drawn"]), (name, width, st)
                        if _overlap(st["title"], st["legend"]):
                            problems.append(f"{name} at {width} px, {st['label']}: title over legend")
                        if _overlap(st["legend"], st["plot"]):
                            problems.append(f"{name} at {width} px, {st['label']}: legend over plot")
                pg.close()
            browser.close()
    assert not problems, problems
