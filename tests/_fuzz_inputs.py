"""Input generators and the result check of the fuzz test (tests/test_fuzz.py).

A callable's arguments are a list of :class:`Arg`: each has a strategy of *valid* values and a strategy of
*hostile* ones (NaN, +-inf, 1e300, 1e-300, negative numbers, wrong shapes, wrong types, empty arrays...). An
example draws how many arguments to make hostile (0 = a fully valid call), which ones, and their values.

:func:`non_finite` walks a returned object (numbers, arrays, tuples, lists, dicts, dataclasses and plain
objects' attributes) and names the first entry that is not finite.
"""
from __future__ import annotations

import dataclasses
import functools
import math
import numbers
import types

import numpy as np
from hypothesis import strategies as st

# --------------------------------------------------------------------------------------------------
# the hostile values
# --------------------------------------------------------------------------------------------------
#: floats that break numeric code: NaN, infinities, huge, tiny, negative, zero
BAD_FLOATS = (math.nan, math.inf, -math.inf, 1e300, -1e300, 1e-300, -1e-300, -1.0, 0.0)


class _Opaque:
    """An object of no numeric meaning (stands for ``object()`` with a stable repr)."""

    def __repr__(self):
        return "<opaque object>"


#: values of the wrong type for any numeric argument
BAD_TYPES = ("abc", "", None, ["a", "b"], ["a", "b", "c", "d"], True, False, {}, {"a": 1.0}, [], (),
             np.array([]), np.zeros((0, 4)), 1 + 2j, _Opaque(), [None] * 4)

HOSTILE_SCALAR = st.sampled_from(BAD_FLOATS + BAD_TYPES + (np.array([1.0, 2.0]), np.float64("nan"), [0.5]))


def _arrays(shape, lo, hi):
    size = int(np.prod(shape))
    return st.lists(st.floats(lo, hi), min_size=size, max_size=size).map(
        lambda v: np.asarray(v, dtype=float).reshape(shape))


def _wrong_shapes(shape):
    """Arrays of a shape other than ``shape`` (scalar, shorter, longer, 2-D for 1-D, 3-D...)."""
    out = [0.3, np.float64(0.3)]
    if len(shape) == 1:
        n = shape[0]
        out += [np.full(max(n - 1, 1), 0.3), np.full(n + 1, 0.3), np.full((2, n), 0.3), np.full((n, n), 0.3),
                np.full((1, n, 1), 0.3), np.zeros((0, n)), [[0.1, 0.2], [0.3]], ["a"] * n, [None] * n,
                [True] * n]
    else:
        out += [np.full(shape[-1], 0.3), np.full(tuple(s + 1 for s in shape), 0.3), np.full((2, *shape), 0.3),
                np.zeros((0, *shape[1:]))]
    return st.sampled_from(out)


def _poisoned(valid, bad=BAD_FLOATS):
    """A valid array with one entry replaced by a hostile float."""
    def poison(args):
        arr, i, b = args
        arr = np.array(arr, dtype=float, copy=True)
        if arr.size == 0:
            return arr
        arr.flat[i % arr.size] = b
        return arr
    return st.tuples(valid, st.integers(0, 63), st.sampled_from(bad)).map(poison)


# --------------------------------------------------------------------------------------------------
# arguments
# --------------------------------------------------------------------------------------------------
@dataclasses.dataclass
class Arg:
    """One argument: its keyword, its valid values, its hostile values; an optional one may be left out."""

    name: str
    valid: st.SearchStrategy
    hostile: st.SearchStrategy
    optional: bool = False
    fuzz: bool = True  # False: a caller-side contract argument (a name in messages...), always valid


def contract(name, value):
    """An argument the package's own code supplies (a name for messages, a shape to check against...): always
    ``value``, never made hostile (the fuzz test is about bad data, not about misuse of internal helpers)."""
    return Arg(name, st.just(value), st.just(value), False, fuzz=False)


def vector(name, n, lo=-1.0, hi=1.0, optional=False, valid=None):
    """A float array argument of shape ``(n,)`` (or ``n`` a tuple: that shape)."""
    shape = (n,) if isinstance(n, int) else tuple(n)
    v = valid if valid is not None else _arrays(shape, lo, hi)
    return Arg(name, v, st.one_of(_poisoned(v), _wrong_shapes(shape), st.sampled_from(BAD_TYPES),
                                  st.sampled_from(BAD_FLOATS)), optional)


def scalar(name, lo, hi, optional=False, valid=None):
    """A float argument valid in ``[lo, hi]``."""
    v = valid if valid is not None else st.floats(lo, hi)
    return Arg(name, v, HOSTILE_SCALAR, optional)


