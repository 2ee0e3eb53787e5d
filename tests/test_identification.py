"""Checks of scara.identification: the exact recovery of pi from noise-free data, the statistics of the least-squares
estimate (1/sqrt(N) law, covariance against the empirical scatter, coverage of the confidence intervals), the
sensors (quantisation), the differentiation filter on a known sine, the exciting trajectory and its optimisation,
the identifiable combinations, and the refusal of bad inputs.

Statistical checks draw many independent trials with fixed seeds; each bound is a number of standard errors of
the statistic for that number of trials (written next to it), not a tolerance tuned to pass."""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.signal import butter, freqz

from scara import (PDGravityController, ScaraError, ScaraParams, ShapeError, UnreachableError, clik2,
                   dynamic_parameters, inverse_dynamics, reference_trajectory, regressor, simulate)
from scara.errors import NonFiniteError
from scara.identification import (
    BOOK_DESIGN, DRAWN_FIELDS, ENCODER_COUNTS, PAYLOAD_RANGE, QUILL_RESOLUTION, SPEED_LIMITS, FourierExcitation,
    base_parameters, book_design, draw_arm, encoder_resolution, excitation_margins, filtered_data, identify,
    least_squares, lowpass, measure, optimise_excitation, predicted_torques, quantise, read_sensors,
    regressor_condition, stacked_regressor, torque_noise_std,
)


@pytest.fixture(scope="module")
def search():
    """A search with the defaults, on this machine."""
    return optimise_excitation()


@pytest.fixture(scope="module")
def design():
    """The book's design (the one such a search found, kept as data): the statistics below do not follow the last
    digits a CPU's BLAS gives the search."""
    return book_design()


@pytest.fixture(scope="module")
def excitation(design):
    return design.excitation


@pytest.fixture(scope="module")
def grid_motion(excitation):
    """The exact excitation at 100 samples per period (the decimated rate of the book's 5 Hz cut-off)."""
    return excitation.motion(np.arange(100) * (excitation.period / 100))


# --------------------------------------------------------------------------------------------------
# noise-free data: the estimate is the truth
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", [0, 7, 2025])
def test_noise_free_engine_data_give_the_true_parameters(excitation, seed):
    arm = draw_arm(seed)
    run = simulate(PDGravityController(), plant=arm, joint_reference=excitation.reference(1))
    # the engine's exact q, qd, qdd (the acceleration just after the torque update) and the applied torques
    est = least_squares(stacked_regressor(run.q, run.qd, run.qdd), run.tau.ravel(), weighted=False)
    truth = dynamic_parameters(arm)
    assert np.all(np.abs(est.pi - truth) <= 1e-9 * np.abs(truth))
    assert est.rank == 13


def test_stacked_regressor_is_the_regressor_row_by_row(grid_motion):
    q, qd, qdd = (a[:7] for a in grid_motion)
    p = ScaraParams(a1=0.4, a2=0.6, g0=9.0)
    Y = stacked_regressor(q, qd, qdd, p)
    for k in range(7):
        assert np.array_equal(Y[4 * k:4 * k + 4], regressor(q[k], qd[k], qd[k], qdd[k], p))
    arm = draw_arm(3, base=p)
    assert np.allclose(predicted_torques(q, qd, qdd, dynamic_parameters(arm), p), inverse_dynamics(q, qd, qdd, arm),
                       rtol=1e-12, atol=1e-9)


# --------------------------------------------------------------------------------------------------
# the statistics of the estimate (exact regressor, white Gaussian noise of known standard deviation)
# --------------------------------------------------------------------------------------------------
SIGMA = np.array([0.5, 0.2, 2.5, 0.03])      # about 1 % of the peak torques of the book's excitation


def _trials(Y, truth, trials, seed, weighted, sigma=SIGMA):
    rng = np.random.default_rng(seed)
    tau0 = Y @ truth
    n = len(tau0) // 4
    return [least_squares(Y, tau0 + (rng.standard_normal((n, 4)) * sigma).ravel(), weighted=weighted)
            for _ in range(trials)]


