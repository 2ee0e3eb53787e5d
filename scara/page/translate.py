"""The translator from the package's compiled kernels to JavaScript: the code the book's pages run.

The kernels (:func:`scara._compile.kernel`) are written in a small subset of Python that numba compiles:
scalar arithmetic, loops over ``range``, tuples, float arrays indexed element by element, calls of other kernels.
:func:`translate` turns a set of kernels, and every kernel they call, into one JavaScript script, statement by
statement, so the page computes with the same source numba compiles: nothing of the math is written twice.
Anything outside the subset raises :class:`TranslationError`, naming the kernel, the file and line and the
construct, so a kernel that grows beyond it is caught at build time, not in a reader's browser.

The subset (what the translator accepts):

* functions with positional parameters only, no closures, no recursion;
* statements: assignment to a name, to ``a[i]`` or ``a[i, j]``, or to a tuple of those; augmented assignment;
  ``for ... in range(...)``; ``while``; ``if``/``elif``/``else``; ``break``; ``continue``; ``return``; ``pass``;
  a call as a statement; a docstring;
* expressions: numbers and booleans, names, ``+ - * / // % **`` (``//`` and ``%`` with Python's signs), unary
  ``-``, ``+`` and ``not``, comparisons (chained too), ``and``/``or``, ``x if c else y``, tuples (made, indexed,
  unpacked), module-level constants (numbers, tuples of numbers, namedtuple classes), calls of kernels, of
  :data:`MATH` functions, of ``abs min max float int len range``, of ``np.empty``/``np.zeros`` (float64, one or
  two dimensions) and :data:`NUMPY` scalar functions; ``a.shape[k]``; ``a[lo:hi]`` (a view: entries, or rows of a
  2-D array), ``a[i, :]``, ``a[i, lo:hi]`` and ``a[i]`` of a 2-D array (a row view), ``a.reshape(n, m)``,
  ``a.copy()``.

In the script a 1-D float array is a ``Float64Array``, a 2-D one a ``Float64Array`` of its rows one after the
other with the row length in ``.n1``, a tuple a JavaScript array, a namedtuple an object holding its entries by
position and by field name: indexing is JavaScript's own, as fast as V8 makes it. A negative index must be a
literal (``a[-1]``), as in every kernel of the package. The runtime (``RUNTIME``, the few helpers the translated
kernels call) is part of the script.
"""
from __future__ import annotations

import ast
import collections
import inspect
import json
import math
import textwrap
import types

import numpy as np

from ..errors import ScaraError

__all__ = ["TranslationError", "translate", "translated_name", "MATH", "NUMPY", "RUNTIME"]


class TranslationError(ScaraError):
    """A kernel uses a construct the page's translator does not support."""


#: the ``math`` functions and constants the translator maps, with their JavaScript
MATH = {
    "sqrt": "Math.sqrt", "sin": "Math.sin", "cos": "Math.cos", "tan": "Math.tan", "asin": "Math.asin",
    "acos": "Math.acos", "atan": "Math.atan", "atan2": "Math.atan2", "hypot": "Math.hypot", "exp": "Math.exp",
    "log": "Math.log", "log10": "Math.log10", "floor": "Math.floor", "ceil": "Math.ceil", "fabs": "Math.abs",
    "isfinite": "Number.isFinite", "isnan": "Number.isNaN", "copysign": "$copysign", "degrees": "$degrees",
    "radians": "$radians", "tanh": "Math.tanh", "sinh": "Math.sinh", "cosh": "Math.cosh", "expm1": "Math.expm1",
    "log1p": "Math.log1p", "trunc": "Math.trunc",
}
MATH_CONSTANTS = {"pi": "Math.PI", "e": "Math.E", "inf": "Infinity", "tau": "(2 * Math.PI)", "nan": "NaN"}
#: the numpy scalar functions the translator maps (numpy's array functions are not in the subset)
NUMPY = {"sqrt": "Math.sqrt", "sin": "Math.sin", "cos": "Math.cos", "abs": "Math.abs", "fabs": "Math.abs",
         "isfinite": "Number.isFinite", "isnan": "Number.isNaN", "arctan2": "Math.atan2", "exp": "Math.exp",
         "hypot": "Math.hypot", "sign": "$sign", "floor": "Math.floor", "tanh": "Math.tanh"}
NUMPY_CONSTANTS = {"pi": "Math.PI", "inf": "Infinity", "nan": "NaN"}

#: JavaScript words a Python name cannot keep
_RESERVED = set("""break case catch class const continue debugger default delete do else enum export extends false
finally for function if import in instanceof new null return super switch this throw true try typeof var void while
with yield let static implements interface package private protected public await arguments eval undefined NaN
Infinity Math Number A""".split())

