"""Tests of scara.errors: every error the package raises is a ``ValueError`` (a caller may catch either)."""
import pytest

from scara import ikine


def test_all_errors_are_value_errors():
    with pytest.raises(ValueError):
        ikine([3.0, 0.0, 0.5, 0.0])
