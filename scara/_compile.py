"""The project decorator for compiled kernels.

:func:`kernel` applies ``numba.njit(cache=True)`` when numba can be imported and returns the function
unchanged otherwise, so that every hot loop runs as the same plain-Python code where numba is missing.
Setting the environment variable ``SCARA_NO_NUMBA=1`` (or numba's own ``NUMBA_DISABLE_JIT=1``) forces the
plain-Python path, which the tests use to check that both paths agree.

Kernels take and return floats and numpy arrays only (no parameter objects), and write their results into
output arrays passed by the caller, so that a compiled loop allocates nothing per step.

Nothing is compiled at import: a :func:`kernel` compiles (or loads from the on-disk cache) on its first call,
and a kernel that needs an explicit signature (a first-class function argument) is made with
:func:`signature_kernel`, which compiles that signature on its first call too. :func:`ensure_signature`
compiles a lazy kernel for one given signature before it is passed as a first-class function.

A kernel called from another kernel is compiled for the plain types of the call's arguments (``int64``, not the
literal ``0`` the caller wrote), the types a call from Python gives it, so that one machine-code version serves
every caller (:class:`_PlainCallsDispatcher`): numba would otherwise compile a kernel once more for each literal
a caller passes (a controller's law for ``k = 0``, a program's refusal kernel for each of eight gain indices).

A set-up kernel declared ``light`` (a few numbers checked or packed, a plan resolved segment by segment) runs
as plain Python when called from Python, with every kernel it calls: a chapter on an empty cache no longer
spends seconds compiling what runs in microseconds (the planner's ``build_plan`` took 6 s to compile and runs
in 0.3 ms as Python). Called from another kernel it is compiled into it as usual.

The closed loop's contract with a controller's law is declared here once, beside :func:`kernel`: the flat
arrays' fields (:class:`ArrayLayout`), the numba types of the compiled loops (:data:`VECTOR`, :data:`MATRIX`,
:data:`LAW_DATA_TYPE`...), the law's signature :data:`LAW_SIGNATURE` and its decorator :func:`control_law`
(re-exported as ``scara.control_law``); the contract itself is written in :class:`scara._simulate.Controller`.
"""
from __future__ import annotations

import functools
import os
import threading

try:  # pragma: no cover - depends on the environment
    if os.environ.get("SCARA_NO_NUMBA", "") == "1":
        raise ImportError("disabled by SCARA_NO_NUMBA=1")
    import numba as _numba
except ImportError:  # pragma: no cover
    _numba = None

#: True when kernels are compiled by numba.
COMPILED = _numba is not None and os.environ.get("NUMBA_DISABLE_JIT", "0") != "1"


#: Sub-packages that hold no compiled code (figures and panels): their source does not key the cache.
UNCOMPILED_PACKAGES = ("plots", "widgets")