#: the runtime every translated kernel calls: arrays, indexing with Python's negative indices, Python's ``//``,
#: ``%``, ``min`` and ``max`` (which keep their first argument on a NaN comparison)
RUNTIME = r"""
"use strict";
// A 1-D float array is a Float64Array; a 2-D one a Float64Array of its rows one after the other, with the row
// length in .n1; a tuple is a JavaScript array; a namedtuple an object of its entries by position and by name.
// Every 2-D array is made by $two, so all have one hidden class: the row length always a small integer (`| 0`; one
// V8 held as a double, as int() of a float gives, would change the class, and every loop that had seen the old
// one slowed down 2-6x), then the row views' cache.
function $size(n) {
  if (!(Number.isInteger(n) && n >= 0)) throw new RangeError("array size " + n + " is not a count");
  return n;
}
function $two(a, m) {  // a seen as rows of m entries: the row length, and for a small array the caches of its views
  a.n1 = m | 0;
  a.$v = a.length <= 64 * m ? [] : undefined;  // its rows
  a.$s = undefined;  // its slices and reshapes, made on first use (every 2-D array has these three, in this order)
  return a;
}
function $positions(klass, fields) {  // a namedtuple class's entries by position, and its length (an array-like)
  fields.forEach((f, i) => Object.defineProperty(klass.prototype, i, {get() { return this[f]; }}));
  Object.defineProperty(klass.prototype, "length", {get() { return fields.length; }});
}
function $cached(a, key, make) {  // a small 2-D array's view made once (a law's work rows, sliced on every step)
  let s = a.$s;
  if (s === undefined) s = a.$s = new Map();
  let v = s.get(key);
  if (v === undefined) { v = make(); s.set(key, v); }
  return v;
}
function $empty2(n, m) { return $two(new Float64Array($size(n) * $size(m)), m); }
function $row(a, i) {  // a row's view; a small array makes each once (a law's work rows: no allocation per step)
  const m = a.n1, v = a.$v;
  if (v === undefined) return a.subarray(i * m, i * m + m);
  return v[i] || (v[i] = a.subarray(i * m, i * m + m));
}
function $g1(a, i) { return a.n1 !== undefined ? $row(a, i) : a[i]; }         // a[i]: an entry, or a row's view
function $g2(a, i, j) { return a.n1 !== undefined ? a[i * a.n1 + j] : a[i][j]; }  // a[i][j]
function $n0(a) { return a.n1 !== undefined ? a.length / a.n1 : a.length; }
function $slice(a, lo, hi) {  // a[lo:hi]: entries of a 1-D array, rows of a 2-D one (a view)
  const n = $n0(a);
  lo = lo === null ? 0 : (lo < 0 ? Math.max(lo + n, 0) : Math.min(lo, n));
  hi = hi === null ? n : (hi < 0 ? Math.max(hi + n, 0) : Math.min(hi, n));
  hi = Math.max(hi, lo);
  if (a.n1 === undefined) return a.subarray(lo, hi);
  const m = a.n1;
  if (a.$v === undefined) return $two(a.subarray(lo * m, hi * m), m);
  return $cached(a, lo * 65 + hi, () => $two(a.subarray(lo * m, hi * m), m));  // a small array: n <= 64
}
function $reshape(a, n, m) {  // a contiguous array (1-D, or rows of a 2-D one) seen as (n, m): a view
  if (!(a instanceof Float64Array) || n * m !== a.length) throw new RangeError("cannot reshape " + a.length + " entries to (" + n + ", " + m + ")");
  if (a.n1 === undefined || a.$v === undefined) return $two(a.subarray(0, a.length), m);
  return $cached(a, -1 - m, () => $two(a.subarray(0, a.length), m));  // keys below 0: the reshapes
}
function $copy(a) { const c = a.slice(); return a.n1 !== undefined ? $two(c, a.n1) : c; }  // a.copy()
function $shape(a, k) { if (k === 0) return $n0(a); if (k === 1 && a.n1 !== undefined) return a.n1; throw new RangeError("shape[" + k + "]"); }
function $floordiv(a, b) { return Math.floor(a / b); }
function $mod(a, b) { const r = a % b; return (r !== 0 && (r < 0) !== (b < 0)) ? r + b : r; }
function $min(a, ...b) { for (const x of b) { if (x < a) a = x; } return a; }
function $max(a, ...b) { for (const x of b) { if (x > a) a = x; } return a; }
function $int(x) { if (!Number.isFinite(x)) throw new RangeError("int() of " + x); return Math.trunc(x); }
function $copysign(a, b) { return (b < 0 || Object.is(b, -0)) ? -Math.abs(a) : Math.abs(a); }
function $degrees(x) { return x * (180.0 / Math.PI); }
function $radians(x) { return x * (Math.PI / 180.0); }
function $sign(x) { return x > 0 ? 1 : (x < 0 ? -1 : (x === 0 ? 0 : NaN)); }
function $pow(a, b) { return Math.pow(a, b); }
function $arr(v) {  // a float array from a typed array, a list, or {shape, data} (two dimensions)
  if (v instanceof Float64Array) return v;
  if (v && v.shape) { const d = Float64Array.from(v.data); return v.shape.length === 2 ? $two(d, v.shape[1]) : d; }
  return Float64Array.from(v);
}
"""


def translated_name(fn) -> str:
    """The JavaScript name of the kernel ``fn``: its module and name, dots made ``$``."""
    fn = _python(fn)
    return (fn.__module__ + "." + fn.__qualname__).replace(".", "$").replace("<", "_").replace(">", "_")


def _python(obj):
    """The plain Python function behind a kernel (a numba dispatcher, a lazily compiled kernel, a function)."""
    inner = getattr(obj, "py_func", None)
    if inner is not None:
        return inner
    return obj


def _is_kernel(obj) -> bool:
    """Whether ``obj`` is a function of the project (the package, its tests), not of a library: only those are
    translated (a library's function, ``np.linalg.norm``, is refused)."""
    import sysconfig  # noqa: PLC0415

    fn = _python(obj)
    if not isinstance(fn, types.FunctionType):
        return False
    if (fn.__module__ or "").split(".")[0] == "scara":
        return True
    file = fn.__code__.co_filename
    libraries = {sysconfig.get_paths()[k] for k in ("stdlib", "platstdlib", "purelib", "platlib")}
    return not any(file.startswith(lib) for lib in libraries) and "site-packages" not in file


