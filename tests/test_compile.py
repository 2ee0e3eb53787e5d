"""The project decorator for compiled kernels (``scara._compile.kernel``): a ``light`` kernel runs as plain Python
when called from Python, with every kernel it calls, and is compiled into a kernel that calls it."""
from __future__ import annotations

import warnings
from fractions import Fraction

import numpy as np
import pytest

from scara import _compile
from scara._compile import COMPILED, kernel

pytestmark = pytest.mark.skipif(not COMPILED, reason="without numba every kernel is plain Python already")


@kernel
def _twice(x):
    return x + x


@kernel(light=True)
def _light(x):
    return _twice(x) + 1


@kernel
def _calls_light(x):
    return _light(x) * 3.0


def test_a_light_kernel_runs_as_python_from_python_and_compiles_into_its_callers():
    assert _light(2.0) == 5.0
    assert _light.signatures == [] and _twice.signatures == []      # nothing compiled for a call from Python
    assert _light(Fraction(1, 3)) == Fraction(5, 3)                   # only Python takes a Fraction
    with pytest.raises(TypeError):
        _light(None)
    assert _compile._PLAIN_RUN.depth == 0                             # a failed run leaves no plain mode behind
    assert _calls_light(2.0) == 15.0 and _calls_light.signatures      # compiled, the light kernel inside
    assert _light(Fraction(1, 3)) == Fraction(5, 3)                   # from Python: still plain
    assert _twice(1.5) == 3.0 and _twice.signatures                     # an ordinary kernel: compiled


def test_a_light_kernel_overflows_to_inf_without_a_warning_as_compiled_code_does():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _light(np.float64(1e308)) == np.inf
        assert _calls_light(1e308) == np.inf