def integer(name, lo, hi, optional=False):
    """An integer argument valid in ``[lo, hi]`` (hostile: floats, huge, negative, bools, strings...)."""
    return Arg(name, st.integers(lo, hi),
               st.one_of(HOSTILE_SCALAR, st.sampled_from((0, -1, -(10 ** 6), 2.5, 10 ** 12))), optional)


def choice(name, options, optional=False, extra_bad=()):
    """One of ``options`` (strings, flags); hostile: other strings, numbers, None, containers."""
    return Arg(name, st.sampled_from(list(options)),
               st.one_of(HOSTILE_SCALAR, st.sampled_from(("nope", "INVERSE", 7, -1, 2, *extra_bad))), optional)


def fixed(name, values, hostile=None, optional=False):
    """An argument valid among ``values`` (objects such as trajectories or results)."""
    return Arg(name, st.sampled_from(list(values)) if isinstance(values, (list, tuple)) else values,
               hostile if hostile is not None else st.sampled_from(BAD_TYPES + BAD_FLOATS), optional)


def gain(name, n=4, lo=1.0, hi=500.0, optional=False):
    """A diagonal gain: a positive number, (n,) vector or diagonal matrix."""
    v = st.one_of(st.floats(lo, hi), _arrays((n,), lo, hi))
    return Arg(name, v, st.one_of(_poisoned(_arrays((n,), lo, hi)), _wrong_shapes((n,)),
                                  st.sampled_from(BAD_TYPES + BAD_FLOATS),
                                  st.just(np.full((n, n), 1.0)), st.just(-np.ones(n))), optional)


def arguments(draw, args, mutate_max=2):
    """Draw the keyword arguments of one call: ``(kwargs, names of the hostile arguments)``."""
    fuzzed = [a.name for a in args if a.fuzz]
    # mostly one hostile argument (a second one often hides the first behind its own check); 0 = a valid call
    counts = [c for c in (1, 0, 2, 1, 1) if c <= min(mutate_max, len(fuzzed))]
    k = draw(st.sampled_from(counts), label="hostile count") if fuzzed else 0
    hostile = set(draw(st.lists(st.sampled_from(fuzzed), min_size=k, max_size=k, unique=True),
                       label="hostile args")) if k else set()
    kwargs = {}
    for a in args:
        if a.name in hostile:
            kwargs[a.name] = draw(a.hostile, label=a.name)
        elif a.optional and not draw(st.booleans(), label=f"give {a.name}"):
            continue
        else:
            kwargs[a.name] = draw(a.valid, label=a.name)
    return kwargs, sorted(hostile)


# --------------------------------------------------------------------------------------------------
# showing inputs in messages
# --------------------------------------------------------------------------------------------------
#: labels of the shared objects (trajectories, results, controllers) for messages: ``id -> (object, label)``
#: (the object is kept alive, so that its id is not reused by another object)
LABELS: dict[int, tuple] = {}


def label(obj, text):
    LABELS[id(obj)] = (obj, text)
    return obj


def show(v, limit=160):
    if id(v) in LABELS and LABELS[id(v)][0] is v:
        return LABELS[id(v)][1]
    if isinstance(v, np.ndarray):
        if v.size > 8:
            fin = np.isfinite(v).all() if v.dtype.kind in "fc" else True
            return f"array(shape={v.shape}, {'finite' if fin else 'NON-FINITE'})"
        s = "array(" + np.array2string(v, separator=", ", threshold=8, precision=4) + ")"
        if v.size == 0 or v.ndim != 1:  # "array([])" alone would hide a (0, 4) batch
            s = s[:-1] + f", shape={v.shape})"
    elif isinstance(v, types.SimpleNamespace):
        # the odd fields first (non-finite or not arrays); the ordinary finite arrays only counted
        def plain(x):
            return isinstance(x, np.ndarray) and x.size > 8 and (x.dtype.kind not in "fc" or np.isfinite(x).all())
        odd = [f"{k}={show(x, 60)}" for k, x in vars(v).items() if not plain(x)]
        n_plain = sum(plain(x) for x in vars(v).values())
        s = "namespace(" + ", ".join(odd + ([f"+{n_plain} finite arrays"] if n_plain else [])) + ")"
    elif isinstance(v, (list, tuple)) and v and not isinstance(v[0], (numbers.Number, str, type(None))):
        s = type(v).__name__ + "[" + ", ".join(show(x, 60) for x in v) + "]"
    else:
        s = repr(v)
    return s if len(s) <= limit else s[: limit - 3] + "..."


def show_call(name, kwargs):
    return f"{name}(" + ", ".join(f"{k}={show(v)}" for k, v in kwargs.items()) + ")"


