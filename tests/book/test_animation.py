"""The animations of chapters 3, 4, 6 and of the introduction (scara.plots.animation): frames with Play/Pause
buttons and a slider whose steps match the frames, a frame count and page weight within limits, a last frame
at the motion's end, and bad arguments refused with a ScaraError. Fast: no browser."""
from __future__ import annotations

import numpy as np
import pytest

import scara
from scara import plots
from scara.plots.animation import MAX_FRAMES, frame_indices, magnification_text

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone

#: the page weight of one animation (the built page must stay under 3 MB)
MAX_JSON = 1_500_000


@pytest.fixture(scope="module")
def traj():
    return scara.reference_trajectory()


@pytest.fixture(scope="module")
def animations(traj):
    clik_runs = [scara.clik(traj, m) for m in ("inverse", "transpose", "pseudoinverse")] + [scara.clik2(traj)]
    plant = scara.ScaraParams().with_payload(5.0)
    ref = clik_runs[-1]
    ctl_runs = [scara.simulate(scara.RobustController(), traj, plant, joint_reference=ref),
                scara.simulate(scara.AdaptiveController(), traj, plant, joint_reference=ref),
                scara.simulate(scara.OperationalSpaceController(), traj, plant)]
    return {
        "trajectory": (plots.trajectory_animation(traj), traj.x[-1, :2], [3]),
        "course": (plots.course_animation(traj), traj.x[-1, :3], None),
        "clik": (plots.clik_animation(clik_runs), None, clik_runs),
        "control": (plots.control_animation(ctl_runs, true_mass=5.0), None, ctl_runs),
    }


@pytest.mark.parametrize("name", ["trajectory", "course", "clik", "control"])
def test_frames_buttons_slider(animations, name):
    fig = animations[name][0]
    frames = fig.frames
    assert 10 <= len(frames) <= MAX_FRAMES
    labels = [b.label for b in fig.layout.updatemenus[0].buttons]
    assert any("Play" in s for s in labels) and any("Pause" in s for s in labels)
    assert fig.layout.updatemenus[0].buttons[0].method == "animate"
    steps = fig.layout.sliders[0].steps
    assert len(steps) == len(frames)
    assert [s.args[0][0] for s in steps] == [f.name for f in frames]
    # only the changing traces are carried by a frame
    for f in frames:
        assert f.traces is not None and len(f.traces) == len(f.data) < len(fig.data)
    assert len(fig.to_json()) < MAX_JSON


def test_play_controls_readout_is_painted():
    """The slider's readout (the time) is written in an opaque colour: the slider's own font, which it would
    inherit, is transparent so that the step labels (one per frame) are not drawn."""
    slider = plots.animation.play_controls([0.0, 0.1, 0.2])["sliders"][0]
    assert slider["font"]["color"] == "rgba(0,0,0,0)"
    colour = slider["currentvalue"]["font"]["color"]
    assert colour.startswith("#") and len(colour) == 7


#: the buttons and the slider take 165 px under the plot: a single plot gets 80 px more than the default 560
@pytest.mark.parametrize("name, max_height", [("trajectory", 640), ("course", 640), ("clik", 780),
                                              ("control", 780)])
def test_reading_rules(animations, name, max_height):
    fig = animations[name][0]
    check_reads_on_a_laptop_and_a_phone(name, fig, max_height=max_height)
    check_axis_titles_with_units(name, fig)


def test_frame_rule(traj):
    idx = frame_indices(traj.t, traj.x)
    gaps = np.diff(traj.t[idx])
    assert gaps.min() >= 0.1 - 1.5e-3 and gaps.max() <= 1.0 + 1.5e-3
    v = np.linalg.norm(np.gradient(traj.x[:, :3], traj.dt, axis=0), axis=1)
    fast = v[idx[:-1]] >= 0.5 * v.max()
    assert fast.any() and np.all(gaps[fast] <= 0.1 + 1.5e-3)  # >= 10 frames a second where the motion is fast
    assert idx[0] == 0 and idx[-1] == traj.t.size - 1


