"""The figures of scara.plots.interaction, built as chapter 7 builds them (shorter runs): each draws its data (the
normal force and the penetration of every run, the sweep's formula and runs one gain per slider step, the peg
where peg_frames puts it with the force arrow scaled as stated), reads on a laptop and a phone with a unit on
every axis, plays as an animation (Play/Pause, a step per frame, only the moving traces in a frame) and refuses
bad input with a ScaraError before any work."""
from __future__ import annotations

import numpy as np
import pytest

import scara
from scara import plots
from scara.interaction import (ComplianceController, ForceController, ForceSensor, Surface, approach_run,
                               peg_frames, peg_in_hole, stiffness_sweep)
from scara.plots.interaction import INTERACTION_COLOURS, INTERACTION_DASHES

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone, title_lines

MAX_JSON = 1_500_000


@pytest.fixture(scope="module")
def runs():
    s, sensor = Surface(), ForceSensor()
    return {"compliance": approach_run(ComplianceController(), s, sensor, move=0.5, hold=0.5),
            "force": approach_run(ForceController(), s, sensor, move=0.5, hold=1.0)}


@pytest.fixture(scope="module")
def sweep():
    return stiffness_sweep([3000.0, 9000.0], [5e3, 4e4], depth=2e-3, points=21)


@pytest.fixture(scope="module")
def frames():
    return peg_frames(peg_in_hole((0.0, 1.5e-3)), every=50)


def test_contact_force_figure_draws_force_and_penetration_of_each_run(runs):
    fig = plots.contact_force_figure(runs, target=10.0)
    check_reads_on_a_laptop_and_a_phone("contact", fig)
    check_axis_titles_with_units("contact", fig)
    for name, r in runs.items():
        force, pen = [t for t in fig.data if t.legendgroup == name]
        idx = np.unique(np.linspace(0, len(r.t) - 1, 1000).round().astype(int)) if len(r.t) > 1000 else np.arange(len(r.t))
        assert np.allclose(force.y, r.normal_force[idx], atol=1e-4) and force.yaxis in (None, "y")
        assert np.allclose(pen.y, 1e3 * (0.3 - r.x[idx, 2]), atol=1e-4) and pen.yaxis == "y2"
        assert (force.line.color, force.line.dash) == (INTERACTION_COLOURS[name], INTERACTION_DASHES[name])
    target = fig.data[-1]
    assert list(target.y) == [10.0, 10.0] and target.line.dash == "dot"
    assert fig.layout.yaxis.title.text == "−h_z (N)" and fig.layout.yaxis2.title.text == "z_s − p_z (mm)"
    with pytest.raises(scara.ScaraError, match=r"points = 1 "):
        plots.contact_force_figure(None, points=1)
    with pytest.raises(scara.ScaraError, match="non-empty dict"):
        plots.contact_force_figure({})
    with pytest.raises(scara.ScaraError, match="needs runs of simulate_contact"):
        plots.contact_force_figure({"a": object()})
    with pytest.raises(scara.ScaraError, match=r"len\(runs\) = 9"):
        plots.contact_force_figure({str(k): None for k in range(9)})


def test_stiffness_slider_shows_formula_and_runs_one_gain_per_step(sweep):
    fig = plots.stiffness_slider_figure(sweep, depth=2e-3)
    check_reads_on_a_laptop_and_a_phone("stiffness", fig)
    check_axis_titles_with_units("stiffness", fig)
    steps = fig.layout.sliders[0].steps
    assert [s.label for s in steps] == ["3000", "9000"] and len(fig.data) == 8
    for i, s in enumerate(steps):
        assert s.args[0]["visible"] == [4 * i <= j < 4 * (i + 1) for j in range(8)]
        assert "K_P,z = " + steps[i].label + " N/m" in s.args[1]["title.text"]
        assert s.args[1]["yaxis.range"] == [0.0, pytest.approx(1.15 * sweep["gains"][i] * 2e-3)]
        assert all(len(ln) <= 45 for ln in title_lines(s.args[1]["title.text"]))
        formula, sim, stiff, soft = fig.data[4 * i: 4 * (i + 1)]
        assert np.allclose(formula.y, sweep["dense_formula"][i], atol=1e-4)
        assert np.allclose(sim.y, sweep["simulated"][i], atol=1e-4) and sim.mode == "markers"
        assert list(stiff.y) == [pytest.approx(sweep["gains"][i] * 2e-3)] * 2
        assert np.allclose(soft.y, np.asarray(soft.x) * 2e-3, rtol=1e-3)
    assert [t.visible for t in fig.data] == [True] * 4 + [False] * 4
    assert fig.layout.xaxis.type == "log"
    with pytest.raises(scara.ScaraError, match="must be the dict of stiffness_sweep"):
        plots.stiffness_slider_figure({"gains": [1.0]}, depth=2e-3)


def test_peg_animation_plays_and_puts_the_peg_where_the_run_was(frames):
    fig = plots.peg_animation(frames, scale=0.5)
    check_reads_on_a_laptop_and_a_phone("peg", fig, max_height=660)
    check_axis_titles_with_units("peg", fig)
    labels = [b.label for b in fig.layout.updatemenus[0].buttons]
    assert any("Play" in s for s in labels) and any("Pause" in s for s in labels)
    # the filled peg moves only on a full redraw
    assert fig.layout.updatemenus[0].buttons[0].args[1]["frame"]["redraw"] is True
    steps = fig.layout.sliders[0].steps
    assert len(fig.frames) == len(frames["t"]) == len(steps)
    assert [s.args[0][0] for s in steps] == [f.name for f in fig.frames]
    for f in fig.frames:
        assert list(f.traces) == [1, 2, 4] and len(f.data) == 3 < len(fig.data)
    # the peg's axis at the run's offset along y (the start's direction), its end at the run's height
    k = len(fig.frames) // 2
    peg, arrow, _ = fig.frames[k].data
    s_mm = 1e3 * (frames["tip"][k, 1] - frames["centre"][1])
    z_mm = 1e3 * (frames["tip"][k, 2] - frames["height"])
    assert 0.5 * (min(peg.x) + max(peg.x)) == pytest.approx(s_mm, abs=1e-3) and min(peg.y) == pytest.approx(z_mm, abs=1e-3)
    assert max(peg.x) - min(peg.x) == pytest.approx(1e3 * 2 * frames["peg_radius"], abs=1e-3)
    assert arrow.y[1] - arrow.y[0] == pytest.approx(0.5 * -frames["force"][k, 2], abs=2e-3)
    walls = fig.data[0]
    R = 1e3 * frames["hole_radius"]
    assert sorted(set(np.round(walls.x, 6)))[1:3] == [pytest.approx(-R), pytest.approx(R)] and min(walls.y) == pytest.approx(-1e3 * (frames["height"] - frames["bottom"]))
    assert len(fig.to_json()) < MAX_JSON
    with pytest.raises(scara.ScaraError, match="must be the dict of peg_frames"):
        plots.peg_animation({"t": [0.0]})
    with pytest.raises(scara.ScaraError, match="scale = -1"):
        plots.peg_animation(frames, scale=-1)
    one = dict(frames, t=frames["t"][:1])
    with pytest.raises(scara.ScaraError, match="the frames = 1"):
        plots.peg_animation(one)