def test_scatter_falls_as_one_over_sqrt_n(grid_motion):
    """Over M trials the sample standard deviation s has Var(ln s) = 1 / (2 (M - 1)); the slope of ln s against
    ln N fitted over the lengths x has the standard error sqrt(Var(ln s) / sum (x - mean x)^2). The fitted slope of
    every parameter must lie within 4 of those of the theory's -1/2."""
    truth = dynamic_parameters(draw_arm(11))
    trials, periods = 200, np.array([1, 2, 4, 8, 16])
    Y1 = stacked_regressor(*grid_motion)
    log_s = []
    for k, n in enumerate(periods):
        Y = np.vstack([Y1] * n)
        est = np.array([e.pi for e in _trials(Y, truth, trials, 100 + k, weighted=False)])
        log_s.append(np.log(est.std(axis=0, ddof=1)))
    x = np.log(100 * periods)
    slope = np.polyfit(x, np.array(log_s), 1)[0]                 # one slope per parameter
    se = math.sqrt(1 / (2 * (trials - 1)) / ((x - x.mean()) ** 2).sum())
    assert np.all(np.abs(slope + 0.5) < 4 * se), (slope, se)


def test_covariance_formula_matches_the_scatter(grid_motion):
    """The empirical variance of M estimates over the formula's variance is chi^2_{M-1} / (M - 1): mean 1, standard
    deviation sqrt(2 / (M - 1)); every parameter within 4 of those."""
    truth = dynamic_parameters(draw_arm(12))
    Y = np.vstack([stacked_regressor(*grid_motion)] * 2)
    trials = 400
    ests = _trials(Y, truth, trials, 5, weighted=True)
    pis = np.array([e.pi for e in ests])
    # the formula with the true noise: (Y^T W Y)^-1, W = diag(1 / sigma_i^2) repeated sample by sample
    w = np.tile(1 / SIGMA, len(Y) // 4)
    formula = np.diag(np.linalg.inv((Y * w[:, None]).T @ (Y * w[:, None])))
    ratio = pis.var(axis=0, ddof=1) / formula
    assert np.all(np.abs(ratio - 1) < 4 * math.sqrt(2 / (trials - 1))), ratio
    # the covariance each estimate reports (from its own residuals) averages to the formula: within 4 standard
    # errors of the mean of M reports, plus the bias of an inverted variance estimate, E[n / chi^2_n] - 1 = 2 / (n - 2)
    # with n the residual dof of the least-determined joint (N less its share of the parameters, at most 7)
    reported = np.array([np.diag(e.covariance) for e in ests]) / formula
    n = len(Y) // 4 - 7
    bound = 4 * reported.std(axis=0, ddof=1) / math.sqrt(trials) + 2 / (n - 2)
    assert np.all(np.abs(reported.mean(axis=0) - 1) < bound), (reported.mean(axis=0), bound)


@pytest.mark.parametrize("weighted", [True, False])
def test_intervals_cover_the_truth_at_their_rate(grid_motion, weighted):
    """Each parameter's 95 % interval, over M independent trials, covers the truth a binomial number of times:
    rate 0.95 with standard error sqrt(0.95 0.05 / M); within 4 of those (the ordinary intervals assume one
    variance for all joints, so they are checked with equal noise)."""
    truth = dynamic_parameters(draw_arm(13))
    Y = stacked_regressor(*grid_motion)
    trials = 400
    sigma = SIGMA if weighted else np.full(4, 0.3)
    ests = _trials(Y, truth, trials, 6, weighted=weighted, sigma=sigma)
    covered = np.mean([(e.interval[:, 0] <= truth) & (truth <= e.interval[:, 1]) for e in ests], axis=0)
    assert np.all(np.abs(covered - 0.95) < 4 * math.sqrt(0.95 * 0.05 / trials)), covered


def test_weighted_residual_variances_estimate_the_noise(grid_motion):
    """The per-joint residual standard deviations of one long record are the noise's: the relative standard
    error of a standard deviation from n residuals is about 1 / sqrt(2 n); within 4 of those."""
    truth = dynamic_parameters(draw_arm(14))
    Y = np.vstack([stacked_regressor(*grid_motion)] * 20)
    est = _trials(Y, truth, 1, 8, weighted=True)[0]
    assert np.all(np.abs(est.sigma / SIGMA - 1) < 4 / math.sqrt(2 * est.samples)), est.sigma / SIGMA


# --------------------------------------------------------------------------------------------------
# sensors and filter
# --------------------------------------------------------------------------------------------------
def test_encoder_resolution_values():
    r = encoder_resolution()
    assert r[0] == r[1] == r[3] == 2 * math.pi / 2 ** 17 and r[2] == 1e-6
    assert ENCODER_COUNTS == 131072 and QUILL_RESOLUTION == 1e-6


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(-10.0, 10.0, allow_nan=False), min_size=4, max_size=4),
       st.lists(st.floats(1e-7, 1e-2), min_size=4, max_size=4))