def test_last_frame_is_the_end(animations, traj):
    fig, end, _ = animations["trajectory"]
    last = fig.frames[-1]
    tool = last.data[list(last.traces).index(3)]
    assert np.allclose([tool.x[0], tool.y[0]], end, atol=1e-4)
    fig, end, _ = animations["course"]
    arm = fig.frames[-1].data[-1]
    assert np.allclose([arm.x[-1], arm.y[-1], arm.z[-1]], end, atol=1e-4)
    for name in ("clik", "control"):
        fig, _, runs = animations[name]
        last = fig.frames[-1]
        # the arm traces of the last frame end at each run's final tool position
        for j, r in enumerate(runs):
            arm = last.data[2 * j]
            assert np.allclose([arm.x[-1], arm.y[-1]], r.x[-1, :2], atol=1e-4)


def test_payload_marker_reaches_the_estimate(animations):
    fig, _, runs = animations["control"]
    marker = fig.frames[-1].data[-1]
    assert np.isclose(marker.y[0], runs[1].payload_estimate[-1], rtol=1e-3)


def test_magnification_text():
    assert magnification_text(1.0) == "1" and magnification_text(20.0) == "20"
    assert magnification_text(1e6) == "10⁶" and magnification_text(2e5) == "2·10⁵"


@pytest.mark.parametrize("kwargs", [dict(fast=0.0), dict(fast=-1), dict(rest=0.05), dict(fast="0.1"),
                                    dict(fast=True), dict(fast=float("nan"))])
def test_bad_frame_settings(traj, kwargs):
    with pytest.raises(scara.ScaraError):
        plots.trajectory_animation(traj, **kwargs)


def test_bad_arguments(traj):
    with pytest.raises(scara.ScaraError):
        plots.trajectory_animation("not a trajectory")
    with pytest.raises(scara.ScaraError):
        plots.course_animation(None)
    with pytest.raises(scara.ScaraError):
        plots.clik_animation([])
    with pytest.raises(scara.ScaraError):
        plots.clik_animation(["nope"])
    with pytest.raises(scara.ScaraError):
        plots.control_animation([traj])
    with pytest.raises(scara.ScaraError):
        frame_indices(traj.t, traj.x, fast=0.001)  # more than MAX_FRAMES frames
    with pytest.raises(scara.ScaraError):
        frame_indices(traj.t[:10], traj.x)
    with pytest.raises(scara.ScaraError):
        frame_indices(traj.t, traj.x, dense=(0.0, 1.0))


def test_a_coarsely_sampled_motion_has_a_frame_at_every_sample(traj):
    """A motion sampled more coarsely than ``fast`` (here every 0.5 s against fast = 0.1 s) is animated with one
    frame per sample, not refused for asking too many frames."""
    coarse = slice(None, None, int(round(0.5 / (traj.t[1] - traj.t[0]))))
    t, x = traj.t[coarse], traj.x[coarse]
    assert t.size < MAX_FRAMES
    idx = frame_indices(t, x, fast=0.1)
    assert idx[0] == 0 and idx[-1] == t.size - 1 and np.all(np.diff(idx) >= 1)
    gaps = np.diff(t[idx])
    assert gaps.max() <= 1.0 + 1e-9  # never more than ``rest`` = 1 s apart
    moving = np.linalg.norm(np.diff(x[:, :3], axis=0), axis=1) > 0
    assert np.isclose(gaps.min(), 0.5) and moving.any()  # while the tool moves, a frame at every sample


def test_too_many_frames_message_is_true(traj):
    with pytest.raises(scara.ScaraError, match=rf"fast = 0.001 s asks for more than {MAX_FRAMES} frames"):
        frame_indices(traj.t, traj.x, fast=0.001)