def _is_namedtuple_class(obj) -> bool:
    return isinstance(obj, type) and issubclass(obj, tuple) and hasattr(obj, "_fields")


def _number(value) -> str:
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    v = float(value)
    if math.isnan(v):
        return "NaN"
    if math.isinf(v):
        return "Infinity" if v > 0 else "(-Infinity)"
    text = repr(v)
    return f"({text})" if text.startswith("-") else text


class _Function:
    """The translation of one kernel (see :func:`translate`)."""

    def __init__(self, fn, unit, args=None):
        self.fn = fn
        self.unit = unit
        self.types, callees = (None, {}) if args is None else _infer(fn, args)
        for callee, cargs in callees.items():
            unit.argtypes.setdefault(translated_name(callee), cargs)
        self.name = translated_name(fn)
        try:
            lines, self.first = inspect.getsourcelines(fn)
        except (OSError, TypeError) as exc:
            raise TranslationError(f"kernel {fn.__qualname__}: its source cannot be read ({exc})") from exc
        self.file = inspect.getsourcefile(fn)
        self.tree = ast.parse(textwrap.dedent("".join(lines)))
        self.globals = fn.__globals__
        self.tmp = 0
        self.locals: set = set()

    # -- errors ---------------------------------------------------------------------------------------
    def refuse(self, node, what: str):
        line = self.first + getattr(node, "lineno", 1) - 1
        raise TranslationError(f"kernel {self.fn.__module__}.{self.fn.__qualname__} ({self.file}, line {line}): "
                               f"{what} is not supported by the page's translator")

    # -- names ----------------------------------------------------------------------------------------
    def local(self, name: str) -> str:
        return name + "_" if name in _RESERVED or name.startswith("$") else name

    def fresh(self) -> str:
        self.tmp += 1
        return f"$t{self.tmp}"

    def global_value(self, node, name):
        if name in self.globals:
            return self.globals[name]
        import builtins  # noqa: PLC0415

        if hasattr(builtins, name):
            return getattr(builtins, name)
        self.refuse(node, f"the name {name!r} (not a local, a global or a builtin)")

    def constant(self, node, value) -> str:
        if isinstance(value, (bool, int, float, np.integer, np.floating, np.bool_)):
            return _number(value)
        if isinstance(value, tuple) and all(isinstance(v, (bool, int, float, np.integer, np.floating)) or
                                            isinstance(v, tuple) for v in value):
            return self.unit.constant(value)
        self.refuse(node, f"the global {type(value).__name__} value {value!r:.60}")

    # -- the function ---------------------------------------------------------------------------------
    def source(self) -> str:
        fdef = self.tree.body[0]
        if not isinstance(fdef, ast.FunctionDef):
            self.refuse(fdef, "a kernel that is not a plain function")
        a = fdef.args
        if a.vararg or a.kwarg or a.kwonlyargs or a.defaults or a.kw_defaults or a.posonlyargs:
            self.refuse(fdef, "a parameter with a default, or *args, **kwargs, keyword-only parameters")
        if self.fn.__code__.co_freevars:
            self.refuse(fdef, f"a closure (it reads {self.fn.__code__.co_freevars} of an enclosing function)")
        params = [self.local(x.arg) for x in a.args]
        self.params = set(x.arg for x in a.args)
        body = fdef.body
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) and \
                isinstance(body[0].value.value, str):
            body = body[1:]
        for node in ast.walk(fdef):
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store) and node.id not in self.params:
                self.locals.add(node.id)
            if isinstance(node, (ast.Global, ast.Nonlocal)):
                self.refuse(node, "global/nonlocal")
        code = self.block(body, 1)
        decl = sorted(self.local(n) for n in self.locals)
        temps = [f"$t{i}" for i in range(1, self.tmp + 1)] + [f"$k{i}" for i in range(1, self._loops + 1)] + \
                [f"$e{i}" for i in range(1, self._loops + 1)]
        head = f"function {self.name}({', '.join(params)}) {{\n"
        lets = f"  let {', '.join(decl + temps)};\n" if decl or temps else ""
        return head + lets + code + "}\n"

    _loops = 0

    def block(self, stmts, depth) -> str:
        return "".join(self.statement(s, depth) for s in stmts)

    # -- statements -----------------------------------------------------------------------------------
    def statement(self, s, depth) -> str:
        ind = "  " * depth
        if isinstance(s, ast.Pass):
            return ""
        if isinstance(s, ast.Expr):
            if isinstance(s.value, ast.Constant) and isinstance(s.value.value, str):
                return ""
            if not isinstance(s.value, ast.Call):
                self.refuse(s, "an expression statement that is not a call")
            return f"{ind}{self.expr(s.value)};\n"
        if isinstance(s, ast.Assign):
            if len(s.targets) != 1:
                self.refuse(s, "a chained assignment (a = b = ...)")
            return self.assign(s.targets[0], s.value, ind, s)
        if isinstance(s, ast.AnnAssign):
            if s.value is None:
                return ""
            return self.assign(s.target, s.value, ind, s)
        if isinstance(s, ast.AugAssign):
            op = self.binop(s.op, s)
            t = s.target
            if isinstance(t, ast.Name):
                return f"{ind}{self.name_of(t)} = {op(self.name_of(t), self.expr(s.value))};\n"
            if isinstance(t, ast.Subscript):
                # evaluate the array and the indices once
                pre, arr, idx = self.subscript_parts(t, ind)
                get = self.index_get(arr, idx, t)
                return pre + self.index_set(arr, idx, op(get, self.expr(s.value)), t, ind)
            self.refuse(s, "an augmented assignment to this target")
        if isinstance(s, ast.Return):
            return f"{ind}return{'' if s.value is None else ' ' + self.expr(s.value)};\n"
        if isinstance(s, ast.If):
            out = f"{ind}if ({self.truth(s.test)}) {{\n{self.block(s.body, depth + 1)}{ind}}}"
            if s.orelse:
                if len(s.orelse) == 1 and isinstance(s.orelse[0], ast.If):
                    out += " else " + self.statement(s.orelse[0], depth).lstrip()
                    return out
                out += f" else {{\n{self.block(s.orelse, depth + 1)}{ind}}}"
            return out + "\n"
        if isinstance(s, ast.While):
            if s.orelse:
                self.refuse(s, "while ... else")
            return f"{ind}while ({self.truth(s.test)}) {{\n{self.block(s.body, depth + 1)}{ind}}}\n"
        if isinstance(s, ast.For):
            return self.for_loop(s, depth)
        if isinstance(s, ast.Break):
            return f"{ind}break;\n"
        if isinstance(s, ast.Continue):
            return f"{ind}continue;\n"
        self.refuse(s, f"the statement {type(s).__name__}")

    def for_loop(self, s, depth) -> str:
        ind = "  " * depth
        if s.orelse:
            self.refuse(s, "for ... else")
        it = s.iter
        if not (isinstance(it, ast.Call) and isinstance(it.func, ast.Name) and it.func.id == "range" and
                self.global_value(it, "range") is range and not it.keywords and 1 <= len(it.args) <= 3):
            self.refuse(s, "a for loop that is not over range(...)")
        if not isinstance(s.target, ast.Name):
            self.refuse(s, "a for loop over a target that is not a name")
        args = [self.expr(a) for a in it.args]
        start, stop, step = ("0", args[0], "1") if len(args) == 1 else (args[0], args[1], "1") if len(args) == 2 \
            else tuple(args)
        self._loops += 1
        k, e = f"$k{self._loops}", f"$e{self._loops}"
        var = self.name_of(s.target)
        if len(args) == 3:
            literal = it.args[2]
            sign = None
            if isinstance(literal, ast.Constant) and isinstance(literal.value, int):
                sign = literal.value
            elif isinstance(literal, ast.UnaryOp) and isinstance(literal.op, ast.USub) and \
                    isinstance(literal.operand, ast.Constant):
                sign = -literal.operand.value
            if not sign:
                self.refuse(s, "range(...) with a step that is not a nonzero integer literal")
            cond = f"{k} < {e}" if sign > 0 else f"{k} > {e}"
        else:
            cond = f"{k} < {e}"
        return (f"{ind}for ({k} = {start}, {e} = {stop}; {cond}; {k} += {step}) {{\n{ind}  {var} = {k};\n"
                f"{self.block(s.body, depth + 1)}{ind}}}\n")

    def assign(self, target, value, ind, node) -> str:
        if isinstance(target, ast.Name):
            return f"{ind}{self.name_of(target)} = {self.expr(value)};\n"
        if isinstance(target, ast.Subscript):
            pre, arr, idx = self.subscript_parts(target, ind)
            return pre + self.index_set(arr, idx, self.expr(value), target, ind)
        if isinstance(target, (ast.Tuple, ast.List)):
            if isinstance(value, (ast.Tuple, ast.List)):
                if len(value.elts) != len(target.elts):
                    self.refuse(node, "unpacking a tuple of another length")
                temps = []
                out = ""
                for v in value.elts:
                    t = self.fresh()
                    temps.append(t)
                    out += f"{ind}{t} = {self.expr(v)};\n"
                for tgt, t in zip(target.elts, temps):
                    out += self.assign_js(tgt, t, ind, node)
                return out
            t = self.fresh()
            out = f"{ind}{t} = {self.expr(value)};\n"
            for i, tgt in enumerate(target.elts):
                out += self.assign_js(tgt, f"{t}[{i}]", ind, node)
            return out
        self.refuse(node, f"an assignment to a {type(target).__name__}")

    def assign_js(self, target, js, ind, node) -> str:
        """Assign the JavaScript expression ``js`` to the Python target ``target``."""
        if isinstance(target, ast.Name):
            return f"{ind}{self.name_of(target)} = {js};\n"
        if isinstance(target, ast.Subscript):
            pre, arr, idx = self.subscript_parts(target, ind)
            return pre + self.index_set(arr, idx, js, target, ind)
        if isinstance(target, (ast.Tuple, ast.List)):
            t = self.fresh()
            out = f"{ind}{t} = {js};\n"
            for i, tgt in enumerate(target.elts):
                out += self.assign_js(tgt, f"{t}[{i}]", ind, node)
            return out
        self.refuse(node, f"an assignment to a {type(target).__name__}")

    # -- subscripts -----------------------------------------------------------------------------------
    def subscript_parts(self, t, ind):
        """(statements, array, indices) of ``a[i]`` / ``a[i, j]`` with the array and indices held in temporaries
        when they are not plain names or numbers."""
        pre = ""
        arr = self.expr(t.value)
        if not _simple(t.value):
            tmp = self.fresh()
            pre += f"{ind}{tmp} = {arr};\n"
            arr = tmp
        sl = t.slice
        elts = sl.elts if isinstance(sl, ast.Tuple) else [sl]
        idx = []
        for e in elts:
            if isinstance(e, ast.Slice):
                self.refuse(t, "assigning into a slice")
            js = self.expr(e)
            if not _simple(e):
                tmp = self.fresh()
                pre += f"{ind}{tmp} = {js};\n"
                js = tmp
            idx.append(self.index(e, arr, js, len(idx)))
        if len(idx) > 2:
            self.refuse(t, "an array of more than two dimensions")
        return pre, arr, idx

    def index_get(self, arr, idx, node) -> str:
        if len(idx) == 1:
            return f"{arr}[{idx[0]}]" if self.ndim(node.value) in (0, 1) else f"$g1({arr}, {idx[0]})"
        return f"{arr}[{idx[0]} * {arr}.n1 + {idx[1]}]"

    def index_set(self, arr, idx, value, node, ind) -> str:
        target = f"{arr}[{idx[0]}]" if len(idx) == 1 else f"{arr}[{idx[0]} * {arr}.n1 + {idx[1]}]"
        return f"{ind}{target} = {value};\n"

    def index(self, node, arr: str, js: str, axis: int = 0) -> str:
        """The JavaScript index of ``node`` along ``axis`` of ``arr``: a negative literal counts from the end, as
        in Python; a negative index that is not a literal is outside the subset (it would read past the array)."""
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and isinstance(node.operand, ast.Constant):
            return f"({arr}.n1 - {_number(node.operand.value)})" if axis else f"($n0({arr}) - {_number(node.operand.value)})"
        return js

    def subscript(self, e) -> str:
        sl = e.slice
        if isinstance(e.value, ast.Attribute) and e.value.attr == "shape" and not isinstance(sl, (ast.Slice, ast.Tuple)):
            return f"$shape({self.expr(e.value.value)}, {self.expr(sl)})"
        if isinstance(sl, ast.Slice):
            if sl.step is not None:
                self.refuse(e, "a slice with a step")
            arr = self.expr(e.value)
            lo = "null" if sl.lower is None else self.expr(sl.lower)
            hi = "null" if sl.upper is None else self.expr(sl.upper)
            return f"$slice({arr}, {lo}, {hi})"
        if isinstance(sl, ast.Tuple):
            arr = self.expr(e.value)
            if len(sl.elts) != 2:
                self.refuse(e, "an array of more than two dimensions")
            i, j = sl.elts
            if isinstance(i, ast.Slice):
                self.refuse(e, "a slice of rows with a column index (a[lo:hi, j])")
            ii = self.index(i, arr, self.expr(i))
            if isinstance(j, ast.Slice):
                if j.step is not None:
                    self.refuse(e, "a slice with a step")
                row = f"$row({arr}, {ii})"
                if j.lower is None and j.upper is None:
                    return row
                lo = "null" if j.lower is None else self.expr(j.lower)
                hi = "null" if j.upper is None else self.expr(j.upper)
                return f"$slice({row}, {lo}, {hi})"
            return f"{arr}[{ii} * {arr}.n1 + {self.index(j, arr, self.expr(j), 1)}]"
        # a[i][j]: one element of a 2-D array (or of a tuple of arrays), with no row view made
        inner = e.value
        if isinstance(inner, ast.Subscript) and not isinstance(inner.slice, (ast.Slice, ast.Tuple)) and not (
                isinstance(inner.value, ast.Attribute) and inner.value.attr == "shape"):
            nd = self.ndim(inner.value)
            if nd != 0 and (_simple(inner.value) or isinstance(inner.value, ast.Attribute)):
                arr = self.expr(inner.value)
                i = self.index(inner.slice, arr, self.expr(inner.slice))
                j = self.index(sl, arr, self.expr(sl), 1)
                return f"{arr}[{i} * {arr}.n1 + {j}]" if nd == 2 else f"$g2({arr}, {i}, {j})"
        arr = self.expr(e.value)
        nd = self.ndim(e.value)
        i = self.index(sl, arr, self.expr(sl))
        if nd == 2:
            return f"$row({arr}, {i})"
        if nd in (0, 1):
            return f"{arr}[{i}]"
        return f"$g1({arr}, {i})"

    # -- numba's types of expressions (None when unknown) ---------------------------------------------------
    def ty(self, node):
        if self.types is None:
            return None
        from numba.core import types as nt  # noqa: PLC0415

        if isinstance(node, ast.Name):
            t = self.types.get(node.id)
            return None if t is _MIXED else t
        if isinstance(node, ast.Attribute):
            bt = self.ty(node.value)
            if isinstance(bt, nt.BaseNamedTuple):
                fields = bt.instance_class._fields
                if node.attr in fields:
                    return bt.types[fields.index(node.attr)]
            return None
        if isinstance(node, ast.Subscript):
            bt = self.ty(node.value)
            sl = node.slice
            if isinstance(bt, nt.Array):
                if isinstance(sl, ast.Slice):
                    return bt
                n = len(sl.elts) if isinstance(sl, ast.Tuple) else 1
                if isinstance(sl, ast.Tuple) and any(isinstance(x, ast.Slice) for x in sl.elts):
                    return bt.copy(ndim=1)
                return bt.dtype if n == bt.ndim else bt.copy(ndim=bt.ndim - n)
            if isinstance(bt, nt.BaseTuple) and not isinstance(sl, (ast.Slice, ast.Tuple)):
                if isinstance(bt, nt.UniTuple):
                    return bt.dtype
                if isinstance(sl, ast.Constant) and isinstance(sl.value, int):
                    return bt.types[sl.value]
            return None
        return None

    def ndim(self, node):
        """1 or 2 for an array of known type, 0 for a known non-array (tuple), None when unknown."""
        t = self.ty(node)
        if t is None:
            return None
        nd = _array_ndim(t)
        return 0 if nd is None else nd

    # -- expressions ----------------------------------------------------------------------------------
    def name_of(self, node) -> str:
        n = node.id
        if n in self.locals or n in self.params:
            return self.local(n)
        self.refuse(node, f"the name {n!r} here")

    def truth(self, e) -> str:
        return self.expr(e)

    def binop(self, op, node):
        table = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/"}
        if type(op) in table:
            sym = table[type(op)]
            return lambda a, b: f"({a} {sym} {b})"
        if isinstance(op, ast.FloorDiv):
            return lambda a, b: f"$floordiv({a}, {b})"
        if isinstance(op, ast.Mod):
            return lambda a, b: f"$mod({a}, {b})"
        if isinstance(op, ast.Pow):
            return lambda a, b: f"$pow({a}, {b})"
        self.refuse(node, f"the operator {type(op).__name__}")

    def expr(self, e) -> str:
        if isinstance(e, ast.Constant):
            if isinstance(e.value, (bool, int, float)):
                return _number(e.value)
            self.refuse(e, f"the constant {e.value!r:.40}")
        if isinstance(e, ast.Name):
            if e.id in self.locals or e.id in self.params:
                return self.local(e.id)
            value = self.global_value(e, e.id)
            if _is_kernel(value) or _is_namedtuple_class(value) or isinstance(value, types.ModuleType):
                self.refuse(e, f"{e.id!r} used as a value (only called)")
            if value is True or value is False:
                return _number(value)
            return self.constant(e, value)
        if isinstance(e, ast.BinOp):
            return self.binop(e.op, e)(self.expr(e.left), self.expr(e.right))
        if isinstance(e, ast.UnaryOp):
            if isinstance(e.op, ast.USub):
                return f"(-{self.expr(e.operand)})"
            if isinstance(e.op, ast.UAdd):
                return f"(+{self.expr(e.operand)})"
            if isinstance(e.op, ast.Not):
                return f"(!{self.expr(e.operand)})"
            self.refuse(e, f"the operator {type(e.op).__name__}")
        if isinstance(e, ast.BoolOp):
            sym = " && " if isinstance(e.op, ast.And) else " || "
            return "(" + sym.join(self.expr(v) for v in e.values) + ")"
        if isinstance(e, ast.Compare):
            table = {ast.Lt: "<", ast.LtE: "<=", ast.Gt: ">", ast.GtE: ">=", ast.Eq: "===", ast.NotEq: "!=="}
            parts, left = [], self.expr(e.left)
            for op, right in zip(e.ops, e.comparators):
                if type(op) not in table:
                    self.refuse(e, f"the comparison {type(op).__name__}")
                r = self.expr(right)
                parts.append(f"({left} {table[type(op)]} {r})")
                left = r
            return parts[0] if len(parts) == 1 else "(" + " && ".join(parts) + ")"
        if isinstance(e, ast.IfExp):
            return f"({self.expr(e.test)} ? {self.expr(e.body)} : {self.expr(e.orelse)})"
        if isinstance(e, ast.Tuple):
            return "[" + ", ".join(self.expr(x) for x in e.elts) + "]"
        if isinstance(e, ast.Subscript):
            return self.subscript(e)
        if isinstance(e, ast.Attribute):
            return self.attribute(e)
        if isinstance(e, ast.Call):
            return self.call(e)
        self.refuse(e, f"the expression {type(e).__name__}")

    def attribute(self, e) -> str:
        base = e.value
        if isinstance(base, ast.Name) and base.id not in self.locals and base.id not in self.params:
            mod = self.global_value(base, base.id)
            if mod is math:
                if e.attr in MATH_CONSTANTS:
                    return MATH_CONSTANTS[e.attr]
                self.refuse(e, f"math.{e.attr} as a value")
            if mod is np:
                if e.attr in NUMPY_CONSTANTS:
                    return NUMPY_CONSTANTS[e.attr]
                self.refuse(e, f"np.{e.attr} as a value")
            if isinstance(mod, types.ModuleType):
                value = getattr(mod, e.attr, None)
                if value is None:
                    self.refuse(e, f"{base.id}.{e.attr}")
                return self.constant(e, value)
            if _is_namedtuple_class(mod) or _is_kernel(mod):
                self.refuse(e, f"the attribute {e.attr!r} of {base.id!r}")
            value = getattr(mod, e.attr, None)  # a constant of a global object (an Offsets namedtuple)
            if value is not None and isinstance(value, (int, float, tuple)):
                return self.constant(e, value)
            self.refuse(e, f"the attribute {base.id}.{e.attr}")
        if e.attr in ("shape", "size", "ndim"):
            if e.attr == "size":
                self.refuse(e, "a.size (use len(a) of a 1-D array)")
            self.refuse(e, f"a.{e.attr} as a value (use a.shape[k])")
        if e.attr.startswith("_") and not e.attr.startswith("__"):
            return f"{self.expr(base)}.{e.attr}"
        if e.attr in ("real", "imag", "T", "flat", "data"):
            self.refuse(e, f"the array attribute .{e.attr}")
        return f"{self.expr(base)}.{e.attr}"  # a namedtuple's field

    def call(self, e) -> str:
        if e.keywords:
            if not (isinstance(e.func, ast.Attribute) and e.func.attr in ("empty", "zeros")):
                self.refuse(e, "a call with keyword arguments")
        f = e.func
        args = [self.expr(a) for a in e.args if not isinstance(a, ast.Starred)]
        if any(isinstance(a, ast.Starred) for a in e.args):
            self.refuse(e, "a call with *args")
        if isinstance(f, ast.Attribute):
            base = f.value
            if isinstance(base, ast.Name) and base.id not in self.locals and base.id not in self.params:
                mod = self.global_value(base, base.id)
                if mod is math:
                    if f.attr not in MATH:
                        self.refuse(e, f"math.{f.attr}")
                    return f"{MATH[f.attr]}({', '.join(args)})"
                if mod is np:
                    return self.numpy_call(e, f.attr, args)
                if isinstance(mod, types.ModuleType):
                    value = getattr(mod, f.attr, None)
                    return self.call_value(e, value, f"{base.id}.{f.attr}", args)
            if f.attr == "reshape" and self.ndim(base) == 2 and not _contiguous_rows(self.ty(base)):
                self.refuse(e, "reshape of an array that is not contiguous")
            if f.attr == "reshape":
                dims = e.args
                if len(dims) == 1 and isinstance(dims[0], ast.Tuple):
                    dims = dims[0].elts
                if len(dims) != 2:
                    self.refuse(e, "reshape to other than two dimensions")
                return f"$reshape({self.expr(base)}, {self.expr(dims[0])}, {self.expr(dims[1])})"
            if f.attr == "copy" and not e.args and self.ndim(base) in (None, 1, 2):
                return f"$copy({self.expr(base)})"
            self.refuse(e, f"the method .{f.attr}()")
        if isinstance(f, ast.Name):
            if f.id in self.locals or f.id in self.params:
                self.refuse(e, f"calling the variable {f.id!r} (a first-class function)")
            value = self.global_value(f, f.id)
            return self.call_value(e, value, f.id, args)
        self.refuse(e, "this call")

    def call_value(self, e, value, label, args) -> str:
        import builtins  # noqa: PLC0415

        if value is abs:
            return f"Math.abs({args[0]})"
        if value is min or value is max:
            if len(args) < 2:
                self.refuse(e, f"{label}() of fewer than two numbers")
            return f"${value.__name__}({', '.join(args)})"
        if value is float:
            return f"(+{args[0]})" if args else "0.0"
        if value is int:
            return f"$int({args[0]})"
        if value is len:
            nd = self.ndim(e.args[0])
            return f"{args[0]}.length" if nd in (0, 1) else f"$n0({args[0]})"
        if value is bool:
            return f"(!!{args[0]})"
        if value is range:
            self.refuse(e, "range() outside a for loop")
        if _is_namedtuple_class(value):
            fields = value._fields
            if len(args) != len(fields):
                self.refuse(e, f"{label}() with {len(args)} values for its {len(fields)} fields")
            return f"{self.unit.namedtuple(value)}({', '.join(args)})"
        if _is_kernel(value):
            fn = _python(value)
            if fn is self.fn:
                self.refuse(e, "recursion")
            self.unit.need(value)
            return f"{translated_name(fn)}({', '.join(args)})"
        if getattr(builtins, label, None) is value:
            self.refuse(e, f"the builtin {label}()")
        self.refuse(e, f"calling {label} ({type(value).__name__})")

    def numpy_call(self, e, name, args) -> str:
        if name in ("empty", "zeros"):
            for kw in e.keywords:
                if kw.arg != "dtype" or not (isinstance(kw.value, ast.Attribute) and kw.value.attr == "float64"
                                             or isinstance(kw.value, ast.Name) and kw.value.id == "float"):
                    self.refuse(e, f"np.{name}(..., {kw.arg}=...) other than dtype=np.float64")
            shape = e.args[0] if e.args else None
            if isinstance(shape, ast.Tuple):
                if len(shape.elts) == 1:
                    return f"new Float64Array($size({self.expr(shape.elts[0])}))"
                if len(shape.elts) == 2:
                    return f"$empty2({self.expr(shape.elts[0])}, {self.expr(shape.elts[1])})"
                self.refuse(e, "an array of more than two dimensions")
            if len(e.args) != 1:
                self.refuse(e, f"np.{name} with {len(e.args)} arguments")
            return f"new Float64Array($size({args[0]}))"
        if name in NUMPY:
            return f"{NUMPY[name]}({', '.join(args)})"
        self.refuse(e, f"np.{name}")


