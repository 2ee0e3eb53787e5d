"""Tests of scara.trajectory.timing (chapter 3): the trapezoidal timing law, checked by symbolic integration and
against its limits."""
from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from scara import Trapezoidal, trapezoidal


# --------------------------------------------------------------------------------------------------
# the timing law
# --------------------------------------------------------------------------------------------------
def test_trapezoidal_boundary_values_and_peak_speed():
    L, T, tc = 0.3, 4.0, 1.0
    law = Trapezoidal(L, T, tc)
    s, sd, sdd = law.evaluate(np.array([0.0, tc, T / 2, T - tc, T]))
    np.testing.assert_allclose(s, [0, law.acceleration * tc ** 2 / 2, L / 2, L - law.acceleration * tc ** 2 / 2, L],
                               atol=1e-15)
    np.testing.assert_allclose(sd[[0, -1]], 0.0, atol=1e-15)
    assert law.cruise_speed == pytest.approx(L / (T - tc))
    tt = np.linspace(-1, T + 1, 200001)
    s, sd, sdd = law.evaluate(tt)
    assert sd.max() == pytest.approx(L / (T - tc), rel=1e-12)
    assert np.all(sd >= 0) and s[0] == 0 and s[-1] == L
    # sd is the integral of sdd and s of sd (cumulative trapezoid on a fine grid)
    from scipy.integrate import cumulative_trapezoid
    np.testing.assert_allclose(cumulative_trapezoid(sd, tt, initial=0), s, atol=1e-9)
    np.testing.assert_allclose(cumulative_trapezoid(sdd, tt, initial=0), sd, atol=2e-5 * law.acceleration)
    # the default blend is T/3 (peak 1.5 L/T); the triangular profile peaks at 2 L/T
    assert trapezoidal(np.array([T / 2]), L, T)[1][0] == pytest.approx(1.5 * L / T)
    assert Trapezoidal(L, T, T / 2).evaluate(T / 2)[1] == pytest.approx(2 * L / T)


def test_trapezoidal_integrates_to_the_length_symbolically():
    L, T, tc, tau = sp.symbols("L T t_c tau", positive=True)
    a = L / ((T - tc) * tc)
    sdd = sp.Piecewise((a, tau < tc), (0, tau < T - tc), (-a, True))
    sd = sp.integrate(sdd, (tau, 0, tau))
    s_T = sp.integrate(sd, (tau, 0, T))
    vals = {L: sp.Rational(3, 10), T: 4, tc: 1}
    assert sp.simplify(s_T.subs(vals)) == sp.Rational(3, 10)
    assert sp.simplify(sd.subs(vals).subs(tau, 4)) == 0
    law = Trapezoidal(0.3, 4.0, 1.0)
    for x in (0.5, 1.7, 3.2):
        assert float(sd.subs(vals).subs(tau, x)) == pytest.approx(float(law.evaluate(x)[1]), abs=1e-15)


def test_minimum_time_respects_the_limits_and_is_tight():
    for L, v, a in [(0.4, 0.2, 0.4), (0.02, 0.2, 0.4), (0.3, 0.05, 0.02)]:
        law = Trapezoidal.minimum_time(L, v, a)
        assert law.cruise_speed <= v * (1 + 1e-12) and law.acceleration == pytest.approx(a)
        if L >= v * v / a:
            assert law.duration == pytest.approx(L / v + v / a)
        else:
            assert law.duration == pytest.approx(2 * math.sqrt(L / a))
        rounded = Trapezoidal.minimum_time(L, v, a, dt=1e-3)
        n = rounded.duration / 1e-3
        assert abs(n - round(n)) < 1e-9 and law.duration <= rounded.duration < law.duration + 1e-3
        assert rounded.acceleration == pytest.approx(a) and rounded.cruise_speed <= v * (1 + 1e-12)


def test_nan_and_infinite_times_are_refused():
    from scara import NonFiniteError
    law = Trapezoidal(length=0.3, duration=3.0, blend=1.0)
    with pytest.raises(NonFiniteError, match=r"tau = nan is not a finite time; every time must be a finite number"):
        law.evaluate(math.nan)
    with pytest.raises(NonFiniteError, match=r"tau\[1\] = inf is not a finite time"):
        law.evaluate_sorted([0.0, math.inf])


def test_profile_too_long_for_its_duration_or_too_finely_sampled_is_refused():
    from scara import ScaraError
    import re
    from scara.trajectory.timing import MAX_SEGMENT_SAMPLES
    with pytest.raises(ScaraError, match=r"length = 1e\+300 m over duration = 1e-300 s .* not finite: the length is "
                                         r"too large for the duration"):
        Trapezoidal(1e300, 1e-300, 5e-301)
    with pytest.raises(ScaraError, match=r"dt = 1e-300 s is too short .* MAX_SEGMENT_SAMPLES = "
                                         + re.escape(f"{MAX_SEGMENT_SAMPLES:g}")):
        Trapezoidal.minimum_time(1.0, 1.0, 1.0, dt=1e-300)
    with pytest.raises(ScaraError, match=r"length must be a number, got True"):
        Trapezoidal(True, 1.0, 0.5)
