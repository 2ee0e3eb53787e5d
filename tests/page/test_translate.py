"""The page's translator (scara.page.translate): every kernel of the package translates, the translation computes
what numba computes (Node 20), and a construct outside the subset is refused naming the kernel and the line."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

import scara
from scara import dynamics as D
from scara import kinematics as K
from scara import _manipulability as M
from scara.page.translate import TranslationError, translate

from ._node import run_js

P = scara.ScaraParams().with_payload(3.0)
DP = D.dynamic_array(P)
RNG = np.random.default_rng(20261203)
N = 200  # random evaluations of each kernel


def _configs(n):
    q = RNG.uniform(-math.pi, math.pi, (n, 4))
    q[:, 2] = RNG.uniform(P.d3_min, P.d3_max, n)
    return q


def _rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = max(np.max(np.abs(b)), 1e-300)
    return float(np.max(np.abs(a - b)) / scale)


# each case: (kernel, arguments -> the argument list, index of the output argument or None for the return value)
CASES = {
    "pose": (K.pose_kernel, lambda q, qd: [q, P.a1, P.a2, P.d0, np.zeros(4)], 4),
    "jacobian": (K.jacobian_kernel, lambda q, qd: [q, P.a1, P.a2, np.zeros((4, 4))], 3),
    "jacobian_dot": (K.jacobian_dot_kernel, lambda q, qd: [q, qd, P.a1, P.a2, np.zeros((4, 4))], 4),
    "inertia": (D.inertia_kernel, lambda q, qd: [q, DP, np.zeros((4, 4))], 2),
    "coriolis": (D.coriolis_kernel, lambda q, qd: [q, qd, DP, np.zeros((4, 4))], 3),
    "gravity": (D.gravity_kernel, lambda q, qd: [q, DP, np.zeros(4)], 2),
    "bias": (D.bias_kernel, lambda q, qd: [q, qd, DP, np.zeros(4)], 3),
    "inverse_dynamics": (D.inverse_dynamics_kernel,
                         lambda q, qd: [q, qd, qd[::-1].copy(), DP, D.dynamics_workspace(), np.zeros(4)], 5),
    "forward_dynamics": (D.forward_dynamics_kernel,
                         lambda q, qd: [q, qd, 10 * qd[::-1].copy(), DP, D.dynamics_workspace(), np.zeros(4)], 5),
    "regressor": (D.regressor_kernel, lambda q, qd: [q, qd, 0.5 * qd, qd[::-1].copy(), DP,
                                                      np.zeros((4, D.N_PI))], 5),
    "kinetic_energy": (D.kinetic_energy_kernel, lambda q, qd: [q, qd, DP, D.dynamics_workspace()], None),
    "manipulability": (M.manipulability_kernel, lambda q, qd: [q, P.a1, P.a2], None),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_single_evaluations_equal_numba(case):
    kernel, make, at = CASES[case]
    js = translate([kernel])
    qs, qds = _configs(N), RNG.normal(0, 2, (N, 4))
    calls, expected = [], []
    for q, qd in zip(qs, qds):
        args = make(q, qd)
        calls.append((kernel.__name__, [np.array(a) if isinstance(a, np.ndarray) else a for a in args], 1))
        ret = kernel(*args)
        expected.append(ret if at is None else args[at])
    got = run_js(js, calls)
    worst = max(_rel(g[0] if at is None else g[1][at], e) for g, e in zip(got, expected))
    assert worst <= 1e-12, f"{case}: largest relative difference {worst:.3g}"


def test_inverse_kinematics_codes_and_angles():
    js = translate([K.ikine_kernel])
    targets = RNG.uniform(-0.9, 0.9, (N, 4))
    targets[:, 2] = RNG.uniform(-0.2, 1.2, N)
    calls, expected = [], []
    for x in targets:
        for elbow in (1.0, -1.0):
            out = np.zeros(4)
            code = K.ikine_kernel(x, P.a1, P.a2, P.d0, P.d3_min, P.d3_max, elbow, out)
            expected.append((code, out))
            calls.append(("ikine_kernel", [x, P.a1, P.a2, P.d0, P.d3_min, P.d3_max, elbow, np.zeros(4)], 1))
    got = run_js(js, calls)
    codes = {int(c) for c, _ in expected}
    assert codes >= {K.IK_OK, K.IK_OUTSIDE_ANNULUS, K.IK_OUTSIDE_STROKE}, codes  # every branch is exercised
    for (ret, args, _), (code, out) in zip(got, expected):
        assert int(ret) == int(code)
        assert _rel(args[7], out) <= 1e-12 if np.any(out) else not np.any(args[7])


def test_every_kernel_of_the_package_translates_or_is_named():
    """Every compiled kernel translates, except the two loops that call a controller's law as a first-class
    function (the closed loop's engine and the replay of a law; the page programs pick their law by an if-chain)."""
    import importlib
    import pkgutil

    refused = {}
    count = 0
    for info in pkgutil.walk_packages(scara.__path__, "scara."):
        if info.name.startswith(("scara.widgets", "scara.plots", "scara.page")):
            continue
        mod = importlib.import_module(info.name)
        for name, value in vars(mod).items():
            fn = getattr(value, "py_func", None)
            if fn is None or getattr(fn, "__module__", None) != mod.__name__:
                continue
            count += 1
            try:
                translate([value])
            except TranslationError as exc:
                refused[f"{info.name}.{name}"] = str(exc)
    assert count > 60
    # the loops that take a law as a first-class function (the engine's, the contact engine's, the replay's): the page
    # programs run their own loops, which pick the law by index
    assert set(refused) <= {"scara._simulate.engine.closed_loop_kernel", "scara.control._common._replay_kernel",
                            "scara.interaction.engine.contact_loop_kernel"}, refused
    for text in refused.values():
        assert "first-class function" in text and "line" in text


# ---- constructs outside the subset are refused, naming the kernel and the line ------------------------------------
def _uses_try(x):
    try:
        return x
    except ValueError:
        return 0.0


def _uses_list(x):
    v = [x, x]
    return v[0]


def _uses_string(x):
    s = "no"
    return x


def _uses_keyword(x):
    return round(x, ndigits=2)


def _calls_variable(f, x):
    return f(x)


def _uses_default(x, y=1.0):
    return x + y


def _uses_comprehension(x):
    return sum(i for i in range(3))


def _recursive(x):
    return _recursive(x - 1) if x > 0 else 0.0


@pytest.mark.parametrize("fn, words", [
    (_uses_try, "Try"), (_uses_list, "List"), (_uses_string, "constant 'no'"), (_uses_keyword, "keyword"),
    (_calls_variable, "first-class"), (_uses_default, "default"), (_uses_comprehension, "GeneratorExp"),
    (_recursive, "recursion"),
])
def test_refusals_name_the_kernel_and_line(fn, words):
    with pytest.raises(TranslationError) as info:
        translate([fn])
    text = str(info.value)
    assert fn.__name__ in text and words in text, text
    line = int(re.search(r"line (\d+)", text).group(1))
    import inspect
    lines, first = inspect.getsourcelines(fn)
    assert first <= line < first + len(lines)


def _python_semantics(a, b):
    return a // b, a % b, -a // b, -a % b, min(a, b), max(a, -b), int(-2.7), 2 ** 0.5, abs(-a)


def test_python_integer_semantics():
    js = translate([_python_semantics])
    pairs = [(7.0, 3.0), (7.5, -2.0), (-3.0, 4.0), (5.0, 5.0)]
    got = run_js(js, [("_python_semantics", [a, b], 1) for a, b in pairs])
    for (a, b), (ret, _, _) in zip(pairs, got):
        assert np.allclose(ret, _python_semantics(a, b), rtol=0, atol=0), (a, b, ret)


def _copies(a, b):
    c = a.copy()      # a copy, not a view: writing it leaves a alone
    c[0] = -1.0
    d = b.copy()
    d[1, 0] = 7.0
    return c[0] + a[0] + d.shape[1] + d[1, 0] + b[1, 0]


def test_copies_are_copies_with_their_shape():
    a, b = np.array([2.0, 3.0]), np.arange(6.0).reshape(3, 2)
    (ret, (a_after, b_after), _), = run_js(translate([_copies]), [("_copies", [a, b], 1)])
    assert ret == _copies(a.copy(), b.copy()) == -1.0 + 2.0 + 2 + 7.0 + 2.0
    np.testing.assert_array_equal(a_after, a)
    np.testing.assert_array_equal(b_after, b)