# --------------------------------------------------------------------------------------------------
# the result check
# --------------------------------------------------------------------------------------------------
def _members(obj, path):
    """The ``(path, value)`` pairs one level inside ``obj`` (a dict's items, a sequence's entries, a dataclass's
    fields, an object's attributes), or None for anything else."""
    if isinstance(obj, dict):
        return [(f"{path}[{k!r}]", v) for k, v in obj.items()]
    if isinstance(obj, (list, tuple)):
        return [(f"{path}[{i}]", v) for i, v in enumerate(obj)]
    if dataclasses.is_dataclass(obj):
        return [(f"{path}.{f.name}", getattr(obj, f.name)) for f in dataclasses.fields(obj)]
    if hasattr(obj, "__dict__") and not callable(obj):
        return [(f"{path}.{k}", v) for k, v in vars(obj).items() if not k.startswith("__")]
    return None


def arrays_in(obj, path="args", depth=0, seen=None):
    """Every NumPy array reachable from ``obj`` (through dicts, lists, tuples, dataclasses and objects'
    attributes, as :func:`non_finite` walks them), as ``(path, array)`` pairs."""
    if seen is None:
        seen = set()
    if depth > 6 or obj is None or isinstance(obj, (str, bytes, bool, numbers.Number, type, types.ModuleType)):
        return
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind != "O":
            yield path, obj
        return
    if id(obj) in seen:
        return
    seen.add(id(obj))
    items = _members(obj, path)
    if items is None:
        return
    for sub, v in items:
        yield from arrays_in(v, sub, depth + 1, seen)


class Ownership:
    """The arrays a call is given, before the call: :meth:`problem` then says whether the call changed one, made
    one read-only, or returned a result that shares memory with one (a result owns its arrays)."""

    def __init__(self, kwargs):
        self.inputs = [(path, a, a.copy(), a.flags.writeable) for path, a in arrays_in(kwargs)]

    def problem(self, result):
        for path, a, copy, writeable in self.inputs:
            if a.flags.writeable != writeable:
                return f"the call made the caller's array {path} read-only"
            if a.shape != copy.shape or not np.array_equal(a, copy, equal_nan=True):
                return f"the call changed the caller's array {path}"
        for rpath, r in arrays_in(result, "result"):
            for path, a, _, _ in self.inputs:
                if r.size and a.size and np.shares_memory(r, a):
                    return f"{rpath} shares memory with the caller's {path}"
        return None


def non_finite(obj, path="result", allow_inf=False, depth=0, seen=None, skip=()):
    """The path and value of the first number of ``obj`` that is not finite (NaN always, +-inf unless
    ``allow_inf``), or None. Paths in ``skip`` (documented non-finite values, e.g. ``"result[2]"``) are not
    walked."""
    if seen is None:
        seen = set()
    if path in skip:
        return None
    if depth > 6 or obj is None or isinstance(obj, (str, bytes, bool, np.bool_, type, types.ModuleType)):
        return None
    bad = (lambda x: math.isnan(x)) if allow_inf else (lambda x: not math.isfinite(x))
    if isinstance(obj, numbers.Real):
        return f"{path} = {obj!r}" if bad(float(obj)) else None
    if isinstance(obj, numbers.Complex):
        return f"{path} = {obj!r}" if bad(obj.real) or bad(obj.imag) else None
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fc":
            mask = np.isnan(obj) if allow_inf else ~np.isfinite(obj)
            if mask.any():
                idx = tuple(int(i) for i in np.argwhere(mask)[0])
                return f"{path}{list(idx)} = {obj[idx]!r} (shape {obj.shape}, {int(mask.sum())} non-finite)"
            return None
        if obj.dtype.kind == "O":
            for i, x in enumerate(obj.flat):
                r = non_finite(x, f"{path}.flat[{i}]", allow_inf, depth + 1, seen, skip)
                if r:
                    return r
        return None
    if id(obj) in seen:
        return None
    seen.add(id(obj))
    items = _members(obj, path)
    if items is None:
        return None
    for p, v in items:
        if callable(v) and not isinstance(v, np.ndarray) and not hasattr(v, "__dict__"):
            continue
        r = non_finite(v, p, allow_inf, depth + 1, seen, skip)
        if r:
            return r
    return None


@functools.lru_cache(maxsize=None)
def reachable_points():
    """A few reachable (x, y, z) points of the default arm, away from the singular circles."""
    return ((0.5, 0.3, 0.5), (0.55, 0.3, 0.5), (0.5, 0.35, 0.45), (0.45, 0.35, 0.5), (0.4, 0.4, 0.3),
            (0.6, 0.1, 0.6), (0.3, 0.5, 0.5))