def test_quantisation_error_is_at_most_half_a_count(q, res):
    q, res = np.array(q), np.array(res)
    out = quantise(q, res)
    # half a count, plus the rounding of the product round(q / r) r (a few ulps of |q|)
    assert np.all(np.abs(out - q) <= 0.5 * res + 4 * np.finfo(float).eps * np.maximum(np.abs(q), res))
    counts = out / res
    assert np.allclose(counts, np.round(counts), rtol=0, atol=1e-6)


def test_quantise_returns_a_new_array():
    q = np.array([[0.1, 0.2, 0.3, 0.4]])
    out = quantise(q)
    assert not np.shares_memory(out, q) and q[0, 0] == 0.1


@pytest.mark.parametrize("f", [0.5, 1.0, 2.0])
def test_differentiation_of_a_known_sine(f):
    """q = A sin(w t + phase): the kept velocity and acceleration are the filter's exact response, A w |H|^2
    sinc(w dt) cos(...) and -A w^2 |H|^2 sinc(w dt)^2 sin(...) (|H|^2 the Butterworth gain forward and backward,
    sinc the central difference's); away from the ends to 1e-7 of the amplitude, everywhere kept to 1e-4 (the
    filter's start-up transient), and within (1 - |H|^2 sinc^2) + 1e-4 of the true derivatives."""
    dt, cutoff, A, phase = 1e-3, 5.0, 0.3, 0.7
    t = np.arange(10001) * dt
    w = 2 * math.pi * f
    q = np.tile((A * np.sin(w * t + phase))[:, None], (1, 4))
    b, a = butter(4, cutoff, fs=1 / dt)
    gain = abs(freqz(b, a, worN=[f], fs=1 / dt)[1][0]) ** 2
    sinc = math.sin(w * dt) / (w * dt)
    d = filtered_data(t, q, q, cutoff)
    exact_qd = A * w * np.cos(w * d.t + phase)
    exact_qdd = -A * w * w * np.sin(w * d.t + phase)
    err_qd = np.abs(d.qd[:, 0] - gain * sinc * exact_qd) / (A * w)
    err_qdd = np.abs(d.qdd[:, 0] - gain * sinc ** 2 * exact_qdd) / (A * w * w)
    inner = (d.t > 2.0) & (d.t < 8.0)
    assert err_qd[inner].max() < 1e-7 and err_qdd[inner].max() < 1e-7
    assert err_qd.max() < 1e-4 and err_qdd.max() < 1e-4
    assert np.all(np.abs(d.qdd[:, 0] - exact_qdd) / (A * w * w) < (1 - gain * sinc ** 2) + 1e-4)
    assert d.step == 100 and np.allclose(np.diff(d.t), 0.1)


