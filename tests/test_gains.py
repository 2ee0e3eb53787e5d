"""The one gain check of the package (scara/gains.py): forms accepted, the two rules, the messages."""
import numpy as np
import pytest
from hypothesis import given, strategies as st

from scara.errors import ScaraError, ShapeError
from scara.gains import gain_vector

LABELS = ("x", "y", "z", "phi")


@given(st.floats(min_value=1e-9, max_value=1e9))
def test_number_vector_and_diagonal_matrix_agree(k):
    v = np.array([k, 2 * k, 3 * k, 4 * k])
    assert np.array_equal(gain_vector(k, "K"), np.full(4, k))
    assert np.array_equal(gain_vector(v, "K"), v)
    assert np.array_equal(gain_vector(np.diag(v), "K"), v)


def test_result_is_a_fresh_float_vector():
    src = np.array([1.0, 2.0, 3.0, 4.0])
    out = gain_vector(src, "K")
    out[0] = 99.0
    assert src[0] == 1.0 and out.dtype == float
    assert np.array_equal(gain_vector([1, 2, 3, 4], "K"), src)


def test_default_and_other_sizes():
    assert np.array_equal(gain_vector(None, "K", default=(400, 400, 400, 100)), [400, 400, 400, 100])
    assert np.array_equal(gain_vector(2.0, "K_pi", 13), np.full(13, 2.0))
    assert np.array_equal(gain_vector(0.05, "max_error", 1), [0.05])


@pytest.mark.parametrize("value, match", [
    ("fast", "a number"), (None, "a number"), (True, "a number"), ([1, 2, 3], r"shape \(3,\)"),
    (np.ones((3, 3)), r"shape \(3, 3\)"), (np.ones((4, 4)), "largest off-diagonal entry is 1"),
    ([[1, 2], [3, 4]], r"shape \(2, 2\)"), ({"a": 1}, "a number"),
])
def test_shapes_refused(value, match):
    with pytest.raises(ShapeError, match=match):
        gain_vector(value, "K")


def test_positive_rule_names_the_entry_and_the_limit():
    with pytest.raises(ScaraError, match=r"K must be positive definite: its z entry is 0 \(every entry must be > 0\)"):
        gain_vector([400, 400, 0, 100], "K", labels=LABELS)
    with pytest.raises(ScaraError, match=r"K_P\[1\] = -2 .*> 0"):
        gain_vector([1, -2, 3, 4], "K_P")


def test_nonnegative_rule_accepts_zero_refuses_negative():
    assert np.array_equal(gain_vector([0, 1, 0, 1], "K_D", rule="nonnegative"), [0, 1, 0, 1])
    with pytest.raises(ScaraError, match=r"K_D\[3\] = -1 .*>= 0"):
        gain_vector([0, 1, 0, -1], "K_D", rule="nonnegative")


def test_non_finite_entries():
    with pytest.raises(ScaraError, match=r"finite: its y entry is nan"):
        gain_vector([1, np.nan, 1, 1], "K", labels=LABELS)
    with pytest.raises(ScaraError, match="finite"):
        gain_vector(np.inf, "K")
    assert np.isinf(gain_vector(np.inf, "K_pi", 2, allow_inf=True)).all()
    with pytest.raises(ScaraError, match="finite"):
        gain_vector(np.nan, "K_pi", 2, allow_inf=True)


def test_unknown_rule():
    with pytest.raises(ScaraError, match="rule = 'strict'"):
        gain_vector(1.0, "K", rule="strict")


def test_boolean_gains_are_refused():
    with pytest.raises(ShapeError, match=r"K must be a number, a vector of 4 numbers or a diagonal 4x4 matrix, got "
                                         r"\[True, True, True, True\]"):
        gain_vector([True] * 4, "K")
    assert gain_vector(np.array([1, 2, 3, 4], dtype=object), "K").tolist() == [1.0, 2.0, 3.0, 4.0]