def _safe_field(name: str) -> str:
    if name in ("length", "n1", "constructor", "prototype", "__proto__") or name in _RESERVED:
        raise TranslationError(f"a namedtuple field called {name!r} cannot be kept in the page's engine")
    return name


#: what :func:`_infer` found, by (function, argument types): a kernel called by many is typed once per process
_INFERRED: dict = {}


def _infer(fn, args):
    """numba's type inference of the function ``fn`` for the argument types ``args`` (no code is generated):
    ``(variable types by name, {callee's Python function: its argument types})``, or ``(None, {})`` when
    numba is missing or cannot type it (the kernel is then translated with run-time dispatch). Each pair is
    inferred once per process (the same function and types give the same types); callers get their own dicts."""
    key = (fn, tuple(args))
    if key not in _INFERRED:
        _INFERRED[key] = _infer_types(fn, key[1])
    types, callees = _INFERRED[key]
    return (None if types is None else dict(types)), dict(callees)


def _infer_types(fn, args):
    try:
        from numba.core import compiler, typed_passes  # noqa: PLC0415
        from numba.core import types as nt  # noqa: PLC0415
        from numba.core.registry import cpu_target  # noqa: PLC0415
    except ImportError:  # pragma: no cover
        return None, {}
    try:
        interp = compiler.run_frontend(fn)
        res = typed_passes.type_inference_stage(cpu_target.typing_context, cpu_target.target_context, interp,
                                                tuple(args), None)
    except Exception:  # noqa: BLE001 - an untyped translation is still exact, only slower
        return None, {}
    callees = {}
    for expr, sig in res.calltypes.items():
        if getattr(expr, "op", None) != "call" or sig is None:
            continue
        fty = res.typemap.get(expr.func.name)
        if isinstance(fty, nt.Dispatcher):
            callees.setdefault(fty.dispatcher.py_func, tuple(sig.args))
    return _named(res.typemap), callees


