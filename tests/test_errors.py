"""Tests of scara.errors: every error the package raises is a ``ValueError`` (a caller may catch either)."""
import pytest

from scara import ikine


def test_all_errors_are_value_errors():
    with pytest.raises(ValueError):
        ikine([3.0, 0.0, 0.5, 0.0])


def test_count_flag_index_checks_name_the_value_and_the_limit():
    import numpy as np
    from scara.errors import ScaraError, ShapeError, as_vector, check_count, check_flag, check_index, check_positive
    assert check_count(np.int64(5), "n", 3, 10) == 5
    with pytest.raises(ScaraError, match=r"n = 11 samples is outside the allowed range 3 <= n <= 10"):
        check_count(11, "n", 3, 10, "samples")
    with pytest.raises(ScaraError, match=r"n = 4\.0 must be a whole number \(an int\) of samples, between 3 and 10"):
        check_count(4.0, "n", 3, 10, "samples")
    with pytest.raises(ScaraError, match=r"n = True must be a whole number"):
        check_count(True, "n", 0, 10)
    assert check_flag(np.bool_(True), "check") is True
    with pytest.raises(ScaraError, match=r"check = 'yes' must be True or False"):
        check_flag("yes", "check")
    with pytest.raises(ScaraError, match=r"row = 0\.7 must be an integer index 0\.\.2"):
        check_index(0.7, "row", 3)
    with pytest.raises(ScaraError, match=r"row = 3 is out of range: it must lie in 0\.\.2"):
        check_index(3, "row", 3)
    with pytest.raises(ScaraError, match=r"dt must be a number, got True"):
        check_positive(True, "dt")
    with pytest.raises(ShapeError, match=r"q must be an array of numbers, got \[True, True, False, False\]"):
        as_vector([True, True, False, False], "q")


def test_check_finite_result_names_the_largest_input():
    import numpy as np
    from scara.errors import NonFiniteError, check_finite_result
    assert check_finite_result(1.0, "y", x=[1.0]) == 1.0
    with pytest.raises(NonFiniteError, match=r"qd = \[1\.e\+300 0\.e\+000\] gives a non-finite C qd: qd is too large "
                                             r"\(an entry of magnitude 1e\+300\) and the result overflows"):
        check_finite_result(np.array([np.inf, 0.0]), "C qd", q=[1.0, 2.0], qd=[1e300, 0.0])