def _source_digest() -> str:
    """A digest of every source file of the package that may hold or call compiled code (all but
    :data:`UNCOMPILED_PACKAGES`)."""
    import hashlib
    from pathlib import Path

    h = hashlib.sha1()
    root = Path(__file__).resolve().parent
    for f in sorted(root.rglob("*.py")):
        rel = f.relative_to(root)
        if rel.parts[0] in UNCOMPILED_PACKAGES:
            continue
        h.update(str(rel).encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


# numba's on-disk cache checks only the decorated function's own file: a kernel that calls kernels of
# another module would keep running their old code after that module changed. Keying the cache folder on
# the source of every module that may hold kernels makes any change there start a fresh cache (editing a
# figure or a panel does not). A NUMBA_CACHE_DIR set by the user wins.
if _numba is not None and not os.environ.get("NUMBA_CACHE_DIR"):
    from pathlib import Path as _Path

    _numba.config.CACHE_DIR = str(_Path(__file__).resolve().parent / "__pycache__" / f"numba-{_source_digest()}")


def kernel(fn=None, *, light: bool = False, **options):
    """Compile ``fn`` with ``numba.njit(cache=True, **options)`` when numba is available.

    Use as ``@kernel`` or ``@kernel(fastmath=False)``. Without numba the function is returned as it is.

    ``light=True`` declares a set-up kernel: a check or a packing of a few numbers, a plan resolved segment by
    segment, work of microseconds whose compilation costs a second or more. Called from Python it runs as plain
    Python (``py_func``), and so does every kernel it calls; called from another kernel it is compiled as part of
    that kernel, as any kernel is. Its results are the same either way (the tests run every kernel both ways).
    """

    def wrap(f):
        if _numba is None:
            return f
        dispatcher = _plain_calls(_numba.njit(cache=True, **options)(f))
        dispatcher.light = bool(light)
        return dispatcher

    return wrap if fn is None else wrap(fn)


class _PlainRun(threading.local):
    """How deep the current thread is inside a plain-Python run of a :func:`kernel` (``light``, or called by
    one): inside it every kernel called runs as plain Python."""

    depth = 0


_PLAIN_RUN = _PlainRun()


def _plain_calls(dispatcher):
    """``dispatcher`` (a fresh numba dispatcher) made a :class:`_PlainCallsDispatcher` of its own class."""
    cls = _PLAIN_CALLS.get(type(dispatcher))
    if cls is None:
        cls = _PLAIN_CALLS[type(dispatcher)] = type(f"PlainCalls{type(dispatcher).__name__}",
                                                   (_PlainCallsDispatcher, type(dispatcher)), {})
    dispatcher.__class__ = cls  # the same object and state: only the typing of calls from kernels changes
    return dispatcher


class _PlainCallsDispatcher:
    """A numba dispatcher that a call from another kernel compiles for the plain (non-literal) types of its arguments.

    When kernel ``f`` calls kernel ``g(x, 0)``, numba types the constant as ``Literal[int](0)`` and compiles ``g``
    for it: a second machine-code version of ``g`` beside the ``int64`` one that ``g(x, k)`` or a call from Python
    compiles, and one more per literal (8 versions of a kernel called with each of 8 constants). Each costs a full
    compile of ``g``: chapter 6, run on an empty cache, compiled about thirty such versions.
    Typed for ``int64`` instead, ``g`` runs the same operations on the same values, so its results are the same
    bits (numba compiles without fast-math: LLVM folds no floating-point operation differently for a known
    integer). A kernel that can only be typed with the literal (a heterogeneous tuple indexed by it) still gets
    its literal version: when the plain types fail, the call is typed as numba types it.
    """

    #: True for a kernel made with ``kernel(light=True)``: a call from Python runs ``py_func``
    light = False

    def __call__(self, *args, **kws):
        """A call from Python: the compiled kernel, or ``py_func`` for a light kernel and anything it calls."""
        if _PLAIN_RUN.depth:
            return self.py_func(*args, **kws)
        if self.light:
            import numpy as np  # noqa: PLC0415 - numba imports it anyway

            _PLAIN_RUN.depth += 1
            try:  # floating-point overflow gives inf as in the compiled kernel, whose checks report it: no warning
                with np.errstate(all="ignore"):
                    return self.py_func(*args, **kws)
            finally:
                _PLAIN_RUN.depth -= 1
        return super().__call__(*args, **kws)

    def get_call_template(self, args, kws):
        plain = tuple(_numba.types.unliteral(a) for a in args)
        plain_kws = {k: _numba.types.unliteral(v) for k, v in kws.items()}
        if plain != tuple(args) or plain_kws != kws:
            try:
                return super().get_call_template(plain, plain_kws)
            except _numba.core.errors.NumbaError:
                pass
        return super().get_call_template(args, kws)


#: the :class:`_PlainCallsDispatcher` class made for each numba dispatcher class
_PLAIN_CALLS: dict = {}


def signature_kernel(signature):
    """Like ``numba.njit(signature, cache=True)``, but compiled (or loaded from the cache) on the first call
    instead of at import.

    The returned object calls the compiled dispatcher (its attributes are the dispatcher's: ``signatures``,
    ``py_func``...); :func:`dispatcher_of` gives the dispatcher itself. Without numba (or under
    ``NUMBA_DISABLE_JIT=1``) the function is returned unchanged.
    """

    def wrap(f):
        if not COMPILED:
            return f
        return _SignatureKernel(f, signature)

    return wrap


class _SignatureKernel:
    """A function compiled with an explicit signature on its first call (see :func:`signature_kernel`)."""

    def __init__(self, fn, signature):
        functools.update_wrapper(self, fn)
        self.py_func = fn
        self._signature = signature
        self._dispatcher = None

    @property
    def dispatcher(self):
        """The numba dispatcher, compiled for the signature (on first access)."""
        if self._dispatcher is None:
            self._dispatcher = _numba.njit(self._signature, cache=True)(self.py_func)
        return self._dispatcher

    def __call__(self, *args):
        return self.dispatcher(*args)

    def __getattr__(self, name):
        if name.startswith("__") or name in ("py_func", "_signature", "_dispatcher"):
            raise AttributeError(name)
        return getattr(self.dispatcher, name)

    def __repr__(self):
        state = "compiled" if self._dispatcher is not None else "compiled on first call"
        return f"<signature kernel {self.__name__} ({state})>"


def dispatcher_of(fn):
    """The numba dispatcher behind ``fn`` (a :func:`signature_kernel` is compiled now); ``fn`` itself otherwise."""
    return fn.dispatcher if isinstance(fn, _SignatureKernel) else fn


def ensure_signature(fn, signature):
    """Compile the lazy kernel ``fn`` for ``signature`` (return type included) unless it has that overload.

    Needed before a lazy kernel is passed as a first-class function (``numba.types.FunctionType``): numba
    would otherwise compile it for the argument types alone and infer the return type. Returns the
    dispatcher. Raises ``TypeError`` when ``fn`` already has an overload for those arguments with another
    return type. Does nothing without numba or for an object that is not a numba dispatcher (a ``cfunc``, a
    plain function under ``SCARA_NO_NUMBA=1``).
    """
    fn = dispatcher_of(fn)
    if _numba is None or not isinstance(fn, _numba.core.dispatcher.Dispatcher):
        return fn
    args = tuple(signature.args)
    cres = fn.overloads.get(args)
    if cres is None:
        fn.compile(signature)
    elif cres.signature.return_type != signature.return_type:
        raise TypeError(f"{fn.__name__} returns {cres.signature.return_type}, but it must return "
                        f"{signature.return_type} (signature {signature})")
    return fn


class ArrayLayout:
    """Named fields of a flat float array, declared once: what a compiled kernel reads by offset.

    A compiled law receives its gains, model, state, scratch rows and signals as flat arrays (see
    :data:`LAW_SIGNATURE` and :class:`scara._simulate.Controller`); declaring the fields here, with their sizes,
    gives both the offsets the kernel reads (module-level ints, constants to numba) and the one packer that
    writes the array, so the two cannot drift::

        GAINS = ArrayLayout(("K_P", 4), ("K_D", 4), ("rho", 1))
        _KP, _KD, _RHO = GAINS.offsets                      # 0, 4, 8
        GAINS.pack(K_P=kp, K_D=kd, rho=20.0)                # array of GAINS.size = 9 floats

    A field's size may be given as a tuple of labels instead of a number: ``("w", ("x", "y"))`` holds two
    entries named ``w_x`` and ``w_y`` in :attr:`entry_names` (a numeric size ``n > 1`` names them ``w_1`` ...
    ``w_n``). With ``width`` each entry is a row of ``width`` floats (the scratch rows of a law:
    ``ArrayLayout(("J", 4), ("y", 1), width=4)`` is a (5, 4) array, ``J`` rows 0-3).

    >>> ArrayLayout(("K_P", 4), ("rho", 1)).offsets
    Offsets(K_P=0, rho=4)
    >>> ArrayLayout(("z_norm", 1), ("w", 2)).entry_names
    ('z_norm', 'w_1', 'w_2')
    """

    def __init__(self, *fields, width: int | None = None):
        from collections import namedtuple  # noqa: PLC0415

        names = [str(name) for name, _ in fields]
        if len(set(names)) != len(names):
            raise ValueError(f"repeated field names in {names}")
        self.labels = {}
        for name, size in fields:
            if isinstance(size, (tuple, list)):
                self.labels[str(name)] = tuple(f"{name}_{lab}" for lab in size)
            elif int(size) == 1:
                self.labels[str(name)] = (str(name),)
            else:
                self.labels[str(name)] = tuple(f"{name}_{i + 1}" for i in range(int(size)))
        self.sizes = {name: len(self.labels[name]) for name in names}
        starts, at = [], 0
        for name in names:
            starts.append(at)
            at += self.sizes[name]
        #: the offset of each field, in the declared order (unpack them into module-level ints)
        self.offsets = namedtuple("Offsets", names)(*starts)
        #: the number of entries (rows, with ``width``) of the array
        self.size = at
        #: the length of each row (None: a flat array)
        self.width = None if width is None else int(width)

    @classmethod
    def of_names(cls, names, width: int | None = None) -> "ArrayLayout":
        """The layout of one entry per name (a controller that lists its ``signal_names`` only)."""
        return cls(*((str(n), 1) for n in names), width=width)

    @classmethod
    def rows(cls, n: int, width: int = 4) -> "ArrayLayout":
        """``n`` unnamed scratch rows of ``width`` floats (a controller that gives its ``work_rows`` only)."""
        return cls(("rows", n), width=width) if int(n) > 0 else cls(width=width)

    @property
    def names(self) -> tuple:
        return self.offsets._fields

    @property
    def entry_names(self) -> tuple:
        """The name of every entry, in order (a field of size 1 keeps its own name)."""
        return tuple(lab for name in self.names for lab in self.labels[name])

    @property
    def shape(self) -> tuple:
        """The shape of the array: ``(size,)``, or ``(size, width)`` for rows."""
        return (self.size,) if self.width is None else (self.size, self.width)

    def zeros(self) -> "np.ndarray":  # noqa: F821
        """A new zeroed float array of :attr:`shape`."""
        import numpy as np  # noqa: PLC0415

        return np.zeros(self.shape)

    def pack(self, **values):
        """The flat float array holding ``values`` (one per field, a number or ``size`` numbers) in the
        declared order. Raises ``ValueError`` naming a missing, unknown or wrongly sized field."""
        import numpy as np  # noqa: PLC0415

        unknown = sorted(set(values) - set(self.names))
        missing = [n for n in self.names if n not in values]
        if unknown or missing:
            raise ValueError(f"fields {self.names}: missing {missing}, unknown {unknown}")
        out = np.empty(self.size)
        for name, start in zip(self.names, self.offsets):
            v = np.asarray(values[name], dtype=float).ravel()
            if v.size != self.sizes[name]:
                raise ValueError(f"field {name!r} holds {self.sizes[name]} numbers, got {v.size}")
            out[start:start + v.size] = v
        return out

    def __repr__(self):
        fields = ", ".join(f"({n!r}, {self.sizes[n]})" for n in self.names)
        return f"ArrayLayout({fields}{'' if self.width is None else f', width={self.width}'})"


# --------------------------------------------------------------------------------------------------
# the numba types of the closed loop (declared here once) and the decorator of a controller's law
# --------------------------------------------------------------------------------------------------
from collections import namedtuple as _namedtuple  # noqa: E402

#: The controller's arrays a law receives at every sample, in the order of :data:`LAW_SIGNATURE`: ``gains``,
#: ``model`` and ``state`` (flat) and the scratch ``work`` (rows of 4).
LawData = _namedtuple("LawData", ("gains", "model", "state", "work"))

if COMPILED:
    from numba import types as numba_types

    _t = numba_types
    #: a C-contiguous float vector / matrix / int vector (the only array types of the compiled loops)
    VECTOR = _t.float64[::1]
    MATRIX = _t.float64[:, ::1]
    INT_VECTOR = _t.int64[::1]
    #: ``int64 law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau)``
    LAW_SIGNATURE = _t.int64(_t.int64, _t.float64, _t.float64, VECTOR, VECTOR, VECTOR, VECTOR, VECTOR, VECTOR,
                             MATRIX, VECTOR, VECTOR)
    #: the type of a law passed to a compiled loop (a first-class function)
    LAW_TYPE = _t.FunctionType(LAW_SIGNATURE)
    #: the type of a :data:`LawData`
    LAW_DATA_TYPE = _t.NamedTuple((VECTOR, VECTOR, VECTOR, MATRIX), LawData)
else:  # pragma: no cover - plain Python
    numba_types = VECTOR = MATRIX = INT_VECTOR = LAW_TYPE = LAW_DATA_TYPE = None
    LAW_SIGNATURE = "int64(int64, float64, float64, f8[::1] x6, f8[:, ::1], f8[::1], f8[::1])"


def control_law(fn):
    """Make ``fn`` a controller's step kernel: a numba dispatcher (cached on disk) that the engine compiles
    with :data:`LAW_SIGNATURE` when it first runs it (:func:`compiled_law`), not at import.

    The law is compiled without numba's reference counting (``_nrt=False``): it must not allocate arrays (it
    writes into the arrays it is given), and in exchange no array view it takes (``work[0]``) costs a
    reference-count update per sample. Without numba the function is returned unchanged. The arguments are
    those of :class:`scara._simulate.Controller` (the contract of a law).
    """
    if not COMPILED:
        return fn
    return _plain_calls(_numba.njit(cache=True, _nrt=False)(fn))


def compiled_law(law):
    """``law`` compiled for :data:`LAW_SIGNATURE` (loaded from the cache when it is there), ready to be passed
    to a compiled loop; returned unchanged without numba or when it is not a numba dispatcher.
    Raises ``TypeError`` when it was already compiled for the same arguments with another return type."""
    if not COMPILED:
        return law
    return ensure_signature(law, LAW_SIGNATURE)


def python_law(law):
    """The plain-Python function behind a :func:`control_law` (the law itself without numba)."""
    return getattr(dispatcher_of(law), "py_func", law)