def _named(typemap):
    out = {}
    for key, ty in typemap.items():
        if key.startswith("$"):
            continue
        name = key[4:] if key.startswith("arg.") else key.split(".")[0]
        if name in out and out[name] != ty:
            out[name] = _MIXED
        else:
            out.setdefault(name, ty)
    return out


_MIXED = object()  # a variable whose versions have different types


def _array_ndim(ty):
    from numba.core import types as nt  # noqa: PLC0415 - typed translation happens with numba only

    return ty.ndim if isinstance(ty, nt.Array) else None


def _contiguous_rows(ty) -> bool:
    return getattr(ty, "layout", "C") == "C"


def _simple(node) -> bool:
    return isinstance(node, (ast.Name, ast.Constant)) or (
        isinstance(node, ast.UnaryOp) and isinstance(node.operand, ast.Constant))


class _Unit:
    """The script being built: the kernels translated so far and the constants they use."""

    def __init__(self):
        self.functions: "collections.OrderedDict[str, str]" = collections.OrderedDict()
        self.pending: list = []
        self.constants: dict = {}
        self.factories: dict = {}
        self.argtypes: dict = {}

    def need(self, obj, args=None):
        """Translate the kernel ``obj`` too; ``args`` are its argument types (numba's), when known: the
        translation is then typed (see :func:`_infer`)."""
        name = translated_name(obj)
        if args is not None:
            self.argtypes.setdefault(name, tuple(args))
        elif getattr(obj, "overloads", None):
            self.argtypes.setdefault(name, next(iter(obj.overloads)))
        if name not in self.functions and all(translated_name(p) != name for p in self.pending):
            self.pending.append(obj)

    def namedtuple(self, cls) -> str:
        """The factory of the namedtuple class ``cls``: an object of a class holding its values by field name, in
        its own slots (one allocation: V8's fastest object), whose prototype reads them by position too and
        gives its ``length`` (an array-like). An object literal with the positions as keys makes two allocations
        (the positions are kept apart), an array given named properties afterwards is slower still (it made the
        controllers' loop half as fast)."""
        name = "$nt$" + (cls.__module__ + "." + cls.__qualname__).replace(".", "$")
        if name not in self.factories:
            f = [_safe_field(x) for x in cls._fields]
            args = ", ".join(f"v{i}" for i in range(len(f)))
            slots = " ".join(f"this.{n} = v{i};" for i, n in enumerate(f))
            klass = "$NT" + name[3:]
            self.factories[name] = (f"class {klass} {{ constructor({args}) {{ {slots} }} }}\n"
                                    f"$positions({klass}, {json.dumps(f)});\n"
                                    f"function {name}({args}) {{ return new {klass}({args}); }}\n")
        return name

    def constant(self, value: tuple) -> str:
        def js(v):
            if isinstance(v, tuple):
                return "[" + ", ".join(js(x) for x in v) + "]"
            return _number(v)

        text = js(value)
        if text not in self.constants:
            self.constants[text] = f"$C{len(self.constants)}"
        return self.constants[text]

    def run(self):
        while self.pending:
            fn = self.pending.pop(0)
            name = translated_name(fn)
            if name in self.functions:
                continue
            self.functions[name] = None  # placeholder: a cycle is caught as recursion below
            self.functions[name] = _Function(_python(fn), self, self.argtypes.get(name)).source()


