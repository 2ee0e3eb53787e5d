"""The figures of scara.plots.identification (chapter 5's identification section): each draws the data it is given
(the curves read back equal the inputs, to the figures' float32), reads on a laptop and a phone, and refuses
inconsistent inputs and sample counts before any work."""
from __future__ import annotations

import numpy as np
import pytest

from scara import ScaraError, ShapeError
from scara.plots.identification import error_size_figure, excitation_figure, validation_figure

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone
from _plots_shared import SAMPLE_COUNTS, check_sample_count_refused

T = np.linspace(0.0, 10.0, 501)
Q = np.column_stack([np.sin(T), np.cos(T), 0.5 + 0.1 * np.sin(T), T / 10])


def _panel(fig, name, j):
    """The trace ``name`` of panel ``j`` (joint j + 1)."""
    axis = "y" if j == 0 else f"y{j + 1}"
    return next(tr for tr in fig.data if tr.name == name and tr.yaxis == axis)


def test_excitation_figure_draws_each_joint():
    fig = excitation_figure(T, Q, 0.5 * Q, target=1000)
    for j in range(4):
        assert np.allclose(_panel(fig, "optimised", j).y, Q[:, j].astype(np.float32))
        assert np.allclose(_panel(fig, "start of the search", j).y, (0.5 * Q[:, j]).astype(np.float32))
    check_reads_on_a_laptop_and_a_phone("excitation", fig)
    check_axis_titles_with_units("excitation", fig)


def test_validation_figure_draws_measured_and_predicted():
    fig = validation_figure(T, Q, Q + 0.1, Q - 0.1)
    for j in range(4):
        assert np.allclose(_panel(fig, "measured", j).y, Q[:, j].astype(np.float32))
        assert np.allclose(_panel(fig, "identified π̂", j).y, (Q[:, j] + 0.1).astype(np.float32))
        assert np.allclose(_panel(fig, "nominal π", j).y, (Q[:, j] - 0.1).astype(np.float32))
    check_reads_on_a_laptop_and_a_phone("validation", fig)
    check_axis_titles_with_units("validation", fig)


def test_error_size_figure_draws_markers_and_lines():
    d = np.array([10.0, 20.0, 40.0, 80.0])
    errors = {"1 %": 0.01 / np.sqrt(d / 10), "2 %": 0.02 / np.sqrt(d / 10)}
    theory = {k: 1.1 * v for k, v in errors.items()}
    fig = error_size_figure(d, errors, theory)
    for k in errors:
        marks = next(tr for tr in fig.data if tr.name == f"noise {k}")
        line = next(tr for tr in fig.data if tr.name == f"theory {k}")
        assert marks.mode == "markers" and line.mode == "lines"
        assert np.allclose(marks.y, errors[k].astype(np.float32)) and np.allclose(line.y, theory[k].astype(np.float32))
    assert fig.layout.xaxis.type == "log" and fig.layout.yaxis.type == "log"
    check_reads_on_a_laptop_and_a_phone("error size", fig)
    check_axis_titles_with_units("error size", fig)


def test_inconsistent_inputs_are_refused():
    with pytest.raises(ShapeError, match=r"q must have shape \(501, 4\)"):
        excitation_figure(T, Q[:-1])
    with pytest.raises(ShapeError, match="predicted"):
        validation_figure(T, Q, Q[:, :3])
    with pytest.raises(ScaraError, match="same noise levels"):
        error_size_figure([10.0, 20.0], {"1 %": [0.1, 0.05]}, {"2 %": [0.1, 0.05]})
    with pytest.raises(ShapeError):
        error_size_figure([10.0, 20.0], {"1 %": [0.1]}, {"1 %": [0.1, 0.05]})


@pytest.mark.parametrize("build", ["excitation_figure", "validation_figure"])
@pytest.mark.parametrize("value, names", SAMPLE_COUNTS)
def test_sample_counts_are_refused_first(build, value, names):
    args = (T, Q) if build == "excitation_figure" else (T, Q, Q)
    check_sample_count_refused(build, args, "target", value, names)