def test_filter_keeps_the_torque_consistent_with_the_motion(excitation):
    """With exact positions and torques, the filtered regressor times the truth is the filtered torque to a
    small fraction of the torque: the parallel filtering and the hold alignment leave no lag."""
    arm = draw_arm(21)
    run = simulate(PDGravityController(), plant=arm, joint_reference=excitation.reference(2))
    d = filtered_data(run.t, run.q, run.tau, 5.0)
    pred = predicted_torques(d.q, d.qd, d.qdd, dynamic_parameters(arm))
    peak = np.abs(run.tau).max(axis=0)
    assert np.all(np.abs(pred - d.tau).max(axis=0) < 1e-3 * peak), np.abs(pred - d.tau).max(axis=0) / peak


def test_lowpass_passes_low_and_removes_high():
    t = np.arange(0, 4, 1e-3)
    x = np.sin(2 * np.pi * 0.5 * t) + np.sin(2 * np.pi * 100 * t)
    y = lowpass(x, 5.0, 1e-3)
    assert np.abs(y - np.sin(2 * np.pi * 0.5 * t))[1000:-1000].max() < 1e-4
    assert not np.shares_memory(y, x)


def test_torque_noise_is_one_percent_of_the_peak():
    tau = np.array([[1.0, -2.0, 30.0, 0.5], [-4.0, 1.0, 10.0, 0.1]])
    assert np.allclose(torque_noise_std(tau), [0.04, 0.02, 0.3, 0.005], rtol=1e-15)


def test_read_sensors(excitation):
    arm = draw_arm(4)
    m = measure(arm, excitation.reference(1), seed=3)
    r = encoder_resolution()
    assert np.all(np.abs(m.q - m.run.q) <= 0.5 * r + 1e-15)
    assert np.allclose(m.sigma, 0.01 * np.abs(m.run.tau).max(axis=0), rtol=1e-15)
    z = (m.tau - m.run.tau) / m.sigma
    # 4 x 10001 standard normal draws: mean within 4 standard errors, variance within 4 of its own
    assert abs(z.mean()) < 4 / math.sqrt(z.size) and abs(z.var() - 1) < 4 * math.sqrt(2 / z.size)
    again = read_sensors(m.run, seed=3)
    assert np.array_equal(again.tau, m.tau) and not np.shares_memory(again.q, m.run.q)


# --------------------------------------------------------------------------------------------------
# the black box
# --------------------------------------------------------------------------------------------------
@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2 ** 32))
def test_drawn_arm_within_its_ranges(seed):
    arm, base = draw_arm(seed), ScaraParams()
    for name in DRAWN_FIELDS:
        v, n = np.asarray(getattr(arm, name)), np.asarray(getattr(base, name))
        assert np.all((0.8 * n <= v) & (v <= 1.2 * n)), name
    assert PAYLOAD_RANGE[0] <= arm.m_L <= PAYLOAD_RANGE[1]
    assert (arm.a1, arm.a2, arm.d0, arm.k_r, arm.g0) == (base.a1, base.a2, base.d0, base.k_r, base.g0)
    assert draw_arm(seed) == arm


# --------------------------------------------------------------------------------------------------
# the exciting trajectory
# --------------------------------------------------------------------------------------------------
@settings(max_examples=30, deadline=None)
@given(st.integers(2, 6), st.integers(0, 10_000))
def test_fourier_series_starts_and_ends_at_rest_and_differentiates(h, seed):
    rng = np.random.default_rng(seed)
    e = FourierExcitation.at_rest(rng.standard_normal(8 * (h - 1)), period=8.0)
    q, qd, qdd = e.motion([0.0, 8.0])
    assert np.abs(qd).max() < 1e-12 and np.abs(qdd).max() < 1e-10 and np.allclose(q[0], q[1], atol=1e-12)
    # the analytic derivatives against central differences of q and qd
    t = rng.uniform(0, 8, 5)
    step = 1e-5
    qp, qdp, _ = e.motion(t + step)
    qm, qdm, _ = e.motion(t - step)
    _, qd0, qdd0 = e.motion(t)
    scale = 1 + np.abs(e.a).sum() + np.abs(e.b).sum()
    assert np.allclose((qp - qm) / (2 * step), qd0, atol=1e-6 * scale)
    assert np.allclose((qdp - qdm) / (2 * step), qdd0, atol=1e-6 * scale * h)
    assert np.allclose(FourierExcitation.at_rest(e.free(), period=8.0).a, e.a)