def translate(kernels, exports: dict | None = None, signatures: dict | None = None) -> str:
    """One JavaScript script holding the translation of ``kernels`` and of every kernel they call, the
    runtime (:data:`RUNTIME`) first.

    ``kernels`` is a list of kernels (numba dispatchers or their Python functions). The script defines the
    object ``SCARA_KERNELS`` mapping each given kernel's ``__name__`` (or the names of ``exports``, a dict
    name -> kernel, when given) to its translation, and exports it under Node (``module.exports``), so the same
    file serves a Web Worker and the tests. ``signatures`` (name -> numba argument types) types the given
    kernels; a kernel without one is typed from its first compiled overload when it has one. From a typed
    kernel numba's type inference types the kernels it calls, and the translation indexes arrays and tuples
    directly (untyped, it dispatches at run time: the same numbers, more slowly). Raises :class:`TranslationError` for a construct outside the subset
    (see the module's docstring), naming the kernel, its file and line.
    """
    unit = _Unit()
    signatures = dict(signatures or {})
    named = dict(exports or {})
    for k in kernels:
        named.setdefault(_python(k).__name__, k)
    by_js = {}
    for name, k in named.items():
        fn = _python(k)
        if not _is_kernel(fn):
            raise TranslationError(f"{name}: {k!r} is not a kernel of the package (a Python function)")
        unit.need(k, signatures.get(name))
        by_js[name] = translated_name(fn)
    unit.run()
    consts = "".join(f"const {name} = {text};\n" for text, name in unit.constants.items())
    table = ",\n".join(f"  {name}: {js}" for name, js in by_js.items())
    return (RUNTIME + consts + "".join(unit.factories.values()) + "".join(unit.functions.values()) +
            f"const SCARA_KERNELS = {{\n{table}\n}};\n"
            "const SCARA_RUNTIME = {$arr, $empty2, $reshape, $n0};\n"
            "if (typeof module !== 'undefined') module.exports = {SCARA_KERNELS, SCARA_RUNTIME};\n")
