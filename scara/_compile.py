"""The project decorator for compiled kernels.

:func:`kernel` applies ``numba.njit(cache=True)`` when numba can be imported and returns the function
unchanged otherwise, so that every hot loop runs as the same plain-Python code where numba is missing.
Setting the environment variable ``SCARA_NO_NUMBA=1`` (or numba's own ``NUMBA_DISABLE_JIT=1``) forces the
plain-Python path, which the tests use to check that both paths agree.

Kernels take and return floats and numpy arrays only (no parameter objects), and write their results into
output arrays passed by the caller, so that a compiled loop allocates nothing per step.
"""
from __future__ import annotations

import os

try:  # pragma: no cover - depends on the environment
    if os.environ.get("SCARA_NO_NUMBA", "") == "1":
        raise ImportError("disabled by SCARA_NO_NUMBA=1")
    import numba as _numba
except ImportError:  # pragma: no cover
    _numba = None

#: True when kernels are compiled by numba.
COMPILED = _numba is not None and os.environ.get("NUMBA_DISABLE_JIT", "0") != "1"


def _source_digest() -> str:
    """A digest of every source file of the package."""
    import hashlib
    from pathlib import Path

    h = hashlib.sha1()
    root = Path(__file__).resolve().parent
    for f in sorted(root.rglob("*.py")):
        h.update(str(f.relative_to(root)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


# numba's on-disk cache checks only the decorated function's own file: a kernel that calls kernels of
# another module would keep running their old code after that module changed. Keying the cache folder on
# the whole package's source makes any change start a fresh cache. A NUMBA_CACHE_DIR set by the user wins.
if _numba is not None and not os.environ.get("NUMBA_CACHE_DIR"):
    from pathlib import Path as _Path

    _numba.config.CACHE_DIR = str(_Path(__file__).resolve().parent / "__pycache__" / f"numba-{_source_digest()}")


def kernel(fn=None, **options):
    """Compile ``fn`` with ``numba.njit(cache=True, **options)`` when numba is available.

    Use as ``@kernel`` or ``@kernel(fastmath=False)``. Without numba the function is returned as it is.
    """

    def wrap(f):
        if _numba is None:
            return f
        return _numba.njit(cache=True, **options)(f)

    return wrap if fn is None else wrap(fn)
