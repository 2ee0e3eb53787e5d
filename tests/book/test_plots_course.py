"""The course figure of the introduction (scara.plots.course): each slider step moves the arm to the path's position
at that instant (checked through the inverse then the forward kinematics), the scene holds the whole path, and
the counts beyond the figure's limits are refused at once, before any work. ``traj`` is the session's reference
trajectory (tests/conftest.py)."""
from __future__ import annotations

import numpy as np
import pytest

from scara import ScaraError
from scara.plots import course_figure

from _plots_shared import refusal


def test_course_figure_moves_the_arm_along_the_path(traj):
    fig = course_figure(traj, steps=8)
    (sl,) = fig.layout.sliders
    assert len(sl.steps) == 8 and sl.steps[0].label == "0" and sl.steps[-1].label == "70"
    names = [t.name for t in fig.data]
    arm, trail = names.index("arm (Ch. 1, 4)"), names.index("covered")
    for s in sl.steps:
        data, layout, idx = s.args
        assert list(idx) == [trail, arm]
        t = float(s.label)
        k = int(round(t / traj.dt))
        tool = np.array([data["x"][1][-1], data["y"][1][-1], data["z"][1][-1]])
        # the arm's last point is the gripper, at the path's position at that instant (forward kinematics of
        # the inverse kinematics: an independent route through eq. (1.5))
        assert np.allclose(tool, traj.x[k, :3], atol=1e-4), (t, tool, traj.x[k, :3])
        assert np.allclose([data["x"][0][-1], data["y"][0][-1]], traj.x[k, :2], atol=1e-4)
        assert f"t = {t:.0f} s" in layout["title.text"]
    # the scene holds the whole path and the arm's base
    lay = fig.layout.scene
    for ax, c in ((lay.xaxis, 0), (lay.yaxis, 1)):
        assert ax.range[0] <= min(traj.x[:, c].min(), 0.0) and ax.range[1] >= traj.x[:, c].max()


@pytest.mark.parametrize("kwargs, names", [
    (dict(steps=10**6), ("steps = 1000000", "<= 121")),
    (dict(steps=0), ("steps = 0", "1 <= ")),
    (dict(steps=2.5), ("steps = 2.5", "whole number", "between 1 and 121")),
    (dict(steps="36"), ("steps = '36'", "whole number")),
    (dict(points=10**7), ("points = 10000000", "<= 10000")),
])
def test_course_figure_refuses_counts_beyond_its_limits_before_any_work(traj, kwargs, names):
    message = refusal(course_figure, traj, **kwargs)
    for text in names:
        assert text in message


def test_course_figure_with_a_million_steps_is_refused_at_once(traj):
    import time

    from scara.plots import course_figure

    t0 = time.perf_counter()
    with pytest.raises(ScaraError, match=r"steps = 1000000 slider steps is outside the allowed range 1 <= steps <= 121"):
        course_figure(traj, steps=10**6)
    assert time.perf_counter() - t0 < 0.5
    assert len(course_figure(traj, steps=121).layout.sliders[0].steps) == 121  # the limit itself is drawn