def test_the_search_reaches_the_books_design(search, design):
    """On any CPU the search ends at the kept design's optimum to about 1e-6 in its condition number (the two CPUs
    the book was built on gave 29.0870767 and 29.0870997), from the same start, within the same constraints."""
    assert search.success and design.success and search.cond_start == design.cond_start
    assert math.isclose(search.cond, design.cond, rel_tol=1e-5), (search.cond, design.cond)
    assert abs(search.iterations - design.iterations) <= 5
    assert np.array_equal(design.excitation.free(), np.array(BOOK_DESIGN))


@pytest.mark.parametrize("which", ["search", "design"])
def test_optimisation_lowers_the_condition_number(which, request):
    design = request.getfixturevalue(which)
    assert design.cond < design.cond_start / 5, (design.cond, design.cond_start)
    t = np.arange(200) * (design.excitation.period / 200)
    assert math.isclose(regressor_condition(*design.excitation.motion(t)), design.cond, rel_tol=1e-9)
    assert math.isclose(regressor_condition(*design.start.motion(t)), design.cond_start, rel_tol=1e-9)
    assert excitation_margins(*design.excitation.motion(t)).min() > -1e-6
    # on a fine grid: inside the stroke, the torque bounds, the speeds to within 1 %
    q, qd, qdd = design.excitation.motion(np.linspace(0, design.excitation.period, 20001))
    assert 0.0 <= q[:, 2].min() and q[:, 2].max() <= 1.0
    assert np.all(np.abs(qd) <= 1.01 * np.array(SPEED_LIMITS))


def test_reference_path_excites_badly_and_loses_a_combination():
    ref = clik2(reference_trajectory())
    q, qd, qdd = ref.q[::20], ref.qd[::20], ref.qdd[::20]
    assert regressor_condition(q, qd, qdd) > 1e10
    Y = stacked_regressor(q, qd, qdd)
    base = base_parameters(Y)
    assert base.rank == 12 and len(base.dependent) == 1
    # Y pi = Y_1 (pi_1 + K pi_2) for any pi: the base parameters carry all that the torques say
    pi = dynamic_parameters(draw_arm(5))
    assert np.allclose(Y[:, list(base.independent)] @ base.of(pi), Y @ pi, rtol=1e-10, atol=1e-9)
    with pytest.raises(ScaraError, match="rank 12 < 13"):
        least_squares(Y, Y @ pi)


def test_excitation_has_full_rank(grid_motion):
    base = base_parameters(stacked_regressor(*grid_motion))
    assert base.rank == 13 and base.dependent == () and base.K.shape == (13, 0)


# --------------------------------------------------------------------------------------------------
# bad inputs
# --------------------------------------------------------------------------------------------------
def test_bad_inputs_raise_clear_errors(excitation, grid_motion):
    Y = stacked_regressor(*grid_motion)
    tau = Y @ dynamic_parameters()
    with pytest.raises(ShapeError, match=r"\(4N, 13\)"):
        least_squares(Y[:, :12], tau)
    with pytest.raises(ShapeError, match="tau must have shape"):
        least_squares(Y, tau[:-4])
    with pytest.raises(ShapeError, match="Y must be an array of numbers"):
        least_squares("abc", tau)
    bad = Y.copy()
    bad[3, 2] = np.nan
    with pytest.raises(NonFiniteError):
        least_squares(bad, tau)
    with pytest.raises(ScaraError, match="more equations than parameters"):
        least_squares(Y[:12], tau[:12])
    with pytest.raises(ScaraError, match="joint 1 has 6 samples for the 7 parameters"):
        least_squares(Y[100:124], tau[100:124])
    with pytest.raises(ScaraError, match="confidence"):
        least_squares(Y, tau, confidence=1.0)
    with pytest.raises(ScaraError, match=r"resolution\[2\] = 0 must be > 0"):
        quantise([0, 0, 0, 0], [1e-3, 1e-3, 0.0, 1e-3])
    with pytest.raises(ScaraError, match="fraction = -0.01 must be > 0"):
        torque_noise_std(np.ones((3, 4)), -0.01)
    with pytest.raises(ScaraError, match="counts"):
        encoder_resolution(0)
    with pytest.raises(ScaraError, match="quill = 0"):
        encoder_resolution(quill=0.0)
    with pytest.raises(ScaraError, match="Nyquist"):
        lowpass(np.ones(100), 600.0, 1e-3)
    with pytest.raises(ShapeError, match="needs more than"):
        lowpass(np.ones(10), 5.0, 1e-3)
    with pytest.raises(ShapeError, match="x must be a series of numbers"):
        lowpass("abc", 5.0, 1e-3)
    with pytest.raises(NonFiniteError, match="x holds NaN"):
        lowpass(np.full(100, np.nan), 5.0, 1e-3)
    with pytest.raises(ShapeError, match="leave none"):
        filtered_data(np.arange(500) * 1e-3, np.zeros((500, 4)), np.zeros((500, 4)), 5.0)
    with pytest.raises(ShapeError, match="same N"):
        filtered_data(np.arange(5000) * 1e-3, np.zeros((5000, 4)), np.zeros((4999, 4)), 5.0)
    with pytest.raises(ScaraError, match="spread = 1 must be < 1"):
        draw_arm(0, spread=1.0)
    with pytest.raises(ScaraError, match="payload"):
        draw_arm(0, payload=(5.0, 1.0))
    with pytest.raises(ShapeError, match="free must hold"):
        FourierExcitation.at_rest(np.ones(7))
    with pytest.raises(ScaraError, match="period"):
        FourierExcitation.at_rest(np.ones(8), period=0.0)
    with pytest.raises(ScaraError, match="measurement must be a Measurement"):
        identify("data", 5.0)
    with pytest.raises(ScaraError, match="run must be a SimulationResult"):
        read_sensors(np.zeros((3, 4)), seed=0)
    ref = excitation.reference(1)
    ref[:, 2] += 0.6                               # the quill pushed past the end of its stroke
    with pytest.raises(UnreachableError, match=r"d3 = .* outside the quill's stroke \[0, 1\] m"):
        measure(draw_arm(0), ref, seed=0)
    with pytest.raises(ScaraError, match="sigma"):
        read_sensors(simulate(PDGravityController(), plant=ScaraParams(), joint_reference=excitation.reference(1)[:50]),
                     seed=0, sigma=[1.0, 0.0, 1.0, 1.0])


def test_the_design_does_not_depend_on_the_blas_thread_count():
    """SLSQP follows the last bits of every SVD, and a multi-threaded BLAS sums in an order set by its thread
    count: the search runs on one BLAS thread, so the caller's setting cannot change the design (it did: the
    condition number came out 29.0870767 on one thread and 29.0870814 on two before)."""
    import scipy.optimize  # noqa: F401 - loads scipy's own BLAS, so that the limits below reach it too
    from threadpoolctl import threadpool_limits

    from scara.identification import optimise_excitation

    designs = []
    for threads in (1, 2):
        with threadpool_limits(limits=threads, user_api="blas"):
            designs.append(optimise_excitation())  # the book's search: 32 or 33 iterations, where the paths parted
    a, b = designs
    assert a.cond == b.cond and a.iterations == b.iterations
    t = np.linspace(0.0, 10.0, 50)
    assert np.array_equal(a.excitation.motion(t)[0], b.excitation.motion(t)[0])
